"""uvfeat.plot: the mesh coloured by a feature from standard views, one column per radius, one
colour range for all radii; and the pictures the commands write."""

import json

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest

import uvfeat
from uvfeat.cli import main


def picture_of(figure) -> np.ndarray:
    figure.canvas.draw()
    pixels = np.asarray(figure.canvas.buffer_rgba())[..., :3].astype(float) / 255
    plt.close(figure)
    return pixels


def test_a_stack_is_one_column_per_radius_and_one_row_per_view():
    sphere = uvfeat.shapes.uv_sphere(1.0, 48, 24)
    values = np.stack([sphere.positions[:, 1], 2 * sphere.positions[:, 1]])
    fig = uvfeat.plot(sphere, values, feature="mean_curvature", radius=["1%", 0.25], views=("front", "side"))
    panels = [ax for ax in fig.axes if ax.images]
    assert len(panels) == 4
    assert [ax.get_title() for ax in panels if ax.get_title()] == ["r = 1%", "r = 0.25"]
    colour_bar = [ax for ax in fig.axes if not ax.images]
    assert len(colour_bar) == 1 and colour_bar[0].get_ylabel() == "mean_curvature (1/length)"
    # signed feature: diverging map, symmetric range shared by both radii (set by the larger one)
    low, high = colour_bar[0].get_ylim()
    assert low == pytest.approx(-high) and high > 1.5
    plt.close(fig)


def test_signed_features_are_centred_on_zero_and_the_mesh_is_coloured():
    sphere = uvfeat.shapes.uv_sphere(1.0, 48, 24)
    # top half +1, bottom half -1 (y up): red above, blue below in a diverging map
    values = np.sign(sphere.positions[:, 1])
    pixels = picture_of(uvfeat.plot(sphere, values, feature="mean_curvature", views=("front",), dpi=80))
    sphere_part = pixels[:, : pixels.shape[1] * 2 // 3]      # the colour bar (red and blue too) on the right
    red = sphere_part[..., 0] > sphere_part[..., 2] + 0.2
    blue = sphere_part[..., 2] > sphere_part[..., 0] + 0.2
    assert red.sum() > 500 and blue.sum() > 500
    assert np.nonzero(red)[0].mean() < np.nonzero(blue)[0].mean()     # red on top


def test_a_feature_map_brings_its_name_and_radius():
    mesh = uvfeat.shapes.uv_sphere(1.0, 48, 24)
    maps = uvfeat.Atlas(mesh, resolution=256).compute("mean_curvature", radius=[0.2, 0.4], compute_resolution=64,
                                                      samples=64)
    fig = uvfeat.plot(mesh, maps["mean_curvature"], views="front")
    titles = [ax.get_title() for ax in fig.axes if ax.get_title()]
    assert titles == ["r = 0.2", "r = 0.4"] and "mean_curvature" in fig._suptitle.get_text()
    plt.close(fig)


def test_bad_arguments_raise_typed_errors():
    sphere = uvfeat.shapes.uv_sphere(1.0, 16, 8)
    with pytest.raises(uvfeat.InvalidParameterError, match="per vertex"):
        uvfeat.plot(sphere, np.zeros(3))
    with pytest.raises(uvfeat.InvalidParameterError, match="unknown view"):
        uvfeat.plot(sphere, np.zeros(sphere.n_vertices), views=("sideways",))
    with pytest.raises(uvfeat.InvalidParameterError, match="2 radii"):
        uvfeat.plot(sphere, np.zeros(sphere.n_vertices), radius=[1, 2])
    with pytest.raises(uvfeat.InvalidParameterError, match="up must be"):
        uvfeat.plot(sphere, np.zeros(sphere.n_vertices), up="w")


def test_compute_writes_a_3d_picture_of_every_feature(tmp_path):
    sphere = uvfeat.shapes.uv_sphere(1.0, 48, 24)
    import trimesh

    path = tmp_path / "sphere.obj"
    trimesh.Trimesh(sphere.positions, sphere.faces, process=False).export(path)
    out = tmp_path / "out"
    assert main(["compute", str(path), "--feature", "mean_curvature,curvedness", "--radius", "10%,20%",
                 "--resolution", "128", "--compute-resolution", "64", "--samples", "64", "--out", str(out)]) == 0
    for name in ("mean_curvature_3d.png", "curvedness_3d.png"):
        assert (out / name).stat().st_size > 10_000
    assert json.loads((out / "summary.json").read_text())["timings_s"]["pictures_3d_s"] > 0


@pytest.mark.shared
def test_a_100k_face_scan_is_drawn_in_seconds(shared_mesh, tmp_path):
    import time

    import trimesh

    scan = trimesh.load(shared_mesh("dragon.obj"), process=False, force="mesh")
    mesh = uvfeat.Mesh(scan.vertices, scan.faces, name="dragon")   # no UVs needed to draw it
    assert mesh.n_faces >= 100_000
    values = mesh.positions[:, 1] - mesh.positions[:, 1].mean()
    started = time.perf_counter()
    uvfeat.plot(mesh, values, feature="mean_curvature", radius="2%", path=tmp_path / "dragon.png")
    elapsed = time.perf_counter() - started
    plt.close("all")
    assert elapsed < 10.0, f"three views of {mesh.n_faces} faces took {elapsed:.1f} s"
    assert (tmp_path / "dragon.png").stat().st_size > 50_000


def test_pictures_leave_the_callers_matplotlib_backend_and_figures_alone(tmp_path):
    """uvfeat draws on figures of its own: a notebook's backend and open figures stay as they were."""
    import matplotlib

    backend, before = matplotlib.get_backend(), plt.get_fignums()
    sphere = uvfeat.shapes.uv_sphere(1.0, 16, 8)
    uvfeat.plot(sphere, sphere.positions[:, 1], feature="k1", path=tmp_path / "plot.png")
    from uvfeat.pictures.images import save_feature_figure

    save_feature_figure(tmp_path / "map.png", "k1", np.zeros((8, 8)), 0.1)
    assert matplotlib.get_backend() == backend and plt.get_fignums() == before
    assert (tmp_path / "plot.png").stat().st_size > 0 and (tmp_path / "map.png").stat().st_size > 0
