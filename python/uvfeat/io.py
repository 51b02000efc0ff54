"""Loading meshes from files (glTF/GLB, OBJ, PLY, OFF, STL, ...) through trimesh, and writing
files whole (:func:`atomic_file`)."""

from __future__ import annotations

import contextlib
import glob
import os
import warnings
from collections.abc import Iterator

import numpy as np

from .atlas import Atlas
from .errors import InvalidMeshError, MeshFileError, UVError, UVWarning
from .mesh import Mesh
from .unwrap import UNWRAP_METHODS, UV_POLICIES

#: File extensions uvfeat reads (through trimesh).
SUPPORTED_FORMATS = ("obj", "ply", "glb", "gltf", "off", "stl")


#: Formats that are text only: a NUL byte in them means the file is not what its name says.
TEXT_FORMATS = ("obj", "off")

#: Bytes read to tell a text file from a binary one.
SNIFF_BYTES = 1 << 16

#: With ``uv="auto"``, a file whose UVs overlap on more than this share of their texels is
#: re-atlased: past it the overlaps are folded or stacked parts, not a few stray triangles.
MAX_OVERLAP_SHARE = 0.01

#: Buffer size of the overlap check (about 50 ms for 100K faces).
OVERLAP_CHECK_RESOLUTION = 512


def _trimesh_geometry(path: str):
    import trimesh

    try:
        loaded = trimesh.load(path, process=False)
        # A scene's parts are only decoded here (their textures too): still part of the reading.
        parts = loaded.dump() if isinstance(loaded, trimesh.Scene) and loaded.geometry else []
    except Exception as exc:  # trimesh raises many types for broken files
        raise MeshFileError(f"cannot read {path!r}: {exc}") from exc
    if isinstance(loaded, trimesh.Scene):
        # A part without faces adds nothing but trouble (no UVs to lay out, no rows to merge).
        meshes = [g for g in parts if isinstance(g, trimesh.Trimesh) and len(g.faces)]
        if not meshes:
            raise InvalidMeshError(f"{path!r} contains no triangle mesh")
        return meshes
    if not isinstance(loaded, trimesh.Trimesh):
        raise InvalidMeshError(f"{path!r} holds a {type(loaded).__name__}, not a triangle mesh")
    return [loaded]


def _parts(path: str) -> list:
    """The triangle meshes of a file (one per glTF primitive instance), with clear errors."""
    if not os.path.exists(path):
        raise MeshFileError(f"no such file: {path!r}")
    if not os.path.isfile(path) or not os.access(path, os.R_OK):
        raise MeshFileError(f"not a readable file: {path!r}")
    extension = os.path.splitext(path)[1].lower().lstrip(".")
    if extension not in SUPPORTED_FORMATS:
        raise MeshFileError(f"unsupported format {extension!r} of {path!r}; supported: {', '.join(SUPPORTED_FORMATS)}")
    if extension in TEXT_FORMATS:
        with open(path, "rb") as file:
            if b"\0" in file.read(SNIFF_BYTES):
                raise MeshFileError(f"cannot read {path!r}: binary data in a text {extension.upper()} file")
    return _trimesh_geometry(path)


def _rows(values, dtype, what: str, path: str) -> np.ndarray:
    """``values`` as rows of three (a broken file's empty parts, whose arrays trimesh may leave
    one-dimensional, as no rows), or an :class:`InvalidMeshError` naming what is malformed."""
    array = np.asarray(values, dtype=dtype)
    if array.size % 3:
        raise InvalidMeshError(f"{path!r}: its {what} are not rows of three (shape {array.shape})")
    return array.reshape(-1, 3)


def _merged(parts: list, path: str) -> tuple[np.ndarray, np.ndarray]:
    """Positions and faces of all parts, concatenated in order."""
    positions = [_rows(g.vertices, np.float64, "vertices", path) for g in parts]
    offsets = np.cumsum([0] + [len(p) for p in positions])[:-1]
    faces = [_rows(g.faces, np.int64, "faces", path) + o for g, o in zip(parts, offsets)]
    return np.concatenate(positions), np.concatenate(faces)


def read_geometry(path: str | os.PathLike) -> tuple[np.ndarray, np.ndarray]:
    """Positions ``(n_vertices, 3)`` float64 and faces ``(n_faces, 3)`` int64 of a mesh file, in
    the order :func:`load` gives them, without building a :class:`~uvfeat.Mesh` or an atlas
    (animation frames stored as mesh files).

    Raises
    ------
    MeshFileError, InvalidMeshError
        As for :func:`load`.
    """
    path = os.fspath(path)
    return _merged(_parts(path), path)


def _uvs_of(geometry) -> np.ndarray | None:
    """A part's per-vertex UVs, or None where it has none (or none that are pairs, one per vertex)."""
    uv = getattr(getattr(geometry, "visual", None), "uv", None)
    if uv is None or len(uv) != len(geometry.vertices):
        return None
    uv = np.asarray(uv, dtype=np.float64)
    return uv[:, :2] if uv.ndim == 2 and uv.shape[1] >= 2 else None


