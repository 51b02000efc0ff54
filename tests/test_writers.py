"""Files the command line writes (uvfeat.files.writers): per-vertex NPZ and PLY, and JSON summaries."""

import json
import math

import numpy as np
import pytest
import trimesh

import uvfeat
from uvfeat.pictures.images import vertex_colours
from uvfeat.files.writers import direction_properties, write_json, write_per_vertex


@pytest.fixture
def mesh():
    return uvfeat.shapes.uv_sphere(1.0, 16, 8)


@pytest.fixture
def values(mesh):
    n = mesh.n_vertices
    rng = np.random.default_rng(1)
    mean = rng.normal(1.0, 0.3, n)
    mean[[3, 7]] = np.nan
    return {"mean_curvature": mean, "curvedness": np.abs(rng.normal(size=n)).astype(np.float32)}


@pytest.fixture
def directions(mesh):
    d = np.random.default_rng(2).normal(size=(mesh.n_vertices, 2, 3))
    return d / np.linalg.norm(d, axis=-1, keepdims=True)


def test_direction_properties(directions):
    assert direction_properties(None) == {}
    properties = direction_properties(directions)
    assert list(properties) == ["d1_x", "d1_y", "d1_z", "d2_x", "d2_y", "d2_z"]
    for k in range(2):
        for a, axis in enumerate("xyz"):
            p = properties[f"d{k + 1}_{axis}"]
            assert p.dtype == np.float32 and p.shape == (len(directions),)
            np.testing.assert_array_equal(p, directions[:, k, a].astype(np.float32))


def test_npz_reads_back_equal(tmp_path, mesh, values, directions):
    write_per_vertex(str(tmp_path), "0.05", mesh, 0.05, values, directions)
    with np.load(tmp_path / "per_vertex_r0.05.npz") as npz:
        assert set(npz.files) == {"positions", "faces", "radius", "mean_curvature", "curvedness",
                                  "principal_directions"}
        np.testing.assert_array_equal(npz["positions"], mesh.positions)
        np.testing.assert_array_equal(npz["faces"], mesh.faces)
        assert float(npz["radius"]) == 0.05
        for name, v in values.items():
            np.testing.assert_array_equal(npz[name], v)
            assert npz[name].dtype == v.dtype
        np.testing.assert_array_equal(npz["principal_directions"], directions)


def test_npz_without_directions(tmp_path, mesh, values):
    write_per_vertex(str(tmp_path), "2pc", mesh, 0.1, values)
    with np.load(tmp_path / "per_vertex_r2pc.npz") as npz:
        assert "principal_directions" not in npz.files
    ply = trimesh.load(tmp_path / "per_vertex_r2pc.ply", process=False)
    names = ply.metadata["_ply_raw"]["vertex"]["data"].dtype.names
    assert not any(name.startswith("d1_") or name.startswith("d2_") for name in names)


def test_ply_reads_back_equal(tmp_path, mesh, values, directions):
    write_per_vertex(str(tmp_path), "0.05", mesh, 0.05, values, directions)
    path = tmp_path / "per_vertex_r0.05.ply"
    header = path.read_bytes().split(b"end_header")[0].decode()
    assert f"element vertex {mesh.n_vertices}" in header and f"element face {mesh.n_faces}" in header
    for name in ["mean_curvature", "curvedness", "d1_x", "d1_y", "d1_z", "d2_x", "d2_y", "d2_z"]:
        assert f"property float {name}\n" in header, name

    ply = trimesh.load(path, process=False)
    np.testing.assert_allclose(ply.vertices, mesh.positions, rtol=1e-6, atol=1e-7)  # float32 in the file
    np.testing.assert_array_equal(ply.faces, mesh.faces)
    vertex = ply.metadata["_ply_raw"]["vertex"]["data"]
    for name, v in values.items():
        np.testing.assert_array_equal(vertex[name], v.astype(np.float32))
    assert np.isnan(vertex["mean_curvature"][[3, 7]]).all()
    for k in range(2):
        for a, axis in enumerate("xyz"):
            np.testing.assert_array_equal(vertex[f"d{k + 1}_{axis}"], directions[:, k, a].astype(np.float32))


def test_ply_coloured_by_the_first_feature(tmp_path, mesh, values):
    write_per_vertex(str(tmp_path), "a", mesh, 0.05, values)
    ply = trimesh.load(tmp_path / "per_vertex_ra.ply", process=False)
    expected = vertex_colours("mean_curvature", values["mean_curvature"])
    np.testing.assert_array_equal(ply.visual.vertex_colors, expected)
    np.testing.assert_array_equal(ply.visual.vertex_colors[3], (128, 128, 128, 255))  # NaN: grey
    # the first feature, not the second
    reordered = {"curvedness": values["curvedness"], "mean_curvature": values["mean_curvature"]}
    write_per_vertex(str(tmp_path), "b", mesh, 0.05, reordered)
    ply = trimesh.load(tmp_path / "per_vertex_rb.ply", process=False)
    np.testing.assert_array_equal(ply.visual.vertex_colors, vertex_colours("curvedness", values["curvedness"]))
    assert not np.array_equal(ply.visual.vertex_colors, expected)


def test_write_json_numpy_scalars(tmp_path):
    summary = {
        "radius": np.float32(0.25),
        "error": np.float64(1.5),
        "count": np.int64(3),
        "flag": np.bool_(True),
        "plain": [1, "two", None],
        "nested": {"value": np.float64(-2.0), "missing": float("nan")},
    }
    path = tmp_path / "summary.json"
    write_json(str(path), summary)
    text = path.read_text()
    assert "\n  " in text                                  # indented
    back = json.loads(text)
    assert back["radius"] == 0.25 and back["error"] == 1.5 and back["count"] == 3
    assert back["flag"] == 1
    assert back["plain"] == [1, "two", None]
    assert back["nested"]["value"] == -2.0 and math.isnan(back["nested"]["missing"])

