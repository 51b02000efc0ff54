"""Invariances of geometry as property tests (DESIGN.md §0 conventions) on every analytic
shape (sphere, ellipsoid, torus, cylinder, plane): a rigid motion
changes no feature, scaling by ``s`` scales each feature by ``s`` to the power of its length unit,
reversing the orientation flips the signed curvatures and keeps ``K``, and two tessellations (and
two atlases) of one surface agree within the Monte Carlo error the estimators report.

The parametric sampling depends only on the UV layout and the seed, so the first three hold up to
f32 rounding of the buffers, and the rounding moves a sample across the ball's rim or a face edge
here and there. Where the moved sample is at the rim of the pattern it can also switch the coverage
check's second gather on or off, which draws the whole neighbourhood anew (a Monte Carlo
difference, up to a fifth of the range with 64 samples, in a vertex or two). So the mean
difference must stay below a thousandth of each feature's range and fewer than 1 % of the vertices
may differ by more than 1 % of it: far below any wrong factor or sign."""

from __future__ import annotations

import warnings

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import uvfeat

#: Length exponent of each feature's unit (DESIGN.md §0): values scale by ``s ** exponent``.
LENGTH_EXPONENT = {"mean_curvature": -1, "k1": -1, "k2": -1, "curvedness": -1, "gaussian_curvature": -2,
                   "bending_energy": -2, "volume_invariant": 3, "open_volume": 3, "shape_index": 0}
FEATURES = list(LENGTH_EXPONENT)
OPTIONS = dict(samples=64, compute_resolution=64, seed=5)
#: In object units: a share of the bounding-box diagonal would change under a rotation.
RADIUS = 0.3

SHAPES = {
    "torus": lambda: uvfeat.shapes.torus(2.0, 0.5, 48, 24),
    "ellipsoid": lambda: uvfeat.shapes.ellipsoid(1.0, 0.8, 0.6, 48, 24),
    "sphere": lambda: uvfeat.shapes.uv_sphere(1.0, 48, 24),
    "cylinder": lambda: uvfeat.shapes.cylinder(1.0, 2.0, 48, 24),
    "plane": lambda: uvfeat.shapes.plane(2.0, 32),
}
EXAMPLES = settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def features_of(mesh: uvfeat.Mesh, features=FEATURES, radius=RADIUS, **options) -> dict[str, np.ndarray]:
    atlas = uvfeat.Atlas(mesh, 256)
    maps = atlas.compute(features, radius, **{**OPTIONS, **options})
    return {name: maps[name].per_vertex() for name in features}


def moved(mesh: uvfeat.Mesh, positions=None, faces=None, uv_faces=None) -> uvfeat.Mesh:
    return uvfeat.Mesh(mesh.positions if positions is None else positions, mesh.faces if faces is None else faces,
                       uvs=mesh.uvs, uv_faces=mesh.uv_faces if uv_faces is None else uv_faces, name=mesh.name)


def assert_close(actual: np.ndarray, expected: np.ndarray, name: str, shape: str, radius: float = RADIUS) -> None:
    finite = np.isfinite(expected)
    assert np.array_equal(finite, np.isfinite(actual)), f"{shape} {name}: NaNs moved"
    if not finite.any():  # the shape index of a plane: undefined everywhere, on both sides
        return
    # A feature that is constant on a shape (every curvature of the plane) has no range: 1 % of its
    # natural unit (r to the power of its length exponent) stands in.
    floor = 1e-2 * radius ** LENGTH_EXPONENT[name]
    spread = max(np.percentile(expected[finite], 99) - np.percentile(expected[finite], 1), floor)
    error = np.abs(actual[finite] - expected[finite]) / spread
    outliers = np.mean(error > 1e-2)
    summary = f"{shape} {name}: mean {error.mean():.2e} of the range, {outliers:.1%} of the vertices over 1 %"
    assert error.mean() < 1e-3 and outliers < 1e-2, summary


