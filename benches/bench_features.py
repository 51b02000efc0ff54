"""Benchmark of the feature pipeline: its stages, and its time against the radius and the samples.

    .venv/bin/python benches/bench_features.py [--mesh PATH] [--feature mean_curvature] [--method fit]

Default configuration (DESIGN.md §1.10): 1024² geometry buffers, 512² computation texture, 256 samples.
Prints ms per stage and in total, then the time against the radius (1–16 % of the diagonal) and
against the number of samples (64–400). Without --mesh it uses a 102,400-triangle torus with an
xatlas multi-chart atlas. RAYON_NUM_THREADS caps the threads.
"""

from __future__ import annotations

import argparse
import os
import time
import warnings

import uvfeat


def timed(fn):
    """``fn()``, its wall milliseconds and its CPU milliseconds (process time of all threads)."""
    started, cpu = time.perf_counter(), time.process_time()
    out = fn()
    return out, 1e3 * (time.perf_counter() - started), 1e3 * (time.process_time() - cpu)


def benchmark_mesh(path: str | None) -> uvfeat.Mesh:
    """The mesh file at ``path``, or the 102,400-triangle torus with an xatlas atlas."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if path:
            return uvfeat.load(path)
        torus = uvfeat.shapes.torus(2.0, 0.5, 320, 160)
        return uvfeat.Mesh(torus.positions, torus.faces, name="torus 102K (xatlas)").with_atlas(method="xatlas")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--mesh", default=None)
    parser.add_argument("--feature", default="mean_curvature")
    parser.add_argument("--radii", default="1%,2%,4%,8%,16%")
    parser.add_argument("--samples", default="64,100,256,400")
    parser.add_argument("--method", choices=("integral", "fit"), default="integral", help="curvature estimators")
    args = parser.parse_args()

    mesh = benchmark_mesh(args.mesh)
    _, pre_ms, _ = timed(lambda: mesh.topology)
    threads = os.environ.get("RAYON_NUM_THREADS", str(os.cpu_count()))
    print(f"{mesh.name}: {mesh.n_faces} faces, {mesh.n_charts} charts; {threads} threads; feature {args.feature}, method {args.method}")
    atlas, raster_ms, _ = timed(lambda: uvfeat.Atlas(mesh, 1024))
    _, frame_ms, _ = timed(lambda: atlas.update(mesh.positions))
    maps, features_ms, features_cpu = timed(lambda: atlas.compute(args.feature, "4%", method=args.method))
    _, vertex_ms, _ = timed(lambda: maps[args.feature].per_vertex())
    print("\ndefault configuration, r = 4 % of the diagonal")
    print(f"  pre-processing (once)      {pre_ms:9.1f} ms")
    print(f"  rasterisation (once)       {raster_ms - frame_ms:9.1f} ms")
    print(f"  buffers per frame          {frame_ms:9.1f} ms")
    print(f"  features 512² x 256        {features_ms:9.1f} ms (CPU {features_cpu:.0f} ms)")
    print(f"  per-vertex lookup          {vertex_ms:9.1f} ms")
    print(f"  per frame (buffers + features + per-vertex) {frame_ms + features_ms + vertex_ms:9.1f} ms")

    print("\nradius sweep (256 samples)")
    print(f"  {'radius':>8}{'ms':>10}{'CPU ms':>10}{'valid/texel':>13}{'missing %':>11}")
    for radius in args.radii.split(","):
        maps, ms, cpu = timed(lambda: atlas.compute(args.feature, radius, method=args.method))
        s = maps[args.feature].summary
        print(f"  {radius:>8}{ms:>10.1f}{cpu:>10.0f}{s['mean_valid_samples']:>13.1f}{100 * s['missing_fraction']:>11.3f}")

    print("\nsample sweep (r = 4 %)")
    print(f"  {'samples':>8}{'ms':>10}{'CPU ms':>10}{'ms/sample':>11}")
    for n in (int(x) for x in args.samples.split(",")):
        _, ms, cpu = timed(lambda: atlas.compute(args.feature, "4%", samples=n, method=args.method))
        print(f"  {n:>8}{ms:>10.1f}{cpu:>10.0f}{ms / n:>11.2f}")


if __name__ == "__main__":
    main()
