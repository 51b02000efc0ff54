"""Plots of benches/experiments.py (matplotlib, Agg): one PNG per experiment, the paper's numbers
as dashed lines or on a second axis where it gives them."""

from __future__ import annotations

from pathlib import Path

import numpy as np

H = "mean_curvature"


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _mean(rows, key, **match):
    values = [r[key] for r in rows if all(r.get(k) == v for k, v in match.items()) and r.get(key) is not None]
    return float(np.nanmean(values)) if values else float("nan")


def _save(fig, path: Path) -> None:
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    _pyplot().close(fig)


def table1(rows, path: Path) -> None:
    from experiments_report import PAPER_T1

    plt = _pyplot()
    ns = sorted({r["N"] for r in rows})
    fig, (ax_t, ax_e) = plt.subplots(1, 2, figsize=(11, 4.2))
    for variant in dict.fromkeys(r["variant"] for r in rows):
        ax_t.plot(ns, [_mean(rows, "parametric_ms", N=n, variant=variant) for n in ns], "o-", label=f"ours, {variant}")
        ax_e.plot(ns, [_mean(rows, "percent_ae", N=n, variant=variant) for n in ns], "o-", label=f"ours, {variant}")
    paper_ax = ax_t.twinx()
    for variant, style in (("full", "k--"), ("adaptive", "k:")):
        xs = [n for n in PAPER_T1]
        paper_ax.plot(xs, [PAPER_T1[n][variant][0] for n in xs], style, label=f"paper (GPU), {variant}")
        ax_e.plot(xs, [PAPER_T1[n][variant][1] for n in xs], style, label=f"paper, {variant}")
    paper_ax.set_ylabel("paper ms (GPU)")
    ax_t.set(xlabel="samples N", ylabel="ours ms (CPU)", title="time")
    ax_e.set(xlabel="samples N", ylabel="%AE", title="%AE against the reference")
    ax_t.legend(fontsize=7, loc="upper left")
    paper_ax.legend(fontsize=7, loc="lower right")
    ax_e.legend(fontsize=7)
    _save(fig, path)


def features(rows, path: Path) -> None:
    from experiments_report import PAPER_AVERAGE_AE

    plt = _pyplot()
    per = [r for r in rows if r["feature"] != "all (one pass)"]
    meshes = list(dict.fromkeys(r["mesh"] for r in per))
    names = list(dict.fromkeys(r["feature"] for r in per))
    x = np.arange(len(names))
    width = 0.8 / max(len(meshes), 1)
    fig, (ax_e, ax_s) = plt.subplots(2, 1, figsize=(12, 7.5), sharex=True)
    for i, mesh in enumerate(meshes):
        ax_e.bar(x + i * width, [_mean(per, "percent_ae", mesh=mesh, feature=f) for f in names], width, label=mesh)
        ax_s.bar(x + i * width, [_mean(per, "speedup", mesh=mesh, feature=f) for f in names], width, label=mesh)
    ax_e.axhline(PAPER_AVERAGE_AE, color="k", ls="--", label=f"paper average {PAPER_AVERAGE_AE} %")
    ax_s.axhline(1.0, color="k", lw=0.8)
    ax_e.set(ylabel="%AE against the reference", yscale="log", title="per-feature %AE, r = 2 %")
    ax_s.set(ylabel="speed-up (reference / parametric)", yscale="log")
    ax_s.set_xticks(x + 0.4 - width / 2, names, rotation=20)
    ax_e.legend(fontsize=7, ncol=3)
    _save(fig, path)


