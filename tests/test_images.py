"""Pictures of parametric-space buffers and feature maps (uvfeat.pictures.images): colour ranges, masks,
orientation (v up) and the files written."""

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
from PIL import Image

import uvfeat
from uvfeat.pictures import images


def rgba_of(colormap: str, t: float) -> np.ndarray:
    return np.asarray(matplotlib.colormaps[colormap](t))


# -- PNG writing ----------------------------------------------------------------------------------

def test_save_png_size_mode_values_and_v_up(tmp_path):
    rgba = np.zeros((6, 10, 4))
    rgba[..., 3] = 1.0
    rgba[0, :, 0] = 1.0           # buffer row 0 is v = 0: the bottom of the picture
    rgba[-1, :, 2] = 0.5          # last row (v = 1): the top, half blue
    rgba[2, 3] = (2.0, -1.0, 0.25, 1.0)  # out of range: clipped
    path = tmp_path / "a.png"
    images.save_png(path, rgba)
    with Image.open(path) as picture:
        assert picture.size == (10, 6)
        assert picture.mode == "RGBA"
        pixels = np.asarray(picture)
    np.testing.assert_array_equal(pixels[-1, 0], (255, 0, 0, 255))
    np.testing.assert_array_equal(pixels[0, 0], (0, 0, 128, 255))  # 0.5 rounds to 128
    np.testing.assert_array_equal(pixels[6 - 1 - 2, 3], (255, 0, 64, 255))


def test_save_png_rgb(tmp_path):
    path = tmp_path / "rgb.png"
    images.save_png(path, np.full((4, 4, 3), 1.0))
    with Image.open(path) as picture:
        assert picture.mode == "RGB" and picture.size == (4, 4)
        assert np.all(np.asarray(picture) == 255)


# -- buffer pictures --------------------------------------------------------------------------------

def test_position_image_normalises_by_bounding_box_and_masks_nan():
    position = np.array([[[0.0, 10.0, -1.0], [np.nan, np.nan, np.nan]],
                         [[2.0, 30.0, 1.0], [1.0, 20.0, 0.0]]])
    rgba = images.position_image(position)
    assert rgba.shape == (2, 2, 4)
    np.testing.assert_allclose(rgba[0, 0], (0, 0, 0, 1))
    np.testing.assert_allclose(rgba[1, 0], (1, 1, 1, 1))
    np.testing.assert_allclose(rgba[1, 1], (0.5, 0.5, 0.5, 1))
    np.testing.assert_array_equal(rgba[0, 1], (0, 0, 0, 0))  # empty texel: transparent


def test_normal_image_maps_minus_one_one_to_zero_one():
    normal = np.array([[[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0]], [[np.nan] * 3, [0.6, -0.8, 0.0]]])
    rgba = images.normal_image(normal)
    np.testing.assert_allclose(rgba[0, 0], (0.5, 0.5, 1.0, 1.0))
    np.testing.assert_allclose(rgba[0, 1], (0.0, 0.5, 0.5, 1.0))
    np.testing.assert_allclose(rgba[1, 1], (0.8, 0.1, 0.5, 1.0))
    assert rgba[1, 0, 3] == 0


def test_chart_colours_distinct_deterministic_in_range():
    colours = images.chart_colours(20)
    assert colours.shape == (20, 3)
    assert np.all((colours >= 0) & (colours <= 1))
    np.testing.assert_array_equal(colours, images.chart_colours(20))
    np.testing.assert_array_equal(colours[:5], images.chart_colours(5))
    distances = np.linalg.norm(colours[:, None] - colours[None], axis=-1)
    assert np.min(distances[~np.eye(20, dtype=bool)]) > 0.01
    assert images.chart_colours(0).shape == (0, 3)


