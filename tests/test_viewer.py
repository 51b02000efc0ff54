"""The interactive viewer, rendered headless on polyscope's EGL backend: the screenshot must show
the mesh, coloured, and the radius slider (driven through the Viewer's own methods, as the panel
drives it) must change the colours. Skips only where polyscope or EGL is missing."""

import subprocess
import sys

import numpy as np
import pytest

import uvfeat
from uvfeat.errors import InvalidParameterError

pytest.importorskip("polyscope", reason="the viewer needs the extra uvfeat[view] (polyscope)")


def egl_problem() -> str | None:
    """Why polyscope cannot render headless here (None when it can); probed in a child process,
    as a broken GL stack may abort the process rather than raise."""
    probe = subprocess.run([sys.executable, "-c", "import polyscope as ps; ps.init('openGL3_egl')"],
                           capture_output=True, text=True, timeout=120)
    return None if probe.returncode == 0 else (probe.stderr.strip().splitlines() or ["no output"])[-1]


PROBLEM = egl_problem()
pytestmark = pytest.mark.skipif(PROBLEM is not None, reason=f"no EGL for a headless viewer: {PROBLEM}")


def covered(picture):
    return picture[..., 3] > 0


#: Red minus blue (or blue minus red) of a pixel that shows a coloured value: the shaded material
#: darkens the colour map's ends (measured: red 37-58, blue about -83; an uncoloured mesh 0).
HUE = 25


def reds_and_blues(picture):
    rgb = picture[..., :3].astype(int)
    return ((rgb[..., 0] - rgb[..., 2] > HUE) & covered(picture)).sum(), \
           ((rgb[..., 2] - rgb[..., 0] > HUE) & covered(picture)).sum()


