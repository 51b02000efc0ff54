"""Meshes users already hold (trimesh, PyVista, Open3D, array tuples) go into every entry point and
give the values of the same uvfeat.Mesh, in the source's own vertex order; results go back onto
the source objects (uvfeat.interop)."""

import functools
import importlib.util
import warnings

import numpy as np
import pytest
import trimesh

import uvfeat
from conftest import usage_examples
from uvfeat.files.bake import split_by_uv

pyvista = pytest.importorskip("pyvista")

H = ["mean_curvature"]
HK = ["mean_curvature", "gaussian_curvature"]


@functools.lru_cache(maxsize=None)
def torus_arrays():
    """A torus with one UV per vertex (the lat-long chart split at its seams), as plain arrays."""
    torus = uvfeat.shapes.torus(2.0, 0.5, 48, 24)
    source, uvs, faces = split_by_uv(torus)
    return np.asarray(torus.positions)[source], faces, uvs


def same_values(a: dict, b: dict):
    assert a.keys() == b.keys()
    for name in a:
        np.testing.assert_array_equal(a[name], b[name], err_msg=name)


@functools.lru_cache(maxsize=None)
def expected() -> dict:
    positions, faces, uvs = torus_arrays()
    return uvfeat.compute(uvfeat.Mesh(positions, faces, uvs), HK, radius="4%")


def test_array_tuples_give_the_mesh_values():
    positions, faces, uvs = torus_arrays()
    same_values(uvfeat.compute((positions, faces, uvs, faces), HK, radius="4%"), expected())
    plain = uvfeat.compute([positions, faces], H, radius="4%")
    assert plain["mean_curvature"].shape == (len(positions),)


def test_a_trimesh_with_texture_uvs_gives_the_mesh_values():
    positions, faces, uvs = torus_arrays()
    source = trimesh.Trimesh(positions, faces, process=False, visual=trimesh.visual.TextureVisuals(uv=uvs))
    assert uvfeat.interop.as_mesh(source).has_uvs
    same_values(uvfeat.compute(source, HK, radius="4%"), expected())


def test_a_processed_trimesh_is_taken_in_its_own_vertex_order():
    sphere = trimesh.creation.icosphere(4, radius=2.0)
    # The sphere the vertices sample (the facets, 2 edges across the ball, lie inside it).
    values = uvfeat.compute(sphere, HK, radius="5%", surface="smooth")
    assert values["mean_curvature"].shape == (len(sphere.vertices),)
    np.testing.assert_allclose(np.median(values["mean_curvature"]), 0.5, rtol=0.01)
    np.testing.assert_allclose(np.median(values["gaussian_curvature"]), 0.25, rtol=0.02)


def test_a_polydata_with_texture_coordinates_gives_the_mesh_values():
    positions, faces, uvs = torus_arrays()
    poly = pyvista.PolyData(positions, np.column_stack([np.full(len(faces), 3), faces]).ravel())
    poly.point_data["uv"] = uvs
    poly.point_data.active_texture_coordinates_name = "uv"
    assert uvfeat.interop.as_mesh(poly).has_uvs
    same_values(uvfeat.compute(poly, HK, radius="4%"), expected())


def quad_cylinder(radius: float, height: float, around: int, along: int):
    """An open cylinder around z made of quads, as a PolyData."""
    angle = np.linspace(0, 2 * np.pi, around, endpoint=False)
    z = np.linspace(-height / 2, height / 2, along + 1)
    points = np.array([(radius * np.cos(a), radius * np.sin(a), h) for h in z for a in angle])
    quads = [(4, j * around + i, j * around + (i + 1) % around, (j + 1) * around + (i + 1) % around,
              (j + 1) * around + i) for j in range(along) for i in range(around)]
    return pyvista.PolyData(points, np.array(quads).ravel())


def test_a_polydata_of_quads_is_triangulated_and_keeps_its_points():
    surface = quad_cylinder(2.0, 6.0, 96, 48)
    assert not surface.is_all_triangles
    values = uvfeat.compute(surface, HK, radius="5%", surface="smooth")
    assert values["mean_curvature"].shape == (surface.n_points,)
    # A cylinder: H = 1/(2R) = 0.25, K = 0 away from its rims.
    middle = np.abs(np.asarray(surface.points)[:, 2]) < 1.0
    np.testing.assert_allclose(np.median(values["mean_curvature"][middle]), 0.25, rtol=0.02)
    assert abs(np.median(values["gaussian_curvature"][middle])) < 0.005


