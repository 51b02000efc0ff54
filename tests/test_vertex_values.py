"""Values at the vertices (DESIGN.md §1.4.9): with quadrature="surfels" each vertex is the centre of
its own neighbourhood, whose surfels' exact area moments are summed with no maps in between
(``Atlas.per_vertex``, ``uvfeat.compute``), against the analytic truth, the converged reference on
a bumpy surface cut into many charts, and the flat surfel quadrature."""

import functools

import numpy as np
import pytest

import uvfeat
from analytic import range_normalised_error, torus_truth, torus_xatlas

HK = ["mean_curvature", "gaussian_curvature"]
SURFELS = dict(quadrature="surfels", surface="facets")


@functools.lru_cache(maxsize=None)
def bumpy_sphere() -> uvfeat.Mesh:
    """A sphere with bumps of several sizes (8 % of its radius), with uvfeat's own many-chart atlas."""
    s = uvfeat.shapes.uv_sphere(1.0, 160, 80)
    p = np.asarray(s.positions)
    lon, lat = np.arctan2(p[:, 1], p[:, 0]), np.arcsin(np.clip(p[:, 2], -1, 1))
    radial = 1.0 + 0.05 * np.sin(5 * lon) * np.cos(3 * lat) + 0.03 * np.sin(11 * lat + 2 * lon)
    mesh = uvfeat.Mesh(p * radial[:, None], s.faces, name="bumpy sphere").with_atlas(cache=False)
    assert mesh.n_charts >= 8
    return mesh


def test_torus_values_at_the_vertices_against_the_analytic_curvatures():
    # xatlas's 18-chart torus at r = 2 % on the smooth surface, 512² buffers: measured 0.34 % /
    # 0.39 % (the flat surfels read directly: 0.85 % / 0.39 %). A wrong factor or sign would be
    # tens of percent.
    mesh = torus_xatlas()
    h, k, _ = torus_truth(mesh)
    values = uvfeat.Atlas(mesh, resolution=512).per_vertex(HK, "2%", quadrature="surfels")
    assert range_normalised_error(values["mean_curvature"], h) < 0.006
    assert range_normalised_error(values["gaussian_curvature"], k) < 0.006


@pytest.mark.parametrize("radius", ["2%", "6%"])
def test_a_bumpy_many_chart_surface_agrees_with_the_converged_reference(radius):
    mesh = bumpy_sphere()
    rows = np.random.default_rng(1).choice(mesh.n_vertices, 400, replace=False)
    truth = uvfeat.converged_reference(mesh, HK, radius, vertices=rows, max_levels=2).values
    values = uvfeat.compute(mesh, HK, radius, resolution=512, **SURFELS)
    for name in HK:
        error = range_normalised_error(values[name][rows], truth[name])
        assert error < 0.006, (name, error)


def test_one_shot_and_atlas_agree_and_radius_lists_stack():
    mesh = bumpy_sphere()
    atlas = uvfeat.Atlas(mesh, resolution=512)
    one = atlas.per_vertex(HK, "3%", **SURFELS)
    stack = atlas.per_vertex(HK, ["3%", "6%"], **SURFELS)
    shot = uvfeat.compute(mesh, HK, "3%", resolution=512, **SURFELS)
    for name in HK:
        assert one[name].shape == (mesh.n_vertices,) and stack[name].shape == (2, mesh.n_vertices)
        np.testing.assert_array_equal(stack[name][0], one[name])
        np.testing.assert_array_equal(shot[name], one[name])


def test_the_direct_query_is_the_values_at_the_vertices_and_the_texture_agrees():
    atlas = uvfeat.Atlas(bumpy_sphere(), resolution=512)
    at_vertices = atlas.per_vertex(HK, "4%", samples=256, **SURFELS)  # the maps' surfels per ball
    maps = atlas.compute(HK, "4%", compute_resolution=512, **SURFELS)
    for name in HK:
        np.testing.assert_array_equal(maps[name].per_vertex(query="direct"), at_vertices[name])
        # The texture read at the vertices: measured 0.36 % (H) and 0.34 % (K) of the range away.
        error = range_normalised_error(maps[name].per_vertex(query="texture"), at_vertices[name])
        assert error < 0.006, (name, error)


