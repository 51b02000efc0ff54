"""Per-vertex H and K on real scans, as a user gets them: error against the converged reference and
time of each method, from a loaded mesh with a cached automatic atlas.

    .venv/bin/python benches/bench_scan_vertices.py [--meshes armadillo.obj dragon.obj stanford-bunny.obj
        spot_triangulated.obj bob_tri.obj]
        [--radii 1 2 4 6 8] [--methods default vertices reference] [--probe 1000] [--repeats 3]
        [--resolution 512] [--truth facets|smooth]

Methods: `default` is `uvfeat.compute` with its defaults (on these many-chart atlases, the values at
the vertices from the surfels of the facets), `default:128` the same with `samples=128` (surfels per
ball), `default/smooth` with `surface="smooth"`; `kept` the same values from `Atlas.per_vertex` on an Atlas kept for
the mesh and radius (built, with its surfels, before the timing); `pattern` the pattern read from its 512² maps, the default of a
single chart (`quadrature="pattern"`, 1024² buffers); `vertices` is `uvfeat.compute` with
`quadrature="surfels", surface="facets"` (values at the vertices from the surfels' moments, no
maps; `vertices/smooth` on the smooth surface, `vertices@1024` with 1024² buffers instead of
`--resolution`); `reference` is `uvfeat.reference.compute`. Each
call is timed end to end (atlas buffers, features, per-vertex values); the methods of a cell alternate
`--repeats` times and the table keeps the median. The truth is `uvfeat.converged_reference`
at `--probe` random vertices (three levels at most) of the surface `--truth` names (the flat faces,
or the smooth surface through the vertices), cached under uvfeat-out/bench-cache. Errors are %AE:
mean |value - truth| over the truth's Q1-Q99 range, in percent.
"""

from __future__ import annotations

import argparse
import os
import pathlib
import time
import warnings

import numpy as np

import uvfeat
from uvfeat.options import sums_mesh, surfel_resolution

FEATURES = ["mean_curvature", "gaussian_curvature"]
CACHE = pathlib.Path("uvfeat-out/bench-cache")


def percent_error(values: np.ndarray, truth: np.ndarray) -> float:
    spread = np.nanpercentile(truth, 99) - np.nanpercentile(truth, 1)
    return float(100 * np.nanmean(np.abs(values - truth)) / spread)


def truth(mesh: uvfeat.Mesh, name: str, radius: str, probe: np.ndarray,
          surface: str) -> tuple[dict[str, np.ndarray], str]:
    """The converged values at `probe` and a note of their level and last change (%)."""
    kind = "converged" if surface == "facets" else f"converged-{surface}"
    path = CACHE / f"{name}-{radius.rstrip('%')}pc-{len(probe)}-{kind}.npz"
    if not path.exists():
        result = uvfeat.converged_reference(mesh, FEATURES, radius, vertices=probe, max_levels=3, surface=surface)
        change = max(result.changes[-1].values()) if result.changes else float("nan")
        CACHE.mkdir(parents=True, exist_ok=True)
        np.savez(path, level=result.level, change=change, **result.values)
    stored = dict(np.load(path))
    return {f: stored[f] for f in FEATURES}, f"{int(stored['level'])} ({float(stored['change']):.2f})"


KEPT: dict = {}


def kept_atlas_values(mesh: uvfeat.Mesh, radius: str) -> dict[str, np.ndarray]:
    """`Atlas.per_vertex` with its defaults on an Atlas kept for the mesh and radius, on the mesh
    and grid `uvfeat.compute` picks (the first call builds it and its surfels)."""
    key = (id(mesh), radius)
    if key not in KEPT:
        KEPT.clear()
        own = sums_mesh(mesh, FEATURES, {}, paper_mode=False)
        KEPT[key] = uvfeat.Atlas(own, resolution=surfel_resolution(own, radius))
    return KEPT[key].per_vertex(FEATURES, radius)


def method(name: str, resolution: int):
    if name == "reference":
        return lambda mesh, radius: uvfeat.reference.compute(mesh, FEATURES, radius=radius)
    if name.startswith("default"):
        name, _, surface = name.partition("/")
        samples = name.partition(":")[2]
        options = {**({"samples": int(samples)} if samples else {}), **({"surface": surface} if surface else {})}
        return lambda mesh, radius: uvfeat.compute(mesh, FEATURES, radius, **options)
    if name == "kept":
        return kept_atlas_values
    if name == "pattern":
        return lambda mesh, radius: uvfeat.compute(mesh, FEATURES, radius, quadrature="pattern")
    name, _, size = name.partition("@")
    resolution = int(size) if size else resolution
    surface = name.partition("/")[2] or "facets"
    return lambda mesh, radius: uvfeat.compute(mesh, FEATURES, radius, resolution=resolution,
                                               quadrature="surfels", surface=surface)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--meshes", nargs="+", default=["armadillo.obj", "dragon.obj", "stanford-bunny.obj",
                                                         "spot_triangulated.obj", "bob_tri.obj"])
    parser.add_argument("--radii", nargs="+", type=float, default=[1, 2, 4, 6, 8])
    parser.add_argument("--methods", nargs="+", default=["default", "vertices", "reference"])
    parser.add_argument("--probe", type=int, default=1000)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--resolution", type=int, default=512, help="atlas resolution of the 'vertices' methods")
    parser.add_argument("--truth", choices=["facets", "smooth"], default="facets",
                        help="the surface of the converged reference")
    args = parser.parse_args()
    warnings.simplefilter("ignore")
    folder = pathlib.Path(os.environ.get("UVFEAT_SHARED_MESHES", "../shared/meshes"))
    print(f"{os.cpu_count()} cores; median of {args.repeats} alternating calls; %AE against the converged reference "
          f"of the {args.truth} surface")
    print("| mesh (faces, charts) | r | truth level (last change %) | "
          + " | ".join(f"{m}: H / K %AE, s" for m in args.methods) + " |")
    print("|---|---|---|" + "---|" * len(args.methods))
    for file in args.meshes:
        mesh = uvfeat.load(str(folder / file))
        if not mesh.has_uvs:
            mesh = mesh.with_atlas()
        probe = np.sort(np.random.default_rng(0).choice(mesh.n_vertices, min(args.probe, mesh.n_vertices),
                                                        replace=False))
        for r in args.radii:
            radius = f"{r:g}%"
            expected, level = truth(mesh, pathlib.Path(file).stem, radius, probe, args.truth)
            runs = {m: [] for m in args.methods}
            values = {}
            if "kept" in args.methods:
                kept_atlas_values(mesh, radius)  # the Atlas and its surfels, built before the timing
            for _ in range(args.repeats):
                for m in args.methods:
                    started = time.perf_counter()
                    values[m] = method(m, args.resolution)(mesh, radius)
                    runs[m].append(time.perf_counter() - started)
            cells = [" / ".join(f"{percent_error(values[m][f][probe], expected[f]):.2f}" for f in FEATURES)
                     + f", {np.median(runs[m]):.3f}" for m in args.methods]
            print(f"| {file} ({mesh.n_faces // 1000}K, {mesh.n_charts}) | {radius} | {level} | " + " | ".join(cells)
                  + " |", flush=True)


if __name__ == "__main__":
    main()
