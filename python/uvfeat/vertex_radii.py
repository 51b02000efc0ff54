"""One radius per vertex: the scale varies over the surface.

``radius`` given as a NumPy array of one length per row of ``mesh.positions`` (mesh units; a list
stays a scale stack) sets each vertex's own ball. With ``quadrature="surfels"`` and the integral
estimators every vertex is the centre of its own ball of its own radius (DESIGN.md §1.4.9), exactly.
The map-based paths compute one map per radius, so there the maps are computed at radii spaced
by at most :data:`LEVEL_RATIO` from the smallest to the largest given radius, and each vertex
reads the two levels around its radius, interpolated linearly in ``log r``. A feature map's texel
does the same at the radius of its surface point, the vertices' radii interpolated over its face
(:func:`uvfeat.vertex_texture.vertex_texture`). A constant array is one level: the scalar radius's
values exactly.
"""

from __future__ import annotations

import numpy as np

from .errors import InvalidParameterError

#: Largest ratio between two consecutive radii of the maps that per-vertex radii read: features
#: change slowly with log r, so over a fourth of an octave linear interpolation is within a small
#: fraction of that change.
LEVEL_RATIO = 2.0 ** 0.25


def per_vertex_radii(radius, n_vertices: int) -> np.ndarray | None:
    """``radius`` as float64 lengths when it is an array of one radius per vertex; None otherwise
    (a number, a percentage or a list of radii).

    Raises
    ------
    InvalidParameterError
        A radius that is not positive and finite (naming the first such vertex).
    """
    if not isinstance(radius, np.ndarray) or radius.ndim != 1 or len(radius) != n_vertices or n_vertices < 2:
        return None
    if not np.issubdtype(radius.dtype, np.number):
        raise InvalidParameterError(f"per-vertex radii must be numbers (lengths in mesh units), got dtype {radius.dtype}")
    radii = radius.astype(np.float64, copy=False)
    bad = ~(np.isfinite(radii) & (radii > 0))
    if bad.any():
        vertex = int(np.flatnonzero(bad)[0])
        raise InvalidParameterError(f"the radius of vertex {vertex} is {radii[vertex]}: radii must be positive and "
                                    f"finite ({int(bad.sum())} vertices are not)")
    return radii


def levels(radii: np.ndarray) -> np.ndarray:
    """Radii from ``radii.min()`` to ``radii.max()``, consecutive ones at most :data:`LEVEL_RATIO` apart
    (one level where all radii are equal)."""
    low, high = float(radii.min()), float(radii.max())
    steps = int(np.ceil(np.log(high / low) / np.log(LEVEL_RATIO) - 1e-9))
    return np.array([low]) if steps <= 0 else low * (high / low) ** (np.arange(steps + 1) / steps)


class LevelReader:
    """Values given at the radii ``at`` (level ``k`` at ``at[k]``) read at each of ``radii``: where
    each radius lies among the levels is worked out once, for every array read."""

    def __init__(self, at: np.ndarray, radii: np.ndarray):
        position = (np.zeros(len(radii)) if len(at) == 1 else
                    np.interp(np.log(radii), np.log(at), np.arange(len(at), dtype=np.float64)))
        self.columns = np.arange(len(radii))
        self.below = np.minimum(position.astype(np.int64), max(len(at) - 2, 0))
        self.t = position - self.below
        self.nearest_level = np.rint(position).astype(np.int64)

    def interpolate(self, values: np.ndarray) -> np.ndarray:
        """``values`` (``(n_levels, n)``) linearly in ``log r`` between the two levels around
        each radius."""
        if len(values) == 1:
            return values[0]
        t = self.t.astype(values.dtype)
        low, high = values[self.below, self.columns], values[self.below + 1, self.columns]
        # A radius on a level reads that level alone (its neighbour level may be NaN there).
        return np.where(t == 0, low, np.where(t == 1, high, (1 - t) * low + t * high))

    def nearest(self, values: np.ndarray) -> np.ndarray:
        """``values`` (``(n_levels, n, ...)``) of the level nearest each radius in ``log r``: for
        what cannot be blended (counts, flags, directions)."""
        return values[self.nearest_level, self.columns]

    def read(self, values: np.ndarray, interpolated: bool = True) -> np.ndarray:
        return self.interpolate(values) if interpolated else self.nearest(values)


def interpolate(values: np.ndarray, at: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """Per vertex, ``values`` (``(n_levels, n_vertices)``, level ``k`` at radius ``at[k]``) read at its
    radius, linearly in ``log r`` between the two levels around it."""
    return LevelReader(at, radii).interpolate(values)
