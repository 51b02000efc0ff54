"""uvfeat batch on Dask: 20 generated meshes (2 corrupt) and a 48-frame animation on a local
cluster of 2 worker processes give the files of the serial commands; a killed worker loses no
mesh; an interrupted run resumes without recomputing what it finished. Inputs, folders and bad
options without a cluster."""

import os
import pathlib
import signal

import numpy as np
import pytest
import trimesh

import uvfeat
from uvfeat.batch.inputs import MemoryMesh, batch_inputs, discover, output_folders
from uvfeat.cli import main
from uvfeat.errors import InvalidParameterError, MeshFileError

distributed = pytest.importorskip("distributed")
pyarrow_parquet = pytest.importorskip("pyarrow.parquet")

SETTINGS = ["--radius", "5%", "--resolution", "256", "--compute-resolution", "64", "--samples", "32"]
OPTIONS = dict(resolution=256, compute_resolution=64, samples=32)
CORRUPT = {"nan.obj": "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
           "truncated.ply": "ply\nformat ascii 1.0\nelement vertex 30\nproperty float x\nend_header\n0\n"}


@pytest.fixture(scope="module")
def meshes(tmp_path_factory) -> pathlib.Path:
    """18 small tori of different shapes (PLY without UVs: an automatic atlas) and 2 corrupt files."""
    folder = tmp_path_factory.mktemp("meshes")
    for k in range(18):
        torus = uvfeat.shapes.torus(2.0, 0.4 + 0.05 * (k % 6), 32 + 4 * (k // 6), 16)
        trimesh.Trimesh(torus.positions, torus.faces, process=False).export(folder / f"torus_{k:02d}.ply")
    for name, text in CORRUPT.items():
        (folder / name).write_text(text)
    return folder


@pytest.fixture(scope="module")
def serial(meshes, tmp_path_factory) -> pathlib.Path:
    """``uvfeat compute`` on every good mesh, one after the other in this process."""
    out = tmp_path_factory.mktemp("serial")
    for path in sorted(meshes.glob("torus_*.ply")):
        assert main(["compute", str(path), *SETTINGS, "--out", str(out / path.stem)]) == 0
    return out


@pytest.fixture(scope="module")
def client():
    """A local cluster of 2 worker processes on the loopback interface, always closed."""
    from uvfeat.batch.cluster import local_cluster

    with local_cluster(2, dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        client.wait_for_workers(2, timeout=120)
        yield client


def test_local_workers_keep_the_engine_threads_and_glibcs_own_memory_tuning(client):
    """Dask's nannies set MALLOC_TRIM_THRESHOLD_, which fixes glibc's mmap threshold and made a
    worker 22 % slower per mesh than one process (docs/BENCHMARKS.md); local workers go without."""
    import os

    environments = client.run(lambda: {k: os.environ.get(k) for k in ("MALLOC_TRIM_THRESHOLD_", "RAYON_NUM_THREADS")})
    assert len(environments) == 2
    for environment in environments.values():
        assert environment["MALLOC_TRIM_THRESHOLD_"] is None
        assert int(environment["RAYON_NUM_THREADS"]) >= 1


def assert_same_files(computed: pathlib.Path, serial: pathlib.Path) -> None:
    numeric = sorted(p.name for p in serial.iterdir() if p.suffix in (".npz", ".npy"))
    assert numeric and numeric == sorted(p.name for p in computed.iterdir() if p.suffix in (".npz", ".npy"))
    for name in numeric:
        a, b = np.load(computed / name), np.load(serial / name)
        if name.endswith(".npz"):
            assert sorted(a.files) == sorted(b.files)
            for key in a.files:
                np.testing.assert_array_equal(a[key], b[key], err_msg=f"{name}: {key}")
        else:
            np.testing.assert_array_equal(a, b, err_msg=name)


def read_table(out: pathlib.Path) -> dict[str, dict]:
    rows = pyarrow_parquet.read_table(out / "batch.parquet").to_pylist()
    return {pathlib.Path(row["path"]).name: row for row in rows}


def test_twenty_meshes_on_two_workers_give_the_serial_files_and_report_the_corrupt_ones(
        meshes, serial, client, tmp_path):
    assert client.scheduler.address.startswith("tcp://127.0.0.1:") and len(client.nthreads()) == 2
    assert set(client.run(lambda: os.environ["RAYON_NUM_THREADS"]).values()) == {str(max(1, os.cpu_count() // 2))}
    out = tmp_path / "run"
    assert main(["batch", str(meshes), *SETTINGS, "--scheduler", client.scheduler.address, "--out", str(out)]) == 1
    rows = read_table(out)
    assert len(rows) == 20
    assert rows["nan.obj"]["status"] == "failed" and rows["nan.obj"]["error"].startswith("InvalidMeshError: vertex 0")
    assert rows["truncated.ply"]["status"] == "failed" and rows["truncated.ply"]["error"].startswith("MeshFileError")
    for path in sorted(meshes.glob("torus_*.ply")):
        row = rows[path.name]
        assert row["status"] == "computed" and row["error"] is None
        assert row["faces"] == trimesh.load(path, process=False).faces.shape[0] and row["charts"] >= 1
        low, high = row["mean_curvature_r5pct_min"], row["mean_curvature_r5pct_max"]
        values = np.load(serial / path.stem / "per_vertex_r5pct.npz")["mean_curvature"]
        assert (low, high) == pytest.approx((values.min(), values.max()))
        assert_same_files(out / path.stem, serial / path.stem)
        assert not list((out / path.stem).glob("*.png"))  # no pictures unless asked
    csv = (out / "batch.csv").read_text().splitlines()
    assert len(csv) == 21 and csv[0].startswith('"path","output","status","error"')


def test_a_48_frame_animation_on_two_workers_gives_the_serial_files(client, tmp_path):
    torus = uvfeat.shapes.torus(2.0, 0.5, 32, 16)
    mesh = tmp_path / "torus.ply"
    trimesh.Trimesh(torus.positions, torus.faces, process=False).export(mesh)
    rest = uvfeat.load(mesh).positions
    squash = 1.0 + 0.5 * np.sin(np.linspace(0, 2 * np.pi, 48))
    np.save(tmp_path / "frames.npy", rest[None] * np.stack([squash, 1 / squash, np.ones(48)], axis=1)[:, None])
    command = ["animate", str(mesh), "--frames", str(tmp_path / "frames.npy"), *SETTINGS]
    assert main(command + ["--out", str(tmp_path / "serial")]) == 0
    assert main(command + ["--out", str(tmp_path / "cluster"), "--scheduler", client.scheduler.address,
                           "--frames-per-task", "10"]) == 0
    assert len(list((tmp_path / "cluster").glob("frame_*.npz"))) == 48
    assert_same_files(tmp_path / "cluster", tmp_path / "serial")
    for picture in ["mean_curvature.gif", "mean_curvature_3d.gif", *(f"mean_curvature_{k:04d}.png" for k in (0, 47))]:
        assert (tmp_path / "cluster" / picture).read_bytes() == (tmp_path / "serial" / picture).read_bytes()


def test_bad_cluster_settings_of_an_animation_are_refused_before_any_cluster_starts(tmp_path):
    from uvfeat.batch.frames import animate_on_cluster

    for settings in (dict(frames_per_task=0), dict(frames_per_task=-1), dict(workers=0)):
        with pytest.raises(InvalidParameterError, match="positive"):
            animate_on_cluster("mesh.glb", ["mean_curvature"], "2%", {}, str(tmp_path), 10, **settings)


def test_pictures_when_asked_and_a_rerun_asking_for_them_recomputes(meshes, client, tmp_path):
    inputs = tmp_path / "in"
    inputs.mkdir()
    for path in sorted(meshes.glob("torus_*.ply"))[:2]:
        (inputs / path.name).write_bytes(path.read_bytes())
    out = tmp_path / "run"

    def run(**settings):
        table = uvfeat.batch(inputs, "mean_curvature", "5%", client=client, out=out, **OPTIONS, **settings)
        return sorted(table.column("status").to_pylist())

    assert run() == ["computed"] * 2 and not list(out.rglob("*.png"))
    assert run(pictures=True) == ["computed"] * 2  # finished, but without the pictures asked for now
    for folder in (out / p.stem for p in inputs.iterdir()):
        assert (folder / "mean_curvature_3d.png").exists() and (folder / "mean_curvature_r5pct.png").exists()
    assert run(pictures=True) == ["skipped"] * 2
    assert run() == ["skipped"] * 2


class Interrupted(Exception):
    pass


def test_a_killed_worker_loses_no_mesh_and_an_interrupted_run_resumes(meshes, serial, client, tmp_path):
    out = tmp_path / "run"
    before = client.run(os.getpid)
    killed = []

    def kill_a_worker(row):
        if not killed:
            killed.append(next(iter(before.values())))
            os.kill(killed[0], signal.SIGKILL)

    table = uvfeat.batch(meshes, "mean_curvature", "5%", client=client, out=out, on_row=kill_a_worker, **OPTIONS)
    assert killed and table.num_rows == 20
    statuses = {row["path"]: row["status"] for row in table.to_pylist()}
    assert sorted(statuses.values()).count("computed") == 18
    for path in meshes.glob("torus_*.ply"):
        assert_same_files(out / path.stem, serial / path.stem)
    client.wait_for_workers(2, timeout=120)
    assert killed[0] not in client.run(os.getpid).values()  # the nanny started a new worker process

    resumed = tmp_path / "resumed"
    finished = []

    def interrupt(row):
        finished.append(row)
        if len(finished) == 6:
            raise Interrupted

    with pytest.raises(Interrupted):
        uvfeat.batch(meshes, "mean_curvature", "5%", client=client, out=resumed, on_row=interrupt, **OPTIONS)
    done = {pathlib.Path(row["path"]).stem for row in finished if row["status"] == "computed"}
    assert len(read_table(resumed)) >= 6 and done
    written = {stem: (resumed / stem / "summary.json").stat().st_mtime_ns for stem in done}
    rows = {pathlib.Path(r["path"]).stem: r for r in
            uvfeat.batch(meshes, "mean_curvature", "5%", client=client, out=resumed, **OPTIONS).to_pylist()}
    assert len(rows) == 20 and all(rows[stem]["status"] == "skipped" for stem in done)
    assert {stem: (resumed / stem / "summary.json").stat().st_mtime_ns for stem in done} == written
    assert sum(r["status"] in ("computed", "skipped") for r in rows.values()) == 18
    for path in meshes.glob("torus_*.ply"):
        assert_same_files(resumed / path.stem, serial / path.stem)
    forced = uvfeat.batch(meshes, "mean_curvature", "5%", client=client, out=resumed, force=True, **OPTIONS)
    assert sorted(forced.column("status").to_pylist()).count("computed") == 18
    changed = uvfeat.batch(meshes, "mean_curvature", "5%", client=client, out=resumed, **dict(OPTIONS, seed=1))
    assert "skipped" not in changed.column("status").to_pylist()  # other settings: nothing is finished


def test_meshes_in_memory_run_beside_files_and_resume_by_their_arrays(meshes, serial, client, tmp_path):
    path = sorted(meshes.glob("torus_*.ply"))[0]
    loaded = trimesh.load(path, process=False)
    held = [str(path), loaded, uvfeat.Mesh(loaded.vertices, loaded.faces, name="as uvfeat.Mesh"),
            (np.asarray(loaded.vertices), np.asarray(loaded.faces))]
    out = tmp_path / "run"

    def run(inputs, **settings):
        return {row["path"]: row for row in
                uvfeat.batch(inputs, "mean_curvature", "5%", client=client, out=out, **OPTIONS, **settings).to_pylist()}

    rows = run(held)
    labels = [str(path), "mesh_1 (in memory)", "as uvfeat.Mesh (in memory)", "mesh_3 (in memory)"]
    assert sorted(rows) == sorted(labels) and all(row["status"] == "computed" for row in rows.values())
    for label in labels:  # the same arrays give the serial command's files, wherever they come from
        assert_same_files(pathlib.Path(rows[label]["output"]), serial / path.stem)
    assert {pathlib.Path(row["output"]).parent for row in rows.values()} == {out}
    assert all(row["status"] == "skipped" for row in run(held).values())
    moved = uvfeat.Mesh(loaded.vertices * 1.5, loaded.faces, name="as uvfeat.Mesh")
    again = run({"as uvfeat.Mesh": moved, "mesh_3": held[3]})
    assert again["as uvfeat.Mesh (in memory)"]["status"] == "computed" and again["mesh_3 (in memory)"]["status"] == "skipped"


def test_a_mesh_whose_workers_keep_dying_becomes_a_failed_row_with_the_cause(client, tmp_path):
    from uvfeat.batch.cluster import run_tasks
    from uvfeat.batch.run import _lost
    from uvfeat.files.feature_files import FeatureJob

    def dies_with_its_worker(*call):  # as a worker out of memory or killed from outside
        os._exit(9)

    before = set(client.run(os.getpid).values())
    job = FeatureJob(features="mean_curvature", radii="5%", **OPTIONS)
    calls = [("poison", "poison.obj", str(tmp_path / "poison"), job, {})]
    (index, row), = list(run_tasks(client, dies_with_its_worker, calls,
                                   lambda call, error: dict(_lost(call, error), error_type=type(error))))
    assert index == 0 and row["status"] == "failed" and row["path"] == "poison"
    assert row["error_type"] is distributed.KilledWorker and "workers computing it died" in row["error"]
    client.wait_for_workers(2, timeout=120)
    assert not before & set(client.run(os.getpid).values())  # each worker that took it died and was replaced


def test_inputs_are_files_folders_and_patterns_each_once(tmp_path):
    for name in ("a/x.obj", "a/b/y.ply", "a/b/y.stl", "c/z.off", "a/notes.txt"):
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text("")
    found = discover([tmp_path / "a", str(tmp_path / "c" / "*.off"), tmp_path / "a" / "x.obj"])
    assert [pathlib.Path(p).relative_to(tmp_path).as_posix() for p in found] == \
        ["a/x.obj", "a/b/y.ply", "a/b/y.stl", "c/z.off"]
    assert sorted(output_folders(found).values()) == ["a/b/y_ply", "a/b/y_stl", "a/x", "c/z"]
    with pytest.raises(MeshFileError, match="no such file or folder"):
        discover([tmp_path / "missing.obj"])
    with pytest.raises(MeshFileError, match="no file matches"):
        discover([str(tmp_path / "*.glb")])
    (tmp_path / "empty").mkdir()
    with pytest.raises(InvalidParameterError, match="no mesh files"):
        discover([tmp_path / "empty"])


def test_odd_mesh_names_write_only_inside_the_run_folder(tmp_path):
    names = ["in/my scan.obj", "in/tête à tête.ply", "in/..hidden.obj", "in/a..b.obj", "in/sub/../up.off",
             "in/$(rm -rf).stl", "in/x.obj", "in/x.ply"]
    for name in names:
        path = tmp_path / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text("")
    found = discover([tmp_path / "in"])
    out = tmp_path / "run"
    folders = output_folders(found)
    assert len(set(folders.values())) == len(found) == len(names)
    held = batch_inputs({name: uvfeat.shapes.plane(4, 4) for name in ("..", "../up", "a/b", "C:\\x", ".", "")})
    assert all(isinstance(item, MemoryMesh) for item in held)
    folders |= output_folders(held)
    assert len(set(folders.values())) == len(found) + len(held)
    for folder in folders.values():
        inside = os.path.normpath(out / folder)
        assert inside.startswith(str(out) + os.sep) and ".." not in pathlib.Path(folder).parts, folder


def test_a_killed_writer_leaves_no_half_file_and_the_rerun_clears_its_leftovers(tmp_path):
    from uvfeat.io import atomic_file

    target = tmp_path / "values.npy"
    with pytest.raises(RuntimeError), atomic_file(target) as partial:
        pathlib.Path(partial).write_bytes(b"half a file")
        raise RuntimeError("killed while writing")
    assert not target.exists() and list(tmp_path.iterdir()) == []
    (tmp_path / "values.partial-12345.npy").write_bytes(b"left by a killed process")
    assert main(["compute", str(uvfeat.examples.spot_path()), "--radius", "20%", "--resolution", "64", "--compute-resolution", "32",
                 "--samples", "16", "--out", str(tmp_path)]) == 0
    assert not list(tmp_path.glob("*.partial-*")) and (tmp_path / "summary.json").exists()


def test_bad_options_are_named_before_any_cluster_starts(tmp_path, capsys):
    with pytest.raises(InvalidParameterError, match="unknown option"):
        uvfeat.batch(tmp_path, "mean_curvature", "2%", smaples=32)
    with pytest.raises(InvalidParameterError, match="unknown feature"):
        uvfeat.batch(tmp_path, "curvy", "2%")
    assert main(["batch", str(tmp_path / "nothing.obj"), "--out", str(tmp_path)]) == 2
    assert "no such file or folder" in capsys.readouterr().err
    assert main(["batch", str(tmp_path), "--workers", "0"]) == 2
    assert "workers must be a positive number" in capsys.readouterr().err
