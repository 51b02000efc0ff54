"""The ``uvfeat`` command line: ``uvfeat atlas``, ``compute``, ``compare``, ``animate``, ``demo``.
Run ``uvfeat --help``."""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import sys
import time
import warnings

from . import __version__
from .errors import InvalidParameterError, UvfeatError


def _console():
    from rich.console import Console

    return Console(stderr=True)


@contextlib.contextmanager
def _steps(console, total: int):
    """A progress bar over named steps; yields ``advance(description)``."""
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    progress = Progress(TextColumn("{task.description:<28}"), BarColumn(), TextColumn("{task.completed}/{task.total}"),
                        TimeElapsedColumn(), console=console, transient=True, disable=not console.is_terminal)
    with progress:
        task = progress.add_task("starting", total=total)

        def advance(description: str, done: bool = True):
            progress.update(task, description=description, advance=1 if done else 0)

        yield advance


def _load(path: str, args):
    from .io import load

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mesh = load(path, uv=args.uv, resolution=args.resolution, normalize_uv=not args.strict_uv)
    return mesh, [str(w.message) for w in caught]


def _write_atlas(mesh, args, console, load_notes: list[str], started: float) -> dict:
    from .atlas import Atlas
    from .images import save_atlas_pictures

    os.makedirs(args.out, exist_ok=True)
    with _steps(console, 3) as advance:
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
        with open(os.path.join(args.out, "summary.json"), "w") as f:
            json.dump(summary, f, indent=2)
        advance("done")
    console.print(atlas.summary())
    for note in load_notes:
        console.print(f"[yellow]note:[/yellow] {note}")
    console.print(f"wrote {', '.join(sorted(pictures))} pictures and summary.json to {args.out}")
    return summary


def _on_file(writer):
    """A command that loads ``args.mesh`` and hands it to ``writer``."""

    def command(args) -> int:
        started = time.perf_counter()
        mesh, notes = _load(args.mesh, args)
        writer(mesh, args, _console(), notes, started)
        return 0

    return command


def _radius_tag(radius) -> str:
    return str(radius).strip().replace("%", "pct").replace(".", "p")


def _print_notes_and_outputs(console, notes: list[str], written: str, out: str) -> None:
    for note in notes:
        console.print(f"[yellow]note:[/yellow] {note}")
    console.print(f"wrote {written} to {out}")


def _direction_properties(directions) -> dict:
    """PLY vertex properties d1_x ... d2_z of ``(n_vertices, 2, 3)`` principal directions."""
    if directions is None:
        return {}
    return {f"d{k + 1}_{axis}": directions[:, k, a].astype("float32") for k in range(2) for a, axis in enumerate("xyz")}


def _write_features(mesh, args, console, load_notes: list[str], started: float) -> dict:
    """Computes the features at every radius and writes per-vertex files, maps and a summary."""
    import numpy as np
    import trimesh

    from .atlas import Atlas
    from .features import feature_names
    from .images import save_feature_figure, vertex_colours

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
    with _steps(console, 1 + 3 * len(radii)) as advance:
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
            tag = _radius_tag(radius)
            arrays = {f"{n}": v for n, v in per_vertex.items()}
            if args.method == "fit":
                arrays["principal_directions"] = first.per_vertex_directions()
            np.savez_compressed(os.path.join(args.out, f"per_vertex_r{tag}.npz"), positions=mesh.positions,
                                faces=mesh.faces, radius=first.radius, **arrays)
            ply = trimesh.Trimesh(mesh.positions, mesh.faces, process=False)
            for n, v in per_vertex.items():
                ply.vertex_attributes[n] = v.astype(np.float32)
            for n, v in _direction_properties(arrays.get("principal_directions")).items():
                ply.vertex_attributes[n] = v
            ply.visual.vertex_colors = vertex_colours(names[0], per_vertex[names[0]])
            ply.export(os.path.join(args.out, f"per_vertex_r{tag}.ply"))
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
        summary["timings_s"] = dict(timings, total=time.perf_counter() - started)
        with open(os.path.join(args.out, "summary.json"), "w") as f:
            json.dump(summary, f, indent=2, default=float)
    console.print(atlas.summary())
    for radius, info in summary["radii"].items():
        d = info["diagnostics"]
        console.print(f"r = {radius} ({info['radius']:.4g}): {info['features_s']:.2f} s, "
                      f"{d['mean_valid_samples']:.0f} samples/texel, {100 * d['missing_fraction']:.2f} % missing, "
                      f"{d['truncated_texels']} texels truncated by mesh borders")
    _print_notes_and_outputs(console, summary["warnings"], "per-vertex .ply/.npz, maps .npy/.png and summary.json",
                             args.out)
    return summary


