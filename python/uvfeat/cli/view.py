"""``uvfeat view``: the interactive viewer (polyscope, ``pip install 'uvfeat[view]'``) on a mesh
file, with the features computed at the given radii; ``--screenshot`` renders it headless."""

from __future__ import annotations

from .common import add_feature_command_options, on_file, steps


def add_command(commands) -> None:
    parser = commands.add_parser("view", help="interactive viewer: the mesh coloured by a feature, a radius slider, "
                                 "the UV map beside it (needs uvfeat[view])",
                                 description="Computes the features at every radius, then opens the viewer: feature "
                                 "selector, radius slider and 'compute another radius', colour range, principal "
                                 "directions after --method fit, the UV map with the picked point, the value under the "
                                 "cursor. --screenshot writes a picture without a display (EGL) instead.")
    add_feature_command_options(parser, "; comma-separated for the slider's stops")
    parser.add_argument("--screenshot", metavar="PNG", help="render headless (EGL) to this file and exit")
    parser.set_defaults(handler=on_file(open_viewer), radius="1%,4%,16%")


def open_viewer(mesh, args, console, load_notes: list[str], started: float) -> None:
    from PIL import Image

    from ..atlas import Atlas
    from ..extras import require
    from ..files.feature_files import FeatureJob
    from ..pictures.viewer import HEADLESS, view

    require("polyscope", "the viewer")  # before minutes of computing, not after
    job = FeatureJob.from_args(args, pictures=False)
    radii, options = list(job.radii), job.compute_options()
    with steps(console, 2) as advance:
        advance("pre-processing + rasterising", done=False)
        atlas = Atlas(mesh, resolution=job.resolution)
        advance(f"features at r = {', '.join(radii)}")
        maps = atlas.compute(list(job.features), radii, **options)
    for note in load_notes + atlas.warnings():
        console.print(f"[yellow]note:[/yellow] {note}")
    viewer = view(mesh, maps, radius=radii, atlas=atlas, compute_options=options,
                  backend=HEADLESS if args.screenshot else "auto", show=not args.screenshot)
    if args.screenshot:
        Image.fromarray(viewer.screenshot()).save(args.screenshot)
        viewer.close()
        console.print(f"wrote {args.screenshot} ({viewer.title})")
