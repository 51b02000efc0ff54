"""``uvfeat compute``: features at one or several radii, written as per-vertex files, maps and
pictures."""

from __future__ import annotations

import contextlib
import threading

from ..files.feature_files import FeatureJob, write_feature_files
from .common import add_computation_options, add_feature_command_options, on_file, print_notes_and_outputs, steps


def add_command(commands) -> None:
    parser = commands.add_parser("compute", help="compute features and write per-vertex values, maps and pictures",
                                 description="Writes per_vertex_r*.ply (vertex properties + colours) and .npz, "
                                 "FEATURE_r*.npy and .png maps (v up), FEATURE_3d.png (the mesh coloured by the "
                                 "feature from three views, one column per radius) and summary.json.")
    add_feature_command_options(parser, "; comma-separated for several scales")
    add_computation_options(parser)
    parser.set_defaults(handler=on_file(write_features))


def import_picture_modules() -> None:
    """Imports what the pictures draw with (see :func:`picture_modules_loading`)."""
    try:
        from matplotlib import figure  # noqa: F401
        from matplotlib.backends import backend_agg  # noqa: F401
    except ImportError:
        pass  # the pictures' own import says what is missing


@contextlib.contextmanager
def picture_modules_loading(pictures: bool):
    """Imports matplotlib's figure and Agg canvas on a thread while the block runs, when it will
    draw pictures: the atlas and the features run in Rust without the GIL, so the import (0.7 s
    on the development machine, most of it matplotlib setting up its artists' docstrings)
    overlaps them. The thread is joined when the block ends, so none outlives the command (a
    process forked while a thread holds an import lock hangs in its next import); the main
    thread's own imports of these modules wait for it, holding no import lock of their own."""
    if not pictures:
        yield
        return
    thread = threading.Thread(target=import_picture_modules, name="uvfeat-import-matplotlib", daemon=True)
    thread.start()
    try:
        yield
    finally:
        thread.join()


def write_features(mesh, args, console, load_notes: list[str], started: float, explain=None) -> dict:
    """Computes the features at every radius and writes per-vertex files, maps and a summary. The
    notes are printed as they are, or as the lines ``explain(notes)`` gives (summary.json keeps
    them all)."""
    job = FeatureJob.from_args(args)
    with steps(console, 2 + 2 * len(job.radii)) as advance, picture_modules_loading(job.pictures):
        atlas, summary = write_feature_files(mesh, job, args.out, load_notes, started, advance)
    console.print(atlas.summary())
    for radius, info in summary["radii"].items():
        d = info["diagnostics"]
        if "maps" in d:  # the values at the vertices, the maps interpolated from them
            described = f"values at the vertices, {info['flagged_vertices']['truncated']} truncated by mesh borders"
        else:
            described = (f"{d['mean_valid_samples']:.0f} samples/texel, {100 * d['missing_fraction']:.2f} % missing, "
                         f"{d['truncated_texels']} texels truncated by mesh borders")
        console.print(f"r = {radius} ({info['radius']:.4g}): {info['features_s']:.2f} s, {described}")
    notes = summary["warnings"] if explain is None else explain(summary["warnings"])
    print_notes_and_outputs(console, notes, "per-vertex .ply/.npz, maps .npy/.png, 3D pictures *_3d.png and summary.json",
                            args.out)
    return summary
