import numpy as np
import pytest

import uvfeat
from uvfeat import InvalidParameterError, ResolutionTooLargeError


@pytest.fixture(scope="module")
def torus_atlas():
    return uvfeat.Atlas(uvfeat.shapes.torus(2.0, 0.5, 64, 32), resolution=256)


def test_buffers_have_the_documented_shapes_dtypes_and_are_read_only(torus_atlas):
    r = 256
    a = torus_atlas
    expected = {"position": ((r, r, 3), np.float32), "normal": ((r, r, 3), np.float32), "sigma": ((r, r, 2), np.float32),
                "theta": ((r, r), np.float32), "chart": ((r, r), np.int32), "border": ((r, r), np.bool_),
                "adjacent_chart": ((r, r), np.int32), "face": ((r, r), np.int32)}
    for name, (shape, dtype) in expected.items():
        array = getattr(a, name)
        assert array.shape == shape and array.dtype == dtype, name
        assert not array.flags.writeable, name
    empty = a.chart < 0
    assert np.isnan(a.position[empty]).all() and np.isfinite(a.position[~empty]).all()
    assert a.n_charts == 1
    assert np.allclose(np.linalg.norm(a.normal[~empty], axis=-1), 1.0, atol=1e-5)


def test_positions_match_the_barycentric_interpolation_at_texel_centres(torus_atlas):
    a, mesh = torus_atlas, torus_atlas.mesh
    r = a.resolution
    j, i = np.nonzero(a.face >= 0)
    centres = np.stack([(i + 0.5) / r, (j + 0.5) / r], axis=1)
    faces = a.face[j, i]
    uv = mesh.uvs[mesh.uv_faces[faces]]  # (n, 3, 2)
    e1, e2, d = uv[:, 1] - uv[:, 0], uv[:, 2] - uv[:, 0], centres - uv[:, 0]
    area = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    b1 = (d[:, 0] * e2[:, 1] - d[:, 1] * e2[:, 0]) / area
    b2 = (e1[:, 0] * d[:, 1] - e1[:, 1] * d[:, 0]) / area
    inside = (b1 >= 0) & (b2 >= 0) & (b1 + b2 <= 1)
    corners = mesh.positions[mesh.faces[faces]]
    exact = corners[:, 0] * (1 - b1 - b2)[:, None] + corners[:, 1] * b1[:, None] + corners[:, 2] * b2[:, None]
    err = np.abs(a.position[j, i] - exact)[inside].max()
    assert inside.sum() > 40_000 and err < 1e-5


def test_sigma_of_a_lat_long_sphere_follows_the_analytic_metric():
    radius = 2.0
    atlas = uvfeat.Atlas(uvfeat.shapes.uv_sphere(radius, 256, 128), 512)
    scale = 0.96  # chart spans [0.02, 0.98]
    j, i = np.nonzero((atlas.chart >= 0) & ~atlas.border)
    lat = np.pi * (((j + 0.5) / 512 - 0.02) / scale - 0.5)
    area = atlas.sigma[j, i, 0] * atlas.sigma[j, i, 1]
    analytic = (2 * np.pi * radius * np.cos(lat) / scale) * (np.pi * radius / scale)
    # Per texel the face's constant metric is that of a point up to half a triangle row away
    # (first order in the row height); the second-order 1e-3 check per face is in the Rust tests.
    rel = np.abs(area - analytic) / analytic
    assert np.median(rel[np.abs(lat) < 1.2]) < 1e-2


def test_f16_precision_rounds_positions_to_half_floats():
    mesh = uvfeat.shapes.torus(2.0, 0.5, 32, 16)
    half = uvfeat.Atlas(mesh, 128, precision="f16")
    full = uvfeat.Atlas(mesh, 128)
    assert half.position.dtype == np.float16
    covered = full.chart >= 0
    diff = np.abs(half.position[covered].astype(np.float64) - full.position[covered])
    assert 0 < diff.max() < 2.5 * 2.0**-10  # |x| <= 2.5: half-float spacing 2^-9 there, rounding <= half


def test_update_recomputes_the_buffers_and_keeps_the_coverage(torus_atlas):
    mesh = uvfeat.shapes.torus(2.0, 0.5, 64, 32)
    atlas = uvfeat.Atlas(mesh, 256)
    chart_before = atlas.chart.copy()
    np.testing.assert_allclose(atlas.position, torus_atlas.position)  # buffers read before the update
    atlas.update(mesh.positions * 2.0 + [1.0, 0, 0])
    covered = chart_before >= 0
    np.testing.assert_allclose(atlas.position[covered], torus_atlas.position[covered] * 2 + [1, 0, 0], atol=1e-5)
    np.testing.assert_allclose(atlas.sigma[covered], torus_atlas.sigma[covered] * 2, rtol=1e-5)
    np.testing.assert_array_equal(atlas.chart, chart_before)
    assert "update_s" in atlas.timings
    with pytest.raises(uvfeat.InvalidMeshError, match="vertices"):
        atlas.update(mesh.positions[:-1])
    with pytest.raises(uvfeat.InvalidMeshError, match="non-finite"):
        atlas.update(np.full_like(mesh.positions, np.nan))


