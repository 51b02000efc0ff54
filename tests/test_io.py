import os

import numpy as np
import pytest
import trimesh

import uvfeat
from uvfeat import MeshFileError, UVError


def _trimesh_with_uv(mesh: uvfeat.Mesh) -> trimesh.Trimesh:
    """Per-vertex-UV copy (vertices split per corner, as glTF does)."""
    corners = mesh.faces.reshape(-1)
    uv = mesh.uvs[mesh.uv_faces.reshape(-1)]
    faces = np.arange(len(corners)).reshape(-1, 3)
    return trimesh.Trimesh(mesh.positions[corners], faces, visual=trimesh.visual.TextureVisuals(uv=uv), process=False)


def test_missing_unreadable_and_unsupported_files(tmp_path):
    with pytest.raises(MeshFileError, match="no such file"):
        uvfeat.load(tmp_path / "nope.obj")
    (tmp_path / "mesh.xyz").write_text("1 2 3\n")
    with pytest.raises(MeshFileError, match="unsupported format 'xyz'"):
        uvfeat.load(tmp_path / "mesh.xyz")
    (tmp_path / "broken.glb").write_bytes(b"\x00garbage" * 10)
    with pytest.raises(MeshFileError, match="cannot read"):
        uvfeat.load(tmp_path / "broken.glb")
    with pytest.raises(MeshFileError, match="not a readable file"):
        uvfeat.load(tmp_path)


def test_binary_bytes_in_a_text_format_name_the_problem(tmp_path):
    rng = np.random.default_rng(3)
    for extension in ("obj", "off"):
        path = tmp_path / f"random.{extension}"
        path.write_bytes(rng.integers(0, 256, 3000, dtype=np.uint8).tobytes() + b"\0")
        with pytest.raises(MeshFileError, match=f"binary data in a text {extension.upper()} file") as raised:
            uvfeat.load(path)
        assert "module" not in str(raised.value)


def test_latin1_obj_is_read(tmp_path):
    path = tmp_path / "latin.obj"
    path.write_bytes(b"# caf\xe9 cr\xe8me\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n")
    assert uvfeat.load(path, uv="require").n_faces == 1


def test_empty_file_is_an_error(tmp_path):
    (tmp_path / "empty.obj").write_text("# nothing\n")
    with pytest.raises((uvfeat.InvalidMeshError, MeshFileError)):
        uvfeat.load(tmp_path / "empty.obj")


@pytest.mark.parametrize("extension", ["glb", "ply", "obj"])
def test_round_trip_through_files_keeps_charts_and_welds_seams(tmp_path, extension):
    torus = uvfeat.shapes.torus(2.0, 0.5, 32, 16)
    path = tmp_path / f"torus.{extension}"
    _trimesh_with_uv(torus).export(path)
    loaded = uvfeat.load(path, uv="require")
    assert loaded.n_faces == torus.n_faces
    assert loaded.n_charts == 1
    assert len(np.unique(loaded.vertex_ids)) == torus.n_vertices  # every split vertex welded back


def test_file_without_uvs_gets_an_automatic_atlas_or_a_clear_error(tmp_path):
    path = tmp_path / "ico.obj"
    trimesh.creation.icosphere(3).export(path)
    with pytest.raises(UVError, match="no UV coordinates"):
        uvfeat.load(path, uv="require")
    automatic, charts, xatlas = (uvfeat.load(path, uv=uv) for uv in ("auto", "charts", "xatlas"))
    np.testing.assert_array_equal(automatic.uvs, charts.uvs)
    assert charts.n_charts > 1 and xatlas.n_charts > 1
    assert not np.array_equal(charts.uvs.shape, xatlas.uvs.shape) or not np.allclose(charts.uvs, xatlas.uvs)
    with pytest.raises(ValueError, match="uv must be one of"):
        uvfeat.load(path, uv="lscm")


def test_multi_mesh_scene_is_merged_with_non_overlapping_uvs(tmp_path):
    a = _trimesh_with_uv(uvfeat.shapes.uv_sphere(1.0, 24, 12))
    b = _trimesh_with_uv(uvfeat.shapes.torus(2.0, 0.5, 24, 12))
    b.apply_translation([5.0, 0, 0])
    path = tmp_path / "scene.glb"
    trimesh.Scene([a, b]).export(path)
    with pytest.warns(uvfeat.UVWarning, match="tiled"):
        mesh = uvfeat.load(path)
    assert mesh.n_faces == len(a.faces) + len(b.faces)
    assert mesh.n_charts == 2
    atlas = uvfeat.Atlas(mesh, 256)
    assert atlas.diagnostics["overlapping_texels"] == 0
