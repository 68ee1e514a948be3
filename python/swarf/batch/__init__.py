"""Studies and shop-wide verification on Dask: many jobs planned, verified or
compared at once, on a laptop's cores or a cluster, collected as one table.

- :func:`plan_many`: plan each job (``swarf plan``: the program verified on the
  stock by the gate unless ``gate=False``);
- :func:`compare_many`: plan each job and verify its program on the part (paper
  004's Table 1: time, length, scallop range, gouge and excess);
- :func:`verify_many`: verify programs (``swarf verify``), one task per program
  set;
- :func:`map_jobs`: any function of a job, with the same outputs, keys and rows;
- :func:`load_sweep`, :func:`run_sweep`: a sweep file (``swarf batch``).

Jobs are files, TOML texts, dicts or ``swarf.Job``s, or a sweep: ``{"base": job,
"sweep": {"strategy.scallop": [...], ...}}`` (a cross product; a list of such
tables is concatenated). One Dask task per job; each writes its output set whole
under ``results`` (a local folder or an fsspec URL) and returns a row; the table
(one row per task, in order; a failed task is a row with its error) is written as
``table.parquet`` and ``table.csv`` with the plots, and returned as a DataFrame.
A rerun skips every task whose output set is complete. Dask, pandas, pyarrow and
matplotlib come with ``pip install swarf[batch]``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Callable, Dict, Iterable, List, Optional, Union

from .errors import BatchError
from .sweep import DEFAULT_MAX_TASKS, MODES, Task, check_limit, check_verify_options, count, job_table, load_toml, make_tasks, sweep_entries

__all__ = [
    "BatchError",
    "DEFAULT_MAX_TASKS",
    "compare_many",
    "load_sweep",
    "local_client",
    "map_jobs",
    "plan_many",
    "run_sweep",
    "tasks_of",
    "verify_many",
]


def _version() -> str:
    import swarf

    return swarf.__version__


def local_client(n_workers: Optional[int] = None, **kwargs):
    """A ``dask.distributed.Client`` on a new ``LocalCluster``: ``n_workers``
    single-threaded worker processes (default: one per core)."""
    from .engine import local_client as make

    return make(n_workers, **kwargs)


def tasks_of(jobs: Any, mode: str = "plan", options: Optional[Dict[str, Any]] = None, max_tasks: Optional[int] = None) -> List[Task]:
    """The tasks of ``jobs``: a list of jobs (files, TOML texts, dicts, ``swarf.Job``)
    or a sweep spec (a dict with ``base`` and ``sweep``), each with its key.
    ``BatchError`` naming the job or key for bad input, or when a sweep expands to
    more than ``max_tasks`` (default :data:`DEFAULT_MAX_TASKS`)."""
    if mode not in MODES:
        raise BatchError(f"mode `{mode}` is not one of {', '.join(MODES)}")
    if isinstance(jobs, dict) and ("sweep" in jobs or "base" in jobs or "jobs" in jobs):
        entries = sweep_entries(jobs, Path.cwd(), "the sweep", max_tasks)
    else:
        if isinstance(jobs, (str, dict)) or hasattr(jobs, "toml"):
            jobs = [jobs]
        jobs = list(jobs)
        check_limit(len(jobs), max_tasks, "the job list")
        entries = []
        for i, j in enumerate(jobs):
            table, base = job_table(j, f"jobs[{i}]")
            label = str(j) if not isinstance(j, (dict, str)) or (isinstance(j, str) and "\n" not in j) else f"jobs[{i}]"
            entries.append((table, base, {}, {}, label))
    return make_tasks(entries, mode, dict(options or {}), _version())


def _run(tasks, results, client, fn, progress, plots):
    from .engine import run

    return run(tasks, str(results), client=client, fn=fn, progress=progress, plots=plots)


def plan_many(
    jobs: Any,
    results: Union[str, Path],
    client=None,
    *,
    gate: bool = True,
    allow_unsafe: bool = False,
    max_tasks: Optional[int] = None,
    progress: bool = True,
    plots: bool = True,
):
    """Plans every job as ``swarf plan`` does (``gate=False``: ``--no-verify``;
    ``allow_unsafe``: ``--allow-unsafe``) on ``client`` (default: a
    :func:`local_client`). Output set of a task: ``job.toml``, ``program.ngc``,
    ``summary.json``, the plan record and what the job's ``[output]`` asks for.
    Returns the table (a pandas DataFrame)."""
    opts = {"gate": gate, "allow_unsafe": allow_unsafe}
    return _run(tasks_of(jobs, "plan", opts, max_tasks), results, client, None, progress, plots)


def compare_many(
    jobs: Any,
    results: Union[str, Path],
    client=None,
    *,
    verify: Optional[Dict[str, Any]] = None,
    gate: bool = True,
    max_tasks: Optional[int] = None,
    progress: bool = True,
    plots: bool = True,
):
    """Plans every job and verifies its program on the part (``swarf verify`` with
    the keyword arguments ``verify``, e.g. ``{"cell": 0.5}``; the tool and scallop
    from the plan record): the plan's figures, the scallop range, gouge and excess.
    The verification is in the output set's ``verify/`` (with ``deviation.npy``)."""
    opts = {"gate": gate, "verify": dict(verify or {})}
    return _run(tasks_of(jobs, "compare", opts, max_tasks), results, client, None, progress, plots)


