"""Files the command line writes: per-vertex values as PLY (vertex properties and colours) and
NPZ, and JSON summaries, each complete or absent (:func:`atomic_file`). Pictures are written by
:mod:`uvfeat.pictures.images`."""

from __future__ import annotations

import json
import os

import numpy as np

from ..pictures.images import vertex_colours
from ..io import atomic_file
from ..mesh import Mesh


def direction_properties(directions: np.ndarray | None) -> dict[str, np.ndarray]:
    """PLY vertex properties ``d1_x ... d2_z`` of ``(n_vertices, 2, 3)`` principal directions."""
    if directions is None:
        return {}
    return {f"d{k + 1}_{axis}": directions[:, k, a].astype("float32") for k in range(2) for a, axis in enumerate("xyz")}


def write_per_vertex(out: str, tag: str, mesh: Mesh, radius: float, values: dict[str, np.ndarray],
                     directions: np.ndarray | None = None) -> None:
    """Writes ``per_vertex_r<tag>.npz`` (positions, faces, radius, one array per feature and the
    principal directions when given) and ``per_vertex_r<tag>.ply`` (the same values as vertex
    properties, the first feature also as ``quality``, which MeshLab reads as its per-vertex
    quality, and coloured by it)."""
    import trimesh

    arrays = dict(values)
    if directions is not None:
        arrays["principal_directions"] = directions
    # Uncompressed: zlib took longer than the features of a 280K-face mesh (0.46 s against 0.5 s).
    with atomic_file(os.path.join(out, f"per_vertex_r{tag}.npz")) as path:
        np.savez(path, positions=mesh.positions, faces=mesh.faces, radius=radius, **arrays)
    ply = trimesh.Trimesh(mesh.positions, mesh.faces, process=False)
    first = next(iter(values))
    ply.vertex_attributes["quality"] = values[first].astype(np.float32)
    for name, v in values.items():
        ply.vertex_attributes[name] = v.astype(np.float32)
    for name, v in direction_properties(directions).items():
        ply.vertex_attributes[name] = v
    ply.visual.vertex_colors = vertex_colours(first, values[first])
    with atomic_file(os.path.join(out, f"per_vertex_r{tag}.ply")) as path:
        ply.export(path)


def write_json(path: str, summary: dict) -> None:
    """Writes ``summary`` as indented JSON (NumPy scalars as floats)."""
    with atomic_file(path) as partial, open(partial, "w") as f:
        json.dump(summary, f, indent=2, default=float)
