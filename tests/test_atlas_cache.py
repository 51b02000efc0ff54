"""The on-disk cache of atlases (uvfeat's charts and xatlas's): keyed by the mesh's content, the
options and the unwrapper, read back instead of unwrapping again, and never trusted when
unreadable."""

import numpy as np
import pytest
import trimesh

import uvfeat
from uvfeat import unwrap


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("UVFEAT_CACHE_DIR", str(tmp_path))
    return tmp_path / "atlases"


@pytest.fixture
def sphere():
    ico = trimesh.creation.icosphere(subdivisions=3)
    return uvfeat.Mesh(ico.vertices, ico.faces, name="icosphere")


#: Each unwrapper, and the function of ``uvfeat.unwrap`` that runs it when the cache misses.
UNWRAPPERS = pytest.mark.parametrize("method, runner", [("charts", "_charts"), ("xatlas", "_unwrap")])


def _forbid_unwrapping(monkeypatch, runner):
    def unwrap_called(*args, **kwargs):
        raise AssertionError("the unwrapper ran although the atlas was cached")

    monkeypatch.setattr(unwrap, runner, unwrap_called)


@UNWRAPPERS
def test_a_second_unwrap_of_the_same_mesh_reads_the_cache(cache, sphere, monkeypatch, method, runner):
    first = sphere.with_atlas(resolution=256, method=method)
    assert len(list(cache.glob("*.npz"))) == 1
    _forbid_unwrapping(monkeypatch, runner)
    second = sphere.with_atlas(resolution=256, method=method)
    assert np.array_equal(first.uvs, second.uvs) and np.array_equal(first.uv_faces, second.uv_faces)
    assert second.n_charts == first.n_charts > 1
    with pytest.raises(AssertionError, match="the unwrapper ran"):
        sphere.with_atlas(resolution=256, method=method, cache=False)


def test_the_unwrappers_do_not_share_cache_files(cache, sphere):
    sphere.with_atlas(resolution=256, method="charts")
    sphere.with_atlas(resolution=256, method="xatlas")
    assert len(list(cache.glob("*.npz"))) == 2


def test_a_rebuilt_core_library_charts_again(cache, sphere, monkeypatch):
    sphere.with_atlas(resolution=256)
    monkeypatch.setattr(unwrap, "_charts_build", lambda: "uvfeat rebuilt")
    sphere.with_atlas(resolution=256)
    assert len(list(cache.glob("*.npz"))) == 2


@UNWRAPPERS
def test_other_positions_or_options_unwrap_again(cache, sphere, method, runner):
    sphere.with_atlas(resolution=256, method=method)
    sphere.with_atlas(resolution=512, method=method)
    moved = sphere.positions.copy()
    moved[0, 0] += 1e-9
    uvfeat.Mesh(moved, sphere.faces).with_atlas(resolution=256, method=method)
    assert len(list(cache.glob("*.npz"))) == 3


@UNWRAPPERS
def test_a_corrupt_cache_file_is_ignored_and_rewritten(cache, sphere, method, runner):
    first = sphere.with_atlas(resolution=256, method=method)
    (path,) = cache.glob("*.npz")
    path.write_bytes(b"not an npz file")
    again = sphere.with_atlas(resolution=256, method=method)
    assert np.array_equal(first.uvs, again.uvs)
    with np.load(path) as data:
        assert np.array_equal(data["uvs"], first.uvs)


@UNWRAPPERS
def test_the_cache_can_be_turned_off(tmp_path, sphere, monkeypatch, method, runner):
    monkeypatch.setenv("UVFEAT_CACHE_DIR", "off")
    assert unwrap.cache_dir() is None
    sphere.with_atlas(resolution=256, method=method)
    monkeypatch.setenv("UVFEAT_CACHE_DIR", str(tmp_path))
    sphere.with_atlas(resolution=256, cache=False, method=method)
    assert not (tmp_path / "atlases").exists()


@UNWRAPPERS
def test_an_unwritable_cache_warns_and_still_returns_the_atlas(tmp_path, sphere, monkeypatch, method, runner):
    blocker = tmp_path / "file"
    blocker.write_text("a file where the cache folder should be")
    monkeypatch.setenv("UVFEAT_CACHE_DIR", str(blocker))
    with pytest.warns(RuntimeWarning, match="atlas cache"):
        mesh = sphere.with_atlas(resolution=256, method=method)
    assert mesh.n_charts > 1


def test_xatlas_options_are_passed_through_and_key_the_cache(cache, sphere):
    default = unwrap.xatlas_uvs(sphere.positions, sphere.faces, resolution=256)
    rotated = unwrap.xatlas_uvs(sphere.positions, sphere.faces, resolution=256, pack_options={"rotate_charts": False})
    assert len(list(cache.glob("*.npz"))) == 2
    assert default[1].shape == rotated[1].shape
    with pytest.raises(ValueError, match="no option 'max_cots'"):
        unwrap.xatlas_uvs(sphere.positions, sphere.faces, chart_options={"max_cots": 4.0}, cache=False)
