"""Multi-scale features (DESIGN.md §1.4–§1.10, §2): :class:`FeatureMap` and the option handling behind
``Atlas.compute`` and ``uvfeat.compute``.

Conventions: ``H = (k1 + k2)/2``, positive where the surface bends away from the (outward) normal;
``k1 >= k2``; units 1/length for H, k1, k2, curvedness, 1/length² for K and bending energy,
length³ for the sphere volumes; shape index in [-1, 1] (+1 convex cap).
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field

import numpy as np

from . import _core
from .errors import InvalidParameterError, NeighbourhoodWarning
from .mesh import _readonly
from .neighbourhood_flags import FLAGS, notes, texel_flags, vertex_flags, vertex_share
from .options import (ARGUMENT_DEFAULTS, core_options, feature_names, maps_samples, per_vertex_defaults,
                      resolve_options, resolve_radius, sums_samples, warn_paper_mode)
from .vertex_radii import LevelReader, levels, per_vertex_radii
from .vertex_texture import vertex_texture

#: How the notes about flagged vertices name the scale when each vertex has its own radius.
OWN_RADII = "at each vertex's own radius"

@dataclass
class FeatureMap:
    """One feature over the computation texture, at one radius or a stack of radii.

    ``texture`` is ``(W_c, W_c)`` float32 (``(n_radii, W_c, W_c)`` for a scale stack), indexed
    ``[j, i]`` with v up, NaN outside charts. Diagnostics maps have the same layout: ``n_valid``,
    ``n_missing`` (relocation failed), ``n_border`` (samples dropped at a mesh border: the
    neighbourhood is truncated there and values are biased; see ``truncated``). The diagnostics
    maps (and ``area_ratio``, ``sheet_area``, the fit's maps) belong to the neighbourhoods and are
    shared, read-only, by the features of one computation: copy one to change it.

    With ``method="fit"`` the curvature features come from the quadric fit, and
    ``principal_directions`` (``(W_c, W_c, 2, 3)``: unit ``d1`` of ``k1`` and ``d2`` of ``k2``, a
    line field whose sign is arbitrary) and ``fit_residual`` (``(W_c, W_c)``, RMS distance to the
    fit relative to r) are set (a leading ``n_radii`` axis for a stack); None otherwise.
    ``area_ratio`` is each neighbourhood's surface area over ``pi r^2`` (about 1 for one smooth
    sheet, 2 for both sides of a thin part) and ``sheet_area`` the area one sheet holds there (1 on
    a smooth mesh, more where rough facets tilt about the surface); :meth:`vertex_flags` says which
    vertices have neighbourhoods that are truncated, partly missing or hold several sheets.

    With one radius per vertex, ``radius`` is that ``(n_vertices,)`` array and ``levels`` the radii
    the maps were computed at: each texel reads the levels around the radius of its surface point
    (the vertices' radii interpolated over its triangle), linearly in ``log r``, and takes its
    counts and flags from the nearest level; :meth:`per_vertex` reads each vertex at its own radius.
    """

    name: str
    radius: float | np.ndarray
    texture: np.ndarray
    n_valid: np.ndarray
    n_missing: np.ndarray
    n_border: np.ndarray
    standard_error: np.ndarray | None = None
    principal_directions: np.ndarray | None = None
    fit_residual: np.ndarray | None = None
    area_ratio: np.ndarray | None = None
    sheet_area: np.ndarray | None = None
    summary: dict = field(default_factory=dict)
    settings: dict = field(default_factory=dict)
    levels: np.ndarray | None = None
    _atlas: object = field(default=None, repr=False)
    _maps: tuple = field(default=(), repr=False)
    _index: int = field(default=0, repr=False)
    _cache: dict = field(default_factory=dict, repr=False)

    @property
    def truncated(self) -> np.ndarray:
        """Texels whose neighbourhood was cut by a mesh border (values there are biased)."""
        return self.n_border > 0

    @property
    def is_stack(self) -> bool:
        return self.texture.ndim == 3

    @property
    def radius_per_vertex(self) -> bool:
        return self.levels is not None

    def _by_radius(self, per_level: list, interpolated: bool = True, radii: np.ndarray | None = None):
        """Values computed per map (``per_level``, one per vertex or per ``radii``) as this map
        gives them: one radius, a stack, or each at its own radius (interpolated in ``log r``, or
        the nearest level's where values cannot be blended)."""
        if self.levels is None:
            return per_level[0] if not self.is_stack else np.stack(per_level)
        if radii is None:
            if "vertex levels" not in self._cache:  # shared by the features of one computation
                self._cache["vertex levels"] = LevelReader(self.levels, self.radius)
            reader = self._cache["vertex levels"]
        else:
            reader = LevelReader(self.levels, radii)
        return reader.read(np.stack(per_level), interpolated)

    def per_vertex(self, query: str | None = None) -> np.ndarray:
        """Per-vertex values, ``(n_vertices,)`` (``(n_radii, n_vertices)`` for a stack), one per
        vertex of ``mesh.positions``: chart-masked bilinear lookup at every corner UV, averaged
        (``query="texture"``, default), or the estimators evaluated at the corner UVs
        (``query="direct"``)."""
        query = query or self.settings.get("query", "texture")
        if query not in self._cache:  # shared by the features of one computation
            self._cache[query] = [maps.per_vertex(self._atlas._core, query) for maps in self._maps]
        return self._by_radius([per_feature[self._index] for per_feature in self._cache[query]])

    def corner_values(self) -> tuple[np.ndarray, np.ndarray]:
        """Every atlas corner (a vertex's distinct UV; seams give a vertex several): its UV
        ``(n_corners, 2)`` and the value a texture read there should give ``(n_corners,)``: the
        chart-masked bilinear lookup that :meth:`per_vertex` averages per vertex, or, where no
        texel of the corner's chart has samples nearby (the average leaves such corners out), the
        vertex's own value. Bakes fit their gutters to it. One radius: index a stack first."""
        if self.is_stack:
            raise InvalidParameterError("corner_values needs one radius; take one map of the stack first")
        if "corners" not in self._cache:  # shared by the features of one computation
            self._cache["corners"] = [maps.per_corner(self._atlas._core) for maps in self._maps]
        uvs, vertex, _ = self._cache["corners"][0]
        mesh = self._atlas.mesh
        corner_radii = None
        if self.levels is not None:  # a welded vertex takes its first row's radius
            welded, first_row = np.unique(mesh.vertex_ids, return_index=True)
            radius_of = np.empty(mesh.topology.n_geometric_vertices)
            radius_of[welded] = self.radius[first_row]
            corner_radii = radius_of[vertex]
        corner = self._by_radius([values[self._index] for _, _, values in self._cache["corners"]],
                                 radii=corner_radii).astype(np.float64)
        missing = ~np.isfinite(corner)
        if missing.any():
            by_vertex = np.full(mesh.topology.n_geometric_vertices, np.nan)
            by_vertex[mesh.vertex_ids] = self.per_vertex()
            corner[missing] = by_vertex[vertex[missing]]
        return uvs, corner

    def vertex_flags(self) -> dict[str, np.ndarray]:
        """Vertices whose values come from neighbourhoods that are not what the radius asks for
        (see :mod:`uvfeat.neighbourhood_flags`): ``{"truncated", "partly_missing",
        "several_sheets"}`` -> ``(n_vertices,)`` bool (``(n_radii, n_vertices)`` for a stack)."""
        if "flags" not in self._cache:  # shared by the features of one computation
            self._cache["flags"] = [vertex_flags(self._atlas.mesh, texel_flags(m.n_valid, m.n_missing, m.n_border,
                                                                               m.area_ratio, m.sheet_area))
                                    for m in self._maps]
        per_radius = self._cache["flags"]
        return {n: self._by_radius([f[n] for f in per_radius], interpolated=False) for n in FLAGS}

    def per_vertex_directions(self) -> np.ndarray:
        """Principal directions of the fit at every vertex, ``(n_vertices, 2, 3)`` (``(n_radii,
        n_vertices, 2, 3)`` for a stack): ``[d1, d2]``, evaluated directly at the vertex (a line
        field cannot be averaged from texels like a scalar). Needs ``method="fit"``."""
        if self.principal_directions is None:
            raise InvalidParameterError('principal directions need method="fit" in compute()')
        if "directions" not in self._cache:
            self._cache["directions"] = [maps.per_vertex_directions(self._atlas._core) for maps in self._maps]
        return self._by_radius(self._cache["directions"], interpolated=False)

    def uv_principal_directions(self) -> np.ndarray:
        """The principal directions as a line field in the UV plane: ``(W_c, W_c, 2, 2)`` unit
        ``(du, dv)`` of ``[d1, d2]`` (v up, as ``texture``), NaN off the charts (a leading
        ``n_radii`` axis for a stack). For drawing them on the map. Needs ``method="fit"``."""
        from .pictures.line_field import uv_line_field

        if self.principal_directions is None:
            raise InvalidParameterError('principal directions need method="fit" in compute()')
        stack = self.principal_directions if self.is_stack else self.principal_directions[None]
        fields = [uv_line_field(self._atlas, d) for d in stack]
        return fields[0] if not self.is_stack else np.stack(fields)


def _core_options(samples, resolution, adaptive, seed, opts) -> dict:
    return core_options(dict(opts, samples=samples, compute_resolution=resolution, adaptive=adaptive, seed=seed))


def _core_settings(names, radius, samples, resolution, adaptive, seed, opts):
    return _core.compute_settings(names, radius, _core_options(samples, resolution, adaptive, seed, opts))


def compute_maps_settings(atlas, radius, samples, compute_resolution, seed, options):
    """Core settings for neighbourhood tiles: sampling alone, no estimator runs on them."""
    opts = resolve_options(options, paper_mode=False)
    r = resolve_radius(radius, atlas.mesh.bounding_box_diagonal)
    settings = _core.sampling_settings(r, _core_options(samples, compute_resolution, False, seed, opts))
    return settings, int(compute_resolution)  # a whole number: the core checked it


def compute_maps(atlas, features, radius, *, samples: int, compute_resolution: int, adaptive: bool, seed: int,
                 paper_mode: bool, options: dict) -> dict[str, FeatureMap]:
    """The work behind :meth:`uvfeat.Atlas.compute`."""
    names = feature_names(features)
    opts = resolve_options(options, paper_mode)
    own_radii = per_vertex_radii(radius, atlas.mesh.n_vertices)
    stack = own_radii is None and isinstance(radius, (list, tuple, np.ndarray))
    given = list(levels(own_radii)) if own_radii is not None else radius if stack else [radius]
    radii = [resolve_radius(r, atlas.mesh.bounding_box_diagonal) for r in given]
    if paper_mode and atlas.precision != "f16":
        warnings.warn("paper_mode: the paper stores buffers as half floats; build the Atlas with precision='f16' "
                      "to reproduce that too", UserWarning, stacklevel=3)
    all_maps, timings = [], []
    for r in radii:
        settings = _core_settings(names, r, samples, compute_resolution, adaptive, seed, opts)
        started = time.perf_counter()
        all_maps.append(_core.compute_maps(atlas._core, settings))
        timings.append(time.perf_counter() - started)
    compute_resolution = int(compute_resolution)  # a whole number: the core checked it
    described = dict(opts, samples=int(samples), compute_resolution=compute_resolution, adaptive=bool(adaptive),
                     seed=int(seed), paper_mode=bool(paper_mode), radii=radii, resolution=atlas.resolution,
                     precision=atlas.precision, features_s=timings)

    if own_radii is not None:
        # float64: a texel on a level reads it alone only where its radius equals the level's exactly.
        texel_radius = vertex_texture(atlas, own_radii, compute_resolution, dtype=np.float64)
        # Off the charts every map is empty: any level will do there.
        texels = LevelReader(np.array(radii), np.where(np.isfinite(texel_radius), texel_radius, radii[0]).ravel())

    def gather(get, interpolated=True):
        arrays = [get(m) for m in all_maps]
        if own_radii is None:
            return np.stack(arrays) if stack else arrays[0]
        values = np.stack(arrays)
        flat = values.reshape(len(arrays), values.shape[1] * values.shape[2], *values.shape[3:])
        return texels.read(flat, interpolated).reshape(values.shape[1:])

    # The neighbourhoods' maps are the same for every feature: one read-only copy serves them all.
    neighbourhood_maps = ["n_valid", "n_missing", "n_border", "area_ratio", "sheet_area"]
    if opts["method"] == "fit":
        neighbourhood_maps += ["principal_directions", "fit_residual"]
    shared = {name: _readonly(gather(lambda m, name=name: getattr(m, name), interpolated=False))
              for name in neighbourhood_maps}
    out, cache = {}, {}
    for k, name in enumerate(names):
        has_errors = all_maps[0].standard_errors(k) is not None
        out[name] = FeatureMap(
            name=name,
            radius=_readonly(own_radii) if own_radii is not None else np.array(radii) if stack else radii[0],
            texture=gather(lambda m, k=k: m.values(k)),
            standard_error=gather(lambda m, k=k: m.standard_errors(k)) if has_errors else None,
            **shared,
            summary=all_maps[0].summary if not stack and own_radii is None else [m.summary for m in all_maps],
            settings=described,
            levels=None if own_radii is None else np.array(radii),
            _atlas=atlas,
            _maps=tuple(all_maps),
            _index=k,
            _cache=cache,
        )
    _warn_about_flagged_vertices(out[names[0]], [OWN_RADII] if own_radii is not None
                                 else radius if stack else [radius])
    return out


def vertex_values(atlas, features, radius, *, samples: int | None, compute_resolution: int, adaptive: bool, seed: int,
                  paper_mode: bool, options: dict) -> dict[str, np.ndarray]:
    """The work behind :meth:`uvfeat.Atlas.per_vertex`: with ``quadrature="surfels"`` and the
    integral estimators each vertex is the centre of its own neighbourhood, summed over the
    surfels with no maps in between (DESIGN.md §1.4.9); otherwise the maps of
    :func:`compute_maps`, read with ``query``. An atlas of more than one chart takes the surfels
    unless ``options`` say otherwise (:func:`~uvfeat.options.per_vertex_defaults`)."""
    return vertex_values_and_flags(atlas, features, radius, samples=samples, compute_resolution=compute_resolution,
                                   adaptive=adaptive, seed=seed, paper_mode=paper_mode, **options)[0]


def vertex_values_and_flags(atlas, features, radius, *, samples: int | None = None,
                            compute_resolution: int = ARGUMENT_DEFAULTS["compute_resolution"],
                            adaptive: bool = ARGUMENT_DEFAULTS["adaptive"], seed: int = ARGUMENT_DEFAULTS["seed"],
                            paper_mode: bool = False, **options) -> tuple[dict, dict]:
    """:func:`vertex_values` and the flagged vertices (``FeatureMap.vertex_flags``): from the
    surfel sums only ``"truncated"`` (a mesh border cuts the ball), which the sums tell. Takes the
    arguments of :meth:`uvfeat.Atlas.per_vertex`."""
    named = {**options, "adaptive": adaptive}
    # The maps say it when they are computed instead.
    opts = resolve_options({**per_vertex_defaults(atlas.mesh, features, named, paper_mode), **options}, paper_mode,
                           warn=False)
    own_radii = per_vertex_radii(radius, atlas.mesh.n_vertices)
    names = feature_names(features)
    stack = own_radii is None and isinstance(radius, (list, tuple, np.ndarray))
    diagonal = atlas.mesh.bounding_box_diagonal
    surfels_per_ball = sums_samples(samples)
    def settings(r):
        return _core_settings(names, r, surfels_per_ball, compute_resolution, adaptive, seed, opts)

    # Per call: the radius and its settings (at the largest of the vertices' own radii, which the
    # core reads instead), the vertices' radii, a label.
    if own_radii is not None:
        largest = resolve_radius(float(own_radii.max()), diagonal)
        calls = [(largest, settings(largest), own_radii, OWN_RADII)]
    else:
        calls = [(length, settings(length), None, _scale(r))
                 for r, length in ((r, resolve_radius(r, diagonal)) for r in (radius if stack else [radius]))]
    if not _core.sums_apply(atlas._core, calls[0][1]):
        maps = compute_maps(atlas, features, radius, samples=maps_samples(samples),
                            compute_resolution=compute_resolution, adaptive=adaptive, seed=seed,
                            paper_mode=paper_mode, options=options)
        return {name: feature.per_vertex() for name, feature in maps.items()}, maps[names[0]].vertex_flags()
    if paper_mode:
        warn_paper_mode(stacklevel=5)
    per_radius, truncated, texts = [], [], []
    for length, call_settings, radii, label in calls:
        values, summed, border = _core.vertex_feature_values(atlas._core, call_settings, radii)
        if radii is None:
            _fill_empty_balls(atlas.mesh, names, length, values, summed, opts)
        per_radius.append(values)
        truncated.append(border > 0)
        # The sums say where a border cuts the ball; the other flags read the maps' samples.
        counts = dict.fromkeys(FLAGS, 0) | {"truncated": int(np.count_nonzero(border))}
        texts += notes(counts, atlas.mesh.n_vertices, label)
        few = int(np.count_nonzero((summed > 0) & (summed < FEW_SURFELS)))
        texts += _coarse_ball_notes(few, atlas.mesh.n_vertices, label, atlas.resolution, surfels_per_ball)
    if texts:
        warnings.warn("; ".join(texts), NeighbourhoodWarning, stacklevel=4)
    values = {name: np.stack([v[k] for v in per_radius]) if stack else per_radius[0][k] for k, name in enumerate(names)}
    return values, {"truncated": np.stack(truncated) if stack else truncated[0]}


#: Features NaN by design where the sums are whole: the shape index of a planar point.
NAN_WHERE_FLAT = ("shape_index",)

#: A ball summed over fewer surfels spans about a texel of the surfel grid: a coarse quadrature.
FEW_SURFELS = 8


def _coarse_ball_notes(few: int, n_vertices: int, scale: str, resolution: int, samples: int) -> list[str]:
    """The note for ``few`` vertices whose balls summed fewer than :data:`FEW_SURFELS` surfels
    (balls with none took the object-space reference's values: ``_fill_empty_balls``): ``samples``
    asked for so few, or the radius spans about a texel, or the vertex's piece of surface is cut off
    from its neighbours in the atlas (on the dragon, a chart of one face among single-face charts)."""
    if not few:
        return []
    share = f"{scale}, {vertex_share(few, n_vertices)} summed fewer than {FEW_SURFELS} surfels"
    if samples < 2 * FEW_SURFELS:
        return [f"{share}: samples={samples} sums about that many surfels per ball and their values are coarse "
                "(raise samples)"]
    return [f"{share}: the radius spans about a texel of the {resolution}² grid there, or their piece of surface "
            "is cut off from its neighbours in the atlas, and their values are coarse (a finer resolution, or "
            "uvfeat.reference, serves them)"]


def _fill_empty_balls(mesh, names: list[str], radius: float, values: list, summed: np.ndarray, opts: dict) -> None:
    """Where the ball of a vertex of a face held no surfel, or none beyond the inner exclusion
    (its atlas texels are longer than the ball there: a sliver chart, UVs squeezed into a few
    texels), the sums give NaN; ``values`` take the object-space reference's there instead, with
    the same estimators (on the facets, with the mesh's kept :meth:`Reference.of`). A
    planar point's shape index is NaN by design, not a failed ball."""
    on_faces = np.zeros(mesh.n_vertices, dtype=bool)
    on_faces[mesh.faces.ravel()] = True
    unsummed = np.asarray(summed) == 0
    for name, feature in zip(names, values):
        if name not in NAN_WHERE_FLAT:
            unsummed |= np.isnan(feature)
    empty = np.flatnonzero(unsummed & on_faces)
    if empty.size == 0:
        return
    from .reference import DEFAULT_OPTIONS as REFERENCE_OPTIONS, Reference

    estimators = {name: opts[name] for name in REFERENCE_OPTIONS if name != "method"}
    with warnings.catch_warnings():
        # A ball with no other vertex stays NaN, as the reference says of its own calls.
        warnings.simplefilter("ignore", UserWarning)
        filled = Reference.of(mesh).compute(names, radius, vertices=empty, **estimators)
    for k, name in enumerate(names):
        values[k][empty] = filled[name]


def _scale(radius) -> str:
    return radius if radius == OWN_RADII else f"at r = {radius if isinstance(radius, str) else f'{radius:.4g}'}"


def _warn_about_flagged_vertices(feature: FeatureMap, radii) -> None:
    flags = feature.vertex_flags()
    per_radius = [flags] if not feature.is_stack else [{n: f[k] for n, f in flags.items()} for k in range(len(radii))]
    n_vertices = feature._atlas.mesh.n_vertices
    texts = [text for r, f in zip(radii, per_radius)
             for text in notes({n: int(v.sum()) for n, v in f.items()}, n_vertices, _scale(r))]
    if texts:
        warnings.warn("; ".join(texts), NeighbourhoodWarning, stacklevel=4)
