"""A short coverage-guided fuzzing run of the file loaders and the core entry points
(docs/RELIABILITY.md has the long runs). Each harness runs for 10 s from its seed corpus (copied,
since libFuzzer adds what it finds to the corpus folder); any exception other than a typed
:class:`uvfeat.UvfeatError`, a crash or a hang fails the run. The inputs that once failed, kept in
fuzz/regressions, are replayed first, without the coverage instrumentation they do not need."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("atheris", reason="atheris (coverage-guided fuzzer) has no wheel for this platform")

FUZZ = Path(__file__).resolve().parent.parent / "fuzz"
SECONDS = 10


def fuzz(harness: str, inputs: list[Path], tmp_path: Path, *options: str, replay: bool = False):
    env = {**os.environ, "RAYON_NUM_THREADS": "1", "UVFEAT_FUZZ_REPLAY": "1" if replay else "0"}
    command = [sys.executable, str(FUZZ / harness), *map(str, inputs), "-timeout=20", "-rss_limit_mb=2048",
               f"-artifact_prefix={tmp_path}/", *options]
    return subprocess.run(command, cwd=FUZZ, env=env, capture_output=True, text=True, timeout=SECONDS * 4 + 60)


def assert_clean(run: subprocess.CompletedProcess) -> None:
    tail = (run.stdout + run.stderr)[-3000:]
    assert run.returncode == 0, tail
    assert "DONE" in tail or "Executed" in tail, tail


@pytest.mark.parametrize("harness, corpus", [("fuzz_loaders.py", "loaders"), ("fuzz_core.py", "core")])
def test_a_short_fuzzing_run_finds_nothing(harness, corpus, tmp_path):
    working = tmp_path / "corpus"
    seeds = FUZZ / "corpus" / corpus
    shutil.copytree(seeds, working) if seeds.exists() else working.mkdir()
    assert_clean(fuzz(harness, [working], tmp_path, f"-max_total_time={SECONDS}"))


@pytest.mark.parametrize("name", ["loaders", "core"])
def test_the_inputs_that_once_failed_pass(name, tmp_path):
    inputs = sorted((FUZZ / "regressions").glob(f"{name}-*"))
    assert inputs
    assert_clean(fuzz(f"fuzz_{name}.py", inputs, tmp_path, replay=True))