def verify_many(
    programs: Iterable[Dict[str, Any]],
    results: Union[str, Path],
    client=None,
    *,
    max_tasks: Optional[int] = None,
    progress: bool = True,
    plots: bool = True,
    **verify: Any,
):
    """Verifies programs as ``swarf verify`` does: each item a dict with ``part``,
    ``program`` (a path or a list run in order on one stock), optionally ``tool``
    and any keyword of :func:`swarf.verify`; ``verify`` gives keywords for all."""
    items = list(programs)
    for i, p in enumerate(items):
        if not isinstance(p, dict) or "part" not in p or "program" not in p:
            raise BatchError(f"programs[{i}]: a dict with `part` and `program` (and optionally `tool`), not {p!r}")
        check_verify_options({k: v for k, v in p.items() if k not in ("part", "program", "tool")}, f"programs[{i}]")
    entries = [(dict(p), Path.cwd(), {}, {}, str(p["program"])) for p in items]
    check_limit(len(entries), max_tasks, "the program list")
    tasks = make_tasks(entries, "verify", {"verify": verify}, _version())
    return _run(tasks, results, client, None, progress, plots)


def map_jobs(
    fn: Callable[[Dict[str, Any], Path], Optional[Dict[str, Any]]],
    jobs: Any,
    results: Union[str, Path],
    client=None,
    *,
    max_tasks: Optional[int] = None,
    progress: bool = True,
    plots: bool = False,
):
    """Runs ``fn(task, folder)`` for every job: ``task`` is the task as a dict
    (``job``, ``params``, ``key``, ...), ``folder`` the empty local folder of its
    output set; the dict it returns joins the task's row (keys of the table's
    columns). The output set is kept whole or not at all, as for the others; the
    key includes ``fn``'s module and name, so two functions never share outputs."""
    name = f"{getattr(fn, '__module__', '?')}.{getattr(fn, '__qualname__', repr(fn))}"
    tasks = tasks_of(jobs, "plan", {"fn": name}, max_tasks)
    return _run(tasks, results, client, fn, progress, plots)


def load_sweep(path: Union[str, Path], max_tasks: Optional[int] = None):
    """The tasks and settings of a sweep file (TOML: ``[batch]`` with ``mode``,
    ``max_tasks``, ``gate``, ``[batch.verify]``; ``jobs``; ``[base]`` and
    ``[sweep]`` or ``[[sweep]]``). Returns ``(tasks, batch_table)``."""
    path = Path(path)
    if not path.is_file():
        raise BatchError(f"{path}: the sweep file does not exist")
    spec = load_toml(path)
    batch = spec.get("batch", {})
    if not isinstance(batch, dict):
        raise BatchError(f"{path}: [batch] is a table")
    known = {"mode", "max_tasks", "gate", "allow_unsafe", "verify"}
    for k in batch:
        if k not in known:
            raise BatchError(f"{path}: [batch] has no field `{k}` (known: {', '.join(sorted(known))})")
    mode = batch.get("mode", "plan")
    if mode not in ("plan", "compare"):
        raise BatchError(f"{path}: [batch] mode = `{mode}`: a sweep file plans (\"plan\") or compares (\"compare\") jobs")
    if "max_tasks" in batch and (not isinstance(batch["max_tasks"], int) or batch["max_tasks"] < 1):
        raise BatchError(f"{path}: [batch] max_tasks is a whole number of tasks, at least 1")
    verify = batch.get("verify", {})
    if not isinstance(verify, dict):
        raise BatchError(f"{path}: [batch.verify] is a table of swarf.verify keywords (cell, stock, tol, ...)")
    check_verify_options(verify, f"{path}: [batch.verify]")
    opts = {"gate": bool(batch.get("gate", True)), "allow_unsafe": bool(batch.get("allow_unsafe", False)), "verify": verify}
    entries = sweep_entries(spec, path.resolve().parent, str(path), max_tasks)
    return make_tasks(entries, mode, opts, _version()), batch


def run_sweep(path: Union[str, Path], results: Union[str, Path], client=None, *, max_tasks: Optional[int] = None, progress: bool = True, plots: bool = True):
    """Runs a sweep file (:func:`load_sweep`) into ``results``; the table."""
    tasks, _ = load_sweep(path, max_tasks)
    return _run(tasks, results, client, None, progress, plots)
