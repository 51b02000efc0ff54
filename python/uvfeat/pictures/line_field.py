"""Principal directions (3D unit vectors per texel) as a line field in the UV plane, and drawn as
short segments on a feature-map picture."""

from __future__ import annotations

import numpy as np


def uv_line_field(atlas, directions: np.ndarray) -> np.ndarray:
    """``(W_c, W_c, ..., 2)`` unit directions in the UV plane (u right, v up) of the 3D tangent
    directions ``(W_c, W_c, ..., 3)`` of a computation texture (any number of directions per
    texel), NaN off the charts.

    A direction ``d`` of the surface is pulled back through the affine map of the triangle each
    texel shows: with ``e1, e2`` its edges in 3D and ``f1, f2`` in UV, ``d ~ a e1 + b e2`` (least
    squares in the triangle's plane) gives ``a f1 + b f2``. The sign is that of ``d`` (a line field
    has none)."""
    directions = np.asarray(directions, dtype=np.float64)
    width = directions.shape[0]
    face_buffer = atlas.face
    pick = ((np.arange(width) + 0.5) * face_buffer.shape[0] / width).astype(np.int64)
    faces = face_buffer[np.ix_(pick, pick)]
    covered = faces >= 0
    mesh, positions = atlas.mesh, atlas.positions
    corners = mesh.faces[faces[covered]]
    uv_corners = mesh.uv_faces[faces[covered]]
    d = directions[covered].reshape(int(covered.sum()), -1, 3)
    e1 = (positions[corners[:, 1]] - positions[corners[:, 0]])[:, None]
    e2 = (positions[corners[:, 2]] - positions[corners[:, 0]])[:, None]
    f1 = (mesh.uvs[uv_corners[:, 1]] - mesh.uvs[uv_corners[:, 0]])[:, None]
    f2 = (mesh.uvs[uv_corners[:, 2]] - mesh.uvs[uv_corners[:, 0]])[:, None]
    g11, g12, g22 = (e1 * e1).sum(-1), (e1 * e2).sum(-1), (e2 * e2).sum(-1)
    r1, r2 = (e1 * d).sum(-1), (e2 * d).sum(-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        det = g11 * g22 - g12 * g12
        a, b = (g22 * r1 - g12 * r2) / det, (g11 * r2 - g12 * r1) / det
        uv = a[..., None] * f1 + b[..., None] * f2
        uv /= np.linalg.norm(uv, axis=-1, keepdims=True)
    out = np.full(directions.shape[:-1] + (2,), np.nan)
    out[covered] = uv.reshape(out[covered].shape)
    return out


def draw_line_field(ax, field: np.ndarray, segments: int = 48, colour: str = "black") -> None:
    """Draws ``field`` (``(W, W, 2)`` from :func:`uv_line_field`) on ``ax``, where the map is shown
    with ``imshow(np.flipud(texture))``: one centred segment per cell of a ``segments``²
    grid, 0.8 cells long."""
    from matplotlib.collections import LineCollection

    width = field.shape[0]
    step = max(1, width // segments)
    centres = np.arange(step // 2, width, step)
    j, i = np.meshgrid(centres, centres, indexing="ij")
    d = field[j, i]
    keep = np.isfinite(d).all(-1)
    # Image rows grow downwards while v grows upwards.
    x, y = i[keep].astype(float), (width - 1 - j[keep]).astype(float)
    half = 0.4 * step * np.stack([d[keep][:, 0], -d[keep][:, 1]], -1)
    lines = np.stack([np.stack([x, y], -1) - half, np.stack([x, y], -1) + half], 1)
    ax.add_collection(LineCollection(lines, colors=colour, linewidths=0.6))
