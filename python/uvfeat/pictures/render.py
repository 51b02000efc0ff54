"""Pictures of per-vertex values on the mesh itself: an orthographic z-buffer rasteriser (no
OpenGL, no display), smooth-shaded by interpolated vertex normals and coloured per pixel by the
interpolated value. The core draws them; this module sets up the views. docs/BENCHMARKS.md (3D
pictures) has the measurements that chose it over matplotlib's painter's algorithm and an
offscreen GL stack."""

from __future__ import annotations

import numpy as np

from .. import _core

#: Default view: elevation and azimuth in degrees (matplotlib's 3D convention), y up (the OBJ
#: and glTF convention).
VIEW = (25.0, -60.0)

#: Coordinates reordered so that the named axis is up (the view below is built with z up).
UP_AXES = {"x": [1, 2, 0], "y": [2, 0, 1], "z": [0, 1, 2]}

#: Pixels per output pixel along each axis: edges are antialiased by averaging them.
SUPERSAMPLING = 2


def view_rotation(elevation: float, azimuth: float) -> np.ndarray:
    """(3, 3) rotation whose rows are the view axes in object coordinates: right, up, and towards
    a camera at ``elevation`` degrees above the xy plane and ``azimuth`` degrees around z."""
    e, a = np.radians(elevation), np.radians(azimuth)
    towards = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    right = np.array([-np.sin(a), np.cos(a), 0.0])
    return np.stack([right, np.cross(towards, right), towards])


def view_coordinates(positions: np.ndarray, view: tuple[float, float], up: str,
                     centre: np.ndarray | None = None) -> np.ndarray:
    """Positions in view coordinates (x right, y up, z towards the camera) around ``centre``
    (default: the mean of the positions)."""
    centre = positions.mean(axis=0) if centre is None else centre
    # einsum, not a matrix product: after a large product OpenBLAS's threads spin on the cores
    # for a while, and the core's picture drawn next took 35-40 ms longer (of 60).
    return np.einsum("ij,vj->vi", view_rotation(*view), (positions - centre)[:, UP_AXES[up]])


def front_side(positions: np.ndarray, faces: np.ndarray) -> int:
    """Which side of the faces can be seen: 0 for an open mesh (both: its inside shows through
    the borders), +1 for a closed mesh whose faces turn counter-clockwise seen from outside, -1
    for one whose faces turn inwards (the sign of its volume says which; the core works it out)."""
    return _core.front_side(np.ascontiguousarray(positions, dtype=np.float64),
                            np.ascontiguousarray(faces, dtype=np.int64))


def render_values(positions: np.ndarray, faces: np.ndarray, values: np.ndarray, cmap: str, low: float, high: float,
                  view: tuple[float, float] = VIEW, up: str = "y", pixels_per_unit: float = 100.0,
                  bounds: tuple[np.ndarray, np.ndarray] | None = None, centre: np.ndarray | None = None,
                  front: int | None = None) -> np.ndarray:
    """(H, W, 4) float RGBA picture (row 0 at the top, transparent off the mesh) of the mesh
    coloured by per-vertex ``values`` through ``cmap`` clamped to ``[low, high]`` (NaN grey),
    smooth-shaded, seen orthographically from ``view`` with the ``up`` axis up.

    The picture spans ``bounds`` (lower-left and upper-right corners in view coordinates; default
    the mesh's own extent) at ``pixels_per_unit``; ``centre`` is the point the view turns around
    (default the mean vertex). Fixed bounds and centre keep the frames of an animation still.
    ``front`` is the mesh's :func:`front_side`, worked out here when not given (pass it when
    drawing the same faces several times). The core draws it (``uvfeat-core``, ``shaded_view``):
    the faces the viewer can see, a value per pixel barycentric over the corners whose value is
    known, a headlight on the interpolated normal (two-sided), edges antialiased by averaging
    :data:`SUPERSAMPLING`² pixels."""
    import matplotlib

    p = np.ascontiguousarray(view_coordinates(positions, view, up, centre), dtype=np.float64)
    lower, upper = bounds if bounds is not None else (p[:, :2].min(axis=0), p[:, :2].max(axis=0))
    scale = pixels_per_unit * SUPERSAMPLING
    width, height = (max(1, int(np.ceil(float(e) * scale))) for e in (upper - lower))
    colormap = matplotlib.colormaps[cmap]
    palette = np.ascontiguousarray(colormap(np.arange(colormap.N))[:, :3], dtype=np.float64)
    return _core.shaded_view(p, np.ascontiguousarray(faces, dtype=np.int64),
                             np.ascontiguousarray(values, dtype=np.float64), palette, (float(low), float(high)),
                             (float(lower[0]), float(upper[1])), float(scale), (height, width), SUPERSAMPLING,
                             front_side(positions, faces) if front is None else int(front))


def axes_pixels(ax) -> tuple[float, float]:
    """The size of ``ax`` in display pixels."""
    box = ax.get_window_extent()
    return box.width, box.height


def draw_vertex_values(ax, positions: np.ndarray, faces: np.ndarray, values: np.ndarray, cmap: str, low: float,
                       high: float, view: tuple[float, float] = VIEW, up: str = "y", front: int | None = None):
    """Draws the mesh into ``ax`` coloured by its per-vertex values (NaN grey), smooth-shaded and
    seen from ``view`` with the ``up`` axis up, at the axes' own pixel size. Returns a
    ScalarMappable for a colourbar."""
    import matplotlib

    p = view_coordinates(positions, view, up)
    lower, upper = p[:, :2].min(axis=0), p[:, :2].max(axis=0)
    extent = np.maximum(upper - lower, 1e-300)
    width, height = axes_pixels(ax)
    pixels_per_unit = min(width / extent[0], height / extent[1])
    picture = render_values(positions, faces, values, cmap, low, high, view, up, pixels_per_unit, (lower, upper),
                            front=front)
    ax.imshow(picture, extent=(lower[0], upper[0], lower[1], upper[1]), interpolation="antialiased")
    ax.set_xlim(lower[0], upper[0])
    ax.set_ylim(lower[1], upper[1])
    ax.set_aspect("equal")
    ax.set_axis_off()
    return matplotlib.cm.ScalarMappable(norm=matplotlib.colors.Normalize(low, high), cmap=cmap)
