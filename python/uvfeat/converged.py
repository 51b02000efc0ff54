"""A converged object-space reference: the reference of :mod:`uvfeat.reference` evaluated on a
refined copy of the same surface, at the original vertices.

Midpoint subdivision keeps the piecewise-flat surface and its original vertices (first, in their
order), so the reference of the subdivided mesh measures the same surface with neighbourhoods
that no longer grow in whole coarse vertex rings: its error of order ``h / r`` shrinks with each
level. Levels are added until two successive ones agree within ``tolerance`` (range-normalised
mean change), and the history of changes is returned as the evidence of convergence. Use it
where "the reference" stands for the truth (comparisons, experiments, peers).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from .errors import InvalidParameterError
from .interop import as_mesh
from .mesh import Mesh
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


def _change(finer: np.ndarray, coarser: np.ndarray) -> float:
    known = np.isfinite(finer) & np.isfinite(coarser)
    if not known.any():
        return float("nan")
    # The Q1-Q99 range, or the mean magnitude where the feature hardly varies (H of a sphere).
    scale = max(np.percentile(finer[known], 99) - np.percentile(finer[known], 1), np.mean(np.abs(finer[known])))
    return float(100 * np.mean(np.abs(finer[known] - coarser[known])) / max(scale, np.finfo(float).tiny))


def converged_reference(mesh: Mesh, features, radius, *, vertices=None, tolerance: float = 0.5, max_levels: int = 3,
                        min_levels: int = 1, progress=None, coarse: dict[str, np.ndarray] | None = None,
                        **options) -> ConvergedReference:
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
    """
    mesh = as_mesh(mesh)
    if not (isinstance(max_levels, int) and isinstance(min_levels, int) and 0 <= min_levels <= max_levels <= 5):
        raise InvalidParameterError(f"need 0 <= min_levels <= max_levels <= 5, got {min_levels}, {max_levels}")
    if not (np.isfinite(tolerance) and tolerance > 0):
        raise InvalidParameterError(f"tolerance must be a positive percentage, got {tolerance!r}")
    import trimesh

    names = feature_names(features)
    r = resolve_radius(radius, mesh.bounding_box_diagonal)
    rows = np.arange(mesh.n_vertices) if vertices is None else np.asarray(vertices, dtype=np.int64)
    if rows.ndim != 1 or (rows.size and (rows.min() < 0 or rows.max() >= mesh.n_vertices)):
        raise InvalidParameterError(f"vertices must be indices of the mesh's {mesh.n_vertices} vertices")
    positions, faces, welded = _welded(mesh)
    result = ConvergedReference(values={}, level=0)
    previous = None
    for level in range(max_levels + 1):
        started = time.perf_counter()
        if level:
            positions, faces = trimesh.remesh.subdivide(positions, faces)
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
