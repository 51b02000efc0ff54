"""One-shot feature computation: mesh in, per-vertex arrays out."""

from __future__ import annotations

import numpy as np

from .atlas import Atlas
from .interop import mesh_source
from .options import ATLAS_RESOLUTION, sums_mesh, surfel_resolution, vertex_sums_options


def compute(mesh, features, radius, *, resolution: int | None = None, precision: str = "f32",
            paper_mode: bool = False, **options) -> dict[str, np.ndarray]:
    """Per-vertex features of ``mesh`` (a :class:`~uvfeat.Mesh` or any of
    :data:`uvfeat.interop.ACCEPTED`), one value per vertex of it: per row of ``mesh.positions``,
    of a trimesh's ``vertices``, of a PolyData's ``points`` (NaN at a volume grid's inner points).

    Builds an :class:`~uvfeat.Atlas` at ``resolution`` and calls :meth:`~uvfeat.Atlas.per_vertex`
    with ``features``, ``radius`` and ``**options`` (``samples``, ``compute_resolution``,
    ``adaptive``, ``seed``, ``quadrature``, ...): with ``quadrature="surfels"`` the values are
    evaluated at the vertices, with no maps. For several calls on the same mesh keep an Atlas.

    A mesh without UVs gets uvfeat's automatic atlas. On an atlas of more than one chart (that one,
    or the mesh's own) each vertex is the centre of its own ball over the surfels of the mesh's
    flat facets by default (``quadrature="surfels"``, ``surface="facets"``, about ``samples``
    surfels per ball, 160 unless named; the pattern's options,
    ``sampling``, ``margin`` ..., do not apply then), unless ``options`` name ``quadrature`` or
    ``query`` or ask for what the sums do not serve (``method="fit"``, ``adaptive``,
    ``standard_error``, the geodesic methods, ``paper_mode``): then the maps are read. The sums
    run on uvfeat's own atlas even where the mesh has UVs of its own
    (:func:`~uvfeat.options.sums_mesh`: a file's atlas may squeeze parts of the surface into few
    texels; uvfeat's gives every chart one texel size), and a vertex whose ball
    holds no surfel takes the object-space reference's value. ``resolution`` defaults to 1024 for
    the maps and, for the surfel sums, to the grid up to 512 whose finest surfels put ``samples`` in
    a ball of the smallest radius (:func:`~uvfeat.options.surfel_resolution`: 512 up to about 2 %
    of the diagonal on a scan's atlas, about 200-250 at 4 % and 110-130 at 8 %, with the default
    ``samples``).

    Returns
    -------
    dict of str to ndarray
        ``(n_vertices,)`` float32 per feature (``(n_radii, n_vertices)`` for a list of radii).
    """
    source = mesh_source(mesh)
    # The sums at the vertices run on uvfeat's own atlas, whatever the file's UVs (``sums_mesh``).
    mesh = sums_mesh(source.mesh, features, options, paper_mode)
    if not mesh.has_uvs:
        # Packed for the atlas resolution `load` unwraps at, so that both share the cached unwrap.
        mesh = mesh.with_atlas(resolution=resolution or ATLAS_RESOLUTION)
    surfels = vertex_sums_options(mesh, features, options, paper_mode) is not None
    if resolution is None:
        resolution = surfel_resolution(mesh, radius, options.get("samples")) if surfels else ATLAS_RESOLUTION
    if paper_mode:
        precision = "f16"
    atlas = Atlas(mesh, resolution=resolution, precision=precision, coverage_on_first_use=surfels)
    return source.to_points(atlas.per_vertex(features, radius, paper_mode=paper_mode, **options))
