"""The native module's type stubs (python/uvfeat/_core.pyi) match what the extension exports:
every class, function, method, property and signature, checked by mypy's stubtest."""

import subprocess
import sys

import pytest


def test_the_native_module_matches_its_stubs():
    pytest.importorskip("mypy")
    run = subprocess.run([sys.executable, "-m", "mypy.stubtest", "uvfeat._core"], capture_output=True, text=True,
                         timeout=600)
    assert run.returncode == 0, run.stdout + run.stderr
