"""``uvfeat.plot``: a feature on the mesh from a few standard views, one column per radius, with
one colour range for all of them (so scales compare) and a colour bar in the feature's units."""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidParameterError
from ..interop import as_mesh

#: Standard views as (elevation, azimuth) in degrees around the up axis; azimuth 0 looks at the
#: front of a model facing +z with y up (the OBJ and glTF convention), 90 at its +x side.
VIEWS = {
    "front": (10.0, 0.0),
    "three_quarter": (20.0, 45.0),
    "side": (10.0, 90.0),
    "back": (10.0, 180.0),
    "other_side": (10.0, -90.0),
    "top": (90.0, 0.0),
}

DEFAULT_VIEWS = ("three_quarter", "side", "back")


def resolve_view(view) -> tuple[float, float]:
    """A view by name (see :data:`VIEWS`) or as ``(elevation, azimuth)`` in degrees."""
    if isinstance(view, str):
        if view not in VIEWS:
            raise InvalidParameterError(f"unknown view {view!r}; use one of {sorted(VIEWS)} or (elevation, azimuth)")
        return VIEWS[view]
    try:
        elevation, azimuth = (float(x) for x in view)
    except (TypeError, ValueError):
        raise InvalidParameterError(f"a view is a name or (elevation, azimuth) in degrees, got {view!r}") from None
    return elevation, azimuth


def radius_label(radius) -> str:
    """A radius as shown: labels such as ``"4%"`` as given, numbers to 4 significant digits."""
    return radius if isinstance(radius, str) else f"{float(radius):.4g}"


def per_vertex_rows(mesh, values, radius=None, name: str = "values") -> tuple[np.ndarray, list[str] | None]:
    """Per-vertex values as ``(n_radii, n_vertices)`` rows and a label per radius (None when no
    radius is known), from a :class:`~uvfeat.FeatureMap` (its radii unless ``radius`` is given) or
    an array ``(n_vertices,)`` / ``(n_radii, n_vertices)``; ``radius`` holds numbers or labels."""
    from ..features import FeatureMap

    if isinstance(values, FeatureMap):
        if radius is None:
            radius = "r per vertex" if values.radius_per_vertex else values.radius
        values = values.per_vertex()
    values = np.asarray(values, dtype=np.float64)
    rows = values[None] if values.ndim == 1 else values
    if rows.ndim != 2 or rows.shape[1] != mesh.n_vertices:
        raise InvalidParameterError(f"{name} must be per vertex, (n_vertices,) or (n_radii, n_vertices) with "
                                    f"n_vertices = {mesh.n_vertices}, got shape {values.shape}")
    if radius is None:
        return rows, None
    labels = [radius_label(r) for r in np.atleast_1d(np.asarray(radius, dtype=object))]
    if len(labels) != len(rows):
        raise InvalidParameterError(f"{len(labels)} radii given for {len(rows)} rows of {name}")
    return rows, labels