def triangles(rows, path: Path) -> None:
    plt = _pyplot()
    faces = [r["faces"] for r in rows]
    fig, (ax_t, ax_e) = plt.subplots(1, 2, figsize=(11, 4.2))
    ax_t.plot(faces, [r["parametric_ms"] for r in rows], "o-", label="parametric")
    ax_t.plot(faces, [r["reference_ms"] for r in rows], "s-", label="reference")
    ax_t.set(xscale="log", yscale="log", xlabel="triangles", ylabel="ms", title="time, r = 4 %")
    ax_e.plot(faces, [r["percent_ae"] for r in rows], "o-", label="parametric vs reference")
    ax_e.plot(faces, [r.get("truth_pct_ae", np.nan) for r in rows], "^--", label="parametric vs truth")
    ax_e.plot(faces, [r.get("reference_truth_pct_ae", np.nan) for r in rows], "v--", label="reference vs truth")
    ax_e.set(xscale="log", xlabel="triangles", ylabel="%AE", title="error")
    for ax in (ax_t, ax_e):
        ax.legend(fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
    _save(fig, path)


def radius(rows, path: Path) -> None:
    plt = _pyplot()
    fig, (ax_t, ax_e, ax_m) = plt.subplots(1, 3, figsize=(14, 4.2))
    for jumps, style in (("default", "-"), (1, "--")):
        subset = [r for r in rows if r["max_jumps"] == jumps]
        rs = [r["radius_pct"] for r in subset]
        label = "max_jumps 32" if jumps == "default" else "max_jumps 1"
        ax_t.plot(rs, [r["parametric_ms"] for r in subset], "o" + style, color="C0", label=f"parametric, {label}")
        ax_e.plot(rs, [r["percent_ae"] for r in subset], "o" + style, color="C0", label=f"vs reference, {label}")
        ax_e.plot(rs, [r.get("truth_pct_ae", np.nan) for r in subset], "^" + style, color="C2",
                  label=f"vs truth, {label}")
        ax_m.plot(rs, [100 * r["missing_fraction"] for r in subset], "o" + style, color="C0", label=f"samples, {label}")
        ax_m.plot(rs, [100 * r["texels_with_missing"] for r in subset], "x" + style, color="C3",
                  label=f"texels, {label}")
        if jumps == "default":
            ax_t.plot(rs, [r["reference_ms"] for r in subset], "s-", color="C1", label="reference")
    ax_t.set(yscale="log", xlabel="radius, % of the diagonal", ylabel="ms", title="time")
    ax_e.set(xlabel="radius, % of the diagonal", ylabel="%AE", title="error of H")
    ax_m.set(xlabel="radius, % of the diagonal", ylabel="%", title="missing samples / texels with one")
    for ax in (ax_t, ax_e, ax_m):
        ax.legend(fontsize=7)
        ax.grid(True, alpha=0.3)
    _save(fig, path)


def samples(rows, path: Path) -> None:
    plt = _pyplot()
    ns = sorted({r["N"] for r in rows})
    fig, (ax_t, ax_e) = plt.subplots(1, 2, figsize=(11, 4.2))
    for config in dict.fromkeys(r["config"] for r in rows):
        ax_t.plot(ns, [_mean(rows, "parametric_ms", N=n, config=config) for n in ns], "o-", label=config)
        ax_e.plot(ns, [_mean(rows, "percent_ae", N=n, config=config) for n in ns], "o-", label=config)
    ax_t.set(xlabel="samples N", ylabel="ms", title="time (Fig. 11)", xlim=(0, None), ylim=(0, None))
    ax_e.set(xlabel="samples N", ylabel="%AE", title="%AE (Fig. 12)", xlim=(0, None))
    for ax in (ax_t, ax_e):
        ax.legend(title="buffers / computation", fontsize=8)
        ax.grid(True, alpha=0.3)
    _save(fig, path)


def charts(rows, path: Path) -> None:
    plt = _pyplot()
    rows = sorted(rows, key=lambda r: r["charts"])
    labels = [f"{r['atlas']}\n{r['charts']} charts" for r in rows]
    x = np.arange(len(rows))
    fig, (ax_t, ax_e) = plt.subplots(1, 2, figsize=(12, 4.5))
    ax_t.bar(x, [r["parametric_ms"] for r in rows])
    ax_t.set(ylabel="parametric ms", title="time")
    ax_e.bar(x - 0.2, [r["percent_ae"] for r in rows], 0.4, label="vs reference")
    ax_e.bar(x + 0.2, [r.get("truth_pct_ae", np.nan) for r in rows], 0.4, label="vs analytic truth")
    ax_e.set(ylabel="%AE", title="error of H")
    ax_e.legend(fontsize=8)
    for ax in (ax_t, ax_e):
        ax.set_xticks(x, labels, fontsize=7)
    _save(fig, path)


PLOTS = {"table1": table1, "features": features, "triangles": triangles, "radius": radius, "samples": samples,
         "charts": charts}


def write_all(data: dict, folder: Path) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    for name, plot in PLOTS.items():
        rows = data["experiments"].get(name, {}).get("rows")
        if rows:
            plot(rows, folder / f"{name}.png")
