"""Sampler speed (issue 12): the fast path against the exact path and the object-space reference,
measured in one run on the 102,400-face torus with one chart (lat-long) and with an xatlas atlas.

    .venv/bin/python benches/bench_sampler.py [--radii 2,4,16] [--exact-radii 4] [--samples 256]

Default configuration: 1024² buffers, 512² computation texture, 256 samples, H + K. Prints wall
and CPU time (process time, all threads) per computation, CPU ns per drawn sample, and the ratios
fast / exact and reference / fast. RAYON_NUM_THREADS caps the threads.
"""

from __future__ import annotations

import argparse
import os
import time
import warnings

import numpy as np

import uvfeat

FEATURES = ["mean_curvature", "gaussian_curvature"]


def timed(fn):
    wall, cpu = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - wall, time.process_time() - cpu


def tori() -> list[uvfeat.Mesh]:
    t = uvfeat.shapes.torus(2.0, 0.5, 320, 160)
    single = uvfeat.Mesh(t.positions, t.faces, uvs=t.uvs, uv_faces=t.uv_faces, name="torus 102K, lat-long (1 chart)")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        multi = uvfeat.Mesh(t.positions, t.faces, name="torus 102K, xatlas").with_atlas()
    return [single, multi]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--radii", default="2,4,16", help="radii in %% of the diagonal (fast path)")
    parser.add_argument("--exact-radii", default="4", help="radii where the exact path and the reference run too")
    parser.add_argument("--samples", type=int, default=256)
    args = parser.parse_args()
    threads = os.environ.get("RAYON_NUM_THREADS", str(os.cpu_count()))
    print(f"{threads} threads; 1024² buffers, 512² texels x {args.samples} samples, {' + '.join(FEATURES)}")
    exact_radii = {float(r) for r in args.exact_radii.split(",") if r}
    print(f"| mesh | charts | r % | path | wall ms | CPU ms | CPU ns / sample | ratio |")
    print("|---|---|---|---|---|---|---|---|")
    for mesh in tori():
        atlas = uvfeat.Atlas(mesh, 1024)
        for radius in (float(r) for r in args.radii.split(",")):
            r = f"{radius:g}%"
            maps, wall, cpu = timed(lambda: atlas.compute(FEATURES, r, samples=args.samples))
            drawn = maps[FEATURES[0]].summary["texels"] * args.samples
            row = f"| {mesh.name} | {mesh.n_charts} | {radius:g} |"
            print(f"{row} fast | {1e3 * wall:.0f} | {1e3 * cpu:.0f} | {1e9 * cpu / drawn:.1f} | |", flush=True)
            if radius not in exact_radii:
                continue
            exact, e_wall, e_cpu = timed(lambda: atlas.compute(FEATURES, r, samples=args.samples, sampling="exact"))
            print(f"{row} exact | {1e3 * e_wall:.0f} | {1e3 * e_cpu:.0f} | {1e9 * e_cpu / drawn:.1f} | "
                  f"exact / fast {e_wall / wall:.2f}x |", flush=True)
            h_fast, h_exact = maps[FEATURES[0]].per_vertex(), exact[FEATURES[0]].per_vertex()
            spread = np.percentile(h_exact, 99) - np.percentile(h_exact, 1)
            print(f"{row} fast vs exact per-vertex H | mean |diff| / range {np.mean(np.abs(h_fast - h_exact)) / spread:.2e} | | | |")
            reference = uvfeat.reference.Reference(mesh)
            _, r_wall, r_cpu = timed(lambda: reference.compute(FEATURES, r))
            print(f"{row} object-space reference | {1e3 * r_wall:.0f} | {1e3 * r_cpu:.0f} | | "
                  f"reference / fast {r_wall / wall:.2f}x |", flush=True)


if __name__ == "__main__":
    main()
