"""The interactive viewer (``uvfeat.view``, ``uvfeat view``) on polyscope (``pip install
'uvfeat[view]'``): the mesh coloured by a feature, its UV map beside it, a feature selector, a
slider over the computed radii, colour-range controls, principal-direction glyphs after the fit,
the picked point on both and the value under the cursor.

Everything the panel does goes through :class:`Viewer` methods (``set_feature``, ``set_scale``,
``set_range``, ``add_radius``, ``pick``), so a script or a test drives it the same way, and
``screenshot`` renders it without a window on the EGL backend."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InvalidParameterError, ViewerError
from ..interop import as_mesh
from ..mesh import Mesh
from ..options import DEFAULT_OPTIONS

#: The options of ``Atlas.compute`` a FeatureMap's settings record: "compute another radius" uses
#: them, so that the new radius is computed as the others were.
COMPUTE_OPTIONS = ("samples", "compute_resolution", "seed", "adaptive", *DEFAULT_OPTIONS)

#: Polyscope's headless backend (EGL, no display).
HEADLESS = "openGL3_egl"

#: Marker of the picked point, in the colour no colour map here uses.
PICK_COLOUR = (0.1, 0.9, 0.1)


@dataclass
class Scale:
    """One radius: its label, per-vertex values per feature and, after the fit, the principal
    directions per vertex ``(n_vertices, 2, 3)``."""

    label: str
    values: dict[str, np.ndarray]
    directions: np.ndarray | None = None


def scales_from_results(mesh: Mesh, results: dict, radius=None) -> list[Scale]:
    """Scales from ``{feature: FeatureMap}`` (one radius or a stack) or ``{feature: array}`` of
    shape ``(n_vertices,)`` or ``(n_radii, n_vertices)`` with ``radius`` labelling the rows."""
    from .surface_plot import per_vertex_rows

    if not results:
        raise InvalidParameterError("the viewer needs at least one feature")
    rows, labels, directions = {}, None, None
    for name, result in results.items():
        if getattr(result, "principal_directions", None) is not None and directions is None:
            directions = result.per_vertex_directions()
        rows[name], labels = per_vertex_rows(mesh, result, radius, name)
    counts = {len(v) for v in rows.values()}
    if len(counts) != 1:
        raise InvalidParameterError(f"every feature needs the same number of radii, got {sorted(counts)}")
    n = counts.pop()
    labels = labels or [f"scale {k + 1}" for k in range(n)]
    if directions is not None and directions.ndim == 3:
        directions = directions[None]
    return [Scale(labels[k], {name: v[k] for name, v in rows.items()}, None if directions is None else directions[k])
            for k in range(n)]


def tangent_basis(normals: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit tangents per vertex, orthogonal to the normal and to each other."""
    helper = np.where(np.abs(normals[:, :1]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]])
    x = np.cross(normals, helper)
    x /= np.maximum(np.linalg.norm(x, axis=1, keepdims=True), 1e-300)
    return x, np.cross(normals, x)


