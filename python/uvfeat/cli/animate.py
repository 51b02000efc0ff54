"""``uvfeat animate``: features of every frame of an animation, written as per-frame files and an
animated GIF of each feature map."""

from __future__ import annotations

import os
import time

import numpy as np

from .._core import __version__
from ..animation.frame_rate import DEFAULT_FPS
from ..errors import InvalidParameterError
from ..options import ARGUMENT_DEFAULTS, DEFAULT_OPTIONS, maps_samples
from ..pictures.surface_plot import VIEWS
from ..unwrap import UV_POLICIES
from ..files.writers import write_json
from .common import add_atlas_options, add_cluster_options, add_feature_options, console, print_dashboard, throughput


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
    parser.add_argument("--uv", choices=UV_POLICIES, default="auto", help="as for `uvfeat atlas`")
    parser.add_argument("--seed", type=int, default=ARGUMENT_DEFAULTS["seed"], help="sample-pattern seed, the same for every frame")
    add_cluster_options(parser)
    parser.add_argument("--frames-per-task", type=int, metavar="N", help="with --scheduler/--workers: frames per "
                        "task, each building the atlas once (default: two tasks per worker thread)")
    parser.add_argument("--view", choices=sorted(VIEWS), default="three_quarter",
                        help="camera of the 3D pictures, framed on the first frame (default %(default)s)")
    parser.set_defaults(handler=run)


def run(args) -> int:
    from ..animation.frame_files import open_animation, write_frames, write_pictures

    out, started = console(), time.perf_counter()
    if "," in args.radius:
        raise InvalidParameterError(f"uvfeat animate takes one radius, got {args.radius!r}")
    # Every frame's maps: the per-vertex default of many charts does not apply.
    quadrature = args.quadrature or DEFAULT_OPTIONS["quadrature"]
    surface = args.surface or DEFAULT_OPTIONS["surface"]
    options = dict(frames=args.frames, fps=args.fps, animation=args.animation, resolution=args.resolution, uv=args.uv,
                   samples=maps_samples(args.samples), compute_resolution=args.compute_resolution, seed=args.seed,
                   method=args.method, sampling=args.sampling, quadrature=quadrature, surface=surface)
    frames, notes = open_animation(args.mesh, args.feature, args.radius, **options)
    notes += frames.atlas.warnings()
    total = len(frames) if args.max_frames is None else max(0, min(len(frames), args.max_frames))
    with throughput(out, f"{frames.mesh.name}: {', '.join(frames.features)}", total, "frames/s") as advance:
        if args.scheduler or args.workers is not None or args.frames_per_task is not None:
            from ..batch.frames import animate_on_cluster

            # Workers may run elsewhere, in another folder: they get absolute paths
            options["frames"] = [os.path.abspath(f) for f in args.frames] if args.frames else None
            per_frame, task_notes = animate_on_cluster(
                os.path.abspath(args.mesh), frames.features, args.radius, options, os.path.abspath(args.out), total,
                scheduler=args.scheduler,
                workers=args.workers, frames_per_task=args.frames_per_task,
                on_start=lambda client: print_dashboard(out, client), on_frames=advance)
            notes = sorted(set(notes) | set(task_notes))
        else:
            per_frame = write_frames(frames, args.out, 0, total, on_frame=lambda frame: advance())
    os.makedirs(args.out, exist_ok=True)
    ranges, picture_notes = write_pictures(args.out, frames.features, total, args.fps, frames.mesh.faces, args.view)
    notes += picture_notes
    mean_ms = {key: float(np.mean([f[key] for f in per_frame])) for key in per_frame[0] if key.endswith("_ms")} \
        if per_frame else {}
    summary = {
        "uvfeat": __version__, "mesh": frames.mesh.name, "animation": frames.animation_name, "frames": total,
        "settings": {"features": frames.features, "radius": frames.radius, "fps": args.fps, "samples": options["samples"],
                     "resolution": args.resolution, "compute_resolution": args.compute_resolution, "seed": args.seed,
                     "method": args.method, "sampling": args.sampling, "quadrature": quadrature,
                     "surface": surface},
        "colour_ranges": ranges, "warnings": notes, "diagnostics": frames.atlas.diagnostics,
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
