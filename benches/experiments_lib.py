"""Helpers of benches/experiments.py: the test meshes (with cached xatlas atlases), one timed
parametric-vs-reference measurement, and the results file.

Timings follow `uvfeat.compare` (paper §5): the parametric side counts what every frame costs
(`Atlas.update` buffers + features + per-vertex texture lookup), the reference its estimation
(`Reference.last_timings["estimation_s"]`); pre-processing, rasterisation, half-edges and the
xatlas unwrap are not timed. Unlike `compare`, atlases and references are kept per mesh, so a
sweep rasterises and builds half-edges once, and the options `compare` does not take (precision,
adaptive sampling, max_jumps, tau) can be set.
"""

from __future__ import annotations

import json
import re
import sys
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
SHARED_MESHES = ROOT.parent / "shared" / "meshes"
CACHE_DIR = ROOT / "uvfeat-out" / "experiments-cache"  # xatlas atlases (git-ignored)
sys.path.insert(0, str(ROOT / "benches" / "peers"))

import surfaces  # noqa: E402  (analytic truth of the torus and the ellipsoid)

import uvfeat  # noqa: E402
from uvfeat.compare import PARAMETRIC_GAUSSIAN, absolute_errors  # noqa: E402
from uvfeat.io import read_geometry  # noqa: E402
from uvfeat.unwrap import xatlas_uvs  # noqa: E402
from report_common import machine  # noqa: E402  (benches/ is on the path as a script)

#: Shared meshes by short name: (file, needs an xatlas atlas).
SHARED = {"spot": ("spot_triangulated.obj", False), "bob": ("bob_tri.obj", False), "blub": ("blub.obj", False),
          "bunny": ("stanford-bunny.obj", True), "armadillo": ("armadillo.obj", True), "dragon": ("dragon.obj", True)}
TRUTH = {"torus": surfaces.torus_truth, "ellipsoid": surfaces.ellipsoid_truth}
TRUTH_FEATURES = ("mean_curvature", "gaussian_curvature")
START = time.perf_counter()


def log(message: str) -> None:
    """A progress line with the minutes since the start."""
    elapsed = time.perf_counter() - START
    print(f"[{int(elapsed // 60):3d}:{int(elapsed % 60):02d}] {message}", flush=True)


@dataclass
class Case:
    """A test mesh with its per-resolution atlases, its reference and (analytic meshes) its truth."""

    key: str
    mesh: uvfeat.Mesh
    truth: dict = field(default_factory=dict)
    unwrap_s: float = 0.0
    atlases: dict = field(default_factory=dict)
    _reference: object = None
    _reference_values: dict = field(default_factory=dict)

    @property
    def info(self) -> dict:
        return {"mesh": self.key, "faces": self.mesh.n_faces, "vertices": self.mesh.n_vertices,
                "charts": self.mesh.n_charts, "diagonal": self.mesh.bounding_box_diagonal}

    def atlas(self, resolution: int, precision: str = "f32") -> uvfeat.Atlas:
        if (resolution, precision) not in self.atlases:
            self.atlases[resolution, precision] = uvfeat.Atlas(self.mesh, resolution=resolution, precision=precision)
        return self.atlases[resolution, precision]

    def reference(self, feature: str, radius: str, gaussian_method: str = "moments") -> tuple[np.ndarray, float, float]:
        """Reference values, estimation seconds and mean neighbourhood size (computed once)."""
        if self._reference is None:
            self._reference = uvfeat.reference.Reference(self.mesh)
        key = (feature, radius, gaussian_method)
        if key not in self._reference_values:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                values = self._reference.compute(feature, radius, gaussian_method=gaussian_method)[feature]
            self._reference_values[key] = (values, self._reference.last_timings["estimation_s"],
                                           float(np.mean(self._reference.last_samples)))
        return self._reference_values[key]

    def all_features_timing(self, radius: str, samples: int, resolution: int, compute_resolution: int) -> dict:
        """Milliseconds of every feature in one pass on both sides (one sampling, all estimators)."""
        atlas = self.atlas(resolution)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            started = time.perf_counter()
            atlas.update(self.mesh.positions)
            maps = atlas.compute(uvfeat.FEATURES, radius, samples=samples, compute_resolution=compute_resolution)
            for fmap in maps.values():
                fmap.per_vertex()
            parametric_s = time.perf_counter() - started
            self.reference(uvfeat.FEATURES[0], radius)  # builds the half-edges outside the timing
            self._reference.compute(uvfeat.FEATURES, radius)
        reference_s = self._reference.last_timings["estimation_s"]
        return {"radius_pct": float(radius.rstrip("%")), "parametric_ms": 1e3 * parametric_s,
                "reference_ms": 1e3 * reference_s, "speedup": reference_s / parametric_s}


