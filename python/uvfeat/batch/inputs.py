"""The meshes of a batch: files, folders (searched recursively for mesh files), glob patterns and
meshes held in memory, each mesh once, in a stable order; and the output folder of each, named
after its path or its name."""

from __future__ import annotations

import glob
import hashlib
import os
import re
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidParameterError, MeshFileError
from ..interop import as_mesh
from ..io import SUPPORTED_FORMATS, with_uv_policy
from ..mesh import Mesh


@dataclass(frozen=True)
class MemoryMesh:
    """A mesh the caller holds in memory, as a batch sends it to a worker: its name and arrays."""

    name: str
    positions: np.ndarray
    faces: np.ndarray
    uvs: np.ndarray | None = None
    uv_faces: np.ndarray | None = None

    @classmethod
    def of(cls, source, name: str) -> MemoryMesh:
        mesh = as_mesh(source)
        return cls(name, mesh.positions, mesh.faces, mesh.uvs, mesh.uv_faces)

    @property
    def label(self) -> str:
        """The mesh in the run table (its ``path`` column)."""
        return f"{self.name} (in memory)"

    def record(self) -> dict:
        """What identifies the mesh: changed arrays are computed again."""
        digest = hashlib.blake2b(digest_size=16)
        for array in (self.positions, self.faces, self.uvs, self.uv_faces):
            digest.update(b"-" if array is None else np.ascontiguousarray(array).tobytes())
        return {"name": self.name, "vertices": len(self.positions), "faces": len(self.faces),
                "blake2b": digest.hexdigest()}

    def load(self, uv: str, resolution: int) -> Mesh:
        """The mesh, with :func:`uvfeat.io.load`'s ``uv`` policy applied."""
        return with_uv_policy(Mesh(self.positions, self.faces, self.uvs, self.uv_faces, name=self.name), uv,
                              resolution)


def batch_inputs(inputs) -> list[str | MemoryMesh]:
    """The meshes of ``inputs``: a path, folder or pattern, a ``{name: mesh}`` dict of meshes in
    memory, or a list of any of these and of meshes (each of :data:`uvfeat.interop.ACCEPTED`,
    named after its ``name`` attribute or its place in the list). Paths as :func:`discover`
    gives them; names made unique."""
    if isinstance(inputs, (str, os.PathLike)):
        inputs = [inputs]
    named = inputs.items() if isinstance(inputs, dict) else (
        (None, item) if isinstance(item, (str, os.PathLike)) else (getattr(item, "name", None) or f"mesh_{k}", item)
        for k, item in enumerate(inputs))
    items, names, paths = [], set(), set()
    for name, item in named:
        if name is None:
            found = [path for path in discover([item]) if path not in paths]
            items += found
            paths.update(found)
            continue
        unique, k = str(name), 2
        while unique in names:
            unique, k = f"{name}_{k}", k + 1
        names.add(unique)
        items.append(MemoryMesh.of(item, unique))
    if not items:
        raise InvalidParameterError("no meshes to compute: give mesh files, folders, patterns or meshes")
    return items


def memory_folder(name: str, taken: set[str]) -> str:
    """An output folder for an in-memory mesh called ``name``: one path component (separators
    replaced by ``_``, leading dots removed), not in ``taken``."""
    folder = re.sub(r"[/\\:\x00]", "_", name).lstrip(".") or "mesh"
    unique, k = folder, 2
    while unique in taken:
        unique, k = f"{folder}_{k}", k + 1
    return unique


def _mesh_files(folder: str) -> list[str]:
    found = []
    for root, dirs, files in os.walk(folder):
        dirs.sort()
        found += [os.path.join(root, f) for f in sorted(files)
                  if os.path.splitext(f)[1].lower().lstrip(".") in SUPPORTED_FORMATS]
    return found


def discover(inputs) -> list[str]:
    """Mesh paths from files, folders and glob patterns. A file is taken whatever its extension
    (a bad one becomes its row's error); folders and patterns give their mesh files."""
    if isinstance(inputs, (str, os.PathLike)):
        inputs = [inputs]
    paths = []
    for item in map(os.fspath, inputs):
        if os.path.isdir(item):
            paths += _mesh_files(item)
        elif os.path.isfile(item):
            paths.append(item)
        elif glob.has_magic(item):
            matches = sorted(glob.glob(item, recursive=True))
            if not matches:
                raise MeshFileError(f"no file matches the pattern {item!r}")
            paths += [p for m in matches for p in (_mesh_files(m) if os.path.isdir(m) else [m])]
        else:
            raise MeshFileError(f"no such file or folder: {item!r}")
    unique = list(dict.fromkeys(os.path.abspath(p) for p in paths))
    if not unique:
        raise InvalidParameterError(f"no mesh files ({', '.join(SUPPORTED_FORMATS)}) in {list(inputs)}")
    return unique


def output_folders(items: list[str | MemoryMesh]) -> dict[str, str]:
    """Each input's output folder, relative to the run's, by its label (a path, or an in-memory
    mesh's :attr:`~MemoryMesh.label`): a path's path below the inputs' common folder without the
    extension (``scans/bunny.obj`` -> ``scans/bunny``), or with it (``bunny_obj``) where two meshes
    differ only there; an in-memory mesh's name."""
    paths = [item for item in items if isinstance(item, str)]
    folders = _path_folders(paths) if paths else {}
    # Nor the folder above a path's: an in-memory mesh's files stay apart from every path's.
    taken = {part for folder in folders.values() for part in (folder, folder.split(os.sep)[0])}
    for item in items:
        if isinstance(item, MemoryMesh):
            folders[item.label] = memory_folder(item.name, taken)
            taken.add(folders[item.label])
    return folders


def _path_folders(paths: list[str]) -> dict[str, str]:
    root = os.path.commonpath([os.path.dirname(p) for p in paths])
    relative = {p: os.path.relpath(p, root) for p in paths}
    stems = [os.path.splitext(r)[0] for r in relative.values()]
    folders, taken = {}, set()
    for p, r in relative.items():
        folder = os.path.splitext(r)[0] if stems.count(os.path.splitext(r)[0]) == 1 else r.replace(".", "_")
        unique, k = folder, 2
        while unique in taken:  # x.obj and x.ply become x_obj, x_ply: a file x_obj.ply must not share one
            unique, k = f"{folder}_{k}", k + 1
        taken.add(unique)
        folders[p] = unique
    return folders
