"""The parametric method against the object-space reference (uvfeat.compare): the documented
error formula, the comparison on analytic meshes, and the pictures."""

import json
import math

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
from PIL import Image

import uvfeat
from uvfeat.compare import PARAMETRIC_GAUSSIAN, Comparison, absolute_errors, compare, save_comparison_pictures

SMALL = dict(samples=64, resolution=256, compute_resolution=64)


# -- the error formula ------------------------------------------------------------------------------

def test_absolute_errors_by_hand():
    # reference 0..100: Q1 = 1 and Q99 = 99 exactly (linear interpolation), mean |f_ref| = 50
    reference = np.arange(101.0)
    values = reference + np.where(np.arange(101) % 2 == 0, 0.5, -0.5)   # |error| 0.5 everywhere
    errors = absolute_errors(values, reference)
    assert errors["compared"] == 101
    assert errors["mean_absolute"] == pytest.approx(0.5)
    assert errors["percent_ae"] == pytest.approx(100 * 0.5 / 98)
    assert errors["mean_normalised"] == pytest.approx(0.5 / 50)


def test_absolute_errors_leave_nan_out_on_either_side():
    reference = np.arange(101.0)
    values = reference + 1.0
    with_gaps = np.concatenate([values, [np.nan, 1e9, np.inf]])
    reference_gaps = np.concatenate([reference, [5.0, np.nan, 3.0]])
    errors = absolute_errors(with_gaps, reference_gaps)
    assert errors["compared"] == 101
    assert errors["mean_absolute"] == pytest.approx(1.0)
    assert errors["percent_ae"] == pytest.approx(100 / 98)
    assert errors["mean_normalised"] == pytest.approx(1 / 50)


def test_absolute_errors_small_arrays():
    values = np.array([1.0, 2.0, np.nan, -1.0, 4.0])
    reference = np.array([1.5, 1.0, 3.0, np.nan, 2.0])
    # compared: (1, 1.5), (2, 1), (4, 2): |e| = 0.5, 1, 2
    error = (0.5 + 1.0 + 2.0) / 3
    q1, q99 = 1.0 + 0.02 * 0.5, 1.5 + 0.98 * 0.5           # percentiles of [1, 1.5, 2]
    errors = absolute_errors(values, reference)
    assert errors["compared"] == 3
    assert errors["mean_absolute"] == pytest.approx(error)
    assert errors["percent_ae"] == pytest.approx(100 * error / (q99 - q1))
    assert errors["mean_normalised"] == pytest.approx(error / 1.5)
    # signed references: the scale is the mean of |f_ref|, the range is Q99 - Q1
    errors = absolute_errors(np.array([0.0, 0.0]), np.array([-2.0, 2.0]))
    assert errors["mean_normalised"] == pytest.approx(1.0)
    assert errors["percent_ae"] == pytest.approx(100 * 2.0 / (2.0 * 0.98 - (-2.0 * 0.98)))


def test_absolute_errors_degenerate_references():
    constant = absolute_errors(np.array([1.0, 2.0, 3.0]), np.full(3, 2.0))
    assert math.isnan(constant["percent_ae"])
    assert constant["mean_normalised"] == pytest.approx((1 + 0 + 1) / 3 / 2)
    zero = absolute_errors(np.array([1.0, 1.0]), np.zeros(2))
    assert math.isnan(zero["mean_normalised"]) and math.isnan(zero["percent_ae"])
    assert zero["mean_absolute"] == 1.0
    nothing = absolute_errors(np.array([np.nan, 1.0]), np.array([1.0, np.nan]))
    assert nothing["compared"] == 0
    assert all(math.isnan(nothing[k]) for k in ("percent_ae", "mean_normalised", "mean_absolute"))
    exact = absolute_errors(np.arange(5.0), np.arange(5.0))
    assert exact["percent_ae"] == 0.0 and exact["mean_normalised"] == 0.0


def test_absolute_errors_accept_lists_and_float32():
    errors = absolute_errors(np.array([1, 2, 3], dtype=np.float32), [1.0, 2.0, 4.0])
    assert errors["mean_absolute"] == pytest.approx(1 / 3)
    assert isinstance(errors["percent_ae"], float) and isinstance(errors["compared"], int)


# -- the comparison ---------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def ellipsoid_comparison():
    mesh = uvfeat.shapes.ellipsoid(1.0, 0.8, 0.6, 64, 32)
    return compare(mesh, ["mean_curvature", "gaussian_curvature"], 0.3, **SMALL)


def test_parametric_agrees_with_the_reference_on_an_ellipsoid(ellipsoid_comparison):
    result = ellipsoid_comparison
    assert isinstance(result, Comparison)
    assert set(result.errors) == {"mean_curvature", "gaussian_curvature"}
    for name, errors in result.errors.items():
        assert errors["percent_ae"] < 5.0, (name, errors)
        assert errors["mean_normalised"] < 0.1, (name, errors)
        assert errors["compared"] > 0.95 * result.mesh.n_vertices


