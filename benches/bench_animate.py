"""Benchmark of features per animation frame (issue: animated and deformable meshes).

    .venv/bin/python benches/bench_animate.py [--mesh ANIMATED.glb] [--frames 8] [--radius 2%]

Default configuration (DESIGN.md §1.10): 1024² geometry buffers, 512² computation texture, 256 samples.
Without --mesh it writes a skinned 102,400-triangle torus (xatlas atlas, 8 joints around the ring,
each tilting back and forth about its own radial axis, so the ring waves) to a temporary GLB and plays it. Prints
what runs once, the median milliseconds per frame by stage, and the share of the buffer pipeline
that each frame no longer repeats. RAYON_NUM_THREADS caps the threads.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
import warnings

import numpy as np

import uvfeat

# The GLB writer of the tests (the reader under test is independent of it).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
from gltf_builder import GltfBuilder, per_vertex_uvs  # noqa: E402
from uvfeat.animation.scene import trs_matrix  # noqa: E402


def quaternion(axis, angle: float) -> np.ndarray:
    return np.append(np.asarray(axis, dtype=float) * np.sin(angle / 2), np.cos(angle / 2))


def skinned_torus(path: str, n_joints: int = 8) -> str:
    """A 102,400-triangle torus on ``n_joints`` joints spaced around its ring; each vertex follows
    the two nearest joints, blended by angle, and each joint tilts by up to 20 degrees."""
    torus = uvfeat.shapes.torus(2.0, 0.5, 320, 160)
    mesh = uvfeat.Mesh(torus.positions, torus.faces, name="torus").with_atlas(method="xatlas")
    positions, faces, uvs = per_vertex_uvs(mesh)
    step = 2 * np.pi / n_joints
    slot = np.arctan2(positions[:, 1], positions[:, 0]) % (2 * np.pi) / step
    below = np.floor(slot).astype(int) % n_joints
    joints = np.zeros((len(positions), 4), dtype=int)
    joints[:, 0], joints[:, 1] = below, (below + 1) % n_joints
    weights = np.zeros((len(positions), 4))
    weights[:, 1] = slot - np.floor(slot)
    weights[:, 0] = 1 - weights[:, 1]
    b = GltfBuilder()
    rest, nodes, channels = [], [], []
    keys = np.linspace(0.0, 1.0, 5)
    for j in range(n_joints):
        angle = j * step
        turn = quaternion([0, 0, 1], angle)
        radial = [np.cos(angle), np.sin(angle), 0.0]
        nodes.append(b.node(root=True, translation=[2 * radial[0], 2 * radial[1], 0.0], rotation=turn.tolist()))
        rest.append(trs_matrix([2 * radial[0], 2 * radial[1], 0.0], turn, [1, 1, 1]))
        # local x is radial: tilting about it lifts the ring on one side, with a phase per joint
        tilt = np.radians(20) * np.sin(2 * np.pi * keys + angle)
        frames = [_multiply(turn, quaternion([1, 0, 0], a)) for a in tilt]
        channels.append((nodes[-1], "rotation", keys, frames, "LINEAR"))
    skin = b.skin(nodes, np.linalg.inv(np.stack(rest)))
    b.node(root=True, mesh=b.mesh([b.primitive(positions, faces, uvs, joints=joints, weights=weights)]), skin=skin)
    b.animation("wave", channels)
    return b.save(path)


def _multiply(q: np.ndarray, r: np.ndarray) -> np.ndarray:
    """Hamilton product of (x, y, z, w) quaternions: the rotation r, then q."""
    x1, y1, z1, w1 = q
    x2, y2, z2, w2 = r
    return np.array([w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2, w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
                     w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2, w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2])


def timed_ms(fn) -> float:
    started = time.perf_counter()
    fn()
    return 1e3 * (time.perf_counter() - started)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--mesh", default=None, help="an animated glTF/GLB file (default: the skinned torus)")
    parser.add_argument("--animation", default=None)
    parser.add_argument("--feature", default="mean_curvature")
    parser.add_argument("--radius", default="2%")
    parser.add_argument("--frames", type=int, default=8)
    parser.add_argument("--fps", type=float, default=24.0)
    args = parser.parse_args()

    load = os.getloadavg()
    folder = tempfile.mkdtemp()
    path = args.mesh or skinned_torus(os.path.join(folder, "skinned_torus.glb"))
    started = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        frames = uvfeat.animate(path, args.feature, args.radius, fps=args.fps, animation=args.animation)
    once_ms = 1e3 * (time.perf_counter() - started)
    pre_ms, raster_ms = (1e3 * frames.atlas.timings[k] for k in ("preprocessing_s", "rasterisation_s"))
    threads = os.environ.get("RAYON_NUM_THREADS", str(os.cpu_count()))
    mesh = frames.mesh
    print(f"{mesh.name}: {mesh.n_faces} faces, {mesh.n_vertices} vertices, {mesh.n_charts} charts; animation "
          f"{frames.animation_name!r}, {len(frames)} frames at {args.fps:g} fps; {threads} threads; {args.feature} "
          f"at r = {args.radius}")
    timings, cpu_ms = [], []
    for k in range(min(args.frames, len(frames))):
        cpu = time.process_time()
        timings.append(frames.frame(k).timings)
        cpu_ms.append(1e3 * (time.process_time() - cpu))
    median = {key: float(np.median([t[key] for t in timings])) for key in timings[0]}
    frames.atlas.update(mesh.positions)
    reference = timed_ms(lambda: frames.atlas.compute(args.feature, frames.radius))

    print(f"\nonce (uvfeat.animate: load, glTF, pre-processing, rasterisation)  {once_ms:9.1f} ms")
    print(f"  pre-processing (welding, charts, seams)   {pre_ms:9.1f} ms")
    print(f"  rasterisation + first buffers             {raster_ms:9.1f} ms")
    print(f"\nper frame, median of {len(timings)} frames")
    for key, label in (("positions_ms", "positions (skinning, morphs)"), ("update_ms", "buffers (Atlas.update)"),
                       ("features_ms", "features 512² x 256"), ("per_vertex_ms", "per-vertex lookup"),
                       ("total_ms", "total")):
        print(f"  {label:<40}  {median[key]:9.1f} ms")
    print(f"  {'CPU time, all threads':<40}  {np.median(cpu_ms):9.1f} ms")
    print(f"  {'features on the mesh at rest (reference)':<40}  {reference:9.1f} ms")
    print(f"load average before / after: {load[0]:.1f} / {os.getloadavg()[0]:.1f} (other processes slow wall times)")
    buffers_from_scratch = pre_ms + raster_ms
    print(f"\nbuffers per frame: {median['update_ms']:.1f} ms instead of {buffers_from_scratch:.1f} ms from scratch: "
          f"{100 * (1 - median['update_ms'] / buffers_from_scratch):.1f} % of the buffer pipeline is not repeated")
    one_shot = buffers_from_scratch + median["features_ms"] + median["per_vertex_ms"]
    print(f"per frame with reuse {median['total_ms']:.0f} ms vs {one_shot:.0f} ms for uvfeat.compute on every frame "
          f"({100 * (1 - median['total_ms'] / one_shot):.1f} % saved)")


if __name__ == "__main__":
    main()
