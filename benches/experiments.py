"""Reproduces the paper's evaluation (DESIGN.md §5.2-§5.8) in one command and writes docs/EXPERIMENTS.md.

    make experiments                                   # or: .venv/bin/python benches/experiments.py
    .venv/bin/python benches/experiments.py --quick    # smoke run, tiny sizes (uvfeat-out/experiments-quick/)
    .venv/bin/python benches/experiments.py --only table1,radius --resume
    .venv/bin/python benches/experiments.py --report-only   # tables and plots from the JSON

Experiments (mean curvature H unless stated; r in % of the bounding-box diagonal):
  table1     §5.2  full vs two-stage adaptive sampling, N = 64/100/256/400, r = 4 %
  table2     §5.3  computation texture 512² vs 1024² x f32 vs f16 buffers; geodesic-area K f16/f32
  features   §5.4  every feature, parametric vs reference, r = 2 %, shared + analytic meshes
  triangles  §5.5  torus (xatlas) at 25K-400K triangles, r = 4 %
  radius     §5.6  the 100K torus (or --radius-mesh bunny, ...), r = 2-16 %, max_jumps 32 vs 1, missing samples
  samples    §5.7  N = 64-400 x buffers/computation 512/512, 1024/512, 1024/1024
  charts     §5.8  the torus's single-chart UVs vs xatlas atlases with chart-area budgets

Writes OUT/EXPERIMENTS.md (between its markers), OUT/experiments/results.json (after every
experiment, so a cut-off run keeps what it has; --resume skips the experiments already there)
and OUT/experiments/*.png; OUT is docs/ (uvfeat-out/experiments-quick/ with --quick).
Shared meshes are read from ../shared/meshes/ next to the repository (skipped when absent);
xatlas atlases are cached in uvfeat-out/experiments-cache/.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import experiments_report as report  # benches/ is on the path when run as a script
from experiments_lib import ROOT, SHARED, Results, analytic, describe, log, measure, model, release_atlases

import uvfeat

H = "mean_curvature"

FULL = {
    "resolution": 1024, "compute": 512, "compute_hi": 1024,    # geometry buffers, computation texture
    "samples": [64, 100, 256, 400], "N": 256, "taus": [0.01, 0.05],
    "models": ["spot", "bob", "blub"],                         # averaged in table1, table2, samples
    "feature_models": ["spot", "bob", "blub"], "analytic_faces": 50_000,
    "triangles": [25_000, 50_000, 100_000, 200_000, 400_000],
    "radius_mesh": "torus", "radius_faces": 100_000, "radii": [2, 4, 8, 12, 16],
    "configs": [(512, 512), (1024, 512), (1024, 1024)],
    "chart_faces": 50_000, "chart_areas": [1 / 8, 1 / 32],
}
QUICK = {
    "resolution": 256, "compute": 64, "compute_hi": 128,
    "samples": [16, 32], "N": 32, "taus": [0.01, 0.05],
    "models": ["spot"],
    "feature_models": ["spot"], "analytic_faces": 8_000,
    "triangles": [2_000, 4_000, 8_000],
    "radius_mesh": "torus", "radius_faces": 8_000, "radii": [2, 8],
    "configs": [(128, 64), (256, 64), (256, 128)],
    "chart_faces": 8_000, "chart_areas": [1 / 8],
}


def _models(names):
    return [case for case in (model(n) for n in names) if case is not None]


def _run(case, feature, radius, tags: dict, **settings) -> dict:
    row = {**tags, **measure(case, feature, radius, **settings)}
    label = ", ".join(f"{k} {v:.3g}" if isinstance(v, float) else f"{k} {v}" for k, v in tags.items())
    log(f"  {case.key}: {feature} r {radius}" + (f" ({label})" if label else "") + f": {describe(row)}")
    return row


def table1(cfg):
    rows = []
    for case in _models(cfg["models"]):
        for n in cfg["samples"]:
            common = dict(samples=n, resolution=cfg["resolution"], compute_resolution=cfg["compute"])
            rows.append(_run(case, H, "4%", {"variant": "full", "N": n}, **common))
            for tau in cfg["taus"]:
                rows.append(_run(case, H, "4%", {"variant": f"adaptive tau={tau:g}", "N": n}, adaptive=True, tau=tau,
                                 **common))
    return rows


def table2(cfg):
    rows = []
    for case in _models(cfg["models"]):
        for precision in ("f32", "f16"):
            for compute in (cfg["compute"], cfg["compute_hi"]):
                rows.append(_run(case, H, "4%", {"variant": "H", "precision": precision, "compute": compute},
                                 precision=precision, samples=cfg["N"], resolution=cfg["resolution"],
                                 compute_resolution=compute))
            # Geodesic-area K against the object-space moments K (the accurate reference).
            rows.append(_run(case, "gaussian_curvature", "4%", {"variant": "K geodesic area", "precision": precision},
                             precision=precision, samples=cfg["N"], resolution=cfg["resolution"],
                             compute_resolution=cfg["compute"], gaussian_method="moments",
                             parametric_gaussian="geodesic_area"))
    return rows


def features(cfg):
    rows = []
    cases = _models(cfg["feature_models"]) + [analytic(s, cfg["analytic_faces"], resolution=cfg["resolution"])
                                              for s in ("torus", "ellipsoid")]
    for case in cases:
        for feature in uvfeat.FEATURES:
            rows.append(_run(case, feature, "2%", {}, samples=cfg["N"], resolution=cfg["resolution"],
                             compute_resolution=cfg["compute"]))
        one_pass = case.all_features_timing("2%", cfg["N"], cfg["resolution"], cfg["compute"])
        rows.append({**case.info, "feature": "all (one pass)", **one_pass})
        log(f"  {case.key}: all features in one pass: parametric {one_pass['parametric_ms']:,.0f} ms, "
            f"reference {one_pass['reference_ms']:,.0f} ms")
        release_atlases()
    return rows


def triangles(cfg):
    rows = []
    for faces in cfg["triangles"]:
        case = analytic("torus", faces, resolution=cfg["resolution"])
        rows.append(_run(case, H, "4%", {"unwrap_s": case.unwrap_s}, samples=cfg["N"], resolution=cfg["resolution"],
                         compute_resolution=cfg["compute"]))
        release_atlases()
    return rows


def radius(cfg):
    rows = []
    name = cfg["radius_mesh"]
    case = analytic(name, cfg["radius_faces"], resolution=cfg["resolution"]) if name in ("torus", "ellipsoid") \
        else model(name, cfg["resolution"])
    if case is None:
        return rows
    for pct in cfg["radii"]:
        for jumps in ("default", 1):
            options = {} if jumps == "default" else {"max_jumps": jumps}
            rows.append(_run(case, H, f"{pct}%", {"max_jumps": jumps}, samples=cfg["N"], resolution=cfg["resolution"],
                             compute_resolution=cfg["compute"], **options))
    return rows


def samples(cfg):
    rows = []
    for case in _models(cfg["models"]):
        for buffers, compute in cfg["configs"]:
            for n in cfg["samples"]:
                rows.append(_run(case, H, "4%", {"config": f"{buffers}/{compute}", "N": n}, samples=n,
                                 resolution=buffers, compute_resolution=compute))
        release_atlases()
    return rows


def charts(cfg):
    faces, rows = cfg["chart_faces"], []
    cases = [(analytic("torus", faces, "single"), "single chart (own UVs)"),
             (analytic("torus", faces, resolution=cfg["resolution"]), "xatlas default")]
    cases += [(analytic("torus", faces, chart_area=a, resolution=cfg["resolution"]),
               f"xatlas, charts <= {a:.3g} of the area") for a in cfg["chart_areas"]]
    for case, label in cases:
        rows.append(_run(case, H, "4%", {"atlas": label, "unwrap_s": case.unwrap_s}, samples=cfg["N"],
                         resolution=cfg["resolution"], compute_resolution=cfg["compute"]))
        release_atlases()
    return rows


EXPERIMENTS = {"table1": table1, "table2": table2, "features": features, "triangles": triangles, "radius": radius,
               "samples": samples, "charts": charts}


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="tiny sizes for a smoke run")
    parser.add_argument("--only", default=",".join(EXPERIMENTS), help="comma-separated subset of: %(default)s")
    parser.add_argument("--resume", action="store_true", help="skip the experiments already in the results file")
    parser.add_argument("--report-only", action="store_true", help="rewrite the Markdown and plots from the JSON")
    parser.add_argument("--out", default=None, help="docs/ (uvfeat-out/experiments-quick/ with --quick)")
    parser.add_argument("--radius-mesh", default="torus", choices=["torus", "ellipsoid", *SHARED],
                        help="mesh of the radius experiment (the torus at 100K, or a shared mesh: bunny is the "
                             "paper's Fig. 2 model; scans without UVs get a cached xatlas atlas)")
    args = parser.parse_args(argv)
    out = Path(args.out) if args.out else ROOT / ("uvfeat-out/experiments-quick" if args.quick else "docs")
    path = out / "experiments" / "results.json"
    if args.report_only:
        report.write(json.loads(path.read_text()), out)
        print(f"wrote {out / 'EXPERIMENTS.md'} and the plots in {out / 'experiments'}")
        return
    only = [name.strip() for name in args.only.split(",") if name.strip()]
    unknown = sorted(set(only) - set(EXPERIMENTS))
    if unknown:
        parser.error(f"unknown experiment(s) {unknown}; choose from {', '.join(EXPERIMENTS)}")
    cfg = dict(QUICK if args.quick else FULL, radius_mesh=args.radius_mesh)
    command = " ".join(["benches/experiments.py"] + (argv if argv is not None else sys.argv[1:]))
    results = Results(path, "quick" if args.quick else "full", command, args.resume or len(only) < len(EXPERIMENTS))
    results.data["config"] = cfg
    log(f"{results.data['machine']}; {'quick smoke run' if args.quick else 'full run'}; writing {path}")
    for name in (n for n in EXPERIMENTS if n in only):
        if args.resume and results.done(name):
            log(f"{name}: already in {path.name}, skipped (--resume)")
            continue
        log(f"{name} ...")
        started = time.perf_counter()
        rows = EXPERIMENTS[name](cfg)
        results.store(name, rows, time.perf_counter() - started, command)
        release_atlases()
        log(f"{name}: {len(rows)} rows in {time.perf_counter() - started:.0f} s, saved")
        report.write(results.data, out)
    report.write(results.data, out)
    log(f"done: {out / 'EXPERIMENTS.md'}, {path}, plots in {out / 'experiments'}")


if __name__ == "__main__":
    main()
