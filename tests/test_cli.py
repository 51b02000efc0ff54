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
    features = json.loads((tmp_path / "features" / "summary.json").read_text())
    assert features["settings"]["compute_resolution"] == 256 and list(features["radii"]) == ["1%", "4%", "16%"]


def test_the_demo_says_only_what_a_user_can_act_on(tmp_path):
    """Run as users run it: one line per note, none about the built-in mesh's own file, and no
    Python warning format (file, line number, source line)."""
    import re
    import subprocess
    import sys

    run = subprocess.run([sys.executable, "-m", "uvfeat", "demo", "--resolution", "256", "--compute-resolution", "64",
                          "--out", str(tmp_path)], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    lines = (run.stdout + run.stderr).splitlines()
    assert not any(re.search(r"\.py:\d+: \w+Warning", line) for line in lines), lines
    notes = [line for line in lines if line.startswith(("note:", "warning:"))]
    assert len(notes) <= 1 and not any("UVs span" in line for line in notes), notes
    assert all(len(line) < 400 for line in lines) and lines[-1].startswith("wrote ")


def test_errors_exit_with_status_2_and_a_message(tmp_path, capsys):
    assert main(["atlas", str(tmp_path / "missing.obj"), "--out", str(tmp_path)]) == 2
    assert main(["atlas", str(tmp_path / "missing.obj"), "--resolution", "0"]) == 2
    with pytest.raises(SystemExit):
        main(["atlas"])


def test_compute_command_writes_per_vertex_files_maps_and_summary(tmp_path):
    import numpy as np
    import trimesh

    path = tmp_path / "ico.obj"
    trimesh.creation.icosphere(3).export(path)
    out = tmp_path / "out"
    args = ["compute", str(path), "--feature", "mean_curvature,shape_index", "--radius", "10%,0.3",
            "--resolution", "256", "--compute-resolution", "64", "--samples", "64", "--out", str(out)]
    assert main(args) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert set(summary["radii"]) == {"10%", "0.3"}
    data = np.load(out / "per_vertex_r0p3.npz")
    # The unit icosphere's facets, which the default sums, lie inside its sphere: 2 edges across
    # the ball, their H is 1.13 (measured).
    assert abs(np.median(data["mean_curvature"]) - 1.13) < 0.05
    ply = trimesh.load(out / "per_vertex_r10pct.ply", process=False)
    assert len(ply.vertices) == len(data["positions"])
    for name in ("mean_curvature_r10pct.png", "shape_index_r0p3.npy"):
        assert (out / name).stat().st_size > 0
    assert main(["compute", str(path), "--feature", "bogus", "--out", str(out)]) == 2
    assert main(["compute", str(path), "--radius", "-1", "--out", str(out)]) == 2


def test_compute_command_writes_the_default_per_vertex_values_of_many_charts(tmp_path):
    # An icosphere without UVs gets uvfeat's atlas (many charts): its per-vertex files hold
    # `uvfeat.compute`'s values at the vertices; its maps are those values interpolated over the
    # faces where the ball spans 3 face sides (10 %: 4.9 sides), and computed at the texels below
    # (5 %: 2.5 sides); --quadrature pattern computes every map and reads the per-vertex values from them.
    import numpy as np

    import uvfeat
    from uvfeat.options import surfel_resolution

    path = tmp_path / "ico.obj"
    trimesh.creation.icosphere(4).export(path)
    options = ["--feature", "mean_curvature", "--compute-resolution", "64", "--samples", "64"]
    for kind, radii in [("default", "10%"), ("both", "10%,5%"), ("pattern", "10%,5%")]:
        named = ["--quadrature", "pattern"] if kind == "pattern" else []
        assert main(["compute", str(path), *options, "--radius", radii, *named, "--out", str(tmp_path / kind)]) == 0
    mesh = uvfeat.load(str(path))
    assert mesh.n_charts > 1
    # --samples sets the surfels per ball, as in uvfeat.compute.
    expected = uvfeat.compute(mesh, "mean_curvature", "10%", samples=64)["mean_curvature"]
    assert not np.array_equal(expected, uvfeat.compute(mesh, "mean_curvature", "10%")["mean_curvature"])
    # Several radii take the surfel grid of the smallest, as uvfeat.compute.
    beside = uvfeat.compute(mesh, "mean_curvature", ["10%", "5%"], samples=64)["mean_curvature"][0]
    for kind, values in [("default", expected), ("both", beside)]:
        np.testing.assert_array_equal(np.load(tmp_path / kind / "per_vertex_r10pct.npz")["mean_curvature"], values)
    from_maps = np.load(tmp_path / "pattern" / "per_vertex_r10pct.npz")["mean_curvature"]
    assert not np.array_equal(from_maps, expected) and abs(np.median(from_maps) - 1.0) < 0.1

    # One radius: the maps on the sums' own atlas; with a smaller radius beside it, on the 1024² one.
    load = lambda kind, tag: np.load(tmp_path / kind / f"mean_curvature_r{tag}.npy")
    sums_atlas = uvfeat.Atlas(mesh, resolution=surfel_resolution(mesh, "10%", 64))
    np.testing.assert_array_equal(load("default", "10pct"), sums_atlas.vertex_texture(expected, 64))
    np.testing.assert_array_equal(load("both", "10pct"), uvfeat.Atlas(mesh).vertex_texture(beside, 64))
    np.testing.assert_array_equal(load("both", "5pct"), load("pattern", "5pct"))
    baked, pattern_map = load("default", "10pct"), load("pattern", "10pct")
    assert baked.shape == pattern_map.shape == (64, 64) and not np.array_equal(baked, pattern_map)
    assert abs(np.nanmedian(baked) - 1.0) < 0.05 and np.isfinite(baked).mean() > 0.3
    summary = json.loads((tmp_path / "both" / "summary.json").read_text())
    assert summary["radii"]["10%"]["diagnostics"]["maps"].startswith("values at the vertices")
    assert "mean_valid_samples" in summary["radii"]["5%"]["diagnostics"]
    # Named surfels: the values at the vertices too, as uvfeat.compute gives them.
    assert main(["compute", str(path), *options, "--radius", "10%", "--quadrature", "surfels",
                 "--out", str(tmp_path / "surfels")]) == 0
    named = uvfeat.compute(mesh, "mean_curvature", "10%", quadrature="surfels", samples=64)["mean_curvature"]
    np.testing.assert_array_equal(np.load(tmp_path / "surfels" / "per_vertex_r10pct.npz")["mean_curvature"], named)


def test_compute_command_leaves_no_import_thread_behind(tmp_path, capsys, monkeypatch):
    """matplotlib is imported on a thread while the features run; a thread left importing could
    hang a process forked later (batch workers), so the command joins it, even when it fails
    (here the import is slowed down, as on a cold start, so that a thread not joined is caught)."""
    import threading
    import time

    from uvfeat.cli import compute

    monkeypatch.setattr(compute, "import_picture_modules", lambda: time.sleep(1.0))

    path = tmp_path / "ico.obj"
    trimesh.creation.icosphere(2).export(path)
    blocked = tmp_path / "not_a_directory"
    blocked.write_text("a file where the output directory should go")
    options = ["--resolution", "128", "--compute-resolution", "32", "--samples", "32"]
    assert main(["compute", str(path), *options, "--out", str(tmp_path / "out")]) == 0
    assert main(["compute", str(path), *options, "--out", str(blocked / "out")]) == 2
    assert "error: Not a directory" in capsys.readouterr().err
    assert not [t for t in threading.enumerate() if t.name == "uvfeat-import-matplotlib"]


def test_compute_command_with_the_fit_saves_principal_directions(tmp_path):
    import numpy as np

    path = tmp_path / "ico.obj"
    trimesh.creation.icosphere(3).export(path)
    out = tmp_path / "out"
    args = ["compute", str(path), "--feature", "k1", "--radius", "0.3", "--method", "fit", "--resolution", "256",
            "--compute-resolution", "64", "--samples", "64", "--out", str(out)]
    assert main(args) == 0
    data = np.load(out / "per_vertex_r0p3.npz")
    assert abs(np.median(data["k1"]) - 1.0) < 0.05  # unit icosphere
    assert data["principal_directions"].shape == (len(data["positions"]), 2, 3)
    assert json.loads((out / "summary.json").read_text())["settings"]["method"] == "fit"
    ply = trimesh.load(out / "per_vertex_r0p3.ply", process=False)
    d1 = np.stack([ply.metadata["_ply_raw"]["vertex"]["data"][f"d1_{a}"] for a in "xyz"], -1)
    np.testing.assert_allclose(d1, data["principal_directions"][:, 0], atol=1e-6)
    with_segments = tmp_path / "segments"
    assert main(args[:-1] + [str(with_segments), "--directions", "d1"]) == 0
    assert (with_segments / "k1_r0p3.png").stat().st_size > 0
    integral = [a if a != "fit" else "integral" for a in args[:-1]] + [str(tmp_path / "bad"), "--directions", "d1"]
    assert main(integral) == 2  # the directions need --method fit


def test_compute_and_compare_take_the_surfel_quadrature(tmp_path, capsys):
    import numpy as np

    path = tmp_path / "ico.obj"
    trimesh.creation.icosphere(3).export(path)
    out = tmp_path / "out"
    args = ["compute", str(path), "--feature", "mean_curvature", "--radius", "0.3", "--resolution", "256",
            "--compute-resolution", "64", "--quadrature", "surfels", "--surface", "facets", "--out", str(out)]
    assert main(args) == 0
    settings = json.loads((out / "summary.json").read_text())["settings"]
    assert (settings["quadrature"], settings["surface"]) == ("surfels", "facets")
    # The values at the vertices of the facets, as uvfeat.compute gives them: the polyhedron's,
    # whose vertices lie on the unit sphere and faces inside it (its converged reference: 1.117).
    import uvfeat

    written = np.load(out / "per_vertex_r0p3.npz")["mean_curvature"]
    expected = uvfeat.compute(uvfeat.load(str(path), resolution=256), "mean_curvature", 0.3, resolution=256,
                              quadrature="surfels", surface="facets")["mean_curvature"]
    np.testing.assert_array_equal(written, expected)
    assert abs(np.median(written) - 1.12) < 0.02
    assert main(args[:-2] + ["--adaptive", "--out", str(out)]) == 2  # a quadrature without random samples
    assert "quadrature" in capsys.readouterr().err
    assert main(["compare", str(path), "--radius", "0.3", "--resolution", "256", "--compute-resolution", "64",
                 "--quadrature", "surfels", "--truth-levels", "1", "--no-pictures", "--json"]) == 0


def test_the_program_returns_mains_status_with_the_collector_set_for_a_short_run(tmp_path):
    import gc

    from uvfeat.cli import COLLECT_EVERY, run

    threshold = gc.get_threshold()
    try:
        assert run(["compute", str(tmp_path / "missing.obj"), "--out", str(tmp_path / "out")]) == 2
        assert gc.get_freeze_count() > 0
        assert gc.get_threshold()[0] == COLLECT_EVERY
    finally:
        gc.unfreeze()
        gc.set_threshold(*threshold)