_CASES: dict[str, Case] = {}


def _unwrapped(key: str, mesh: uvfeat.Mesh, resolution: int, max_chart_area: float = 0.0) -> tuple[uvfeat.Mesh, float]:
    """``mesh`` with an xatlas atlas, cached on disk (the unwrap is slow and not timed)."""
    safe = re.sub(r"[^A-Za-z0-9.]+", "_", key)
    path = CACHE_DIR / f"{safe}-{mesh.n_faces}-{resolution}-{max_chart_area:.6g}.npz"
    if path.exists():
        cached = np.load(path)
        if len(cached["uv_faces"]) == mesh.n_faces:
            out = uvfeat.Mesh(mesh.positions, mesh.faces, cached["uvs"], cached["uv_faces"], name=key)
            return out, float(cached["s"])
    log(f"  xatlas unwrap of {key} ({mesh.n_faces:,} faces) ...")
    started = time.perf_counter()
    uvs, uv_faces = xatlas_uvs(mesh.positions, mesh.faces, resolution=resolution, max_chart_area=max_chart_area)
    seconds = time.perf_counter() - started
    CACHE_DIR.mkdir(parents=True, exist_ok=True)
    np.savez(path, uvs=uvs, uv_faces=uv_faces, s=seconds)
    out = uvfeat.Mesh(mesh.positions, mesh.faces, uvs, uv_faces, name=key)
    log(f"  xatlas: {out.n_charts} charts in {seconds:.1f} s")
    return out, seconds


def model(name: str, resolution: int = 1024) -> Case | None:
    """A shared mesh (``spot`` falls back to the bundled copy), None with a note when absent."""
    if name in _CASES:
        return _CASES[name]
    file, needs_atlas = SHARED[name]
    path = SHARED_MESHES / file
    if name == "spot" and not path.exists():
        path = Path(uvfeat.examples.spot_path())
    if not path.exists():
        print(f"note: {file} not found in ../shared/meshes/, skipping {name}", flush=True)
        return None
    seconds = 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if not needs_atlas:
            mesh = uvfeat.load(str(path), uv="require")
        else:
            positions, faces = read_geometry(str(path))
            used = np.unique(faces)  # the bunny has unreferenced vertices
            remap = np.full(len(positions), -1, dtype=np.int64)
            remap[used] = np.arange(len(used))
            mesh, seconds = _unwrapped(name, uvfeat.Mesh(positions[used], remap[faces], name=name), resolution)
    case = _CASES[name] = Case(name, mesh, unwrap_s=seconds)
    return case


def analytic(shape: str, faces: int, atlas: str = "xatlas", chart_area: float = 0.0, resolution: int = 1024) -> Case:
    """Torus (R = 2, a = 0.5) or ellipsoid (1 x 0.8 x 0.6) of about ``faces`` triangles with its own
    single-chart UVs (``atlas="single"``) or an xatlas atlas (charts at most ``chart_area`` of the
    surface area when > 0)."""
    n = max(4, int(round(np.sqrt(faces / 4))))  # both grids have about 4 n^2 faces with n_u = 2 n_v = 2 n
    if shape == "torus":
        mesh = uvfeat.shapes.torus(*surfaces.TORUS, 2 * n, n)
    else:
        mesh = uvfeat.shapes.ellipsoid(*surfaces.ELLIPSOID, 2 * n, n + 1)
    tag = f"{shape} {mesh.n_faces / 1000:.3g}K"
    key = f"{tag} single chart" if atlas == "single" else \
        f"{tag} xatlas" + (f" area<{chart_area:.3g}" if chart_area else "")
    if key in _CASES:  # the label holds the face count to 3 digits: unique for the sizes used here
        return _CASES[key]
    seconds = 0.0
    if atlas == "single":
        mesh = uvfeat.Mesh(mesh.positions, mesh.faces, mesh.uvs, mesh.uv_faces, name=key)
    else:
        corners = mesh.positions[mesh.faces]
        cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        area = 0.5 * np.linalg.norm(cross, axis=1).sum()
        mesh, seconds = _unwrapped(key, uvfeat.Mesh(mesh.positions, mesh.faces, name=key), resolution,
                                   chart_area * area)
    h, k = TRUTH[shape](np.asarray(mesh.positions))
    case = _CASES[key] = Case(key, mesh, {"mean_curvature": h, "gaussian_curvature": k}, seconds)
    return case


