"""uvfeat: multi-scale geometric features of triangle meshes, computed in UV parameter space.

Quick start::

    import uvfeat
    mesh = uvfeat.load("model.obj")            # or uvfeat.Mesh(positions, faces, uvs, uv_faces)
    atlas = uvfeat.Atlas(mesh, resolution=1024)
    atlas.position, atlas.normal, atlas.chart  # (R, R, ...) read-only NumPy buffers
    maps = atlas.compute(["mean_curvature", "shape_index"], radius="2%")
    maps["mean_curvature"].texture, maps["mean_curvature"].per_vertex()
    values = uvfeat.compute(mesh, "gaussian_curvature", radius=0.05)   # one shot, per vertex
    values = uvfeat.compute(trimesh_mesh, "mean_curvature", "2%")   # trimesh, PyVista, Open3D, arrays too
    for frame in uvfeat.animate("fox.glb", "mean_curvature", "2%", fps=24):   # per animation frame
        frame.time, frame["mean_curvature"]
    table = uvfeat.batch(["scans/", "*.ply"], "mean_curvature", "2%", out="runs/")   # many meshes, on Dask
    ref = uvfeat.reference.compute(mesh, "gaussian_curvature", radius=0.05)  # object-space reference
    uvfeat.plot(mesh, maps["mean_curvature"], path="H.png")    # the mesh coloured by it, headless
    uvfeat.view(mesh, maps)                    # interactive: radius slider, UV map (uvfeat[view])

Conventions: lengths in the mesh's units; UV in [0, 1]^2 with v up; outward normals by the
right-hand rule on counter-clockwise faces; H = (k1 + k2)/2 > 0 on convex regions.
"""

from . import compare, errors, examples, options, reference, shapes, unwrap
from ._core import __version__
from .animation import Animation, AnimationFrame, GltfAnimation, animate
from .atlas import Atlas, Location, Neighbourhoods, SeamCrossing
from .files.bake import bake
from .batch import batch
from .compute import compute
from .converged import ConvergedReference, converged_reference
from .errors import (
    AnimationError,
    ClusterError,
    InvalidMeshError,
    InvalidParameterError,
    MeshFileError,
    MeshWarning,
    MissingDependencyError,
    NeighbourhoodWarning,
    ResolutionTooLargeError,
    UvfeatError,
    UVError,
    UVWarning,
    ViewerError,
)
from .features import FeatureMap
from .options import FEATURES
from .pictures.surface_plot import plot
from .pictures.viewer import view
from .interop import attach, to_pyvista
from .io import SUPPORTED_FORMATS, load
from .mesh import Mesh

__all__ = [
    "Animation",
    "AnimationError",
    "AnimationFrame",
    "Atlas",
    "ClusterError",
    "FEATURES",
    "FeatureMap",
    "GltfAnimation",
    "Neighbourhoods",
    "attach",
    "bake",
    "compute",
    "ConvergedReference",
    "converged_reference",
    "InvalidMeshError",
    "InvalidParameterError",
    "Location",
    "Mesh",
    "MeshFileError",
    "MeshWarning",
    "MissingDependencyError",
    "NeighbourhoodWarning",
    "ResolutionTooLargeError",
    "SUPPORTED_FORMATS",
    "SeamCrossing",
    "UVError",
    "UVWarning",
    "UvfeatError",
    "ViewerError",
    "__version__",
    "animate",
    "batch",
    "compare",
    "errors",
    "examples",
    "load",
    "options",
    "plot",
    "to_pyvista",
    "reference",
    "shapes",
    "unwrap",
    "view",
]
