"""``uvfeat bake``: features written as textures on the mesh's UVs, GLB and PLY files that other
tools open (MeshLab, Blender, glTF viewers, texture painters)."""

from __future__ import annotations

from ..files.bake import write_bakes
from ..files.feature_files import FeatureJob
from .common import add_feature_command_options, on_file, print_notes_and_outputs, steps


def add_command(commands) -> None:
    parser = commands.add_parser("bake", help="bake features into textures (16-bit PNG, float TIFF, curvature map), "
                                 "GLB and PLY for other tools (needs uvfeat[bake])",
                                 description="Per feature and radius: FEATURE_rR.png (16-bit grey, range in the text "
                                 "chunks), .tif (float32), _curvature.png (8-bit, 128 = 0, signed features), "
                                 "_colour.png, _colours.glb (vertex colours) and _texture.glb (texture), all on the "
                                 "mesh's own UVs with dilated gutters; per radius per_vertex_rR.ply (quality = the first "
                                 "feature); bake.json.")
    add_feature_command_options(parser, "; comma-separated for several scales")
    parser.set_defaults(handler=on_file(bake_file), out="uvfeat-out/bake")


def bake_file(mesh, args, console, load_notes: list[str], started: float) -> dict:
    job = FeatureJob.from_args(args, pictures=False)
    with steps(console, 1 + 2 * len(job.radii)) as advance:
        summary = write_bakes(mesh, job, args.out, load_notes, advance)
    print_notes_and_outputs(console, summary["warnings"], "textures (.png 16-bit, .tif float, curvature and colour "
                            ".png), .glb, .ply and bake.json", args.out)
    return summary
