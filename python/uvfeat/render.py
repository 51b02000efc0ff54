"""Pictures of per-vertex values on the mesh itself: an orthographic z-buffer rasteriser (the
core's, no OpenGL, no display), smooth-shaded by interpolated vertex normals and coloured per
pixel by the interpolated value. docs/BENCHMARKS.md (3D pictures) has the
measurements that chose it over matplotlib's painter's algorithm and an offscreen GL stack."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _core

#: Default view: elevation and azimuth in degrees (matplotlib's 3D convention), y up (the OBJ
#: and glTF convention).
VIEW = (25.0, -60.0)

#: Coordinates reordered so that the named axis is up (the view below is built with z up).
UP_AXES = {"x": [1, 2, 0], "y": [2, 0, 1], "z": [0, 1, 2]}

#: Shading: a headlight, so what faces the viewer is lit fully and the silhouette darkens to AMBIENT.
AMBIENT = 0.35

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
    return (positions - centre)[:, UP_AXES[up]] @ view_rotation(*view).T


def vertex_normals(positions: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Unit area-weighted vertex normals (zero where a vertex has no area around it)."""
    corners = positions[faces]
    face_normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    corner_vertices = faces.reshape(-1)
    normals = np.column_stack([np.bincount(corner_vertices, np.repeat(face_normals[:, axis], 3), len(positions))
                               for axis in range(3)])
    length = np.linalg.norm(normals, axis=1, keepdims=True)
    return normals / np.where(length > 0, length, 1.0)


@dataclass
class Fragments:
    """The nearest triangle under each covered pixel of a ``height x width`` picture (row 0 at
    the top): flat pixel indices, triangle ids and barycentric weights ``(n, 3)``."""

    height: int
    width: int
    pixel: np.ndarray
    face: np.ndarray
    weights: np.ndarray


def rasterise(screen: np.ndarray, faces: np.ndarray, height: int, width: int) -> Fragments:
    """Z-buffer rasterisation of triangles whose vertices are given in pixel units
    (``screen[:, 0]`` right, ``[:, 1]`` down, ``[:, 2]`` towards the viewer, nearest wins), in
    the core (parallel; about 10x faster than the NumPy rasteriser it replaced)."""
    face, weights = _core.rasterise_screen(np.ascontiguousarray(screen, dtype=np.float64),
                                          np.ascontiguousarray(faces, dtype=np.int64), int(height), int(width))
    pixel = np.flatnonzero(face.reshape(-1) >= 0)
    return Fragments(height, width, pixel, face.reshape(-1)[pixel], weights.reshape(-1, 3)[pixel])


def is_closed(faces: np.ndarray) -> bool:
    """Whether every edge is shared by exactly two faces (no border: back faces are never seen)."""
    edges = np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    _, counts = np.unique(edges[:, 0] * (int(faces.max()) + 1) + edges[:, 1], return_counts=True)
    return bool((counts == 2).all())


def signed_volume(positions: np.ndarray, faces: np.ndarray) -> float:
    """Volume enclosed by a closed mesh: positive when its faces turn counter-clockwise seen from
    outside, negative when they face inwards."""
    a, b, c = (positions[faces[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->", a, np.cross(b, c))) / 6.0


def front_side(positions: np.ndarray, faces: np.ndarray) -> int:
    """Which side of the faces can be seen: 0 for an open mesh (both: its inside shows through
    the borders), +1 for a closed mesh whose faces turn counter-clockwise seen from outside, -1
    for one whose faces turn inwards (the sign of its volume says which)."""
    if not is_closed(faces):
        return 0
    return 1 if signed_volume(positions, faces) >= 0.0 else -1


def visible_faces(screen: np.ndarray, faces: np.ndarray, front: int) -> np.ndarray:
    """The faces that can be seen from the :func:`front_side` ``front``: all of an open mesh, those
    turned towards the viewer of a closed one (half the rasterisation work)."""
    if front == 0:
        return faces
    a, b, c = (screen[faces[:, k]] for k in range(3))
    # Counter-clockwise from outside; the screen's y points down, so facing faces turn clockwise.
    area = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    return faces[area <= 0] if front > 0 else faces[area >= 0]


def interpolate_values(fragments: Fragments, faces: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Per-pixel values, barycentric over the corners whose value is known (NaN only where no
    corner of the triangle has one), so one unknown vertex does not blank its faces."""
    corner_values = values[faces[fragments.face]]
    known = np.isfinite(corner_values)
    weights = np.where(known, fragments.weights, 0.0)
    total = weights.sum(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(known.any(axis=1), (weights * np.nan_to_num(corner_values)).sum(axis=1) / total, np.nan)


def shade(fragments: Fragments, faces: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """Headlight brightness per pixel from the interpolated normal (two-sided: open meshes show
    their inside lit too)."""
    normal = np.einsum("ij,ijk->ik", fragments.weights, normals[faces[fragments.face]])
    facing = np.abs(normal[:, 2]) / np.maximum(np.linalg.norm(normal, axis=1), 1e-300)
    return AMBIENT + (1.0 - AMBIENT) * facing


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
    drawing the same faces several times)."""
    from .images import colour_values

    p = view_coordinates(positions, view, up, centre)
    lower, upper = bounds if bounds is not None else (p[:, :2].min(axis=0), p[:, :2].max(axis=0))
    scale = pixels_per_unit * SUPERSAMPLING
    width, height = (max(1, int(np.ceil(float(e) * scale))) for e in (upper - lower))
    screen = np.column_stack([(p[:, 0] - lower[0]) * scale, (upper[1] - p[:, 1]) * scale, p[:, 2]])
    faces = visible_faces(screen, faces, front_side(positions, faces) if front is None else front)
    fragments = rasterise(screen, faces, height, width)
    value = interpolate_values(fragments, faces, np.asarray(values, dtype=np.float64))
    colour = colour_values(value, cmap, low, high)
    picture = np.zeros((height * width, 4))
    picture[fragments.pixel, :3] = colour * shade(fragments, faces, vertex_normals(p, faces))[:, None]
    picture[fragments.pixel, 3] = 1.0
    return downsample(picture.reshape(height, width, 4))


def downsample(picture: np.ndarray) -> np.ndarray:
    """Averages SUPERSAMPLING² blocks (premultiplied by coverage, so edges blend, not darken)."""
    s = SUPERSAMPLING
    height, width = (-(-n // s) * s for n in picture.shape[:2])
    padded = np.zeros((height, width, 4))
    padded[:picture.shape[0], :picture.shape[1]] = picture
    blocks = padded.reshape(height // s, s, width // s, s, 4).mean(axis=(1, 3))
    alpha = blocks[..., 3:]
    blocks[..., :3] = np.where(alpha > 0, blocks[..., :3] / np.maximum(alpha, 1e-12), 0.0)
    return blocks


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
