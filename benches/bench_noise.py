"""Noise study: integral and fit estimators against the analytic truth on noisy surfaces.

    make bench-noise                         # or: .venv/bin/python benches/bench_noise.py
    .venv/bin/python benches/bench_noise.py --quick                  # noise 0 and 0.2 %, radii 2-8 %
    .venv/bin/python benches/bench_noise.py --report-only            # tables and plot from the JSON

Surfaces: the torus (R = 2, a = 0.5) and ellipsoid (1 x 0.8 x 0.6) of the peers benchmark at ~50K
faces (`benches/peers/surfaces.py`), every vertex moved along its clean normal by a Gaussian offset
of 0, 0.05, 0.2 and 0.5 % of the diagonal. Radii 1-16 % of the diagonal, default configuration
(1024² buffers, 256 samples; the computation texture is 512² unless --compute-resolution says
otherwise), per-vertex values by texture lookup, principal
directions evaluated at the vertices. Errors: range-normalised mean absolute error of H, K, k1, k2
(relative to the mean |truth| where the truth is constant: k1 = 1/a on the torus) and the median
angle between the fitted d1 and the analytic one where |k1 - k2| > 20 % of |k1|.
Writes docs/NOISE.md (between its markers), docs/noise/results.json and docs/noise/noise_error.png.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benches" / "peers"))

import surfaces  # noqa: E402  (the peers benchmark's surfaces, truth and error measure)
from report_common import machine, write_section  # noqa: E402  (benches/ is on the path as a script)

import uvfeat  # noqa: E402

NOISE = [0.0, 0.05, 0.2, 0.5]          # % of the diagonal
RADII = [1.0, 2.0, 4.0, 8.0, 16.0]     # % of the diagonal
SHAPES = ["torus", "ellipsoid"]
METHODS = ["integral", "fit"]
CURVATURES = ["mean_curvature", "gaussian_curvature", "k1", "k2"]
SHORT = {"mean_curvature": "H", "gaussian_curvature": "K", "k1": "k1", "k2": "k2"}
START, END = "<!-- noise-results:start -->", "<!-- noise-results:end -->"


def principal_truth(shape: str, p: np.ndarray):
    """Analytic (k1, k2, d1) at clean points ``p`` (outward normals, k1 >= k2)."""
    if shape == "torus":
        major, minor = surfaces.TORUS
        radial = p * [1, 1, 0]
        radial /= np.linalg.norm(radial, axis=1, keepdims=True)
        normal = (p - major * radial) / minor
        parallel = np.cross([0.0, 0.0, 1.0], radial)
        cos_v = (normal * radial).sum(1)
        # The meridian's curvature 1/minor exceeds the parallel's |cos v| / (R + a cos v) everywhere.
        return np.full(len(p), 1.0 / minor), cos_v / (major + minor * cos_v), np.cross(normal, parallel)
    axes = np.asarray(surfaces.ELLIPSOID)
    hessian = 2.0 / axes ** 2                      # of F = sum (x_i / a_i)^2, diagonal
    grad = hessian * p
    length = np.linalg.norm(grad, axis=1, keepdims=True)
    normal = grad / length
    t1 = np.cross(normal, np.where(np.abs(normal[:, :1]) < 0.9, [[1.0, 0, 0]], [[0, 1.0, 0]]))
    t1 /= np.linalg.norm(t1, axis=1, keepdims=True)
    t2 = np.cross(normal, t1)
    form = lambda a, b: (a * hessian * b).sum(1) / length[:, 0]  # noqa: E731  shape operator
    e, f, g = form(t1, t1), form(t1, t2), form(t2, t2)
    mean, root = (e + g) / 2, np.hypot((e - g) / 2, f)
    k1 = mean + root
    use_first = np.abs(k1 - e) > np.abs(k1 - g)
    a = np.where(use_first, f, k1 - g)
    b = np.where(use_first, k1 - e, f)
    d1 = a[:, None] * t1 + b[:, None] * t2
    return k1, mean - root, d1 / np.linalg.norm(d1, axis=1, keepdims=True)


def run_case(shape: str, noise: float, radii: list[float], methods: list[str], compute_resolution: int) -> list[dict]:
    surface = surfaces.build(shape, "50K", noise > 0, noise_fraction=noise / 100)
    clean = surface.positions if noise == 0 else surfaces.build(shape, "50K", False).positions
    k1_true, k2_true, d1_true = principal_truth(shape, clean)
    truth = {"mean_curvature": surface.true_h, "gaussian_curvature": surface.true_k, "k1": k1_true, "k2": k2_true}
    anisotropic = np.abs(k1_true - k2_true) > 0.2 * np.abs(k1_true)
    mesh = uvfeat.Mesh(*(np.array(a) for a in (surface.positions, surface.faces, surface.uvs, surface.uv_faces)))
    atlas = uvfeat.Atlas(mesh, resolution=1024)
    rows = []
    for pct in radii:
        for method in methods:
            started = time.perf_counter()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                maps = atlas.compute(CURVATURES, pct / 100 * surface.diagonal, method=method,
                                     compute_resolution=compute_resolution)
                values = {name: m.per_vertex() for name, m in maps.items()}
            seconds = time.perf_counter() - started
            row = {"shape": shape, "faces": int(len(surface.faces)), "noise_pct": noise, "radius_pct": pct,
                   "method": method, "seconds": seconds, "compute_resolution": compute_resolution,
                   **{SHORT[n]: surfaces.normalised_error(values[n], truth[n]) for n in CURVATURES}}
            if method == "fit":
                d1 = maps["k1"].per_vertex_directions()[:, 0]
                cosine = np.abs((d1 * d1_true).sum(1)).clip(0, 1)
                row["d1_angle_deg"] = float(np.degrees(np.median(np.arccos(cosine[anisotropic]))))
            rows.append(row)
            print(f"{shape} noise {noise} % r {pct} % {method}: " + ", ".join(
                f"{k} {100 * row[k]:.2f} %" for k in ("H", "K", "k1", "k2")) +
                (f", d1 {row['d1_angle_deg']:.2f} deg" if "d1_angle_deg" in row else "") + f" ({seconds:.1f} s)",
                flush=True)
    return rows


def _cell(row: dict) -> str:
    text = " / ".join(f"{100 * row[k]:.3g}" for k in ("H", "K", "k1", "k2"))
    return text + (f" ({row['d1_angle_deg']:.2g}°)" if "d1_angle_deg" in row else "")


def tables(data: dict) -> str:
    rows = data["results"]
    radii = sorted({r["radius_pct"] for r in rows})
    out = [f"Measured on {data['machine']}; command: `{data['command']}`.", ""]
    for shape in SHAPES:
        subset = [r for r in rows if r["shape"] == shape]
        if not subset:
            continue
        out += [f"### {shape}, {subset[0]['faces']:,} faces", "",
                "Each cell: error % of H / K / k1 / k2 (median d1 angle error where |k1 - k2| > 0.2 |k1|).", "",
                "| noise | method | " + " | ".join(f"r = {r:g} %" for r in radii) + " |",
                "|---|---|" + "---:|" * len(radii)]
        for noise in sorted({r["noise_pct"] for r in subset}):
            for method in METHODS:
                cells = {r["radius_pct"]: _cell(r) for r in subset if r["noise_pct"] == noise and r["method"] == method}
                if cells:
                    out.append(f"| {noise:g} % | {method} | " + " | ".join(cells.get(r, "") for r in radii) + " |")
        out.append("")
    seconds = {m: [r["seconds"] for r in rows if r["method"] == m] for m in METHODS}
    width = rows[0].get("compute_resolution", 512)
    out.append(f"Mean time per computation (features + per-vertex lookup, {width}² x 256): " + ", ".join(
        f"{m} {np.mean(s):.1f} s" for m, s in seconds.items() if s) + ".")
    return "\n".join(out) + "\n"


def plot(data: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = data["results"]
    noises = sorted({r["noise_pct"] for r in rows})
    colours = plt.get_cmap("viridis")(np.linspace(0, 0.85, len(noises)))
    panels = [("H", "H error, %"), ("K", "K error, %"), ("d1_angle_deg", "d1 angle error, degrees (fit)")]
    fig, axes = plt.subplots(len(SHAPES), len(panels), figsize=(13, 7.5), squeeze=False)
    for i, shape in enumerate(SHAPES):
        for j, (key, title) in enumerate(panels):
            ax = axes[i, j]
            for noise, colour in zip(noises, colours):
                for method, style in zip(METHODS, ("--", "-")):
                    pts = sorted((r["radius_pct"], r[key] * (1 if key == "d1_angle_deg" else 100)) for r in rows
                                 if r["shape"] == shape and r["noise_pct"] == noise and r["method"] == method and key in r)
                    if pts:
                        x, y = zip(*pts)
                        ax.plot(x, y, style, marker="o", ms=3, color=colour,
                                label=f"{method}, noise {noise:g} %" if i == 0 and j == 0 else None)
            ax.set(xscale="log", yscale="log", title=f"{shape}: {title}", xlabel="radius, % of the diagonal")
            ax.set_xticks(RADII, [f"{r:g}" for r in RADII])
            ax.grid(True, which="both", alpha=0.3)
    fig.legend(loc="lower center", ncol=len(noises), fontsize=8)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write_markdown(data: dict, path: Path) -> None:
    write_section(path, START, END, tables(data), "# Noise study\n")


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="noise 0 and 0.2 %%, radii 2, 4, 8 %%")
    parser.add_argument("--shapes", default=",".join(SHAPES))
    parser.add_argument("--radii", default=",".join(f"{r:g}" for r in RADII), help="%% of the diagonal")
    parser.add_argument("--compute-resolution", type=int, default=512, help="computation texture (default 512)")
    parser.add_argument("--results", default=str(ROOT / "docs/noise/results.json"))
    parser.add_argument("--markdown", default=str(ROOT / "docs/NOISE.md"))
    parser.add_argument("--plot", default=str(ROOT / "docs/noise/noise_error.png"))
    parser.add_argument("--report-only", action="store_true", help="rewrite tables and plot from --results")
    parser.add_argument("--merge", action="store_true", help="add to the rows already in --results (same cases replaced)")
    args = parser.parse_args(argv)
    results = Path(args.results)
    if args.report_only:
        data = json.loads(results.read_text())
    else:
        noise, radii = ([0.0, 0.2], [2.0, 4.0, 8.0]) if args.quick else (NOISE, [float(r) for r in args.radii.split(",")])
        data = {"machine": machine(),
                "command": " ".join(["bench_noise.py"] + (argv if argv is not None else sys.argv[1:])), "results": []}
        if args.merge and results.exists():
            earlier = json.loads(results.read_text())
            data["command"] = f"{earlier['command']}, then {data['command']}"
            data["results"] = [r for r in earlier["results"] if r["radius_pct"] not in radii or r["noise_pct"] not in noise]
        # The headline level first, so that a cut-off run has the most telling rows.
        for level in sorted(noise, key=lambda n: (n != 0.2, n)):
            for shape in args.shapes.split(","):
                data["results"] += run_case(shape, level, radii, METHODS, args.compute_resolution)
                results.parent.mkdir(parents=True, exist_ok=True)
                results.write_text(json.dumps(data, indent=1))
    write_markdown(data, Path(args.markdown))
    plot(data, Path(args.plot))
    print(f"wrote {args.markdown}, {args.plot}")


if __name__ == "__main__":
    main()