def plot(mesh, values, *, feature: str | None = None, radius=None, views=DEFAULT_VIEWS, up: str = "y",
         low: float | None = None, high: float | None = None, panel_inches: float = 3.2, dpi: int = 120,
         title: str | None = None, path: str | os.PathLike | None = None):
    """Draws per-vertex ``values`` on ``mesh``, smooth-shaded, one row per view and one column per
    radius, and returns the matplotlib Figure (also saved to ``path`` when given).

    ``values`` is a :class:`~uvfeat.FeatureMap` (its name, radius and per-vertex values are used),
    or an array ``(n_vertices,)`` or ``(n_radii, n_vertices)`` with ``feature`` naming it (for its
    colour map and units) and ``radius`` giving the radius of each row (numbers, or labels such as
    ``"4%"``). Signed features get a diverging map centred on 0; the range is a robust percentile
    range over all radii unless ``low``/``high`` are given. ``views`` are names of :data:`VIEWS`
    or ``(elevation, azimuth)`` pairs, ``up`` the axis that points up. Runs without a display."""
    import matplotlib

    from .images import FEATURE_UNITS, colour_range, offscreen_figure, save_figure
    from .render import UP_AXES, draw_vertex_values, front_side

    if up not in UP_AXES:
        raise InvalidParameterError(f"up must be one of {sorted(UP_AXES)}, got {up!r}")
    mesh = as_mesh(mesh)
    feature = feature or getattr(values, "name", None) or "value"
    rows, labels = per_vertex_rows(mesh, values, radius)
    angles = [resolve_view(v) for v in ([views] if isinstance(views, str) else views)]
    if not angles:
        raise InvalidParameterError("plot needs at least one view")
    cmap, robust_low, robust_high = colour_range(feature, rows.ravel())
    low = robust_low if low is None else float(low)
    high = robust_high if high is None else float(high)
    height = panel_inches * len(angles) + 0.8
    fig = offscreen_figure((panel_inches * len(rows) + 1.2, height), dpi)
    axes = fig.subplots(len(angles), len(rows), squeeze=False)
    # Room at the top for the title and the radii, whatever the number of rows.
    fig.subplots_adjust(left=0.02, right=0.98, bottom=0.02, top=1.0 - 0.75 / height, wspace=0.05, hspace=0.05)
    unit = FEATURE_UNITS.get(feature, "")
    # The colour bar first: it takes its room from the panels, which then render at their final size.
    fig.colorbar(matplotlib.cm.ScalarMappable(matplotlib.colors.Normalize(low, high), cmap), ax=axes.ravel().tolist(),
                 fraction=0.04, pad=0.03, panchor=False, label=f"{feature} ({unit})" if unit else feature)
    front = front_side(mesh.positions, mesh.faces)
    for column, (row_values, label) in enumerate(zip(rows, labels or [None] * len(rows))):
        for line, angles_of_view in enumerate(angles):
            draw_vertex_values(axes[line, column], mesh.positions, mesh.faces, row_values, cmap, low, high,
                               view=angles_of_view, up=up, front=front)
            if line == 0 and label:
                axes[line, column].set_title(f"r = {label}")
    fig.suptitle(title if title is not None else f"{mesh.name}: {feature}")
    if path is not None:
        save_figure(fig, path)
    return fig


def save_plot(path: str | os.PathLike, mesh, values, **options) -> None:
    """:func:`plot` written to ``path`` (for writing many pictures in a row)."""
    plot(mesh, values, path=path, **options)


@dataclass
class FixedCamera:
    """A view framed once, on the first frame of an animation, so that the mesh moves inside a
    still picture: the point the view turns around, the picture's bounds in view coordinates and
    its scale. Build it with :meth:`framing`."""

    view: tuple[float, float]
    up: str
    centre: np.ndarray
    bounds: tuple[np.ndarray, np.ndarray]
    pixels_per_unit: float
    #: The animated mesh's :func:`~uvfeat.pictures.render.front_side`, worked out on the first frame.
    front: int | None = None

    @classmethod
    def framing(cls, positions: np.ndarray, view="three_quarter", up: str = "y", pixels: int = 480,
                margin: float = 0.25) -> "FixedCamera":
        """Frames ``positions`` with ``margin`` (a fraction of their extent) of room to move on
        every side, the longer side of the picture ``pixels`` wide."""
        from .render import view_coordinates

        angles = resolve_view(view)
        centre = positions.mean(axis=0)
        p = view_coordinates(positions, angles, up, centre)[:, :2]
        lower, upper = p.min(axis=0), p.max(axis=0)
        room = margin * float((upper - lower).max())
        lower, upper = lower - room, upper + room
        return cls(angles, up, centre, (lower, upper), pixels / float((upper - lower).max()))

    def picture(self, positions: np.ndarray, faces: np.ndarray, values: np.ndarray, cmap: str, low: float,
                high: float) -> np.ndarray:
        """(H, W, 3) uint8 picture of the mesh at ``positions`` coloured by ``values``, on white."""
        from .render import front_side, render_values

        if self.front is None:
            self.front = front_side(positions, faces)
        rgba = render_values(positions, faces, values, cmap, low, high, self.view, self.up, self.pixels_per_unit,
                             self.bounds, self.centre, self.front)
        rgb = rgba[..., :3] * rgba[..., 3:] + (1.0 - rgba[..., 3:])
        return (np.clip(rgb, 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8)
