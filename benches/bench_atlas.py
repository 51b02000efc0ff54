"""Benchmark of buffer generation (issue: foundation): pre-processing once, then ms per frame.

    .venv/bin/python benches/bench_atlas.py [--resolution 1024] [--repeat 20] [--mesh PATH ...]

Without --mesh it runs a ~100K-triangle analytic torus (single chart with self-adjacent seams)
and its xatlas multi-chart version, plus the shared Stanford dragon (100K triangles) when
../shared/meshes is present. Times are wall-clock medians on this machine; RAYON_NUM_THREADS
caps the threads.
"""

from __future__ import annotations

import argparse
import os
import pathlib
import statistics
import time
import warnings

import numpy as np

import uvfeat


def bench(mesh: uvfeat.Mesh, resolution: int, repeat: int) -> dict:
    started = time.perf_counter()
    topology = mesh.topology
    preprocessing = time.perf_counter() - started
    started = time.perf_counter()
    atlas = uvfeat.Atlas(mesh, resolution)
    first = time.perf_counter() - started
    rng = np.random.default_rng(0)
    frames = []
    for _ in range(repeat):
        moved = mesh.positions + rng.normal(scale=1e-4, size=mesh.positions.shape)
        started = time.perf_counter()
        atlas._core.update(moved)  # the core call alone: no NumPy views are materialised
        frames.append(time.perf_counter() - started)
    per_frame = statistics.median(frames)
    return {
        "mesh": mesh.name,
        "faces": mesh.n_faces,
        "charts": topology.n_charts,
        "preprocessing_ms": 1e3 * preprocessing,
        "rasterisation_ms": 1e3 * max(first - per_frame, 0.0),
        "frame_ms": 1e3 * per_frame,
        "frame_min_ms": 1e3 * min(frames),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--resolution", type=int, default=1024)
    parser.add_argument("--repeat", type=int, default=20)
    parser.add_argument("--mesh", nargs="*", default=None)
    args = parser.parse_args()

    meshes = []
    if args.mesh:
        meshes = [uvfeat.load(p) for p in args.mesh]
    else:
        torus = uvfeat.shapes.torus(2.0, 0.5, 320, 160)
        meshes = [torus, uvfeat.Mesh(torus.positions, torus.faces, name="torus (xatlas)").with_atlas(method="xatlas")]
        dragon = pathlib.Path(__file__).resolve().parents[2] / "shared" / "meshes" / "dragon.obj"
        if dragon.exists():
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                meshes.append(uvfeat.load(dragon, uv="xatlas"))
    threads = os.environ.get("RAYON_NUM_THREADS", str(os.cpu_count()))
    print(f"buffer generation at {args.resolution}², {threads} threads, median of {args.repeat} frames")
    print(f"{'mesh':<22}{'faces':>8}{'charts':>8}{'pre-proc ms':>13}{'raster ms':>11}{'frame ms':>10}{'min ms':>8}")
    for mesh in meshes:
        r = bench(mesh, args.resolution, args.repeat)
        print(f"{r['mesh']:<22}{r['faces']:>8}{r['charts']:>8}{r['preprocessing_ms']:>13.1f}"
              f"{r['rasterisation_ms']:>11.1f}{r['frame_ms']:>10.1f}{r['frame_min_ms']:>8.1f}")


if __name__ == "__main__":
    main()
