"""Draws docs/images/spot_mean_curvature.png, the README's picture: the bundled Spot mesh coloured by
its mean curvature at three radii, one colour range for all three.

    .venv/bin/python docs/images/readme_picture.py
"""

from __future__ import annotations

import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import uvfeat  # noqa: E402
from uvfeat.images import colour_range  # noqa: E402
from uvfeat.render import draw_vertex_values  # noqa: E402

RADII = ("1%", "4%", "16%")


def main() -> None:
    mesh = uvfeat.examples.spot()
    maps = uvfeat.Atlas(mesh).compute("mean_curvature", radius=list(RADII))
    values = maps["mean_curvature"].per_vertex()  # (n_radii, n_vertices)
    cmap, low, high = colour_range("mean_curvature", values.ravel())
    figure, axes = plt.subplots(1, len(RADII), figsize=(10, 3.6))
    for ax, radius, per_vertex in zip(axes, RADII, values):
        mappable = draw_vertex_values(ax, mesh.positions, mesh.faces, per_vertex, cmap, low, high, view=(15.0, -50.0))
        ax.set_title(f"r = {radius} of the diagonal")
    figure.colorbar(mappable, ax=axes, shrink=0.8, label="mean curvature H (1 / length)")
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "spot_mean_curvature.png")
    figure.savefig(path, dpi=90, bbox_inches="tight")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