def _write_comparison(mesh, args, console, load_notes: list[str], started: float) -> dict:
    """Runs both methods, prints the errors and timings (or JSON) and writes the pictures."""
    from .compare import compare, save_comparison_pictures

    with _steps(console, 2) as advance:
        advance("reference + parametric", done=False)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            result = compare(mesh, args.feature, args.radius, samples=args.samples, resolution=args.resolution,
                             compute_resolution=args.compute_resolution, gaussian_method=args.gaussian_method,
                             seed=args.seed, query=args.query, method=args.method, sampling=args.sampling)
        advance("pictures")
        summary = result.to_dict()
        summary["warnings"] = load_notes + sorted({str(w.message) for w in caught})
        if not args.no_pictures:
            pictures = save_comparison_pictures(result, args.out)
            summary["pictures"] = {k: os.path.basename(v) for k, v in pictures.items()}
        os.makedirs(args.out, exist_ok=True)
        with open(os.path.join(args.out, "compare.json"), "w") as f:
            json.dump(summary, f, indent=2, default=float)
    if args.json:
        print(json.dumps(summary, indent=2, default=float))
        return summary
    from rich.table import Table

    t = result.timings
    table = Table(title=f"{mesh.name}: r = {result.radius:.4g} ({args.radius})")
    for column in ("feature", "%AE", "mean-normalised", "compared vertices"):
        table.add_column(column, justify="left" if column == "feature" else "right")
    for name, e in result.errors.items():
        table.add_row(name, f"{e['percent_ae']:.3f}", f"{e['mean_normalised']:.4f}", str(e["compared"]))
    console.print(table)
    console.print(f"parametric {1e3 * t['parametric']:.0f} ms (buffers {1e3 * t['parametric_buffers']:.0f}, "
                  f"features {1e3 * t['parametric_features']:.0f}, per-vertex {1e3 * t['parametric_per_vertex']:.0f}); "
                  f"reference {1e3 * t['reference']:.0f} ms; speed-up {t['speedup']:.2f}x "
                  f"(untimed: pre-processing {1e3 * t['untimed_preprocessing']:.0f} ms, "
                  f"half-edges {1e3 * t['untimed_connectivity']:.0f} ms)")
    _print_notes_and_outputs(console, summary["warnings"], "compare.json" + ("" if args.no_pictures else " and pictures"),
                             args.out)
    return summary


def _cmd_demo(args) -> int:
    from .examples import spot_path

    console = _console()
    console.print(f"uvfeat {__version__} demo on the built-in Spot mesh (Keenan Crane, CC0)")
    started = time.perf_counter()
    args.uv, args.strict_uv, args.precision = "require", False, "f32"
    mesh, notes = _load(spot_path(), args)
    root = args.out
    args.out = os.path.join(root, "atlas")
    _write_atlas(mesh, args, console, notes, started)
    args.out = os.path.join(root, "features")
    args.feature, args.radius = "mean_curvature,gaussian_curvature,shape_index", "1%,4%,16%"
    args.samples, args.compute_resolution, args.adaptive, args.paper_mode = 256, args.compute_resolution, False, False
    args.seed, args.query, args.standard_error, args.method, args.directions = 0, "texture", False, "integral", None
    args.sampling = "fast"
    _write_features(mesh, args, console, [], time.perf_counter())
    return 0


def _add_atlas_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--resolution", type=int, default=1024, help="geometry-buffer size W_g in texels (default 1024)")
    parser.add_argument("--out", default="uvfeat-out", help="output folder (created if missing)")


def _feature_names():
    from .features import FEATURES

    return FEATURES


def _add_feature_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--samples", type=int, default=256, help="Monte Carlo samples per texel (default 256)")
    parser.add_argument("--compute-resolution", type=int, default=512, help="computation texture size (default 512)")
    parser.add_argument("--method", choices=("integral", "fit"), default="integral",
                        help="curvature estimators: integral invariants or the osculating-circle fit (adds principal "
                        "directions)")
    parser.add_argument("--sampling", choices=("fast", "exact"), default="fast",
                        help="sampler: the fast path (default) or the exact path it is checked against")


