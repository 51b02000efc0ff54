"""One-shot feature computation: mesh in, per-vertex arrays out."""

from __future__ import annotations

import numpy as np

from .atlas import Atlas
from .mesh import Mesh


def compute(mesh: Mesh, features, radius, *, resolution: int = 1024, precision: str = "f32",
            paper_mode: bool = False, **options) -> dict[str, np.ndarray]:
    """Per-vertex features of ``mesh`` (one value per row of ``mesh.positions``).

    Builds an :class:`~uvfeat.Atlas` at ``resolution`` and calls :meth:`~uvfeat.Atlas.per_vertex`
    with ``features``, ``radius`` and ``**options`` (``samples``, ``compute_resolution``,
    ``adaptive``, ``seed``, ``quadrature``, ...): with ``quadrature="surfels"`` the values are
    evaluated at the vertices, with no maps. For several calls on the same mesh keep an Atlas.

    Returns
    -------
    dict of str to ndarray
        ``(n_vertices,)`` float32 per feature (``(n_radii, n_vertices)`` for a list of radii).
    """
    if not mesh.has_uvs:
        mesh = mesh.with_atlas(resolution=resolution)
    if paper_mode:
        precision = "f16"
    atlas = Atlas(mesh, resolution=resolution, precision=precision)
    return atlas.per_vertex(features, radius, paper_mode=paper_mode, **options)
