"""uvfeat and its peers on the shared real scans: per-vertex H and K at r = 1-8 % of the diagonal,
the time of each method and the error against `uvfeat.converged_reference` (the mesh's facets,
1,000 random vertices, the truth cached with benches/bench_scan_vertices.py's). pgeof and
jakteristics compute radius features of the vertices as a point cloud (PCA, no curvature): their
time only. Run in the peers venv (`make bench-peers` builds it; it needs the shared meshes):

    .venv-peers/bin/python benches/peers/bench_scans.py [--meshes armadillo.obj dragon.obj stanford-bunny.obj]
        [--radii 1 2 4 8] [--methods default reference trueform libigl pgeof jakteristics] [--repeats 3]

Each cell's methods alternate; a method's time is the median of `--repeats` calls (one call where
the first took over `--slow` seconds), each including the library's own set-up for the mesh
(uvfeat: its atlas buffers from the cached UVs; the others: their trees or mesh structures).
k-ring methods take k = round(r / h) rings, h the mean edge length, as in docs/PEERS.md.
"""

from __future__ import annotations

import argparse
import os
import pathlib
import sys
import time
import warnings
from types import SimpleNamespace

import numpy as np
from scipy.spatial import cKDTree

import uvfeat

HERE = pathlib.Path(__file__).parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))
from bench_scan_vertices import FEATURES, percent_error, truth  # noqa: E402
from methods import libigl, trueform_kring  # noqa: E402
from surfaces import mean_edge  # noqa: E402


def pgeof_features(points: np.ndarray, radius: float) -> None:
    import pgeof

    # Its radius search keeps at most `max_knn` neighbours: room for the fullest ball of a sample.
    sample = points[np.random.default_rng(0).choice(len(points), min(500, len(points)), replace=False)]
    fullest = max(len(n) for n in cKDTree(points).query_ball_point(sample, radius))
    pgeof.compute_features_selected(points, radius, 2 * fullest, [pgeof.EFeatureID.Curvature])


def jakteristics_features(points: np.ndarray, radius: float) -> None:
    import jakteristics

    jakteristics.compute_features(points, search_radius=radius, feature_names=["surface_variation"])


def methods(mesh: uvfeat.Mesh, scan: SimpleNamespace) -> dict:
    """Per method: a function of the radius (object units) giving (H, K) per vertex, or None."""
    return {
        "default": lambda r: _hk(uvfeat.compute(mesh, FEATURES, r)),
        "reference": lambda r: _hk(uvfeat.reference.compute(mesh, FEATURES, radius=r)),
        "trueform": lambda r: trueform_kring(scan, r),
        "libigl": lambda r: libigl(True)(scan, r),
        "pgeof": lambda r: pgeof_features(scan.positions, r),
        "jakteristics": lambda r: jakteristics_features(scan.positions, r),
    }


def _hk(values: dict) -> tuple:
    return values[FEATURES[0]], values[FEATURES[1]]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--meshes", nargs="+", default=["armadillo.obj", "dragon.obj", "stanford-bunny.obj"])
    parser.add_argument("--radii", nargs="+", type=float, default=[1, 2, 4, 8])
    parser.add_argument("--methods", nargs="+", default=["default", "reference", "trueform", "libigl", "pgeof",
                                                         "jakteristics"])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--slow", type=float, default=5.0, help="seconds above which a method is called once")
    parser.add_argument("--probe", type=int, default=1000)
    args = parser.parse_args()
    warnings.simplefilter("ignore")
    folder = pathlib.Path(os.environ.get("UVFEAT_SHARED_MESHES", HERE.parents[2] / "shared" / "meshes"))
    print(f"{os.cpu_count()} cores; H / K %AE against the converged reference (where the method gives them), "
          f"median s of {args.repeats} alternating calls")
    print("| mesh (faces) | r | " + " | ".join(args.methods) + " |")
    print("|---|---|" + "---|" * len(args.methods))
    for file in args.meshes:
        mesh = uvfeat.load(str(folder / file))
        # Writable copies: some peers reject read-only arrays.
        positions, faces = np.array(mesh.positions, dtype=np.float64), np.array(mesh.faces)
        scan = SimpleNamespace(positions=positions, faces=faces, spacing=mean_edge(positions, faces))
        probe = np.sort(np.random.default_rng(0).choice(mesh.n_vertices, min(args.probe, mesh.n_vertices),
                                                        replace=False))
        run = methods(mesh, scan)
        diagonal = mesh.bounding_box_diagonal
        for pct in args.radii:
            radius = f"{pct:g}%"
            expected, _ = truth(mesh, pathlib.Path(file).stem, radius, probe, "facets")
            r = pct / 100 * diagonal
            times = {m: [] for m in args.methods}
            results = {}
            for attempt in range(args.repeats):
                for m in args.methods:
                    if attempt and times[m][0] > args.slow:
                        continue
                    started = time.perf_counter()
                    results[m] = run[m](radius if m in ("default", "reference") else r)
                    times[m].append(time.perf_counter() - started)
            cells = []
            for m in args.methods:
                error = ("" if results[m] is None else
                         " / ".join(f"{percent_error(v[probe], expected[f]):.2f}" for v, f in zip(results[m], FEATURES))
                         + " %, ")
                cells.append(f"{error}{np.median(times[m]):.2f} s")
            print(f"| {file} ({mesh.n_faces // 1000}K) | {radius} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