def test_a_volume_grid_gives_its_surface_values_and_nan_inside():
    grid = pyvista.ImageData(dimensions=(9, 9, 9)).cast_to_unstructured_grid()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", uvfeat.NeighbourhoodWarning)
        values = uvfeat.compute(grid, H, radius="10%")["mean_curvature"]
    assert values.shape == (grid.n_points,)
    inner = np.all((grid.points > 0) & (grid.points < 8), axis=1)
    assert np.isnan(values[inner]).all() and np.isfinite(values[~inner]).all()
    # A face of the cube is flat: H = 0 at its middle.
    middle = np.flatnonzero(np.all(np.isclose(grid.points, [4, 4, 0]), axis=1))
    assert abs(values[middle[0]]) < 1e-3


def test_open3d_meshes_give_the_mesh_values():
    open3d = pytest.importorskip("open3d")
    positions, faces, uvs = torus_arrays()
    source = open3d.geometry.TriangleMesh(open3d.utility.Vector3dVector(positions),
                                          open3d.utility.Vector3iVector(faces.astype(np.int32)))
    source.triangle_uvs = open3d.utility.Vector2dVector(uvs[faces].reshape(-1, 2))
    same_values(uvfeat.compute(source, HK, radius="4%"), expected())


def test_the_other_entry_points_take_the_same_sources():
    positions, faces, uvs = torus_arrays()
    mesh = uvfeat.Mesh(positions, faces, uvs)
    source = trimesh.Trimesh(positions, faces, process=False, visual=trimesh.visual.TextureVisuals(uv=uvs))
    same_values(uvfeat.reference.compute(source, HK, radius="4%"), uvfeat.reference.compute(mesh, HK, radius="4%"))
    converged = uvfeat.converged_reference(source, H, "8%", vertices=[0, 7], max_levels=1)
    np.testing.assert_array_equal(converged.values["mean_curvature"],
                                  uvfeat.converged_reference(mesh, H, "8%", vertices=[0, 7],
                                                             max_levels=1).values["mean_curvature"])
    atlas = uvfeat.Atlas((positions, faces, uvs, faces), resolution=256)
    assert atlas.mesh.n_vertices == len(positions)
    figure = uvfeat.plot(source, expected()["mean_curvature"], feature="mean_curvature", views=["front"])
    assert figure.axes


@pytest.mark.parametrize("source, named", [
    (object(), "builtins.object"),
    ((np.zeros((3, 3)), np.array([[0, 1, 2]]), np.zeros((3, 2))), "tuple of 3 items"),
    ("torus.obj", "builtins.str"),
    ({"positions": np.zeros((3, 3))}, "builtins.dict"),
])
def test_anything_else_is_an_invalid_mesh_that_says_what_is_taken(source, named):
    with pytest.raises(uvfeat.InvalidMeshError, match="trimesh.Trimesh, a pyvista.PolyData") as error:
        uvfeat.compute(source, H, radius="4%")
    assert named in str(error.value)


def test_a_tuple_of_bad_arrays_names_what_is_wrong():
    with pytest.raises(uvfeat.InvalidMeshError, match="NaN|finite"):
        uvfeat.compute((np.full((3, 3), np.nan), np.array([[0, 1, 2]])), H, radius=0.1)


def test_results_attach_to_trimesh_and_pyvista_and_colour_a_pyvista_mesh():
    positions, faces, uvs = torus_arrays()
    source = trimesh.Trimesh(positions, faces, process=False)
    values = uvfeat.compute(source, HK, radius=["4%", "8%"])
    assert uvfeat.attach(source, values) is source
    assert source.vertex_attributes["mean_curvature"].shape == (len(positions), 2)
    poly = uvfeat.to_pyvista(source, {"mean_curvature": values["mean_curvature"][0]})
    assert poly.active_scalars_name == "mean_curvature" and poly.n_points == len(positions)
    np.testing.assert_array_equal(poly.point_data["mean_curvature"], values["mean_curvature"][0])
    with pytest.raises(uvfeat.InvalidParameterError, match="101 values per row"):
        uvfeat.attach(poly, {"mean_curvature": np.zeros(101)})
    with pytest.raises(uvfeat.InvalidParameterError, match="no per-vertex fields"):
        uvfeat.attach(object(), values)


def test_the_usage_examples_run_as_written(capsys):
    examples = usage_examples("From trimesh, PyVista, Open3D")
    assert len(examples) == 2
    for example in examples:
        if "import open3d" in example and importlib.util.find_spec("open3d") is None:
            continue
        exec(compile(example, "docs/USAGE.md", "exec"), {})
    medians = [float(line) for line in capsys.readouterr().out.split()]
    # The icosphere's facets, then the smooth sphere through its vertices (1 / R = 0.5), then Open3D's.
    assert 0.53 < medians[0] < 0.56 and 0.49 < medians[1] < 0.51
    assert all(0.95 < m < 1.05 for m in medians[2:])
