"""Scaling of swarf.batch: the test sweep (python/tests/batch_sweep.py: 252 jobs,
paper 004's strategies on wave, die and a generated mold) planned in a plain loop
in this process, then on a LocalCluster of 1 and of 2 workers; prints the wall
times, the speed-up and the overhead per task (batch wall time x workers minus the
loop's, per task).

    python python/examples/batch_scaling.py [--workers 1,2] [--keep DIR]

The cluster's start is timed apart from the sweep (a long-lived cluster pays it
once).
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from batch_sweep import write_sweep  # noqa: E402

from swarf import batch  # noqa: E402
from swarf.batch.task import run_task  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--workers", default="1,2")
    ap.add_argument("--keep", default=None, help="folder for the inputs and results (default: a temporary one)")
    ap.add_argument("--loop-only", action="store_true", help="time the plain loop only (prints its seconds)")
    args = ap.parse_args()
    root = Path(args.keep or tempfile.mkdtemp(prefix="swarf-batch-scaling-"))
    sweep = write_sweep(root / "in")
    tasks, _ = batch.load_sweep(sweep)
    n = len(tasks)

    t0 = time.perf_counter()
    for t in tasks:
        row = run_task(t.to_dict(), str(root / "loop"))
        assert row["status"] == "ok", row["error"]
    loop = time.perf_counter() - t0
    if args.loop_only:
        print(loop)
        return
    print(f"{n} tasks; plain loop in one process (swarf on every core): {loop:.2f} s ({1000 * loop / n:.0f} ms per task)")
    env = dict(os.environ, RAYON_NUM_THREADS="1")
    one = subprocess.run(
        [sys.executable, __file__, "--loop-only", "--keep", str(root / "loop1")], env=env, capture_output=True, text=True, check=True
    )
    loop1 = float(one.stdout.split()[-1])
    print(f"plain loop, swarf on one core (as each worker): {loop1:.2f} s ({1000 * loop1 / n:.0f} ms per task)")

    for w in (int(x) for x in args.workers.split(",")):
        t0 = time.perf_counter()
        client = batch.local_client(w)
        client.wait_for_workers(w)
        start = time.perf_counter() - t0
        t0 = time.perf_counter()
        df = batch.run_sweep(sweep, root / f"w{w}", client, progress=False, plots=False)
        wall = time.perf_counter() - t0
        cluster = client.cluster
        client.close()
        cluster.close()
        assert (df["status"] == "ok").all()
        busy = df["task_s"].sum()
        overhead = (wall * w - loop1) / n
        print(
            f"{w} worker(s): sweep {wall:.2f} s (cluster start {start:.2f} s), speed-up {loop / wall:.2f}x "
            f"against the loop on every core, {loop1 / wall:.2f}x against the loop on one; tasks busy {busy:.2f} s; "
            f"overhead {1000 * overhead:.1f} ms per task (workers x wall - one-core loop, per task)"
        )
    print(f"results in {root}")


if __name__ == "__main__":
    main()
