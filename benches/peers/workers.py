"""One worker process per method, so that a method can be stopped at a time limit and a crash or
a memory blow-up in a peer library cannot take the benchmark down with it.

Workers are spawned (not forked: the parent has run uvfeat's thread pool) and serve requests over
a pipe; the time is measured inside the worker, around the method call alone.
"""

from __future__ import annotations

import importlib
import multiprocessing
import os
import resource
import time
import traceback


def _serve(conn, key: str, memory_bytes: int) -> None:
    # The peers print progress on stdout from C++; the results come back over the pipe.
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    resource.setrlimit(resource.RLIMIT_AS, (memory_bytes, memory_bytes))
    from methods import METHODS

    method = METHODS[key]
    # Imported before the first request, so that no timed call pays it (the tables exclude imports).
    importlib.import_module(method.module)
    while True:
        request = conn.recv()
        if request is None:
            return
        surface, radius = request
        try:
            started, cpu_started = time.perf_counter(), time.process_time()
            h, k = method.run(surface, radius)
            conn.send(("ok", (time.perf_counter() - started, time.process_time() - cpu_started, h, k)))
        except MemoryError:
            conn.send(("error", f"out of memory (limit {memory_bytes / 2**30:.0f} GiB)"))
        except Exception as error:
            last = traceback.extract_tb(error.__traceback__)[-1]
            conn.send(("error", f"{type(error).__name__}: {error} ({last.filename}:{last.lineno})"))


class Worker:
    """Runs one method in a child process; restarted after a timeout or a crash."""

    def __init__(self, key: str, memory_gb: float):
        self.key = key
        self.memory_bytes = int(memory_gb * 2**30)
        self._process = None
        self._conn = None

    def _start(self) -> None:
        context = multiprocessing.get_context("spawn")
        self._conn, child = context.Pipe()
        self._process = context.Process(target=_serve, args=(child, self.key, self.memory_bytes), daemon=True)
        self._process.start()
        child.close()

    def run(self, surface, radius: float, timeout: float):
        """Returns (status, (wall s, cpu s), h, k, detail): status 'ok', 'timeout' or 'error'."""
        if self._process is None or not self._process.is_alive():
            self._start()
        self._conn.send((surface, radius))
        if not self._conn.poll(timeout):
            self.stop()
            return "timeout", (timeout, None), None, None, f"stopped after {timeout:.0f} s"
        try:
            status, payload = self._conn.recv()
        except EOFError:
            self._process.join()
            code = self._process.exitcode
            self.stop()
            return "error", (None, None), None, None, f"worker died (exit code {code})"
        if status != "ok":
            return "error", (None, None), None, None, payload
        wall, cpu, h, k = payload
        return "ok", (wall, cpu), h, k, ""

    def stop(self) -> None:
        if self._process is not None:
            if self._process.is_alive():
                self._process.kill()
            self._process.join()
        self._process = self._conn = None

    def close(self) -> None:
        if self._process is not None and self._process.is_alive():
            self._conn.send(None)
            self._process.join(timeout=10)
        self.stop()
