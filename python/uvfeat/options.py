"""Names, defaults and validation of the options of a feature computation: the feature names,
the radius (a length or a percentage of the bounding-box diagonal, resolved once), the
resolutions, and the options of ``Atlas.compute`` with their defaults and the paper's choices."""

from __future__ import annotations

import re
import warnings
import weakref

import numpy as np

from . import _core
from .errors import InvalidParameterError
from .vertex_radii import per_vertex_radii

#: Every feature name, in output order.
FEATURES = tuple(_core.feature_names())

_CORE_DEFAULTS = _core.default_options()

#: The named arguments of ``Atlas.compute`` and ``uvfeat.compute`` with their defaults.
ARGUMENT_DEFAULTS = {name: _CORE_DEFAULTS[name] for name in ("samples", "compute_resolution", "adaptive", "seed")}

#: The names each choice option takes, the default first.
CHOICES = _core.option_choices_by_name()

#: The per-vertex query: a choice of the maps, not of their computation.
PER_VERTEX_OPTIONS = {"query": CHOICES["query"][0]}

#: Options of ``compute`` beyond the named arguments, with their defaults (DESIGN.md §1.10).
DEFAULT_OPTIONS = {**{k: v for k, v in _CORE_DEFAULTS.items() if k not in ARGUMENT_DEFAULTS}, **PER_VERTEX_OPTIONS}

#: What ``paper_mode=True`` changes (DESIGN.md §1.10). The paper's f16 buffers belong to the atlas:
#: ``Atlas(mesh, precision="f16")``.
PAPER_OPTIONS = _core.paper_options()

#: What per-vertex values default to on an atlas of more than one chart (a scan's automatic atlas
#: has hundreds, where the pattern's development overlaps itself across seams): each vertex the
#: centre of its own ball, summed over the surfels of the mesh's own flat facets, the surface the
#: object-space reference and ``converged_reference`` measure (DESIGN.md §1.4.9).
SURFEL_DEFAULTS = {"quadrature": "surfels", "surface": "facets"}

#: About how many surfels a ball sums where the per-vertex values are the surfel sums at the
#: vertices and the call names no ``samples`` (the pattern's maps take ``ARGUMENT_DEFAULTS["samples"]``
#: points per texel). Fewer than the pattern's: the surfels are exact pieces of the facets, and
#: their count sets the time of the sums; K, read from every surfel's normal curvature, is the
#: first to lose from fewer (DESIGN.md §1.4.9).
SURFELS_PER_BALL = 160


def sums_samples(samples: int | None) -> int:
    """``samples`` as the sums at the vertices take it: :data:`SURFELS_PER_BALL` where None."""
    return SURFELS_PER_BALL if samples is None else samples


def maps_samples(samples: int | None) -> int:
    """``samples`` as the maps take it: the pattern's default where None."""
    return ARGUMENT_DEFAULTS["samples"] if samples is None else samples


#: The largest atlas resolution ``uvfeat.compute`` takes where the per-vertex values are the surfel
#: sums (:func:`vertex_sums_options`); :func:`surfel_resolution` takes less for large radii.
SURFEL_RESOLUTION = 512

#: The atlas resolution ``uvfeat.compute`` takes otherwise.
ATLAS_RESOLUTION = 1024


def _integral(options: dict) -> bool:
    """Whether ``options`` ask for the integral estimators, which the surfel sums serve (the fit
    needs every sample: ``evaluation::integration``)."""
    return options.get("method", DEFAULT_OPTIONS["method"]) == "integral"


