"""Tables (Markdown, between markers in docs/PEERS.md) and the error-versus-radius plot of the
peers benchmark, both made from the results JSON alone."""

from __future__ import annotations

import re
from pathlib import Path

from methods import METHODS

START, END = "<!-- peers-results:start -->", "<!-- peers-results:end -->"
SHAPES = ["sphere", "torus", "ellipsoid"]
Y_CLIP = 1e4   # plot range in %: the degenerate small-radius fits reach 1e35 and would flatten the rest


def label(key: str) -> str:
    return METHODS[key].label if key in METHODS else key


def progress_line(row: dict, name: str) -> str:
    where = f"  r={row['radius_pct']:g}%  {name:<22}"
    if row["status"] != "ok":
        return f"{where} {row['status']}: {row['detail']}"
    return (f"{where} {row['seconds']:8.2f} s (cpu {row['cpu_seconds']:8.2f} s)   "
            f"H {100 * row['h_error']:7.2f} %   K {100 * row['k_error']:7.2f} %")


def percent(value: float) -> str:
    """Three significant digits below 1 (= 100 %), whole percent up to 10^4 %, then 2.6e7 style."""
    value *= 100
    if value < 100:
        return f"{value:.3g}"
    if value < 1e4:
        return f"{value:.0f}"
    mantissa, exponent = f"{value:.1e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def seconds(value: float) -> str:
    return f"{value:.2g} s" if value < 10 else f"{value:.0f} s"


def cell(row: dict | None, notes: list[str]) -> str:
    if row is None:
        return "–"
    if row["status"] == "timeout":
        return "timeout"
    if row["status"] != "ok":
        notes.append(f"{label(row['method'])}, {row['shape']} {row['size']}, r = {row['radius_pct']:g} %: {row['detail']}")
        return f"error [{len(notes)}]"
    text = (f"{percent(row['h_error'])} / {percent(row['k_error'])} / {seconds(row['seconds'])} "
            f"(cpu {seconds(row['cpu_seconds'])})")
    if row.get("nonfinite"):
        text += f" ({row['nonfinite']} NaN)"
    if row.get("detail"):
        notes.append(f"{label(row['method'])}, {row['shape']} {row['size']}, r = {row['radius_pct']:g} %: {row['detail']}")
        text += f" [{len(notes)}]"
    return text


def _index(results: list[dict]) -> dict:
    return {(r["shape"], r["size"], r["noisy"], r["radius_pct"], r["method"]): r for r in results}


def _ordered(values, order):
    return sorted(set(values), key=lambda v: order.index(v) if v in order else len(order))


def summary_table(data: dict) -> list[str]:
    """The headline question: noisy torus and ellipsoid at 50K, H error at 4 and 8 %, and the time
    per noisy 200K-face mesh at 4 %."""
    index = _index(data["results"])
    methods = _ordered([r["method"] for r in data["results"]], list(METHODS))
    lines = ["| method | torus H 4 % | torus H 8 % | ellipsoid H 4 % | ellipsoid H 8 % | "
             "time 200K torus 4 % | time 200K ellipsoid 4 % |", "|---|---:|---:|---:|---:|---:|---:|"]
    for key in methods:
        cells = []
        for shape in ("torus", "ellipsoid"):
            for pct in (4.0, 8.0):
                row = index.get((shape, "50K", True, pct, key))
                cells.append(percent(row["h_error"]) if row and row["status"] == "ok" else (row or {}).get("status", "–"))
        for shape in ("torus", "ellipsoid"):
            row = index.get((shape, "200K", True, 4.0, key))
            cells.append(seconds(row["seconds"]) if row and row["status"] == "ok" else (row or {}).get("status", "–"))
        lines.append(f"| {label(key)} | " + " | ".join(cells) + " |")
    return lines


def detail_tables(data: dict, notes: list[str]) -> list[str]:
    results = data["results"]
    index = _index(results)
    methods = _ordered([r["method"] for r in results], list(METHODS))
    radii = sorted({r["radius_pct"] for r in results})
    lines = []
    for size in _ordered([r["size"] for r in results], ["50K", "200K"]):
        for shape in _ordered([r["shape"] for r in results if r["size"] == size], SHAPES):
            for noisy in (False, True):
                rows = [r for r in results if (r["shape"], r["size"], r["noisy"]) == (shape, size, noisy)]
                if not rows:
                    continue
                lines += ["", f"#### {shape}, {rows[0]['faces']:,} faces, {'noisy' if noisy else 'clean'}", "",
                          "| method | " + " | ".join(f"r = {pct:g} %" for pct in radii) + " |",
                          "|---|" + "---:|" * len(radii)]
                for key in methods:
                    cells = [cell(index.get((shape, size, noisy, pct, key)), notes) for pct in radii]
                    lines.append(f"| {label(key)} | " + " | ".join(cells) + " |")
    return lines