def test_chart_image_border_in_the_adjacent_charts_colour():
    chart = np.array([[0, 0, 1, 1],
                      [0, 0, 1, 1],
                      [-1, 0, 2, -1]])
    border = np.array([[False, True, True, False],
                       [True, False, False, False],
                       [False, False, True, False]])
    adjacent = np.array([[-1, 1, 0, -1],
                         [-1, -1, -1, -1],
                         [-1, -1, 1, -1]])
    colours = images.chart_colours(3)
    rgba = images.chart_image(chart, border, adjacent)
    np.testing.assert_allclose(rgba[0, 0, :3], colours[0])                # interior of chart 0
    np.testing.assert_allclose(rgba[0, 3, :3], colours[1])                # interior of chart 1
    np.testing.assert_allclose(rgba[0, 1, :3], 0.6 * colours[1])          # chart 0 at the seam with 1
    np.testing.assert_allclose(rgba[0, 2, :3], 0.6 * colours[0])          # chart 1 at the seam with 0
    np.testing.assert_allclose(rgba[2, 2, :3], 0.6 * colours[1])
    np.testing.assert_allclose(rgba[1, 0, :3], 1.0)                       # mesh border: white
    assert rgba[2, 0, 3] == 0 and rgba[2, 3, 3] == 0                      # empty texels transparent
    assert np.all(rgba[chart >= 0, 3] == 1)


@pytest.fixture(scope="module")
def spot_atlas():
    return uvfeat.Atlas(uvfeat.examples.spot(), 128)


def test_chart_image_of_a_multi_chart_atlas(spot_atlas):
    atlas = spot_atlas
    rgba = images.chart_image(atlas.chart, atlas.border, atlas.adjacent_chart)
    colours = images.chart_colours(atlas.n_charts)
    seam = atlas.border & (atlas.adjacent_chart >= 0)
    inside = (atlas.chart >= 0) & ~atlas.border
    assert seam.sum() > 100 and inside.sum() > 1000
    np.testing.assert_allclose(rgba[seam, :3], 0.6 * colours[atlas.adjacent_chart[seam]])
    np.testing.assert_allclose(rgba[inside, :3], colours[atlas.chart[inside]])
    np.testing.assert_array_equal(rgba[..., 3], (atlas.chart >= 0).astype(float))
    # seams between two different charts show the other chart's colour, not the texel's own
    cross = seam & (atlas.adjacent_chart != atlas.chart)
    assert cross.any()
    assert np.all(np.abs(rgba[cross, :3] - 0.6 * colours[atlas.chart[cross]]).max(axis=-1) > 1e-6)


def test_mesh_border_texels_are_white():
    atlas = uvfeat.Atlas(uvfeat.shapes.cylinder(1.0, 2.0, 32, 8), 128)
    rgba = images.chart_image(atlas.chart, atlas.border, atlas.adjacent_chart)
    open_end = atlas.border & (atlas.adjacent_chart < 0)
    assert open_end.any()
    np.testing.assert_allclose(rgba[open_end], 1.0)


# -- scalar pictures and colour ranges ---------------------------------------------------------------

def test_scalar_image_robust_percentiles_nan_transparent():
    values = np.linspace(0.0, 1.0, 1000).reshape(20, 50)
    values[0, 0] = 1e6                 # outlier must not set the range
    values[5, 5] = np.nan
    rgba, low, high = images.scalar_image(values)
    assert 0.0 <= low < 0.02
    assert 0.97 < high < 1.0
    assert rgba[5, 5, 3] == 0 and np.all(rgba[5, 5] == 0)
    assert np.sum(rgba[..., 3] == 0) == 1
    np.testing.assert_allclose(rgba[0, 0, :3], rgba_of("viridis", 1.0)[:3])   # clamped high
    np.testing.assert_allclose(rgba[0, 1, :3], rgba_of("viridis", 0.0)[:3])   # value ~0.001, below low


def test_scalar_image_explicit_range_and_colormap():
    values = np.array([[-2.0, 0.0, 2.0, 4.0]])
    rgba, low, high = images.scalar_image(values, "RdBu_r", low=-2.0, high=2.0)
    assert (low, high) == (-2.0, 2.0)
    np.testing.assert_allclose(rgba[0, 0, :3], rgba_of("RdBu_r", 0.0)[:3])
    np.testing.assert_allclose(rgba[0, 1, :3], rgba_of("RdBu_r", 0.5)[:3])
    np.testing.assert_allclose(rgba[0, 2, :3], rgba_of("RdBu_r", 1.0)[:3])
    np.testing.assert_allclose(rgba[0, 3, :3], rgba_of("RdBu_r", 1.0)[:3])


