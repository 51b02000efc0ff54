"""The ``uvfeat`` command line, one module per command: ``uvfeat atlas``, ``compute``,
``batch``, ``compare``, ``animate``, ``demo``, ``view``, ``bake``. Run ``uvfeat --help``."""

from __future__ import annotations

import argparse
import gc
import sys
import warnings

from .._core import __version__
from ..errors import UvfeatError
from . import animate, atlas, bake, batch, compare, compute, demo, view
from .common import console

COMMANDS = (atlas, compute, batch, compare, animate, demo, view, bake)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="uvfeat", description="Multi-scale geometric features of triangle meshes, "
                                     "computed in UV parameter space.")
    parser.add_argument("--version", action="version", version=f"uvfeat {__version__}")
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for command in COMMANDS:
        command.add_command(commands)
    return parser


def print_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """A warning as one line of the command's output (Python's own format adds the file, the line
    number and the source line of the library call that raised it)."""
    console().print(f"[yellow]warning:[/yellow] {message}", highlight=False)


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    for option in ("resolution", "compute_resolution"):
        if getattr(args, option, 1) <= 0:
            console().print(f"[red]error:[/red] --{option.replace('_', '-')} must be a positive integer, "
                            f"got {getattr(args, option)}")
            return 2
    try:
        with warnings.catch_warnings():
            warnings.showwarning = print_warning
            return args.handler(args)
    except UvfeatError as exc:
        console().print(f"[red]error:[/red] {exc}")
        return 2
    except KeyboardInterrupt:
        console().print("interrupted")
        return 130
    except OSError as exc:  # an output folder that cannot be made or written, a full disk
        console().print(f"[red]error:[/red] {exc.strerror or exc}: {exc.filename or ''}".rstrip(": "))
        return 2


#: Allocations between two collections of the youngest generation while the program runs
#: (Python's default: 700).
COLLECT_EVERY = 100_000


def run(argv: list[str] | None = None) -> int:
    """The ``uvfeat`` program: :func:`main` with the garbage collector set for a short run. A
    command makes many objects it keeps (the imports: matplotlib's, trimesh's) and few reference
    cycles, so the collector ran 229 times in a ``uvfeat compute`` (85-100 ms); every
    :data:`COLLECT_EVERY` allocations, once (45-55 ms). Interpreter shutdown then ran it over every
    object (matplotlib's alone take 0.15 s): freezing them skips that, and reference counting
    still frees them."""
    gc.set_threshold(COLLECT_EVERY, *gc.get_threshold()[1:])
    code = main(argv)
    gc.freeze()
    return code


if __name__ == "__main__":
    sys.exit(run())
