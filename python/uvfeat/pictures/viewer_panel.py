"""The viewer's control panel (ImGui, drawn by polyscope every frame): feature selector, radius
slider, "compute another radius", colour range, and the value under the cursor. It only calls
:class:`uvfeat.pictures.viewer.Viewer` methods, so what it does can be scripted and tested without it."""

from __future__ import annotations

from ..errors import UvfeatError


def radius_argument(text: str):
    """A radius typed in the panel: a number in object units, or a string such as ``"2%"``."""
    text = text.strip()
    try:
        return float(text)
    except ValueError:
        return text


class Panel:
    def __init__(self, viewer):
        import polyscope.imgui

        self.viewer, self.imgui = viewer, polyscope.imgui
        self.new_radius, self.message = "8%", ""

    def draw(self) -> None:
        v, ui = self.viewer, self.imgui
        ui.TextUnformatted(v.title)
        changed, index = ui.Combo("feature", v.features.index(v.feature), v.features)
        if changed:
            v.set_feature(v.features[index])
        if len(v.scales) > 1:
            changed, index = ui.SliderInt("radius", v.scale_index, 0, len(v.scales) - 1, format=f"r = {v.scale.label}")
            if changed:
                v.set_scale(index)
        _, self.new_radius = ui.InputText("##new radius", self.new_radius)
        ui.SameLine()
        if ui.Button("compute another radius"):
            self._try(lambda: v.add_radius(radius_argument(self.new_radius)))
        changed_low, low = ui.InputFloat("low", v.low, format="%.4g")
        changed_high, high = ui.InputFloat("high", v.high, format="%.4g")
        if changed_low or changed_high:
            self._try(lambda: v.set_range(low, high))
        if ui.Button("robust range"):
            v.reset_range()
        if v.scale.directions is not None:
            changed, shown = ui.Checkbox("principal directions", v.show_directions)
            if changed:
                v.set_directions(shown)
        self._cursor()
        if self.message:
            ui.TextUnformatted(self.message)

    def _cursor(self) -> None:
        v, ui = self.viewer, self.imgui
        io = ui.GetIO()
        if not io.WantCaptureMouse:
            v.hovered = v.vertex_under(io.MousePos)
            if v.hovered is not None and ui.IsMouseClicked(0):
                v.pick(v.hovered)
        for what, vertex in (("under the cursor", v.hovered), ("picked", v.picked)):
            if vertex is not None:
                ui.TextUnformatted(f"{what}: vertex {vertex}, {v.feature} = {v.value_at(vertex):.4g}")

    def _try(self, action) -> None:
        try:
            action()
            self.message = ""
        except UvfeatError as error:
            self.message = str(error)
