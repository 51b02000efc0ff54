"""The per-vertex defaults on docs/PEERS.md's 200K surfaces without their UVs (uvfeat's own atlas,
tens of charts): the values at the vertices from the surfels (the default on many charts) against
the pattern's maps (the default of one chart), H and K error as in PEERS.md against the analytic
truth, medians of alternating calls.

    .venv/bin/python benches/bench_many_charts.py [--radii 2 4 8] [--repeats 3] [--shapes sphere torus ellipsoid]
"""

from __future__ import annotations

import argparse
import pathlib
import sys
import time
import warnings

import numpy as np

import uvfeat

sys.path.insert(0, str(pathlib.Path(__file__).parent / "peers"))
import surfaces  # noqa: E402

FEATURES = ["mean_curvature", "gaussian_curvature"]
METHODS = {"default": {}, "pattern": {"quadrature": "pattern"}}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--radii", nargs="+", type=float, default=[2, 4, 8])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--shapes", nargs="+", default=["sphere", "torus", "ellipsoid"])
    args = parser.parse_args()
    warnings.simplefilter("ignore")
    print("| surface | charts | r | " + " | ".join(f"{m}: H / K error %, s" for m in METHODS) + " |")
    print("|---|---|---|" + "---|" * len(METHODS))
    for shape in args.shapes:
        for noisy in (True, False):
            surface = surfaces.build(shape, "200K", noisy)
            mesh = uvfeat.Mesh(surface.positions, surface.faces).with_atlas()
            for r in args.radii:
                times, values = {m: [] for m in METHODS}, {}
                for _ in range(args.repeats):
                    for name, options in METHODS.items():
                        started = time.perf_counter()
                        values[name] = uvfeat.compute(mesh, FEATURES, f"{r:g}%", **options)
                        times[name].append(time.perf_counter() - started)
                cells = [f"{100 * surfaces.normalised_error(values[m][FEATURES[0]], surface.true_h):.3g} / "
                         f"{100 * surfaces.normalised_error(values[m][FEATURES[1]], surface.true_k):.3g}, "
                         f"{np.median(times[m]):.2f}" for m in METHODS]
                print(f"| {shape}, {'noisy' if noisy else 'clean'} | {mesh.n_charts} | {r:g}% | " + " | ".join(cells)
                      + " |", flush=True)


if __name__ == "__main__":
    main()
