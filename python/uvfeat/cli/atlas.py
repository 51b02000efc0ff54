"""``uvfeat atlas``: rasterise a mesh's UV atlas and write the buffers as pictures."""

from __future__ import annotations

import os
import time

from .._core import __version__
from ..options import CHOICES
from ..files.writers import write_json
from .common import MESH_HELP, add_atlas_options, add_uv_options, on_file, steps


def add_command(commands) -> None:
    parser = commands.add_parser("atlas", help="rasterise a mesh's UV atlas and write Figure-1 pictures",
                                 description="Writes position.png, normal.png, charts.png, distortion.png and "
                                 "summary.json (pictures with v up).")
    parser.add_argument("mesh", help=MESH_HELP)
    add_atlas_options(parser)
    parser.add_argument("--precision", choices=CHOICES["precision"], default=CHOICES["precision"][0],
                        help="storage of positions/normals (default %(default)s)")
    add_uv_options(parser)
    parser.set_defaults(handler=on_file(write_atlas))


def write_atlas(mesh, args, console, load_notes: list[str], started: float) -> dict:
    """Builds the atlas and writes its pictures and ``summary.json`` to ``args.out``."""
    from ..atlas import Atlas
    from ..pictures.images import save_atlas_pictures

    os.makedirs(args.out, exist_ok=True)
    with steps(console, 3) as advance:
        advance("pre-processing + rasterising", done=False)
        atlas = Atlas(mesh, resolution=args.resolution, precision=args.precision)
        advance("writing pictures")
        pictures = save_atlas_pictures(atlas, args.out)
        advance("writing summary")
        summary = {
            "uvfeat": __version__,
            "mesh": mesh.name,
            "settings": {"resolution": args.resolution, "precision": args.precision, "uv": args.uv},
            "diagnostics": atlas.diagnostics,
            "warnings": load_notes + atlas.warnings(),
            "timings_s": dict(atlas.timings, total=time.perf_counter() - started),
            "pictures": {k: os.path.basename(v) for k, v in pictures.items()},
        }
        write_json(os.path.join(args.out, "summary.json"), summary)
        advance("done")
    console.print(atlas.summary())
    for note in load_notes:
        console.print(f"[yellow]note:[/yellow] {note}")
    console.print(f"wrote {', '.join(sorted(pictures))} pictures and summary.json to {args.out}")
    return summary
