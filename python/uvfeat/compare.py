"""The parametric method side by side with the object-space reference (DESIGN.md §5.1): per-feature
%AE and mean-normalised error, timings as the paper takes them, and pictures.

Timings follow the paper (§5): the parametric side counts what every frame costs (buffer
generation, the feature computation and the per-vertex lookup) but not the once-per-topology
pre-processing and rasterisation; the reference counts its estimation (vertex normals and areas
included) but not the half-edge construction.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass, field

import numpy as np

from ._core import __version__
from .interop import as_mesh
from .mesh import Mesh
from .options import ARGUMENT_DEFAULTS, DEFAULT_OPTIONS

#: Gaussian-curvature methods ``compare`` accepts; the parametric side has no exact geodesics
#: and uses its geodesic-area estimator when the reference uses ``exact_geodesic_area``.
PARAMETRIC_GAUSSIAN = {"moments": "moments", "geodesic_area": "geodesic_area", "exact_geodesic_area": "geodesic_area"}


def absolute_errors(values: np.ndarray, reference: np.ndarray) -> dict:
    """DESIGN.md §5.1 error of ``values`` against ``reference`` (per vertex, NaN on either side left out).

    ``percent_ae = 100 mean|f - f_ref| / (Q99(f_ref) - Q1(f_ref))`` (range-normalised, because H
    and K cross zero; NaN when the reference is constant) and ``mean_normalised = mean|f - f_ref|
    / mean|f_ref|``, with the number of vertices ``compared``.
    """
    values, reference = np.asarray(values, dtype=np.float64), np.asarray(reference, dtype=np.float64)
    both = np.isfinite(values) & np.isfinite(reference)
    if not both.any():
        return {"percent_ae": float("nan"), "mean_normalised": float("nan"), "mean_absolute": float("nan"),
                "compared": 0}
    error = np.abs(values[both] - reference[both]).mean()
    low, high = np.percentile(reference[both], [1.0, 99.0])
    scale = np.abs(reference[both]).mean()
    return {
        "percent_ae": float(100.0 * error / (high - low)) if high > low else float("nan"),
        "mean_normalised": float(error / scale) if scale > 0 else float("nan"),
        "mean_absolute": float(error),
        "compared": int(both.sum()),
    }


@dataclass
class Comparison:
    """Result of :func:`compare`: per-vertex values of both methods, errors and timings."""

    mesh: Mesh
    radius: float
    parametric: dict[str, np.ndarray]
    reference: dict[str, np.ndarray]
    errors: dict[str, dict]
    timings: dict[str, float]
    settings: dict = field(default_factory=dict)
    truth: dict[str, np.ndarray] | None = None
    """The converged reference the errors are measured against (None: the reference itself)."""
    reference_errors: dict[str, dict] | None = None
    """Errors of the reference itself against the converged truth (None without one)."""

    def to_dict(self) -> dict:
        """Everything but the arrays, JSON-ready."""
        return {"uvfeat": __version__, "mesh": self.mesh.name, "vertices": self.mesh.n_vertices,
                "faces": self.mesh.n_faces, "radius": self.radius, "settings": self.settings,
                "errors": self.errors, "reference_errors": self.reference_errors, "timings_s": self.timings}


def compare(mesh: Mesh, features, radius, *, samples: int | None = None, resolution: int = 1024,
            compute_resolution: int = ARGUMENT_DEFAULTS["compute_resolution"],
            gaussian_method: str = DEFAULT_OPTIONS["gaussian_method"], seed: int = ARGUMENT_DEFAULTS["seed"],
            query: str = DEFAULT_OPTIONS["query"], method: str = DEFAULT_OPTIONS["method"],
            sampling: str = DEFAULT_OPTIONS["sampling"], quadrature: str | None = None,
            surface: str | None = None, truth_levels: int = 2) -> Comparison:
    """Runs the parametric method (per-vertex values by ``query``, curvature estimators by ``method``:
    ``"integral"`` or ``"fit"``, sampler by ``sampling``: ``"shared"``, ``"fast"`` or ``"exact"``,
    neighbourhood sums by ``quadrature`` and ``surface``, see :meth:`uvfeat.Atlas.compute`) and the
    object-space reference on ``mesh`` for ``features`` at ``radius`` (object units or ``"2%"``),
    times both, and measures both against the truth: the reference on the same surface refined
    until it converges (up to ``truth_levels`` midpoint subdivisions, see
    :func:`uvfeat.converged.converged_reference`), or the reference itself with ``truth_levels=0``.

    With ``quadrature`` None the per-vertex values are those ``uvfeat.compute`` gives: on an atlas
    of more than one chart the surfel sums at the vertices, on the surfels' own atlas (``resolution``
    left at 1024: the grid of the radius), the pyramid of surfels timed with the features; the
    maps otherwise, or where ``query`` is not the default."""
    from .atlas import Atlas
    from .errors import InvalidParameterError
    from .options import (feature_names, maps_samples, resolve_radius, sums_mesh, sums_resolution, sums_samples,
                          vertex_sums_options)
    from .converged import converged_reference
    from .reference import Reference

    names = feature_names(features)
    if gaussian_method not in PARAMETRIC_GAUSSIAN:
        raise InvalidParameterError(f"gaussian_method {gaussian_method!r} is not one of {list(PARAMETRIC_GAUSSIAN)}")
    mesh = as_mesh(mesh)
    reference = Reference(mesh)
    ref_values = reference.compute(names, radius, gaussian_method=gaussian_method)
    truth = None
    if truth_levels:
        truth = converged_reference(mesh, names, radius, max_levels=int(truth_levels), coarse=ref_values,
                                    gaussian_method=gaussian_method)
    if not mesh.has_uvs:
        mesh = mesh.with_atlas(resolution=resolution)
    options = {"gaussian_method": PARAMETRIC_GAUSSIAN[gaussian_method], "method": method, "sampling": sampling}
    if surface is not None:
        options["surface"] = surface
    # A query other than the default asks how maps are read, as a named one does in uvfeat.compute.
    named = options if query == DEFAULT_OPTIONS["query"] else {**options, "query": query}
    sums = None if quadrature is not None else vertex_sums_options(mesh, names, named, paper_mode=False)
    if sums is not None:
        mesh = sums_mesh(mesh, names, named, paper_mode=False)
        resolution = sums_resolution(mesh, radius, resolution, samples)
    atlas = Atlas(mesh, resolution=resolution, coverage_on_first_use=sums is not None)
    started = time.perf_counter()
    atlas.update(mesh.positions)
    buffers_s = time.perf_counter() - started
    if sums is None:
        samples = maps_samples(samples)
        maps = atlas.compute(names, radius, samples=samples, compute_resolution=compute_resolution, seed=seed,
                             query=query, quadrature=quadrature or DEFAULT_OPTIONS["quadrature"], **options)
        features_s = time.perf_counter() - started - buffers_s
        values = {name: m.per_vertex() for name, m in maps.items()}
        first = next(iter(maps.values()))
        length, parametric_samples = float(first.radius), float(first.summary["mean_valid_samples"])
    else:
        samples = sums_samples(samples)
        values = atlas.per_vertex(names, radius, samples=samples, seed=seed, **options, **sums)
        features_s = time.perf_counter() - started - buffers_s
        length, parametric_samples = resolve_radius(radius, mesh.bounding_box_diagonal), None
    parametric_s = time.perf_counter() - started
    reference_s = reference.last_timings["estimation_s"]
    timings = {
        "parametric": parametric_s,
        "parametric_buffers": buffers_s,
        "parametric_features": features_s,
        "parametric_per_vertex": parametric_s - buffers_s - features_s,
        "reference": reference_s,
        "speedup": reference_s / parametric_s,
        "untimed_preprocessing": atlas.timings["preprocessing_s"] + atlas.timings["rasterisation_s"],
        "untimed_connectivity": reference.connectivity_s,
    }
    settings = {"features": names, "radius": str(radius), "samples": int(samples), "resolution": int(resolution),
                "compute_resolution": int(compute_resolution), "gaussian_method": gaussian_method,
                "parametric_gaussian_method": PARAMETRIC_GAUSSIAN[gaussian_method], "seed": int(seed),
                "query": query, "charts": mesh.n_charts,
                "parametric": "maps" if sums is None else "values at the vertices (surfel sums)",
                "mean_reference_samples": float(np.mean(reference.last_samples)),
                "mean_parametric_samples": parametric_samples}
    if truth is None:
        errors = {name: absolute_errors(values[name], ref_values[name]) for name in names}
        return Comparison(mesh, length, values, ref_values, errors, timings, settings)
    settings.update(truth_level=truth.level, truth_faces=truth.faces[-1], truth_changes=truth.changes,
                    truth_converged=truth.converged)
    errors = {name: absolute_errors(values[name], truth[name]) for name in names}
    reference_errors = {name: absolute_errors(ref_values[name], truth[name]) for name in names}
    return Comparison(mesh, length, values, ref_values, errors, timings, settings, truth.values, reference_errors)


def save_comparison_pictures(comparison: Comparison, out_dir: str | os.PathLike) -> dict[str, str]:
    """Per feature, ``compare_<feature>.png`` (parametric | reference | absolute difference, same
    view, shared colour range) and ``error_<feature>.png`` (the difference alone, larger).
    Returns the paths."""
    from .pictures.images import FEATURE_UNITS, colour_range, offscreen_figure, save_figure
    from .pictures.render import draw_vertex_values

    os.makedirs(out_dir, exist_ok=True)
    mesh = comparison.mesh
    paths = {}
    for name, ref in comparison.reference.items():
        par = comparison.parametric[name].astype(np.float64)
        cmap, low, high = colour_range(name, ref)
        difference = np.abs(par - ref)
        finite = difference[np.isfinite(difference)]
        top = float(np.percentile(finite, 98.0)) if finite.size else 1.0
        unit = FEATURE_UNITS.get(name, "")
        err = comparison.errors[name]
        panels = [("parametric", par, cmap, low, high), ("reference", ref, cmap, low, high),
                  (f"|difference|  %AE {err['percent_ae']:.3g}", difference, "magma", 0.0, top or 1.0)]
        fig = offscreen_figure((15, 5.2), 110)
        axes = fig.subplots(1, 3)
        for ax, (title, values, colours, lo, hi) in zip(axes, panels):
            mappable = draw_vertex_values(ax, mesh.positions, mesh.faces, values, colours, lo, hi)
            ax.set_title(title)
            fig.colorbar(mappable, ax=ax, fraction=0.046, pad=0.04, label=unit)
        t = comparison.timings
        fig.suptitle(f"{mesh.name}: {name}, r = {comparison.radius:.4g}   parametric {1e3 * t['parametric']:.0f} ms, "
                     f"reference {1e3 * t['reference']:.0f} ms (speed-up {t['speedup']:.2f}x)")
        paths[f"compare_{name}"] = os.path.join(os.fspath(out_dir), f"compare_{name}.png")
        save_figure(fig, paths[f"compare_{name}"])
        fig = offscreen_figure((7, 6), 110)
        ax = fig.subplots()
        mappable = draw_vertex_values(ax, mesh.positions, mesh.faces, difference, "magma", 0.0, top or 1.0)
        ax.set_title(f"{name}: |parametric - reference| (mean-normalised {err['mean_normalised']:.3g})")
        fig.colorbar(mappable, ax=ax, fraction=0.046, pad=0.04, label=unit)
        paths[f"error_{name}"] = os.path.join(os.fspath(out_dir), f"error_{name}.png")
        save_figure(fig, paths[f"error_{name}"])
    return paths
