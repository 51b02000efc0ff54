"""Automatic multi-chart UV atlases with xatlas, for meshes that have none (SPEC §1.1)."""

from __future__ import annotations

import numpy as np

from .errors import InvalidMeshError


def xatlas_uvs(positions: np.ndarray, faces: np.ndarray, *, resolution: int = 1024, padding: int = 4,
               max_chart_area: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Charts and packs the mesh with xatlas.

    Parameters
    ----------
    positions : (n_vertices, 3) float64
    faces : (n_faces, 3) int64
    resolution : int
        Texture size the packing is made for; ``padding`` is in texels at that size. Use the
        geometry-buffer resolution so that gutters are at least 2 texels there (SPEC §1.1).
    padding : int
        Gutter between charts, in texels at ``resolution``.
    max_chart_area : float
        Upper bound of a chart's surface area (0 = xatlas's default, unbounded); smaller values
        give more charts.

    Returns
    -------
    uvs : (n_uvs, 2) float64 in [0, 1]
    uv_faces : (n_faces, 3) int64, in the order of ``faces``
    """
    import xatlas

    atlas = xatlas.Atlas()
    atlas.add_mesh(np.ascontiguousarray(positions, dtype=np.float32), np.ascontiguousarray(faces, dtype=np.uint32))
    chart_options = xatlas.ChartOptions()
    if max_chart_area > 0:
        chart_options.max_chart_area = float(max_chart_area)
    pack_options = xatlas.PackOptions()
    pack_options.resolution = int(resolution)
    pack_options.padding = int(padding)
    pack_options.bilinear = True
    atlas.generate(chart_options, pack_options)
    vmapping, indices, uvs = atlas[0]
    if len(indices) != len(faces) or not np.array_equal(vmapping[indices], faces):
        raise InvalidMeshError("xatlas changed the faces of the mesh (degenerate or non-manifold input?); "
                               "clean the mesh or provide UVs")
    return np.ascontiguousarray(uvs, dtype=np.float64), np.ascontiguousarray(indices, dtype=np.int64)
