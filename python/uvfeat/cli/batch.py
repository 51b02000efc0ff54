"""``uvfeat batch``: ``uvfeat compute`` on many meshes on a Dask cluster, with a run table."""

from __future__ import annotations

import contextlib
import time

from ..files.feature_files import FeatureJob
from .common import (
    add_cluster_options,
    add_computation_options,
    add_feature_selection,
    console,
    print_dashboard,
    throughput,
)


def add_command(commands) -> None:
    parser = commands.add_parser(
        "batch", help="compute features of many meshes on a Dask cluster (local processes or a scheduler)",
        description="Writes, per mesh, the files of `uvfeat compute` (no pictures unless --pictures) into OUT/<mesh "
        "path>/, and the run table OUT/batch.parquet and OUT/batch.csv (a row per mesh: sizes, charts, warnings, "
        "timings, feature ranges, status, error). Meshes finished with the same settings are skipped.")
    parser.add_argument("inputs", nargs="+", metavar="INPUTS", help="mesh files, folders (searched recursively) or "
                        "glob patterns (quote them)")
    add_feature_selection(parser, " of each mesh; comma-separated for several scales")
    add_computation_options(parser)
    add_cluster_options(parser)
    parser.add_argument("--force", action="store_true", help="recompute meshes an earlier run finished")
    parser.add_argument("--pictures", action="store_true", help="also write the pictures: .png maps and the 3D views <feature>_3d.png")
    parser.set_defaults(handler=run, out="uvfeat-out/batch")


def run(args) -> int:
    from ..batch import batch

    out, started = console(), time.perf_counter()
    options = FeatureJob.from_args(args).options()
    counts = {"computed": 0, "skipped": 0, "failed": 0}
    with contextlib.ExitStack() as stack:
        advance = None

        def on_start(total: int, client) -> None:
            nonlocal advance
            print_dashboard(out, client)
            advance = stack.enter_context(throughput(out, "meshes", total, "meshes/min", per_seconds=60.0))

        def on_row(row: dict) -> None:
            counts[row["status"]] += 1
            if row["status"] == "failed":
                out.print(f"[red]failed:[/red] {row['path']}: {row['error']}")
            advance()

        table = batch(args.inputs, args.feature, args.radius, out=args.out, scheduler=args.scheduler,
                      workers=args.workers, force=args.force, pictures=args.pictures, on_start=on_start,
                      on_row=on_row, **options)
    minutes = (time.perf_counter() - started) / 60
    out.print(f"{table.num_rows} meshes: {counts['computed']} computed ({counts['computed'] / minutes:.1f} per "
              f"minute), {counts['skipped']} skipped (finished earlier), {counts['failed']} failed")
    out.print(f"wrote per-mesh files and batch.parquet, batch.csv to {args.out}")
    return 1 if counts["failed"] else 0
