"""The :class:`Mesh`: positions, faces and per-corner UVs, validated once.

Array contract (one place): positions are float64 ``(n_vertices, 3)``, faces int64
``(n_faces, 3)`` with counter-clockwise corners seen from outside, UVs float64 ``(n_uvs, 2)`` in
``[0, 1]^2`` (u right, v up) and uv_faces int64 ``(n_faces, 3)`` indexing ``uvs`` per corner (OBJ
style). Arrays handed out are read-only.
"""

from __future__ import annotations

import functools
import warnings

import numpy as np

from . import _core
from .errors import InvalidMeshError, MeshWarning, UVError, UVWarning


def _readonly(array: np.ndarray) -> np.ndarray:
    array.flags.writeable = False
    return array


def _float_rows(values, width: int, name: str) -> np.ndarray:
    # A copy: the mesh's arrays are read-only, the caller's stay as they were.
    array = np.array(values, dtype=np.float64, order="C")
    if array.ndim != 2 or array.shape[1] != width:
        raise InvalidMeshError(f"{name} must have shape (n, {width}), got {array.shape}")
    # One flat test first: the per-row one (axis=1), needed only for the message, costs a few ms
    # per 100K rows.
    if np.isfinite(array).all():
        return array
    bad = ~np.isfinite(array).all(axis=1)
    index = int(np.flatnonzero(bad)[0])
    what = "vertex" if name == "positions" else "UV"
    error = InvalidMeshError if name == "positions" else UVError
    raise error(f"{what} {index} has a non-finite value {array[index].tolist()} (NaN or Inf); "
                f"{bad.sum()} rows are affected")


def _index_rows(values, count: int, name: str, what: str) -> np.ndarray:
    """Faces as int64 (m, k); polygons (k > 3) are fan-triangulated with a warning."""
    array = np.asarray(values)
    if array.ndim != 2 or array.shape[1] < 3:
        raise InvalidMeshError(f"{name} must have shape (n_faces, 3) (or (n_faces, k>3) polygons), got {array.shape}")
    if not np.issubdtype(array.dtype, np.integer):
        if not np.all(np.mod(array, 1) == 0):
            raise InvalidMeshError(f"{name} must hold integer indices, got dtype {array.dtype}")
    array = array.astype(np.int64)
    if array.size and (array.min() < 0 or array.max() >= count):
        bad = int(np.flatnonzero((array < 0).any(axis=1) | (array >= count).any(axis=1))[0])
        raise InvalidMeshError(f"face {bad} of {name} refers to {what} {array[bad].tolist()}, "
                               f"but there are only {count}")
    if array.shape[1] > 3:
        k = array.shape[1]
        warnings.warn(f"{name}: {len(array)} polygons of {k} corners were fan-triangulated", MeshWarning,
                      stacklevel=3)
        fans = [array[:, [0, j, j + 1]] for j in range(1, k - 1)]
        array = np.stack(fans, axis=1).reshape(-1, 3)
    return np.ascontiguousarray(array)


def face_area_vectors(positions: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """(n_faces, 3): each face's normal scaled by twice its area (counter-clockwise corners)."""
    corners = positions[faces]
    return np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])


