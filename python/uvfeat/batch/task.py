"""One mesh of a batch, as a task on a worker: load it, compute and write what ``uvfeat compute``
writes, and answer a row of the run table; and whether an earlier run already finished it."""

from __future__ import annotations

import contextlib
import json
import os
import time

from ..files.feature_files import SUMMARY, FeatureJob, load_with_notes, radius_tag, write_feature_files
from ..files.notes import recorded_notes
from .inputs import MemoryMesh


def source_record(path: str) -> dict:
    """What identifies the input file: a changed file is computed again."""
    stat = os.stat(path)
    return {"path": path, "bytes": stat.st_size, "modified_ns": stat.st_mtime_ns}


def finished_summary(folder: str, job: FeatureJob, source: dict) -> dict | None:
    """The summary of an earlier run that wrote this mesh's files with the same settings (and the
    pictures, when asked for), if any."""
    try:
        with open(os.path.join(folder, SUMMARY)) as f:
            summary = json.load(f)
    except (OSError, ValueError):
        return None
    same = summary.get("settings") == job.settings() and summary.get("source") == source
    return summary if same and (summary.get("pictures") or not job.pictures) else None


def summary_row(path: str, folder: str, summary: dict, status: str) -> dict:
    """The run-table row of a mesh whose files are written."""
    timings = summary["timings_s"]
    row = {"path": path, "output": folder, "status": status, "error": None, "mesh": summary["mesh"],
           "vertices": summary["sizes"]["vertices"], "faces": summary["sizes"]["faces"],
           "charts": summary["diagnostics"]["charts"], "warnings": len(summary["warnings"]),
           "warning_text": "; ".join(summary["warnings"]),
           "preprocessing_s": timings["preprocessing_s"], "rasterisation_s": timings["rasterisation_s"],
           "features_s": sum(info["features_s"] for info in summary["radii"].values()), "total_s": timings["total"]}
    for radius, info in summary["radii"].items():
        for name, (low, high) in info["per_vertex_range"].items():
            row[f"{name}_r{radius_tag(radius)}_min"], row[f"{name}_r{radius_tag(radius)}_max"] = low, high
    return row


def failed_row(path: str, folder: str, error: BaseException | str, seconds: float | None = None) -> dict:
    message = error if isinstance(error, str) else f"{type(error).__name__}: {error}"
    return {"path": path, "output": folder, "status": "failed", "error": message, "total_s": seconds}


def source_of(item: str | MemoryMesh) -> dict:
    """What identifies an input: a changed file or changed arrays are computed again."""
    return source_record(item) if isinstance(item, str) else item.record()


def label_of(item: str | MemoryMesh) -> str:
    """An input's row key and ``path`` column."""
    return item if isinstance(item, str) else item.label


def mesh_task(path: str, item: str | MemoryMesh, folder: str, job: FeatureJob, source: dict) -> dict:
    """Computes one mesh (a file, or a mesh sent from memory) and answers its row, labelled
    ``path``; any failure of this mesh becomes its row, so the run goes on."""
    started = time.perf_counter()
    # Until the new files are complete no summary may claim them (a run killed half-way recomputes)
    with contextlib.suppress(FileNotFoundError):
        os.remove(os.path.join(folder, SUMMARY))
    try:
        if isinstance(item, str):
            mesh, notes = load_with_notes(item, job.uv, job.resolution, job.strict_uv)
        else:
            with recorded_notes() as notes:
                mesh = item.load(job.uv, job.resolution)
        _, summary = write_feature_files(mesh, job, folder, notes, started, source=source)
    except Exception as exc:  # unreadable, degenerate, no UVs, ...: reported in the table
        return failed_row(path, folder, exc, time.perf_counter() - started)
    return summary_row(path, folder, summary, "computed")