def test_the_pattern_still_reads_its_maps():
    atlas = uvfeat.Atlas(bumpy_sphere(), resolution=256)
    values = atlas.per_vertex("mean_curvature", "4%", compute_resolution=64, quadrature="pattern")
    maps = atlas.compute("mean_curvature", "4%", compute_resolution=64)
    np.testing.assert_array_equal(values["mean_curvature"], maps["mean_curvature"].per_vertex())


def test_many_charts_default_to_the_values_at_the_vertices_and_one_chart_to_the_maps():
    many = bumpy_sphere()
    default = uvfeat.compute(many, HK, "3%")
    sums = uvfeat.Atlas(many, resolution=uvfeat.options.surfel_resolution(many, "3%")).per_vertex(HK, "3%", **SURFELS)
    one = uvfeat.shapes.torus(2.0, 0.5, 64, 32)
    assert one.n_charts == 1
    single = uvfeat.compute(one, HK, "4%", compute_resolution=64)
    maps = uvfeat.Atlas(one, resolution=1024).compute(HK, "4%", compute_resolution=64)
    for name in HK:
        np.testing.assert_array_equal(default[name], sums[name])
        np.testing.assert_array_equal(single[name], maps[name].per_vertex())
    # Naming the quadrature or the maps' query, or asking for what the sums do not serve (the fit,
    # adaptive sampling, standard errors), keeps the maps, on 1024² buffers.
    atlas = uvfeat.Atlas(many, resolution=1024)
    for options in ({"quadrature": "pattern"}, {"query": "direct"}, {"method": "fit"}, {"adaptive": True},
                    {"standard_error": True}):
        read = uvfeat.compute(many, "mean_curvature", "3%", compute_resolution=32, samples=32, **options)
        maps = atlas.compute("mean_curvature", "3%", compute_resolution=32, samples=32, **options)
        query = options.get("query", "texture")
        np.testing.assert_array_equal(read["mean_curvature"], maps["mean_curvature"].per_vertex(query), str(options))
        adaptive = atlas.per_vertex("mean_curvature", "3%", compute_resolution=32, samples=32, **options)
        np.testing.assert_array_equal(adaptive["mean_curvature"], read["mean_curvature"], str(options))


def test_the_surfel_grid_follows_the_radius_with_the_same_values():
    # The grid whose mean texel puts 160 surfels in a plane's ball: about sqrt(160 A / (pi r^2 A_uv))
    # wide, to a multiple of 16, at most 512 (the smallest radius of a list counts). Its sums agree
    # with the 512² pyramid's levels within their quadrature (measured: H 0.09 / 0.16 %, K 0.05 /
    # 0.08 % of the range at 6 / 12 %).
    mesh = bumpy_sphere()
    widths = [uvfeat.options.surfel_resolution(mesh, f"{r}%") for r in (1, 2, 4, 8)]
    assert widths[0] == 512 and all(w % 16 == 0 for w in widths)
    for wide, narrow in zip(widths[1:], widths[2:]):
        assert abs(wide / narrow - 2) < 0.3, widths
    assert uvfeat.options.surfel_resolution(mesh, ["8%", "2%"]) == widths[1]
    atlas = uvfeat.Atlas(mesh, resolution=512)
    for radius in ("6%", "12%"):
        assert uvfeat.options.surfel_resolution(mesh, radius) < 256
        default = uvfeat.compute(mesh, HK, radius)
        finest = atlas.per_vertex(HK, radius, **SURFELS)
        for name in HK:
            error = range_normalised_error(default[name], finest[name])
            assert 0 < error < 0.003, (radius, name, error)


def test_samples_sets_the_surfels_per_ball():
    # At r = 6 % with 32 surfels per ball (an 80² grid): H / K 0.29 / 0.29 % of the range, with
    # 160 (the default, 176²) 0.19 / 0.11 %; measured.
    mesh = bumpy_sphere()
    assert [uvfeat.options.surfel_resolution(mesh, "6%", n) for n in (32, 160, 256)] == [80, 176, 208]
    assert uvfeat.options.surfel_resolution(mesh, "6%") == 176
    rows = np.random.default_rng(1).choice(mesh.n_vertices, 400, replace=False)
    truth = uvfeat.converged_reference(mesh, HK, "6%", vertices=rows, max_levels=2).values
    errors = {n: {name: range_normalised_error(values[rows], truth[name])
                  for name, values in uvfeat.compute(mesh, HK, "6%", samples=n, **SURFELS).items()}
              for n in (32, 160)}
    for name in HK:
        assert 1.4 * errors[160][name] < errors[32][name] < 0.01, (name, errors)
    # So few that a ball sums a handful: the warning names samples.
    with pytest.warns(uvfeat.NeighbourhoodWarning, match="samples=4 sums about that many surfels"):
        uvfeat.compute(mesh, HK, "6%", samples=4, **SURFELS)
    # A kept atlas sums as many: the 512² pyramid, its levels chosen for each count.
    atlas = uvfeat.Atlas(mesh, resolution=512)
    few, default = (atlas.per_vertex(HK, "6%", samples=n, **SURFELS) for n in (32, None))
    for name in HK:
        assert range_normalised_error(few[name][rows], truth[name]) > 1.5 * range_normalised_error(
            default[name][rows], truth[name]), name