def rotation(q) -> np.ndarray:
    w, x, y, z = np.asarray(q) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


shapes = st.sampled_from(sorted(SHAPES))
unit = st.floats(-1.0, 1.0)
quaternions = st.tuples(unit, unit, unit, unit).filter(lambda q: np.linalg.norm(q) > 0.1)
translations = st.tuples(*(st.floats(-50.0, 50.0),) * 3)


@EXAMPLES
@given(shape=shapes, q=quaternions, t=translations)
def test_a_rigid_motion_changes_no_feature(shape, q, t):
    mesh = SHAPES[shape]()
    before = features_of(mesh)
    after = features_of(moved(mesh, positions=mesh.positions @ rotation(q).T + np.asarray(t)))
    for name in FEATURES:
        assert_close(after[name], before[name], name, shape)


@EXAMPLES
@given(shape=shapes, scale=st.floats(0.01, 100.0))
def test_scaling_scales_each_feature_by_its_unit(shape, scale):
    mesh = SHAPES[shape]()
    before = features_of(mesh)
    after = features_of(moved(mesh, positions=mesh.positions * scale), radius=RADIUS * scale)
    for name, exponent in LENGTH_EXPONENT.items():
        assert_close(after[name], before[name] * scale ** exponent, name, shape, RADIUS * scale)


@EXAMPLES
@given(shape=shapes)
def test_reversing_the_orientation_flips_the_signed_curvatures(shape):
    mesh = SHAPES[shape]()
    signed = ["mean_curvature", "gaussian_curvature", "k1", "k2", "shape_index", "curvedness"]
    before = features_of(mesh, signed)
    after = features_of(moved(mesh, faces=mesh.faces[:, ::-1], uv_faces=mesh.uv_faces[:, ::-1]), signed)
    expected = {"mean_curvature": -before["mean_curvature"], "gaussian_curvature": before["gaussian_curvature"],
                "k1": -before["k2"], "k2": -before["k1"], "shape_index": -before["shape_index"],
                "curvedness": before["curvedness"]}
    for name in signed:
        assert_close(after[name], expected[name], name, shape)


def torus_tube_angle(positions: np.ndarray, major: float = 2.0) -> np.ndarray:
    ring = np.hypot(positions[:, 0], positions[:, 1]) - major
    return np.arctan2(positions[:, 2], ring)


def test_two_tessellations_and_two_atlases_agree_within_the_monte_carlo_error():
    """H and K of a torus depend on the tube angle alone: binned by it, a 48 x 24 and a 96 x 48
    tessellation, and the 96 x 48 one with an xatlas atlas, agree within the standard error."""
    options = dict(samples=256, compute_resolution=128, standard_error=True)
    coarse = uvfeat.shapes.torus(2.0, 0.5, 48, 24)
    fine = uvfeat.shapes.torus(2.0, 0.5, 96, 48)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fine_xatlas = uvfeat.Mesh(fine.positions, fine.faces, name="xatlas").with_atlas()
    bins = np.linspace(-np.pi, np.pi, 13)
    results = {}
    for label, mesh in (("coarse", coarse), ("fine", fine), ("fine xatlas", fine_xatlas)):
        maps = uvfeat.Atlas(mesh, 512).compute(["mean_curvature", "gaussian_curvature"], RADIUS, **options)
        which = np.digitize(torus_tube_angle(mesh.positions), bins)
        results[label] = {name: (np.array([np.nanmean(f.per_vertex()[which == b]) for b in range(1, len(bins))]),
                                 np.nanmedian(f.standard_error)) for name, f in maps.items()}
    for name in ("mean_curvature", "gaussian_curvature"):
        reference, error = results["fine"][name]
        for label in ("coarse", "fine xatlas"):
            values, other_error = results[label][name]
            tolerance = 3.0 * np.hypot(error, other_error)
            worst = np.abs(values - reference).max()
            assert worst < tolerance, f"{label} {name}: binned values differ by {worst:.4f} > {tolerance:.4f}"
