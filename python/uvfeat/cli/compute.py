"""``uvfeat compute``: features at one or several radii, written as per-vertex files, maps and
pictures."""

from __future__ import annotations

from ..feature_files import FeatureJob, write_feature_files
from .common import add_computation_options, add_feature_command_options, on_file, print_notes_and_outputs, steps


def add_command(commands) -> None:
    parser = commands.add_parser("compute", help="compute features and write per-vertex values, maps and pictures",
                                 description="Writes per_vertex_r*.ply (vertex properties + colours) and .npz, "
                                 "FEATURE_r*.npy and .png maps (v up), FEATURE_3d.png (the mesh coloured by the "
                                 "feature from three views, one column per radius) and summary.json.")
    add_feature_command_options(parser, "; comma-separated for several scales")
    add_computation_options(parser)
    parser.set_defaults(handler=on_file(write_features))


def write_features(mesh, args, console, load_notes: list[str], started: float) -> dict:
    """Computes the features at every radius and writes per-vertex files, maps and a summary."""
    job = FeatureJob.from_args(args)
    with steps(console, 2 + 2 * len(job.radii)) as advance:
        atlas, summary = write_feature_files(mesh, job, args.out, load_notes, started, advance)
    console.print(atlas.summary())
    for radius, info in summary["radii"].items():
        d = info["diagnostics"]
        console.print(f"r = {radius} ({info['radius']:.4g}): {info['features_s']:.2f} s, "
                      f"{d['mean_valid_samples']:.0f} samples/texel, {100 * d['missing_fraction']:.2f} % missing, "
                      f"{d['truncated_texels']} texels truncated by mesh borders")
    print_notes_and_outputs(console, summary["warnings"], "per-vertex .ply/.npz, maps .npy/.png, 3D pictures *_3d.png and summary.json",
                            args.out)
    return summary