@pytest.mark.parametrize("radius", ["2%", "6%"])
@pytest.mark.parametrize("surface", ["facets", "smooth"])
def test_the_defaults_on_many_charts_agree_with_the_converged_reference(radius, surface):
    # The defaults sum the mesh's facets, which the converged reference refines; surface="smooth"
    # sums the smooth surface through the vertex normals, which its smooth surface refines. Each
    # against its own truth, measured H / K: facets 0.14 / 0.15 % at 2 %, 0.21 / 0.13 % at 6 %;
    # smooth 0.17 / 0.42 %, 0.21 / 0.36 % (K's truth has that surface's creases between faces).
    # Against the other's truth H is 1.25-1.33 % off at 2 %: the two surfaces part by the facets'
    # sag where a ball spans a few edges. A wrong factor or sign would be tens of percent.
    mesh = bumpy_sphere()
    rows = np.random.default_rng(2).choice(mesh.n_vertices, 400, replace=False)
    truth = uvfeat.converged_reference(mesh, HK, radius, vertices=rows, max_levels=2, surface=surface).values
    values = uvfeat.compute(mesh, HK, radius, **({} if surface == "facets" else {"surface": surface}))
    for name in HK:
        error = range_normalised_error(values[name][rows], truth[name])
        assert error < (0.004 if surface == "facets" or name == "mean_curvature" else 0.01), (name, error)


@pytest.mark.parametrize("radius", ["2%", "8%"])
def test_the_shared_armadillo_agrees_with_the_converged_reference(shared_mesh, radius):
    mesh = uvfeat.load(shared_mesh("armadillo.obj")).with_atlas()
    rows = np.random.default_rng(0).choice(mesh.n_vertices, 300, replace=False)
    truth = uvfeat.converged_reference(mesh, HK, radius, vertices=rows, max_levels=2).values
    values = uvfeat.compute(mesh, HK, radius, resolution=512, **SURFELS)
    # The defaults (the facets at the grid of the radius; measured on 1,000 vertices: 0.11-0.17 % at 2 and 8 %).
    default = uvfeat.compute(mesh, HK, radius)
    for name in HK:
        assert range_normalised_error(values[name][rows], truth[name]) < 0.01, name
        assert range_normalised_error(default[name][rows], truth[name]) < 0.01, name


def test_a_vertex_on_no_face_is_nan_and_the_others_are_not():
    s = uvfeat.shapes.torus(2.0, 0.5, 64, 32)
    positions = np.vstack([s.positions, [[9.0, 9.0, 9.0]]])
    mesh = uvfeat.Mesh(positions, s.faces, s.uvs, s.uv_faces)
    values = uvfeat.compute(mesh, HK, 0.3, resolution=256, **SURFELS)
    for name in HK:
        assert np.isnan(values[name][-1]) and np.isfinite(values[name][:-1]).all(), name


def test_neighbourhoods_cut_by_a_border_are_named_in_a_warning():
    plane = uvfeat.shapes.plane(1.0, 48)
    with pytest.warns(uvfeat.NeighbourhoodWarning, match="cut by a mesh border") as caught:
        values = uvfeat.Atlas(plane, resolution=256).per_vertex("mean_curvature", 0.1, **SURFELS)
    # The band within r of the square's edges: 1 - 0.8^2 = 36 % of its area.
    share = float(caught[0].message.args[0].split("(")[1].split(" %")[0])
    assert 25 < share < 50, share
    assert np.nanmax(np.abs(values["mean_curvature"])) < 1e-3  # a plane is flat, border or not