def _add_feature_command_options(parser: argparse.ArgumentParser, radius_note: str) -> None:
    """Arguments shared by the commands that compute features on a mesh file."""
    parser.add_argument("mesh", help="mesh file (obj, ply, glb, gltf, off, stl)")
    parser.add_argument("--feature", default="mean_curvature",
                        help="comma-separated names, or 'all' (" + ", ".join(_feature_names()) + ")")
    parser.add_argument("--radius", default="2%", help="radius in object units or %% of the bounding-box diagonal"
                        f"{radius_note} (default 2%%)")
    _add_atlas_options(parser)
    _add_feature_options(parser)
    parser.add_argument("--uv", choices=("auto", "require", "xatlas"), default="auto", help="as for `uvfeat atlas`")
    parser.add_argument("--strict-uv", action="store_true", help="fail on UVs outside [0, 1] instead of normalising")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--query", choices=("texture", "direct"), default="texture", help="per-vertex query")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="uvfeat", description="Multi-scale geometric features of triangle meshes, "
                                     "computed in UV parameter space.")
    parser.add_argument("--version", action="version", version=f"uvfeat {__version__}")
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    atlas = commands.add_parser("atlas", help="rasterise a mesh's UV atlas and write Figure-1 pictures",
                                description="Writes position.png, normal.png, charts.png, distortion.png and "
                                "summary.json (pictures with v up).")
    atlas.add_argument("mesh", help="mesh file (obj, ply, glb, gltf, off, stl)")
    _add_atlas_options(atlas)
    atlas.add_argument("--precision", choices=("f32", "f16"), default="f32", help="storage of positions/normals")
    atlas.add_argument("--uv", choices=("auto", "require", "xatlas"), default="auto",
                       help="auto: use the file's UVs, xatlas when there are none (default); require: fail "
                       "without UVs; xatlas: always build a new atlas")
    atlas.add_argument("--strict-uv", action="store_true", help="fail on UVs outside [0, 1] instead of normalising them")
    atlas.set_defaults(handler=_on_file(_write_atlas))

    compute = commands.add_parser("compute", help="compute features and write per-vertex values, maps and pictures",
                                  description="Writes per_vertex_r*.ply (vertex properties + colours) and .npz, "
                                  "FEATURE_r*.npy and .png maps (v up), and summary.json.")
    _add_feature_command_options(compute, "; comma-separated for several scales")
    compute.add_argument("--adaptive", action="store_true", help="two-stage adaptive sampling (DESIGN.md §1.8)")
    compute.add_argument("--paper-mode", action="store_true", help="the paper's choices, for reproduction")
    compute.add_argument("--directions", choices=("d1", "d2"), default=None,
                         help="draw this principal direction (d1 of k1, d2 of k2) as segments on the map pictures; "
                         "needs --method fit")
    compute.add_argument("--standard-error", action="store_true", help="also compute Monte Carlo standard errors")
    compute.set_defaults(handler=_on_file(_write_features))

    compare = commands.add_parser("compare", help="run the parametric method and the object-space reference "
                                  "side by side: errors, timings, pictures",
                                  description="Prints %%AE (DESIGN.md §5.1: mean |f - f_ref| over the Q1-Q99 range of "
                                  "f_ref) and the mean-normalised error per feature, the time of each method "
                                  "(parametric: buffers + features + per-vertex lookup; reference: without the "
                                  "half-edge construction) and the speed-up; writes compare_FEATURE.png "
                                  "(parametric | reference | difference), error_FEATURE.png and compare.json.")
    _add_feature_command_options(compare, "")
    compare.add_argument("--gaussian-method", choices=("moments", "geodesic_area", "exact_geodesic_area"),
                         default="moments", help="K of both sides; exact_geodesic_area: exact geodesics in the "
                         "reference, geodesic-area K on the parametric side")
    compare.add_argument("--no-pictures", action="store_true", help="errors and timings only")
    compare.add_argument("--json", action="store_true", help="print the summary as JSON on stdout")
    compare.set_defaults(handler=_on_file(_write_comparison), out="uvfeat-out/compare")

    from .animation.cli import add_command as add_animate_command

    add_animate_command(commands, _add_atlas_options, _add_feature_options)

    demo = commands.add_parser("demo", help="run on the built-in Spot mesh: atlas pictures and features at 3 radii")
    _add_atlas_options(demo)
    # 256² texels are ~11 per triangle of the 5,856-triangle Spot: the pictures stay sharp and the
    # three radii take ~20 s on 2 cores instead of ~80 s at 512² (16 % dominates).
    demo.add_argument("--compute-resolution", type=int, default=256,
                      help="computation texture size (default 256, enough for the 5,856-triangle Spot)")
    demo.set_defaults(handler=_cmd_demo)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    for option in ("resolution", "compute_resolution"):
        if getattr(args, option, 1) <= 0:
            _console().print(f"[red]error:[/red] --{option.replace('_', '-')} must be a positive integer, "
                             f"got {getattr(args, option)}")
            return 2
    try:
        return args.handler(args)
    except UvfeatError as exc:
        _console().print(f"[red]error:[/red] {exc}")
        return 2


if __name__ == "__main__":
    sys.exit(main())
