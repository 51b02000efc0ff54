import json

import pytest
import trimesh

from uvfeat.cli import main


def test_atlas_command_writes_pictures_and_summary(tmp_path):
    path = tmp_path / "ico.obj"
    trimesh.creation.icosphere(2).export(path)
    out = tmp_path / "out"
    assert main(["atlas", str(path), "--resolution", "128", "--out", str(out)]) == 0
    for name in ("position.png", "normal.png", "charts.png", "distortion.png", "summary.json"):
        assert (out / name).stat().st_size > 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["diagnostics"]["charts"] > 1 and summary["settings"]["resolution"] == 128


def test_demo_runs_on_the_built_in_mesh(tmp_path):
    assert main(["demo", "--resolution", "256", "--out", str(tmp_path)]) == 0
    summary = json.loads((tmp_path / "atlas" / "summary.json").read_text())
    assert summary["diagnostics"]["charts"] == 13


def test_errors_exit_with_status_2_and_a_message(tmp_path, capsys):
    assert main(["atlas", str(tmp_path / "missing.obj"), "--out", str(tmp_path)]) == 2
    assert main(["atlas", str(tmp_path / "missing.obj"), "--resolution", "0"]) == 2
    with pytest.raises(SystemExit):
        main(["atlas"])
