"""Feature estimators against analytic truth (DESIGN.md §5.9) on several parameterisations, their
invariances, and the public API's contract."""

import os
import subprocess
import sys

import numpy as np
import pytest

import uvfeat
from analytic import (charts_icosphere, lat_long_sphere, range_normalised_error, torus_charts, torus_single,
                      torus_truth, torus_xatlas, xatlas_icosphere)

ACCEPTANCE = ["mean_curvature", "gaussian_curvature", "bending_energy", "shape_index", "k1", "k2", "curvedness"]


@pytest.mark.parametrize("mesh_factory", [lat_long_sphere, xatlas_icosphere, charts_icosphere],
                         ids=["lat-long", "xatlas", "charts"])
def test_unit_sphere_acceptance(mesh_factory):
    mesh = mesh_factory()
    # The acceptance setting, N = 256 (on the icospheres' many charts: surfels per ball of their facets).
    values = uvfeat.compute(mesh, ACCEPTANCE, radius=0.2, compute_resolution=256, samples=256)
    assert np.median(np.abs(values["mean_curvature"] - 1)) < 0.03
    assert np.median(np.abs(values["gaussian_curvature"] - 1)) < 0.05
    assert abs(np.median(values["bending_energy"]) - 1) < 0.03
    assert np.median(values["shape_index"]) > 0.95
    assert abs(np.median(values["curvedness"]) - 1) < 0.03
    assert np.all(values["k1"][np.isfinite(values["k1"])] >= values["k2"][np.isfinite(values["k1"])])


def test_volumes_of_the_unit_sphere_are_exact_to_monte_carlo_noise():
    r = 0.2
    maps = uvfeat.Atlas(xatlas_icosphere(), 1024).compute(["open_volume", "volume_invariant"], r, compute_resolution=128)
    v_r = 2 * np.pi * r**3 / 3 - np.pi * r**4 / 4
    assert abs(np.nanmedian(maps["volume_invariant"].texture) / v_r - 1) < 0.01
    assert abs(np.nanmedian(maps["open_volume"].texture) / (4 * np.pi * r**3 / 3 - v_r) - 1) < 0.01


@pytest.mark.parametrize("mesh", [uvfeat.shapes.plane(1.0, 32), uvfeat.shapes.split_plane(32, mirrored=True)],
                         ids=["affine", "two charts, mirrored"])
def test_plane_has_no_curvature(mesh):
    maps = uvfeat.Atlas(mesh, 512).compute(["mean_curvature", "gaussian_curvature"], radius=0.1, compute_resolution=128)
    interior = ~maps["mean_curvature"].truncated & (maps["mean_curvature"].n_valid > 0)
    assert maps["mean_curvature"].truncated.any(), "neighbourhoods cut by the border must be flagged"
    for name in ("mean_curvature", "gaussian_curvature"):
        assert np.max(np.abs(maps[name].texture[interior])) < 1e-3, name


@pytest.mark.parametrize("mesh_factory", [torus_single, torus_xatlas, torus_charts], ids=["single chart", "xatlas", "charts"])
def test_torus_outer_and_inner_equator(mesh_factory):
    atlas = uvfeat.Atlas(mesh_factory(), 1024)
    maps = atlas.compute(["mean_curvature", "gaussian_curvature"], radius=0.15, compute_resolution=256)

    def tube_cosine(tile):  # cos v of each texel's centre p, from the neighbourhood tiles
        return (np.hypot(tile.centres[:, 0], tile.centres[:, 1]) - 2.0) / 0.5

    cos_v = atlas.map_operator(tube_cosine, 0.15, samples=4, compute_resolution=256)
    for name, where, cos in (("outer", cos_v > 0.995, 1.0), ("inner", cos_v < -0.995, -1.0)):
        h_true = (2.0 + 2 * 0.5 * cos) / (2 * 0.5 * (2.0 + 0.5 * cos))
        k_true = cos / (0.5 * (2.0 + 0.5 * cos))
        h = np.nanmedian(maps["mean_curvature"].texture[where])
        k = np.nanmedian(maps["gaussian_curvature"].texture[where])
        assert abs(h / h_true - 1) < 0.05, (name, h)
        assert abs(k / k_true - 1) < 0.05, (name, k)


