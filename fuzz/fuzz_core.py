"""Fuzzes the core entry points on random arrays: ``Mesh`` (positions, faces, UVs with NaN, Inf,
huge and out-of-range values), ``Atlas``, ``Atlas.compute`` (both quadratures), ``Atlas.locate`` and
``Atlas.update`` with random parameters, the automatic atlas (``uvfeat.unwrap.chart_uvs``) and the core's
pictures of per-vertex values (``_core.shaded_view``, behind ``uvfeat.pictures.render``). Run (no corpus needed)::

    .venv/bin/python fuzz/fuzz_core.py fuzz/corpus/core -max_total_time=60 -timeout=20

A finding is an exception other than :class:`uvfeat.UvfeatError`, a crash or a hang.
"""

from __future__ import annotations

import contextlib
import os
import sys

import atheris
import numpy as np

# Replaying inputs (UVFEAT_FUZZ_REPLAY=1) needs no coverage feedback, and instrumenting takes seconds.
with contextlib.nullcontext() if os.environ.get("UVFEAT_FUZZ_REPLAY") == "1" else atheris.instrument_imports():
    import uvfeat
    from harness import EXPECTED, numbers, quiet
    from uvfeat import _core

FEATURES = uvfeat.options.FEATURES
RADII = (-1.0, 0.0, float("nan"), 1e-9, 0.05, 0.3, 1e9)


SHAPES = (uvfeat.shapes.torus(2.0, 0.5, 8, 4), uvfeat.shapes.uv_sphere(1.0, 8, 4), uvfeat.shapes.plane(1.0, 4),
          uvfeat.shapes.split_plane(4))


def random_arrays(fdp) -> tuple:
    """Arrays of any content: most fail validation, which must say why."""
    n_vertices = fdp.ConsumeIntInRange(0, 40)
    n_faces = fdp.ConsumeIntInRange(0, 60)
    positions = numbers(fdp.ConsumeBytes(8 * 3 * n_vertices), 3 * n_vertices).reshape(-1, 3)
    if fdp.ConsumeBool():
        positions = np.nan_to_num(positions, nan=0.0, posinf=1.0, neginf=-1.0).clip(-10.0, 10.0)
    faces = np.array(fdp.ConsumeIntListInRange(3 * n_faces, -1, n_vertices), dtype=np.int64).reshape(-1, 3)
    uvs = numbers(fdp.ConsumeBytes(8 * 2 * n_vertices), 2 * n_vertices).reshape(-1, 2)
    if fdp.ConsumeBool():
        uvs = np.abs(np.nan_to_num(uvs, nan=0.5, posinf=1.0, neginf=0.0)) % 1.0
    return positions, faces, uvs, faces if fdp.ConsumeBool() else None


def perturbed_shape(fdp) -> tuple:
    """A valid analytic mesh with some positions and UVs moved by the input (folds, collapsed
    and coincident vertices, overlaps), so that the inputs reach the atlas and the sampler."""
    shape = fdp.PickValueInList(list(SHAPES))
    positions, uvs = shape.positions.copy(), shape.uvs.copy()
    for _ in range(fdp.ConsumeIntInRange(0, 8)):
        positions[fdp.ConsumeIntInRange(0, len(positions) - 1)] = numbers(fdp.ConsumeBytes(24), 3)
        uvs[fdp.ConsumeIntInRange(0, len(uvs) - 1)] = np.clip(numbers(fdp.ConsumeBytes(16), 2), 0.0, 1.0)
    return positions, shape.faces, uvs, shape.uv_faces


def run(data: bytes) -> None:
    fdp = atheris.FuzzedDataProvider(data)
    positions, faces, uvs, uv_faces = perturbed_shape(fdp) if fdp.ConsumeBool() else random_arrays(fdp)
    try:
        mesh = uvfeat.Mesh(positions, faces, uvs=uvs, uv_faces=uv_faces)
        atlas = uvfeat.Atlas(mesh, fdp.PickValueInList([1, 2, 8, 32, 64]))
        feature = fdp.PickValueInList(list(FEATURES))
        radius = fdp.PickValueInList(list(RADII))
        atlas.compute(feature, radius, samples=fdp.PickValueInList([4, 16, 64]), compute_resolution=16,
                      method=fdp.PickValueInList(["integral", "fit"]),
                      quadrature=fdp.PickValueInList(["pattern", "surfels"]))
        start = tuple(numbers(fdp.ConsumeBytes(16), 2))
        target = tuple(numbers(fdp.ConsumeBytes(16), 2))
        atlas.locate(start, target, max_jumps=fdp.ConsumeIntInRange(0, 40))
        atlas.update(positions * fdp.ConsumeFloat())
    except EXPECTED:
        pass
    try:
        uvs, uv_faces = uvfeat.unwrap.chart_uvs(positions, faces, resolution=fdp.PickValueInList([1, 8, 64, 1024]),
                                                padding=fdp.PickValueInList([0.0, 2.0, 4.0, -1.0]),
                                                max_angle=fdp.PickValueInList([1.0, 45.0, 89.0, 0.0, float("nan")]))
        uvfeat.Atlas(uvfeat.Mesh(positions, faces, uvs=uvs, uv_faces=uv_faces), 32)
    except EXPECTED:
        pass
    try:
        values = numbers(fdp.ConsumeBytes(8 * len(positions)), len(positions))
        n_colours = fdp.ConsumeIntInRange(0, 4)
        palette = np.clip(numbers(fdp.ConsumeBytes(24 * n_colours), 3 * n_colours).reshape(-1, 3), 0.0, 1.0)
        _core.shaded_view(np.ascontiguousarray(positions * fdp.ConsumeFloat()), faces, values, palette,
                          (fdp.ConsumeFloat(), fdp.ConsumeFloat()), (fdp.ConsumeFloat(), fdp.ConsumeFloat()),
                          fdp.ConsumeFloat(), (fdp.ConsumeIntInRange(0, 48), fdp.ConsumeIntInRange(0, 48)),
                          fdp.ConsumeIntInRange(0, 3), fdp.ConsumeIntInRange(-1, 1))
    except EXPECTED:
        pass


def main() -> None:
    quiet()
    atheris.Setup(sys.argv, run)
    atheris.Fuzz()


if __name__ == "__main__":
    main()