def per_vertex_defaults(mesh, features, options: dict, paper_mode: bool) -> dict:
    """:data:`SURFEL_DEFAULTS` where they are the default of ``mesh``'s per-vertex values of
    ``features``: its atlas has more than one chart, or it has no UVs (so uvfeat's atlas will cut
    it), the call names neither the quadrature, the maps' ``query`` nor the paper's choices, asks
    for the integral estimators and the core accepts its options with the surfels (not adaptive
    sampling, standard errors or the geodesic methods); otherwise nothing, and invalid options are
    left for the computation to name. ``options`` holds every option of the call, the named
    arguments (``adaptive``, ...) included."""
    if paper_mode or "quadrature" in options or "query" in options or (mesh.has_uvs and mesh.n_charts == 1):
        return {}
    if not _integral(options):
        return {}
    try:
        _core.compute_settings(feature_names(features), 1.0, core_options({**DEFAULT_OPTIONS, **options,
                                                                            **SURFEL_DEFAULTS}))
    except (InvalidParameterError, TypeError, ValueError):
        return {}
    return dict(SURFEL_DEFAULTS)


def vertex_sums_options(mesh, features, options: dict, paper_mode: bool) -> dict | None:
    """The options to add to ``options`` where ``mesh``'s per-vertex values are the surfel sums at
    the vertices: none where ``options`` name them (``quadrature="surfels"`` with the integral
    estimators), :func:`per_vertex_defaults` where they are the default; None where the values are
    read from maps."""
    if options.get("quadrature") == "surfels" and _integral(options):
        return {}
    return per_vertex_defaults(mesh, features, options, paper_mode) or None


_SUMS_MESHES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def sums_mesh(mesh, features, options: dict, paper_mode: bool):
    """The mesh the surfel sums at the vertices run on where they are the default
    (:func:`per_vertex_defaults`): ``mesh`` with uvfeat's own atlas (:meth:`~uvfeat.Mesh.with_atlas`,
    cached on disk; the same vertices and faces) unless its UVs already are one. The values at the
    vertices do not depend on the UVs, but their accuracy does: a texel's surfel is as long in space
    as the UVs are compressed there, and a file's atlas packs its charts at any scale (a region
    given 300x less UV area than the rest held balls of one or no surfel, NaN or 8-19 % off),
    where uvfeat's charts share one texel size. The atlas is packed for :data:`ATLAS_RESOLUTION`,
    as :func:`uvfeat.load`'s, whose unwrap it shares on disk (surfels of two charts may share a
    texel of a coarser grid). Otherwise ``mesh``."""
    if mesh.automatic_atlas is None and per_vertex_defaults(mesh, features, options, paper_mode):
        # Kept per mesh (meshes never change), so that calls at several radii build its topology once.
        if mesh not in _SUMS_MESHES:
            _SUMS_MESHES[mesh] = mesh.with_atlas(resolution=ATLAS_RESOLUTION)
        return _SUMS_MESHES[mesh]
    return mesh


def surfel_resolution(mesh, radius, samples: int | None = None) -> int:
    """The atlas resolution of the surfel sums at the vertices of ``mesh`` for ``radius`` (a length,
    a percentage, a list, or one per vertex: the smallest counts) over about ``samples`` surfels per
    ball (:func:`sums_samples`): the width whose finest surfels, of the mean size on its charts, put
    ``samples`` in a plane's ball, to a multiple of 16 from 64 up to :data:`SURFEL_RESOLUTION`
    (``_core.surfel_grid_width``). Radii the computation will reject give
    :data:`SURFEL_RESOLUTION` (the computation names them)."""
    diagonal = mesh.bounding_box_diagonal
    try:
        own = per_vertex_radii(radius, mesh.n_vertices)
        if own is not None:
            smallest = float(own.min())
        elif isinstance(radius, (list, tuple, np.ndarray)):
            smallest = min(resolve_radius(r, diagonal) for r in radius)
        else:
            smallest = resolve_radius(radius, diagonal)
    except (InvalidParameterError, TypeError, ValueError):
        return SURFEL_RESOLUTION
    return _core.surfel_grid_width(mesh.surface_area, mesh.uv_area, smallest, float(sums_samples(samples)),
                                   SURFEL_RESOLUTION)