@pytest.mark.parametrize("mesh_factory", [torus_xatlas, torus_charts], ids=["xatlas", "charts"])
def test_single_and_multi_chart_atlases_agree(mesh_factory):
    # Evaluated at the vertices with enough samples that Monte Carlo noise (about 3 % of the range
    # per vertex at N = 256 on this torus) does not hide what is compared: the atlases.
    options = dict(radius=0.15, samples=2048, compute_resolution=64, query="direct")
    single = uvfeat.compute(torus_single(), "mean_curvature", **options)["mean_curvature"]
    multi = uvfeat.compute(mesh_factory(), "mean_curvature", **options)["mean_curvature"]
    assert range_normalised_error(multi, single) < 0.02


def test_neighbourhoods_cover_the_ball_on_a_many_chart_atlas():
    # The sampled area of every neighbourhood must be the geodesic disk's, pi r^2 (1 - K r^2 / 12),
    # also where the xatlas atlas has UV slivers (stretch ratios over 100) and seams: an ellipse or
    # a seam map built from a sliver's metric lost up to 66 % of the area.
    r = 0.15
    atlas = uvfeat.Atlas(torus_xatlas(), 1024)

    def relative_area_error(tile):
        ring = np.hypot(tile.centres[:, 0], tile.centres[:, 1]) - 2.0
        k = np.clip(ring / 0.5, -1, 1) / (0.5 * (2.0 + np.clip(ring, -0.5, 0.5)))
        area = np.where(tile.valid, tile.areas, 0).sum(axis=1)
        return area / (np.pi * r * r * (1 - k * r * r / 12)) - 1

    error = atlas.map_operator(relative_area_error, r, samples=1024, compute_resolution=96)
    error = error[np.isfinite(error)]
    assert abs(np.median(error)) < 0.005
    assert np.percentile(error, 0.5) > -0.15 and np.percentile(error, 99.5) < 0.10, np.percentile(error, [0.5, 99.5])


def test_flipping_the_faces_flips_h_k1_k2_and_shape_index_but_not_k():
    mesh = xatlas_icosphere()
    flipped = uvfeat.Mesh(mesh.positions, mesh.faces[:, ::-1], mesh.uvs, mesh.uv_faces[:, ::-1])
    names = ["mean_curvature", "gaussian_curvature", "k1", "k2", "shape_index"]
    # On the mesh's own atlas for both (by default the flipped copy, a mesh of its own, would be
    # summed on uvfeat's unwrap of it, another atlas).
    a = uvfeat.compute(mesh, names, radius=0.2, compute_resolution=256, quadrature="surfels")
    b = uvfeat.compute(flipped, names, radius=0.2, compute_resolution=256, quadrature="surfels")
    np.testing.assert_allclose(b["mean_curvature"], -a["mean_curvature"], atol=1e-4)
    np.testing.assert_allclose(b["gaussian_curvature"], a["gaussian_curvature"], atol=1e-4)
    np.testing.assert_allclose(b["k1"], -a["k2"], atol=1e-4)
    np.testing.assert_allclose(b["shape_index"], -a["shape_index"], atol=1e-4)


