"""Issue 16: parametric H on real scans against the converged reference (the reference of the same
surface refined by midpoint subdivision until it converges), as the radius grows.

    .venv/bin/python benches/bench_scan_drift.py [--meshes armadillo.obj stanford-bunny.obj]
        [--radii 1 3 6] [--probe 2000]

Prints a Markdown table: %AE (range-normalised) and bias (mean signed error over mean |H|) of the
coarse reference and of the parametric method with overlaps kept and dropped, with CPU times.
Meshes come from the shared folder ($UVFEAT_SHARED_MESHES or ../shared/meshes) with xatlas atlases.
"""

from __future__ import annotations

import argparse
import os
import pathlib
import time
import warnings

import numpy as np

import uvfeat


def errors(values: np.ndarray, truth: np.ndarray) -> tuple[float, float]:
    spread = np.nanpercentile(truth, 99) - np.nanpercentile(truth, 1)
    return (float(100 * np.nanmean(np.abs(values - truth)) / spread),
            float(100 * np.nanmean(values - truth) / np.nanmean(np.abs(truth))))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--meshes", nargs="+", default=["armadillo.obj", "stanford-bunny.obj"])
    parser.add_argument("--radii", nargs="+", type=float, default=[1.0, 3.0, 6.0])
    parser.add_argument("--probe", type=int, default=2000, help="vertices compared (random, seed 0)")
    args = parser.parse_args()
    folder = pathlib.Path(os.environ.get("UVFEAT_SHARED_MESHES", pathlib.Path(__file__).parents[1].parent / "shared" / "meshes"))
    warnings.simplefilter("ignore")
    print("| mesh | charts | r | truth level (last change %) | coarse reference %AE / bias % | parametric %AE / bias % (CPU s) | overlaps dropped %AE / bias % (CPU s) |")
    print("|---|---|---|---|---|---|---|")
    for name in args.meshes:
        path = folder / name
        if not path.exists():
            print(f"| {name} | missing | | | | | |")
            continue
        mesh = uvfeat.load(str(path), uv="xatlas")
        probe = np.random.default_rng(0).choice(mesh.n_vertices, min(args.probe, mesh.n_vertices), replace=False)
        atlas = uvfeat.Atlas(mesh)
        for pct in args.radii:
            radius = f"{pct:g}%"
            truth = uvfeat.converged_reference(mesh, "mean_curvature", radius, vertices=probe, max_levels=2)
            coarse = uvfeat.reference.compute(mesh, "mean_curvature", radius, vertices=probe)["mean_curvature"]
            row = [name, str(mesh.n_charts), radius,
                   f"{truth.level} ({max(truth.changes[-1].values()):.2f})", "%.2f / %+.2f" % errors(coarse, truth["mean_curvature"])]
            for overlaps in ("keep", "drop"):
                started = time.process_time()
                H = atlas.compute("mean_curvature", radius, query="direct", overlaps=overlaps)["mean_curvature"]
                values = H.per_vertex()[probe]
                cpu = time.process_time() - started
                row.append("%.2f / %+.2f" % errors(values, truth["mean_curvature"]) + f" ({cpu:.0f})")
            print("| " + " | ".join(row) + " |", flush=True)


if __name__ == "__main__":
    main()
