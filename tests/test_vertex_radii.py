"""One radius per vertex (uvfeat.vertex_radii): each vertex's own ball with the surfel sums, the
maps' scale stack read at each vertex's radius otherwise; a constant array is the scalar radius."""

import functools
import warnings

import numpy as np
import pytest

import uvfeat
from analytic import range_normalised_error, torus_truth
from conftest import usage_examples
from uvfeat.vertex_radii import LEVEL_RATIO, interpolate, levels

HK = ["mean_curvature", "gaussian_curvature"]
SURFELS = dict(quadrature="surfels", samples=256)  # the lat-long torus stretches its surfels 3-5 : 1


@functools.lru_cache(maxsize=None)
def sphere() -> uvfeat.Mesh:
    return uvfeat.shapes.uv_sphere(2.0, 96, 48)


@functools.lru_cache(maxsize=None)
def torus() -> uvfeat.Mesh:
    return uvfeat.shapes.torus(2.0, 0.5, 128, 64)


def mixed_radii(mesh: uvfeat.Mesh, low: float, high: float) -> np.ndarray:
    return np.random.default_rng(1).uniform(low, high, mesh.n_vertices)


@pytest.mark.parametrize("options", [{}, SURFELS], ids=["maps", "surfels"])
def test_the_sphere_gives_one_over_r_at_any_mix_of_radii(options):
    radii = mixed_radii(sphere(), 0.15, 0.8)
    values = uvfeat.compute(sphere(), HK, radius=radii, **options)
    # Away from the lat-long poles, where the pattern's lattice is coarse (the scalar radius's too).
    z = np.asarray(sphere().positions)[:, 2]
    body = np.abs(z) < 1.6
    np.testing.assert_allclose(values["mean_curvature"][body], 0.5, rtol=0.02)
    np.testing.assert_allclose(values["gaussian_curvature"][body], 0.25, rtol=0.04)


@pytest.mark.parametrize("options", [{}, SURFELS], ids=["maps", "surfels"])
def test_a_constant_array_gives_the_scalar_result(options):
    n = torus().n_vertices
    same = uvfeat.compute(torus(), HK, radius=np.full(n, 0.3), **options)
    scalar = uvfeat.compute(torus(), HK, radius=0.3, **options)
    for name in HK:
        np.testing.assert_array_equal(same[name], scalar[name])


def test_each_vertex_takes_its_own_ball_with_the_surfel_sums():
    # Two radii on alternate vertices: each vertex's value is the scalar radius's at it, exactly
    # (on one surfel grid: by default each call takes the grid of its smallest radius).
    radii = np.where(np.arange(torus().n_vertices) % 2 == 0, 0.2, 0.45)
    mixed = uvfeat.compute(torus(), HK, radius=radii, resolution=512, **SURFELS)
    for r in (0.2, 0.45):
        scalar = uvfeat.compute(torus(), HK, radius=r, resolution=512, **SURFELS)
        rows = radii == r
        for name in HK:
            np.testing.assert_array_equal(mixed[name][rows], scalar[name][rows])


def test_the_maps_read_each_vertex_between_the_levels_around_its_radius():
    # Radii within one level ratio: two levels, the given radii themselves, read exactly.
    radii = np.where(np.arange(torus().n_vertices) % 3 == 0, 0.3, 0.3 * LEVEL_RATIO)
    mixed = uvfeat.compute(torus(), ["mean_curvature"], radius=radii)["mean_curvature"]
    for r in (0.3, 0.3 * LEVEL_RATIO):
        scalar = uvfeat.compute(torus(), ["mean_curvature"], radius=r)["mean_curvature"]
        np.testing.assert_array_equal(mixed[radii == r], scalar[radii == r])


@pytest.mark.parametrize("options", [{}, SURFELS], ids=["maps", "surfels"])
def test_the_torus_with_radii_varying_over_it_against_the_analytic_curvatures(options):
    # The radius grows around the tube (0.1 to 0.4): what a user varying the scale does.
    p = np.asarray(torus().positions)
    radii = 0.25 + 0.15 * np.cos(np.arctan2(p[:, 1], p[:, 0]))
    values = uvfeat.compute(torus(), HK, radius=radii, **options)
    h, k, _ = torus_truth(torus())
    assert range_normalised_error(values["mean_curvature"], h) < 0.02
    assert range_normalised_error(values["gaussian_curvature"], k) < 0.03


