"""Sampler speed: the shared lattice (default), the per-texel fast path, the exact path
and the object-space reference, measured in one run on the 102,400-face torus with one chart
(lat-long) and with an xatlas atlas.

    .venv/bin/python benches/bench_sampler.py [--radii 2,4,16] [--paths shared,fast] [--exact-radii 4] [--samples 256]

Default configuration: 1024² buffers, 512² computation texture, 256 samples, H + K. Prints wall
and CPU time (process time, all threads) per computation, CPU ns per drawn sample (texels x N),
the per-vertex error of H and K against the analytic torus (mean absolute error in % of the mean
|truth|), the ratio of each path to the shared lattice, and per path time(largest r) /
time(smallest r). RAYON_NUM_THREADS caps the threads.
"""

from __future__ import annotations

import argparse
import os
import time
import warnings

import numpy as np

import uvfeat

FEATURES = ["mean_curvature", "gaussian_curvature"]
MAJOR, MINOR = 2.0, 0.5


def timed(fn):
    wall, cpu = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - wall, time.process_time() - cpu


def tori() -> list[uvfeat.Mesh]:
    t = uvfeat.shapes.torus(MAJOR, MINOR, 320, 160)
    single = uvfeat.Mesh(t.positions, t.faces, uvs=t.uvs, uv_faces=t.uv_faces, name="torus 102K, lat-long")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        multi = uvfeat.Mesh(t.positions, t.faces, name="torus 102K, xatlas").with_atlas(method="xatlas")
    return [single, multi]


def torus_truth(positions: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Analytic H and K of the torus at `positions`."""
    cos_v = np.clip((np.hypot(positions[:, 0], positions[:, 1]) - MAJOR) / MINOR, -1.0, 1.0)
    ring = MAJOR + MINOR * cos_v
    return (MAJOR + 2 * MINOR * cos_v) / (2 * MINOR * ring), cos_v / (MINOR * ring)


def errors(mesh: uvfeat.Mesh, values: list[np.ndarray]) -> str:
    parts = []
    for name, estimate, truth in zip(("H", "K"), values, torus_truth(np.asarray(mesh.positions))):
        ok = np.isfinite(estimate)
        parts.append(f"{name} {100 * np.mean(np.abs(estimate[ok] - truth[ok])) / np.mean(np.abs(truth[ok])):.2f}")
    return " / ".join(parts)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--radii", default="2,4,16", help="radii in %% of the diagonal")
    parser.add_argument("--paths", default="shared,fast", help="sampling paths run at every radius")
    parser.add_argument("--exact-radii", default="4", help="radii where the exact path and the reference run too")
    parser.add_argument("--samples", type=int, default=256)
    args = parser.parse_args()
    threads = os.environ.get("RAYON_NUM_THREADS", str(os.cpu_count()))
    print(f"{threads} threads; 1024² buffers, 512² texels x {args.samples} samples, {' + '.join(FEATURES)}")
    exact_radii = {float(r) for r in args.exact_radii.split(",") if r}
    radii = [float(r) for r in args.radii.split(",")]
    paths = args.paths.split(",")
    print("| mesh | charts | r % | path | wall ms | CPU ms | CPU ns / sample | H / K error % | ratio to shared (wall) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for mesh in tori():
        atlas = uvfeat.Atlas(mesh, 1024)
        walls: dict[str, list[float]] = {}
        for radius in radii:
            r = f"{radius:g}%"
            row = f"| {mesh.name} | {mesh.n_charts} | {radius:g} |"
            runs = paths + (["exact"] if radius in exact_radii and "exact" not in paths else [])
            baseline = None
            for path in runs:
                maps, wall, cpu = timed(lambda: atlas.compute(FEATURES, r, samples=args.samples, sampling=path))
                drawn = maps[FEATURES[0]].summary["texels"] * args.samples
                baseline = baseline or wall
                walls.setdefault(path, []).append(wall)
                error = errors(mesh, [maps[f].per_vertex() for f in FEATURES])
                print(f"{row} {path} | {1e3 * wall:.0f} | {1e3 * cpu:.0f} | {1e9 * cpu / drawn:.1f} | {error} | "
                      f"{wall / baseline:.2f}x |", flush=True)
            if radius in exact_radii:
                reference = uvfeat.reference.Reference(mesh)
                values, r_wall, r_cpu = timed(lambda: reference.compute(FEATURES, r))
                error = errors(mesh, [values[f] for f in FEATURES])
                print(f"{row} object-space reference | {1e3 * r_wall:.0f} | {1e3 * r_cpu:.0f} | | {error} | "
                      f"{r_wall / baseline:.2f}x |", flush=True)
        for path, times in walls.items():
            if len(times) == len(radii) > 1:
                print(f"{mesh.name}, {path}: time({radii[-1]:g} %) / time({radii[0]:g} %) = {times[-1] / times[0]:.1f}")


if __name__ == "__main__":
    main()
