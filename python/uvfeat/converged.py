"""A converged object-space reference: the reference of :mod:`uvfeat.reference` evaluated on a
refined copy of the same surface, at the original vertices.

Midpoint subdivision keeps the original vertices (first, in their order) and, with
``surface="facets"``, the piecewise-flat surface, so the reference of the subdivided mesh measures
the same surface with neighbourhoods that no longer grow in whole coarse vertex rings: its error of
order ``h / r`` shrinks with each level. With ``surface="smooth"`` every new vertex is lifted onto
the smooth surface uvfeat's ``surface="smooth"`` integrates (DESIGN.md §1.3): on each face the
Phong surface through its vertices with their area-weighted normals, ``p + 1/2 sum b_i ((x_i - p)
. n_i) n_i``, so the limit is that surface rather than the chords between the vertices. The two
differ by the facets' sagitta, about ``h^2 k / 8``, which is a large part of ``H r^2 / 4`` where
``r`` spans a few edges. Levels are added until two successive ones agree within ``tolerance``
(range-normalised mean change), and the history of changes is returned as the evidence of
convergence. Use it where "the reference" stands for the truth (comparisons, experiments, peers).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from .errors import InvalidParameterError
from .interop import as_mesh
from .mesh import Mesh, vertex_normals
from .options import feature_names, resolve_radius
from .reference import Reference


@dataclass
class ConvergedReference:
    """Reference values at the original vertices of a mesh, from its finest refinement."""

    values: dict[str, np.ndarray]
    """``(n,)`` float64 per feature, one per requested vertex (every row of ``mesh.positions``
    by default)."""
    level: int
    """Subdivision levels of the returned values (each level has 4x the faces)."""
    changes: list[dict[str, float]] = field(default_factory=list)
    """Per level ``k >= 1``: the mean change of each feature from level ``k - 1``, in percent of
    the feature's Q1-Q99 range at level ``k`` (of its mean magnitude where that is larger)."""
    faces: list[int] = field(default_factory=list)
    """Faces of each level."""
    timings_s: list[float] = field(default_factory=list)
    """Seconds of each level (subdivision, connectivity and estimation)."""
    converged: bool = False
    """Whether the last change met the tolerance asked for."""

    def __getitem__(self, name: str) -> np.ndarray:
        return self.values[name]