def load(path: str | os.PathLike, *, uv: str = "auto", resolution: int = 1024, normalize_uv: bool = True) -> Mesh:
    """Reads a mesh file into a :class:`~uvfeat.Mesh`.

    Scenes with several meshes or primitives are merged into one mesh, with their node transforms
    applied. Vertices split at UV or normal seams (glTF, PLY) are kept as they are in the file, so
    per-vertex results line up with the file's vertices; uvfeat welds them internally.

    Parameters
    ----------
    path : str or PathLike
        A file of one of :data:`SUPPORTED_FORMATS`.
    uv : {"auto", "require", "charts", "xatlas"}
        ``"auto"`` (default) keeps the file's UVs and builds an automatic atlas (uvfeat's
        normal-cone charts, :mod:`uvfeat.unwrap`) when there are none or when they overlap on more
        than :data:`MAX_OVERLAP_SHARE` of their texels (with a :class:`~uvfeat.errors.UVWarning`;
        smaller overlaps are kept, and :meth:`Atlas.warnings` counts them); ``"require"`` keeps the
        file's UVs as they are and raises :class:`~uvfeat.errors.UVError` when there are none;
        ``"charts"`` and ``"xatlas"`` always build a new atlas with that unwrapper (tiled UVs, for
        instance). Per-vertex results follow the file's vertex order
        whichever atlas is used.
    resolution : int
        Geometry-buffer resolution an automatic atlas is packed for (2+ texel gutters there).
    normalize_uv : bool
        See :class:`~uvfeat.Mesh`.

    Raises
    ------
    MeshFileError
        Missing, unreadable or unsupported file.
    InvalidMeshError, UVError
        As for :class:`~uvfeat.Mesh`.
    """
    if uv not in UV_POLICIES:
        raise ValueError(f"uv must be one of {UV_POLICIES}, got {uv!r}")
    path = os.fspath(path)
    parts = _parts(path)
    positions, faces = _merged(parts, path)
    part_uvs = [_uvs_of(g) for g in parts]
    name = os.path.basename(path)
    has_uvs = all(u is not None for u in part_uvs)
    if not has_uvs and uv == "require":
        missing = "some of its meshes have" if any(u is not None for u in part_uvs) else "it has"
        raise UVError(f"{name}: {missing} no UV coordinates; use uv='auto' for an automatic atlas")
    if uv in UNWRAP_METHODS or not has_uvs:
        return with_uv_policy(Mesh(positions, faces, name=name), uv, resolution)
    if len(parts) > 1:
        part_uvs = _tile_part_uvs(part_uvs)
        warnings.warn(f"{name}: {len(parts)} meshes merged; their UV layouts were tiled side by side into one "
                      "atlas so they do not overlap", UVWarning, stacklevel=2)
    mesh = Mesh(positions, faces, np.concatenate(part_uvs), name=name, normalize_uv=normalize_uv)
    return with_uv_policy(mesh, uv, resolution)


def with_uv_policy(mesh: Mesh, uv: str = "auto", resolution: int = 1024) -> Mesh:
    """``mesh`` with :func:`load`'s ``uv`` policy applied: its own UVs (checked for overlaps with
    ``"auto"``), or an automatic atlas (vertex order unchanged) where it has none or ``uv`` names an
    unwrapper.

    Raises
    ------
    UVError
        ``uv="require"`` and the mesh has no UVs.
    """
    if uv not in UV_POLICIES:
        raise ValueError(f"uv must be one of {UV_POLICIES}, got {uv!r}")
    if uv in UNWRAP_METHODS or not mesh.has_uvs:
        if uv == "require":
            raise UVError(f"{mesh.name}: it has no UV coordinates; use uv='auto' for an automatic atlas")
        bare = Mesh(mesh.positions, mesh.faces, name=mesh.name) if mesh.has_uvs else mesh
        return bare.with_atlas(resolution=resolution, method=uv if uv in UNWRAP_METHODS else UNWRAP_METHODS[0])
    if uv == "auto":
        share = Atlas(mesh, OVERLAP_CHECK_RESOLUTION).overlap_share
        if share > MAX_OVERLAP_SHARE:
            warnings.warn(f"{mesh.name}: the UVs overlap on {share:.1%} of their texels, so the features there "
                          "would mix surface points; re-atlased (vertex order unchanged; uv='require' keeps "
                          "the UVs)", UVWarning, stacklevel=3)
            return Mesh(mesh.positions, mesh.faces, name=mesh.name).with_atlas(resolution=resolution)
    return mesh


def _tile_part_uvs(part_uvs: list[np.ndarray], margin: float = 0.01) -> list[np.ndarray]:
    """Places each part's UV layout (normalised to the unit square) in its own cell of a grid."""
    from .mesh import normalize_uvs

    side = int(np.ceil(np.sqrt(len(part_uvs))))
    cell = 1.0 / side
    tiled = []
    for k, uvs in enumerate(part_uvs):
        unit, _ = normalize_uvs(uvs)
        corner = np.array([k % side, k // side], dtype=np.float64) * cell
        tiled.append(corner + cell * (margin + (1.0 - 2.0 * margin) * unit))
    return tiled


#: What :func:`atomic_file`'s temporary names hold between the stem and the process id.
PARTIAL = ".partial-"


def remove_partials(folder: str | os.PathLike) -> None:
    """Removes the temporary files of :func:`atomic_file` that a killed run left in ``folder``."""
    for stale in glob.glob(os.path.join(glob.escape(os.fspath(folder)), f"*{PARTIAL}*")):
        with contextlib.suppress(FileNotFoundError):
            os.remove(stale)


@contextlib.contextmanager
def atomic_file(path: str | os.PathLike) -> Iterator[str]:
    """A temporary name beside ``path`` to write to, renamed to ``path`` when the block ends
    without an error and removed otherwise: a file is complete or absent, never half-written, even
    when the process is killed while writing. The name keeps the extension, from which NumPy,
    trimesh, Pillow and matplotlib take the format."""
    stem, extension = os.path.splitext(os.fspath(path))
    temporary = f"{stem}{PARTIAL}{os.getpid()}{extension}"
    try:
        yield temporary
        os.replace(temporary, path)
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.remove(temporary)
