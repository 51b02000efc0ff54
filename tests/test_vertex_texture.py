"""Per-vertex values as a texture (``Atlas.vertex_texture``): each texel the values of its face's
corners interpolated at its centre, against a linear function, the analytic torus and the
surfels' maps computed at the texels."""

import numpy as np
import pytest

import uvfeat
from analytic import range_normalised_error, torus_charts

HK = ["mean_curvature", "gaussian_curvature"]


def torus_curvatures(p: np.ndarray, major: float = 2.0, minor: float = 0.5):
    ring = np.hypot(p[..., 0], p[..., 1]) - major
    cos_v = np.clip(ring / minor, -1.0, 1.0)
    return (major + 2 * minor * cos_v) / (2 * minor * (major + minor * cos_v)), cos_v / (minor * (major + minor * cos_v))


def test_a_linear_function_is_interpolated_exactly_over_the_faces():
    atlas = uvfeat.Atlas(torus_charts(), resolution=256)
    x = atlas.vertex_texture(atlas.mesh.positions[:, 0], 256)
    covered = atlas.face >= 0
    assert x.dtype == np.float32 and x.shape == (256, 256)
    np.testing.assert_array_equal(np.isfinite(x), covered)
    # Off the facets by the smooth surface's lift (h^2 k / 8, 7e-4 here) inside the faces; the
    # border texels' centres lie outside their face, whose clamped corner weights differ more.
    error = np.abs(x - atlas.position[..., 0])[covered]
    assert np.percentile(error, 90) < 2e-3 and np.median(error) < 1e-4


def test_values_at_the_vertices_as_a_texture_against_the_analytic_torus_and_the_surfels_maps():
    # 36 charts, r = 2 %, the sums at the vertices on the smooth surface through them (the torus
    # the vertices sample; the default's facets lie inside it): measured 0.42 % (H) and 0.48 % (K)
    # of the range from the analytic values at the texels' surface points; the surfels' maps
    # computed at every texel of the same 256² atlas are 1.5 % and 1.8 % off. A wrong factor or
    # sign would be tens of percent.
    mesh = torus_charts()
    atlas = uvfeat.Atlas(mesh, resolution=256)
    values = uvfeat.compute(mesh, HK, "2%", surface="smooth")
    textures = atlas.vertex_texture(np.stack([values[f] for f in HK]), 256)
    assert textures.shape == (2, 256, 256)
    covered = atlas.face >= 0
    surfel_maps = atlas.compute(HK, "2%", compute_resolution=256, quadrature="surfels")
    for texture, name, truth in zip(textures, HK, torus_curvatures(atlas.position)):
        assert range_normalised_error(texture[covered], truth[covered]) < 0.008, name
        assert range_normalised_error(surfel_maps[name].texture[covered], truth[covered]) < 0.025, name
        assert range_normalised_error(texture, surfel_maps[name].texture) < 0.02, name


def test_vertices_without_values_are_left_out_and_bad_input_is_named():
    atlas = uvfeat.Atlas(uvfeat.shapes.plane(1.0, 8), resolution=64)
    values = np.ones(atlas.mesh.n_vertices)
    values[0] = np.nan
    texture = atlas.vertex_texture(values, 32)
    np.testing.assert_array_equal(texture[np.isfinite(texture)], 1.0)
    # NaN only where the vertex without a value holds all the weight (the corner texel here).
    covered = np.isfinite(atlas.vertex_texture(np.ones_like(values), 32))
    assert 0 < covered.sum() - np.isfinite(texture).sum() <= 1
    with pytest.raises(uvfeat.InvalidParameterError, match="n_vertices"):
        atlas.vertex_texture(values[:-1], 32)
    with pytest.raises(uvfeat.InvalidParameterError, match="width"):
        atlas.vertex_texture(values, 0)
