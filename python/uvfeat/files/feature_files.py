"""What ``uvfeat compute`` writes for one mesh, shared with ``uvfeat batch``: per-vertex values
(``.ply``, ``.npz``), feature maps (``.npy``, optionally ``.png`` and the 3D pictures
``FEATURE_3d.png``) and ``summary.json`` with the
settings, which a later batch run compares to decide whether the mesh is finished."""

from __future__ import annotations

import os
import time
from dataclasses import asdict, dataclass, field

import numpy as np

from .. import _core
from .._core import __version__
from ..errors import InvalidParameterError
from ..io import atomic_file, remove_partials
from .notes import recorded_notes
from ..options import (ARGUMENT_DEFAULTS, ATLAS_RESOLUTION, DEFAULT_OPTIONS, PAPER_OPTIONS, check_query,
                       check_resolution, feature_names, maps_samples, parse_radius, resolve_radius, sums_mesh,
                       sums_resolution, sums_samples, vertex_sums_options)
from .writers import write_json, write_per_vertex

SUMMARY = "summary.json"


def radius_tag(radius) -> str:
    """A radius as written in file names: ``2%`` -> ``2pct``, ``0.05`` -> ``0p05``."""
    return str(radius).strip().replace("%", "pct").replace(".", "p")


def radius_list(radius) -> list[str]:
    """Radii as the command line writes them: ``"1%,4%"``, ``0.05`` or a list -> ``["1%", "4%"]``."""
    items = radius.split(",") if isinstance(radius, str) else radius if isinstance(radius, (list, tuple)) else [radius]
    radii = [str(r).strip() for r in items if str(r).strip()]
    if not radii:
        raise InvalidParameterError(f"no radius in {radius!r}")
    return radii


#: Radii of at least this many face sides (``Mesh.face_side``, about an edge) let the maps be the
#: values at the vertices interpolated over each face: the features then vary over several faces.
#: On the shared scans the interpolated maps came closer to the surfels summed at every texel than
#: the pattern's maps from 2-3 sides up; below, 0.6-2.7 % of H's range off (K up to 4.2 %), worse
#: than the pattern's in five cells of eight.
VERTEX_MAP_SIDES = 3.0


