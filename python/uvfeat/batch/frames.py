"""An animation's frames on a Dask cluster: the frames cut into chunks, one task per chunk; each
task builds the atlas once and updates it frame by frame (``Atlas.update``), as one process would."""

from __future__ import annotations

import math

from ..animation.frame_files import animate_frames
from ..errors import ClusterError, InvalidParameterError, UvfeatError
from .cluster import check_workers, dask_client, distributed, run_tasks

#: Chunks per worker thread: two keep the threads busy while the last chunks finish.
CHUNKS_PER_THREAD = 2


def frame_chunks(total: int, frames_per_task: int) -> list[tuple[int, int]]:
    """``(start, stop)`` of each chunk of ``frames_per_task`` frames (the last may be shorter)."""
    return [(start, min(start + frames_per_task, total)) for start in range(0, total, frames_per_task)]


def _lost(call: tuple, error: BaseException):
    if isinstance(error, UvfeatError):  # a bad frame: the same error as without a cluster
        raise error
    start, stop = call[-2:]
    why = "the workers computing them died" if isinstance(error, distributed().KilledWorker) else "their task failed"
    raise ClusterError(f"frames {start} to {stop - 1} were lost: {why} ({type(error).__name__}: {error})") from error


def animate_on_cluster(mesh: str, features, radius, options: dict, out: str, total: int, *, client=None,
                       scheduler: str | None = None, workers: int | None = None, frames_per_task: int | None = None,
                       on_start=None, on_frames=None) -> tuple[list[dict], list[str]]:
    """Frames ``0`` to ``total - 1`` of ``uvfeat.animate(mesh, features, radius, **options)``
    written to ``out`` by the cluster's workers; returns the frames' rows (index, time, timings)
    in order and the notes. ``on_start(client)`` before the first task, ``on_frames(n)`` as each
    chunk of ``n`` frames finishes."""
    if frames_per_task is not None and (isinstance(frames_per_task, bool) or not isinstance(frames_per_task, int)
                                        or frames_per_task < 1):
        raise InvalidParameterError(f"frames per task must be a positive number, got {frames_per_task!r}")
    if client is None and scheduler is None:
        check_workers(workers)
    rows, notes = [], set()
    with dask_client(client, scheduler, workers) as running:
        if on_start:
            on_start(running)
        threads = max(1, sum(running.nthreads().values()))
        size = frames_per_task or max(1, math.ceil(total / (CHUNKS_PER_THREAD * threads)))
        calls = [(mesh, features, radius, options, out, start, stop) for start, stop in frame_chunks(total, size)]
        for _, result in run_tasks(running, animate_frames, calls, _lost):
            rows += result["frames"]
            notes.update(result["notes"])
            if on_frames:
                on_frames(len(result["frames"]))
    return sorted(rows, key=lambda row: row["index"]), sorted(notes)
