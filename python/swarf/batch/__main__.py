"""``python -m swarf.batch SWEEP.toml --scheduler ADDRESS|local --out DIR``: the
``swarf batch`` command (the Rust command line runs this). Exit status 0 when every
task has a row and none failed, 1 when some rows are errors or the input is bad,
130 when interrupted (a rerun does the unfinished tasks)."""

from __future__ import annotations

import argparse
import sys


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        prog="swarf batch",
        description="Plan or compare the jobs of a sweep on Dask and write their table (Parquet, CSV) and plots.",
    )
    ap.add_argument("sweep", help="the sweep file (TOML: [batch], jobs, [base], [sweep])")
    ap.add_argument("--scheduler", default="local", help="a Dask scheduler address (tcp://host:8786), or `local` (a LocalCluster on this machine)")
    ap.add_argument("--out", "-o", required=True, help="the results folder (a path or an fsspec URL the workers can reach)")
    ap.add_argument("--max-tasks", type=int, default=None, help="run a sweep of up to this many tasks (default: the sweep's max_tasks, else 1000)")
    ap.add_argument("--workers", type=int, default=None, help="workers of the local cluster (default: one per core)")
    ap.add_argument("--no-plots", action="store_true", help="write the table only")
    ap.add_argument("--quiet", action="store_true", help="no progress bar")
    args = ap.parse_args(argv)
    try:
        return _run(args)
    except KeyboardInterrupt:
        print("swarf batch: interrupted; the finished tasks are kept, a rerun does the rest", file=sys.stderr)
        return 130


def _run(args) -> int:
    try:
        import dask.distributed  # noqa: F401
        import pandas  # noqa: F401
        import pyarrow  # noqa: F401
    except ImportError as e:
        print(
            f"swarf batch: error: the Python module `{e.name}` is missing; install the batch extra: pip install 'swarf[batch]' "
            "(dask[distributed], pandas, pyarrow, matplotlib, fsspec)",
            file=sys.stderr,
        )
        return 1
    from . import BatchError, load_sweep
    from .engine import run

    if args.max_tasks is not None and args.max_tasks < 1:
        print("swarf batch: error: --max-tasks is a whole number of tasks, at least 1", file=sys.stderr)
        return 1
    try:
        tasks, _ = load_sweep(args.sweep, args.max_tasks)
        client = None if args.scheduler == "local" else _connect(args.scheduler)
        try:
            df = run(tasks, args.out, client=client, progress=not args.quiet, plots=not args.no_plots, n_workers=args.workers)
        finally:
            if client is not None:
                client.close()
    except BatchError as e:
        print(f"swarf batch: error: {e}", file=sys.stderr)
        return 1
    errors = df[df["status"] != "ok"]
    for _, r in errors.head(10).iterrows():
        print(f"swarf batch: task {r['label']}: {r['error']}", file=sys.stderr)
    if len(errors):
        print(f"swarf batch: error: {len(errors)} of {len(df)} tasks failed (their rows hold the messages)", file=sys.stderr)
        return 1
    return 0


def _connect(address: str):
    from dask.distributed import Client

    from . import BatchError

    try:
        return Client(address, timeout="20s")
    except (OSError, TimeoutError, ValueError) as e:
        raise BatchError(f"--scheduler {address}: cannot reach a Dask scheduler there ({e})") from None


if __name__ == "__main__":
    sys.exit(main())