def test_rigid_motion_changes_nothing_and_scaling_scales_h():
    mesh = torus_xatlas()
    angle = 0.7
    rotation = np.array([[np.cos(angle), -np.sin(angle), 0], [np.sin(angle), np.cos(angle), 0], [0, 0, 1]])
    rotation = rotation @ np.array([[1, 0, 0], [0, 0, -1], [0, 1, 0]])
    moved = uvfeat.Mesh(mesh.positions @ rotation.T + [3.0, -1.0, 7.0], mesh.faces, mesh.uvs, mesh.uv_faces)
    scaled = uvfeat.Mesh(mesh.positions * 3.0, mesh.faces, mesh.uvs, mesh.uv_faces)
    # The same atlas moved (by default the moved copies would be summed on uvfeat's unwrap of them,
    # whose charts follow the motion only approximately).
    hk = ["mean_curvature", "gaussian_curvature"]
    base = uvfeat.compute(mesh, hk, radius=0.15, compute_resolution=256, quadrature="surfels")
    after = uvfeat.compute(moved, hk, radius=0.15, compute_resolution=256, quadrature="surfels")
    big = uvfeat.compute(scaled, hk, radius=0.45, compute_resolution=256, quadrature="surfels")
    for name in base:
        assert range_normalised_error(after[name], base[name]) < 1e-3, name
    assert range_normalised_error(big["mean_curvature"] * 3.0, base["mean_curvature"]) < 1e-3
    assert range_normalised_error(big["gaussian_curvature"] * 9.0, base["gaussian_curvature"]) < 1e-3


def test_same_seed_gives_identical_results_with_one_and_two_threads(tmp_path):
    script = (
        "import sys, numpy as np, uvfeat\n"
        "m = uvfeat.shapes.torus(2.0, 0.5, 64, 32)\n"
        "maps = uvfeat.Atlas(m, 512).compute('all', 0.3, compute_resolution=96, seed=5)\n"
        "np.save(sys.argv[1], np.stack([f.texture for f in maps.values()]))\n"
    )
    outputs = []
    for threads in ("1", "2"):
        path = tmp_path / f"t{threads}.npy"
        env = dict(os.environ, RAYON_NUM_THREADS=threads)
        subprocess.run([sys.executable, "-c", script, str(path)], env=env, check=True)
        outputs.append(np.load(path))
    np.testing.assert_array_equal(outputs[0], outputs[1])
    seed6 = uvfeat.Atlas(uvfeat.shapes.torus(2.0, 0.5, 64, 32), 512).compute("mean_curvature", 0.3,
                                                                             compute_resolution=96, seed=6)
    assert not np.array_equal(np.nan_to_num(seed6["mean_curvature"].texture), np.nan_to_num(outputs[0][3]))


def test_scale_stack_and_per_vertex_shapes():
    mesh = uvfeat.shapes.torus(2.0, 0.5, 64, 32)
    maps = uvfeat.Atlas(mesh, 256).compute(["mean_curvature", "curvedness"], ["1%", "4%", 0.5], compute_resolution=64)
    h = maps["mean_curvature"]
    assert h.texture.shape == (3, 64, 64) and h.n_valid.shape == (3, 64, 64)
    assert h.per_vertex().shape == (3, mesh.n_vertices)
    np.testing.assert_allclose(h.radius[:2], np.array([0.01, 0.04]) * mesh.bounding_box_diagonal)
    direct = h.per_vertex(query="direct")
    assert np.isfinite(direct).all()


def test_user_defined_operator_reproduces_the_built_in_mean_curvature():
    atlas = uvfeat.Atlas(uvfeat.shapes.torus(2.0, 0.5, 128, 64), 512)
    r = 0.2

    def mean_curvature(tile):
        offset = tile.positions - tile.centres[:, None, :]
        rho = np.linalg.norm(offset, axis=-1)
        safe = np.where(tile.valid, rho, 1.0)
        sin_alpha = np.einsum("tnk,tk->tn", offset, tile.normals) / safe
        w = tile.areas * np.where(tile.valid, rho, 0.0)
        # -(8/(3r)) <sin(alpha)>_w with the pattern's own radial moment in place of 3r/4.
        return -2.0 * (w * sin_alpha).sum(axis=1) / (w * rho).sum(axis=1)

    mine = atlas.map_operator(mean_curvature, r, compute_resolution=64, tile_texels=1000)
    # The operator sums the per-texel patterns (the fast path's samples), not the shared lattice.
    builtin = atlas.compute("mean_curvature", r, compute_resolution=64, sampling="fast")["mean_curvature"].texture
    np.testing.assert_allclose(mine, builtin, rtol=1e-4, atol=1e-5)
    tile = next(atlas.neighbourhoods(r, samples=64, compute_resolution=32, tile_texels=100))
    assert tile.positions.shape == (len(tile.texels), 64, 3) and tile.valid.any()


