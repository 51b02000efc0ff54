"""What the commands share: the console, progress over named steps, loading a mesh with its
notes, and the options several commands take."""

from __future__ import annotations

import argparse
import contextlib
import time

from ..options import ARGUMENT_DEFAULTS, CHOICES, DEFAULT_OPTIONS, FEATURES, SURFELS_PER_BALL
from ..unwrap import UV_POLICIES

MESH_HELP = "mesh file (obj, ply, glb, gltf, off, stl)"


def console():
    from rich.console import Console

    # Soft wrap: a note is one line however wide the terminal (piped output is not cut at 80 columns).
    return Console(stderr=True, soft_wrap=True)


@contextlib.contextmanager
def steps(out, total: int):
    """A progress bar over named steps; yields ``advance(description)``."""
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    progress = Progress(TextColumn("{task.description:<28}"), BarColumn(), TextColumn("{task.completed}/{task.total}"),
                        TimeElapsedColumn(), console=out, transient=True, disable=not out.is_terminal)
    with progress:
        task = progress.add_task("starting", total=total)

        def advance(description: str, done: bool = True):
            progress.update(task, description=description, advance=1 if done else 0)

        yield advance


@contextlib.contextmanager
def throughput(out, description: str, total: int, unit: str, per_seconds: float = 1.0):
    """A progress bar over ``total`` items that shows how many are done per ``per_seconds``
    (``unit`` names that rate); yields ``advance(n=1)``."""
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn

    progress = Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                        TextColumn("{task.fields[rate]:.2f} " + unit), TimeElapsedColumn(), TimeRemainingColumn(),
                        console=out, transient=True, disable=not out.is_terminal)
    with progress:
        task = progress.add_task(description, total=total, rate=0.0)
        started = time.perf_counter()

        def advance(n: int = 1):
            progress.advance(task, n)
            done = progress.tasks[0].completed
            progress.update(task, rate=done * per_seconds / max(time.perf_counter() - started, 1e-9))

        yield advance


def load_mesh(path: str, args):
    """The mesh at ``path`` loaded with the command's UV options, and its warnings as notes."""
    from ..files.feature_files import load_with_notes

    return load_with_notes(path, args.uv, args.resolution, args.strict_uv)


def on_file(writer):
    """A command that loads ``args.mesh`` and hands it to ``writer(mesh, args, console, notes, started)``."""

    def command(args) -> int:
        started = time.perf_counter()
        mesh, notes = load_mesh(args.mesh, args)
        writer(mesh, args, console(), notes, started)
        return 0

    return command


def print_notes_and_outputs(out, notes: list[str], written: str, folder: str) -> None:
    for note in notes:
        out.print(f"[yellow]note:[/yellow] {note}")
    out.print(f"wrote {written} to {folder}")


def add_atlas_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--resolution", type=int, default=1024, help="geometry-buffer size W_g in texels (default 1024)")
    parser.add_argument("--out", default="uvfeat-out", help="output folder (created if missing)")


def add_uv_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--uv", choices=UV_POLICIES, default="auto",
                        help="auto: use the file's UVs, an automatic atlas (charts) when there are none or they "
                        "overlap (default); require: the file's UVs as they are, fail without UVs; charts: always "
                        "build uvfeat's normal-cone atlas (fast); xatlas: always build xatlas's atlas (slow, cached)")
    parser.add_argument("--strict-uv", action="store_true", help="fail on UVs outside [0, 1] instead of normalising them")


def add_feature_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--samples", type=int, default=None,
                        help="samples per neighbourhood: the pattern's points per texel, or about as many "
                             "surfels per ball with the surfels (fewer: faster and coarser; default: "
                             f"{ARGUMENT_DEFAULTS['samples']} points, {SURFELS_PER_BALL} surfels)")
    parser.add_argument("--compute-resolution", type=int, default=ARGUMENT_DEFAULTS["compute_resolution"],
                        help="computation texture size (default %(default)s)")
    parser.add_argument("--method", choices=CHOICES["method"], default=DEFAULT_OPTIONS["method"],
                        help="curvature estimators: integral invariants or the osculating-circle fit (adds principal "
                        "directions; default %(default)s)")
    parser.add_argument("--sampling", choices=CHOICES["sampling"], default=DEFAULT_OPTIONS["sampling"],
                        help="sampler: one lattice shared by a tile of texels, per-texel samples (fast), or the exact "
                        "path both are checked against (default %(default)s)")
    parser.add_argument("--quadrature", choices=CHOICES["quadrature"], default=None,
                        help="how a neighbourhood is summed: the paper's sample pattern over a parametric disk, or "
                        "the atlas's surfels, each piece of surface counted once (docs/USAGE.md; default: the "
                        "pattern, except the per-vertex values of an atlas of more than one chart, which sum the "
                        "surfels at the vertices, and there compute's maps of radii of 3 face sides or more, those "
                        "values interpolated over the faces)")
    parser.add_argument("--surface", choices=CHOICES["surface"], default=None,
                        help="the surface summed: the smooth surface through the vertex normals, or the mesh's flat "
                        "facets as the object-space reference measures them (default: the facets for the "
                        "per-vertex sums of an atlas of more than one chart, the smooth surface otherwise)")


def add_feature_command_options(parser: argparse.ArgumentParser, radius_note: str) -> None:
    """Arguments shared by the commands that compute features on a mesh file."""
    parser.add_argument("mesh", help=MESH_HELP)
    add_feature_selection(parser, radius_note)


def add_feature_selection(parser: argparse.ArgumentParser, radius_note: str) -> None:
    """What to compute on each mesh and how: features, radii, buffers, sampling, UVs, seed, query."""
    parser.add_argument("--feature", default="mean_curvature",
                        help="comma-separated names, or 'all' (" + ", ".join(FEATURES) + ")")
    parser.add_argument("--radius", default="2%", help="radius in object units or %% of the bounding-box diagonal"
                        f"{radius_note} (default 2%%)")
    add_atlas_options(parser)
    add_feature_options(parser)
    add_uv_options(parser)
    parser.add_argument("--seed", type=int, default=ARGUMENT_DEFAULTS["seed"], help="seed of the sample pattern")
    parser.add_argument("--query", choices=CHOICES["query"], default=DEFAULT_OPTIONS["query"],
                        help="per-vertex query (default %(default)s)")


def add_computation_options(parser: argparse.ArgumentParser) -> None:
    """The options of ``uvfeat compute`` beyond the feature selection (``uvfeat batch`` takes them too)."""
    parser.add_argument("--adaptive", action="store_true", help="two-stage adaptive sampling (DESIGN.md §1.8)")
    parser.add_argument("--paper-mode", action="store_true", help="the paper's choices, for reproduction")
    parser.add_argument("--directions", choices=("d1", "d2"), default=None,
                        help="draw this principal direction (d1 of k1, d2 of k2) as segments on the map pictures; "
                        "needs --method fit")
    parser.add_argument("--standard-error", action="store_true", help="also compute Monte Carlo standard errors")


def add_cluster_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--scheduler", metavar="ADDRESS", help="run on the Dask cluster of this scheduler "
                        "(tcp://host:8786); its workers must see the input and output folders")
    parser.add_argument("--workers", type=int, metavar="N", help="run on a local Dask cluster of N worker processes "
                        "(one thread each; default: one per core)")


def print_dashboard(out, client) -> None:
    """The address of the Dask dashboard, where the cluster's tasks, memory and workers are shown."""
    if client is not None:
        out.print(f"Dask dashboard: {client.dashboard_link} ({len(client.nthreads())} workers)")