def parallelism(data: dict) -> str:
    """CPU time over wall time per method (summed over its runs of 1 s or more): how many cores it used."""
    ratios = []
    for key in _ordered([r["method"] for r in data["results"]], list(METHODS)):
        runs = [r for r in data["results"] if r["method"] == key and r["status"] == "ok" and r["seconds"] >= 1]
        if runs:
            ratio = sum(r["cpu_seconds"] for r in runs) / sum(r["seconds"] for r in runs)
            ratios.append(f"{label(key)} {ratio:.2f}")
    return "CPU time / wall time (cores used on average): " + ", ".join(ratios) + "."


def results_section(data: dict) -> str:
    m = data["machine"]
    versions = ", ".join(f"{name} {v}" for name, v in m["versions"].items() if v)
    notes: list[str] = []
    lines = [START, "",
             f"Measured on {m['cpu']}, {m['cores']} cores (shared with other jobs), Python {m['python']}; {versions}.",
             "Commands: " + ", then ".join(f"`{c}`" for c in data["commands"]) +
             f"; time limit {data['timeout_s']:.0f} s per method and mesh.", ""]
    for key, reason in data.get("skipped", {}).items():
        lines.append(f"- Not run: **{label(key)}**: {reason}")
    lines += ["", parallelism(data), "", "### Summary: noisy surfaces", "",
              "Range-normalised mean absolute error of H in % at 50K faces; wall time per noisy 200K-face mesh.", ""]
    lines += summary_table(data)
    lines += ["", "### All results", "",
              "Each cell: H error % / K error % / wall time (CPU time of the worker process). Errors are "
              "range-normalised mean absolute errors against the analytic value (sphere: normalised by "
              "the true value).",
              "\"timeout\": stopped at the time limit, or not run because a smaller radius already was."]
    lines += detail_tables(data, notes)
    if notes:
        lines += ["", "Errors:", ""] + [f"{i}. {note}" for i, note in enumerate(notes, 1)]
    lines += ["", END]
    return "\n".join(lines)


def write_markdown(data: dict, path: Path) -> None:
    section = results_section(data)
    text = path.read_text() if path.exists() else f"# Peers benchmark\n\n{START}\n{END}\n"
    pattern = re.compile(re.escape(START) + ".*?" + re.escape(END), re.S)
    if not pattern.search(text):
        text += f"\n{START}\n{END}\n"
    path.write_text(pattern.sub(lambda _: section, text))


def plot_noisy(data: dict, path: Path) -> None:
    """Error against radius per method on the noisy torus and ellipsoid (solid 50K, dashed 200K)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import NullFormatter

    results = [r for r in data["results"] if r["noisy"] and r["status"] == "ok"]
    methods = _ordered([r["method"] for r in results], list(METHODS))
    colours = {key: f"C{i}" for i, key in enumerate(METHODS)}
    figure, axes = plt.subplots(2, 2, figsize=(11, 8), sharex=True)
    for row_axes, shape in zip(axes, ("torus", "ellipsoid")):
        for ax, (quantity, name) in zip(row_axes, (("h_error", "H"), ("k_error", "K"))):
            for key in methods:
                for size, style in (("50K", "-"), ("200K", "--")):
                    points = sorted((r["radius_pct"], 100 * r[quantity]) for r in results
                                    if (r["shape"], r["size"], r["method"]) == (shape, size, key))
                    if points:
                        x, y = zip(*points)
                        ax.plot(x, y, style, marker="o", color=colours[key],
                                label=f"{label(key)} {size}" if shape == "torus" and name == "H" else None)
            ax.set(xscale="log", yscale="log", title=f"noisy {shape}: {name}", ylim=(None, Y_CLIP),
                   xlabel="radius, % of the diagonal", ylabel="range-normalised MAE, % (clipped at 10⁴)")
            ax.set_xticks([1, 2, 4, 8], ["1", "2", "4", "8"])
            ax.xaxis.set_minor_formatter(NullFormatter())
            ax.grid(True, which="both", alpha=0.3)
    if any(ax.get_legend_handles_labels()[0] for ax in axes.flat):
        figure.legend(loc="lower center", ncol=4, fontsize=8)
    figure.tight_layout(rect=(0, 0.1, 1, 1))
    path.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(path, dpi=110)
    plt.close(figure)