def test_adaptive_sampling_reports_the_second_stage_fraction():
    atlas = uvfeat.Atlas(uvfeat.shapes.torus(2.0, 0.5, 64, 32), 256)
    always = atlas.compute("mean_curvature", 0.3, compute_resolution=48, adaptive=True, tau=0.0)["mean_curvature"]
    never = atlas.compute("mean_curvature", 0.3, compute_resolution=48, adaptive=True, tau=1e9)["mean_curvature"]
    default = atlas.compute("mean_curvature", 0.3, compute_resolution=48, adaptive=True)["mean_curvature"]
    assert always.summary["second_stage_fraction"] == 1.0
    assert never.summary["second_stage_fraction"] == 0.0
    assert 0.0 <= default.summary["second_stage_fraction"] <= 1.0
    assert np.nanmedian(never.n_valid) < np.nanmedian(always.n_valid)


def test_standard_errors_match_the_spread_over_seeds():
    atlas = uvfeat.Atlas(uvfeat.shapes.torus(2.0, 0.5, 128, 64), 512)
    runs = [atlas.compute("mean_curvature", 0.2, compute_resolution=48, seed=s, standard_error=True)["mean_curvature"]
            for s in range(6)]
    spread = np.nanmedian(np.std([r.texture for r in runs], axis=0, ddof=1))
    predicted = np.nanmedian(runs[0].standard_error)
    assert 0.4 < predicted / spread < 2.5, (predicted, spread)


@pytest.mark.parametrize("kwargs, match", [
    (dict(radius=0), "positive"),
    (dict(radius=-1), "positive"),
    (dict(radius=float("nan")), "positive"),
    (dict(radius="abc"), "percentage"),
    (dict(radius=100.0), "larger than the mesh"),
    (dict(radius=0.1, samples=3), "samples"),
    (dict(radius=0.1, compute_resolution=0), "compute_resolution"),
    (dict(radius=0.1, margin=0.5), "margin"),
    (dict(radius=0.1, bogus=1), "unknown option"),
    (dict(radius=0.1, criterion="manhattan"), "criterion"),
])
def test_bad_parameters_raise_clear_errors(kwargs, match):
    atlas = uvfeat.Atlas(uvfeat.shapes.plane(1.0, 4), 64)
    with pytest.raises(uvfeat.InvalidParameterError, match=match):
        atlas.compute("mean_curvature", **kwargs)


def test_unknown_feature_lists_the_valid_ones():
    atlas = uvfeat.Atlas(uvfeat.shapes.plane(1.0, 4), 64)
    with pytest.raises(uvfeat.InvalidParameterError, match="valid: bending_energy.*shape_index"):
        atlas.compute("mean_curvture", 0.1)


def test_the_neighbourhood_maps_are_shared_read_only_by_the_features_of_one_computation():
    s = uvfeat.shapes.uv_sphere(1.0, 48, 24)
    atlas = uvfeat.Atlas(uvfeat.Mesh(s.positions, s.faces, uvs=s.uvs, uv_faces=s.uv_faces), 128)
    maps = atlas.compute(["mean_curvature", "gaussian_curvature"], 0.3, compute_resolution=64, samples=32)
    h, k = maps["mean_curvature"], maps["gaussian_curvature"]
    for name in ("n_valid", "n_missing", "n_border", "area_ratio", "sheet_area"):
        assert getattr(h, name) is getattr(k, name)
        with pytest.raises(ValueError):
            getattr(h, name)[0, 0] = 0
    assert h.texture is not k.texture and h.texture.flags.writeable
