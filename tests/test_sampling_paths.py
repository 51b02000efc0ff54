"""The samplers against their reference, the exact path (`sampling="exact"`), with the same seeds,
on the single-chart torus, on an xatlas atlas and, where the shared meshes are present, on Pizza
(4,740 charts: most samples cross seams there). The per-texel fast path draws the exact path's
samples and must give its maps up to f32 rounding; the shared lattice (default) draws other
points, so it must be as accurate as the exact path against the truth."""

import numpy as np
import pytest

import uvfeat
from analytic import range_normalised_error, torus_single, torus_truth, torus_xatlas

FEATURES = ["mean_curvature", "gaussian_curvature", "bending_energy"]


@pytest.mark.parametrize("mesh_factory", [torus_single, torus_xatlas], ids=["single-chart", "xatlas"])
def test_every_path_is_as_accurate_as_the_exact_one(mesh_factory):
    mesh = mesh_factory()
    atlas = uvfeat.Atlas(mesh, 1024)
    options = dict(radius=0.15, compute_resolution=128, seed=3)
    shared = atlas.compute(FEATURES, **options)
    fast = atlas.compute(FEATURES, sampling="fast", **options)
    exact = atlas.compute(FEATURES, sampling="exact", **options)
    # f32 rounding can move a sample lying on the sphere |q - p| = r in or out of the ball.
    _assert_same_maps(fast, exact, FEATURES)
    truth_h, truth_k, _ = torus_truth(mesh)
    for name, truth in (("mean_curvature", truth_h), ("gaussian_curvature", truth_k)):
        errors = {path: range_normalised_error(maps[name].per_vertex(), truth)
                  for path, maps in (("shared", shared), ("exact", exact))}
        assert errors["exact"] < 0.03 and errors["shared"] <= 1.1 * errors["exact"], (name, errors)
    # Bending energy has no closed form: the two agree on average (to 0.1 %, where a wrong factor or
    # a biased weight would show) and per vertex within the exact path's noise (about 3 % of the
    # narrow range of bending energy over this torus).
    bending = [maps["bending_energy"].per_vertex() for maps in (shared, exact)]
    assert abs(np.nanmean(bending[0]) / np.nanmean(bending[1]) - 1) < 1e-3
    assert range_normalised_error(*bending) < 0.05


def _assert_same_maps(fast, exact, names):
    for name in names:
        a, b = fast[name].texture, exact[name].texture
        assert np.array_equal(np.isnan(a), np.isnan(b)), name
        close = np.isclose(a, b, rtol=1e-4, atol=1e-4 * np.nanmedian(np.abs(b)))
        assert close[~np.isnan(b)].mean() > 0.99, name
        assert range_normalised_error(fast[name].per_vertex(), exact[name].per_vertex()) < 1e-3, name


def test_every_path_agrees_on_a_many_chart_atlas(shared_mesh):
    mesh = uvfeat.load(shared_mesh("pizza.obj"))
    assert mesh.n_charts > 1000
    atlas = uvfeat.Atlas(mesh, 1024)
    options = dict(radius="4%", compute_resolution=96, seed=5)
    names = ["mean_curvature", "gaussian_curvature"]
    shared = atlas.compute(names, **options)
    fast = atlas.compute(names, sampling="fast", **options)
    exact = atlas.compute(names, sampling="exact", **options)
    _assert_same_maps(fast, exact, names)
    # Against the object-space reference, the shared lattice errs no more than the exact path.
    reference = uvfeat.reference.compute(mesh, names, "4%")
    for name in names:
        errors = {path: range_normalised_error(maps[name].per_vertex(), reference[name])
                  for path, maps in (("shared", shared), ("exact", exact))}
        assert errors["shared"] <= 1.1 * errors["exact"] + 2e-3, (name, errors)


def test_an_unknown_sampler_is_named():
    with pytest.raises(uvfeat.InvalidParameterError, match="sampling"):
        uvfeat.compute(uvfeat.shapes.plane(1.0, 8), "mean_curvature", radius=0.1, compute_resolution=16,
                       sampling="quick")
