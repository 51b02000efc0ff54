"""The paper's choices (DESIGN.md §1.10, `paper_mode=True`), each also available on its own: per-chart
pattern repetition (§1.6), bilinear buffer lookup, chord-sum geodesics, and the geodesic-disk K."""

import warnings

import numpy as np
import pytest

import uvfeat
from analytic import lat_long_sphere, range_normalised_error, torus_single, torus_xatlas, xatlas_icosphere


@pytest.mark.parametrize("mesh_factory", [lat_long_sphere, xatlas_icosphere], ids=["lat-long", "xatlas"])
@pytest.mark.parametrize("option", [dict(relocation="per_chart"), dict(lookup="bilinear")], ids=["per_chart", "bilinear"])
def test_each_paper_choice_keeps_the_unit_sphere(mesh_factory, option):
    # The pattern's choices: its maps (the many-chart default sums the facets at the vertices).
    values = uvfeat.compute(mesh_factory(), ["mean_curvature", "gaussian_curvature"], radius=0.2,
                            compute_resolution=128, quadrature="pattern", **option)
    # Bilinear lookup reads flat facets blurred over a texel: per-texel values move by ~1e-2.
    assert np.median(np.abs(values["mean_curvature"] - 1)) < 0.01
    assert np.median(np.abs(values["gaussian_curvature"] - 1)) < 0.02
    assert not np.isnan(values["mean_curvature"]).any()


def test_per_chart_repetition_crosses_seams_of_a_many_chart_atlas():
    # One jump deep and one seam per chart: coarser than the per-sample walk (1.4 %) but it must
    # still find the samples beyond the seams of a ~700-chart atlas. Without the repetition pass
    # every texel next to a seam loses the far side of its ball.
    options = dict(radius=0.15, compute_resolution=256, relocation="per_chart")
    multi = uvfeat.compute(torus_xatlas(), "mean_curvature", **options)["mean_curvature"]
    single = uvfeat.compute(torus_single(), "mean_curvature", **options)["mean_curvature"]
    assert range_normalised_error(multi, single) < 0.05


def test_geodesic_disk_k_is_unbiased_on_a_plane():
    # Turned copies of one pattern put the same number of samples inside every circle, so before
    # the per-pixel radial shift every texel of a plane read K = 28 at r = 0.1 (2.3 % of the disk
    # area missing); one group of 8 samples is worth 184 here, so single texels stay coarse.
    maps = uvfeat.Atlas(uvfeat.shapes.plane(1.0, 32), 512).compute(
        ["gaussian_curvature"], radius=0.1, compute_resolution=128, gaussian_method="geodesic_area")
    k = maps["gaussian_curvature"]
    interior = ~k.truncated & (k.n_valid > 0)
    assert interior.sum() > 5000
    assert abs(np.mean(k.texture[interior])) < 3.0


def test_geodesic_disk_k_on_the_sphere_and_the_chord_sum_bias():
    # Away from the poles of a lat-long sphere (where the pole fan makes the sampled areas too
    # coarse for a K that amplifies a 1 % area error 130-fold at r = 0.3): the arc estimate gives
    # K = 1; the chord sum follows parameter lines, longer than geodesics, so its K reads high.
    atlas = uvfeat.Atlas(lat_long_sphere(), 1024)
    r = 0.3
    height = atlas.map_operator(lambda tile: np.abs(tile.centres[:, 2]), r, samples=4, compute_resolution=64)
    band = height < 0.5
    k = {geodesic: atlas.compute(["gaussian_curvature"], r, compute_resolution=64, samples=1024,
                                 gaussian_method="geodesic_area", geodesic=geodesic)["gaussian_curvature"].texture[band]
         for geodesic in ("arc", "chord_sum")}
    assert abs(np.nanmean(k["arc"]) - 1) < 0.15
    assert np.nanmean(k["chord_sum"]) > np.nanmean(k["arc"]) + 0.03


def test_paper_mode_switches_every_choice():
    mesh = torus_xatlas()
    with pytest.warns(UserWarning, match="per-chart repetition"):
        maps = uvfeat.Atlas(mesh, 1024, precision="f16").compute(["mean_curvature"], 0.15, compute_resolution=128,
                                                                 paper_mode=True)
    settings = maps["mean_curvature"].settings
    for name, value in uvfeat.options.PAPER_OPTIONS.items():
        assert settings[name] == value, name
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        per_vertex = uvfeat.compute(mesh, "mean_curvature", radius=0.15, compute_resolution=128,
                                    paper_mode=True)["mean_curvature"]
    assert np.isfinite(per_vertex).all()
    # Said once, by the maps the per-vertex values are read from.
    assert sum("paper_mode" in str(w.message) for w in caught) == 1, [str(w.message) for w in caught]


@pytest.mark.parametrize("name, value", [("relocation", "teleport"), ("lookup", "nearest"), ("geodesic", "heat")])
def test_unknown_paper_choices_are_named(name, value):
    with pytest.raises(uvfeat.InvalidParameterError, match=name):
        uvfeat.compute(uvfeat.shapes.plane(1.0, 8), "mean_curvature", radius=0.1, compute_resolution=16, **{name: value})