class Viewer:
    """The scene and its state. Build it with :func:`view`; ``show()`` opens the window. Polyscope
    has one scene per process: a new Viewer replaces the previous one's."""

    def __init__(self, mesh: Mesh, scales: list[Scale], *, atlas=None, compute_options: dict | None = None,
                 feature: str | None = None, backend: str = "auto"):
        from ..extras import require

        self.ps = require("polyscope", "the viewer")
        self.mesh, self.scales = mesh, scales
        self._atlas, self.compute_options = atlas, dict(compute_options or {})
        self.features = list(scales[0].values)
        self.feature = feature or self.features[0]
        if self.feature not in self.features:
            raise InvalidParameterError(f"feature {self.feature!r} was not computed; have {self.features}")
        self.scale_index, self.picked, self.hovered = 0, None, None
        self.show_directions = False
        if not self.ps.is_initialized():
            # polyscope would otherwise write imgui.ini and .polyscope.ini into the working folder
            self.ps.set_use_prefs_file(False)
            # polyscope's start-up log (five "[polyscope] EGL: ..." lines) says nothing a user acts on.
            self.ps.set_verbosity(0)
            try:
                self.ps.init(backend)
            except Exception as error:  # polyscope raises bare RuntimeErrors (no display, no GL)
                raise ViewerError(f"the viewer could not start polyscope's {backend!r} backend ({error}); without a "
                                  f"display, render headless with backend={HEADLESS!r} (uvfeat view --screenshot), "
                                  "which needs EGL (Debian: libegl1 libegl-mesa0 libgl1-mesa-dri)") from None
        self.ps.set_up_dir("y_up")
        self.ps.set_ground_plane_mode("none")
        self.ps.remove_all_structures()
        self.surface = self.ps.register_surface_mesh("mesh", mesh.positions, mesh.faces, smooth_shade=True)
        self.uv_map = self._register_uv_map() if mesh.has_uvs else None
        self.reset_range()

    # -- state ------------------------------------------------------------------------------------
    @property
    def scale(self) -> Scale:
        return self.scales[self.scale_index]

    def values(self) -> np.ndarray:
        """Per-vertex values of the current feature at the current radius."""
        return self.scale.values[self.feature]

    def reset_range(self) -> None:
        """The robust range of the current feature over every radius (as the pictures use)."""
        from .images import colour_range

        stacked = np.concatenate([s.values[self.feature] for s in self.scales])
        self.cmap, self.low, self.high = colour_range(self.feature, stacked)
        self.refresh()

    def set_feature(self, name: str) -> None:
        if name not in self.features:
            raise InvalidParameterError(f"feature {name!r} was not computed; have {self.features}")
        self.feature = name
        self.reset_range()

    def set_scale(self, index: int) -> None:
        """Shows radius number ``index`` (the slider); the colour range stays, so scales compare."""
        if not 0 <= index < len(self.scales):
            raise InvalidParameterError(f"scale {index} of {len(self.scales)}")
        self.scale_index = int(index)
        self.refresh()

    def set_range(self, low: float, high: float) -> None:
        if not high > low:
            raise InvalidParameterError(f"the colour range needs low < high, got [{low}, {high}]")
        self.low, self.high = float(low), float(high)
        self.refresh()

    def add_radius(self, radius) -> None:
        """Computes every feature at one more ``radius`` (object units or ``"2%"``) and shows it."""
        from ..atlas import Atlas
        from .surface_plot import radius_label

        if self._atlas is None:
            self._atlas = Atlas(self.mesh)
        maps = self._atlas.compute(self.features, radius, **self.compute_options)
        first = next(iter(maps.values()))
        directions = first.per_vertex_directions() if first.principal_directions is not None else None
        self.scales.append(Scale(radius_label(radius), {name: m.per_vertex() for name, m in maps.items()}, directions))
        self.set_scale(len(self.scales) - 1)

    def set_directions(self, shown: bool) -> None:
        """Shows or hides the principal-direction glyphs (there are some after ``method="fit"``)."""
        self.show_directions = bool(shown)
        self.refresh()

    def value_at(self, vertex: int) -> float:
        return float(self.values()[vertex])

    def pick(self, vertex: int | None) -> None:
        """Marks ``vertex`` on the mesh and on the UV map (None clears the mark)."""
        self.picked = vertex
        self.refresh()

    # -- scene ------------------------------------------------------------------------------------
    def _uv_layout(self) -> np.ndarray:
        """UV vertices placed beside the mesh (right of it, as tall as it), in object units."""
        low, high = self.mesh.positions.min(axis=0), self.mesh.positions.max(axis=0)
        size = float((high - low).max())
        flat = np.zeros((len(self.mesh.uvs), 3))
        flat[:, 0] = high[0] + 0.15 * size + self.mesh.uvs[:, 0] * size
        flat[:, 1] = low[1] + self.mesh.uvs[:, 1] * size
        flat[:, 2] = (low[2] + high[2]) / 2
        return flat

    def _register_uv_map(self):
        # UV vertices no face uses are never drawn; vertex 0 stands in for them.
        self.uv_vertex = np.zeros(len(self.mesh.uvs), dtype=np.int64)
        self.uv_vertex[self.mesh.uv_faces.ravel()] = self.mesh.faces.ravel()
        self.uv_positions = self._uv_layout()
        return self.ps.register_surface_mesh("UV map", self.uv_positions, self.mesh.uv_faces, material="flat")

    def refresh(self) -> None:
        """Pushes the current feature, radius, range, glyphs and picked point to polyscope."""
        from .images import colour_values

        colours = colour_values(self.values(), self.cmap, self.low, self.high)
        title = f"{self.feature} at r = {self.scale.label}"
        self.surface.add_color_quantity("feature", colours, enabled=True)
        if self.uv_map is not None:
            self.uv_map.add_color_quantity("feature", colours[self.uv_vertex], enabled=True)
        if self.scale.directions is not None:
            self._add_glyphs(self.scale.directions)
        self.ps.remove_point_cloud("picked", error_if_absent=False)
        if self.picked is not None:
            points = [self.mesh.positions[self.picked]]
            if self.uv_map is not None:
                points += list(self.uv_positions[self.uv_vertex == self.picked])
            cloud = self.ps.register_point_cloud("picked", np.array(points), color=PICK_COLOUR, radius=0.008)
            cloud.set_enabled(True)
        self.title = title

    def _add_glyphs(self, directions: np.ndarray) -> None:
        from ..mesh import vertex_normals

        x, y = tangent_basis(vertex_normals(self.mesh.positions, self.mesh.faces))
        for k, name in enumerate(("d1 (direction of k1)", "d2 (direction of k2)")):
            d = directions[:, k]
            # A line field: n_sym=2 draws each direction both ways, as its sign is arbitrary.
            self.surface.add_tangent_vector_quantity(name, np.column_stack([(d * x).sum(1), (d * y).sum(1)]), x, y,
                                                     n_sym=2, enabled=self.show_directions and k == 0,
                                                     length=0.01, radius=0.0015)

    def screenshot(self) -> np.ndarray:
        """(H, W, 4) uint8 picture of the scene as it stands (transparent background)."""
        self.ps.reset_camera_to_home_view()
        return self.ps.screenshot_to_buffer(transparent_bg=True)

    def vertex_under(self, screen_coords) -> int | None:
        """The mesh vertex nearest to what lies under ``screen_coords`` on the mesh or the UV map."""
        hit = self.ps.pick(screen_coords=screen_coords)
        if not hit.is_hit or hit.structure_name not in ("mesh", "UV map"):
            return None
        data = hit.structure_data
        if data.get("element_type") == "vertex":
            corner = data["index"]
        elif data.get("element_type") == "face" and "bary_coords" in data:
            faces = self.mesh.faces if hit.structure_name == "mesh" else self.mesh.uv_faces
            corner = faces[data["index"]][int(np.argmax(data["bary_coords"]))]
        else:
            return None
        return int(corner if hit.structure_name == "mesh" else self.uv_vertex[corner])

    def close(self) -> None:
        """Removes this viewer's meshes from polyscope (the bindings report them as leaked at exit
        otherwise)."""
        self.surface = self.uv_map = None
        self.ps.remove_all_structures()
        self.ps.clear_user_callback()

    # -- window -----------------------------------------------------------------------------------
    def show(self) -> None:
        """Opens the window (blocks until it is closed)."""
        from .viewer_panel import Panel

        self.ps.set_user_callback(Panel(self).draw)
        self.ps.show()
        self.ps.clear_user_callback()


