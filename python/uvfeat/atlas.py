"""The :class:`Atlas`: a mesh rasterised into parametric-space buffers (DESIGN.md §1.3, paper Fig. 1).

Buffers are ``(R, R, ...)`` arrays indexed ``[j, i]``: row ``j`` is the v index (v up, so row 0 is
v = 0, the bottom of a picture) and texel ``(i, j)`` is centred at ``((i + 0.5)/R, (j + 0.5)/R)``.
Empty texels hold NaN (float buffers) or -1 (ids).
"""

from __future__ import annotations

import functools
import os
import time
from typing import NamedTuple

import numpy as np

from . import _core
from .errors import InvalidParameterError, ResolutionTooLargeError
from .interop import as_mesh
from .mesh import Mesh, _readonly
from .options import ARGUMENT_DEFAULTS, check_resolution

PRECISIONS = ("f32", "f16")


def _uv_point(uv, name: str = "uv") -> tuple[float, float]:
    """``uv`` as a pair of finite floats, or an :class:`InvalidParameterError` naming it."""
    try:
        u, v = (float(x) for x in uv)
    except (TypeError, ValueError) as exc:
        raise InvalidParameterError(f"{name} must be a pair of numbers, got {uv!r}") from exc
    if not (np.isfinite(u) and np.isfinite(v)):
        raise InvalidParameterError(f"{name} must be finite, got ({u}, {v})")
    return u, v