@dataclass(frozen=True)
class FeatureJob:
    """Everything that decides the files of one mesh: what to compute, how, and what to write."""

    features: tuple[str, ...]
    radii: tuple[str, ...]
    #: None: 160 surfels per ball for the sums at the vertices, the pattern's 256 points per texel
    #: for the maps (:func:`~uvfeat.options.sums_samples`, :func:`~uvfeat.options.maps_samples`).
    samples: int | None = None
    resolution: int = ATLAS_RESOLUTION
    compute_resolution: int = ARGUMENT_DEFAULTS["compute_resolution"]
    adaptive: bool = False
    paper_mode: bool = False
    seed: int = ARGUMENT_DEFAULTS["seed"]
    query: str = DEFAULT_OPTIONS["query"]
    method: str = DEFAULT_OPTIONS["method"]
    sampling: str = DEFAULT_OPTIONS["sampling"]
    #: None: the per-vertex values by the default of the mesh's atlas
    #: (:func:`~uvfeat.options.per_vertex_defaults`), as ``uvfeat.compute``, and the maps those
    #: values interpolated over the faces where :meth:`maps_from_vertices`, the pattern's elsewhere.
    quadrature: str | None = None
    #: None: the facets for the sums at the vertices where they are the default, the smooth surface
    #: elsewhere (:data:`~uvfeat.options.SURFEL_DEFAULTS`).
    surface: str | None = None
    standard_error: bool = False
    directions: str | None = None
    uv: str = "auto"
    strict_uv: bool = False
    pictures: bool = field(default=True, compare=False)

    def __post_init__(self):
        """Checks every setting, so that a bad one is one error before any mesh, not one per mesh."""
        object.__setattr__(self, "features", tuple(feature_names(self.features)))
        object.__setattr__(self, "radii", tuple(radius_list(self.radii)))
        check_resolution(self.resolution)
        check_query(self.query)
        options = {
            "samples": maps_samples(self.samples), "compute_resolution": self.compute_resolution,
            "adaptive": self.adaptive, "seed": self.seed, "method": self.method, "sampling": self.sampling,
            "standard_error": self.standard_error, **self._named_surface()}
        if self.quadrature is not None:
            options["quadrature"] = self.quadrature
        if self.paper_mode:
            options = {**PAPER_OPTIONS, **options}
        # The core checks the settings with each radius's number (a length, or a percentage of a
        # diagonal not known yet: positive and finite either way).
        for radius in self.radii:
            _core.compute_settings(list(self.features), parse_radius(radius)[0], options)
        if self.directions and self.method != "fit":
            raise InvalidParameterError("--directions needs --method fit (principal directions come from the fit)")

    @classmethod
    def of(cls, features, radius, pictures: bool = False, **options) -> FeatureJob:
        """The job of a Python call's arguments: unknown option names are one clear error."""
        valid = cls.option_names()
        unknown = sorted(set(options) - set(valid))
        if unknown:
            raise InvalidParameterError(f"unknown option(s) {unknown}; valid: {', '.join(valid)}")
        return cls(features=features, radii=radius, pictures=pictures, **options)

    @classmethod
    def from_args(cls, args, pictures: bool = True) -> FeatureJob:
        """The job of a command's parsed arguments (``--feature``, ``--radius``, ``--samples`` ...);
        the computation options a command does not offer (``--adaptive``, ``--paper-mode``,
        ``--standard-error``, ``--directions``) keep their defaults."""
        offered = {name: getattr(args, name) for name in ("adaptive", "paper_mode", "standard_error", "directions",
                                                          "quadrature", "surface") if hasattr(args, name)}
        return cls(features=args.feature, radii=args.radius, samples=args.samples, resolution=args.resolution,
                   compute_resolution=args.compute_resolution, seed=args.seed, query=args.query, method=args.method,
                   sampling=args.sampling, uv=args.uv, strict_uv=args.strict_uv, pictures=pictures, **offered)

    def compute_options(self) -> dict:
        """The keyword options of :meth:`uvfeat.Atlas.compute` this job runs with."""
        return {"samples": maps_samples(self.samples), "compute_resolution": self.compute_resolution,
                "adaptive": self.adaptive, "seed": self.seed, "paper_mode": self.paper_mode, "query": self.query,
                "standard_error": self.standard_error, "method": self.method, "sampling": self.sampling,
                "quadrature": self.quadrature or DEFAULT_OPTIONS["quadrature"], **self._named_surface()}

    def _named_surface(self) -> dict:
        return {} if self.surface is None else {"surface": self.surface}

    def _named(self) -> dict:
        """The options the job names that decide where the per-vertex values come from."""
        named = {} if self.quadrature is None else {"quadrature": self.quadrature}
        return named | {"method": self.method, "standard_error": self.standard_error, "adaptive": self.adaptive}

    def vertex_options(self, mesh) -> dict | None:
        """The options of ``Atlas.per_vertex`` where the per-vertex values are the surfel sums at
        the vertices, as ``uvfeat.compute`` gives them (by default on an atlas of more than one
        chart, or named with ``quadrature="surfels"``); None where they are read from the maps."""
        added = vertex_sums_options(mesh, self.features, self._named(), self.paper_mode)
        if added is None:
            return None
        return {**self.compute_options(), **added, **self._named_surface(), "samples": sums_samples(self.samples)}

    def sums_mesh(self, mesh):
        """The mesh the sums at the vertices run on, as ``uvfeat.compute``'s
        (:func:`~uvfeat.options.sums_mesh`): uvfeat's own atlas of ``mesh`` where they are the
        default, else ``mesh``."""
        return sums_mesh(mesh, self.features, self._named(), self.paper_mode)

    def maps_from_vertices(self, mesh, radius: str) -> bool:
        """Whether the maps of ``radius`` are the values at the vertices interpolated over the faces
        (:func:`~uvfeat.vertex_texture.vertex_texture`) rather than computed at the texels: where the
        job names no quadrature, the per-vertex values are the surfel sums at the vertices
        (:meth:`vertex_options`) and the ball spans at least :data:`VERTEX_MAP_SIDES` face sides."""
        if self.quadrature is not None or self.vertex_options(mesh) is None:
            return False
        return resolve_radius(radius, mesh.bounding_box_diagonal) >= VERTEX_MAP_SIDES * mesh.face_side

    def vertex_resolution(self, mesh) -> int:
        """The atlas resolution of the sums at the vertices: the surfel grid of the smallest radius,
        as ``uvfeat.compute`` takes it, unless ``resolution`` names another size than the default."""
        return sums_resolution(mesh, list(self.radii), self.resolution, self.samples)

    @classmethod
    def option_names(cls) -> list[str]:
        """The settings :meth:`of` takes as keywords (all but the features, radii and pictures)."""
        return [name for name in cls.__dataclass_fields__ if name not in ("features", "radii", "pictures")]

    def options(self) -> dict:
        """The job's settings as :meth:`of` takes them, the features and radii apart."""
        return {name: getattr(self, name) for name in self.option_names()}

    def settings(self) -> dict:
        """The settings recorded in ``summary.json``: equal settings give equal files."""
        recorded = asdict(self)
        del recorded["pictures"]
        # Which maps are interpolated from the vertices: files written under another rule are not this job's.
        recorded["vertex_map_sides"] = VERTEX_MAP_SIDES
        recorded["features"], recorded["radii"] = list(self.features), list(self.radii)
        return recorded


