"""Fanning tasks out on Dask and collecting their rows.

One Dask task per swarf task, keyed by the task's key; a worker that dies is
Dask's to handle (the scheduler gives its tasks to another worker, up to
``distributed.scheduler.allowed-failures`` times), and an output set is only ever
renamed into place whole (:mod:`swarf.batch.task`), so a retried task leaves one
set. Tasks whose sets are complete are not submitted: a rerun does only the rest.
"""

from __future__ import annotations

import os
import sys
import time
from typing import Any, Callable, Dict, List, Optional, Sequence

from .errors import BatchError
from .results import Results
from .row import frame
from .sweep import Task
from .task import run_task

#: The table's files, beside the output sets.
TABLE_PARQUET = "table.parquet"
TABLE_CSV = "table.csv"


def local_client(n_workers: Optional[int] = None, **kwargs):
    """A ``Client`` on a new ``LocalCluster`` sized to the machine: one
    single-threaded worker process per core (swarf's own threads limited to one
    per worker, so the cores are not oversubscribed)."""
    from dask.distributed import Client, LocalCluster

    n = n_workers or os.cpu_count() or 1
    kwargs.setdefault("threads_per_worker", 1)
    kwargs.setdefault("processes", True)
    kwargs.setdefault("dashboard_address", ":0")
    if kwargs["processes"]:
        kwargs.setdefault("env", {"RAYON_NUM_THREADS": "1"})
    cluster = LocalCluster(n_workers=n, **kwargs)
    return Client(cluster)


class Progress:
    """A progress bar on standard error: redrawn in place on a terminal, a line
    every tenth of the tasks otherwise."""

    def __init__(self, total: int, skipped: int, enabled: bool = True, stream=None):
        self.total, self.skipped, self.done, self.errors = total, skipped, 0, 0
        self.enabled = enabled and total > 0
        self.stream = stream or sys.stderr
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self.start = time.monotonic()
        self.last_line = -1

    def update(self, row: Dict[str, Any]) -> None:
        self.done += 1
        self.errors += row.get("status") != "ok"
        if not self.enabled:
            return
        width = 30
        filled = width * self.done // self.total
        text = (
            f"[{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total} tasks"
            f", {self.errors} errors, {time.monotonic() - self.start:.0f} s"
        )
        if self.tty:
            self.stream.write("\r" + text + ("\n" if self.done == self.total else ""))
            self.stream.flush()
        else:
            step = max(1, self.total // 10)
            if self.done == self.total or self.done // step != self.last_line:
                self.last_line = self.done // step
                print(text, file=self.stream, flush=True)


def _failed_row(task: Task, results: str, exc: BaseException) -> Dict[str, Any]:
    from distributed import KilledWorker

    from .task import _base_row

    row = _base_row(task.to_dict())
    row["status"] = "error"
    if isinstance(exc, KilledWorker):
        row["error"] = (
            "the workers running this task died every time it was tried "
            "(distributed.scheduler.allowed-failures); nothing of it was kept"
        )
    else:
        row["error"] = f"{type(exc).__name__}: {exc}"
    Results(results).write_error(task.key, row)
    return row


def run(
    tasks: Sequence[Task],
    results: str,
    client=None,
    fn: Optional[Callable] = None,
    progress: bool = True,
    plots: bool = True,
    n_workers: Optional[int] = None,
    log: Callable[[str], None] = lambda s: print(s, file=sys.stderr, flush=True),
):
    """Runs ``tasks`` (those without a complete output set) on ``client`` (default:
    :func:`local_client`), writes the table and the plots in ``results`` and
    returns the table as a DataFrame, one row per task, in the tasks' order.

    ``BatchError`` when the results folder is not writable or the client cannot
    be reached; a task that fails is an error row."""
    res = Results(results)
    res.check_writable()
    res.clean_partial()
    rows: Dict[str, Dict[str, Any]] = {}
    todo: List[Task] = []
    seen = set()
    for t in tasks:
        if t.key in seen:
            continue
        seen.add(t.key)
        stored = res.complete_row(t.key)
        if stored is not None:
            rows[t.key] = stored
        else:
            todo.append(t)
    log(f"swarf batch: {len(seen)} tasks, {len(rows)} complete already, {len(todo)} to run")
    if todo:
        own = client is None
        if own:
            client = local_client(n_workers)
        try:
            _run_on(client, todo, results, fn, rows, progress, log)
        finally:
            if own:
                cluster = client.cluster
                client.close()
                cluster.close()
        res.clean_partial()
    ordered = [rows[t.key] for t in tasks]
    names: List[str] = []
    for t in tasks:
        names += [k for k in t.params if k not in names]
    df = frame(ordered, names)
    write_table(res, df)
    if plots:
        from .plots import save_plots

        save_plots(df, res, log)
    errors = int((df["status"] != "ok").sum())
    log(f"swarf batch: table in {res.where}/{TABLE_PARQUET} and {TABLE_CSV}; {errors} error rows")
    return df


def _run_on(client, todo, results, fn, rows, progress, log) -> None:
    from distributed import as_completed

    link = getattr(client, "dashboard_link", None)
    if link:
        log(f"swarf batch: Dask dashboard at {link}")
    bar = Progress(len(todo), len(rows), progress)
    futures = {}
    try:
        for t in todo:
            f = client.submit(run_task, t.to_dict(), results, fn, key=f"swarf-batch-{t.key}", pure=False)
            futures[f] = t
        for f in as_completed(list(futures)):
            t = futures[f]
            try:
                row = f.result()
            except Exception as e:  # the task never returned: its workers died, or Dask failed
                row = _failed_row(t, results, e)
            rows[t.key] = row
            bar.update(row)
            f.release()
    except BaseException:
        for f in futures:
            f.cancel()
        raise


def write_table(res: Results, df) -> None:
    """The table as Parquet and CSV in the results folder, each whole or not at all."""
    res.write_frame(TABLE_PARQUET, lambda buf: df.to_parquet(buf, index=False))
    res.write_frame(TABLE_CSV, lambda buf: buf.write(df.to_csv(index=False).encode()))
