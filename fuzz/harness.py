"""What the fuzzers share: the exceptions a well-formed failure may raise, and how a fuzz input is
turned into numbers. A fuzz target must end normally or with a :class:`uvfeat.UvfeatError` (typed,
with a message); anything else (an untyped exception, a Rust panic reaching Python, a crash or a
hang) is a finding."""

from __future__ import annotations

import warnings

import numpy as np

import uvfeat

#: The only exceptions a fuzz input may raise.
EXPECTED = (uvfeat.UvfeatError,)


def quiet() -> None:
    """Warnings are part of normal operation on hostile input; the fuzzers ignore them."""
    warnings.simplefilter("ignore")


def numbers(data: bytes, count: int, dtype=np.float64) -> np.ndarray:
    """``count`` values of ``dtype`` read from ``data`` (repeated to length; NaN and Inf included)."""
    size = np.dtype(dtype).itemsize * count
    if not data:
        return np.zeros(count, dtype=dtype)
    raw = (data * (size // len(data) + 1))[:size]
    return np.frombuffer(raw, dtype=dtype).copy()
