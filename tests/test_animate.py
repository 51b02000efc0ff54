"""Features per animation frame (uvfeat.animate) against analytic truth: a sphere morphing from
radius 1 to 2 (H = 1/R(t)), an ellipsoid whose axes change, a rigid motion; frame sources, the
frame object, bad input, the CLI, and the shared Fox.glb (skins, several animations)."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest
import trimesh

import uvfeat
from analytic import range_normalised_error
from gltf_builder import GltfBuilder, per_vertex_uvs
from test_animation_gltf import axis_angle
from uvfeat.errors import AnimationError, MeshFileError

SMALL = dict(resolution=512, compute_resolution=128)


def growing_sphere(path) -> str:
    """A unit sphere whose one morph target (offsets = positions) is weighted 0 -> 1 over one
    second: radius R(t) = 1 + t."""
    positions, faces, uvs = per_vertex_uvs(uvfeat.shapes.uv_sphere(1.0, 64, 32))
    b = GltfBuilder()
    node = b.node(root=True, mesh=b.mesh([b.primitive(positions, faces, uvs, targets=[positions])]))
    b.animation("grow", [(node, "weights", [0.0, 1.0], [0.0, 1.0], "LINEAR")])
    return b.save(path)


def ellipsoid_truth(points: np.ndarray, axes) -> tuple[np.ndarray, np.ndarray]:
    """H and K of the ellipsoid x²/a² + y²/b² + z²/c² = 1 at points on it (outward normals)."""
    axes = np.asarray(axes, dtype=float)
    a2b2c2 = np.prod(axes**2)
    s = (points**2 / axes**4).sum(axis=1)
    h = (np.sum(axes**2) - (points**2).sum(axis=1)) / (2 * a2b2c2 * s**1.5)
    return h, 1.0 / (a2b2c2 * s**2)


def test_morph_from_radius_1_to_2_gives_h_equal_1_over_r_per_frame(tmp_path):
    frames = uvfeat.animate(growing_sphere(tmp_path / "grow.glb"), ["mean_curvature", "gaussian_curvature"], 0.2,
                            fps=4, **SMALL)
    assert len(frames) == 5 and frames.animation_name == "grow"
    for frame in frames:
        radius = 1.0 + frame.time
        np.testing.assert_allclose(np.linalg.norm(frame.positions, axis=1), radius, rtol=1e-6)
        assert np.median(np.abs(frame["mean_curvature"] * radius - 1)) < 0.03, frame
        assert np.median(np.abs(frame["gaussian_curvature"] * radius**2 - 1)) < 0.05, frame


def test_ellipsoid_with_changing_axes_matches_its_curvature_per_frame():
    sphere = uvfeat.shapes.uv_sphere(1.0, 64, 32)
    axes = np.array([(1.0, 1.0, 1.0), (1.5, 1.0, 0.75), (2.0, 0.8, 0.6)])
    frames = uvfeat.animate(sphere, ["mean_curvature", "gaussian_curvature"], 0.1,
                            frames=sphere.positions[None] * axes[:, None], fps=1, **SMALL)
    for frame in frames:
        h, k = ellipsoid_truth(frame.positions, axes[frame.index])
        h_error = np.abs(frame["mean_curvature"] / h - 1)
        assert np.median(h_error) < 0.03, frame
        assert np.median(np.abs(frame["gaussian_curvature"] / k - 1)) < 0.05, frame
        sharpest = h > np.percentile(h, 90)  # the tips, where H grows from 1 to 4.3 over the frames
        assert np.median(h_error[sharpest]) < 0.05, frame


def test_a_rigid_animation_leaves_every_feature_unchanged(tmp_path):
    positions, faces, uvs = per_vertex_uvs(uvfeat.shapes.torus(2.0, 0.5, 96, 48))
    b = GltfBuilder()
    node = b.node(root=True, mesh=b.mesh([b.primitive(positions, faces, uvs)]))
    b.animation("tumble", [
        (node, "rotation", [0.0, 2.0], [axis_angle([1, 2, 3], 0), axis_angle([1, 2, 3], 170)], "LINEAR"),
        (node, "translation", [0.0, 2.0], [[0, 0, 0], [5.0, -3.0, 40.0]], "LINEAR")])
    frames = list(uvfeat.animate(b.save(tmp_path / "tumble.glb"), "all", 0.3, fps=1, **SMALL))
    assert len(frames) == 3
    assert np.abs(frames[2].positions - frames[0].positions).max() > 10
    for frame in frames[1:]:
        for name in uvfeat.FEATURES:
            # Monte Carlo noise between seeds is 1-2 % of the range here; the same seed on the moved
            # surface draws the same samples, so only rounding may differ
            assert range_normalised_error(frame[name], frames[0][name]) < 1e-4, (name, frame)


def test_frames_from_mesh_files(tmp_path):
    sphere = uvfeat.shapes.uv_sphere(1.0, 48, 24)
    paths = []
    for k, radius in enumerate((1.0, 1.5)):
        paths.append(str(tmp_path / f"frame_{k}.ply"))
        trimesh.Trimesh(sphere.positions * radius, sphere.faces, process=False).export(paths[-1])
    frames = uvfeat.animate(sphere, "mean_curvature", 0.15, frames=paths, fps=10, samples=64, resolution=256,
                            compute_resolution=64)
    assert len(frames) == 2
    for frame, radius in zip(frames, (1.0, 1.5)):
        assert frame.time == pytest.approx(frame.index / 10)
        assert np.median(np.abs(frame["mean_curvature"] * radius - 1)) < 0.05
    other = uvfeat.shapes.uv_sphere(1.0, 48, 24)
    trimesh.Trimesh(other.positions, other.faces[:, ::-1], process=False).export(tmp_path / "flipped.ply")
    frames = uvfeat.animate(sphere, "mean_curvature", 0.15, frames=[tmp_path / "flipped.ply"], resolution=256)
    with pytest.raises(AnimationError, match="frame 0 \\(flipped.ply\\) has different faces"):
        next(iter(frames))


def test_the_frame_is_a_mapping_with_time_maps_and_timings():
    sphere = uvfeat.shapes.uv_sphere(1.0, 32, 16)
    frames = uvfeat.animate(sphere, ["mean_curvature", "k1"], "10%", frames=sphere.positions[None].repeat(2, 0),
                            fps=2, samples=16, resolution=128, compute_resolution=32)
    frame = frames.frame(-1)
    assert (frame.index, frame.time) == (1, 0.5)
    assert list(frame) == ["mean_curvature", "k1"] and dict(frame).keys() == frame.maps.keys()
    assert frame["k1"].shape == (sphere.n_vertices,)
    assert frame.maps["k1"].texture.shape == (32, 32)
    assert set(frame.timings) == {"positions_ms", "update_ms", "features_ms", "per_vertex_ms", "total_ms"}
    assert frames.radius == pytest.approx(0.1 * sphere.bounding_box_diagonal)
    with pytest.raises(IndexError):
        frames.frame(2)


# -- bad input ----------------------------------------------------------------------------------------
@pytest.mark.parametrize("frames, message", [
    (np.zeros((2, 10, 3)), "frames have 10 vertices each, the mesh 'plane 1.0' has 25"),
    (np.zeros((25, 3)), "shape \\(n_frames, 25, 3\\)"),
    (np.zeros((0, 25, 3)), "holds no frame"),
    (np.full((1, 25, 3), np.nan), "frame 0 has NaN or Inf"),
    ("one.obj", "got a single path"),
])
def test_frames_that_disagree_with_the_mesh_are_refused(frames, message):
    with pytest.raises(AnimationError, match=message):
        uvfeat.animate(uvfeat.shapes.plane(1.0, 4), "mean_curvature", 0.1, frames=frames)


def test_sources_without_an_animation_say_what_to_pass(tmp_path):
    plane = uvfeat.shapes.plane(1.0, 4)
    with pytest.raises(AnimationError, match="a Mesh carries no animation"):
        uvfeat.animate(plane, "mean_curvature", 0.1)
    trimesh.Trimesh(plane.positions, plane.faces).export(tmp_path / "still.ply")
    with pytest.raises(AnimationError, match="still.ply has no animation of its own"):
        uvfeat.animate(tmp_path / "still.ply", "mean_curvature", 0.1, uv="xatlas", resolution=64)
    b = GltfBuilder()
    b.node(root=True, mesh=b.mesh([b.primitive(*per_vertex_uvs(plane))]))
    with pytest.raises(AnimationError, match="still.glb has no animation; pass frames="):
        uvfeat.animate(b.save(tmp_path / "still.glb"), "mean_curvature", 0.1, resolution=64)
    with pytest.raises(MeshFileError, match="do not exist"):
        uvfeat.animate(plane, "mean_curvature", 0.1, frames=[tmp_path / "missing.obj"])


@pytest.mark.parametrize("arguments, message", [
    (dict(fps=0), "fps must be a positive number"),
    (dict(animation="grow", frames=np.zeros((1, 25, 3))), "cannot be combined with frames"),
    (dict(frames=np.zeros((1, 25, 3)), sample=64), "unknown option"),
])
def test_bad_animation_arguments_are_refused(arguments, message):
    with pytest.raises(uvfeat.UvfeatError, match=message):
        uvfeat.animate(uvfeat.shapes.plane(1.0, 4), "mean_curvature", 0.1, **arguments)


# -- CLI and a real animated file ----------------------------------------------------------------
def test_cli_writes_frames_maps_and_a_gif(tmp_path):
    from PIL import Image

    out = tmp_path / "out"
    result = subprocess.run([sys.executable, "-m", "uvfeat", "animate", growing_sphere(tmp_path / "grow.glb"),
                             "--radius", "0.2", "--fps", "2", "--samples", "32", "--resolution", "256",
                             "--compute-resolution", "64", "--method", "fit", "--out", str(out)],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert "3 frames" in result.stderr
    with np.load(out / "frame_0002.npz") as last:
        assert last["time"] == 1.0 and np.median(last["mean_curvature"]) == pytest.approx(0.5, rel=0.05)
    assert np.load(out / "mean_curvature_0001.npy").shape == (64, 64)
    assert Image.open(out / "mean_curvature.gif").n_frames == 3
    # the 3D view: one still camera framed on the first frame, so the growing sphere covers more of it
    with Image.open(out / "mean_curvature_3d.gif") as gif:
        covered = []
        for k in range(gif.n_frames):
            gif.seek(k)
            covered.append((np.asarray(gif.convert("RGB")).min(axis=-1) < 200).mean())
    assert len(covered) == 3 and 0.1 < covered[0] < covered[1] < covered[2], covered
    imageio_ffmpeg = pytest.importorskip("imageio_ffmpeg", reason="MP4 needs the extra uvfeat[video]")

    reader = imageio_ffmpeg.read_frames(str(out / "mean_curvature_3d.mp4"))
    meta = next(reader)
    assert meta["size"] == tuple(n + n % 2 for n in gif.size) and len(list(reader)) == 3
    summary = json.loads((out / "summary.json").read_text())
    assert summary["animation"] == "grow" and len(summary["timings"]["per_frame"]) == 3
    assert summary["settings"]["method"] == "fit"
    failed = subprocess.run([sys.executable, "-m", "uvfeat", "animate", str(tmp_path / "grow.glb"), "--animation",
                             "walk", "--out", str(out)], capture_output=True, text=True)
    assert failed.returncode == 2 and "no animation 'walk'" in failed.stderr and "0: 'grow'" in failed.stderr


@pytest.mark.shared
def test_fox_animates_end_to_end(shared_mesh):
    path = shared_mesh("Fox.glb")
    with pytest.raises(AnimationError, match="0: 'Survey', 1: 'Walk', 2: 'Run'"):
        uvfeat.animate(path, "mean_curvature", "4%", animation="Dance")
    frames = uvfeat.animate(path, ["mean_curvature", "shape_index"], "4%", animation="Walk", fps=4, samples=64,
                            resolution=256, compute_resolution=64)
    assert len(frames) == 3 and frames.animation_name == "Walk"
    rest = frames.mesh.positions
    # the skin at its bind pose reproduces the loaded mesh vertex for vertex (Fox's diagonal: 176)
    np.testing.assert_allclose(uvfeat.GltfAnimation(path, reference=frames.mesh).positions(None), rest, atol=1e-3)
    edges = np.concatenate([frames.mesh.faces[:, [0, 1]], frames.mesh.faces[:, [1, 2]], frames.mesh.faces[:, [2, 0]]])
    rest_lengths = np.linalg.norm(rest[edges[:, 0]] - rest[edges[:, 1]], axis=1)
    for frame in frames:
        lengths = np.linalg.norm(frame.positions[edges[:, 0]] - frame.positions[edges[:, 1]], axis=1)
        assert np.abs(frame.positions - rest).max() > 1.0  # the fox moves...
        assert np.median(np.abs(lengths / rest_lengths - 1)) < 0.05  # ...as a skinned body, not scrambled
        assert np.isfinite(frame["mean_curvature"]).mean() > 0.99
        assert np.nanmin(frame["shape_index"]) >= -1 and np.nanmax(frame["shape_index"]) <= 1
    assert os.path.basename(path) == frames.mesh.name
