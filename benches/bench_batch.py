"""Benchmark of ``uvfeat batch``: meshes per minute on a local Dask cluster of 1 and 2
worker processes, against the same work on each mesh in turn in one process (all in the same
run), and the peak memory of one worker per million faces and buffer size.

    .venv/bin/python benches/bench_batch.py [--meshes FOLDER] [--compute-resolution 256] [--samples 64]

Meshes: the OBJ files of ../shared/meshes when present, else 8 generated tori of 20K-80K
triangles. Their xatlas atlases are built once before the timed runs (they are cached on disk, as
a re-run of a dataset would find them). A worker process runs one mesh at a time with
RAYON_NUM_THREADS = cores // workers, so every run uses every core.
"""

from __future__ import annotations

import argparse
import os
import pathlib
import subprocess
import sys
import tempfile
import time

import uvfeat
from uvfeat.files.feature_files import FeatureJob, load_with_notes, write_feature_files

REPO = pathlib.Path(__file__).resolve().parents[1]
SHARED = REPO.parent / "shared" / "meshes"


def bench_meshes(folder: pathlib.Path | None, scratch: pathlib.Path) -> list[str]:
    if folder and folder.is_dir():
        return sorted(str(p) for p in folder.glob("*.obj"))
    import trimesh

    paths = []
    for k in range(8):
        torus = uvfeat.shapes.torus(2.0, 0.5, 100 + 20 * k, 100 + 20 * k)
        paths.append(str(scratch / f"torus_{k}.ply"))
        trimesh.Trimesh(torus.positions, torus.faces, process=False).export(paths[-1])
    return paths


def peak_memory_mib(faces: int, resolution: int) -> tuple[float, float]:
    """Peak resident memory of a fresh process after importing uvfeat, and after doing one mesh's
    work (atlas, features, per-vertex values, files) on a torus of ``faces`` triangles at
    ``resolution``² buffers."""
    n = int((faces / 2) ** 0.5)
    script = ("import resource, tempfile, uvfeat; from uvfeat.files.feature_files import FeatureJob, write_feature_files; "
              "peak = lambda: resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024; print(peak()); "
              f"m = uvfeat.shapes.torus(2.0, 0.5, {2 * n}, {n // 2}); "
              f"job = FeatureJob(('mean_curvature',), ('2%',), samples=16, compute_resolution=128, "
              f"resolution={resolution}, pictures=False); "
              "write_feature_files(m, job, tempfile.mkdtemp(), [], 0.0); print(peak())")
    done = subprocess.run([sys.executable, "-c", script], check=True, capture_output=True, text=True)
    return tuple(float(line) for line in done.stdout.split())


def main_() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--meshes", type=pathlib.Path, default=SHARED)
    parser.add_argument("--compute-resolution", type=int, default=256)
    parser.add_argument("--samples", type=int, default=64)
    parser.add_argument("--skip-memory", action="store_true")
    args = parser.parse_args()
    job = FeatureJob(("mean_curvature",), ("2%",), compute_resolution=args.compute_resolution, samples=args.samples,
                     pictures=False)
    with tempfile.TemporaryDirectory() as scratch:
        scratch = pathlib.Path(scratch)
        meshes = bench_meshes(args.meshes, scratch)
        for path in meshes:  # xatlas once, cached for every run below
            uvfeat.load(path)
        print(f"{len(meshes)} meshes, {os.cpu_count()} cores, r = 2 %, {args.compute_resolution}² x {args.samples}")
        started = time.perf_counter()
        for k, path in enumerate(meshes):  # the work of a batch task, without Dask
            mesh, notes = load_with_notes(path, job.uv, job.resolution, job.strict_uv)
            write_feature_files(mesh, job, str(scratch / "serial" / str(k)), notes, time.perf_counter())
        serial = time.perf_counter() - started
        print(f"one mesh after the other in one process: {serial:.1f} s, {60 * len(meshes) / serial:.1f} meshes/min")
        for workers in (1, 2):
            begun = []
            started = time.perf_counter()
            table = uvfeat.batch(meshes, job.features, job.radii, out=str(scratch / f"w{workers}"), workers=workers,
                                 compute_resolution=job.compute_resolution, samples=job.samples,
                                 on_start=lambda n, client: begun.append(time.perf_counter()))
            ended = time.perf_counter()
            rows = table.to_pylist()
            per_mesh = sum(r["total_s"] for r in rows) / len(rows)
            running = ended - begun[0]
            print(f"uvfeat.batch, {workers} worker(s): {ended - started:.1f} s with the cluster's start, "
                  f"{running:.1f} s from the first task: {60 * len(meshes) / running:.1f} meshes/min "
                  f"({serial / running:.2f}x the serial loop); mean time per mesh in a worker {per_mesh:.2f} s; "
                  f"statuses {sorted({r['status'] for r in rows})}")
    if not args.skip_memory:
        for faces, resolution in ((250_000, 1024), (1_000_000, 1024), (1_000_000, 2048)):
            imported, peak = peak_memory_mib(faces, resolution)
            print(f"peak memory, {faces:,} faces, {resolution}² buffers: {peak:.0f} MiB ({imported:.0f} MiB after "
                  "import uvfeat)")


if __name__ == "__main__":
    main_()