def test_scalar_image_all_nan_is_fully_transparent():
    rgba, low, high = images.scalar_image(np.full((3, 3), np.nan))
    assert np.all(rgba == 0) and (low, high) == (0.0, 1.0)


def test_distortion_image_log_ratio():
    sigma = np.ones((4, 4, 2), dtype=np.float32)
    sigma[0, :, 0] = 4.0                      # anisotropy 4 on the first row
    sigma[3, 3] = np.nan                      # empty texel
    sigma[3, 2] = (1.0, 0.0)                  # degenerate: no finite ratio
    rgba = images.distortion_image(sigma)
    assert rgba[3, 3, 3] == 0 and rgba[3, 2, 3] == 0
    np.testing.assert_allclose(rgba[1, 1, :3], rgba_of("viridis", 0.0)[:3])  # conformal: the low end
    np.testing.assert_allclose(rgba[0, 0, :3], rgba_of("viridis", 1.0)[:3])  # most anisotropic: the high end


def test_colour_range_signed_features_symmetric():
    values = np.concatenate([np.linspace(-1.0, 3.0, 999), [np.nan]])
    cmap, low, high = images.colour_range("mean_curvature", values)
    assert cmap == "RdBu_r"
    assert low == -high
    assert high == pytest.approx(np.percentile(np.abs(values[:-1]), 98.0))
    for name in ("gaussian_curvature", "k1", "k2"):
        assert images.colour_range(name, values)[0] == "RdBu_r"
    assert images.colour_range("shape_index", values) == ("RdBu_r", -1.0, 1.0)


def test_colour_range_ignores_one_huge_outlier():
    values = np.concatenate([np.linspace(0.0, 1.0, 1000), [1e9]])
    cmap, low, high = images.colour_range("curvedness", values)
    assert cmap == "viridis"
    assert 0.0 <= low < 0.05 and 0.95 < high < 1.0
    _, low, high = images.colour_range("mean_curvature", np.concatenate([values, [-1e9]]))
    assert -1.0 <= low < -0.95 and high == -low


def test_colour_range_degenerate_inputs():
    assert images.colour_range("mean_curvature", np.zeros(10)) == ("RdBu_r", -1.0, 1.0)
    assert images.colour_range("curvedness", np.full(5, 2.0)) == ("viridis", 2.0, 3.0)
    assert images.colour_range("curvedness", np.full(5, np.nan)) == ("viridis", -1.0, 1.0)
    assert images.colour_range("k1", np.full(5, np.nan)) == ("RdBu_r", -1.0, 1.0)


def test_vertex_colours():
    values = np.array([-10.0, 0.0, 10.0, np.nan] + [0.5] * 100)
    colours = images.vertex_colours("mean_curvature", values)
    assert colours.shape == (104, 4) and colours.dtype == np.uint8
    np.testing.assert_array_equal(colours[3], (128, 128, 128, 255))
    np.testing.assert_array_equal(colours[0], (rgba_of("RdBu_r", 0.0) * 255).astype(np.uint8))
    np.testing.assert_array_equal(colours[2], (rgba_of("RdBu_r", 1.0) * 255).astype(np.uint8))
    np.testing.assert_array_equal(colours[1], (rgba_of("RdBu_r", 0.5) * 255).astype(np.uint8))


# -- figures and animation frames ------------------------------------------------------------------

def test_save_feature_figure_signed_map(tmp_path):
    texture = np.full((64, 64), np.nan, dtype=np.float32)
    texture[8:56, 8:32] = -1.0
    texture[8:56, 32:56] = 1.0
    field = np.zeros((64, 64, 2))
    field[..., 0] = 1.0
    path = tmp_path / "mean.png"
    images.save_feature_figure(path, "mean_curvature", texture, 0.1, "test", line_field=field)
    with Image.open(path) as picture:
        pixels = np.asarray(picture.convert("RGB")).astype(int)
        assert picture.size[0] > 300 and picture.size[1] > 300
    blue = (pixels[..., 2] > 80) & (pixels[..., 0] < 40)        # RdBu_r low end, dark blue
    red = (pixels[..., 0] > 80) & (pixels[..., 2] < 40)         # high end, dark red
    assert blue.sum() > 500 and red.sum() > 500
    # the map is the first run of coloured columns (the colourbar comes after a gap, on the right);
    # its negative half lies left of its positive half
    coloured = (blue | red).any(axis=0)
    start = int(np.argmax(coloured))
    end = start + int(np.argmin(coloured[start:]))
    assert end - start > 100
    columns_blue = np.nonzero(blue[:, start:end].any(axis=0))[0]
    columns_red = np.nonzero(red[:, start:end].any(axis=0))[0]
    assert columns_blue.max() < columns_red.min() + 3


