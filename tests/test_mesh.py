import warnings

import numpy as np
import pytest

import uvfeat
from uvfeat import InvalidMeshError, MeshWarning, UVError, UVWarning

TRI = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
UV = np.array([[0.1, 0.1], [0.9, 0.1], [0.1, 0.9]])


def test_arrays_are_read_only_and_typed():
    mesh = uvfeat.Mesh(TRI, [[0, 1, 2]], UV)
    assert mesh.positions.dtype == np.float64 and mesh.faces.dtype == np.int64
    with pytest.raises(ValueError):
        mesh.positions[0, 0] = 5
    assert mesh.n_charts == 1


@pytest.mark.parametrize(
    "positions, faces, match",
    [
        (np.zeros((0, 3)), np.zeros((0, 3), int), "empty mesh"),
        (np.array([[0, np.nan, 0], [1, 0, 0], [0, 1, 0]]), [[0, 1, 2]], "vertex 0 has a non-finite"),
        (np.array([[0, np.inf, 0], [1, 0, 0], [0, 1, 0]]), [[0, 1, 2]], "non-finite"),
        (TRI, [[0, 1, 3]], "face 0 of faces refers to vertex"),
        (TRI, [[0, -1, 2]], "refers to vertex"),
        (TRI[:, :2], [[0, 1, 2]], r"positions must have shape \(n, 3\)"),
        (TRI, [[0, 1]], "faces must have shape"),
    ],
)
def test_bad_meshes_raise_clear_errors(positions, faces, match):
    with pytest.raises(InvalidMeshError, match=match):
        uvfeat.Mesh(positions, faces)


def test_bad_uvs_raise_uv_errors():
    with pytest.raises(UVError, match="non-finite"):
        uvfeat.Mesh(TRI, [[0, 1, 2]], [[0, 0], [np.nan, 0], [0, 1]])
    with pytest.raises(UVError, match="one row per vertex"):
        uvfeat.Mesh(TRI, [[0, 1, 2]], [[0, 0], [1, 0]])
    with pytest.raises(UVError, match="outside"):
        uvfeat.Mesh(TRI, [[0, 1, 2]], UV * 2, normalize_uv=False)
    with pytest.raises(UVError, match="no UV coordinates"):
        uvfeat.Mesh(TRI, [[0, 1, 2]]).topology


def test_uvs_outside_the_unit_square_are_normalised_with_a_warning_not_clipped():
    uvs = np.array([[-1.0, 0.0], [3.0, 0.0], [-1.0, 2.0]])
    with pytest.warns(UVWarning, match="normalised"):
        mesh = uvfeat.Mesh(TRI, [[0, 1, 2]], uvs)
    np.testing.assert_allclose(mesh.uvs, [[0, 0], [1, 0], [0, 0.5]])  # layout and aspect kept
    assert mesh.uv_normalization == (-1.0, 0.0, 0.25)


def test_quads_are_triangulated_with_a_warning():
    square = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])
    with pytest.warns(MeshWarning, match="fan-triangulated"):
        mesh = uvfeat.Mesh(square, [[0, 1, 2, 3]], square[:, :2] * 0.8 + 0.1)
    assert mesh.faces.tolist() == [[0, 1, 2], [0, 2, 3]]
    assert mesh.n_charts == 1


def test_split_vertices_are_welded_but_kept_in_the_arrays():
    # A glTF-style square: the two triangles carry their own copies of the shared vertices.
    positions = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 0, 0], [1, 1, 0], [0, 1, 0]])
    uvs = positions[:, :2] * 0.8 + 0.1
    mesh = uvfeat.Mesh(positions, [[0, 1, 2], [3, 4, 5]], uvs)
    assert mesh.n_vertices == 6
    assert mesh.vertex_ids.tolist() == [0, 1, 2, 0, 2, 3]
    assert mesh.n_charts == 1  # same UVs on both sides of the diagonal: one chart


@pytest.mark.parametrize("method", ["charts", "xatlas"])
def test_with_atlas_builds_a_multi_chart_atlas(method):
    sphere = uvfeat.shapes.uv_sphere(1.0, 48, 24)
    fresh = uvfeat.Mesh(sphere.positions, sphere.faces).with_atlas(resolution=512, method=method)
    assert fresh.n_charts > 1
    assert fresh.uvs.min() >= 0 and fresh.uvs.max() <= 1
    np.testing.assert_array_equal(fresh.faces, sphere.faces)
    assert uvfeat.Atlas(fresh, 512).diagnostics["overlapping_texels"] == 0


def test_own_charts_of_a_noisy_scan_merge_its_fragments_and_stay_injective():
    """A 200K-face sphere with normal noise of 0.2 % of its diagonal (docs/PEERS.md's noisy
    sphere, noise along the radius): the faces that fold in every projection used to be 255
    fragments beside 20 charts; they join the charts beside them (DESIGN.md §1.1.1). With this
    seed a fragment beside two charts, all of whose border vertices one of them held, was taken
    for a hole in it and overlapped its faces."""
    sphere = uvfeat.shapes.uv_sphere(1.0, 448, 224)
    radial = sphere.positions / np.linalg.norm(sphere.positions, axis=1)[:, None]
    positions = sphere.positions + np.random.default_rng(0).normal(0.0, 0.002 * 2 * np.sqrt(3), len(radial))[:, None] * radial
    uvs, uv_faces = uvfeat.unwrap.chart_uvs(positions, sphere.faces, cache=False)
    atlas = uvfeat.Atlas(uvfeat.Mesh(positions, sphere.faces, uvs, uv_faces), 1024)
    diagnostics = atlas.diagnostics
    assert diagnostics["charts"] < 100, diagnostics["charts"]
    assert (diagnostics["overlapping_texels"], diagnostics["mirrored_uv_faces"]) == (0, 0)


def test_with_atlas_names_a_bad_method_or_option():
    sphere = uvfeat.shapes.uv_sphere(1.0, 16, 8)
    bare = uvfeat.Mesh(sphere.positions, sphere.faces)
    with pytest.raises(ValueError, match="method must be one of"):
        bare.with_atlas(method="lscm")
    with pytest.raises(uvfeat.InvalidParameterError, match="max_angle"):
        uvfeat.unwrap.chart_uvs(bare.positions, bare.faces, max_angle=95)
    with pytest.raises(uvfeat.InvalidParameterError, match="do not fit"):
        uvfeat.unwrap.chart_uvs(bare.positions, bare.faces, resolution=4, max_angle=1)


def test_the_bounding_box_diagonal_leaves_out_vertices_no_face_uses():
    assert uvfeat.Mesh(TRI, [[0, 1, 2]]).bounding_box_diagonal == pytest.approx(np.sqrt(2.0))
    stray = np.vstack([TRI, [[50.0, -20.0, 7.0]]])
    assert uvfeat.Mesh(stray, [[0, 1, 2]]).bounding_box_diagonal == pytest.approx(np.sqrt(2.0))
    assert uvfeat.Mesh(stray, [[0, 1, 3]]).bounding_box_diagonal == pytest.approx(np.linalg.norm([50, 20, 7]))
