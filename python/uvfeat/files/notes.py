"""Warnings turned into notes: the commands and batch runs report what a computation warned about
(normalised UVs, flagged neighbourhoods, ...) in their summaries and on the console."""

from __future__ import annotations

import contextlib
import warnings


@contextlib.contextmanager
def recorded_notes():
    """Yields a list that, once the block ends, holds the messages of the warnings raised inside
    it, each once, sorted (so that runs compare)."""
    notes: list[str] = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        yield notes
    notes.extend(sorted({str(w.message) for w in caught}))
