"""Pictures of per-vertex values on the mesh itself: an orthographic painter's renderer on
matplotlib (no OpenGL needed), shaded by the facing of each triangle."""

from __future__ import annotations

import numpy as np

#: Default view: elevation and azimuth in degrees (matplotlib's 3D convention), y up (the OBJ
#: and glTF convention).
VIEW = (25.0, -60.0)

#: Coordinates reordered so that the named axis is up (the view below is built with z up).
UP_AXES = {"x": [1, 2, 0], "y": [2, 0, 1], "z": [0, 1, 2]}


def view_rotation(elevation: float, azimuth: float) -> np.ndarray:
    """(3, 3) rotation whose rows are the view axes in object coordinates: right, up, and towards
    a camera at ``elevation`` degrees above the xy plane and ``azimuth`` degrees around z."""
    e, a = np.radians(elevation), np.radians(azimuth)
    towards = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    right = np.array([-np.sin(a), np.cos(a), 0.0])
    return np.stack([right, np.cross(towards, right), towards])


def draw_vertex_values(ax, positions: np.ndarray, faces: np.ndarray, values: np.ndarray, cmap: str, low: float,
                       high: float, view: tuple[float, float] = VIEW, up: str = "y"):
    """Draws the mesh into ``ax`` with each face coloured by the mean of its vertex values
    (NaN grey) and darkened where it turns away from the viewer, seen from ``view`` with the
    ``up`` axis up. Returns a ScalarMappable for a colourbar."""
    import matplotlib
    from matplotlib.collections import PolyCollection

    p = (positions - positions.mean(axis=0))[:, UP_AXES[up]] @ view_rotation(*view).T
    corners = p[faces]                                    # (F, 3, 3)
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    length = np.linalg.norm(normals, axis=1)
    facing = np.abs(normals[:, 2]) / np.where(length > 0, length, 1.0)
    corner_values = values[faces]
    known = np.isfinite(corner_values).sum(axis=1)
    # The mean of the known corners; NaN (drawn grey) where no corner is known.
    face_values = np.where(known > 0, np.nansum(corner_values, axis=1) / np.maximum(known, 1), np.nan)
    norm = matplotlib.colors.Normalize(low, high)
    colours = matplotlib.colormaps[cmap](norm(np.nan_to_num(face_values, nan=low)))
    colours[~np.isfinite(face_values)] = (0.5, 0.5, 0.5, 1.0)
    colours[:, :3] *= (0.35 + 0.65 * facing)[:, None]
    order = np.argsort(corners[:, :, 2].mean(axis=1))    # far to near
    # Edges in the face colour close the hairline gaps antialiasing leaves between polygons.
    ax.add_collection(PolyCollection(corners[order][:, :, :2], facecolors=colours[order], edgecolors=colours[order],
                                     linewidths=0.3))
    ax.set_xlim(p[:, 0].min(), p[:, 0].max())
    ax.set_ylim(p[:, 1].min(), p[:, 1].max())
    ax.set_aspect("equal")
    ax.set_axis_off()
    return matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap)