def test_errors_follow_the_documented_formula(ellipsoid_comparison):
    result = ellipsoid_comparison
    assert result.truth is not None and result.settings["truth_level"] >= 1
    for name in ("mean_curvature", "gaussian_curvature"):
        par, ref = result.parametric[name], result.truth[name]
        assert par.shape == ref.shape == (result.mesh.n_vertices,)
        both = np.isfinite(par) & np.isfinite(ref)
        error = np.mean(np.abs(par[both].astype(np.float64) - ref[both]))
        q1, q99 = np.percentile(ref[both], [1, 99])
        assert result.errors[name]["percent_ae"] == pytest.approx(100 * error / (q99 - q1), rel=1e-9)
        assert result.errors[name]["mean_normalised"] == pytest.approx(error / np.mean(np.abs(ref[both])), rel=1e-9)
        assert result.errors[name]["compared"] == both.sum()


def test_the_truth_is_the_converged_reference_unless_asked_otherwise(ellipsoid_comparison):
    result = ellipsoid_comparison
    for name, own in result.reference_errors.items():
        assert own == absolute_errors(result.reference[name], result.truth[name])
        # the coarse reference's own h / r error is visible against the converged truth
        assert own["mean_normalised"] > 0
    plain = compare(uvfeat.shapes.ellipsoid(1.0, 0.8, 0.6, 32, 16), "mean_curvature", 0.4, truth_levels=0, **SMALL)
    assert plain.truth is None and plain.reference_errors is None
    assert plain.errors["mean_curvature"] == absolute_errors(plain.parametric["mean_curvature"],
                                                             plain.reference["mean_curvature"])


def test_comparison_is_of_the_same_feature():
    # a swapped or misaligned feature would show as a large error: H ~ 1.1, K ~ 1.3 on this ellipsoid
    mesh = uvfeat.shapes.ellipsoid(1.0, 0.8, 0.6, 64, 32)
    result = compare(mesh, "mean_curvature,gaussian_curvature", 0.3, **SMALL)
    crossed = absolute_errors(result.parametric["mean_curvature"], result.reference["gaussian_curvature"])
    assert crossed["percent_ae"] > 3 * result.errors["gaussian_curvature"]["percent_ae"]
    shuffled = absolute_errors(np.roll(result.parametric["mean_curvature"], 500), result.reference["mean_curvature"])
    assert shuffled["percent_ae"] > 3 * result.errors["mean_curvature"]["percent_ae"]


def test_sphere_values_near_analytic():
    # H = 1/r, K = 1/r^2 everywhere. (%AE is range-normalised and a sphere's reference range is
    # only noise, so the mean-normalised error is the measure here. The truth is the coarse
    # reference: refined, the reference measures the 32 x 16 polyhedron, whose H at r = 1.5 h is
    # not the sphere's, while the parametric side measures the smooth surface through it.)
    mesh = uvfeat.shapes.uv_sphere(2.0, 32, 16)
    result = compare(mesh, ["mean_curvature", "gaussian_curvature"], 0.6, truth_levels=0, **SMALL)
    assert abs(np.nanmedian(result.parametric["mean_curvature"]) - 0.5) < 0.02
    assert abs(np.nanmedian(result.reference["mean_curvature"]) - 0.5) < 0.02
    assert abs(np.nanmedian(result.parametric["gaussian_curvature"]) - 0.25) < 0.02
    for errors in result.errors.values():
        assert errors["mean_normalised"] < 0.05
    assert result.radius == pytest.approx(0.6)


def test_timings_settings_and_json(ellipsoid_comparison):
    result = ellipsoid_comparison
    t = result.timings
    for key in ("parametric", "parametric_buffers", "parametric_features", "parametric_per_vertex", "reference",
                "untimed_preprocessing", "untimed_connectivity"):
        assert t[key] >= 0.0, key
    assert t["speedup"] == pytest.approx(t["reference"] / t["parametric"])
    assert t["parametric"] == pytest.approx(t["parametric_buffers"] + t["parametric_features"]
                                            + t["parametric_per_vertex"])
    s = result.settings
    assert s["features"] == ["mean_curvature", "gaussian_curvature"]
    assert (s["samples"], s["resolution"], s["compute_resolution"]) == (64, 256, 64)
    assert s["gaussian_method"] == "moments" and s["parametric_gaussian_method"] == "moments"
    assert s["mean_reference_samples"] > 10 and s["mean_parametric_samples"] > 10
    summary = json.loads(json.dumps(result.to_dict()))
    assert summary["vertices"] == result.mesh.n_vertices and summary["faces"] == result.mesh.n_faces
    assert summary["errors"]["mean_curvature"]["percent_ae"] == pytest.approx(result.errors["mean_curvature"]["percent_ae"])
    assert summary["radius"] == pytest.approx(0.3) and summary["uvfeat"] == uvfeat.__version__


