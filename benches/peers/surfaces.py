"""Analytic test surfaces for the peers benchmark: meshes, per-vertex truth, normal noise.

Each surface is a uvfeat analytic mesh (one UV chart, welded vertices) with the analytic mean
and Gaussian curvature at its vertices (outward normals: unit sphere H = K = +1). The noisy
variant moves every vertex along its clean vertex normal by a Gaussian offset; its truth stays the
clean surface's value at the vertex's original position.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import trimesh

import uvfeat

NOISE_FRACTION = 0.002   # noise std as a fraction of the bounding-box diagonal (0.2 %)
NOISE_SEED = 0

# Grid resolution per size: the lat-long sphere and ellipsoid have 2 n_lon (n_lat - 1) faces,
# the torus 2 n_u n_v: 224 x 112 gives ~50K faces, 448 x 224 ~200K.
GRIDS = {"50K": (224, 112), "200K": (448, 224)}

TORUS = (2.0, 0.5)              # major, minor radius
ELLIPSOID = (1.0, 0.8, 0.6)     # semi-axes along x, y, z


@dataclass
class Surface:
    """A benchmark mesh with its truth; arrays are plain NumPy so they pickle to workers."""

    shape: str
    size: str
    noisy: bool
    positions: np.ndarray
    faces: np.ndarray
    uvs: np.ndarray
    uv_faces: np.ndarray
    true_h: np.ndarray
    true_k: np.ndarray
    diagonal: float      # of the clean mesh: radii are fractions of it, the same for clean and noisy
    spacing: float       # mean edge length of the clean mesh (tangential vertex spacing)

    @property
    def label(self) -> str:
        return f"{self.shape} {self.size} {'noisy' if self.noisy else 'clean'}"



def mean_edge(positions: np.ndarray, faces: np.ndarray) -> float:
    """Mean length of the unique edges (libigl's avg_edge_length on a closed mesh)."""
    edges = np.unique(np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1), axis=0)
    return float(np.linalg.norm(positions[edges[:, 0]] - positions[edges[:, 1]], axis=1).mean())


def sphere_truth(p: np.ndarray, radius: float = 1.0):
    n = len(p)
    return np.full(n, 1.0 / radius), np.full(n, 1.0 / radius ** 2)


def torus_truth(p: np.ndarray, major: float = TORUS[0], minor: float = TORUS[1]):
    """H = (R + 2a cos v) / (2a (R + a cos v)), K = cos v / (a (R + a cos v)); torus around z."""
    cos_v = np.clip((np.hypot(p[:, 0], p[:, 1]) - major) / minor, -1.0, 1.0)
    h = (major + 2 * minor * cos_v) / (2 * minor * (major + minor * cos_v))
    k = cos_v / (minor * (major + minor * cos_v))
    return h, k


def ellipsoid_truth(p: np.ndarray, axes=ELLIPSOID):
    """Implicit-surface formulas with outward normals, S = sum x_i^2 / a_i^4:
    K = 1 / ((abc)^2 S^2),  H = (a^2 + b^2 + c^2 - |p|^2) / (2 (abc)^2 S^(3/2))."""
    a = np.asarray(axes, dtype=np.float64)
    s = (p ** 2 / a ** 4).sum(axis=1)
    abc2 = float(np.prod(a)) ** 2
    k = 1.0 / (abc2 * s ** 2)
    h = ((a ** 2).sum() - (p ** 2).sum(axis=1)) / (2 * abc2 * s ** 1.5)
    return h, k


def _clean_mesh(shape: str, size: str) -> tuple[uvfeat.Mesh, tuple]:
    n_u, n_v = GRIDS[size]
    if shape == "sphere":
        return uvfeat.shapes.uv_sphere(1.0, n_u, n_v), sphere_truth
    if shape == "torus":
        return uvfeat.shapes.torus(*TORUS, n_u, n_v), torus_truth
    if shape == "ellipsoid":
        return uvfeat.shapes.ellipsoid(*ELLIPSOID, n_u, n_v), ellipsoid_truth
    raise ValueError(f"unknown shape {shape!r} (sphere, torus, ellipsoid)")


def build(shape: str, size: str, noisy: bool, noise_fraction: float = NOISE_FRACTION) -> Surface:
    """The surface, clean or with normal noise of ``noise_fraction`` of the diagonal (std)."""
    mesh, truth = _clean_mesh(shape, size)
    clean = np.array(mesh.positions)
    true_h, true_k = truth(clean)
    diagonal = float(np.linalg.norm(clean.max(axis=0) - clean.min(axis=0)))
    positions = clean
    if noisy:
        normals = trimesh.Trimesh(clean, mesh.faces, process=False).vertex_normals
        offsets = np.random.default_rng(NOISE_SEED).normal(0.0, noise_fraction * diagonal, len(clean))
        positions = clean + offsets[:, None] * normals
    return Surface(shape, size, noisy, positions, np.array(mesh.faces), np.array(mesh.uvs),
                   np.array(mesh.uv_faces), true_h, true_k, diagonal,
                   mean_edge(clean, np.array(mesh.faces)))


def normalised_error(estimate: np.ndarray, truth: np.ndarray) -> float:
    """Mean |estimate - truth| over the finite estimates, divided by the truth's range
    (max - min); where the truth is constant (sphere) by its mean magnitude instead."""
    ok = np.isfinite(estimate)
    spread = float(truth.max() - truth.min())
    scale = spread if spread > 1e-9 * float(np.abs(truth).max()) else float(np.abs(truth).mean())
    return float(np.abs(estimate[ok] - truth[ok]).mean() / scale)
