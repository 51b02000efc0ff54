"""Real meshes from ../shared/meshes (skipped when absent). Licences: see that folder's README."""

import warnings

import numpy as np
import pytest

import uvfeat

UV_MESHES = {"spot_triangulated.obj": 13, "bob_tri.obj": 3, "blub.obj": 5, "pizza.obj": 4740, "Fox.glb": 14}


@pytest.mark.shared
@pytest.mark.parametrize("name, charts", UV_MESHES.items())
def test_uv_mapped_meshes_rasterise(shared_mesh, name, charts):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", uvfeat.UVWarning)
        mesh = uvfeat.load(shared_mesh(name), uv="require")
    assert mesh.n_charts == charts
    atlas = uvfeat.Atlas(mesh, 1024)
    d = atlas.diagnostics
    assert d["overlapping_texels"] == 0 and d["non_manifold_edges"] == 0
    assert d["covered_texels"] > 0.15 * 1024**2
    # Every seam texel has a chart across; mesh-border texels only where the mesh has a border.
    seam_texels = atlas.border & (atlas.adjacent_chart >= 0)
    assert seam_texels.sum() > 0
    if d["border_edges"] == 0:
        assert not (atlas.border & (atlas.adjacent_chart < 0)).any()


@pytest.mark.shared
@pytest.mark.parametrize("name", ["stanford-bunny.obj", "armadillo.obj", "dragon.obj"])
def test_scans_without_uvs_get_an_automatic_atlas(shared_mesh, name):
    mesh = uvfeat.load(shared_mesh(name))
    assert mesh.n_charts > 100
    atlas = uvfeat.Atlas(mesh, 1024)
    assert atlas.diagnostics["covered_texels"] > 0.3 * 1024**2
    assert atlas.diagnostics["overlapping_texels"] == 0
    assert atlas.diagnostics["charts_without_texels"] <= 0.01 * mesh.n_charts
    assert np.isfinite(atlas.position[atlas.chart >= 0]).all()


@pytest.mark.shared
@pytest.mark.parametrize("name", ["spot_triangulated.obj", "bob_tri.obj", "blub.obj", "pizza.obj"])
def test_features_on_real_meshes_at_three_radii(shared_mesh, name):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", uvfeat.UVWarning)
        mesh = uvfeat.load(shared_mesh(name), uv="require")
    atlas = uvfeat.Atlas(mesh, 1024)
    for radius in ("1%", "4%", "16%"):
        maps = atlas.compute(["mean_curvature", "gaussian_curvature", "shape_index"], radius, compute_resolution=256)
        h = maps["mean_curvature"]
        assert h.summary["texels"] > 1000
        values = h.per_vertex()
        assert values.shape == (mesh.n_vertices,) and np.isfinite(values).mean() > 0.99
        if radius == "4%":
            # Pizza's 4,740 charts (1,987 single triangles, many smaller than a texel) still lose
            # samples where no border texel of a tiny chart survives rasterisation: measured 7.9 %
            # with the default 8 jumps (24 % with 3); guarded here until the exact triangle walk lands.
            limit = 0.01 if name != "pizza.obj" else 0.1
            assert h.summary["missing_fraction"] < limit, h.summary