def vertex_normals(positions: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Unit area-weighted vertex normals (zero where a vertex has no area around it)."""
    face_normals = face_area_vectors(positions, faces)
    corner_vertices = faces.reshape(-1)
    normals = np.column_stack([np.bincount(corner_vertices, np.repeat(face_normals[:, axis], 3), len(positions))
                               for axis in range(3)])
    length = np.linalg.norm(normals, axis=1, keepdims=True)
    return normals / np.where(length > 0, length, 1.0)


def normalize_uvs(uvs: np.ndarray) -> tuple[np.ndarray, tuple[float, float, float]]:
    """Maps UVs into [0, 1]^2 by one translation and one uniform scale (the aspect ratio and the
    layout are kept; nothing is clipped). Returns the UVs and ``(offset_u, offset_v, scale)``."""
    low = uvs.min(axis=0)
    extent = float((uvs.max(axis=0) - low).max())
    scale = 1.0 / extent if extent > 0 else 1.0
    return np.clip((uvs - low) * scale, 0.0, 1.0), (float(low[0]), float(low[1]), scale)


class Mesh:
    """A triangle mesh with optional per-corner UVs.

    Parameters
    ----------
    positions : array_like, (n_vertices, 3) float
        Vertex positions in object units.
    faces : array_like, (n_faces, 3) int
        Vertex indices, counter-clockwise seen from outside. Polygons ``(n_faces, k)`` are
        fan-triangulated with a :class:`~uvfeat.errors.MeshWarning`.
    uvs : array_like, (n_uvs, 2) float, optional
        Parametric coordinates. Without ``uv_faces`` they are per vertex (``n_uvs == n_vertices``).
    uv_faces : array_like, (n_faces, 3) int, optional
        Indices into ``uvs`` per face corner (OBJ style).
    normalize_uv : bool, default True
        UVs outside ``[0, 1]`` are mapped into it with a :class:`~uvfeat.errors.UVWarning`;
        with False they raise :class:`~uvfeat.errors.UVError`.
    name : str, optional
        Shown in reports.

    Raises
    ------
    InvalidMeshError
        Empty mesh, NaN/Inf positions, indices out of range, wrong shapes.
    UVError
        NaN/Inf UVs, or UVs outside ``[0, 1]`` with ``normalize_uv=False``.
    """

    def __init__(self, positions, faces, uvs=None, uv_faces=None, *, normalize_uv: bool = True,
                 name: str | None = None):
        self.name = name or "mesh"
        positions = _float_rows(positions, 3, "positions")
        faces_in = np.asarray(faces)
        faces = _index_rows(faces_in, len(positions), "faces", "vertex")
        if len(positions) == 0 or len(faces) == 0:
            raise InvalidMeshError(f"empty mesh: {len(positions)} vertices and {len(faces)} faces "
                                   "(need at least one triangle)")
        self._positions = _readonly(positions)
        self._faces = _readonly(faces)
        self.uv_normalization: tuple[float, float, float] | None = None
        #: The unwrapper of the UVs where :meth:`with_atlas` made them (``"charts"``, ``"xatlas"``),
        #: None for UVs given with the mesh (or none).
        self.automatic_atlas: str | None = None
        if uvs is None:
            if uv_faces is not None:
                raise UVError("uv_faces was given without uvs")
            self._uvs = self._uv_faces = None
            return
        uvs = _float_rows(uvs, 2, "uvs")
        if uv_faces is None:
            if len(uvs) != len(positions):
                raise UVError(f"per-vertex uvs need one row per vertex ({len(positions)}), got {len(uvs)}; "
                              "pass uv_faces for per-corner UVs")
            uv_faces = faces_in
        uv_faces = _index_rows(uv_faces, len(uvs), "uv_faces", "uv")
        if uv_faces.shape != faces.shape:
            raise UVError(f"uv_faces must have the same shape as faces {faces.shape}, got {uv_faces.shape}")
        if len(uvs) and (uvs.min() < 0.0 or uvs.max() > 1.0):
            low, high = uvs.min(axis=0).tolist(), uvs.max(axis=0).tolist()
            if not normalize_uv:
                raise UVError(f"UVs span {low} .. {high}, outside [0, 1]^2; pass normalize_uv=True "
                              "(or --normalize-uv) to map them into it")
            uvs, self.uv_normalization = normalize_uvs(uvs)
            warnings.warn(f"{self.name}: UVs span {low} .. {high}, outside [0, 1]^2; normalised by one "
                          "translation and uniform scale (layout kept, nothing clipped)", UVWarning, stacklevel=2)
        self._uvs = _readonly(np.ascontiguousarray(uvs))
        self._uv_faces = _readonly(uv_faces)

    # -- arrays -------------------------------------------------------------------------------
    @property
    def positions(self) -> np.ndarray:
        """(n_vertices, 3) float64, read-only."""
        return self._positions

    @property
    def faces(self) -> np.ndarray:
        """(n_faces, 3) int64, read-only."""
        return self._faces

    @property
    def uvs(self) -> np.ndarray | None:
        """(n_uvs, 2) float64 in [0, 1]^2, read-only; None without UVs."""
        return self._uvs

    @property
    def uv_faces(self) -> np.ndarray | None:
        """(n_faces, 3) int64 indices into :attr:`uvs`, read-only; None without UVs."""
        return self._uv_faces

    @property
    def has_uvs(self) -> bool:
        return self._uvs is not None

    @property
    def n_vertices(self) -> int:
        return len(self._positions)

    @property
    def n_faces(self) -> int:
        return len(self._faces)

    @functools.cached_property
    def surface_area(self) -> float:
        """Total area of the faces (object units squared)."""
        return float(0.5 * np.linalg.norm(face_area_vectors(self._positions, self._faces), axis=1).sum())

    @functools.cached_property
    def face_side(self) -> float:
        """``sqrt(2 surface_area / n_faces)``: the side of the mean face, about an edge length."""
        return float(np.sqrt(2.0 * self.surface_area / max(self.n_faces, 1)))

    @functools.cached_property
    def uv_area(self) -> float:
        """Area the faces cover in UV space (of the unit square; 0 without UVs)."""
        if not self.has_uvs:
            return 0.0
        uv = self._uvs[self._uv_faces]
        edges_u, edges_v = uv[:, 1] - uv[:, 0], uv[:, 2] - uv[:, 0]
        return float(0.5 * np.abs(edges_u[:, 0] * edges_v[:, 1] - edges_u[:, 1] * edges_v[:, 0]).sum())

    @functools.cached_property
    def bounding_box_diagonal(self) -> float:
        """Length of the axis-aligned bounding box diagonal of the vertices the faces use (object units)."""
        # A mask, not np.unique: sorting the corners took a copy of the faces (120 MB at 5M faces).
        used = np.zeros(len(self._positions), dtype=bool)
        used[self._faces.reshape(-1)] = True
        # Coordinate by coordinate: NumPy reduces an (n, 3) array along its rows slowly (7 ms of
        # the 10 here for 100K vertices). Where every vertex is used (most meshes), without the
        # masked copy (2.3 -> 1.1 ms for 100K vertices).
        columns = np.ascontiguousarray((self._positions if used.all() else self._positions[used]).T)
        return float(np.linalg.norm(columns.max(axis=1) - columns.min(axis=1)))

    # -- pre-processing -----------------------------------------------------------------------
    @functools.cached_property
    def topology(self) -> _core.Topology:
        """Welded connectivity, charts and edge classes (DESIGN.md §1.2), built once on first use."""
        if not self.has_uvs:
            raise UVError(f"{self.name} has no UV coordinates; use mesh.with_atlas() or load(..., uv='auto') for an automatic atlas")
        return _core.Topology(self._positions, self._faces, self._uvs, self._uv_faces)

    @property
    def n_charts(self) -> int:
        """Number of UV charts."""
        return self.topology.n_charts

    @property
    def vertex_ids(self) -> np.ndarray:
        """(n_vertices,) int64: the welded geometric vertex of every vertex (seam splits merged)."""
        return _readonly(self.topology.vertex_ids)

    def with_atlas(self, *, resolution: int = 1024, padding: int = 4, cache: bool = True,
                   method: str = "charts") -> "Mesh":
        """A copy of this mesh with an automatic multi-chart atlas (see :mod:`uvfeat.unwrap`).

        ``method="charts"`` (default) cuts uvfeat's own normal-cone charts (a fraction of a second
        for 100K faces); ``method="xatlas"`` runs xatlas (seconds per 10K faces). Either atlas is
        cached on disk by the mesh's content, so a second call on the same mesh does not unwrap
        again (``cache=False`` always unwraps). Its :attr:`automatic_atlas` names the unwrapper.
        """
        from .unwrap import UNWRAP_METHODS, chart_uvs, xatlas_uvs

        if method == "charts":
            uvs, uv_faces = chart_uvs(self._positions, self._faces, resolution=resolution, padding=padding,
                                      cache=cache)
        elif method == "xatlas":
            uvs, uv_faces = xatlas_uvs(self._positions, self._faces, resolution=resolution, padding=padding,
                                       cache=cache)
        else:
            raise ValueError(f"method must be one of {UNWRAP_METHODS}, got {method!r}")
        mesh = Mesh(self._positions, self._faces, uvs, uv_faces, name=self.name)
        mesh.automatic_atlas = method
        return mesh

    def with_positions(self, positions) -> "Mesh":
        """The same connectivity and UVs with new positions (a frame of an animation)."""
        positions = _float_rows(positions, 3, "positions")
        if positions.shape != self._positions.shape:
            raise InvalidMeshError(f"new positions have shape {positions.shape}, the mesh has {self._positions.shape}")
        mesh = Mesh(positions, self._faces, self._uvs, self._uv_faces, name=self.name)
        mesh.automatic_atlas = self.automatic_atlas
        return mesh

    def __repr__(self) -> str:
        uv = f"{self.n_charts} charts" if self.has_uvs else "no UVs"
        return f"<uvfeat.Mesh {self.name!r}: {self.n_vertices} vertices, {self.n_faces} faces, {uv}>"