def test_feature_picture_white_off_charts_v_up():
    texture = np.full((4, 4), np.nan)
    texture[0] = 0.0   # v = 0: the bottom row of the picture
    texture[1] = 1.0
    picture = images.feature_picture("curvedness", texture, 0.0, 1.0)
    assert picture.shape == (4, 4, 3) and picture.dtype == np.uint8
    np.testing.assert_array_equal(picture[:2], 255)
    low, high = (np.round(rgba_of("viridis", t)[:3] * 255).astype(np.uint8) for t in (0.0, 1.0))
    np.testing.assert_array_equal(picture[3, 0], low)
    np.testing.assert_array_equal(picture[2, 0], high)


def test_save_gif_frames_timing_loop(tmp_path):
    frames = [np.full((8, 8, 3), k * 60, dtype=np.uint8) for k in range(4)]
    path = tmp_path / "a.gif"
    images.save_gif(path, frames, fps=10)
    with Image.open(path) as gif:
        assert gif.n_frames == 4
        assert gif.info["duration"] == 100
        assert gif.info["loop"] == 0
        assert gif.size == (8, 8)
        gif.seek(2)
        assert np.asarray(gif.convert("RGB"))[0, 0, 0] == 120


def test_save_atlas_pictures(tmp_path):
    atlas = uvfeat.Atlas(uvfeat.shapes.uv_sphere(1.0, 32, 16), 128)
    paths = images.save_atlas_pictures(atlas, tmp_path / "pictures")
    assert set(paths) == {"position", "normal", "charts", "distortion"}
    covered = np.flipud(atlas.chart >= 0)
    for name, path in paths.items():
        with Image.open(path) as picture:
            assert picture.size == (128, 128) and picture.mode == "RGBA", name
            alpha = np.asarray(picture)[..., 3]
        if name != "distortion":
            np.testing.assert_array_equal(alpha == 255, covered, err_msg=name)
        assert np.all(alpha[~covered] == 0), name
    with Image.open(paths["normal"]) as picture:
        rgb = np.asarray(picture)[..., :3].astype(float) / 255 * 2 - 1
    norms = np.linalg.norm(rgb[covered], axis=-1)
    assert np.median(np.abs(norms - 1)) < 0.02


def test_save_figure_crops_as_matplotlib_tight_without_its_extra_draw(tmp_path, monkeypatch):
    """The crop measured without drawing gives the pixels of ``bbox_inches="tight"``, for a map
    with a long title (wider than the figure) and for the 3D views with their colour bar."""
    texture = np.linspace(-1.0, 1.0, 64 * 64).reshape(64, 64)
    torus = uvfeat.shapes.torus(2.0, 0.5, 48, 24)
    figures = []
    monkeypatch.setattr(images, "save_figure", lambda fig, path, **options: figures.append((fig, options)))
    images.save_feature_figure(tmp_path / "map.png", "mean_curvature", texture, 0.1, "a_scan_with_a_name_" * 4)
    uvfeat.plot(torus, torus.positions[:, 2], feature="mean_curvature", radius=["2%"], path=tmp_path / "3d.png")
    assert len(figures) == 2
    for k, (fig, options) in enumerate(figures):
        monkeypatch.undo()
        images.save_figure(fig, tmp_path / f"ours{k}.png", **options)
        fig.savefig(tmp_path / f"tight{k}.png", bbox_inches="tight", pil_kwargs={"compress_level": 1}, **options)
        with Image.open(tmp_path / f"ours{k}.png") as ours, Image.open(tmp_path / f"tight{k}.png") as tight:
            assert ours.size == tight.size
            np.testing.assert_array_equal(np.asarray(ours), np.asarray(tight))
