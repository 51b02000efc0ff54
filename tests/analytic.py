"""Analytic meshes with several parameterisations, shared by the feature tests."""

import functools
import pathlib

import numpy as np
import trimesh

import uvfeat


@functools.lru_cache(maxsize=None)
def lat_long_sphere() -> uvfeat.Mesh:
    """Unit sphere, one chart with a seam and two poles (25,280 triangles)."""
    return uvfeat.shapes.uv_sphere(1.0, 160, 80)


@functools.lru_cache(maxsize=None)
def xatlas_icosphere() -> uvfeat.Mesh:
    """Unit icosphere (20,480 triangles) with an xatlas multi-chart atlas."""
    ico = trimesh.creation.icosphere(subdivisions=5)
    return uvfeat.Mesh(ico.vertices, ico.faces, name="icosphere").with_atlas(resolution=1024, method="xatlas")


@functools.lru_cache(maxsize=None)
def charts_icosphere() -> uvfeat.Mesh:
    """The same icosphere with uvfeat's own normal-cone atlas (the default for meshes without UVs)."""
    ico = trimesh.creation.icosphere(subdivisions=5)
    return uvfeat.Mesh(ico.vertices, ico.faces, name="icosphere (charts)").with_atlas(resolution=1024)


@functools.lru_cache(maxsize=None)
def charts_sphere_atlas() -> uvfeat.Atlas:
    """The 96 x 48 lat-long sphere re-atlased into uvfeat's own charts (512² buffers): seams all
    round a convex surface, where a developed sampling domain overlaps itself."""
    s = uvfeat.shapes.uv_sphere(1.0, 96, 48)
    mesh = uvfeat.Mesh(s.positions, s.faces).with_atlas(cache=False)
    assert mesh.n_charts > 3
    return uvfeat.Atlas(mesh, resolution=512)


def neighbourhood_areas(atlas: uvfeat.Atlas, radius: float, **options) -> np.ndarray:
    """Each texel's neighbourhood area (48² texels, 256 samples) over pi r^2: 1 on a sphere
    (Archimedes: the sphere inside a ball of radius r centred on it has area pi r^2)."""
    areas = [(tile.areas * tile.valid).sum(1) for tile in
             atlas.neighbourhoods(radius, samples=256, compute_resolution=48, **options)]
    return np.concatenate(areas) / (np.pi * radius * radius)


@functools.lru_cache(maxsize=None)
def torus_single() -> uvfeat.Mesh:
    return uvfeat.shapes.torus(2.0, 0.5, 256, 128)


#: xatlas's atlas of :func:`torus_single` (xatlas 0.0.11 defaults, as ``with_atlas(method="xatlas")``
#: makes it): stored, because computing it takes 14 s of every test process that uses it.
TORUS_XATLAS = pathlib.Path(__file__).parent / "data" / "torus_xatlas.npz"


@functools.lru_cache(maxsize=None)
def torus_xatlas() -> uvfeat.Mesh:
    t = torus_single()
    with np.load(TORUS_XATLAS) as stored:
        return uvfeat.Mesh(t.positions, t.faces, stored["uvs"], stored["uv_faces"].astype(np.int64),
                           name="torus (xatlas)")


@functools.lru_cache(maxsize=None)
def torus_charts() -> uvfeat.Mesh:
    t = torus_single()
    return uvfeat.Mesh(t.positions, t.faces, name="torus (charts)").with_atlas(resolution=1024)


def torus_truth(mesh: uvfeat.Mesh, major: float = 2.0, minor: float = 0.5):
    """Analytic H and K at the vertices of a torus around z."""
    p = mesh.positions
    ring = np.hypot(p[:, 0], p[:, 1]) - major
    cos_v = np.clip(ring / minor, -1.0, 1.0)
    h = (major + 2 * minor * cos_v) / (2 * minor * (major + minor * cos_v))
    k = cos_v / (minor * (major + minor * cos_v))
    return h, k, cos_v


def range_normalised_error(values: np.ndarray, reference: np.ndarray) -> float:
    """DESIGN.md §5.1 %AE / 100: mean |f - f_ref| / (Q99 - Q1 of f_ref)."""
    ok = np.isfinite(values) & np.isfinite(reference)
    q1, q99 = np.percentile(reference[ok], [1, 99])
    return float(np.mean(np.abs(values[ok] - reference[ok])) / (q99 - q1))
