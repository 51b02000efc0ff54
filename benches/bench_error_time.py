"""Error against time as the samples grow: where the default number of samples sits.

    .venv/bin/python benches/bench_error_time.py [--radius 4] [--samples 32,64,100,128,200,256,400]

On the 102,400-face torus (single lat-long chart and an xatlas atlas), default configuration
otherwise (1024² buffers, 512² computation texture, H + K): the shared lattice (default), and the
per-texel fast path with full and with two-stage adaptive sampling (tau = 0.01). For each run:
wall and CPU time, and the per-vertex error of H and K (%AE = mean |x - truth| / (p99 - p1) of
truth, DESIGN.md §5.1) against
- a converged run of the per-texel estimator (4,096 samples, fast path), the value every sampler
  converges to: the sampling error alone, which is what the number of samples controls;
- the analytic torus: noise plus the estimator's bias at this radius, which no sample count removes.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import uvfeat
from bench_sampler import tori  # the same two tori, run from this folder

FEATURES = ["mean_curvature", "gaussian_curvature"]


def percent_ae(values: np.ndarray, truth: np.ndarray) -> float:
    ok = np.isfinite(values) & np.isfinite(truth)
    q1, q99 = np.percentile(truth[ok], [1, 99])
    return 100.0 * float(np.mean(np.abs(values[ok] - truth[ok]))) / (q99 - q1)


def torus_truth(positions: np.ndarray, major: float = 2.0, minor: float = 0.5) -> tuple[np.ndarray, np.ndarray]:
    cos_v = np.clip((np.hypot(positions[:, 0], positions[:, 1]) - major) / minor, -1.0, 1.0)
    h = (major + 2 * minor * cos_v) / (2 * minor * (major + minor * cos_v))
    k = cos_v / (minor * (major + minor * cos_v))
    return h, k


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--radius", type=float, default=4.0, help="radius in %% of the diagonal")
    parser.add_argument("--samples", default="32,64,100,128,200,256,400")
    parser.add_argument("--converged", type=int, default=4096, help="samples of the converged run")
    args = parser.parse_args()
    radius = f"{args.radius}%"
    print(f"r = {radius} of the diagonal, 1024² buffers, 512² computation texture, H + K")
    print("| mesh | samples | sampling | wall ms | CPU ms | H %AE noise | K %AE noise | H %AE truth | K %AE truth |")
    print("|---|---|---|---|---|---|---|---|---|")
    for mesh in tori():
        atlas = uvfeat.Atlas(mesh, 1024)
        truth_h, truth_k = torus_truth(mesh.positions)
        converged = atlas.compute(FEATURES, radius, samples=args.converged, sampling="fast")
        converged_h, converged_k = (converged[f].per_vertex() for f in FEATURES)
        for samples in (int(x) for x in args.samples.split(",")):
            for sampling, adaptive in (("shared", False), ("fast", False), ("fast", True)):
                wall, cpu = time.perf_counter(), time.process_time()
                maps = atlas.compute(FEATURES, radius, samples=samples, adaptive=adaptive, sampling=sampling)
                wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
                h, k = (maps[f].per_vertex() for f in FEATURES)
                name = sampling + (", adaptive" if adaptive else "")
                print(f"| {mesh.name} | {samples} | {name} | {1e3 * wall:.0f} | {1e3 * cpu:.0f} "
                      f"| {percent_ae(h, converged_h):.3f} | {percent_ae(k, converged_k):.3f} "
                      f"| {percent_ae(h, truth_h):.3f} | {percent_ae(k, truth_k):.3f} |", flush=True)


if __name__ == "__main__":
    main()
