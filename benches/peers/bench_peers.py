"""Peers benchmark: uvfeat next to the curvature estimators users would otherwise pick, on analytic
surfaces with known H and K. Writes docs/PEERS.md, docs/peers/results.json and
docs/peers/noisy_error.png.

    make bench-peers                          # full run: separate venv .venv-peers, all sizes and radii
    make bench-peers PEERS_ARGS=--quick       # 50K faces only, radii 4 and 8 %
    .venv-peers/bin/python benches/peers/bench_peers.py --report-only   # tables and plot from the JSON

Surfaces: sphere, torus, ellipsoid at ~50K and ~200K faces, clean and with Gaussian noise along
the normals (std 0.2 % of the diagonal). Radii: 1, 2, 4, 8 % of the clean diagonal. Error:
mean |estimate - truth| divided by the truth's range (sphere: by its mean). Each method runs in its
own process with a time limit; a method that hits it on a mesh is not run at larger radii there
(recorded as a timeout too). With ``--repeats N`` the methods of each cell alternate N times and
the median times are kept (on a shared machine one call's time may wander by 30-50 %).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
from importlib import metadata
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import report  # noqa: E402
import surfaces  # noqa: E402
from methods import METHODS  # noqa: E402
from workers import Worker  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
DISTRIBUTIONS = ["uvfeat", "libigl", "trimesh", "pymeshlab", "trueform", "numpy", "scipy"]


def machine() -> dict:
    cpu = platform.processor()
    try:
        cpu = next(line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    versions = {}
    for name in DISTRIBUTIONS:
        try:
            versions[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            versions[name] = None
    return {"cpu": cpu, "cores": os.cpu_count(), "python": platform.python_version(), "versions": versions}


def parse_args(argv=None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="50K faces only, radii 4 and 8 %%")
    parser.add_argument("--methods", default=",".join(METHODS), help=f"comma-separated, from {', '.join(METHODS)}")
    parser.add_argument("--shapes", default="sphere,torus,ellipsoid")
    parser.add_argument("--sizes", default="50K,200K")
    parser.add_argument("--radii", default="1,2,4,8", help="percent of the clean bounding-box diagonal")
    parser.add_argument("--timeout", type=float, default=600.0, help="seconds per method and mesh")
    parser.add_argument("--repeats", type=int, default=1,
                        help="timed runs per method and cell, alternating with the other methods; the median is kept")
    parser.add_argument("--memory-gb", type=float, default=8.0, help="address-space limit per method process")
    parser.add_argument("--results", default=str(ROOT / "docs/peers/results.json"))
    parser.add_argument("--markdown", default=str(ROOT / "docs/PEERS.md"))
    parser.add_argument("--plot", default=str(ROOT / "docs/peers/noisy_error.png"))
    parser.add_argument("--resume", action="store_true", help="keep the results already in --results (errors are run again)")
    parser.add_argument("--report-only", action="store_true", help="rewrite tables and plot from --results")
    args = parser.parse_args(argv)
    if args.quick:
        args.sizes, args.radii = "50K", "4,8"
    return args


def available_methods(keys: list[str]) -> tuple[list[str], dict]:
    runnable, skipped = [], {}
    for key in keys:
        if key not in METHODS:
            raise SystemExit(f"unknown method {key!r}; choose from {', '.join(METHODS)}")
        reason = METHODS[key].probe()
        if reason:
            print(f"skip {METHODS[key].label}: {reason}", flush=True)
            skipped[key] = reason
        else:
            runnable.append(key)
    return runnable, skipped


def run_key(shape: str, size: str, noisy: bool, radius: float, method: str) -> tuple:
    return shape, size, noisy, radius, method


def benchmark(args, runnable: list[str], results: list[dict], save) -> None:
    done = {run_key(r["shape"], r["size"], r["noisy"], r["radius_pct"], r["method"]) for r in results}
    radii = [float(r) for r in args.radii.split(",")]
    workers = {key: Worker(key, args.memory_gb) for key in runnable}
    try:
        for size in args.sizes.split(","):
            for shape in args.shapes.split(","):
                for noisy in (False, True):
                    surface = surfaces.build(shape, size, noisy)
                    print(f"\n{surface.label}: {len(surface.faces)} faces, diagonal {surface.diagonal:.3f}, "
                          f"mean edge {surface.spacing:.4f}", flush=True)
                    stopped = {}
                    for pct in radii:
                        keys = [key for key in runnable if run_key(shape, size, noisy, pct, key) not in done]
                        for row in measure_cell(args, workers, keys, surface, shape, size, noisy, pct, stopped):
                            print(report.progress_line(row, METHODS[row["method"]].label), flush=True)
                            results.append(row)
                        save()
    finally:
        for worker in workers.values():
            worker.close()


def measure_cell(args, workers: dict, keys: list[str], surface, shape: str, size: str, noisy: bool, pct: float,
                 stopped: dict) -> list[dict]:
    """The rows of one surface and radius. With ``--repeats N`` the methods alternate N times, so
    that a slow minute of a shared machine slows every method alike, and each row's times are the
    medians (the values are those of the first run: every method here is deterministic)."""
    rows = {}
    for key in keys:
        rows[key] = {"shape": shape, "size": size, "noisy": noisy, "radius_pct": pct, "method": key,
                     "faces": len(surface.faces), "radius": pct / 100 * surface.diagonal}
        if key in stopped:
            rows[key].update(status="timeout", seconds=None, detail=f"not run: timed out at {stopped[key]} %")
    runs = {key: [] for key in keys}
    for repeat in range(args.repeats):
        for key in keys:
            if key in stopped or (repeat > 0 and rows[key]["status"] != "ok"):
                continue
            row = measure(workers[key], surface, rows[key]["radius"], args.timeout)
            if repeat == 0:
                rows[key].update(row)
            if row["status"] == "timeout":
                stopped[key] = pct
            elif row["status"] == "ok":
                runs[key].append((row["seconds"], row["cpu_seconds"]))
    for key, times in runs.items():
        if len(times) > 1:
            rows[key].update(seconds=float(np.median([wall for wall, _ in times])),
                             cpu_seconds=float(np.median([cpu for _, cpu in times])),
                             seconds_runs=[wall for wall, _ in times])
    return list(rows.values())


def measure(worker: Worker, surface, radius: float, timeout: float) -> dict:
    status, (wall, cpu), h, k, detail = worker.run(surface, radius, timeout)
    row = {"status": status, "seconds": wall, "cpu_seconds": cpu, "detail": detail}
    if status == "ok":
        finite = np.isfinite(h) & np.isfinite(k)
        row.update(h_error=surfaces.normalised_error(h, surface.true_h),
                   k_error=surfaces.normalised_error(k, surface.true_k),
                   nonfinite=int((~finite).sum()))
    return row


def main(argv=None) -> None:
    args = parse_args(argv)
    results_path = Path(args.results)
    data = json.loads(results_path.read_text()) if (args.resume or args.report_only) and results_path.exists() else {}
    results = [r for r in data.get("results", []) if args.report_only or r["status"] != "error"]
    if not args.report_only:
        runnable, skipped = available_methods(args.methods.split(","))
        command = " ".join(["bench_peers.py"] + (argv or sys.argv[1:]))
        data = {"machine": machine(), "commands": data.get("commands", []) + [command],
                "timeout_s": args.timeout, "skipped": {**{k: v for k, v in data.get("skipped", {}).items() if k not in runnable}, **skipped},
                "results": results}
        results_path.parent.mkdir(parents=True, exist_ok=True)

        def save() -> None:
            results_path.write_text(json.dumps(data, indent=1))

        benchmark(args, runnable, results, save)
        save()
    report.write_markdown(data, Path(args.markdown))
    report.plot_noisy(data, Path(args.plot))
    print(f"\nwrote {args.markdown}, {args.plot}, {args.results}")


if __name__ == "__main__":
    main()
