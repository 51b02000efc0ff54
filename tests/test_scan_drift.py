"""A real scan (skips without the shared meshes): the parametric H against the
converged reference of the same surface, with overlaps kept and dropped, at two radii. Pins the
measured agreement (docs/EXPERIMENTS.md) so a regression shows."""

import warnings

import numpy as np
import pytest

import uvfeat
from conftest import shared_meshes_dir


def errors(values, truth):
    spread = np.nanpercentile(truth, 99) - np.nanpercentile(truth, 1)
    return 100 * np.nanmean(np.abs(values - truth)) / spread, 100 * np.nanmean(values - truth) / np.nanmean(np.abs(truth))


@pytest.fixture(scope="module")
def bunny():
    folder = shared_meshes_dir()
    if folder is None or not (folder / "stanford-bunny.obj").exists():
        pytest.skip("shared mesh stanford-bunny.obj not available")
    path = str(folder / "stanford-bunny.obj")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return uvfeat.load(path, uv="xatlas")


@pytest.mark.parametrize("radius, keep_limits, drop_limits", [
    ("3%", (1.1, 1.0), (1.0, 1.2)),     # measured: keep 0.84 / +0.26, drop 0.77 / -0.87
    # measured: keep 1.94 / +4.10, drop 1.45 / +1.03 (keep was 1.89 / +3.74 before the coverage
    # check stopped rays that come back round a thin part: a ratio estimator does not mind surface
    # counted uniformly often, but a stop at half the loop counts part of it once less; requiring
    # the loop to close behind the centre gave +4.02 and lost the speed-up)
    ("6%", (2.4, 4.5), (1.9, 1.2)),
])
def test_bunny_agrees_with_its_converged_reference(bunny, radius, keep_limits, drop_limits):
    probe = np.random.default_rng(0).choice(bunny.n_vertices, 1000, replace=False)
    truth = uvfeat.converged_reference(bunny, "mean_curvature", radius, vertices=probe, max_levels=1)
    assert truth.converged or truth.changes[-1]["mean_curvature"] < 1.0
    atlas = uvfeat.Atlas(bunny)
    measured = {}
    for overlaps, (ae_limit, bias_limit) in (("keep", keep_limits), ("drop", drop_limits)):
        H = atlas.compute("mean_curvature", radius, query="direct", overlaps=overlaps)["mean_curvature"]
        ae, bias = errors(H.per_vertex()[probe], truth["mean_curvature"])
        assert ae < ae_limit and abs(bias) < bias_limit, (overlaps, ae, bias)
        measured[overlaps] = ae
    assert measured["drop"] < measured["keep"] + 0.05


@pytest.mark.parametrize("radius", ["3%", "6%"])
def test_surfels_agree_with_the_converged_reference(bunny, radius):
    # quadrature="surfels" counts each piece of surface once; the direct query sums the surfels'
    # moments at the vertices. Measured %AE against the once-refined reference: H 0.27 / K 0.40 at
    # 3 %, 0.23 / 0.25 at 6 % (the pattern: 0.84 and 1.94 for H); the product's aim is 1 %.
    probe = np.random.default_rng(0).choice(bunny.n_vertices, 1000, replace=False)
    truth = uvfeat.converged_reference(bunny, ["mean_curvature", "gaussian_curvature"], radius, vertices=probe,
                                       max_levels=1)
    maps = uvfeat.Atlas(bunny).compute(["mean_curvature", "gaussian_curvature"], radius, query="direct",
                                       quadrature="surfels", surface="facets")
    for name in ("mean_curvature", "gaussian_curvature"):
        ae, bias = errors(maps[name].per_vertex()[probe], truth[name])
        assert ae < 0.5 and abs(bias) < 1.5, (name, ae, bias)
