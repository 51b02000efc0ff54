"""``uvfeat bake``: features written as textures on the mesh's UVs, GLB and PLY files that other
tools open (MeshLab, Blender, glTF viewers, texture painters)."""

from __future__ import annotations

import os

from .._core import __version__
from ..extras import require
from ..feature_files import FeatureJob, computed_radii, radius_tag
from ..writers import write_json, write_per_vertex
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
    parser.set_defaults(handler=on_file(write_bakes), out="uvfeat-out/bake")


def write_bakes(mesh, args, console, load_notes: list[str], started: float) -> dict:
    from ..atlas import Atlas
    from ..bake import bake_feature

    require("scipy.ndimage", "dilating texture gutters")  # before minutes of computing, not after
    require("tifffile", "writing float TIFF")
    job = FeatureJob.from_args(args, pictures=False)
    os.makedirs(args.out, exist_ok=True)
    summary = {"uvfeat": __version__, "mesh": mesh.name, "warnings": list(load_notes), "radii": {},
               "settings": {"features": list(job.features), "radii": list(job.radii), "samples": job.samples,
                            "resolution": job.resolution, "compute_resolution": job.compute_resolution,
                            "method": job.method, "seed": job.seed}}
    with steps(console, 1 + 2 * len(job.radii)) as advance:
        advance("pre-processing + rasterising", done=False)
        atlas = Atlas(mesh, resolution=job.resolution)
        summary["warnings"] += atlas.warnings()
        advance("buffers ready")
        for computed in computed_radii(atlas, job, advance):
            summary["warnings"] += computed.notes
            advance(f"bakes at r = {computed.radius}", done=False)
            tag = radius_tag(computed.radius)
            files = {name: {kind: os.path.basename(path) for kind, path in
                            bake_feature(args.out, f"{name}_r{tag}", atlas.mesh, name, m.texture,
                                         computed.per_vertex[name], m.radius, m.corner_values()).items()}
                     for name, m in computed.maps.items()}
            first = next(iter(computed.maps.values()))
            write_per_vertex(args.out, tag, atlas.mesh, first.radius, computed.per_vertex)
            summary["radii"][computed.radius] = {"radius": first.radius, "files": files, "ply": f"per_vertex_r{tag}.ply"}
            advance(f"bakes at r = {computed.radius} written")
        write_json(os.path.join(args.out, "bake.json"), summary)
    print_notes_and_outputs(console, summary["warnings"], "textures (.png 16-bit, .tif float, curvature and colour "
                            ".png), .glb, .ply and bake.json", args.out)
    return summary
