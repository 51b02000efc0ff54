"""The values at the vertices do not depend on how a file packs its UVs: `uvfeat.compute` sums the
surfels on uvfeat's own atlas, and a vertex whose ball holds no surfel of the atlas it is given
takes the object-space reference's value instead of NaN."""

import functools
import warnings

import numpy as np
import pytest
import trimesh

import uvfeat
from uvfeat import _core
from uvfeat.features import _core_settings
from uvfeat.options import resolve_options, resolve_radius, sums_mesh

HK = ["mean_curvature", "gaussian_curvature"]


@functools.lru_cache(maxsize=None)
def icosphere_and_squeezed():
    """The unit icosphere with uvfeat's atlas, and the same mesh with that atlas's largest chart
    shrunk 30x about its centre, as a file's UVs (900x less UV area than the rest per unit of
    surface), with the squeezed chart's vertices."""
    ico = trimesh.creation.icosphere(subdivisions=5)
    charts = uvfeat.Mesh(ico.vertices, ico.faces, name="icosphere").with_atlas(resolution=1024)
    uvs, uv_faces = np.array(charts.uvs), charts.uv_faces
    face_chart = charts.topology.face_chart
    largest = np.argmax(np.bincount(face_chart[face_chart >= 0]))
    used = np.unique(uv_faces[face_chart == largest])
    centre = uvs[used].mean(axis=0)
    uvs[used] = centre + (uvs[used] - centre) / 30
    squeezed = uvfeat.Mesh(charts.positions, charts.faces, uvs, uv_faces, name="squeezed")
    return charts, squeezed, np.unique(charts.faces[face_chart == largest])


def test_compute_sums_on_uvfeats_atlas_whatever_the_files_uvs():
    charts, squeezed, _ = icosphere_and_squeezed()
    assert squeezed.automatic_atlas is None and charts.automatic_atlas == "charts"
    given = uvfeat.compute(squeezed, HK, "4%")
    own = uvfeat.compute(charts, HK, "4%")
    for name in HK:
        np.testing.assert_array_equal(given[name], own[name])
        # The unit sphere's facets, 3.6 edges across the ball, lie inside it: measured H 1.035-1.044,
        # K 1.074-1.095 (a wrong factor is 100 %).
        low, high = (1.03, 1.05) if name == "mean_curvature" else (1.06, 1.11)
        assert low < given[name].min() and given[name].max() < high, name


def test_a_ball_without_surfels_takes_the_references_value():
    _, squeezed, chart_vertices = icosphere_and_squeezed()
    atlas = uvfeat.Atlas(squeezed, resolution=512)
    options = resolve_options({"quadrature": "surfels"}, paper_mode=False, warn=False)
    radius = resolve_radius("2%", squeezed.bounding_box_diagonal)
    sums, summed, _ = _core.vertex_feature_values(atlas._core, _core_settings(HK, radius, 256, 256, False, 0, options),
                                                  None)
    empty = np.flatnonzero((summed == 0) | np.isnan(sums[1]))
    # The squeezed chart's texels are 30x longer than the rest: hundreds of its balls hold no surfel
    # (or none beyond the inner exclusion, where K reads its moments).
    assert len(empty) > 100 and np.isin(empty, chart_vertices).all()
    values = atlas.per_vertex(HK, "2%")
    reference = uvfeat.reference.compute(squeezed, HK, radius="2%", vertices=empty)
    for name in HK:
        assert not np.isnan(values[name]).any(), name
        np.testing.assert_allclose(values[name][empty], reference[name], rtol=1e-6)


def test_balls_of_a_few_surfels_are_named_and_whole_ones_are_not():
    charts, _, _ = icosphere_and_squeezed()
    atlas = uvfeat.Atlas(charts, resolution=256)
    # About 1.4 texels of 256² across: a ball holds a handful of surfels.
    texel = np.sqrt(charts.surface_area / charts.uv_area) / 256
    with pytest.warns(uvfeat.NeighbourhoodWarning, match="summed fewer than 8 surfels: the radius spans about a "
                                                        "texel of the 256² grid"):
        atlas.per_vertex(HK, 1.4 * texel, quadrature="surfels")
    with warnings.catch_warnings():
        warnings.simplefilter("error", uvfeat.NeighbourhoodWarning)
        atlas.per_vertex(HK, 20 * texel, quadrature="surfels")


def test_the_sums_mesh_is_kept_per_mesh_and_an_automatic_atlas_is_its_own():
    charts, squeezed, _ = icosphere_and_squeezed()
    first = sums_mesh(squeezed, HK, {}, paper_mode=False)
    assert first.automatic_atlas == "charts" and sums_mesh(squeezed, HK, {}, paper_mode=False) is first
    assert sums_mesh(charts, HK, {}, paper_mode=False) is charts
    assert charts.with_positions(charts.positions * 2).automatic_atlas == "charts"
    # A named quadrature keeps the mesh's own UVs.
    assert sums_mesh(squeezed, HK, {"quadrature": "surfels"}, paper_mode=False) is squeezed



def test_a_planar_points_shape_index_is_not_a_failed_ball(monkeypatch):
    # The shape index is NaN where the surface is flat, by design: a cube's faces keep their
    # surfels, so the reference must not stand in for them.
    box = trimesh.creation.box(extents=(1, 1, 1)).subdivide().subdivide().subdivide().subdivide()
    cube = uvfeat.Mesh(box.vertices, box.faces, name="cube").with_atlas(resolution=1024)
    assert cube.n_charts > 1

    def refuse(*args, **kwargs):
        raise AssertionError("the reference stood in for balls that held surfels")

    monkeypatch.setattr(uvfeat.reference.Reference, "compute", refuse)
    values = uvfeat.compute(cube, ["shape_index", "mean_curvature"], "5%")
    flat = np.isnan(values["shape_index"])
    assert 0.2 < flat.mean() < 0.8  # the faces' middles; the edges and corners bend
    assert np.isfinite(values["mean_curvature"]).all() and np.max(np.abs(values["mean_curvature"][flat])) < 1e-3
