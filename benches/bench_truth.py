"""Which surface a converged reference measures: `uvfeat.converged_reference` of the flat faces and
of the smooth surface through the vertices, against the analytic curvatures of the peers
benchmark's clean 50K surfaces (docs/PEERS.md), with uvfeat's default next to them.

    .venv/bin/python benches/bench_truth.py [--shapes torus ellipsoid] [--radii 1 2 4] [--probe 500]

At radii of a few edge lengths the faces, chords up to h^2 k / 8 inside the surface through the
vertices, move a ball's H moment by a large part of H r^2 / 4: the flat truth is then the
polyhedron's, not the sampled surface's. Errors are range-normalised %AE (PEERS.md's), at
`--probe` random vertices; the truth is refined three levels at most.
"""

from __future__ import annotations

import argparse
import pathlib
import sys
import warnings

import numpy as np

import uvfeat

sys.path.insert(0, str(pathlib.Path(__file__).parent / "peers"))
import surfaces  # noqa: E402

FEATURES = ["mean_curvature", "gaussian_curvature"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--shapes", nargs="+", default=["torus", "ellipsoid"])
    parser.add_argument("--radii", nargs="+", type=float, default=[1, 2, 4])
    parser.add_argument("--probe", type=int, default=500)
    args = parser.parse_args()
    warnings.simplefilter("ignore", uvfeat.NeighbourhoodWarning)
    print("| surface (50K, clean) | r | edge lengths | converged, facets: H / K %AE (level) "
          "| converged, smooth: H / K %AE (level) | uvfeat default: H / K %AE |")
    print("|---|---|---|---|---|---|")
    for shape in args.shapes:
        s = surfaces.build(shape, "50K", False)
        mesh = uvfeat.Mesh(s.positions, s.faces, s.uvs, s.uv_faces)
        rows = np.random.default_rng(0).choice(len(s.positions), args.probe, replace=False)

        def errors(h, k):
            return (f"{100 * surfaces.normalised_error(h, s.true_h[rows]):.2f} / "
                    f"{100 * surfaces.normalised_error(k, s.true_k[rows]):.2f}")

        for r in args.radii:
            radius = r / 100 * s.diagonal
            cells = []
            for surface in ("facets", "smooth"):
                truth = uvfeat.converged_reference(mesh, FEATURES, radius, vertices=rows, max_levels=3, surface=surface)
                cells.append(f"{errors(truth['mean_curvature'], truth['gaussian_curvature'])} ({truth.level})")
            default = uvfeat.compute(mesh, FEATURES, radius)
            cells.append(errors(default["mean_curvature"][rows], default["gaussian_curvature"][rows]))
            print(f"| {shape} | {r:g}% | {radius / s.spacing:.1f} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
