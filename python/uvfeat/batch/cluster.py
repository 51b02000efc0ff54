"""The Dask side of a batch: a client on a local cluster or an existing scheduler, and tasks run
one per worker thread, their results taken as they finish.

Each local worker is a process with one thread, so a worker holds one mesh (or one chunk of
frames) at a time and its memory is bounded by the largest mesh; the cores are shared through
the Rust engine's own threads instead: ``RAYON_NUM_THREADS`` = cores // workers, so the workers
together use every core once and never oversubscribe them.
"""

from __future__ import annotations

import contextlib
import os

from ..errors import ClusterError, InvalidParameterError, MissingDependencyError

INSTALL_HINT = "pip install 'uvfeat[batch]'"

#: How long a run on an existing scheduler waits for its first worker.
WORKER_WAIT_S = 60


def distributed():
    """The ``dask.distributed`` module, or a clear error saying how to install it."""
    try:
        import distributed
    except ImportError as exc:
        raise MissingDependencyError(f"running on Dask needs dask.distributed ({exc}); {INSTALL_HINT}") from exc
    return distributed


def usable_cores() -> int:
    """Cores this process may run on (its affinity, which containers and batch systems set)."""
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return os.cpu_count() or 1


def engine_threads(workers: int) -> int:
    """Rust threads per worker process: the cores split evenly between the workers."""
    return max(1, usable_cores() // workers)


def check_workers(workers: int | None) -> int:
    """The local worker count: ``workers``, or one per core."""
    if workers is None:
        return usable_cores()
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise InvalidParameterError(f"workers must be a positive number of worker processes, got {workers!r}")
    return workers


def local_cluster(workers: int | None = None, dashboard_address: str | None = "127.0.0.1:8787"):
    """A ``LocalCluster`` of ``workers`` processes (default: one per core) with one thread each,
    on the loopback interface.

    Its workers keep glibc's own memory tuning: Dask's nannies set ``MALLOC_TRIM_THRESHOLD_``,
    which also fixes glibc's mmap threshold at 128 KiB, so every array of a mesh was mapped and
    unmapped afresh; that made a worker 22 % slower per mesh than the same work in one process
    (docs/BENCHMARKS.md). Freed memory is still reused for the next mesh."""
    import dask

    workers = check_workers(workers)
    with dask.config.set({"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}):
        return distributed().LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                                          dashboard_address=dashboard_address,
                                          env={"RAYON_NUM_THREADS": str(engine_threads(workers))})


@contextlib.contextmanager
def dask_client(client=None, scheduler: str | None = None, workers: int | None = None):
    """``client`` itself when given (left open); else a client of the scheduler at ``scheduler``,
    else of a new local cluster of ``workers`` processes; those two are closed on exit."""
    if client is not None:
        yield client
        return
    dask = distributed()
    if scheduler:
        try:
            client = dask.Client(scheduler, timeout="20s")
        except (OSError, TimeoutError) as exc:
            raise ClusterError(f"cannot reach the Dask scheduler at {scheduler!r}: {exc}") from exc
        with client:
            try:  # a scheduler without workers would leave the run waiting at 0 % for ever
                client.wait_for_workers(1, timeout=WORKER_WAIT_S)
            except TimeoutError as exc:
                raise ClusterError(f"the Dask scheduler at {scheduler!r} has no workers (waited "
                                   f"{WORKER_WAIT_S} s); start some with `dask worker {scheduler}`") from exc
            yield client
        return
    try:
        cluster = local_cluster(workers)
    except (OSError, RuntimeError, TimeoutError) as exc:
        raise ClusterError(f"cannot start a local Dask cluster of {check_workers(workers)} workers: {exc}") from exc
    with cluster, dask.Client(cluster) as client:
        try:
            yield client
        except KeyboardInterrupt:
            _stop_workers(cluster)
            raise


def _stop_workers(cluster) -> None:
    """Ends the local workers' processes at once: closing them politely waits for the task each one
    is computing (seconds), while Ctrl-C must stop a run within half a second."""
    import signal

    for nanny in list(cluster.workers.values()):
        nanny.auto_restart = False
        pid = getattr(getattr(getattr(nanny, "process", None), "process", None), "pid", None)
        if pid:
            with contextlib.suppress(OSError):
                os.kill(pid, getattr(signal, "SIGKILL", signal.SIGTERM))  # Windows has no SIGKILL


def run_tasks(client, function, calls: list[tuple], on_lost):
    """Submits ``function(*call)`` for every call and yields ``(index, result)`` as each finishes.
    A task whose workers died too often (Dask retries it on another worker first) yields
    ``on_lost(call, error)`` instead. Leaving early cancels what has not run."""
    dask = distributed()
    futures = {client.submit(function, *call, pure=False): index for index, call in enumerate(calls)}
    try:
        for future in dask.as_completed(futures):
            index = futures[future]
            try:
                result = future.result()
            except Exception as exc:  # KilledWorker, a worker out of memory, a lost connection
                result = on_lost(calls[index], exc)
            future.release()
            yield index, result
    finally:
        client.cancel(list(futures))
