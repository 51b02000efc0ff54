"""``uvfeat compute``: features at one or several radii, written as per-vertex files, maps and
pictures."""

from __future__ import annotations

import os
import time
import warnings

from .._core import __version__
from ..errors import InvalidParameterError
from ..writers import write_json, write_per_vertex
from .common import add_feature_command_options, on_file, print_notes_and_outputs, radius_tag, steps


def add_command(commands) -> None:
    parser = commands.add_parser("compute", help="compute features and write per-vertex values, maps and pictures",
                                 description="Writes per_vertex_r*.ply (vertex properties + colours) and .npz, "
                                 "FEATURE_r*.npy and .png maps (v up), FEATURE_3d.png (the mesh coloured by the "
                                 "feature from three views, one column per radius) and summary.json.")
    add_feature_command_options(parser, "; comma-separated for several scales")
    parser.add_argument("--adaptive", action="store_true", help="two-stage adaptive sampling (DESIGN.md §1.8)")
    parser.add_argument("--paper-mode", action="store_true", help="the paper's choices, for reproduction")
    parser.add_argument("--directions", choices=("d1", "d2"), default=None,
                        help="draw this principal direction (d1 of k1, d2 of k2) as segments on the map pictures; "
                        "needs --method fit")
    parser.add_argument("--standard-error", action="store_true", help="also compute Monte Carlo standard errors")
    parser.set_defaults(handler=on_file(write_features))


def write_features(mesh, args, console, load_notes: list[str], started: float) -> dict:
    """Computes the features at every radius and writes per-vertex files, maps and a summary."""
    import numpy as np

    from ..atlas import Atlas
    from ..options import feature_names
    from ..images import save_feature_figure
    from ..surface_plot import save_plot

    names = feature_names(args.feature)
    radii = [r.strip() for r in args.radius.split(",") if r.strip()]
    if args.directions and args.method != "fit":
        raise InvalidParameterError("--directions needs --method fit (principal directions come from the fit)")
    os.makedirs(args.out, exist_ok=True)
    options = {"query": args.query, "standard_error": args.standard_error, "method": args.method,
               "sampling": args.sampling}
    summary = {"uvfeat": __version__, "mesh": mesh.name, "warnings": list(load_notes), "radii": {},
               "settings": {"features": names, "radii": radii, "samples": args.samples, "resolution": args.resolution,
                            "compute_resolution": args.compute_resolution, "adaptive": args.adaptive,
                            "paper_mode": args.paper_mode, "seed": args.seed, "query": args.query,
                            "method": args.method, "sampling": args.sampling}}
    on_mesh = {name: [] for name in names}
    with steps(console, 2 + 3 * len(radii)) as advance:
        advance("pre-processing + rasterising", done=False)
        atlas = Atlas(mesh, resolution=args.resolution, precision="f16" if args.paper_mode else "f32")
        summary["diagnostics"] = atlas.diagnostics
        summary["warnings"] += atlas.warnings()
        timings = dict(atlas.timings)
        advance("buffers ready")
        for radius in radii:
            advance(f"features at r = {radius}", done=False)
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                maps = atlas.compute(names, radius, samples=args.samples, compute_resolution=args.compute_resolution,
                                     adaptive=args.adaptive, seed=args.seed, paper_mode=args.paper_mode, **options)
            summary["warnings"] += sorted({str(w.message) for w in caught})
            first = next(iter(maps.values()))
            advance(f"per-vertex values at r = {radius}")
            started_pv = time.perf_counter()
            per_vertex = {name: m.per_vertex() for name, m in maps.items()}
            for name, values in per_vertex.items():
                on_mesh[name].append(values)
            tag = radius_tag(radius)
            directions = first.per_vertex_directions() if args.method == "fit" else None
            write_per_vertex(args.out, tag, mesh, first.radius, per_vertex, directions)
            time_pv = time.perf_counter() - started_pv
            advance(f"pictures at r = {radius}")
            line_field = first.uv_principal_directions()[:, :, ["d1", "d2"].index(args.directions)] \
                if args.directions else None
            for n, m in maps.items():
                np.save(os.path.join(args.out, f"{n}_r{tag}.npy"), m.texture)
                save_feature_figure(os.path.join(args.out, f"{n}_r{tag}.png"), n, m.texture, m.radius, mesh.name,
                                    line_field=line_field)
            summary["radii"][radius] = {
                "radius": first.radius,
                "features_s": first.settings["features_s"][0],
                "per_vertex_s": time_pv,
                "diagnostics": first.summary,
                "per_vertex_range": {n: [float(np.nanmin(v)), float(np.nanmax(v))] for n, v in per_vertex.items()},
            }
        advance("3D pictures")
        started_3d = time.perf_counter()
        for name, rows in on_mesh.items():
            save_plot(os.path.join(args.out, f"{name}_3d.png"), mesh, np.stack(rows), feature=name, radius=radii)
        timings["pictures_3d_s"] = time.perf_counter() - started_3d
        summary["timings_s"] = dict(timings, total=time.perf_counter() - started)
        write_json(os.path.join(args.out, "summary.json"), summary)
    console.print(atlas.summary())
    for radius, info in summary["radii"].items():
        d = info["diagnostics"]
        console.print(f"r = {radius} ({info['radius']:.4g}): {info['features_s']:.2f} s, "
                      f"{d['mean_valid_samples']:.0f} samples/texel, {100 * d['missing_fraction']:.2f} % missing, "
                      f"{d['truncated_texels']} texels truncated by mesh borders")
    print_notes_and_outputs(console, summary["warnings"], "per-vertex .ply/.npz, maps .npy/.png, 3D pictures *_3d.png and summary.json",
                            args.out)
    return summary