def _welded(mesh: Mesh) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Positions and faces with the vertices a file splits at seams merged (exactly equal
    positions), and the welded index of every input vertex."""
    positions, inverse = np.unique(mesh.positions, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    return positions, inverse[mesh.faces], inverse


SURFACES = ("facets", "smooth")


def _lifted_onto_smooth_surface(positions: np.ndarray, faces: np.ndarray, flat: np.ndarray,
                                refined_faces: np.ndarray, level: int) -> np.ndarray:
    """The vertices of ``level`` midpoint subdivisions (``flat``, ``refined_faces``) of
    (``positions``, ``faces``) moved onto the coarse mesh's smooth (Phong, 1/2) surface. Midpoint
    subdivision gives each face four consecutive children, so a refined face's coarse face is its
    index over ``4 ** level``; a vertex on a coarse edge gets the same point from either face."""
    normals = vertex_normals(positions, faces)
    # A vertex on no face (the file's, kept by the welding) stays where it is.
    owner = np.full(len(flat), -1, dtype=np.int64)
    owner[refined_faces.reshape(-1)] = np.repeat(np.arange(len(refined_faces)) // 4 ** level, 3)
    lifted = flat.copy()
    used = owner >= 0
    flat, corners = flat[used], faces[owner[used]]
    x = positions[corners]                                        # (n, 3, 3)
    e1, e2, d = x[:, 1] - x[:, 0], x[:, 2] - x[:, 0], flat - x[:, 0]
    g11, g12, g22 = (e1 * e1).sum(1), (e1 * e2).sum(1), (e2 * e2).sum(1)
    r1, r2 = (e1 * d).sum(1), (e2 * d).sum(1)
    det = g11 * g22 - g12 * g12
    area = det > 0
    with np.errstate(invalid="ignore", divide="ignore"):
        b1, b2 = (g22 * r1 - g12 * r2) / det, (g11 * r2 - g12 * r1) / det
    # A face without area has no barycentrics: its points keep their flat positions.
    weights = np.where(area[:, None], np.stack([1 - b1 - b2, b1, b2], axis=1), 0.0)
    n = normals[corners]
    heights = ((x - flat[:, None]) * n).sum(2)
    lifted[used] = flat + 0.5 * (weights[..., None] * heights[..., None] * n).sum(1)
    return lifted


def _change(finer: np.ndarray, coarser: np.ndarray) -> float:
    known = np.isfinite(finer) & np.isfinite(coarser)
    if not known.any():
        return float("nan")
    # The Q1-Q99 range, or the mean magnitude where the feature hardly varies (H of a sphere).
    scale = max(np.percentile(finer[known], 99) - np.percentile(finer[known], 1), np.mean(np.abs(finer[known])))
    return float(100 * np.mean(np.abs(finer[known] - coarser[known])) / max(scale, np.finfo(float).tiny))


def converged_reference(mesh: Mesh, features, radius, *, vertices=None, tolerance: float = 0.5, max_levels: int = 3,
                        min_levels: int = 1, progress=None, coarse: dict[str, np.ndarray] | None = None,
                        surface: str = "facets", **options) -> ConvergedReference:
    """The object-space reference of ``mesh``'s surface, refined until it converges.

    Parameters
    ----------
    mesh : Mesh
        Any triangle mesh (UVs are not needed), or any of :data:`uvfeat.interop.ACCEPTED`
        (values per vertex of its surface).
    features, radius, **options
        As for :meth:`uvfeat.reference.Reference.compute`; a percentage radius is resolved on
        ``mesh`` (subdivision keeps its bounding box).
    vertices : array_like of int, optional
        Evaluate only at these rows of ``mesh.positions`` (default: all).
    tolerance : float
        Stop when every feature changed by less than this from the previous level (percent of
        its Q1-Q99 range, or of its mean magnitude where that is larger; default 0.5).
    max_levels, min_levels : int
        Subdivision levels tried at most (each multiplies the faces by 4) and at least.
    progress : callable, optional
        Called as ``progress(level, faces)`` before each level.
    coarse : dict, optional
        The reference's values on ``mesh`` itself at every row (level 0), when the caller has
        them already: level 0 is then not computed again (its time is recorded as 0).
    surface : {"facets", "smooth"}
        The surface refined: the flat faces, or the smooth surface through the vertices that
        ``surface="smooth"`` of the parametric computation integrates (see the module's notes).
    """
    mesh = as_mesh(mesh)
    if not (isinstance(max_levels, int) and isinstance(min_levels, int) and 0 <= min_levels <= max_levels <= 5):
        raise InvalidParameterError(f"need 0 <= min_levels <= max_levels <= 5, got {min_levels}, {max_levels}")
    if not (np.isfinite(tolerance) and tolerance > 0):
        raise InvalidParameterError(f"tolerance must be a positive percentage, got {tolerance!r}")
    if surface not in SURFACES:
        raise InvalidParameterError(f"surface must be one of {SURFACES}, got {surface!r}")
    import trimesh

    names = feature_names(features)
    r = resolve_radius(radius, mesh.bounding_box_diagonal)
    rows = np.arange(mesh.n_vertices) if vertices is None else np.asarray(vertices, dtype=np.int64)
    if rows.ndim != 1 or (rows.size and (rows.min() < 0 or rows.max() >= mesh.n_vertices)):
        raise InvalidParameterError(f"vertices must be indices of the mesh's {mesh.n_vertices} vertices")
    coarse_positions, coarse_faces, welded = _welded(mesh)
    positions, faces, flat = coarse_positions, coarse_faces, coarse_positions
    result = ConvergedReference(values={}, level=0)
    previous = None
    for level in range(max_levels + 1):
        started = time.perf_counter()
        if level:
            flat, faces = trimesh.remesh.subdivide(flat, faces)
            positions = flat if surface == "facets" else _lifted_onto_smooth_surface(
                coarse_positions, coarse_faces, flat, faces, level)
        if progress is not None:
            progress(level, len(faces))
        if level == 0 and coarse is not None:
            values = {name: np.asarray(coarse[name])[rows] for name in names}
        else:
            refined = Mesh(positions, faces, name=f"{mesh.name} x{4 ** level}")
            values = Reference(refined).compute(names, r, vertices=welded[rows], **options)
        result.faces.append(len(faces))
        result.timings_s.append(time.perf_counter() - started)
        result.values, result.level = values, level
        if previous is not None:
            result.changes.append({name: _change(values[name], previous[name]) for name in names})
            result.converged = all(c < tolerance for c in result.changes[-1].values())
            if result.converged and level >= min_levels:
                break
        previous = values
    return result
