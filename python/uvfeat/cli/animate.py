"""``uvfeat animate``: features of every frame of an animation, written as per-frame files and an
animated GIF of each feature map."""

from __future__ import annotations

import os
import time
import warnings

import numpy as np

from .._core import __version__
from ..animation.frame_rate import DEFAULT_FPS
from ..errors import InvalidParameterError, MissingDependencyError
from ..options import ARGUMENT_DEFAULTS
from ..surface_plot import VIEWS, FixedCamera
from ..writers import write_json
from .common import add_atlas_options, add_feature_options, console


def add_command(commands) -> None:
    parser = commands.add_parser(
        "animate", help="features of every frame of an animation (glTF skins/morphs, mesh files or a .npy array)",
        description="Writes frame_NNNN.npz (time, positions, per-vertex features), FEATURE_NNNN.npy and .png maps "
        "(v up, one colour range for all frames), FEATURE.gif (the maps), FEATURE_3d.gif and FEATURE_3d.mp4 (the mesh "
        "coloured by the feature, one still camera) and summary.json (timings per frame).")
    parser.add_argument("mesh", help="mesh file; a glTF/GLB file plays its own animation unless --frames is given")
    parser.add_argument("--frames", nargs="+", metavar="FILE", help="frames: one .npy array (n_frames, V, 3) or "
                        "mesh files with the mesh's vertices and faces, in order")
    parser.add_argument("--animation", help="glTF animation to play, by name or index (default: the first)")
    parser.add_argument("--fps", type=float, default=DEFAULT_FPS, help="frames per second (default %(default)s)")
    parser.add_argument("--max-frames", type=int, default=None, help="stop after this many frames")
    parser.add_argument("--feature", default="mean_curvature", help="comma-separated feature names, or 'all'")
    parser.add_argument("--radius", default="2%", help="one radius, in object units or %% of the bounding-box "
                        "diagonal of the mesh as loaded (default 2%%)")
    add_atlas_options(parser)
    add_feature_options(parser)
    parser.add_argument("--uv", choices=("auto", "require", "xatlas"), default="auto", help="as for `uvfeat atlas`")
    parser.add_argument("--seed", type=int, default=ARGUMENT_DEFAULTS["seed"], help="sample-pattern seed, the same for every frame")
    parser.add_argument("--view", choices=sorted(VIEWS), default="three_quarter",
                        help="camera of the 3D pictures, framed on the first frame (default %(default)s)")
    parser.set_defaults(handler=run)


def _frames_argument(frames: list[str] | None):
    if frames and len(frames) == 1 and frames[0].endswith(".npy"):
        return np.load(frames[0])
    return frames


def _progress(out):
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn

    return Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                    TextColumn("{task.fields[rate]:.2f} frames/s"), TimeElapsedColumn(), TimeRemainingColumn(),
                    console=out, transient=True, disable=not out.is_terminal)


def run(args) -> int:
    from PIL import Image

    from ..animation.animate import animate
    from ..images import colour_range, feature_picture, save_gif, save_mp4

    out, started = console(), time.perf_counter()
    if "," in args.radius:
        raise InvalidParameterError(f"uvfeat animate takes one radius, got {args.radius!r}")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        frames = animate(args.mesh, args.feature, args.radius, frames=_frames_argument(args.frames), fps=args.fps,
                         animation=args.animation, resolution=args.resolution, uv=args.uv, samples=args.samples,
                         compute_resolution=args.compute_resolution, seed=args.seed,
                         method=args.method, sampling=args.sampling)
    notes = sorted({str(w.message) for w in caught}) + frames.atlas.warnings()
    total = len(frames) if args.max_frames is None else max(0, min(len(frames), args.max_frames))
    os.makedirs(args.out, exist_ok=True)
    colours, pictures, per_frame = {}, {name: [] for name in frames.features}, []
    views, camera = {name: [] for name in frames.features}, None
    with _progress(out) as progress:
        task = progress.add_task(f"{frames.mesh.name}: {', '.join(frames.features)}", total=total, rate=0.0)
        playing = time.perf_counter()
        for frame in (frames.frame(k) for k in range(total)):
            np.savez_compressed(os.path.join(args.out, f"frame_{frame.index:04d}.npz"), time=frame.time,
                                positions=frame.positions, **frame.values)
            camera = camera or FixedCamera.framing(frame.positions, args.view)
            for name, feature in frame.maps.items():
                if name not in colours:  # the first frame fixes the colours, so frames compare
                    colours[name] = colour_range(name, feature.texture)
                views[name].append(camera.picture(frame.positions, frames.mesh.faces, frame.values[name],
                                                  *colours[name]))
                np.save(os.path.join(args.out, f"{name}_{frame.index:04d}.npy"), feature.texture)
                picture = feature_picture(name, feature.texture, *colours[name][1:])
                Image.fromarray(picture).save(os.path.join(args.out, f"{name}_{frame.index:04d}.png"))
                pictures[name].append(picture)
            per_frame.append(dict(index=frame.index, time=frame.time, **frame.timings))
            progress.update(task, advance=1, rate=(frame.index + 1) / (time.perf_counter() - playing))
    for name, frame_pictures in pictures.items():
        if frame_pictures:
            save_gif(os.path.join(args.out, f"{name}.gif"), frame_pictures, args.fps)
            save_gif(os.path.join(args.out, f"{name}_3d.gif"), views[name], args.fps)
            try:
                save_mp4(os.path.join(args.out, f"{name}_3d.mp4"), views[name], args.fps)
            except MissingDependencyError as missing:
                notes.append(f"no MP4 written: {missing}")
    mean_ms = {key: float(np.mean([f[key] for f in per_frame])) for key in per_frame[0] if key.endswith("_ms")} \
        if per_frame else {}
    summary = {
        "uvfeat": __version__, "mesh": frames.mesh.name, "animation": frames.animation_name, "frames": total,
        "settings": {"features": frames.features, "radius": frames.radius, "fps": args.fps, "samples": args.samples,
                     "resolution": args.resolution, "compute_resolution": args.compute_resolution, "seed": args.seed,
                     "method": args.method, "sampling": args.sampling},
        "colour_ranges": {name: c[1:] for name, c in colours.items()}, "warnings": notes, "diagnostics": frames.atlas.diagnostics,
        "timings": {"once_s": frames.atlas.timings, "mean_per_frame_ms": mean_ms, "per_frame": per_frame,
                    "total_s": time.perf_counter() - started},
    }
    write_json(os.path.join(args.out, "summary.json"), summary)
    what = f"animation {frames.animation_name!r} of " if frames.animation_name else ""
    out.print(f"{what}{frames.mesh.name}: {total} frames, {mean_ms.get('total_ms', 0.0):.0f} ms per frame "
                  f"(buffers {mean_ms.get('update_ms', 0.0):.0f} ms, features {mean_ms.get('features_ms', 0.0):.0f} ms)")
    for note in notes:
        out.print(f"[yellow]note:[/yellow] {note}")
    out.print(f"wrote frame_*.npz, per-frame maps .npy/.png, {', '.join(f + '.gif' for f in frames.features)}, "
              f"3D views {', '.join(f + '_3d.gif/.mp4' for f in frames.features)} and summary.json to {args.out}")
    return 0
