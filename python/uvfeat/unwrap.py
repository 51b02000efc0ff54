"""Automatic multi-chart UV atlases for meshes that have none (DESIGN.md §1.1.1).

Two unwrappers, chosen by ``method`` wherever an atlas is built (:meth:`uvfeat.Mesh.with_atlas`,
``uvfeat.load(uv=...)``, the CLI's ``--uv``):

- ``"charts"`` (default): uvfeat's own normal-cone charts, each projected onto the plane across
  its cone's axis and checked to be injective as it grows, packed as bitmaps; rough parts (a
  scan's noise) are charted on a smoothed copy of the surface, and the few faces that still fold
  join a chart beside them where that stays injective. 0.1-0.6 s for 70K-280K faces; the
  features are as accurate on it as on xatlas's atlas (docs/BENCHMARKS.md).
- ``"xatlas"``: xatlas's optimised charts (fewer, rounder, less stretched; about 20 s for 100K
  faces on two cores).

An atlas depends only on the mesh, the options and the unwrapper's build, so both are cached on
disk, keyed by a hash of the positions, the faces, the options and the unwrapper (the xatlas
version, or uvfeat's version and core library): a second run on the same mesh reads the atlas
back in milliseconds (about 2 MB per 100K faces). The cache lives in ``$UVFEAT_CACHE_DIR``
(default ``$XDG_CACHE_HOME/uvfeat`` or ``~/.cache/uvfeat``); ``UVFEAT_CACHE_DIR=off`` or
``cache=False`` turns it off. A cache file that cannot be read is ignored and written anew.
"""

from __future__ import annotations

import hashlib
import os
import tempfile
import warnings
from pathlib import Path

import numpy as np

from . import _core
from .errors import InvalidMeshError

#: The unwrappers, default first.
UNWRAP_METHODS = ("charts", "xatlas")

#: What ``uvfeat.load(..., uv=...)`` and the CLI's ``--uv`` accept: the file's UVs, or a new atlas
#: by one of the unwrappers.
UV_POLICIES = ("auto", "require") + UNWRAP_METHODS

#: Changes whenever what a cache file holds, or how the atlas is made, changes.
_CACHE_FORMAT = 1


def cache_dir() -> Path | None:
    """The folder of cached atlases, or ``None`` when caching is turned off."""
    configured = os.environ.get("UVFEAT_CACHE_DIR")
    if configured is not None:
        return None if configured.strip().lower() in ("", "off", "0", "none") else Path(configured)
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "uvfeat"