def release_atlases() -> None:
    """Frees the buffers of every cached atlas (meshes and references stay)."""
    for case in _CASES.values():
        case.atlases.clear()


_MEMO: dict[str, dict] = {}


def measure(case: Case, feature: str, radius: str, *, samples: int = 256, resolution: int = 1024,
            compute_resolution: int = 512, precision: str = "f32", adaptive: bool = False,
            gaussian_method: str = "moments", parametric_gaussian: str | None = None, **options) -> dict:
    """One timed parametric computation against the reference: a JSON-ready row. K comes from
    ``gaussian_method`` on the reference side and from ``parametric_gaussian`` (default: the
    matching method) on the parametric side. Identical settings are measured once per run
    (tables that share a configuration share the row)."""
    parametric_gaussian = parametric_gaussian or PARAMETRIC_GAUSSIAN[gaussian_method]
    settings = {"feature": feature, "radius_pct": float(radius.rstrip("%")), "samples": samples,
                "resolution": resolution, "compute_resolution": compute_resolution, "precision": precision,
                "adaptive": adaptive, "gaussian_method": gaussian_method, "parametric_gaussian": parametric_gaussian,
                "options": options}
    memo_key = json.dumps({"mesh": case.key, "faces": case.mesh.n_faces, **settings}, sort_keys=True)
    if memo_key in _MEMO:
        return dict(_MEMO[memo_key])
    reference, reference_s, reference_samples = case.reference(feature, radius, gaussian_method)
    atlas = case.atlas(resolution, precision)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        started = time.perf_counter()
        atlas.update(case.mesh.positions)
        buffers_s = time.perf_counter() - started
        fmap = atlas.compute(feature, radius, samples=samples, compute_resolution=compute_resolution,
                             adaptive=adaptive, gaussian_method=parametric_gaussian, **options)[feature]
        features_s = time.perf_counter() - started - buffers_s
        values = fmap.per_vertex()
        parametric_s = time.perf_counter() - started
    covered = np.isfinite(fmap.texture)
    row = {**case.info, **settings, "radius": float(fmap.radius),
           "parametric_ms": 1e3 * parametric_s, "buffers_ms": 1e3 * buffers_s, "features_ms": 1e3 * features_s,
           "per_vertex_ms": 1e3 * (parametric_s - buffers_s - features_s), "reference_ms": 1e3 * reference_s,
           "speedup": reference_s / parametric_s, "reference_samples": reference_samples,
           "second_stage_fraction": fmap.summary["second_stage_fraction"],
           "missing_fraction": fmap.summary["missing_fraction"],
           "texels_with_missing": float(np.mean(fmap.n_missing[covered] > 0)) if covered.any() else 0.0,
           "mean_valid_samples": fmap.summary["mean_valid_samples"],
           **{k: v for k, v in absolute_errors(values, reference).items() if k != "compared"}}
    if feature in case.truth:
        row["truth_pct_ae"] = absolute_errors(values, case.truth[feature])["percent_ae"]
        row["reference_truth_pct_ae"] = absolute_errors(reference, case.truth[feature])["percent_ae"]
    _MEMO[memo_key] = row
    return dict(row)


def describe(row: dict) -> str:
    """A one-line summary of a row for the progress output."""
    truth = f", truth %AE {row['truth_pct_ae']:.3g}" if "truth_pct_ae" in row else ""
    return (f"parametric {row['parametric_ms']:,.0f} ms, reference {row['reference_ms']:,.0f} ms, "
            f"%AE {row['percent_ae']:.3g}{truth}")


class Results:
    """The results file: metadata and, per experiment, its rows; saved after every experiment."""

    def __init__(self, path: Path, mode: str, command: str, resume: bool):
        self.path = path
        old = json.loads(path.read_text()) if resume and path.exists() else None
        if old is not None and old.get("mode") != mode:
            raise SystemExit(f"--resume: {path} holds a {old.get('mode')} run, this is a {mode} run")
        self.data = old or {"mode": mode, "machine": machine(), "command": command, "experiments": {}}

    def done(self, name: str) -> bool:
        return name in self.data["experiments"]

    def store(self, name: str, rows: list[dict], seconds: float, command: str) -> None:
        self.data["experiments"][name] = {"rows": rows, "seconds": seconds, "command": command,
                                          "finished": time.strftime("%Y-%m-%d %H:%M")}
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.path.write_text(json.dumps(self.data, indent=1))