def view(mesh: Mesh, results: dict | None = None, *, feature: str | None = None, radius=None, atlas=None,
         compute_options: dict | None = None, backend: str = "auto", show: bool = True) -> Viewer:
    """Opens the interactive viewer on ``mesh`` with ``results``: ``{feature: FeatureMap}`` as
    ``Atlas.compute`` returns (a stack gives the radius slider its stops), or ``{feature: array}``
    per vertex, ``(n_vertices,)`` or ``(n_radii, n_vertices)``, with ``radius`` labelling the rows.
    Without results the mean curvature is computed at ``radius`` (default 1, 4 and 16 %).

    "Compute another radius" uses ``atlas`` (default the one behind the FeatureMaps, or a new one)
    with ``compute_options`` (``samples``, ``compute_resolution``, ``method``...). ``backend``
    picks polyscope's (``"openGL3_egl"`` renders without a display); ``show=False`` returns the
    :class:`Viewer` without opening the window (for scripts and screenshots). Needs
    ``pip install 'uvfeat[view]'``."""
    from ..files.feature_files import radius_list
    from ..features import FeatureMap
    from ..options import feature_names

    mesh = as_mesh(mesh)
    if results is None:
        from ..atlas import Atlas

        atlas = atlas or Atlas(mesh)
        names = feature_names(feature or "mean_curvature")
        results = atlas.compute(names, radius_list(radius or ["1%", "4%", "16%"]), **(compute_options or {}))
        feature = names[0]
    maps = [r for r in results.values() if isinstance(r, FeatureMap)]
    if maps:
        atlas = atlas or maps[0]._atlas
        settings = maps[0].settings
        compute_options = compute_options or {k: settings[k] for k in COMPUTE_OPTIONS if k in settings}
    viewer = Viewer(mesh, scales_from_results(mesh, results, radius), atlas=atlas,
                    compute_options=compute_options, feature=feature, backend=backend)
    if show:
        viewer.show()
    return viewer

