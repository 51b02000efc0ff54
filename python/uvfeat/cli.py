"""The ``uvfeat`` command line: ``uvfeat atlas``, ``uvfeat demo``. Run ``uvfeat --help``."""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import sys
import time
import warnings

from . import __version__
from .errors import UvfeatError


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


def _cmd_atlas(args) -> int:
    console = _console()
    started = time.perf_counter()
    mesh, notes = _load(args.mesh, args)
    _write_atlas(mesh, args, console, notes, started)
    return 0


def _cmd_demo(args) -> int:
    from .examples import spot_path

    console = _console()
    console.print(f"uvfeat {__version__} demo on the built-in Spot mesh (Keenan Crane, CC0)")
    started = time.perf_counter()
    args.uv, args.strict_uv, args.precision = "require", False, "f32"
    mesh, notes = _load(spot_path(), args)
    args.out = os.path.join(args.out, "atlas")
    _write_atlas(mesh, args, console, notes, started)
    return 0


def _add_atlas_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--resolution", type=int, default=1024, help="geometry-buffer size W_g in texels (default 1024)")
    parser.add_argument("--out", default="uvfeat-out", help="output folder (created if missing)")


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
    atlas.set_defaults(handler=_cmd_atlas)

    demo = commands.add_parser("demo", help="run on the built-in Spot mesh and write pictures")
    _add_atlas_options(demo)
    demo.set_defaults(handler=_cmd_demo)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    if getattr(args, "resolution", 1) <= 0:
        _console().print(f"[red]error:[/red] --resolution must be a positive integer, got {args.resolution}")
        return 2
    try:
        return args.handler(args)
    except UvfeatError as exc:
        _console().print(f"[red]error:[/red] {exc}")
        return 2


if __name__ == "__main__":
    sys.exit(main())
