"""The error map of docs/EXPERIMENTS.md: |H - truth| on the xatlas armadillo at r = 6 %,
with the paper's pattern and with the surfels, against the converged reference, on one colour scale.

    .venv/bin/python docs/images/scan_drift_picture.py      # needs the shared armadillo.obj
"""

import os
import pathlib
import warnings

import numpy as np

import uvfeat

HERE = pathlib.Path(__file__).parent
RADIUS = "6%"


def main() -> None:
    folder = pathlib.Path(os.environ.get("UVFEAT_SHARED_MESHES", HERE.parents[2] / "shared" / "meshes"))
    warnings.simplefilter("ignore")
    mesh = uvfeat.load(str(folder / "armadillo.obj"), uv="xatlas")
    truth = uvfeat.converged_reference(mesh, "mean_curvature", RADIUS, max_levels=1)["mean_curvature"]
    atlas = uvfeat.Atlas(mesh)
    errors = []
    for quadrature in ("pattern", "surfels"):
        H = atlas.compute("mean_curvature", RADIUS, query="direct", quadrature=quadrature)["mean_curvature"]
        errors.append(np.abs(H.per_vertex() - truth))
    spread = np.percentile(truth, 99) - np.percentile(truth, 1)
    errors = 100 * np.stack(errors) / spread
    uvfeat.plot(mesh, errors, feature="|H - truth| (% of range)", radius=[f"{RADIUS}, pattern", f"{RADIUS}, surfels"],
                views=["front", "back"], low=0.0, high=5.0, title="armadillo (266 xatlas charts): error of H",
                path=HERE / "armadillo_H_error.png")
    print("%AE", errors.mean(axis=1))


if __name__ == "__main__":
    main()
