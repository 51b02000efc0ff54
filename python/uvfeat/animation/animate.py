"""Features per animation frame: pre-processing and rasterisation once, then per frame only what
depends on the positions (``Atlas.update``, the features, the per-vertex lookup)."""

from __future__ import annotations

import os
import time
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from ..atlas import Atlas
from ..errors import AnimationError
from ..features import FeatureMap
from ..options import feature_names, resolve_options, resolve_radius
from ..interop import as_mesh
from ..mesh import Mesh
from .sources import frame_source

#: ``animate`` options that are named arguments of ``Atlas.compute`` (the rest are its ``**options``).
COMPUTE_ARGUMENTS = ("samples", "compute_resolution", "adaptive", "seed", "paper_mode")


@dataclass(frozen=True, repr=False, eq=False)
class AnimationFrame(Mapping):
    """One frame's features: a mapping feature name -> per-vertex values (as ``uvfeat.compute``
    returns: ``(n_vertices,)`` float32, ``(n_radii, n_vertices)`` for a list of radii).

    ``maps`` holds the frame's :class:`~uvfeat.FeatureMap` objects (textures, diagnostics); their
    default per-vertex query is evaluated for this frame, other queries would see the atlas's
    current frame. ``timings`` in milliseconds: ``positions_ms`` (evaluating the frame source,
    e.g. skinning), ``update_ms`` (buffers), ``features_ms``, ``per_vertex_ms``, ``total_ms``.
    """

    index: int
    time: float
    positions: np.ndarray
    values: dict[str, np.ndarray]
    maps: dict[str, FeatureMap] = field(default_factory=dict)
    timings: dict[str, float] = field(default_factory=dict)

    # Mapping's value equality would compare arrays (ambiguous truth value): frames are compared by identity
    __eq__ = object.__eq__
    __hash__ = object.__hash__

    def __getitem__(self, name: str) -> np.ndarray:
        return self.values[name]

    def __iter__(self):
        return iter(self.values)

    def __len__(self) -> int:
        return len(self.values)

    def __repr__(self) -> str:
        return (f"<uvfeat.AnimationFrame {self.index} at t = {self.time:.3f} s: {', '.join(self.values)}; "
                f"{self.timings.get('total_ms', float('nan')):.1f} ms>")


class Animation:
    """The frames of :func:`uvfeat.animate`: iterate for :class:`AnimationFrame` objects (computed
    as they are asked for; iterating again recomputes them), ``len()`` is the frame count."""

    def __init__(self, mesh: Mesh, atlas: Atlas, source, features: list[str], radius, options: dict):
        self.mesh, self.atlas, self.source = mesh, atlas, source
        self.features, self.radius, self.options = features, radius, options

    @property
    def times(self) -> np.ndarray:
        """Frame times in seconds."""
        return self.source.times

    @property
    def animation_name(self) -> str | None:
        """The glTF animation being played (None for arrays and file sequences)."""
        return getattr(self.source, "animation_name", None)

    def __len__(self) -> int:
        return len(self.source)

    def frame(self, k: int) -> AnimationFrame:
        """Frame ``k``: positions, buffers, features and per-vertex values."""
        if not -len(self) <= k < len(self):
            raise IndexError(f"frame {k} of an animation of {len(self)} frames")
        k %= len(self)
        ticks = [time.perf_counter()]
        positions = self.source.positions(k)
        ticks.append(time.perf_counter())
        self.atlas.update(positions)
        ticks.append(time.perf_counter())
        maps = self.atlas.compute(self.features, self.radius, **self.options)
        ticks.append(time.perf_counter())
        values = {name: feature.per_vertex() for name, feature in maps.items()}
        ticks.append(time.perf_counter())
        steps = np.diff(ticks) * 1e3
        timings = dict(zip(("positions_ms", "update_ms", "features_ms", "per_vertex_ms"), steps.tolist()))
        timings["total_ms"] = float(steps.sum())
        return AnimationFrame(k, float(self.times[k]), positions, values, maps, timings)

    def __iter__(self):
        return (self.frame(k) for k in range(len(self)))

    def __repr__(self) -> str:
        what = f"animation {self.animation_name!r} of " if self.animation_name else ""
        return f"<uvfeat.Animation: {what}{self.mesh.name!r}, {len(self)} frames, {', '.join(self.features)}>"


def animate(source, features, radius, frames=None, fps: float | None = None, *, animation: int | str | None = None,
            resolution: int = 1024, precision: str = "f32", uv: str = "auto", **options) -> Animation:
    """Features of a deforming mesh, frame by frame.

    Pre-processing (welding, charts, seams) and rasterisation run once, here; each frame then
    re-evaluates only what depends on the positions (:meth:`Atlas.update`) and the features. The
    sample pattern is seeded once (``seed``, default 0), so a rigid motion reproduces the same
    samples on the surface and the same features.

    Parameters
    ----------
    source : Mesh or str or PathLike
        The mesh (with or without UVs), or a mesh file loaded with :func:`uvfeat.load`.
    features : str or list of str
        Names from :data:`uvfeat.FEATURES` (or "all").
    radius : float, str or list
        Object units or a percentage of the bounding-box diagonal of ``source`` (resolved once,
        so every frame uses the same length); a list gives a scale stack.
    frames : array_like or list of paths, optional
        ``(n_frames, V, 3)`` positions in the order of ``source.positions``, or mesh files with
        the same vertices and faces. Omitted: the glTF/GLB file's own animation.
    fps : float, optional
        Frames per second (default 24): the sampling rate of a glTF animation, and the time step
        of ``frames``.
    animation : int or str, optional
        The glTF animation to play, by index or name (default the first).
    resolution, precision : see :class:`~uvfeat.Atlas`.
    uv : see :func:`uvfeat.load` (``source`` given as a path).
    **options
        Passed to :meth:`Atlas.compute` every frame: ``samples``, ``compute_resolution``,
        ``adaptive``, ``seed``, ``paper_mode``, ``margin``, ``max_jumps``, ...

    Returns
    -------
    Animation
        An iterable of :class:`AnimationFrame` (mappings feature name -> per-vertex values with
        ``.time``, ``.index``, ``.maps``, ``.timings``, ``.positions``), with ``len()``.

    Raises
    ------
    AnimationError
        No animation in the file, unknown animation, frames whose vertex count or connectivity
        disagrees with the mesh, inconsistent keyframes.
    InvalidParameterError, MeshFileError, UVError
        As for :func:`uvfeat.load` and :meth:`Atlas.compute`.
    """
    from ..io import load

    path = None
    if isinstance(source, (str, os.PathLike)):
        path = os.fspath(source)
        source = load(path, uv=uv, resolution=resolution)
    source = as_mesh(source)
    names = feature_names(features)
    resolve_options({k: v for k, v in options.items() if k not in COMPUTE_ARGUMENTS}, paper_mode=False)
    diagonal = source.bounding_box_diagonal
    radius = ([resolve_radius(r, diagonal) for r in radius] if isinstance(radius, (list, tuple, np.ndarray))
              else resolve_radius(radius, diagonal))
    frame_positions = frame_source(source, path, frames, fps, animation)
    mesh = source if source.has_uvs else source.with_atlas(resolution=resolution)
    if options.get("paper_mode"):
        precision = "f16"
    return Animation(mesh, Atlas(mesh, resolution=resolution, precision=precision), frame_positions, names, radius,
                     options)
