#!/usr/bin/env python3
"""Drop-cutter throughput: swarf against OpenCAMLib, same mesh, same points, 2 threads.

Usage: python3 tools/ocl/bench_drop.py --swarf target/release/swarf [--work /tmp/swarf-bench]
           [--ocl-points 3000]

Cases (the issue's): ball d=8 on die.toml tessellated to about 80,000 triangles, and
bull d=10 r=2 on wave.toml tessellated to about 180,000 triangles, each over a 0.5 mm
grid of points covering the mesh's XY box. swarf drops the whole grid and the subset
OpenCAMLib runs on (every k-th grid point, `--ocl-points` of them: at OpenCAMLib's
rate the whole grid would take an hour); OpenCAMLib's `BatchDropCutter` runs that
subset with `setThreads(2)`. Wall-clock rates cover the drops only (OpenCAMLib's
`run()`, swarf's parallel drop loop as it reports it on stderr), not reading the mesh
or building the search structures, which are printed separately. On a shared
machine wall-clock rates move with the load, so CPU time per point is printed too
(swarf's run minus a run with no points, i.e. without reading, indexing and
writing; OpenCAMLib's `run()`), and its ratio is the steadier figure. The heights of the two are compared where both report
contact.
"""

import argparse
import os
import re
import resource
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ocl_common  # noqa: E402

CASES = [
    ("die", 0.0008, "ball:d=8"),
    ("wave", 0.001, "bull:d=10,r=2"),
]
STEP = 0.5
THREADS = 2


def grid(tris):
    xs = [p[0] for t in tris for p in t]
    ys = [p[1] for t in tris for p in t]
    x0, y0, x1, y1 = min(xs), min(ys), max(xs), max(ys)
    nx, ny = int((x1 - x0) / STEP) + 1, int((y1 - y0) / STEP) + 1
    return [(x0 + i * STEP, y0 + j * STEP) for j in range(ny) for i in range(nx)]


def child_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_swarf(swarf, stl, spec, pts_csv, out_csv):
    """Drop rate from swarf's own report, and the CPU seconds of the whole run
    (reading, index, drops, writing)."""
    cmd = [swarf, "drop", "--mesh", stl, "--tool", spec, "--points", pts_csv,
           "-o", out_csv, "--threads", str(THREADS)]
    before = child_cpu()
    err = subprocess.run(cmd, check=True, capture_output=True, text=True).stderr
    cpu = child_cpu() - before
    rate = float(re.search(r"([0-9.]+) points/s", err).group(1))
    return rate, cpu, err.strip()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--swarf", required=True)
    ap.add_argument("--work", default="/tmp/swarf-bench")
    ap.add_argument("--ocl-points", type=int, default=3000)
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    print(f"OpenCAMLib {ocl_common.ocl.version()}, {THREADS} threads, grid {STEP} mm")
    for part, tol, spec in CASES:
        stl = os.path.join(args.work, f"{part}-{tol}.stl")
        if not os.path.exists(stl):
            subprocess.run([args.swarf, "tessellate", part, "--tol", str(tol), "-o", stl], check=True)
        tris = ocl_common.read_stl(stl)
        pts = grid(tris)
        k = max(1, len(pts) // args.ocl_points)
        sub = pts[::k]
        full_csv = os.path.join(args.work, f"{part}-grid.csv")
        sub_csv = os.path.join(args.work, f"{part}-sub.csv")
        ocl_common.write_points(full_csv, pts)
        ocl_common.write_points(sub_csv, sub)
        none_csv = os.path.join(args.work, "no-points.csv")
        ocl_common.write_points(none_csv, [])
        _, cpu_fixed, _ = run_swarf(args.swarf, stl, spec, none_csv, none_csv + ".out")
        rate_full, cpu_full, log = run_swarf(args.swarf, stl, spec, full_csv, full_csv + ".out")
        rate_sub, cpu_sub, _ = run_swarf(args.swarf, stl, spec, sub_csv, sub_csv + ".out")
        cpu_full = max(cpu_full - cpu_fixed, 1e-9)
        cpu_sub = max(cpu_sub - cpu_fixed, 1e-9)
        t0 = time.perf_counter()
        surf = ocl_common.surface(tris)
        t1 = time.perf_counter()
        cut = ocl_common.cutter(spec)
        bdc = ocl_common.ocl.BatchDropCutter()
        bdc.setSTL(surf)
        bdc.setCutter(cut)
        bdc.setThreads(THREADS)
        for x, y in sub:
            bdc.appendPoint(ocl_common.ocl.CLPoint(x, y, ocl_common.FLOOR))
        t2 = time.perf_counter()
        c2 = time.process_time()
        bdc.run()
        t3 = time.perf_counter()
        ocl_cpu = time.process_time() - c2
        theirs = [None if str(p.getCC().type) == "NONE" else p.z for p in bdc.getCLPoints()]
        ours = ocl_common.read_z(sub_csv + ".out")
        diffs = [abs(a - b) for a, b in zip(ours, theirs) if a is not None and b is not None]
        contact_mismatch = sum(1 for a, b in zip(ours, theirs) if (a is None) != (b is None))
        ocl_rate = len(sub) / (t3 - t2)
        print(f"\n{spec} on {part} ({len(tris)} triangles), {len(pts)} grid points")
        print(f"  swarf: {log}")
        print(f"  swarf, whole grid: {rate_full:,.0f} points/s; on OpenCAMLib's {len(sub)} points: {rate_sub:,.0f} points/s")
        print(f"  OpenCAMLib: {ocl_rate:,.1f} points/s on {len(sub)} points "
              f"(run {t3 - t2:.2f} s; surface {t1 - t0:.2f} s, setup {t2 - t1:.2f} s)")
        print(f"  ratio swarf/OpenCAMLib: {rate_full / ocl_rate:,.0f}x (whole grid), {rate_sub / ocl_rate:,.0f}x (same points)")
        print(f"  CPU time per point: swarf {1e6 * cpu_full / len(pts):.2f} us (whole grid), "
              f"{1e6 * cpu_sub / len(sub):.2f} us (OpenCAMLib's points); OpenCAMLib "
              f"{1e6 * ocl_cpu / len(sub):,.0f} us: ratio {ocl_cpu / len(sub) / (cpu_full / len(pts)):,.0f}x "
              f"and {ocl_cpu / len(sub) / (cpu_sub / len(sub)):,.0f}x")
        print(f"  heights: max |difference| {max(diffs):.3g} mm over {len(diffs)} points, "
              f"{contact_mismatch} contact mismatches")
        del bdc, cut, surf


if __name__ == "__main__":
    main()