def sums_resolution(mesh, radius, resolution: int, samples: int | None = None) -> int:
    """The atlas resolution of the surfel sums at the vertices where a command or ``compare`` was
    given ``resolution``: the surfel grid of the radius (:func:`surfel_resolution`) where it is the
    default :data:`ATLAS_RESOLUTION` (a default cannot be told from a choice there), else
    ``resolution``."""
    return surfel_resolution(mesh, radius, samples) if resolution == ATLAS_RESOLUTION else resolution


def feature_names(features) -> list[str]:
    """A list of valid feature names from a name, a comma-separated string, a list, or "all"."""
    if isinstance(features, str):
        features = FEATURES if features == "all" else [f.strip() for f in features.split(",") if f.strip()]
    features = list(features)
    unknown = [f for f in features if f not in FEATURES]
    if unknown or not features:
        raise InvalidParameterError(f"unknown feature(s) {unknown or features}; valid: {', '.join(FEATURES)} (or 'all')")
    return list(dict.fromkeys(features))


def parse_radius(radius) -> tuple[float, bool]:
    """A radius's number and whether it is a percentage of the diagonal (``"2%"`` -> ``(2.0,
    True)``); rejects what is neither. The core checks the length itself (positive, finite)."""
    if isinstance(radius, str):
        match = re.fullmatch(r"\s*([-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*(%?)\s*", radius)
        if not match:
            raise InvalidParameterError(f"radius {radius!r}: give a length or a percentage of the diagonal like '2%'")
        value, percent = float(match.group(1)), bool(match.group(2))
    elif isinstance(radius, (int, float, np.floating, np.integer)) and not isinstance(radius, bool):
        value, percent = float(radius), False
    else:
        raise InvalidParameterError(f"radius must be a number or a string like '2%', got {radius!r}")
    return value, percent


def resolve_radius(radius, diagonal: float) -> float:
    """A radius in object units from a number or a percentage string of the bounding-box diagonal
    (``"2%"``); rejects radii beyond the whole mesh, which only the mesh knows."""
    number, percent = parse_radius(radius)
    value = number * diagonal / 100.0 if percent else number
    if value > diagonal:
        raise InvalidParameterError(f"radius {value:g} is larger than the mesh (bounding-box diagonal {diagonal:g}); "
                                    "every neighbourhood would be the whole mesh")
    return value


def resolve_options(options: dict, paper_mode: bool, *, warn: bool = True) -> dict:
    """Defaults, then the paper's choices, then the caller's options. The core checks their names,
    kinds and ranges (``query``, which picks how the maps are read, is checked here). ``warn``:
    say that the paper's choices are less accurate (:func:`warn_paper_mode`), once per call."""
    resolved = dict(DEFAULT_OPTIONS)
    if paper_mode:
        resolved.update(PAPER_OPTIONS)
        if warn:
            warn_paper_mode(stacklevel=4)
    resolved.update(options)
    _core.check_options(core_options(resolved))
    check_query(resolved["query"])
    return resolved


def warn_paper_mode(stacklevel: int) -> None:
    """The warning of a computation with ``paper_mode``."""
    warnings.warn("paper_mode: the paper's choices (margin 1, per-chart repetition with one jump, bilinear "
                  "lookup, chord-sum geodesic-area K, uniform volume weighting); they are less accurate than "
                  "the defaults and meant for reproducing its numbers", UserWarning, stacklevel=stacklevel)


def core_options(options: dict) -> dict:
    """The options the core takes (not the per-vertex query), NumPy scalars as Python numbers."""
    return {name: value.item() if isinstance(value, np.generic) else value for name, value in options.items()
            if name not in PER_VERTEX_OPTIONS}


def check_query(query) -> None:
    """The per-vertex query, the one option the core's computation does not take."""
    if query not in CHOICES["query"]:
        raise InvalidParameterError(f"query must be one of {CHOICES['query']}, got {query!r}")


def check_resolution(resolution, name: str = "resolution") -> int:
    """A positive integer resolution, or a clear error."""
    if isinstance(resolution, bool) or not isinstance(resolution, (int, np.integer)) or resolution <= 0:
        raise InvalidParameterError(f"{name} must be a positive integer, got {resolution!r}")
    return int(resolution)