def test_map_texels_take_the_radius_of_their_surface_point():
    # Half the torus (x > 0.5) at one radius, the other half a level ratio larger: a texel whose
    # triangle lies in one half reads that half's scalar map exactly; the texels between blend.
    p = np.asarray(torus().positions)
    low, high = 0.3, 0.3 * LEVEL_RATIO
    radii = np.where(p[:, 0] > 0.5, low, high)
    atlas = uvfeat.Atlas(torus(), resolution=256)
    mixed = atlas.compute(HK, radii, compute_resolution=128)
    scalars = {r: atlas.compute(HK, r, compute_resolution=128) for r in (low, high)}
    face = atlas.face[np.ix_(np.arange(128) * 2 + 1, np.arange(128) * 2 + 1)]
    face_radii = radii[np.asarray(torus().faces)[np.maximum(face, 0)]]
    for name in HK:
        texture = mixed[name].texture
        assert texture.shape == (128, 128) and not mixed[name].is_stack and mixed[name].radius_per_vertex
        for r in (low, high):
            inside = (face >= 0) & np.all(face_radii == r, axis=-1)
            assert inside.sum() > 1000
            np.testing.assert_array_equal(texture[inside], scalars[r][name].texture[inside])
        between = (face >= 0) & (face_radii.min(-1) < face_radii.max(-1))
        lo, hi = (np.minimum(scalars[low][name].texture, scalars[high][name].texture),
                  np.maximum(scalars[low][name].texture, scalars[high][name].texture))
        assert between.any() and ((texture >= lo - 1e-6) & (texture <= hi + 1e-6))[between].all()
        np.testing.assert_array_equal(mixed[name].per_vertex(), atlas.per_vertex(name, radii, compute_resolution=128)[name])
    uvs, corners = mixed["mean_curvature"].corner_values()
    assert corners.shape == (len(uvs),) and np.isfinite(corners).all()
    assert mixed["mean_curvature"].vertex_flags()["truncated"].shape == (torus().n_vertices,)


def test_sphere_maps_keep_the_spheres_curvatures_at_every_texel_at_any_mix_of_radii():
    radii = mixed_radii(sphere(), 0.15, 0.8)
    atlas = uvfeat.Atlas(sphere(), resolution=512)
    maps = atlas.compute(HK, radii, compute_resolution=256)
    body = np.abs(atlas.position[1::2, 1::2, 2]) < 1.6
    np.testing.assert_allclose(maps["mean_curvature"].texture[body], 0.5, rtol=0.02)
    np.testing.assert_allclose(maps["gaussian_curvature"].texture[body], 0.25, rtol=0.04)


def test_levels_cover_the_radii_within_the_ratio_and_interpolate_in_log_r():
    at = levels(np.array([0.1, 0.37, 1.0]))
    assert at[0] == pytest.approx(0.1) and at[-1] == pytest.approx(1.0)
    assert np.all(at[1:] / at[:-1] <= LEVEL_RATIO * (1 + 1e-12))
    assert len(levels(np.array([0.2, 0.2]))) == 1
    values = np.log(at)[:, None].repeat(3, axis=1).astype(np.float32)   # a feature linear in log r
    radii = np.array([0.1, 0.3, 1.0])
    np.testing.assert_allclose(interpolate(values, at, radii), np.log(radii), rtol=1e-5)
    values[1:, 0] = np.nan                                               # a level's NaN stays its own
    assert interpolate(values, at, radii)[0] == pytest.approx(np.log(0.1))


def test_bad_per_vertex_radii_are_clear_errors():
    n = torus().n_vertices
    radii = np.full(n, 0.3)
    radii[7] = -1.0
    with pytest.raises(uvfeat.InvalidParameterError, match="radius of vertex 7 is -1.0"):
        uvfeat.compute(torus(), HK, radius=radii)
    radii[7] = np.nan
    with pytest.raises(uvfeat.InvalidParameterError, match="radius of vertex 7 is nan"):
        uvfeat.compute(torus(), HK, radius=radii, **SURFELS)
    atlas = uvfeat.Atlas(torus(), resolution=256)
    with pytest.raises(uvfeat.InvalidParameterError, match="radius of vertex 7 is nan"):
        atlas.compute("mean_curvature", radii)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert atlas.per_vertex("mean_curvature", np.full(n, 0.3), **SURFELS)["mean_curvature"].shape == (n,)
    radii[7] = 2 * torus().bounding_box_diagonal
    for options in ({}, SURFELS):
        with pytest.raises(uvfeat.InvalidParameterError, match="larger than the mesh"):
            atlas.per_vertex("mean_curvature", radii, **options)


def test_the_per_vertex_radius_example_runs_as_written(capsys):
    (example,) = usage_examples("A radius per vertex")
    exec(compile(example, "docs/USAGE.md", "exec"), {})
    assert capsys.readouterr().out.split() == ["True", "True"]