def load_with_notes(path: str, uv: str, resolution: int, strict_uv: bool):
    """The mesh at ``path`` loaded with these UV options, and its warnings as notes."""
    from ..io import load

    with recorded_notes() as notes:
        mesh = load(path, uv=uv, resolution=resolution, normalize_uv=not strict_uv)
    return mesh, notes


@dataclass
class RadiusMaps:
    """The features of one radius of a job: per-vertex values, the maps' textures, the flagged
    vertices and the notes of computing them. ``maps`` are the computed :class:`FeatureMap` objects,
    None where the textures are the values at the vertices interpolated over the faces; then
    ``features_s`` is the values' time, ``per_vertex_s`` 0 and ``diagnostics["maps_s"]`` the
    interpolation's (otherwise ``features_s`` is the maps' and ``per_vertex_s`` the values')."""
    radius: str
    length: float
    per_vertex: dict
    textures: dict
    maps: dict | None
    diagnostics: dict
    flagged: dict
    notes: list[str]
    features_s: float
    per_vertex_s: float


def computed_radii(atlas, job: FeatureJob, advance=lambda description, done=True: None, at_vertices=None):
    """The job's features on ``atlas``, one radius after the other (``advance`` reports each). The
    per-vertex values are read from the maps, or, with ``at_vertices`` (an atlas and the options of
    :meth:`FeatureJob.vertex_options`), evaluated at the vertices on that atlas; then, where
    :meth:`FeatureJob.maps_from_vertices`, the maps are those values interpolated over the faces
    instead of computed at the texels."""
    from ..features import vertex_values_and_flags
    from ..vertex_texture import vertex_texture

    for radius in job.radii:
        advance(f"features at r = {radius}", done=False)
        if at_vertices is not None and job.maps_from_vertices(atlas.mesh, radius):
            vertex_atlas, options = at_vertices
            started = time.perf_counter()
            with recorded_notes() as notes:
                per_vertex, flags = vertex_values_and_flags(vertex_atlas, list(job.features), radius, **options)
            features_s = time.perf_counter() - started
            advance(f"per-vertex values at r = {radius}")
            started = time.perf_counter()
            textures = dict(zip(per_vertex, vertex_texture(atlas, np.stack(list(per_vertex.values())),
                                                           job.compute_resolution)))
            diagnostics = {"maps": "values at the vertices, interpolated over each face",
                           "texels": int(np.count_nonzero(np.isfinite(next(iter(textures.values()))))),
                           "maps_s": time.perf_counter() - started}
            yield RadiusMaps(radius, resolve_radius(radius, atlas.mesh.bounding_box_diagonal), per_vertex, textures,
                             None, diagnostics, {n: int(v.sum()) for n, v in flags.items()}, notes, features_s, 0.0)
            continue
        with recorded_notes() as notes:
            maps = atlas.compute(list(job.features), radius, **job.compute_options())
        advance(f"per-vertex values at r = {radius}")
        started = time.perf_counter()
        if at_vertices is None:
            per_vertex = {name: m.per_vertex() for name, m in maps.items()}
        else:
            vertex_atlas, options = at_vertices
            with recorded_notes() as vertex_notes:
                per_vertex = vertex_atlas.per_vertex(list(job.features), radius, **options)
            notes += [note for note in vertex_notes if note not in notes]
        first = next(iter(maps.values()))
        yield RadiusMaps(radius, first.radius, per_vertex, {n: m.texture for n, m in maps.items()}, maps,
                         first.summary, {n: int(v.sum()) for n, v in first.vertex_flags().items()}, notes,
                         first.settings["features_s"][0], time.perf_counter() - started)


