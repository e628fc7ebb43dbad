"""A sweep's points run on Dask, each a full co-simulation on a worker process, rows written as
they finish; a failed point (an error, or a worker that died under it) is retried once, then
recorded as failed with its error, and the sweep goes on.

Worker processes, one thread each: the FMUs are not thread-safe. No more points are handed out
than the cluster has threads, so a worker holds only the point it runs, and the local cluster
fails a point at once when its worker dies (``allowed-failures`` 0): a death blames only the
point that was running there.
"""
from __future__ import annotations

import contextlib
from collections import deque
from dataclasses import dataclass
from pathlib import Path

import dask
from distributed import Client, LocalCluster, as_completed
from tqdm import tqdm

from ..cosim.folder_lock import folder_lock
from .point import run_point
from .sweep_file import Sweep
from .table import ResultsTable

ATTEMPTS = 2  # a failed point is run once more before it is recorded as failed
LOCAL_CLUSTER = {"distributed.scheduler.allowed-failures": 0}


@dataclass
class Outcome:
    """What a call of :func:`run_sweep` did: points in the design, found finished in the table,
    run now (ok and failed), retries, and the files written."""

    points: int
    skipped: int
    ok: int
    failed: int
    retried: int
    files: list[str]


@contextlib.contextmanager
def dask_client(workers: int = 2, scheduler: str | None = None):
    """A Client of the cluster at ``scheduler``, or of a local cluster of ``workers`` worker
    processes (one thread each) closed on exit."""
    if scheduler is not None:
        with Client(scheduler) as client:
            yield client
        return
    if workers < 1:
        raise ValueError(f"'workers' must be >= 1, got {workers}")
    with dask.config.set(LOCAL_CLUSTER):
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                          dashboard_address=None) as cluster, Client(cluster) as client:
            yield client


def run_sweep(sweep: Sweep, out: Path, client: Client, resume: bool = False,
              progress: bool = True, plot: bool = True) -> Outcome:
    """Run the points of ``sweep`` not yet in ``out``/results.csv (all, without ``resume``) on
    ``client``'s workers; then write results.json and, with ``plot``, the plots. ``out`` is
    locked meanwhile (cosim/folder_lock.py: FolderInUse if another sweep or run writes there)."""
    with folder_lock(out):
        return _run_sweep(sweep, Path(out), client, resume, progress, plot)


def _run_sweep(sweep: Sweep, out: Path, client: Client, resume: bool, progress: bool,
               plot: bool) -> Outcome:
    table = ResultsTable(sweep, out)
    done = table.open(resume)
    todo = deque(i for i, point_id in enumerate(sweep.ids) if point_id not in done)
    outcome = Outcome(len(sweep.points), len(sweep.points) - len(todo), 0, 0, 0, [])
    attempt, index_of, futures = {}, {}, as_completed()
    slots = max(1, sum(client.nthreads().values()))

    def submit() -> None:  # the next points, as many as there are free threads
        while todo and len(index_of) < slots:
            index = todo.popleft()
            attempt[index] = attempt.get(index, 0) + 1
            key = f"point-{sweep.ids[index]}-{attempt[index]}"
            index_of[key] = index
            futures.add(client.submit(run_point, sweep.system, sweep.points[index],
                                      sweep.outputs, key=key, pure=False))

    submit()
    bar = tqdm(total=len(sweep.points), initial=outcome.skipped, unit="point", desc=sweep.path.stem,
               disable=not progress)
    try:
        for future in futures:
            index = index_of.pop(future.key)
            try:
                result = future.result()
            except Exception as exc:  # noqa: BLE001 - whatever the point raised, or KilledWorker
                if attempt[index] < ATTEMPTS:
                    outcome.retried += 1
                    todo.appendleft(index)
                    submit()
                    continue
                table.append(index, None, attempt[index], None, f"{type(exc).__name__}: {exc}")
                outcome.failed += 1
            else:
                table.append(index, result["outputs"], attempt[index], result["wall_time_s"], None)
                outcome.ok += 1
            future.release()
            bar.update(1)
            submit()
    finally:
        bar.close()
        table.close()
    outcome.files = [str(table.path), str(table.write_json())]
    if plot:
        from .plots import plot_outputs
        outcome.files += [str(p) for p in plot_outputs(table.path.with_suffix(".json"), out)]
    return outcome
