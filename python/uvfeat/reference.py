"""The object-space reference (DESIGN.md §5.1): every feature estimated per vertex from the mesh
itself, the measure the parametric method is compared against.

The neighbourhood of vertex ``p`` is the set of vertices reached from it over edges whose
endpoints lie within Euclidean distance ``r``; those vertices (without ``p``) are the samples,
weighted by their mixed Voronoi areas, and go through the *same* estimators as the parametric
samples, so both sides share names, conventions and departures (``H = (k1 + k2)/2``, positive on
convex regions; ``k1 >= k2``; K, k1, k2 from curvature moments by default). Gaussian curvature
may instead come from the geodesic-disk area: ``"geodesic_area"`` sums vertex areas within
edge-path (Dijkstra) distance ``r`` as the paper's reference did (strongly biased: edge paths are
too long), ``"exact_geodesic_area"`` clips triangles at exact polyhedral geodesic distance ``r``.

Welding and half-edge connectivity are built once per mesh (:class:`Reference`) and, as in the
paper, are not part of the timings; the estimation (vertex normals and areas included) is.
Works on meshes without UVs.
"""

from __future__ import annotations

import time
import warnings
import weakref

import numpy as np

from . import _core
from .errors import InvalidParameterError
from .interop import as_mesh, mesh_source
from .options import feature_names, resolve_radius
from .mesh import Mesh

#: Gaussian-curvature methods of the reference.
GAUSSIAN_METHODS = ("moments", "geodesic_area", "exact_geodesic_area")

#: Options of the reference, with the parametric defaults (DESIGN.md §1.10) where they are shared.
DEFAULT_OPTIONS = {"gaussian_method": "moments", "volume_weighting": "distance", "rho_min": 0.1, "flat_tol": 1e-3,
                   "method": "integral"}


def _vertex_indices(vertices, n_vertices: int) -> np.ndarray | None:
    if vertices is None:
        return None
    array = np.asarray(vertices)
    if array.ndim != 1 or not (np.issubdtype(array.dtype, np.integer) or array.size == 0):
        raise InvalidParameterError(f"vertices must be a 1-D array of vertex indices, got {array.dtype} {array.shape}")
    if array.size and (array.min() < 0 or array.max() >= n_vertices):
        bad = int(array[(array < 0) | (array >= n_vertices)][0])
        raise InvalidParameterError(f"vertex {bad} does not exist (the mesh has {n_vertices})")
    return np.ascontiguousarray(array, dtype=np.int64)


#: Each mesh's Reference (:meth:`Reference.of`).
_KEPT: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


