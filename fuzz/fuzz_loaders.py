"""Fuzzes ``uvfeat.load`` over every format it reads: the first byte of an input picks the format,
the rest is the file. Run (seed corpus in fuzz/corpus/loaders)::

    .venv/bin/python fuzz/fuzz_loaders.py fuzz/corpus/loaders -max_total_time=60 -timeout=10

A finding is an exception other than :class:`uvfeat.UvfeatError`, a crash or a hang.
"""

from __future__ import annotations

import contextlib
import os
import sys
import tempfile

import atheris

# trimesh's file parsers are what the inputs reach: instrumented for coverage (the whole of trimesh
# would take a minute to instrument at every start). Replaying inputs (UVFEAT_FUZZ_REPLAY=1) needs
# no coverage feedback, so no instrumentation (seconds at every start).
REPLAY = os.environ.get("UVFEAT_FUZZ_REPLAY") == "1"
with contextlib.nullcontext() if REPLAY else atheris.instrument_imports(include=["uvfeat", "trimesh.exchange", "harness"]):
    import trimesh  # noqa: F401
    import uvfeat
    from harness import EXPECTED, quiet

FOLDER = tempfile.mkdtemp(prefix="uvfeat-fuzz-")


def load_bytes(data: bytes) -> None:
    if not data:
        return
    extension = uvfeat.io.SUPPORTED_FORMATS[data[0] % len(uvfeat.io.SUPPORTED_FORMATS)]
    path = os.path.join(FOLDER, f"input.{extension}")
    with open(path, "wb") as file:
        file.write(data[1:])
    try:
        uvfeat.load(path, uv="require")
    except EXPECTED:
        pass


def main() -> None:
    quiet()
    atheris.Setup(sys.argv, load_bytes)
    atheris.Fuzz()


if __name__ == "__main__":
    main()
