"""The run table: one row per mesh (path, sizes, charts, warnings, timings, per-vertex ranges of
every feature, status and error), written as Parquet and CSV through pyarrow."""

from __future__ import annotations

import os

from ..errors import MissingDependencyError
from .cluster import INSTALL_HINT

TABLE = "batch"

#: The columns every run table starts with; the per-vertex ranges (``FEATURE_rTAG_min``, ``_max``) follow.
FIRST_COLUMNS = ("path", "output", "status", "error", "mesh", "vertices", "faces", "charts", "warnings",
                 "warning_text", "preprocessing_s", "rasterisation_s", "features_s", "total_s")


def write_run_table(rows: list[dict], out: str):
    """Writes ``batch.parquet`` and ``batch.csv`` to ``out``; returns the ``pyarrow.Table``.
    Columns: :data:`FIRST_COLUMNS`, then the other keys of the rows in first-seen order; missing
    cells are null."""
    try:
        import pyarrow as pa
        import pyarrow.csv
        import pyarrow.parquet
    except ImportError as exc:
        raise MissingDependencyError(f"the run table needs pyarrow ({exc}); {INSTALL_HINT}") from exc
    columns = list(dict.fromkeys([*FIRST_COLUMNS, *(key for row in rows for key in row)]))
    table = pa.table({name: [row.get(name) for row in rows] for name in columns})
    os.makedirs(out, exist_ok=True)
    pyarrow.parquet.write_table(table, os.path.join(out, f"{TABLE}.parquet"))
    pyarrow.csv.write_csv(table, os.path.join(out, f"{TABLE}.csv"))
    return table
