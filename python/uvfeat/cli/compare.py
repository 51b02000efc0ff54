"""``uvfeat compare``: the parametric method beside the object-space reference on one mesh:
errors, timings and pictures."""

from __future__ import annotations

import json
import os

from ..files.notes import recorded_notes
from ..files.writers import write_json
from .common import add_feature_command_options, on_file, print_notes_and_outputs, steps


def add_command(commands) -> None:
    parser = commands.add_parser("compare", help="run the parametric method and the object-space reference "
                                 "side by side: errors, timings, pictures",
                                 description="Prints %%AE (DESIGN.md §5.1: mean |f - f_ref| over the Q1-Q99 range "
                                 "of f_ref, f_ref the converged reference) and the mean-normalised error per feature "
                                 "(of the reference itself too), the time of each method "
                                 "(parametric: buffers + features + per-vertex lookup; reference: without the "
                                 "half-edge construction) and the speed-up; writes compare_FEATURE.png "
                                 "(parametric | reference | difference), error_FEATURE.png and compare.json.")
    add_feature_command_options(parser, "")
    parser.add_argument("--gaussian-method", choices=("moments", "geodesic_area", "exact_geodesic_area"),
                        default="moments", help="K of both sides; exact_geodesic_area: exact geodesics in the "
                        "reference, geodesic-area K on the parametric side")
    parser.add_argument("--truth-levels", type=int, default=2, metavar="N",
                        help="measure both methods against the reference of the surface refined until it converges, "
                        "up to N midpoint subdivisions (default 2; 0: the reference itself is the truth)")
    parser.add_argument("--no-pictures", action="store_true", help="errors and timings only")
    parser.add_argument("--json", action="store_true", help="print the summary as JSON on stdout")
    parser.set_defaults(handler=on_file(write_comparison), out="uvfeat-out/compare")


def write_comparison(mesh, args, console, load_notes: list[str], started: float) -> dict:
    """Runs both methods, prints the errors and timings (or JSON) and writes the pictures."""
    from ..compare import compare, save_comparison_pictures

    with steps(console, 2) as advance:
        advance("reference + parametric", done=False)
        with recorded_notes() as notes:
            result = compare(mesh, args.feature, args.radius, samples=args.samples, resolution=args.resolution,
                             compute_resolution=args.compute_resolution, gaussian_method=args.gaussian_method,
                             seed=args.seed, query=args.query, method=args.method, sampling=args.sampling,
                             quadrature=args.quadrature, surface=args.surface,
                             truth_levels=args.truth_levels)
        advance("pictures")
        summary = result.to_dict()
        summary["warnings"] = load_notes + notes
        if not args.no_pictures:
            pictures = save_comparison_pictures(result, args.out)
            summary["pictures"] = {k: os.path.basename(v) for k, v in pictures.items()}
        os.makedirs(args.out, exist_ok=True)
        write_json(os.path.join(args.out, "compare.json"), summary)
    if args.json:
        print(json.dumps(summary, indent=2, default=float))
        return summary
    from rich.table import Table

    t = result.timings
    table = Table(title=f"{mesh.name}: r = {result.radius:.4g} ({args.radius})")
    own = result.reference_errors
    columns = ["feature", "%AE", "mean-normalised", "compared vertices"] + (["reference %AE"] if own else [])
    for column in columns:
        table.add_column(column, justify="left" if column == "feature" else "right")
    for name, e in result.errors.items():
        table.add_row(name, f"{e['percent_ae']:.3f}", f"{e['mean_normalised']:.4f}", str(e["compared"]),
                      *([f"{own[name]['percent_ae']:.3f}"] if own else []))
    console.print(table)
    if own:
        s = result.settings
        console.print(f"errors against the reference refined {s['truth_level']} time(s) ({s['truth_faces']} faces; "
                      f"{'converged' if s['truth_converged'] else 'not converged'}: last change "
                      f"{max(s['truth_changes'][-1].values()) if s['truth_changes'] else float('nan'):.2f} %)")
    console.print(f"parametric {1e3 * t['parametric']:.0f} ms (buffers {1e3 * t['parametric_buffers']:.0f}, "
                  f"features {1e3 * t['parametric_features']:.0f}, per-vertex {1e3 * t['parametric_per_vertex']:.0f}); "
                  f"reference {1e3 * t['reference']:.0f} ms; speed-up {t['speedup']:.2f}x "
                  f"(untimed: pre-processing {1e3 * t['untimed_preprocessing']:.0f} ms, "
                  f"half-edges {1e3 * t['untimed_connectivity']:.0f} ms)")
    print_notes_and_outputs(console, summary["warnings"], "compare.json" + ("" if args.no_pictures else " and pictures"),
                            args.out)
    return summary
