"""Files ``uvfeat animate`` writes: per frame ``frame_NNNN.npz`` (time, positions, per-vertex
features) and ``FEATURE_NNNN.npy`` maps, written by whichever process computes the frame; then,
once every frame is on disk, the pictures (``FEATURE_NNNN.png``, ``FEATURE.gif``, and the mesh
coloured by the feature from one still camera, ``FEATURE_3d.gif`` and ``FEATURE_3d.mp4``) in one
colour range taken from the first frame, so frames computed apart still compare."""

from __future__ import annotations

import os

import numpy as np

from ..io import atomic_file
from ..files.notes import recorded_notes
from .animate import Animation, animate


def open_animation(mesh: str, features, radius, frames: list[str] | None = None, **options):
    """:func:`uvfeat.animate` on the command line's arguments (``frames``: one ``.npy`` array or
    mesh files), and the warnings it gave as notes."""
    if frames and len(frames) == 1 and frames[0].endswith(".npy"):
        frames = np.load(frames[0])
    with recorded_notes() as notes:
        animation = animate(mesh, features, radius, frames=frames, **options)
    return animation, notes


def map_path(out: str, name: str, index: int, extension: str) -> str:
    return os.path.join(out, f"{name}_{index:04d}.{extension}")


def write_frames(animation: Animation, out: str, start: int, stop: int, on_frame=lambda frame: None) -> list[dict]:
    """Computes frames ``start`` to ``stop - 1`` and writes their files; returns each frame's
    index, time and timings."""
    os.makedirs(out, exist_ok=True)
    rows = []
    for frame in (animation.frame(k) for k in range(start, stop)):
        with atomic_file(os.path.join(out, f"frame_{frame.index:04d}.npz")) as path:
            np.savez_compressed(path, time=frame.time, positions=frame.positions, **frame.values)
        for name, feature in frame.maps.items():
            with atomic_file(map_path(out, name, frame.index, "npy")) as path:
                np.save(path, feature.texture)
        rows.append(dict(index=frame.index, time=frame.time, **frame.timings))
        on_frame(frame)
    return rows


def animate_frames(mesh: str, features, radius, options: dict, out: str, start: int, stop: int) -> dict:
    """One task of an animation on a cluster: the atlas built once, then frames ``start`` to
    ``stop - 1`` written; returns their rows and the notes."""
    animation, notes = open_animation(mesh, features, radius, **options)
    return {"frames": write_frames(animation, out, start, stop), "notes": notes + animation.atlas.warnings()}


def write_pictures(out: str, features: list[str], n_frames: int, fps: float, faces: np.ndarray,
                   view: str = "three_quarter") -> tuple[dict[str, list[float]], list[str]]:
    """``FEATURE_NNNN.png``, ``FEATURE.gif`` and the 3D views ``FEATURE_3d.gif``/``.mp4`` (camera
    framed on the first frame) from the written files; returns each feature's colour range (that
    of the first frame) and notes (an MP4 that could not be written)."""
    from PIL import Image

    from ..errors import MissingDependencyError
    from ..pictures.images import colour_range, feature_picture, save_gif, save_mp4
    from ..pictures.surface_plot import FixedCamera

    ranges, notes, camera = {}, [], None
    for name in features:
        pictures, views = [], []
        for k in range(n_frames):
            texture = np.load(map_path(out, name, k, "npy"))
            with np.load(os.path.join(out, f"frame_{k:04d}.npz")) as frame:
                positions, values = frame["positions"], frame[name]
            if name not in ranges:
                ranges[name] = list(colour_range(name, texture))
            camera = camera or FixedCamera.framing(positions, view)
            pictures.append(feature_picture(name, texture, *ranges[name][1:]))
            Image.fromarray(pictures[-1]).save(map_path(out, name, k, "png"))
            views.append(camera.picture(positions, faces, values, *ranges[name]))
        if pictures:
            save_gif(os.path.join(out, f"{name}.gif"), pictures, fps)
            save_gif(os.path.join(out, f"{name}_3d.gif"), views, fps)
            try:
                save_mp4(os.path.join(out, f"{name}_3d.mp4"), views, fps)
            except MissingDependencyError as missing:
                notes.append(f"no MP4 written: {missing}")
    return {name: r[1:] for name, r in ranges.items()}, notes
