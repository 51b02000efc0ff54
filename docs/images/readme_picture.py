"""Draws the README's pictures with uvfeat.plot: the bundled Spot mesh coloured by its mean
curvature (docs/images/spot_mean_curvature.png) and by its shape index from two views
(docs/images/spot_shape_index_3d.png), at three radii, one colour range for all three.

    .venv/bin/python docs/images/readme_picture.py
"""

from __future__ import annotations

import os

import uvfeat

RADII = ("1%", "4%", "16%")
FOLDER = os.path.dirname(os.path.abspath(__file__))


def main() -> None:
    mesh = uvfeat.examples.spot()
    maps = uvfeat.Atlas(mesh).compute(["mean_curvature", "shape_index"], radius=list(RADII))
    pictures = {"spot_mean_curvature.png": ("mean_curvature", [(15.0, -50.0)], 2.6),
                "spot_shape_index_3d.png": ("shape_index", ["side", "back"], 2.4)}
    for name, (feature, views, inches) in pictures.items():
        path = os.path.join(FOLDER, name)
        uvfeat.plot(mesh, maps[feature].per_vertex(), feature=feature, radius=[f"{r} of the diagonal" for r in RADII],
                    views=views, panel_inches=inches, dpi=90, title=f"Spot: {feature}", path=path)
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
