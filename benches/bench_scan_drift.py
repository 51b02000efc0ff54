"""Parametric H and K on real scans against the converged reference (the reference of the
same surface refined by midpoint subdivision until it converges), as the radius grows.

    .venv/bin/python benches/bench_scan_drift.py [--meshes armadillo.obj stanford-bunny.obj dragon.obj]
        [--radii 1 3 6] [--probe 2000] [--quadratures default pattern surfels surfels/facets]
        [--cost-radii 1 2 4 8 16]

Prints two Markdown tables:

- accuracy: %AE (range-normalised) and bias (mean signed error over mean |truth|) of H and K at
  `--probe` random vertices, for the coarse reference, `uvfeat.compute`'s defaults (`default`:
  on these many-chart atlases the values at the vertices from the surfels of the facets, on the surfel
  grid of the radius) and each
  quadrature's maps read with the direct query (`surfels/facets` is `quadrature="surfels",
  surface="facets"`), with CPU seconds;
- cost: wall and CPU seconds of the 512² feature maps (H + K) of the first mesh, for the default
  pattern and the surfels at `--cost-radii`, measured one after the other on the same atlas.

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

FEATURES = ("mean_curvature", "gaussian_curvature")


def errors(values: np.ndarray, truth: np.ndarray) -> tuple[float, float]:
    spread = np.nanpercentile(truth, 99) - np.nanpercentile(truth, 1)
    return (float(100 * np.nanmean(np.abs(values - truth)) / spread),
            float(100 * np.nanmean(values - truth) / np.nanmean(np.abs(truth))))


def options(quadrature: str) -> dict:
    name, _, surface = quadrature.partition("/")
    return {"quadrature": name, **({"surface": surface} if surface else {})}


def cell(values: dict, truth) -> str:
    return " / ".join("%.2f (%+.1f)" % errors(values[f], truth[f]) for f in FEATURES)


def accuracy(folder: pathlib.Path, args) -> list[tuple[str, uvfeat.Atlas]]:
    print("| mesh | charts | r | truth level (last change %) | coarse reference | "
          + " | ".join(f"{q} (CPU s)" for q in args.quadratures) + " |")
    print("|---|---|---|---|---|" + "---|" * len(args.quadratures))
    atlases = []
    for name in args.meshes:
        path = folder / name
        if not path.exists():
            print(f"| {name} | missing |")
            continue
        mesh = uvfeat.load(str(path), uv="xatlas")
        probe = np.random.default_rng(0).choice(mesh.n_vertices, min(args.probe, mesh.n_vertices), replace=False)
        atlas = uvfeat.Atlas(mesh)
        atlases.append((name, atlas))
        for pct in args.radii:
            radius = f"{pct:g}%"
            truth = uvfeat.converged_reference(mesh, list(FEATURES), radius, vertices=probe, max_levels=2)
            coarse = uvfeat.reference.compute(mesh, list(FEATURES), radius, vertices=probe)
            row = [name, str(mesh.n_charts), radius, f"{truth.level} ({max(truth.changes[-1].values()):.2f})",
                   cell(coarse, truth)]
            for quadrature in args.quadratures:
                started = time.process_time()
                if quadrature == "default":
                    values = {f: v[probe] for f, v in uvfeat.compute(mesh, list(FEATURES), radius).items()}
                else:
                    maps = atlas.compute(list(FEATURES), radius, query="direct", **options(quadrature))
                    values = {f: maps[f].per_vertex()[probe] for f in FEATURES}
                row.append(cell(values, truth) + f" ({time.process_time() - started:.0f})")
            print("| " + " | ".join(row) + " |", flush=True)
    return atlases


def cost(name: str, atlas: uvfeat.Atlas, radii) -> None:
    print(f"\n{name}, 512² maps of H + K: wall / CPU seconds (2 cores), surfels over pattern")
    print("| r | pattern (shared lattice) | surfels | ratio (wall) |")
    print("|---|---|---|---|")
    atlas.compute("mean_curvature", "2%", quadrature="surfels", compute_resolution=8)  # the pyramid, once
    for pct in radii:
        timings = []
        for quadrature in ("pattern", "surfels"):
            wall, cpu = time.perf_counter(), time.process_time()
            atlas.compute(list(FEATURES), f"{pct:g}%", quadrature=quadrature)
            timings.append((time.perf_counter() - wall, time.process_time() - cpu))
        (pw, pc), (sw, sc) = timings
        print(f"| {pct:g}% | {pw:.2f} / {pc:.2f} | {sw:.2f} / {sc:.2f} | {sw / pw:.1f}x |", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--meshes", nargs="+", default=["armadillo.obj", "stanford-bunny.obj", "dragon.obj"])
    parser.add_argument("--radii", nargs="*", type=float, default=[1.0, 3.0, 6.0])
    parser.add_argument("--probe", type=int, default=2000, help="vertices compared (random, seed 0)")
    parser.add_argument("--quadratures", nargs="*", default=["default", "pattern", "surfels", "surfels/facets"])
    parser.add_argument("--cost-radii", nargs="*", type=float, default=[1.0, 2.0, 4.0, 8.0, 16.0])
    args = parser.parse_args()
    folder = pathlib.Path(os.environ.get("UVFEAT_SHARED_MESHES", pathlib.Path(__file__).parents[1].parent / "shared" / "meshes"))
    warnings.simplefilter("ignore")
    print("%AE / (bias %) of H / K against the converged reference, at random vertices (direct query)\n")
    atlases = accuracy(folder, args)
    if atlases and args.cost_radii:
        cost(*atlases[0], args.cost_radii)


if __name__ == "__main__":
    main()