@pytest.fixture(autouse=True)
def in_a_scratch_folder(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # nothing polyscope might write lands in the repository


@pytest.fixture
def sphere_viewer():
    # polyscope has one scene per process: every Viewer replaces the last one's, so one per test
    sphere = uvfeat.shapes.uv_sphere(1.0, 48, 24)
    upper = np.sign(sphere.positions[:, 1])     # +1 on the upper half (y up), -1 below
    return uvfeat.view(sphere, {"mean_curvature": np.stack([upper, -upper])}, radius=["1%", "4%"],
                       backend="openGL3_egl", show=False)


@pytest.fixture
def mesh_only(sphere_viewer):
    """The viewer with its UV map hidden: what the screenshot shows is the mesh alone."""
    sphere_viewer.uv_map.set_enabled(False)
    yield sphere_viewer
    sphere_viewer.uv_map.set_enabled(True)  # polyscope keeps a structure's state by name


def test_the_screenshot_shows_the_mesh_coloured(mesh_only):
    mesh_only.set_scale(0)
    picture = mesh_only.screenshot()
    assert covered(picture).mean() > 0.05                    # the mesh is there
    red, blue = reds_and_blues(picture)
    assert red > 0.2 * covered(picture).sum() and blue > 0.2 * covered(picture).sum()   # coloured, both signs
    rows = np.nonzero(covered(picture))[0]
    rgb = picture[..., :3].astype(int)
    red_rows = np.nonzero((rgb[..., 0] - rgb[..., 2] > HUE) & covered(picture))[0]
    assert red_rows.mean() < rows.mean()                     # red on the upper half, as the values say


def test_the_radius_slider_changes_the_colours(mesh_only):
    mesh_only.set_scale(0)
    first = mesh_only.screenshot()
    mesh_only.set_scale(1)
    second = mesh_only.screenshot()
    assert (covered(first) == covered(second)).mean() > 0.99  # same mesh, same camera
    changed = (np.abs(first[..., :3].astype(int) - second[..., :3]).max(axis=-1) > 60) & covered(first)
    assert changed.sum() > 0.5 * covered(first).sum()        # the halves swapped colours
    assert mesh_only.title == "mean_curvature at r = 4%"


def test_colour_range_pick_and_errors(sphere_viewer):
    sphere_viewer.set_scale(0)
    sphere_viewer.set_range(-100.0, 100.0)                   # values of +-1 now sit near the white middle
    pale = sphere_viewer.screenshot()
    assert sum(reds_and_blues(pale)) < 0.05 * covered(pale).sum()
    sphere_viewer.reset_range()
    top = int(np.argmax(sphere_viewer.mesh.positions[:, 1]))
    sphere_viewer.pick(top)
    assert sphere_viewer.value_at(top) == 1.0
    with pytest.raises(InvalidParameterError, match="low < high"):
        sphere_viewer.set_range(1.0, 0.0)
    with pytest.raises(InvalidParameterError, match="not computed"):
        sphere_viewer.set_feature("k1")
    with pytest.raises(InvalidParameterError, match="scale 5 of 2"):
        sphere_viewer.set_scale(5)


def test_feature_maps_from_the_fit_add_radii_and_directions():
    mesh = uvfeat.shapes.torus(2.0, 0.5, 64, 32)
    atlas = uvfeat.Atlas(mesh, resolution=256)
    maps = atlas.compute(["mean_curvature", "k1"], radius=["5%", "10%"], compute_resolution=64, samples=64,
                         method="fit")
    viewer = uvfeat.view(mesh, maps, backend="openGL3_egl", show=False)
    assert [s.label for s in viewer.scales] == [f"{f * mesh.bounding_box_diagonal:.4g}" for f in (0.05, 0.1)]
    assert viewer.scale.directions.shape == (mesh.n_vertices, 2, 3)
    plain = viewer.screenshot()
    viewer.set_directions(True)
    with_glyphs = viewer.screenshot()
    assert (np.abs(plain.astype(int) - with_glyphs).max(axis=-1) > 30).mean() > 0.001
    viewer.add_radius("20%")                                 # "compute another radius"
    assert len(viewer.scales) == 3 and viewer.scale_index == 2 and viewer.scale.label == "20%"
    viewer.set_feature("k1")
    assert np.nanmedian(viewer.values()) == pytest.approx(1 / 0.5, rel=0.25)   # k1 = 1/a around the tube


def test_the_view_command_renders_a_screenshot_headless(tmp_path):
    import trimesh
    from PIL import Image

    from uvfeat.cli import main

    path = tmp_path / "ico.obj"
    trimesh.creation.icosphere(3).export(path)
    shot = tmp_path / "view.png"
    assert main(["view", str(path), "--feature", "mean_curvature,curvedness", "--radius", "10%,20%", "--resolution",
                 "128", "--compute-resolution", "64", "--samples", "32", "--screenshot", str(shot)]) == 0
    picture = np.asarray(Image.open(shot))
    assert covered(picture).mean() > 0.05
    assert main(["view", str(path), "--feature", "bogus", "--screenshot", str(shot)]) == 2


def test_the_vertex_under_the_cursor_on_the_mesh_and_on_the_uv_map(sphere_viewer):
    import polyscope as ps

    sphere_viewer.set_scale(0)
    height, width = sphere_viewer.screenshot().shape[:2]
    row = height // 2 - 100                                  # above the middle: the sphere's upper half
    hits = {}
    for x in range(0, width, 20):
        pick = ps.pick(screen_coords=(x, row))
        vertex = sphere_viewer.vertex_under((x, row))
        if pick.is_hit and vertex is not None:
            hits.setdefault(pick.structure_name, []).append(vertex)
    assert set(hits) == {"mesh", "UV map"}, hits
    assert all(sphere_viewer.mesh.positions[v, 1] > 0 for v in hits["mesh"])
    assert all(sphere_viewer.value_at(v) == 1.0 for v in hits["mesh"])


def test_the_panel_draws_a_frame(sphere_viewer):
    import polyscope as ps

    from uvfeat.pictures.viewer_panel import Panel, radius_argument

    panel = Panel(sphere_viewer)
    ps.set_user_callback(panel.draw)
    ps.frame_tick()                                          # every widget once, headless
    ps.clear_user_callback()
    assert panel.message == ""
    assert radius_argument(" 0.25 ") == 0.25 and radius_argument("4%") == "4%"


def test_the_view_command_says_only_its_own_lines(tmp_path):
    """No polyscope start-up log, no nanobind leak report at exit, and warnings as one line with no
    Python source echo."""
    import re

    from uvfeat.examples import spot_path

    shot = tmp_path / "view.png"
    run = subprocess.run([sys.executable, "-m", "uvfeat", "view", str(spot_path()), "--radius", "4%", "--resolution",
                          "256", "--compute-resolution", "128", "--samples", "32", "--screenshot", str(shot)],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    said = run.stdout + run.stderr
    assert "[polyscope]" not in said and "nanobind" not in said and "leaked" not in said, said
    assert not re.search(r"\.py:\d+: \w+Warning", said), said
    assert any(line.startswith("warning: at r = 4%") for line in said.splitlines()), said
