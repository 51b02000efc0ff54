"""The estimators compared, one entry each in METHODS: a function (surface, radius) -> (H, K)
per vertex, in uvfeat's convention (outward normals: unit sphere H = K = +1), and a probe that
says why a method cannot run here (None when it can).

Neighbourhoods are matched to the radius r (object units) as follows: ball methods take r itself;
k-ring methods take k = round(r / h) rings, h the clean mesh's mean edge length (a k-ring reaches
about k edge lengths along the surface). Every function includes the library's own set-up (mesh
structures, trees, atlases), which a user pays per mesh.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from typing import Callable, Optional

import numpy as np

from surfaces import Surface


@dataclass(frozen=True)
class Method:
    label: str
    run: Callable[[Surface, float], tuple]
    probe: Callable[[], Optional[str]]
    note: str
    #: The library's module: its worker imports it before the first timed call.
    module: str


def rings(surface: Surface, radius: float) -> int:
    return max(1, int(round(radius / surface.spacing)))


def _missing(module: str) -> Callable[[], Optional[str]]:
    def probe() -> Optional[str]:
        try:
            importlib.import_module(module)
        except Exception as error:  # an import can fail with more than ImportError (binary wheels)
            return f"cannot import {module}: {error}"
        return None
    return probe


# --- uvfeat -----------------------------------------------------------------------------------

FEATURES = ["mean_curvature", "gaussian_curvature"]


def uvfeat_mesh(surface: Surface):
    import uvfeat
    return uvfeat.Mesh(surface.positions, surface.faces, surface.uvs, surface.uv_faces)


def _uvfeat_values(values: dict) -> tuple:
    return np.asarray(values["mean_curvature"], np.float64), np.asarray(values["gaussian_curvature"], np.float64)


def uvfeat_options(**options) -> Callable[[Surface, float], tuple]:
    """uvfeat.compute with the given options (the defaults when none)."""
    def run(surface: Surface, radius: float) -> tuple:
        import uvfeat
        return _uvfeat_values(uvfeat.compute(uvfeat_mesh(surface), FEATURES, radius=radius, **options))
    return run


def uvfeat_option_probe(**options) -> Callable[[], Optional[str]]:
    """Runs the options once on a small sphere: an unknown option or value says so."""
    def probe() -> Optional[str]:
        reason = _missing("uvfeat")()
        if reason:
            return reason
        import uvfeat
        try:
            uvfeat.compute(uvfeat.shapes.uv_sphere(1.0, 32, 16), FEATURES, radius=0.3, **options)
        except Exception as error:
            return f"uvfeat.compute({', '.join(f'{k}={v!r}' for k, v in options.items())}) fails: {error}"
        return None
    return probe


def uvfeat_reference(surface: Surface, radius: float) -> tuple:
    from uvfeat import reference
    return _uvfeat_values(reference.compute(uvfeat_mesh(surface), FEATURES, radius=radius))


def _reference_probe() -> Optional[str]:
    try:
        from uvfeat import reference
    except ImportError as error:
        return f"uvfeat.reference is not available: {error}"
    return None if hasattr(reference, "compute") else "uvfeat.reference has no compute()"


# --- peers ------------------------------------------------------------------------------------

def libigl(use_kring: bool) -> Callable[[Surface, float], tuple]:
    """igl.principal_curvature: quadric fit, PV1 >= PV2, same sign as ours (unit sphere: PV1 = PV2
    = +1). Its integer `radius` is k rings, or with useKring=False a ball of radius times the
    mesh's mean edge length; both get round(r / h)."""
    def run(surface: Surface, radius: float) -> tuple:
        import igl
        _, _, pv1, pv2, _ = igl.principal_curvature(surface.positions, surface.faces, radius=rings(surface, radius),
                                                   useKring=use_kring)
        return (pv1 + pv2) / 2, pv1 * pv2
    return run


TRIMESH_CHUNK = 256   # query points per call: bounds the candidate edges and neighbour lists trimesh holds at once