def test_relative_radius_and_exact_geodesic_reference_maps_to_geodesic_area():
    mesh = uvfeat.shapes.uv_sphere(1.0, 32, 16)
    result = compare(mesh, "gaussian_curvature", "10%", gaussian_method="exact_geodesic_area", **SMALL)
    assert result.radius == pytest.approx(0.1 * mesh.bounding_box_diagonal)
    assert result.settings["parametric_gaussian_method"] == "geodesic_area"
    assert PARAMETRIC_GAUSSIAN["exact_geodesic_area"] == "geodesic_area"
    # (the geodesic-disk K amplifies sampled-area noise some 100-fold at this radius, so only the
    # reference, with exact geodesics, is held to the analytic K = 1)
    assert abs(np.nanmedian(result.reference["gaussian_curvature"]) - 1.0) < 0.2
    assert np.isfinite(result.parametric["gaussian_curvature"]).mean() > 0.95


def test_unknown_gaussian_method_is_refused():
    with pytest.raises(uvfeat.InvalidParameterError, match="gaussian_method"):
        compare(uvfeat.shapes.uv_sphere(1.0, 16, 8), "gaussian_curvature", 0.3, gaussian_method="angle_defect",
                **SMALL)


# -- pictures ---------------------------------------------------------------------------------------

def test_save_comparison_pictures_writes_what_it_returns(ellipsoid_comparison, tmp_path):
    out = tmp_path / "pictures" / "nested"
    paths = save_comparison_pictures(ellipsoid_comparison, out)
    assert set(paths) == {"compare_mean_curvature", "error_mean_curvature",
                          "compare_gaussian_curvature", "error_gaussian_curvature"}
    assert sorted(p.name for p in out.iterdir()) == sorted(f"{k}.png" for k in paths)
    for key, path in paths.items():
        assert path == str(out / f"{key}.png")
        with Image.open(path) as picture:
            assert picture.format == "PNG"
            width, height = picture.size
            pixels = np.asarray(picture.convert("RGB")).astype(int)
        if key.startswith("compare_"):
            assert width > 2.5 * height and width > 1000      # three panels side by side
        else:
            assert 0.8 < width / height < 1.6
        # the mesh is drawn: many pixels are neither white nor black
        saturated = np.ptp(pixels, axis=-1) > 40
        assert saturated.mean() > 0.05, key


def test_comparison_pictures_survive_all_nan_feature(tmp_path):
    mesh = uvfeat.shapes.uv_sphere(1.0, 16, 8)
    n = mesh.n_vertices
    comparison = Comparison(mesh, 0.3, {"k1": np.full(n, np.nan, np.float32)}, {"k1": np.linspace(0, 1, n)},
                            {"k1": absolute_errors(np.full(n, np.nan), np.linspace(0, 1, n))},
                            {"parametric": 1.0, "reference": 2.0, "speedup": 2.0})
    paths = save_comparison_pictures(comparison, tmp_path)
    assert set(paths) == {"compare_k1", "error_k1"}
    for path in paths.values():
        with Image.open(path) as picture:
            assert picture.size[0] > 100


def test_many_charts_compare_the_values_at_the_vertices_that_uvfeat_compute_gives():
    # An icosphere without UVs gets uvfeat's atlas: compare's parametric side is then
    # uvfeat.compute's default (the surfel sums at the vertices, their own atlas), and a named
    # quadrature keeps the maps. H of the unit sphere is 1; its icosphere's facets, which the sums
    # measure, lie inside it (their converged H is 1.023 at this radius, the sums' 1.024).
    import trimesh

    ico = trimesh.creation.icosphere(4)
    mesh = uvfeat.Mesh(ico.vertices, ico.faces).with_atlas(cache=False)
    assert mesh.n_charts > 1
    result = compare(mesh, "mean_curvature", "10%", truth_levels=0)
    assert result.settings["parametric"].startswith("values at the vertices")
    assert result.settings["mean_parametric_samples"] is None
    np.testing.assert_array_equal(result.parametric["mean_curvature"],
                                  uvfeat.compute(mesh, "mean_curvature", "10%")["mean_curvature"])
    assert abs(np.median(result.parametric["mean_curvature"]) - 1.023) < 0.01
    maps = compare(mesh, "mean_curvature", "10%", truth_levels=0, quadrature="pattern", **SMALL)
    assert maps.settings["parametric"] == "maps" and maps.settings["mean_parametric_samples"] > 10
    assert not np.array_equal(maps.parametric["mean_curvature"], result.parametric["mean_curvature"])
