#!/usr/bin/env python3
"""Drop-cutter on dense meshes: cost per point against the number of triangles, and
swarf against OpenCAMLib's BatchDropCutter on the 180k-triangle mold, in one run.

Usage: python3 tools/ocl/bench_dense.py --swarf target/release/swarf
           [--peer OTHER_SWARF] [--work /tmp/swarf-dense] [--sizes 10k,100k,1m,4m]
           [--ocl-points 3000] [--no-ocl]

The meshes are the mold of `python/tests/ocl_meshes.py` (a 40 x 30 mm height field:
a pocket with a boss, a gentle wave outside) on square grids fine enough for about
10,082, 100,352, 999,698 and 3,998,792 triangles, written as binary STL. Every mesh
is dropped on the same fixed grid of 481 x 321 = 154,401 points over the mold, by
`swarf drop --threads 2`, for a ball d=8 and a bull d=10 r=2. The cost per point is
the CPU time of the whole grid less that of a one-point run (reading the STL and
building the index), divided by the points; the peak resident memory of the
whole-grid run, and of the one-point run, are printed too. The growth exponent is
the slope of log(cost) against log(triangles) between neighbouring sizes. With
`--peer`, another build of swarf (say, of main) runs the same drops in the same run,
and the table gives its cost and the ratio.

OpenCAMLib: BatchDropCutter with `setThreads(2)` on `--ocl-points` points of the same
grid (every k-th) on the 180k mold (its rate over the whole grid would take an
hour); CPU time per point of its `run()` against swarf's per-point cost on the same
mesh, and the largest height difference where both report contact.
"""

import argparse
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "..", "python", "tests"))
import ocl_common  # noqa: E402
import ocl_meshes  # noqa: E402

THREADS = 2
SPECS = ["ball:d=8", "bull:d=10,r=2"]
#: Grid cells per mm of the mold's square grid, per size (about 10k ... 4M triangles).
SIZES = {"10k": 0.488, "100k": 0.1545, "180k": 0.1155, "1m": 0.049, "4m": 0.0245}
POINTS = (481, 321)