def trimesh_ball(surface: Surface, radius: float) -> tuple:
    """Cohen-Steiner & Morvan curvature measures of the ball B(v, r), as trimesh's own example
    turns them into point values: divided by sphere_ball_intersection(1, r), the area of a unit
    sphere inside the ball, which is pi r^2 for any sphere radius (and to leading order for any
    surface). The mean measure sums |e ∩ B| beta_e / 2 over the edges (convex positive), the
    Gaussian measure the angle defects of the vertices inside the ball."""
    import trimesh
    from trimesh.curvature import (discrete_gaussian_curvature_measure, discrete_mean_curvature_measure,
                                   sphere_ball_intersection)

    mesh = trimesh.Trimesh(surface.positions, surface.faces, process=False)
    area = sphere_ball_intersection(1.0, radius)
    chunks = [mesh.vertices[i:i + TRIMESH_CHUNK] for i in range(0, len(mesh.vertices), TRIMESH_CHUNK)]
    h = np.concatenate([discrete_mean_curvature_measure(mesh, c, radius) for c in chunks]) / area
    k = np.concatenate([discrete_gaussian_curvature_measure(mesh, c, radius) for c in chunks]) / area
    return h, k


def pymeshlab_sdqf(surface: Surface, radius: float) -> tuple:
    """MeshLab 'Scale Dependent Quadric Fitting' with an absolute scale r.

    One call gives H as the vertex quality ('Mean Curvature'); the filter stores the principal
    directions scaled by |k1| and |k2|, and K's sign follows from H: equal signs give
    |H| = (|k1| + |k2|)/2, opposite signs |H| = ||k1| - |k2||/2 (checked against a second call
    with 'Gaussian Curvature' in docs/PEERS.md)."""
    import pymeshlab

    meshes = pymeshlab.MeshSet()
    meshes.add_mesh(pymeshlab.Mesh(vertex_matrix=surface.positions, face_matrix=surface.faces))
    meshes.compute_curvature_principal_directions_per_vertex(
        method="Scale Dependent Quadric Fitting", curvcolormethod="Mean Curvature",
        scale=pymeshlab.PureValue(radius), autoclean=False)
    mesh = meshes.current_mesh()
    h = mesh.vertex_scalar_array()
    a = np.linalg.norm(mesh.vertex_curvature_principal_dir1_matrix(), axis=1)
    b = np.linalg.norm(mesh.vertex_curvature_principal_dir2_matrix(), axis=1)
    same_sign = np.abs(np.abs(h) - (a + b) / 2) <= np.abs(np.abs(h) - np.abs(a - b) / 2)
    return h, np.where(same_sign, a * b, -a * b)


def trueform_kring(surface: Surface, radius: float) -> tuple:
    """trueform.principal_curvatures over a k-ring, k0 >= k1 (sign checked on the unit sphere)."""
    import trueform

    k0, k1 = trueform.principal_curvatures((surface.faces.astype(np.int32), surface.positions),
                                           k=rings(surface, radius))
    return (k0 + k1) / 2, k0 * k1


METHODS = {
    "uvfeat": Method("uvfeat parametric", uvfeat_options(), uvfeat_option_probe(),
                     "uvfeat.compute, default options (1024² buffers, 512² texture, 256 samples)", "uvfeat"),
    "uvfeat-fit": Method("uvfeat fit", uvfeat_options(method="fit"), uvfeat_option_probe(method="fit"),
                         "uvfeat.compute(method='fit'): weighted least-squares fit of osculating circles with free offset and tilt",
                         "uvfeat"),
    "uvfeat-reference": Method("uvfeat reference", uvfeat_reference, _reference_probe,
                               "uvfeat.reference.compute: the mesh-space reference estimator", "uvfeat.reference"),
    "libigl": Method("libigl k-ring", libigl(use_kring=True), _missing("igl"),
                     "igl.principal_curvature(radius=k, useKring=True), k = round(r / h)", "igl"),
    "libigl-ball": Method("libigl ball", libigl(use_kring=False), _missing("igl"),
                          "igl.principal_curvature(radius=k, useKring=False): ball of k mean edge lengths", "igl"),
    "trimesh": Method("trimesh ball measures", trimesh_ball, _missing("trimesh"),
                      "discrete mean / Gaussian curvature measures of B(v, r) / (pi r^2)", "trimesh"),
    "pymeshlab": Method("MeshLab SDQF", pymeshlab_sdqf, _missing("pymeshlab"),
                        "pymeshlab Scale Dependent Quadric Fitting, scale = r (absolute)", "pymeshlab"),
    "trueform": Method("trueform k-ring", trueform_kring, _missing("trueform"),
                       "trueform.principal_curvatures(k), k = round(r / h)", "trueform"),
}