def memory_budget() -> int:
    """Bytes the buffers of one atlas may take: half of the physical memory."""
    try:
        return int(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")) // 2
    except (ValueError, OSError, AttributeError):
        return 8 << 30


class Location(NamedTuple):
    """Where a parametric point ends up after relocation across seams (DESIGN.md §1.5)."""

    status: str
    """"inside", "border" (the march left the surface at a mesh border) or "missing"."""
    chart: int
    uv: tuple[float, float] | None
    m_path: np.ndarray | None
    """Product of the crossed seams' 2x2 maps; ``abs(det)`` rescales parametric areas."""
    jumps: int


class Neighbourhoods(NamedTuple):
    """Weighted neighbourhood samples of T texels, padded to N samples each (use ``valid``)."""

    texels: np.ndarray
    """(T,) flat index ``j * W_c + i`` into the computation texture."""
    centres: np.ndarray
    """(T, 3) centre points p."""
    normals: np.ndarray
    """(T, 3) unit normals at p."""
    positions: np.ndarray
    """(T, N, 3) samples q_i (zero where not valid)."""
    sample_normals: np.ndarray
    """(T, N, 3) unit normals n_i."""
    areas: np.ndarray
    """(T, N) surface area dA_i each sample stands for (0 where not valid): integrals are
    ``sum(areas * g)``, means ``sum(areas * g) / sum(areas)``."""
    valid: np.ndarray
    """(T, N) bool: accepted samples (inside the ball of radius r)."""
    resolution: int


class SeamCrossing(NamedTuple):
    """A point carried across the seam of its border texel."""

    chart: int
    uv: tuple[float, float]
    m: np.ndarray
    side: int


class Atlas:
    """Parametric-space buffers of a UV-mapped mesh at one resolution.

    Parameters
    ----------
    mesh : Mesh
        A mesh with UVs (see :meth:`Mesh.with_atlas` for one without).
    resolution : int, default 1024
        Geometry-buffer size ``W_g`` (texels per side).
    precision : {"f32", "f16"}
        Storage of positions and normals; ``"f16"`` rounds them to half floats as the paper's GPU
        textures do (Table 2), and the views are then float16.
    coverage_on_first_use : bool, default False
        Rasterise which face each texel shows when something first reads it, not while the atlas
        is built: for an atlas that serves only :meth:`per_vertex` on many charts (the values at the
        vertices read the surfels, never the texels), as :func:`uvfeat.compute` builds it. The
        maps and texel views then pay for it on their first call.

    Raises
    ------
    UVError
        The mesh has no UVs or its UV map is degenerate.
    InvalidParameterError, ResolutionTooLargeError
        Resolution not a positive integer, or buffers larger than half of the memory (the message
        says how much they would take).
    """

    def __init__(self, mesh: Mesh, resolution: int = 1024, precision: str = "f32", *,
                 coverage_on_first_use: bool = False):
        mesh = as_mesh(mesh)
        resolution = check_resolution(resolution)
        if precision not in PRECISIONS:
            raise InvalidParameterError(f"precision must be one of {PRECISIONS}, got {precision!r}")
        budget = memory_budget()
        needed = _core.atlas_bytes(resolution, mesh.n_faces)
        if needed > budget:
            raise ResolutionTooLargeError(
                f"{mesh.n_faces:,} faces at resolution {resolution} need about {needed >> 20} MiB of buffers and "
                f"per-face tables, more than the {budget >> 20} MiB allowed (half of this machine's memory); choose "
                "a smaller resolution or fewer faces")
        self.mesh = mesh
        started = time.perf_counter()
        topology = mesh.topology
        self.timings = {"preprocessing_s": time.perf_counter() - started}
        started = time.perf_counter()
        self._core = _core.Atlas(topology, mesh.positions, resolution, precision, budget,
                                 coverage_on_first_use=bool(coverage_on_first_use))
        self.timings["rasterisation_s"] = time.perf_counter() - started

    # -- configuration ------------------------------------------------------------------------
    @property
    def resolution(self) -> int:
        return self._core.resolution

    @property
    def precision(self) -> str:
        return self._core.precision

    @property
    def n_charts(self) -> int:
        return self.mesh.topology.n_charts

    # -- buffers (read-only, cached until update) ---------------------------------------------
    @functools.cached_property
    def position(self) -> np.ndarray:
        """(R, R, 3) surface position shown by each texel (object units; NaN when empty)."""
        return _readonly(self._core.position)

    @functools.cached_property
    def normal(self) -> np.ndarray:
        """(R, R, 3) unit normal (outward; NaN when empty)."""
        return _readonly(self._core.normal)

    @functools.cached_property
    def sigma(self) -> np.ndarray:
        """(R, R, 2) float32 ``(sigma_1, sigma_2)``, object units per uv unit, ``sigma_1 >= sigma_2``."""
        return _readonly(self._core.sigma)

    @functools.cached_property
    def theta(self) -> np.ndarray:
        """(R, R) float32 angle (radians) from +u of the ``sigma_1`` axis."""
        return _readonly(self._core.theta)

    @functools.cached_property
    def chart(self) -> np.ndarray:
        """(R, R) int32 chart id, -1 for empty texels."""
        return _readonly(self._core.chart)

    @functools.cached_property
    def face(self) -> np.ndarray:
        """(R, R) int32 triangle shown by each texel, -1 for empty texels."""
        return _readonly(self._core.face)

    @functools.cached_property
    def border(self) -> np.ndarray:
        """(R, R) bool: texel touched by a boundary edge of its chart (carries adjacency)."""
        return _readonly(self._core.border)

    @functools.cached_property
    def adjacent_chart(self) -> np.ndarray:
        """(R, R) int32 chart across the closest boundary edge of a border texel; -1 elsewhere and
        where the mesh itself ends."""
        return _readonly(self._core.adjacent_chart)

    @functools.cached_property
    def border_side(self) -> np.ndarray:
        """(R, R) int32 boundary side (edge of a face) closest to each border texel, -1 elsewhere."""
        return _readonly(self._core.border_side)

    _FRAME_BUFFERS = ("position", "normal", "sigma", "theta")

    @property
    def positions(self) -> np.ndarray:
        """(n_vertices, 3) vertex positions of the current frame (the mesh's until :meth:`update`)."""
        return getattr(self, "_positions", self.mesh.positions)

    def update(self, positions) -> None:
        """Re-evaluates the buffers for new vertex positions (an animation frame): normals,
        metrics, seam maps and buffers are recomputed; charts, coverage and adjacency are reused."""
        positions = np.ascontiguousarray(positions, dtype=np.float64)
        started = time.perf_counter()
        self._core.update(positions)
        self.timings["update_s"] = time.perf_counter() - started
        self._positions = positions
        for name in self._FRAME_BUFFERS:
            self.__dict__.pop(name, None)

    # -- features -------------------------------------------------------------------------------
    def compute(self, features, radius, samples: int = ARGUMENT_DEFAULTS["samples"],
                compute_resolution: int = ARGUMENT_DEFAULTS["compute_resolution"],
                adaptive: bool = ARGUMENT_DEFAULTS["adaptive"], seed: int = ARGUMENT_DEFAULTS["seed"], *,
                paper_mode: bool = False, **options) -> dict:
        """Multi-scale features at every texel of a ``compute_resolution``² texture.

        Parameters
        ----------
        features : str or list of str
            Names from :data:`uvfeat.FEATURES` (a comma-separated string or "all" also work).
        radius : float, str, list or ndarray
            Neighbourhood radius in object units, or a percentage of the bounding-box diagonal
            (``"2%"``); a list gives a scale stack; a NumPy array of one length per row of
            ``mesh.positions`` gives each texel the radius of its surface point (see
            :mod:`uvfeat.vertex_radii`).
        samples : int
            Samples per neighbourhood (>= 4): the pattern's points per texel, or with
            ``quadrature="surfels"`` about as many surfels per ball (the pyramid level summed: on
            the shared scans a quarter as many take 0.4-0.7x the time at r = 4-8 % and add up to
            0.45 % of the range to H's error, 0.8 % to K's; docs/BENCHMARKS.md).
        compute_resolution : int
            Size ``W_c`` of the computation texture.
        adaptive : bool
            Two-stage adaptive sampling (DESIGN.md §1.8; ``tau`` option, default 0.01).
        seed : int
            Seed of the pattern and the per-pixel rotations (results do not depend on threads).
        paper_mode : bool
            The paper's choices where they differ from ours (DESIGN.md §1.10), for reproduction.
        **options
            ``margin`` (1.25), ``grow_margin`` (True: sample again over a larger domain where the
            ellipse did not cover the ball), ``max_jumps`` (32), ``relocation`` ("walk" | "march" | "per_chart"), ``criterion`` ("euclidean" | "geodesic"),
            ``lookup`` ("triangle" | "bilinear"), ``geodesic`` ("arc" | "chord_sum"),
            ``sampling`` ("shared": the texels of a tile share one regular lattice of samples,
            located once, where the settings allow it (integral estimators, no adaptive sampling,
            no standard errors, no geodesic distances), the fast path elsewhere; "fast": per-texel
            samples deep inside their chart are read from the face-id buffer and compact f32 face
            patches, the others take the exact path; "exact": every sample located and evaluated
            on its own in f64, the reference of both),
            ``gaussian_method`` ("moments" | "geodesic_area"), ``volume_weighting``
            ("distance" | "uniform"), ``rho_min`` (0.1, fraction of r), ``flat_tol`` (1e-3),
            ``tau`` (0.01), ``standard_error`` (False), ``query`` ("texture" | "direct"),
            ``method`` ("integral" | "fit": H, K, k1, k2, shape index and curvedness from the
            quadric fit, which also gives ``principal_directions`` and ``fit_residual``),
            ``overlaps`` ("keep" | "drop"), ``quadrature`` ("pattern": the samples above;
            "surfels": the atlas's pieces of surface connected to the centre inside the ball, each
            counted once, for scans cut into many charts; ``adaptive``, the sampler options and the
            geodesic methods do not apply, DESIGN.md §1.4.8) and ``surface``
            ("smooth" | "facets": the surface the surfels lie on).

        Returns
        -------
        dict of str to FeatureMap
        """
        from .features import compute_maps

        return compute_maps(self, features, radius, samples=samples, compute_resolution=compute_resolution,
                            adaptive=adaptive, seed=seed, paper_mode=paper_mode, options=options)

    def per_vertex(self, features, radius, samples: int | None = None,
                   compute_resolution: int = ARGUMENT_DEFAULTS["compute_resolution"],
                   adaptive: bool = ARGUMENT_DEFAULTS["adaptive"], seed: int = ARGUMENT_DEFAULTS["seed"], *,
                   paper_mode: bool = False, **options) -> dict[str, np.ndarray]:
        """Features at every vertex of ``mesh.positions``, without maps where none are needed.

        Arguments as :meth:`compute`. With ``quadrature="surfels"`` (and the integral estimators)
        each vertex is the centre of its own neighbourhood: the surfels connected to it inside the
        ball, summed with their exact area moments (DESIGN.md §1.4.9), with no texture computed
        or read, which is both faster and more accurate than reading maps (``query`` does not
        apply); ``samples`` (about that many surfels per ball) is then 160 unless named. Otherwise
        the maps of :meth:`compute` are read with ``query`` (``samples`` 256 unless named).

        Returns
        -------
        dict of str to ndarray
            ``(n_vertices,)`` float32 per feature (``(n_radii, n_vertices)`` for a list of radii).
        """
        from .features import vertex_values

        return vertex_values(self, features, radius, samples=samples, compute_resolution=compute_resolution,
                             adaptive=adaptive, seed=seed, paper_mode=paper_mode, options=options)

    def vertex_texture(self, values, width: int = ARGUMENT_DEFAULTS["compute_resolution"]) -> np.ndarray:
        """Per-vertex ``values`` (one per row of ``mesh.positions``, or ``(k, n_vertices)``) as a
        ``width``² float32 texture (``(k, width, width)``), ``[j, i]`` with v up as
        :attr:`FeatureMap.texture`, NaN off the charts: each texel the values of the corners of the
        face under its centre, interpolated with its barycentric coordinates. ``uvfeat compute``
        writes the values at the vertices of a many-chart atlas as maps this way."""
        from .vertex_texture import vertex_texture

        return vertex_texture(self, values, width)

    def neighbourhoods(self, radius, samples: int = ARGUMENT_DEFAULTS["samples"],
                       compute_resolution: int = ARGUMENT_DEFAULTS["compute_resolution"],
                       seed: int = ARGUMENT_DEFAULTS["seed"], tile_texels: int = 16384, **options):
        """The weighted neighbourhood samples of every texel, in tiles, for user-defined operators
        ``F(p, S(p))`` (DESIGN.md §2.9). Yields :class:`Neighbourhoods` tuples whose arrays hold
        ``tile_texels x samples`` samples at most (memory-bounded); with
        ``quadrature="surfels"`` a tile's arrays are as wide as its largest neighbourhood."""
        from .features import compute_maps_settings

        settings, resolution = compute_maps_settings(self, radius, samples, compute_resolution, seed, options)
        total = resolution * resolution
        for start in range(0, total, int(tile_texels)):
            texels, centres, normals, positions, sample_normals, areas, valid = _core.neighbourhood_tile_arrays(
                self._core, settings, start, min(start + int(tile_texels), total))
            if len(texels):
                yield Neighbourhoods(texels, centres, normals, positions, sample_normals, areas, valid, resolution)

    def map_operator(self, operator, radius, samples: int = ARGUMENT_DEFAULTS["samples"],
                     compute_resolution: int = ARGUMENT_DEFAULTS["compute_resolution"],
                     seed: int = ARGUMENT_DEFAULTS["seed"], tile_texels: int = 16384, **options) -> np.ndarray:
        """Applies ``operator(neighbourhoods) -> (T,) values`` tile by tile and returns the
        ``(W_c, W_c)`` float32 map (NaN off the charts)."""
        out = None
        for tile in self.neighbourhoods(radius, samples, compute_resolution, seed, tile_texels, **options):
            if out is None:
                out = np.full(tile.resolution * tile.resolution, np.nan, dtype=np.float32)
            values = np.asarray(operator(tile), dtype=np.float32)
            if values.shape != tile.texels.shape:
                raise InvalidParameterError(f"operator returned shape {values.shape}, expected {tile.texels.shape}")
            out[tile.texels] = values
        r = int(compute_resolution)
        return (out if out is not None else np.full(r * r, np.nan, dtype=np.float32)).reshape(r, r)

    # -- diagnostics ------------------------------------------------------------------------------
    @property
    def diagnostics(self) -> dict:
        """Counts from pre-processing and rasterisation (degenerate UV faces, non-manifold edges,
        conflicts, overlapping texels, charts smaller than a texel, ...)."""
        out = dict(self.mesh.topology.diagnostics)
        out.update(self._core.diagnostics)
        out["precision"] = self.precision
        return out

    @property
    def overlap_share(self) -> float:
        """Share of the covered texels that several triangles claim (overlapping UVs; 0 for a
        clean atlas). The first triangle keeps such a texel, so the others are not sampled there."""
        d = self.diagnostics
        return d["overlapping_texels"] / max(d["covered_texels"], 1)

    def warnings(self) -> list[str]:
        """Plain-language warnings about the diagnostics, empty when all is well."""
        d = self.diagnostics
        notes = []
        if d["degenerate_uv_faces"]:
            notes.append(f"{d['degenerate_uv_faces']} faces have zero-area UV triangles: skipped, their edges act as borders")
        if d["non_manifold_edges"]:
            notes.append(f"{d['non_manifold_edges']} non-manifold edges (more than two faces): treated as borders")
        if d["overlapping_texels"]:
            notes.append(f"{d['overlapping_texels']} texels are covered by several triangles (overlapping UVs): "
                         "features there are wrong; re-atlas with uv='charts'")
        if d["conflicts"]:
            notes.append(f"{d['conflicts']} texels are claimed by edges of several charts: more gutter or resolution helps")
        if d["charts_without_texels"]:
            notes.append(f"{d['charts_without_texels']} charts are smaller than a texel at {d['resolution']}²")
        return notes

    def summary(self) -> str:
        d = self.diagnostics
        lines = [f"{self.mesh.name}: {d['faces']} faces, {d['geometric_vertices']} welded vertices, {d['charts']} charts",
                 f"buffers {d['resolution']}² ({d['precision']}): {d['covered_texels']} covered texels, "
                 f"{d['border_texels']} border texels ({d['gutter_texels']} in gutters)",
                 f"edges: {d['interior_edges']} interior, {d['seam_edges']} seam, {d['border_edges']} border, "
                 f"{d['non_manifold_edges']} non-manifold"]
        return "\n".join(lines + [f"warning: {w}" for w in self.warnings()])

    # -- parametric queries ---------------------------------------------------------------------
    def chart_at(self, uv) -> int:
        """Chart id of the texel containing ``uv`` (-1 when empty or outside [0, 1)^2)."""
        u, v = _uv_point(uv)
        if not (0.0 <= u < 1.0 and 0.0 <= v < 1.0):
            return -1
        r = self.resolution
        return int(self.chart[min(int(v * r), r - 1), min(int(u * r), r - 1)])

    def _chart_of(self, uv, chart: int | None) -> int:
        chart = self.chart_at(uv) if chart is None else int(chart)
        if not 0 <= chart < self.mesh.n_charts:
            raise InvalidParameterError(f"uv {tuple(uv)} is not on a chart; pass chart= explicitly"
                                        if chart < 0 else f"chart {chart} does not exist ({self.mesh.n_charts} charts)")
        return chart

    def locate(self, start, target, chart: int | None = None, max_jumps: int = 32) -> Location:
        """Relocates ``target``, an offset of ``start`` (in ``chart``, default: the chart at
        ``start``), across seams (DESIGN.md §1.5)."""
        if not 0 <= int(max_jumps) < 1 << 31:
            raise InvalidParameterError(f"max_jumps must be a non-negative count, got {max_jumps}")
        status, landed, uv, m, jumps = self._core.locate(_uv_point(start), self._chart_of(start, chart),
                                                         _uv_point(target, "target"), int(max_jumps))
        return Location(status, landed, uv, None if m is None else np.array(m), jumps)

    def cross_seam(self, uv, chart: int | None = None) -> SeamCrossing | None:
        """Maps ``uv`` in a border texel across its seam (``None`` where the mesh itself ends)."""
        out = self._core.cross_seam(_uv_point(uv), self._chart_of(uv, chart))
        return None if out is None else SeamCrossing(out[0], out[1], np.array(out[2]), out[3])

    def surface_point(self, uv, chart: int | None = None):
        """``(position, normal, face)`` of the surface at ``uv`` (exact triangle lookup), or None."""
        out = self._core.surface_point(_uv_point(uv), self._chart_of(uv, chart))
        return None if out is None else (np.array(out[0]), np.array(out[1]), out[2])

    def __repr__(self) -> str:
        return f"<uvfeat.Atlas of {self.mesh.name!r}: {self.resolution}², {self.n_charts} charts, {self.precision}>"
