"""A real scan (skips without the shared meshes): the parametric H against the
converged reference of the same surface, with overlaps kept and dropped, at two radii. Pins the
measured agreement so a regression shows."""

import functools
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
        return uvfeat.load(path)  # uvfeat's own atlas: 108 charts


def probe(mesh) -> np.ndarray:
    return np.random.default_rng(0).choice(mesh.n_vertices, 1000, replace=False)


@functools.lru_cache(maxsize=None)
def truth(bunny, radius):
    """H and K of the once-refined reference at the probed vertices (changed by 0.45 / 0.59 % at 3 %,
    0.17 / 0.19 % at 6 % from the mesh's own)."""
    converged = uvfeat.converged_reference(bunny, ["mean_curvature", "gaussian_curvature"], radius, vertices=probe(bunny),
                                           max_levels=1)
    assert converged.converged or max(converged.changes[-1].values()) < 1.0
    return converged


@pytest.mark.parametrize("radius, keep_limits, drop_limits", [
    ("3%", (1.75, 2.4), (1.45, 1.7)),     # measured: keep 1.51 / +2.02, drop 1.25 / -1.44
    # measured: keep 2.16 / +4.57, drop 1.89 / +2.17: the pattern's texture read on a 108-chart
    # atlas, which the surfels below leave behind
    ("6%", (2.5, 5.3), (2.2, 2.6)),
])
def test_bunny_agrees_with_its_converged_reference(bunny, radius, keep_limits, drop_limits):
    atlas = uvfeat.Atlas(bunny)
    measured = {}
    for overlaps, (ae_limit, bias_limit) in (("keep", keep_limits), ("drop", drop_limits)):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", uvfeat.NeighbourhoodWarning)
            H = atlas.compute("mean_curvature", radius, overlaps=overlaps, compute_resolution=256)["mean_curvature"]
        ae, bias = errors(H.per_vertex()[probe(bunny)], truth(bunny, radius)["mean_curvature"])
        assert ae < ae_limit and abs(bias) < bias_limit, (overlaps, ae, bias)
        measured[overlaps] = ae
    assert measured["drop"] < measured["keep"] + 0.05


@pytest.mark.parametrize("radius", ["3%", "6%"])
def test_surfels_agree_with_the_converged_reference(bunny, radius):
    # quadrature="surfels" counts each piece of surface once; the direct query sums the surfels'
    # moments at the vertices. Measured %AE against the once-refined reference: H 0.27 / K 0.41 at
    # 3 %, 0.23 / 0.26 at 6 %; the product's aim is 1 %.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", uvfeat.NeighbourhoodWarning)
        maps = uvfeat.Atlas(bunny).compute(["mean_curvature", "gaussian_curvature"], radius, query="direct",
                                           quadrature="surfels", surface="facets")
    for name in ("mean_curvature", "gaussian_curvature"):
        ae, bias = errors(maps[name].per_vertex()[probe(bunny)], truth(bunny, radius)[name])
        assert ae < 0.5 and abs(bias) < 1.5, (name, ae, bias)