def job_atlases(mesh, job: FeatureJob):
    """The atlas of the job's maps and, where the per-vertex values are the surfel sums at the
    vertices, the atlas and options they take (their own atlas at the surfels' resolution, on
    uvfeat's own UVs by default, as ``uvfeat.compute``) for :func:`computed_radii`'s
    ``at_vertices``, else None; with the rasterisation time of that second atlas
    (``vertex_rasterisation_s``) where there is one."""
    from ..atlas import Atlas

    vertex_options = job.vertex_options(mesh)
    vertex_mesh = mesh if vertex_options is None else job.sums_mesh(mesh)
    vertex_resolution = None if vertex_options is None else job.vertex_resolution(vertex_mesh)
    resolution = job.resolution
    if vertex_mesh is mesh and all(job.maps_from_vertices(mesh, r) for r in job.radii) \
            and vertex_resolution >= job.compute_resolution:
        # The maps are those values interpolated over the faces under their texels: the sums'
        # atlas serves them when it is the maps' mesh and as fine as the maps.
        resolution = vertex_resolution
    atlas = Atlas(mesh, resolution=resolution, precision="f16" if job.paper_mode else "f32")
    if vertex_options is None:
        return atlas, None, {}
    if vertex_mesh is mesh and vertex_resolution == resolution:
        return atlas, (atlas, vertex_options), {}
    vertex_atlas = Atlas(vertex_mesh, resolution=vertex_resolution, coverage_on_first_use=True)
    return atlas, (vertex_atlas, vertex_options), {"vertex_rasterisation_s": vertex_atlas.timings["rasterisation_s"]}


def write_feature_files(mesh, job: FeatureJob, out: str, load_notes: list[str], started: float,
                        advance=lambda description, done=True: None, source: dict | None = None):
    """Computes the job's features on ``mesh`` and writes its files to ``out``; ``advance``
    reports each step. ``summary.json`` is written last, and atomically, so its presence means
    the other files are complete. Returns the atlas and the summary."""
    from ..pictures.images import save_feature_figure
    from ..pictures.surface_plot import save_plot

    os.makedirs(out, exist_ok=True)
    remove_partials(out)
    summary = {"uvfeat": __version__, "mesh": mesh.name, "source": source or {}, "warnings": list(load_notes),
               "radii": {}, "settings": job.settings(), "pictures": job.pictures,
               "sizes": {"vertices": len(mesh.positions), "faces": len(mesh.faces)}}
    advance("pre-processing + rasterising", done=False)
    atlas, at_vertices, vertex_timings = job_atlases(mesh, job)
    summary["diagnostics"] = atlas.diagnostics
    summary["warnings"] += atlas.warnings()
    timings = dict(atlas.timings, **vertex_timings)
    advance("buffers ready")
    on_mesh: dict[str, list] = {name: [] for name in job.features}
    for computed in computed_radii(atlas, job, advance, at_vertices):
        radius, per_vertex = computed.radius, computed.per_vertex
        summary["warnings"] += computed.notes
        started_pv = time.perf_counter()
        for name, values in per_vertex.items():
            on_mesh[name].append(values)
        tag = radius_tag(radius)
        first = None if computed.maps is None else next(iter(computed.maps.values()))
        directions = first.per_vertex_directions() if job.method == "fit" and first is not None else None
        write_per_vertex(out, tag, mesh, computed.length, per_vertex, directions)
        time_pv = computed.per_vertex_s + time.perf_counter() - started_pv
        advance(f"maps at r = {radius}")
        line_field = first.uv_principal_directions()[:, :, ["d1", "d2"].index(job.directions)] \
            if job.directions and job.pictures else None
        for n, texture in computed.textures.items():
            with atomic_file(os.path.join(out, f"{n}_r{tag}.npy")) as path:
                np.save(path, texture)
            if job.pictures:
                save_feature_figure(os.path.join(out, f"{n}_r{tag}.png"), n, texture, computed.length, mesh.name,
                                    line_field=line_field)
        summary["radii"][radius] = {
            "radius": computed.length,
            "features_s": computed.features_s,
            "per_vertex_s": time_pv,
            "diagnostics": computed.diagnostics,
            "per_vertex_range": {n: [float(np.nanmin(v)), float(np.nanmax(v))] for n, v in per_vertex.items()},
            "flagged_vertices": computed.flagged,
        }
    if job.pictures:
        advance("3D pictures", done=False)
        started_3d = time.perf_counter()
        for name, rows in on_mesh.items():
            save_plot(os.path.join(out, f"{name}_3d.png"), mesh, np.stack(rows), feature=name, radius=list(job.radii))
        timings["pictures_3d_s"] = time.perf_counter() - started_3d
        advance("3D pictures ready")
    summary["timings_s"] = dict(timings, total=time.perf_counter() - started)
    write_json(os.path.join(out, SUMMARY), summary)
    return atlas, summary
