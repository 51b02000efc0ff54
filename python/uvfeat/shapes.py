"""Analytic UV-mapped meshes with known curvature (built by the Rust core).

UVs lie in ``[0.02, 0.98]^2``; periodic directions are seams of the single chart.
"""

from __future__ import annotations

from . import _core
from .mesh import Mesh


def _mesh(name: str, sizes, counts, label: str, mirrored: bool = False) -> Mesh:
    positions, faces, uvs, uv_faces = _core.shape(name, [float(s) for s in sizes], [int(c) for c in counts], mirrored)
    return Mesh(positions, faces, uvs, uv_faces, name=label)


def uv_sphere(radius: float = 1.0, n_lon: int = 128, n_lat: int = 64) -> Mesh:
    """Latitude-longitude sphere: ``H = 1/radius``, ``K = 1/radius^2`` (outward normals)."""
    return _mesh("uv_sphere", [radius], [n_lon, n_lat], f"sphere r={radius}")


def ellipsoid(a: float = 1.0, b: float = 0.8, c: float = 0.6, n_lon: int = 128, n_lat: int = 64) -> Mesh:
    """Ellipsoid with semi-axes ``a, b, c`` along x, y, z, latitude-longitude parameterised."""
    return _mesh("ellipsoid", [a, b, c], [n_lon, n_lat], f"ellipsoid {a}x{b}x{c}")


def torus(major: float = 2.0, minor: float = 0.5, n_u: int = 128, n_v: int = 64) -> Mesh:
    """Torus around z; ``H = (R + 2a cos v)/(2a(R + a cos v))``, ``K = cos v/(a(R + a cos v))``."""
    return _mesh("torus", [major, minor], [n_u, n_v], f"torus R={major} a={minor}")


def cylinder(radius: float = 1.0, height: float = 2.0, n_around: int = 128, n_along: int = 32) -> Mesh:
    """Open cylinder around z: ``H = 1/(2 radius)``, ``K = 0``; two border loops."""
    return _mesh("cylinder", [radius, height], [n_around, n_along], f"cylinder r={radius}")


def plane(size: float = 1.0, n: int = 32) -> Mesh:
    """Square ``[0, size]^2`` in ``z = 0`` with an affine parameterisation."""
    return _mesh("plane", [size], [n], f"plane {size}")


def split_plane(n: int = 32, mirrored: bool = False) -> Mesh:
    """Unit square cut into two charts; the right one rotated, stretched and optionally mirrored."""
    return _mesh("split_plane", [], [n], "split plane" + (" (mirrored)" if mirrored else ""), mirrored)
