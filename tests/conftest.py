"""Shared fixtures: analytic meshes are built in code; real meshes come from ../shared/meshes
(or $UVFEAT_SHARED_MESHES) and their tests skip when that folder is absent."""

import os
import pathlib
import re

import pytest

REPO = pathlib.Path(__file__).resolve().parents[1]


def shared_meshes_dir() -> pathlib.Path | None:
    folder = pathlib.Path(os.environ.get("UVFEAT_SHARED_MESHES", REPO.parent / "shared" / "meshes"))
    return folder if folder.is_dir() else None


@pytest.fixture
def shared_mesh():
    """Path of a mesh in the shared folder, or skip."""

    def get(name: str) -> str:
        folder = shared_meshes_dir()
        if folder is None or not (folder / name).exists():
            pytest.skip(f"shared mesh {name} not available")
        return str(folder / name)

    return get


@pytest.fixture(scope="session", autouse=True)
def private_atlas_cache(tmp_path_factory):
    """Cached xatlas atlases go to a folder of this test session, never to the user's cache."""
    previous = os.environ.get("UVFEAT_CACHE_DIR")
    os.environ["UVFEAT_CACHE_DIR"] = str(tmp_path_factory.mktemp("uvfeat-cache"))
    yield
    if previous is None:
        del os.environ["UVFEAT_CACHE_DIR"]
    else:
        os.environ["UVFEAT_CACHE_DIR"] = previous


def usage_examples(heading: str) -> list[str]:
    """The Python examples of docs/USAGE.md's section ``heading``."""
    text = (REPO / "docs" / "USAGE.md").read_text()
    section = text.split(f"## {heading}\n", 1)[1].split("\n## ", 1)[0]
    return re.findall(r"```python\n(.*?)```", section, re.S)
