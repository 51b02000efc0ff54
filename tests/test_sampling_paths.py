"""The sampler's fast path (default) against its reference, the exact path (`sampling="exact"`),
with the same seeds, on the single-chart torus, on an xatlas atlas and, where the shared meshes
are present, on Pizza (4,740 charts: most samples cross seams there)."""

import numpy as np
import pytest

import uvfeat
from analytic import range_normalised_error, torus_single, torus_truth, torus_xatlas

FEATURES = ["mean_curvature", "gaussian_curvature", "bending_energy"]


@pytest.mark.parametrize("mesh_factory", [torus_single, torus_xatlas], ids=["single-chart", "xatlas"])
def test_fast_and_exact_paths_give_the_same_features(mesh_factory):
    mesh = mesh_factory()
    atlas = uvfeat.Atlas(mesh, 1024)
    options = dict(radius=0.15, compute_resolution=128, seed=3)
    fast = atlas.compute(FEATURES, **options)
    exact = atlas.compute(FEATURES, sampling="exact", **options)
    # f32 rounding can move a sample lying on the sphere |q - p| = r in or out of the ball.
    _assert_same_maps(fast, exact, FEATURES)
    # And both are right: H of the torus, per vertex.
    truth_h, _, _ = torus_truth(mesh)
    assert range_normalised_error(fast["mean_curvature"].per_vertex(), truth_h) < 0.03


def _assert_same_maps(fast, exact, names):
    for name in names:
        a, b = fast[name].texture, exact[name].texture
        assert np.array_equal(np.isnan(a), np.isnan(b)), name
        close = np.isclose(a, b, rtol=1e-4, atol=1e-4 * np.nanmedian(np.abs(b)))
        assert close[~np.isnan(b)].mean() > 0.99, name
        assert range_normalised_error(fast[name].per_vertex(), exact[name].per_vertex()) < 1e-3, name


def test_fast_and_exact_paths_agree_on_a_many_chart_atlas(shared_mesh):
    mesh = uvfeat.load(shared_mesh("pizza.obj"))
    assert mesh.n_charts > 1000
    atlas = uvfeat.Atlas(mesh, 1024)
    options = dict(radius="4%", compute_resolution=96, seed=5)
    names = ["mean_curvature", "gaussian_curvature"]
    fast = atlas.compute(names, **options)
    exact = atlas.compute(names, sampling="exact", **options)
    _assert_same_maps(fast, exact, names)


def test_an_unknown_sampler_is_named():
    with pytest.raises(uvfeat.InvalidParameterError, match="sampling"):
        uvfeat.compute(uvfeat.shapes.plane(1.0, 8), "mean_curvature", radius=0.1, compute_resolution=16,
                       sampling="quick")