class Reference:
    """A mesh prepared for the object-space reference: welded, with half-edge connectivity.

    Parameters
    ----------
    mesh : Mesh
        Any triangle mesh (UVs are not needed). Vertices split at seams are welded by position,
        and every input vertex gets the value of its welded vertex.

    Attributes
    ----------
    connectivity_s : float
        Seconds spent on welding and connectivity (not part of the reference timings).
    last_timings : dict
        ``connectivity_s`` and ``estimation_s`` (the timed part) of the last :meth:`compute`.
    last_samples : ndarray or None
        ``(n,)`` uint32 neighbourhood sizes (vertices besides the centre) of the last call.
    """

    def __init__(self, mesh: Mesh):
        mesh = as_mesh(mesh)
        self.mesh = mesh
        started = time.perf_counter()
        self._core = _core.ReferenceMesh(mesh.positions, mesh.faces)
        self.connectivity_s = time.perf_counter() - started
        self.last_timings = {"connectivity_s": self.connectivity_s}
        self.last_samples: np.ndarray | None = None

    @classmethod
    def of(cls, mesh: Mesh) -> "Reference":
        """The Reference of ``mesh``, built on the first call and kept while the mesh lives
        (meshes never change): later calls on the same mesh skip the welding and connectivity."""
        if mesh not in _KEPT:
            _KEPT[mesh] = cls(mesh)
        return _KEPT[mesh]

    def compute(self, features, radius, *, vertices=None, **options) -> dict[str, np.ndarray]:
        """Per-vertex reference values.

        Parameters
        ----------
        features : str or list of str
            Feature names (as for :meth:`uvfeat.Atlas.compute`), comma-separated, or ``"all"``.
        radius : float or str
            Neighbourhood radius in object units, or ``"2%"`` of the bounding-box diagonal.
        vertices : array_like of int, optional
            Evaluate only at these vertices (the geodesic variants are slow on large meshes).
        **options
            ``gaussian_method`` (``"moments"``, ``"geodesic_area"``, ``"exact_geodesic_area"``),
            ``volume_weighting`` (``"distance"``, ``"uniform"``), ``rho_min`` (fraction of r,
            0.1), ``flat_tol`` (1e-3), ``method`` (``"integral"``, or ``"fit"``: the quadric fit of
            the neighbourhood's vertices, Voronoi-area weighted): as for the parametric side.

        Returns
        -------
        dict of str to ndarray
            ``(n_vertices,)`` float64 per feature (``(len(vertices),)`` with ``vertices``); NaN
            where the neighbourhood holds no other vertex (radius below the edge length).
        """
        names = feature_names(features)
        unknown = sorted(set(options) - set(DEFAULT_OPTIONS))
        if unknown:
            raise InvalidParameterError(f"unknown option(s) {unknown}; valid: {', '.join(sorted(DEFAULT_OPTIONS))}")
        opts = dict(DEFAULT_OPTIONS, **options)
        r = resolve_radius(radius, self.mesh.bounding_box_diagonal)
        indices = _vertex_indices(vertices, self.mesh.n_vertices)
        started = time.perf_counter()
        values, samples = self._core.compute(names, r, str(opts["gaussian_method"]), str(opts["volume_weighting"]),
                                             float(opts["rho_min"]), float(opts["flat_tol"]), str(opts["method"]),
                                             indices)
        self.last_timings = {"connectivity_s": self.connectivity_s, "estimation_s": time.perf_counter() - started}
        self.last_samples = samples
        lonely = int((samples == 0).sum())
        if lonely:
            warnings.warn(f"{lonely} of {samples.size} vertices have no other vertex within r = {r:g} (radius below "
                          "the edge length): their values are NaN", UserWarning, stacklevel=2)
        return dict(zip(names, values))

    def geodesic_distances(self, source: int, max_distance: float = np.inf) -> np.ndarray:
        """Exact polyhedral geodesic distances (the ones behind ``"exact_geodesic_area"``) from
        vertex ``source`` to every vertex, ``(n_vertices,)`` float64, ``inf`` beyond
        ``max_distance`` (object units; the search costs grow with it) and off ``source``'s
        connected part."""
        if isinstance(source, bool) or not isinstance(source, (int, np.integer)):
            raise InvalidParameterError(f"source must be a vertex index, got {source!r}")
        return self._core.geodesic_distances(int(source), float(max_distance))


def compute(mesh, features, radius, *, vertices=None, return_timings: bool = False, **options):
    """Per-vertex object-space reference values of ``mesh`` (a :class:`~uvfeat.Mesh` or any of
    :data:`uvfeat.interop.ACCEPTED`; one value per vertex of it, as :func:`uvfeat.compute`); see
    :meth:`Reference.compute`. With ``return_timings=True`` returns
    ``(values, timings)`` with ``connectivity_s`` (welding and half-edges, untimed in the paper)
    and ``estimation_s``. For several calls on one mesh keep a :class:`Reference`."""
    source = mesh_source(mesh)
    if vertices is not None and source.point_of_vertex is not None:
        raise InvalidParameterError("vertices= indexes a mesh's vertices: pass the grid's surface "
                                    "(extract_surface()) to pick some")
    reference = Reference(source.mesh)
    values = reference.compute(features, radius, vertices=vertices, **options)
    values = values if vertices is not None else source.to_points(values)
    return (values, reference.last_timings) if return_timings else values
