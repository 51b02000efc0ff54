"""The whole of `uvfeat.compute` on the 200K-face surfaces of the peers benchmark, stage by stage.

    .venv/bin/python benches/bench_pipeline.py [--shapes torus,sphere,ellipsoid] [--radii 2,4]
        [--size 200K] [--repeat 5] [--reference] [--json PATH]

Each cell is the median of `--repeat` runs in one process (the first run is not dropped: it is
one of them) of what `uvfeat.compute` does with the default options (H and K): the mesh checks
(`uvfeat.Mesh`), the pre-processing (`Topology`), the rasterisation (`Atlas`), the features and
the per-vertex values. `--reference` times the object-space reference on the same mesh in the
same run (median of the same number of runs) and prints the ratio (at 4 % the
target is 5x). The surfaces and their noise are those of docs/PEERS.md (`benches/peers/surfaces.py`).
"""

from __future__ import annotations

import argparse
import json
import pathlib
import statistics
import sys
import time
import warnings

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent / "peers"))

import surfaces  # noqa: E402
from methods import FEATURES, uvfeat_mesh  # noqa: E402

import uvfeat  # noqa: E402

STAGES = ("mesh", "topology", "atlas", "features", "per_vertex")


def run_once(surface: surfaces.Surface, radius: float) -> dict[str, float]:
    """Seconds per stage of one `uvfeat.compute` equivalent."""
    times = {}
    started = time.perf_counter()
    mesh = uvfeat_mesh(surface)
    times["mesh"] = time.perf_counter() - started
    atlas = uvfeat.Atlas(mesh, resolution=1024)
    times["topology"], times["atlas"] = atlas.timings["preprocessing_s"], atlas.timings["rasterisation_s"]
    started = time.perf_counter()
    maps = atlas.compute(FEATURES, radius)
    times["features"] = time.perf_counter() - started
    started = time.perf_counter()
    for feature in maps.values():
        feature.per_vertex()
    times["per_vertex"] = time.perf_counter() - started
    times["total"] = sum(times[stage] for stage in STAGES)
    return times


def reference_once(surface: surfaces.Surface, radius: float) -> float:
    from uvfeat import reference

    mesh = uvfeat_mesh(surface)
    started = time.perf_counter()
    reference.compute(mesh, FEATURES, radius=radius)
    return time.perf_counter() - started


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--shapes", default="torus,sphere,ellipsoid")
    parser.add_argument("--radii", default="2,4", help="radii in %% of the diagonal")
    parser.add_argument("--size", default="200K", choices=["50K", "200K"])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--reference", action="store_true", help="time the object-space reference too")
    parser.add_argument("--clean-only", action="store_true", help="skip the noisy surfaces")
    parser.add_argument("--json", default="", help="write the medians here")
    args = parser.parse_args()
    warnings.simplefilter("ignore")
    print(f"uvfeat {uvfeat.__version__} from {pathlib.Path(uvfeat.__file__).parent}")
    print("| surface | r % | mesh | topology | atlas | features | per-vertex | total s | reference s | ratio |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    rows = []
    for shape in args.shapes.split(","):
        for noisy in (False,) if args.clean_only else (False, True):
            surface = surfaces.build(shape, args.size, noisy)
            for percent in (float(x) for x in args.radii.split(",")):
                radius = percent / 100 * surface.diagonal
                runs = [run_once(surface, radius) for _ in range(args.repeat)]
                median = {key: statistics.median(run[key] for run in runs) for key in runs[0]}
                reference = (statistics.median(reference_once(surface, radius) for _ in range(args.repeat))
                             if args.reference else float("nan"))
                label = f"{shape} {args.size} {'noisy' if noisy else 'clean'}"
                cells = " | ".join(f"{1e3 * median[stage]:.0f} ms" for stage in STAGES)
                print(f"| {label} | {percent:g} | {cells} | {median['total']:.3f} | {reference:.3f} | "
                      f"{reference / median['total']:.2f}x |", flush=True)
                rows.append({"surface": label, "radius_percent": percent, **median, "reference": reference})
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
