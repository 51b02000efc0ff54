"""``uvfeat.batch``: what ``uvfeat compute`` writes, for many meshes, one Dask task per mesh;
finished meshes are skipped, so an interrupted run resumes, and a failed mesh is a row of the
run table rather than the end of the run."""

from __future__ import annotations

import contextlib
import os

from ..files.feature_files import FeatureJob
from .cluster import check_workers, dask_client, distributed, run_tasks
from .inputs import MemoryMesh, batch_inputs, output_folders
from .table import write_run_table
from .task import failed_row, finished_summary, label_of, mesh_task, source_of, summary_row



def batch(paths, features, radius, client=None, *, out: str = "uvfeat-out/batch", scheduler: str | None = None,
          workers: int | None = None, force: bool = False, pictures: bool = False, on_start=None, on_row=None,
          **options):
    """Features of many meshes on a Dask cluster, with the files of ``uvfeat compute`` per mesh.

    Parameters
    ----------
    paths : str, list or dict
        Mesh files, folders (searched recursively for mesh files) and glob patterns; meshes held in
        memory (any of :data:`uvfeat.interop.ACCEPTED`, in the list, named after their ``name``
        attribute, or as a ``{name: mesh}`` dict), sent to the workers whole and written under
        their names (rows ``"<name> (in memory)"``; unchanged arrays count as finished; their UVs are
        taken as given, so ``strict_uv`` applies to files only).
    features, radius
        As for ``uvfeat compute``: names (or "all"), one radius or several (a list or "1%,4%").
    client : distributed.Client, optional
        Run on this client's cluster. Otherwise on the scheduler at ``scheduler``, else on a new
        ``LocalCluster`` of ``workers`` processes (default one per core), closed at the end.
    out : str
        The run's folder: one sub-folder per mesh (named after its path) and ``batch.parquet``,
        ``batch.csv``.
    force : bool
        Recompute meshes an earlier run finished with the same settings (they are skipped otherwise).
    pictures : bool
        Also write the pictures: the ``.png`` maps and the 3D views ``<feature>_3d.png`` (a rerun
        with pictures recomputes meshes an earlier run finished without them).
    on_start : callable, optional
        ``on_start(n_meshes, client)`` before the first row (``client`` is None when every mesh
        is already finished).
    on_row : callable, optional
        ``on_row(row)`` as each mesh is finished, skipped or failed.
    **options
        ``samples``, ``resolution``, ``compute_resolution``, ``adaptive``, ``paper_mode``, ``seed``,
        ``query``, ``method``, ``sampling``, ``standard_error``, ``directions``, ``uv``, ``strict_uv``.

    Returns
    -------
    pyarrow.Table
        The run table, a row per mesh in input order: ``status`` is ``computed``, ``skipped``
        (finished by an earlier run) or ``failed`` (``error`` says why).
    """
    job = FeatureJob.of(features, radius, pictures=pictures, **options)
    if client is None and scheduler is None:
        check_workers(workers)
    items, out = batch_inputs(paths), os.path.abspath(out)  # workers may run in another folder
    meshes = [label_of(item) for item in items]
    folders = {p: os.path.join(out, f) for p, f in output_folders(items).items()}
    rows, pending = {}, []
    for item, path in zip(items, meshes):
        source = source_of(item)
        summary = None if force else finished_summary(folders[path], job, source)
        if summary is None:
            pending.append((path, item, folders[path], job, source))
        else:
            rows[path] = summary_row(path, folders[path], summary, "skipped")
    report = on_row or (lambda row: None)
    # No cluster is started when every mesh is finished already
    cluster = dask_client(client, scheduler, workers) if pending else contextlib.nullcontext()
    try:
        with cluster as running:
            if on_start:
                on_start(len(meshes), running)
            for row in rows.values():
                report(row)
            if running is not None:
                # Arrays held in memory go to the cluster once each, not inside the task graph.
                calls = [(path, running.scatter(item) if isinstance(item, MemoryMesh) else item, *rest)
                         for path, item, *rest in pending]
                for index, row in run_tasks(running, mesh_task, calls, _lost):
                    rows[pending[index][0]] = row
                    report(row)
    finally:
        table = write_run_table([rows[p] for p in meshes if p in rows], out)
    return table


def _lost(call: tuple, error: BaseException) -> dict:
    path, folder = call[0], call[2]
    if isinstance(error, distributed().KilledWorker):
        return failed_row(path, folder, f"the workers computing it died ({error}); too large for a worker's memory?")
    return failed_row(path, folder, error)  # the task itself failed on its worker: its own error
