"""The converged reference: the reference of the same piecewise-flat surface refined by midpoint
subdivision, at the original vertices, with the evidence that it converged."""

import warnings

import numpy as np
import pytest

import uvfeat
from uvfeat.converged import converged_reference


@pytest.fixture(scope="module")
def coarse_torus():
    return uvfeat.shapes.torus(2.0, 0.7, 48, 24)


def test_levels_converge_geometrically_and_values_follow_the_vertices(coarse_torus):
    rows = np.arange(0, coarse_torus.n_vertices, 7)
    result = converged_reference(coarse_torus, ["mean_curvature", "gaussian_curvature"], 0.5, vertices=rows,
                                 max_levels=3, min_levels=3, tolerance=1e-9)
    assert result.level == 3 and len(result.changes) == 3 and len(result.timings_s) == 4
    assert result.faces == [coarse_torus.n_faces * 4 ** k for k in range(4)]
    assert result["mean_curvature"].shape == (len(rows),)
    for name in ("mean_curvature", "gaussian_curvature"):
        changes = [c[name] for c in result.changes]
        # each level halves the edge length: the change shrinks by well over half each time
        assert changes[1] < 0.5 * changes[0] and changes[2] < 0.5 * changes[1], (name, changes)
    assert not result.converged
    # the finest level agrees with a direct reference of the same subdivided surface at those vertices
    direct = converged_reference(coarse_torus, "mean_curvature", 0.5, max_levels=3, min_levels=3, tolerance=1e-9)
    assert np.allclose(direct["mean_curvature"][rows], result["mean_curvature"])


def test_the_converged_reference_of_a_fine_torus_is_the_analytic_curvature():
    # outer equator of a torus (R, a): H = (R + 2a) / (2 a (R + a)), K = 1 / (a (R + a)); at
    # r = 0.25 the ball estimators carry their O((r / a)^2) scale bias (measured: +2 %, +6 %).
    R, a = 2.0, 0.7
    torus = uvfeat.shapes.torus(R, a, 192, 96)
    outer = np.flatnonzero(np.abs(np.linalg.norm(torus.positions[:, :2], axis=1) - (R + a)) < 1e-9)
    result = converged_reference(torus, ["mean_curvature", "gaussian_curvature"], 0.25, vertices=outer,
                                 max_levels=2, tolerance=1.0)
    assert result.converged and result.level == 2
    assert np.median(result["mean_curvature"]) == pytest.approx((R + 2 * a) / (2 * a * (R + a)), rel=0.04)
    assert np.median(result["gaussian_curvature"]) == pytest.approx(1 / (a * (R + a)), rel=0.10)


def test_the_smooth_surface_is_the_one_a_coarse_mesh_samples():
    # A 96 x 48 torus at r = 0.25, under two edge lengths: the flat faces, chords up to h^2 k / 8
    # inside the surface through the vertices, move H by 10 % of its range (measured 9.98 / 4.96 %
    # for H / K); the smooth surface through the same vertices gives the analytic values (0.86 /
    # 0.64 %), as the parametric default does (1.64 / 0.74 % at 0.3).
    from analytic import range_normalised_error, torus_truth

    torus = uvfeat.shapes.torus(2.0, 0.5, 96, 48)
    h, k, _ = torus_truth(torus)
    rows = np.random.default_rng(0).choice(torus.n_vertices, 300, replace=False)
    errors = {}
    for surface in ("facets", "smooth"):
        result = converged_reference(torus, ["mean_curvature", "gaussian_curvature"], 0.25, vertices=rows,
                                     max_levels=3, surface=surface)
        errors[surface] = (range_normalised_error(result["mean_curvature"], h[rows]),
                           range_normalised_error(result["gaussian_curvature"], k[rows]))
    assert errors["smooth"][0] < 0.012 and errors["smooth"][1] < 0.01, errors
    assert errors["facets"][0] > 0.07 and errors["facets"][1] > 0.035, errors
    with pytest.raises(uvfeat.InvalidParameterError, match="surface"):
        converged_reference(torus, "mean_curvature", 0.25, surface="phong")
    # A face without area and a vertex on no face keep their flat positions.
    odd = uvfeat.Mesh(np.vstack([torus.positions, [[9.0, 9.0, 9.0]]]), np.vstack([torus.faces, [[0, 0, 1]]]))
    lifted = converged_reference(odd, "mean_curvature", 0.25, vertices=rows, max_levels=1, surface="smooth")
    assert np.isfinite(lifted["mean_curvature"]).all()


def test_vertices_split_at_seams_are_welded_and_keep_their_rows(coarse_torus):
    # every face with its own three vertices: the same surface, split everywhere
    split = uvfeat.Mesh(coarse_torus.positions[coarse_torus.faces].reshape(-1, 3),
                        np.arange(3 * coarse_torus.n_faces).reshape(-1, 3))
    whole = converged_reference(coarse_torus, "mean_curvature", 0.5, max_levels=1, min_levels=1)
    parts = converged_reference(split, "mean_curvature", 0.5, max_levels=1, min_levels=1)
    assert np.allclose(parts["mean_curvature"], whole["mean_curvature"][coarse_torus.faces.reshape(-1)])


def test_bad_arguments_are_named_errors(coarse_torus):
    with pytest.raises(uvfeat.InvalidParameterError, match="max_levels"):
        converged_reference(coarse_torus, "mean_curvature", 0.5, max_levels=9)
    with pytest.raises(uvfeat.InvalidParameterError, match="tolerance"):
        converged_reference(coarse_torus, "mean_curvature", 0.5, tolerance=0)
    with pytest.raises(uvfeat.InvalidParameterError, match="vertices"):
        converged_reference(coarse_torus, "mean_curvature", 0.5, vertices=[coarse_torus.n_vertices])
    with pytest.raises(uvfeat.InvalidParameterError, match="radius"):
        converged_reference(coarse_torus, "mean_curvature", -1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        converged_reference(coarse_torus, "mean_curvature", "10%", max_levels=1)
