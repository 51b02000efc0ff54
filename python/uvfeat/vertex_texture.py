"""Per-vertex values as a texture on an atlas's charts: each texel the values of the corners of
the face under its centre, interpolated with its barycentric coordinates, as a renderer blends
per-vertex colours over a face. ``uvfeat compute`` writes its maps this way where the per-vertex
values are the surfel sums at the vertices (an atlas of many charts), and a texel's radius is
its surface point's when each vertex has its own (:mod:`uvfeat.vertex_radii`)."""

from __future__ import annotations

import numpy as np

from .errors import InvalidParameterError


def vertex_texture(atlas, values, width: int, dtype=np.float32) -> np.ndarray:
    """``(width, width)`` texture of ``dtype`` (``(k, width, width)`` for ``(k, n_vertices)`` values)
    of ``values`` given per row of ``mesh.positions``, indexed ``[j, i]`` with v up, texel centres
    at ``(i + 0.5) / width``: the values of the triangle under each centre's texel of the atlas's
    face buffer, interpolated with the centre's barycentric coordinates (clamped into the triangle
    where a border texel's centre lies just outside it; a UV triangle without area takes its
    corners' mean). Corners without a finite value are left out and the weights renormalised; NaN
    off the charts and where no corner has a value."""
    mesh = atlas.mesh
    values = np.asarray(values, dtype=np.float64)
    if values.shape[-1:] != (mesh.n_vertices,) or values.ndim > 2:
        raise InvalidParameterError(f"values must be (n_vertices,) or (k, n_vertices) with n_vertices = "
                                    f"{mesh.n_vertices}, got shape {values.shape}")
    if isinstance(width, bool) or not isinstance(width, (int, np.integer)) or width <= 0:
        raise InvalidParameterError(f"width must be a positive integer, got {width!r}")
    face_buffer = atlas.face
    pick = ((np.arange(width) + 0.5) * face_buffer.shape[0] / width).astype(np.int64)
    faces = face_buffer[np.ix_(pick, pick)]
    covered = faces >= 0
    j, i = np.nonzero(covered)
    centre = np.stack([(i + 0.5) / width, (j + 0.5) / width], axis=-1)
    face = faces[covered]
    uv = mesh.uvs[mesh.uv_faces[face]]                               # (n, 3, 2)
    e1, e2, d = uv[:, 1] - uv[:, 0], uv[:, 2] - uv[:, 0], centre - uv[:, 0]
    det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    with np.errstate(invalid="ignore", divide="ignore"):
        b1 = (d[:, 0] * e2[:, 1] - d[:, 1] * e2[:, 0]) / det
        b2 = (e1[:, 0] * d[:, 1] - e1[:, 1] * d[:, 0]) / det
    weights = np.where((det != 0)[:, None], np.clip(np.stack([1 - b1 - b2, b1, b2], axis=-1), 0.0, None), 1.0)
    rows = values.reshape(-1, mesh.n_vertices)
    out = np.full((len(rows), width, width), np.nan, dtype=dtype)
    corners = mesh.faces[face]
    for row, texture in zip(rows, out):
        corner_values = row[corners]
        finite = np.isfinite(corner_values)
        w = np.where(finite, weights, 0.0)
        total = w.sum(axis=-1)
        with np.errstate(invalid="ignore", divide="ignore"):
            texture[covered] = np.where(total > 0, (w * np.where(finite, corner_values, 0.0)).sum(axis=-1) / total,
                                        np.nan)
    return out if values.ndim == 2 else out[0]