def test_coverage_on_first_use_gives_the_same_values_views_and_maps_and_follows_updates():
    mesh = uvfeat.shapes.torus(2.0, 0.5, 48, 24).with_atlas()
    eager, deferred = (uvfeat.Atlas(mesh, 128, coverage_on_first_use=later) for later in (False, True))
    hk = ["mean_curvature", "gaussian_curvature"]
    for feature, values in deferred.per_vertex(hk, "10%").items():
        np.testing.assert_array_equal(values, eager.per_vertex(hk, "10%")[feature])
    np.testing.assert_array_equal(deferred.chart, eager.chart)
    np.testing.assert_array_equal(deferred.face, eager.face)
    np.testing.assert_array_equal(deferred.position, eager.position)
    maps = deferred.compute("mean_curvature", "10%", compute_resolution=64, seed=1)["mean_curvature"]
    np.testing.assert_array_equal(maps.texture, eager.compute("mean_curvature", "10%", compute_resolution=64,
                                                              seed=1)["mean_curvature"].texture)
    # A first use from the parallel maps: the coverage is built before their loops start.
    fresh = uvfeat.Atlas(mesh, 128, coverage_on_first_use=True)
    surfel_maps = {atlas: atlas.compute("mean_curvature", "10%", compute_resolution=64, quadrature="surfels",
                                        lookup="bilinear")["mean_curvature"].texture for atlas in (fresh, eager)}
    np.testing.assert_array_equal(surfel_maps[fresh], surfel_maps[eager])
    # The faces' patches and seam maps follow new positions, built (deferred, eager) or not yet
    # (a fresh deferred atlas moved before any map).
    moved = mesh.positions * np.array([1.2, 1.0, 0.8])
    later = uvfeat.Atlas(mesh, 128, coverage_on_first_use=True)
    moved_maps = []
    for atlas in (deferred, eager, later):
        atlas.update(moved)
        moved_maps.append(atlas.compute("mean_curvature", "10%", compute_resolution=64, seed=1)["mean_curvature"].texture)
    np.testing.assert_array_equal(moved_maps[0], moved_maps[1])
    np.testing.assert_array_equal(moved_maps[2], moved_maps[1])
    assert not np.array_equal(moved_maps[1], maps.texture)


def test_a_mesh_too_large_for_the_memory_budget_is_refused_before_anything_is_built(monkeypatch):
    mesh = uvfeat.shapes.torus(2.0, 0.5, 320, 160)  # 102,400 faces: about 31 MiB of per-face tables
    monkeypatch.setattr(uvfeat.atlas, "memory_budget", lambda: 20 << 20)
    with pytest.raises(ResolutionTooLargeError, match=r"102,400 faces at resolution 64 need about \d+ MiB.*fewer faces"):
        uvfeat.Atlas(mesh, 64)
    assert "topology" not in mesh.__dict__  # refused before the topology was built
    monkeypatch.setattr(uvfeat.atlas, "memory_budget", lambda: 200 << 20)
    assert uvfeat.Atlas(mesh, 64).resolution == 64


@pytest.mark.parametrize("resolution", [0, -5, 1.5, "big", True])
def test_bad_resolutions_are_rejected(resolution):
    with pytest.raises(InvalidParameterError, match="positive integer"):
        uvfeat.Atlas(uvfeat.shapes.plane(), resolution)


def test_too_large_resolution_says_how_much_memory_it_needs():
    with pytest.raises(ResolutionTooLargeError, match=r"need about \d+ MiB"):
        uvfeat.Atlas(uvfeat.shapes.plane(), 30000)
    with pytest.raises(InvalidParameterError, match="precision"):
        uvfeat.Atlas(uvfeat.shapes.plane(), 64, precision="f64")


@pytest.mark.parametrize("mirrored", [False, True])
def test_seam_round_trip_on_a_mirrored_and_rotated_chart(mirrored):
    atlas = uvfeat.Atlas(uvfeat.shapes.split_plane(16, mirrored), 512)
    assert atlas.n_charts == 2
    j, i = np.nonzero(atlas.border & (atlas.adjacent_chart >= 0))
    assert len(j) > 100
    texel = 1.0 / 512
    for jj, ii in zip(j[::7], i[::7]):
        uv = ((ii + 0.5) / 512, (jj + 0.5) / 512)
        crossing = atlas.cross_seam(uv, chart=int(atlas.chart[jj, ii]))
        assert crossing.chart == atlas.adjacent_chart[jj, ii]
        assert (np.linalg.det(crossing.m) < 0) == mirrored
        here = atlas.surface_point(uv)[0]
        there = atlas.surface_point(crossing.uv, chart=crossing.chart)[0]
        assert np.linalg.norm(here - there) < 1e-9  # a plane: the hinge map is exact
        origin_from, origin_to, m = atlas._core.seam_map(atlas._core.reverse_side(crossing.side))
        back = np.asarray(origin_to) + np.asarray(m) @ (np.asarray(crossing.uv) - origin_from)
        assert np.linalg.norm(back - uv) < 1e-6 * texel


def test_locate_crosses_the_seam_and_reports_borders():
    atlas = uvfeat.Atlas(uvfeat.shapes.split_plane(16, True), 1024)
    start = (0.05 + 0.8 * 0.45, 0.05 + 0.9 * 0.5)  # 3D (0.45, 0.5, 0)
    loc = atlas.locate(start, (start[0] + 0.08, start[1]))  # 3D offset (0.1, 0, 0)
    assert loc.status == "inside" and loc.chart == 1 and loc.jumps == 1
    np.testing.assert_allclose(atlas.surface_point(loc.uv, chart=1)[0], [0.55, 0.5, 0.0], atol=1e-9)
    assert atlas.locate((0.1, 0.5), (-0.3, 0.5)).status == "border"
    with pytest.raises(InvalidParameterError, match="not on a chart"):
        atlas.locate((0.001, 0.001), (0.2, 0.2))


def test_diagnostics_and_summary():
    atlas = uvfeat.Atlas(uvfeat.shapes.cylinder(), 256)
    d = atlas.diagnostics
    assert d["border_edges"] == 2 * 128 and d["seam_edges"] == 32 and d["charts"] == 1
    assert "1 charts" in atlas.summary()
    assert atlas.warnings() == []
