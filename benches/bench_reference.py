"""Benchmark of the object-space reference against the parametric method (DESIGN.md §5.1, paper Fig. 10).

    .venv/bin/python benches/bench_reference.py [--mesh PATH] [--feature mean_curvature] [--exact]

For each radius (1–16 % of the diagonal): the parametric time per frame (buffers + features +
per-vertex lookup, DESIGN.md §1.10 defaults), the reference time (estimation, half-edges excluded),
the speed-up (reference / parametric), %AE and the mean samples per vertex/texel. Without
--mesh it uses the 102,400-triangle torus with an xatlas atlas of bench_features.py. --exact adds
the per-vertex cost of the exact-geodesic K on 500 vertices. RAYON_NUM_THREADS caps the threads.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np
from bench_features import benchmark_mesh  # benches/ is on the path when run as a script

import uvfeat
from uvfeat.compare import compare


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--mesh", default=None)
    parser.add_argument("--feature", default="mean_curvature")
    parser.add_argument("--radii", default="1%,2%,4%,8%,16%")
    parser.add_argument("--exact", action="store_true", help="also time the exact-geodesic K")
    args = parser.parse_args()

    mesh = benchmark_mesh(args.mesh)
    threads = os.environ.get("RAYON_NUM_THREADS", str(os.cpu_count()))
    print(f"{mesh.name}: {mesh.n_vertices} vertices, {mesh.n_faces} faces, {mesh.n_charts} charts; {threads} threads; "
          f"feature {args.feature}")
    print(f"  {'radius':>7}{'parametric ms':>15}{'reference ms':>14}{'speed-up':>10}{'%AE':>8}"
          f"{'ref samples':>13}{'par samples':>13}")
    for radius in args.radii.split(","):
        result = compare(mesh, args.feature, radius)
        t, e = result.timings, result.errors[args.feature]
        print(f"  {radius:>7}{1e3 * t['parametric']:>15.0f}{1e3 * t['reference']:>14.0f}{t['speedup']:>10.3f}"
              f"{e['percent_ae']:>8.2f}{result.settings['mean_reference_samples']:>13.0f}"
              f"{result.settings['mean_parametric_samples'] or float('nan'):>13.0f}")
    if args.exact:
        reference = uvfeat.reference.Reference(mesh)
        some = np.linspace(0, mesh.n_vertices - 1, 500).astype(np.int64)
        print("\nexact-geodesic K (500 vertices)")
        for radius in args.radii.split(",")[:3]:
            started = time.perf_counter()
            reference.compute("gaussian_curvature", radius, vertices=some, gaussian_method="exact_geodesic_area")
            per_vertex = 1e3 * (time.perf_counter() - started) / len(some)
            print(f"  {radius:>7}: {per_vertex:.2f} ms per vertex, {per_vertex * mesh.n_vertices / 1e3:.0f} s for the mesh")


if __name__ == "__main__":
    main()
