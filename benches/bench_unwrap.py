"""Meshes without UVs: what the unwrap costs against the features, for uvfeat's own
normal-cone charts at several cone angles and for xatlas with several options, what each atlas
gives in accuracy, and what `uvfeat compute` costs end to end on a first and a second run.

    .venv/bin/python benches/bench_unwrap.py [--mesh PATH] [--radius 2] [--subdivide 1]

Default mesh: the Stanford dragon from the shared meshes (100K faces, no UVs); ``--subdivide 1``
splits every face in four first (400K faces) to reach the size of large scans. For every option
set it prints the unwrap time, the charts, and the per-vertex H of the default configuration at
``--radius`` % of the diagonal against the object-space reference (%AE = mean |x - ref| /
(p99 - p1) of ref), then the end-to-end `uvfeat compute` time of a first run (empty cache) and of
a second run (cached atlas), both in fresh processes.
"""

from __future__ import annotations

import argparse
import os
import pathlib
import subprocess
import sys
import tempfile
import time

import numpy as np
import trimesh

import uvfeat
from uvfeat.unwrap import chart_uvs, xatlas_uvs

REPO = pathlib.Path(__file__).resolve().parents[1]
# (label, unwrapper). xatlas: ChartOptions / PackOptions overrides; max_cost bounds how far a chart
# may grow (xatlas's default 2): larger charts mean fewer seams for the samples to cross.
OPTION_SETS = [
    ("charts 45° (default)", lambda p, f: chart_uvs(p, f)),
    ("charts 60°", lambda p, f: chart_uvs(p, f, max_angle=60.0)),
    ("charts 75°", lambda p, f: chart_uvs(p, f, max_angle=75.0)),
    ("xatlas default", lambda p, f: xatlas_uvs(p, f, cache=False)),
    ("xatlas no chart rotation", lambda p, f: xatlas_uvs(p, f, cache=False, pack_options={"rotate_charts": False})),
    ("xatlas block-aligned packing", lambda p, f: xatlas_uvs(p, f, cache=False, pack_options={"blockAlign": True})),
    ("xatlas brute-force packing", lambda p, f: xatlas_uvs(p, f, cache=False, pack_options={"bruteForce": True})),
    ("xatlas max_cost 4", lambda p, f: xatlas_uvs(p, f, cache=False, chart_options={"max_cost": 4.0})),
    ("xatlas max_cost 8", lambda p, f: xatlas_uvs(p, f, cache=False, chart_options={"max_cost": 8.0})),
]


def percent_ae(values: np.ndarray, truth: np.ndarray) -> float:
    ok = np.isfinite(values) & np.isfinite(truth)
    spread = np.percentile(truth[ok], 99) - np.percentile(truth[ok], 1)
    return 100.0 * float(np.mean(np.abs(values[ok] - truth[ok]))) / spread


def end_to_end(path: pathlib.Path, radius: float, cache: str) -> float:
    with tempfile.TemporaryDirectory() as out:
        command = [sys.executable, "-m", "uvfeat", "compute", str(path), "--feature", "mean_curvature",
                   "--radius", f"{radius}%", "--out", out]
        start = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True, env={**os.environ, "UVFEAT_CACHE_DIR": cache})
        return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--mesh", default=str(REPO.parent / "shared" / "meshes" / "dragon.obj"))
    parser.add_argument("--radius", type=float, default=2.0, help="radius in %% of the diagonal")
    parser.add_argument("--subdivide", type=int, default=0, help="split every face in four this many times")
    parser.add_argument("--skip-options", action="store_true", help="only the end-to-end cache timings")
    parser.add_argument("--only", default="", help="comma-separated parts of the labels of the atlases to run")
    parser.add_argument("--skip-end-to-end", action="store_true", help="only the option sets")
    args = parser.parse_args()

    loaded = trimesh.load(args.mesh, force="mesh", process=False)
    positions, faces = np.asarray(loaded.vertices, dtype=np.float64), np.asarray(loaded.faces, dtype=np.int64)
    for _ in range(args.subdivide):
        positions, faces = trimesh.remesh.subdivide(positions, faces)
    name = f"{pathlib.Path(args.mesh).name} ({len(faces):,} faces)"
    radius = args.radius / 100.0 * float(np.linalg.norm(positions.max(0) - positions.min(0)))
    print(f"{name}, r = {args.radius} % of the diagonal, {os.cpu_count()} CPUs")

    if not args.skip_options:
        reference = uvfeat.reference.compute(uvfeat.Mesh(positions, faces), "mean_curvature", radius)["mean_curvature"]
        print("| atlas | unwrap s | charts | features s | H %AE vs object-space reference |")
        print("|---|---|---|---|---|")
        for label, unwrapper in OPTION_SETS:
            if args.only and not any(part in label for part in args.only.split(",")):
                continue
            start = time.perf_counter()
            uvs, uv_faces = unwrapper(positions, faces)
            unwrap_s = time.perf_counter() - start
            mesh = uvfeat.Mesh(positions, faces, uvs, uv_faces)
            start = time.perf_counter()
            h = uvfeat.compute(mesh, "mean_curvature", radius)["mean_curvature"]
            features_s = time.perf_counter() - start
            print(f"| {label} | {unwrap_s:.2f} | {mesh.n_charts} | {features_s:.1f} | {percent_ae(h, reference):.2f} |",
                  flush=True)

    if args.skip_end_to_end:
        return
    with tempfile.TemporaryDirectory() as folder:
        path = pathlib.Path(folder) / "mesh.ply"
        trimesh.Trimesh(positions, faces, process=False).export(path)
        cache = str(pathlib.Path(folder) / "cache")
        first = end_to_end(path, args.radius, cache)
        second = end_to_end(path, args.radius, cache)
        print(f"uvfeat compute end to end: first run {first:.1f} s, second run (cached atlas) {second:.1f} s")


if __name__ == "__main__":
    main()
