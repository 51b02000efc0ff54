"""Feature maps on many charts: the values at the vertices interpolated over each face (what
`uvfeat compute` writes there), against the surfels' maps summed at every texel and the pattern's
maps, on the shared scans.

    .venv/bin/python benches/bench_scan_maps.py [--meshes armadillo.obj dragon.obj stanford-bunny.obj
        spot_triangulated.obj bob_tri.obj] [--radii 1 2 4 8] [--width 512] [--repeats 3]

`vertices` is `uvfeat.compute` with its defaults (the surfel sums at the vertices, on their own
atlas) then `Atlas.vertex_texture` on a `--width`² atlas (the command's atlas where the sums' atlas
is as fine as the maps). `surfels` is `Atlas.compute(quadrature="surfels", surface="facets")` on
1024² buffers: each texel the centre of its own ball on the facets the values at the vertices sum,
the accurate quadrature at the texels and this table's truth.
`pattern` is `Atlas.compute` with `quadrature="pattern"` on 1024² buffers (one chart's default).
Errors are %AE over the texels both maps cover: mean |map - surfels| over the surfels' Q1-Q99
range. Times are medians of `--repeats` calls (`vertices`: values and texture; the maps: the
features alone, their atlas built beforehand). Face sides: r over `Mesh.face_side`, about an edge
(`uvfeat compute` interpolates the maps from 3 up).
"""

from __future__ import annotations

import argparse
import os
import pathlib
import time
import warnings

import numpy as np

import uvfeat
from uvfeat.options import surfel_resolution

FEATURES = ["mean_curvature", "gaussian_curvature"]


def percent_error(values: np.ndarray, truth: np.ndarray) -> float:
    both = np.isfinite(values) & np.isfinite(truth)
    spread = np.percentile(truth[both], 99) - np.percentile(truth[both], 1)
    return float(100 * np.mean(np.abs(values[both] - truth[both])) / spread)


def timed(call, repeats: int):
    times, result = [], None
    for _ in range(repeats):
        started = time.perf_counter()
        result = call()
        times.append(time.perf_counter() - started)
    return result, float(np.median(times))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--meshes", nargs="+", default=["armadillo.obj", "dragon.obj", "stanford-bunny.obj",
                                                         "spot_triangulated.obj", "bob_tri.obj"])
    parser.add_argument("--radii", nargs="+", type=float, default=[1, 2, 4, 8])
    parser.add_argument("--width", type=int, default=512)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    warnings.simplefilter("ignore")
    folder = pathlib.Path(os.environ.get("UVFEAT_SHARED_MESHES", "../shared/meshes"))
    print(f"{os.cpu_count()} cores; {args.width}² maps; H / K %AE against the surfels' maps at the texels, s")
    print("| mesh (faces, charts) | r | face sides | vertices | pattern | surfels (s) |")
    print("|---|---|---|---|---|---|")
    for file in args.meshes:
        mesh = uvfeat.load(str(folder / file))
        maps_atlas = uvfeat.Atlas(mesh, resolution=1024)
        for r in args.radii:
            radius = f"{r:g}%"
            texture_atlas = uvfeat.Atlas(mesh, resolution=max(args.width, surfel_resolution(mesh, radius)))

            def vertices():
                values = uvfeat.compute(mesh, FEATURES, radius)
                return texture_atlas.vertex_texture(np.stack([values[f] for f in FEATURES]), args.width)

            baked, baked_s = timed(vertices, args.repeats)
            surfels, surfels_s = timed(lambda: maps_atlas.compute(FEATURES, radius, compute_resolution=args.width,
                                                                  quadrature="surfels", surface="facets"), 1)
            pattern, pattern_s = timed(lambda: maps_atlas.compute(FEATURES, radius, compute_resolution=args.width,
                                                                  quadrature="pattern"), args.repeats)
            truth = [surfels[f].texture for f in FEATURES]
            cell = lambda maps, seconds: " / ".join(f"{percent_error(m, t):.2f}" for m, t in zip(maps, truth)) \
                + f", {seconds:.2f}"
            sides = r / 100 * mesh.bounding_box_diagonal / mesh.face_side
            print(f"| {file} ({mesh.n_faces // 1000}K, {mesh.n_charts}) | {radius} | {sides:.1f} | {cell(baked, baked_s)} | "
                  f"{cell([pattern[f].texture for f in FEATURES], pattern_s)} | {surfels_s:.2f} |", flush=True)


if __name__ == "__main__":
    main()