def chart_uvs(positions: np.ndarray, faces: np.ndarray, *, resolution: int = 1024, padding: float = 4.0,
              max_angle: float | None = None, cache: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Normal-cone charts packed into the unit square (uvfeat's own unwrapper).

    Parameters
    ----------
    positions : (n_vertices, 3) float64
    faces : (n_faces, 3) int64
    resolution : int
        Texture size the packing is made for; ``padding`` is in texels at that size.
    padding : float
        Gutter between charts, in texels at ``resolution``.
    max_angle : float, optional
        Half-angle in degrees of each chart's normal cone, in (0, 90); default 45. Smaller angles
        give more charts with less stretch (at most ``1 / cos(max_angle)``).
    cache : bool
        Read and write the on-disk atlas cache (see the module's documentation).

    Returns
    -------
    uvs : (n_uvs, 2) float64 in [0, 1]
    uv_faces : (n_faces, 3) int64, in the order of ``faces``

    Raises
    ------
    InvalidMeshError
        Non-finite positions, out-of-range faces.
    InvalidParameterError
        An option out of range, or more charts than ``resolution`` has room for.
    """
    positions = np.ascontiguousarray(positions, dtype=np.float64)
    faces = np.ascontiguousarray(faces, dtype=np.int64)
    options = {"resolution": int(resolution), "padding": float(padding),
               "max_angle": None if max_angle is None else float(max_angle)}
    return _cached(positions, faces, (sorted(options.items()),), _charts_build() if cache else None,
                   lambda: _charts(positions, faces, options))


def _charts(positions: np.ndarray, faces: np.ndarray, options: dict) -> tuple[np.ndarray, np.ndarray]:
    uvs, uv_faces, _ = _core.unwrap(positions, faces, **options)
    return uvs, uv_faces


def _charts_build() -> str:
    """What identifies the build of uvfeat's unwrapper: the version, and the core library's size
    and time (a rebuilt library of the same version may chart differently)."""
    library = os.stat(_core.__file__)
    return f"uvfeat {_core.__version__} {library.st_size} {library.st_mtime_ns}"


def xatlas_uvs(positions: np.ndarray, faces: np.ndarray, *, resolution: int = 1024, padding: int = 4,
               max_chart_area: float = 0.0, cache: bool = True, chart_options: dict | None = None,
               pack_options: dict | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Charts and packs the mesh with xatlas.

    Parameters
    ----------
    positions : (n_vertices, 3) float64
    faces : (n_faces, 3) int64
    resolution : int
        Texture size the packing is made for; ``padding`` is in texels at that size. Use the
        geometry-buffer resolution so that gutters are at least 2 texels there (DESIGN.md §1.1).
    padding : int
        Gutter between charts, in texels at ``resolution``.
    max_chart_area : float
        Upper bound of a chart's surface area (0 = xatlas's default, unbounded); smaller values
        give more charts.
    cache : bool
        Read and write the on-disk atlas cache (see the module's documentation).
    chart_options, pack_options : dict, optional
        Further fields of xatlas's ``ChartOptions`` and ``PackOptions`` by name (for example
        ``{"max_cost": 4.0}``, ``{"bruteForce": True}``); an unknown name raises ``ValueError``.

    Returns
    -------
    uvs : (n_uvs, 2) float64 in [0, 1]
    uv_faces : (n_faces, 3) int64, in the order of ``faces``
    """
    import xatlas

    positions = np.ascontiguousarray(positions, dtype=np.float64)
    faces = np.ascontiguousarray(faces, dtype=np.int64)
    chart = {"max_chart_area": float(max_chart_area)} if max_chart_area > 0 else {}
    chart.update(chart_options or {})
    pack = {"resolution": int(resolution), "padding": int(padding), "bilinear": True, **(pack_options or {})}
    options = (sorted(chart.items()), sorted(pack.items()))
    return _cached(positions, faces, options, getattr(xatlas, "__version__", "unknown") if cache else None,
                   lambda: _unwrap(xatlas, positions, faces, chart, pack))


def _cached(positions: np.ndarray, faces: np.ndarray, options: tuple, build: str | None,
            make) -> tuple[np.ndarray, np.ndarray]:
    """The atlas ``make()`` returns, read from the cache when it holds one for this mesh, these
    options and this ``build`` of the unwrapper (``None``: no caching), written there otherwise."""
    folder = cache_dir() if build is not None else None
    if folder is None:
        return make()
    path = folder / "atlases" / f"{_cache_key(positions, faces, options, build)}.npz"
    cached = _read_cached(path, len(faces))
    if cached is not None:
        return cached
    uvs, uv_faces = make()
    _write_cached(path, uvs, uv_faces)
    return uvs, uv_faces


def _unwrap(xatlas, positions: np.ndarray, faces: np.ndarray, chart: dict, pack: dict) -> tuple[np.ndarray, np.ndarray]:
    atlas = xatlas.Atlas()
    atlas.add_mesh(positions.astype(np.float32), np.ascontiguousarray(faces, dtype=np.uint32))
    chart_options, pack_options = _options(xatlas.ChartOptions(), chart), _options(xatlas.PackOptions(), pack)
    atlas.generate(chart_options, pack_options)
    vmapping, indices, uvs = atlas[0]
    if len(indices) != len(faces) or not np.array_equal(vmapping[indices], faces):
        raise InvalidMeshError("xatlas changed the faces of the mesh (degenerate or non-manifold input?); "
                               "clean the mesh or provide UVs")
    return np.ascontiguousarray(uvs, dtype=np.float64), np.ascontiguousarray(indices, dtype=np.int64)


def _options(options, fields: dict):
    """xatlas's ``options`` object with ``fields`` set; an unknown field name is an error."""
    for name, value in fields.items():
        if not hasattr(options, name):
            raise ValueError(f"xatlas {type(options).__name__} has no option {name!r}")
        setattr(options, name, value)
    return options


def _cache_key(positions: np.ndarray, faces: np.ndarray, options: tuple, build: str) -> str:
    digest = hashlib.sha256()
    digest.update(repr((_CACHE_FORMAT, build, options, positions.shape, faces.shape)).encode())
    digest.update(positions.tobytes())
    digest.update(faces.tobytes())
    return digest.hexdigest()


def _read_cached(path: Path, n_faces: int) -> tuple[np.ndarray, np.ndarray] | None:
    if not path.is_file():
        return None
    try:
        with np.load(path, allow_pickle=False) as data:
            uvs, uv_faces = data["uvs"], data["uv_faces"]
    except Exception:  # a truncated or foreign file: unwrap again and overwrite it
        return None
    usable = (uvs.ndim == 2 and uvs.shape[1] == 2 and uv_faces.shape == (n_faces, 3) and len(uvs) > 0
              and int(uv_faces.min(initial=0)) >= 0 and int(uv_faces.max(initial=0)) < len(uvs))
    return (uvs.astype(np.float64), uv_faces.astype(np.int64)) if usable else None


def _write_cached(path: Path, uvs: np.ndarray, uv_faces: np.ndarray) -> None:
    temporary = None
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        # Written beside the target and renamed, so that concurrent runs never read half a file.
        with tempfile.NamedTemporaryFile(dir=path.parent, suffix=".tmp", delete=False) as handle:
            temporary = Path(handle.name)
            # int32 faces where they fit: a third less to write and read back.
            np.savez(handle, uvs=uvs, uv_faces=uv_faces.astype(np.int32 if len(uvs) < 2**31 else np.int64))
        os.replace(temporary, path)
    except OSError as error:
        if temporary is not None:
            temporary.unlink(missing_ok=True)
        warnings.warn(f"could not write the atlas cache {path}: {error}; set UVFEAT_CACHE_DIR to a writable "
                      "folder or to 'off'", RuntimeWarning, stacklevel=3)
