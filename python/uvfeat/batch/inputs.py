"""The meshes of a batch: files, folders (searched recursively for mesh files) and glob patterns,
each mesh once, in a stable order; and the output folder of each, named after its path."""

from __future__ import annotations

import glob
import os

from ..errors import InvalidParameterError, MeshFileError
from ..io import SUPPORTED_FORMATS


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


def output_folders(paths: list[str]) -> dict[str, str]:
    """Each path's output folder, relative to the run's: its path below the inputs' common folder
    without the extension (``scans/bunny.obj`` -> ``scans/bunny``), or with it (``bunny_obj``)
    where two meshes differ only there."""
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
