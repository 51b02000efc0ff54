"""3D pictures of a 100K-face mesh: the renderers uvfeat could use, timed on one view written as an
800-pixel PNG (docs/BENCHMARKS.md, "3D pictures").

- painter, flat: matplotlib PolyCollection sorted far to near, one colour per face (uvfeat's
  former renderer);
- painter, Gouraud: matplotlib's Gouraud-shaded triangles (tripcolor), sorted far to near;
- z-buffer: uvfeat.pictures.render (the core's rasteriser; smooth shading, per-pixel values, 2x2 supersampling);
- polyscope, EGL: an offscreen OpenGL stack from PyPI (needs the system's EGL/Mesa; skipped when
  polyscope or EGL is missing).

    .venv/bin/python benches/bench_render.py [--repeat 3] [--pixels 800]
"""

from __future__ import annotations

import argparse
import os
import statistics
import tempfile
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import uvfeat  # noqa: E402
from uvfeat.pictures.render import VIEW, draw_vertex_values, view_coordinates  # noqa: E402


def figure(pixels: int):
    fig = plt.figure(figsize=(pixels / 100, pixels / 100), dpi=100)
    return fig, fig.add_axes([0, 0, 1, 1])


def painter(mesh, values, path, pixels, gouraud):
    from matplotlib.collections import PolyCollection

    p = view_coordinates(mesh.positions, VIEW, "y")
    order = np.argsort(p[mesh.faces][:, :, 2].mean(axis=1))
    fig, ax = figure(pixels)
    if gouraud:
        ax.tripcolor(p[:, 0], p[:, 1], mesh.faces[order], values, shading="gouraud", cmap="RdBu_r")
    else:
        colours = matplotlib.colormaps["RdBu_r"](values[mesh.faces].mean(axis=1))[order]
        ax.add_collection(PolyCollection(p[mesh.faces[order]][:, :, :2], facecolors=colours, edgecolors=colours,
                                         linewidths=0.3))
    ax.set_xlim(p[:, 0].min(), p[:, 0].max())
    ax.set_ylim(p[:, 1].min(), p[:, 1].max())
    ax.set_aspect("equal")
    fig.savefig(path)
    plt.close(fig)


def zbuffer(mesh, values, path, pixels):
    fig, ax = figure(pixels)
    draw_vertex_values(ax, mesh.positions, mesh.faces, values, "RdBu_r", 0.0, 1.0)
    fig.savefig(path)
    plt.close(fig)


def polyscope_egl():
    """A screenshot function on polyscope's EGL backend, or None where it cannot start."""
    try:
        import polyscope as ps

        ps.init("openGL3_egl")
    except Exception as exc:  # noqa: BLE001 - any failure means the candidate is unavailable here
        print(f"polyscope EGL unavailable: {exc}")
        return None

    def shoot(mesh, values, path, pixels):
        ps.remove_all_structures()
        ps.set_window_size(pixels, pixels)
        ps.set_ground_plane_mode("none")
        surface = ps.register_surface_mesh("mesh", mesh.positions, mesh.faces)
        surface.add_scalar_quantity("value", values, cmap="coolwarm", enabled=True)
        ps.screenshot(path, transparent_bg=False)

    return shoot


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--pixels", type=int, default=800)
    args = parser.parse_args()
    mesh = uvfeat.shapes.torus(2.0, 0.5, 320, 160)
    values = (mesh.positions[:, 2] - mesh.positions[:, 2].min()) / np.ptp(mesh.positions[:, 2])
    candidates = {"painter, flat (matplotlib PolyCollection)": lambda *a: painter(*a, gouraud=False),
                  "painter, Gouraud (matplotlib tripcolor)": lambda *a: painter(*a, gouraud=True),
                  "z-buffer (uvfeat.pictures.render)": zbuffer}
    shoot = polyscope_egl()
    if shoot is not None:
        candidates["polyscope, EGL (offscreen OpenGL)"] = shoot
    print(f"{mesh.n_faces:,} faces, one view, {args.pixels}-pixel PNG, median of {args.repeat}")
    with tempfile.TemporaryDirectory() as folder:
        timings = {}
        for name, draw in candidates.items():
            path = os.path.join(folder, "view.png")
            draw(mesh, values, path, args.pixels)  # warm-up: imports, first-call set-up
            times = []
            for _ in range(args.repeat):
                started = time.perf_counter()
                draw(mesh, values, path, args.pixels)
                times.append(time.perf_counter() - started)
            timings[name] = statistics.median(times)
    base = timings["z-buffer (uvfeat.pictures.render)"]
    for name, seconds in timings.items():
        print(f"| {name} | {1e3 * seconds:,.0f} | {seconds / base:.2f} |")


if __name__ == "__main__":
    main()