def write_stl(path, tris):
    """Binary STL of an (n, 3, 3) array, normals zero."""
    tris = np.asarray(tris, dtype=np.float32)
    rec = np.zeros(len(tris), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    rec["v"] = tris
    with open(path, "wb") as f:
        f.write(b"swarf dense mold".ljust(80, b" "))
        f.write(np.uint32(len(tris)).tobytes())
        f.write(rec.tobytes())


def mesh(work, size):
    step = SIZES[size]
    path = os.path.join(work, f"mold-{size}.stl")
    if not os.path.exists(path):
        write_stl(path, ocl_meshes.mold(step))
    n = (os.path.getsize(path) - 84) // 50
    return path, n


def points():
    xs = np.linspace(0.0, 40.0, POINTS[0])
    ys = np.linspace(0.0, 30.0, POINTS[1])
    return [(float(x), float(y)) for y in ys for x in xs]


def run(cmd):
    """CPU seconds and peak resident MiB of one child process."""
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, ru = os.wait4(p.pid, 0)
    err = p.stderr.read().decode()
    if status != 0:
        raise SystemExit(f"{' '.join(cmd)} failed:\n{err}")
    return ru.ru_utime + ru.ru_stime, ru.ru_maxrss / 1024, time.perf_counter() - t0


def swarf_drop(swarf, stl, spec, pts_csv, out_csv):
    return run([swarf, "drop", "--mesh", stl, "--tool", spec, "--points", pts_csv,
                "-o", out_csv, "--threads", str(THREADS)])


def ocl_compare(stl, spec, sub, ours):
    tris = ocl_common.read_stl(stl)
    surf = ocl_common.surface(tris)
    cut = ocl_common.cutter(spec)
    bdc = ocl_common.ocl.BatchDropCutter()
    bdc.setSTL(surf)
    bdc.setCutter(cut)
    bdc.setThreads(THREADS)
    for x, y in sub:
        bdc.appendPoint(ocl_common.ocl.CLPoint(x, y, ocl_common.FLOOR))
    c0 = time.process_time()
    bdc.run()
    cpu = time.process_time() - c0
    theirs = [None if str(p.getCC().type) == "NONE" else p.z for p in bdc.getCLPoints()]
    diffs = [abs(a - b) for a, b in zip(ours, theirs) if a is not None and b is not None]
    del bdc, cut, surf
    return cpu / len(sub), max(diffs), len(diffs)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--swarf", required=True)
    ap.add_argument("--work", default="/tmp/swarf-dense")
    ap.add_argument("--sizes", default="10k,100k,1m,4m")
    ap.add_argument("--ocl-points", type=int, default=3000)
    ap.add_argument("--no-ocl", action="store_true")
    ap.add_argument("--peer", help="another swarf binary to run the same drops")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    pts = points()
    grid_csv = os.path.join(args.work, "grid.csv")
    one_csv = os.path.join(args.work, "one.csv")
    ocl_common.write_points(grid_csv, pts)
    ocl_common.write_points(one_csv, pts[len(pts) // 2: len(pts) // 2 + 1])
    print(f"{len(pts)} points, {THREADS} threads")
    print("| triangles | tool | us/point | exponent | one-point run s | peak MiB (grid, one point) | peer us/point, MiB | peer / this |")
    print("|---|---|---|---|---|---|---|---|")
    last = {}
    for size in args.sizes.split(","):
        stl, n = mesh(args.work, size)
        for spec in SPECS:
            cpu1, mem1, _ = swarf_drop(args.swarf, stl, spec, one_csv, one_csv + ".out")
            cpu, mem, _ = swarf_drop(args.swarf, stl, spec, grid_csv, grid_csv + ".out")
            us = 1e6 * max(cpu - cpu1, 0.0) / len(pts)
            exp = ""
            if spec in last:
                n0, us0 = last[spec]
                exp = f"{np.log(us / us0) / np.log(n / n0):.2f}"
            last[spec] = (n, us)
            peer = " | "
            if args.peer:
                p1, _, _ = swarf_drop(args.peer, stl, spec, one_csv, one_csv + ".peer")
                p, pmem, _ = swarf_drop(args.peer, stl, spec, grid_csv, grid_csv + ".peer")
                pus = 1e6 * max(p - p1, 0.0) / len(pts)
                same = ocl_common.read_z(grid_csv + ".peer") == ocl_common.read_z(grid_csv + ".out")
                peer = f"{pus:.2f}, {pmem:.0f} | {pus / us:.1f}{'' if same else ' (heights differ)'}"
            print(f"| {n:,} | {spec} | {us:.2f} | {exp} | {cpu1:.2f} | {mem:.0f}, {mem1:.0f} | {peer} |", flush=True)
    if args.no_ocl:
        return
    stl, n = mesh(args.work, "180k")
    k = max(1, len(pts) // args.ocl_points)
    sub = pts[::k]
    sub_csv = os.path.join(args.work, "sub.csv")
    ocl_common.write_points(sub_csv, sub)
    for spec in SPECS:
        cpu1, _, _ = swarf_drop(args.swarf, stl, spec, one_csv, one_csv + ".out")
        cpu, _, _ = swarf_drop(args.swarf, stl, spec, grid_csv, grid_csv + ".out")
        ours_us = 1e6 * max(cpu - cpu1, 1e-9) / len(pts)
        swarf_drop(args.swarf, stl, spec, sub_csv, sub_csv + ".out")
        ocl_s, diff, both = ocl_compare(stl, spec, sub, ocl_common.read_z(sub_csv + ".out"))
        print(f"\n{spec} on the mold ({n:,} triangles): swarf {ours_us:.2f} us/point (whole grid), "
              f"OpenCAMLib {1e6 * ocl_s:,.0f} us/point on {len(sub)} points: "
              f"{1e6 * ocl_s / ours_us:,.0f}x; max |dz| {diff:.3g} mm over {both} points", flush=True)


if __name__ == "__main__":
    main()
