"""Surface reached along two routes through seams (overlaps="drop"): across seams the domain is
developed by hinge maps and overlaps itself around convex regions, so part of the surface is
sampled twice. On a sphere the surface within distance r of a point has area pi r^2 exactly
(Archimedes), which shows the double count and its removal."""

import numpy as np
import pytest

import uvfeat
from analytic import charts_sphere_atlas, neighbourhood_areas


@pytest.fixture(scope="module")
def sphere_atlas():
    return charts_sphere_atlas()


def test_overlapping_routes_count_twice_unless_dropped(sphere_atlas):
    kept = neighbourhood_areas(sphere_atlas, 0.6)
    dropped = neighbourhood_areas(sphere_atlas, 0.6, overlaps="drop")
    assert np.median(kept) > 1.02, "the developed domain overlaps itself across seams"
    assert abs(np.median(dropped) - 1.0) < 0.01
    assert np.percentile(dropped, 90) < np.percentile(kept, 90) - 0.02
    # samples are only ever removed
    assert np.all(dropped <= kept + 1e-9)


def test_fast_and_exact_paths_drop_the_same_samples(sphere_atlas):
    fast = sphere_atlas.compute(["mean_curvature", "open_volume"], 0.6, compute_resolution=48, overlaps="drop")
    exact = sphere_atlas.compute(["mean_curvature", "open_volume"], 0.6, compute_resolution=48, overlaps="drop",
                                 sampling="exact")
    for name in ("mean_curvature", "open_volume"):
        a, b = fast[name].texture, exact[name].texture
        both = np.isfinite(a) & np.isfinite(b)
        assert both.mean() > 0.5
        assert np.max(np.abs(a[both] - b[both])) < 1e-3 * np.max(np.abs(b[both]))
    assert np.array_equal(fast["mean_curvature"].n_valid, exact["mean_curvature"].n_valid)


def test_the_option_is_named_and_checked(sphere_atlas):
    assert uvfeat.options.DEFAULT_OPTIONS["overlaps"] == "keep"
    assert uvfeat.options.CHOICES["overlaps"] == ["keep", "drop"]
    with pytest.raises(uvfeat.InvalidParameterError, match="overlaps"):
        sphere_atlas.compute("mean_curvature", 0.3, overlaps="merge")
