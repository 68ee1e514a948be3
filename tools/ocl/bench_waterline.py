#!/usr/bin/env python3
"""Waterline throughput: swarf against OpenCAMLib's Waterline, same mesh, same level,
same threads, in one run.

Usage: python3 tools/ocl/bench_waterline.py --swarf target/release/swarf \
           --bench target/release/examples/waterline_bench [--work /tmp/swarf-wl]
           [--cases wave-100k,wave-1m] [--ocl-timeout 3600]

Meshes are tessellations of the shared parts written by `swarf tessellate` (binary
STL). Each case runs OpenCAMLib's `Waterline` at 0.1 mm sampling with `setThreads(2)`
at one level (its `run()` is timed) and swarf's waterline at the same level with 2
threads (index, drop field and contour all timed: the whole cost of one level; the
drop field is shared by every further level, so a second level costs only its
contour, printed too). Accuracy: swarf's points are exact contour points and its
chords are refined to 0.01 mm; the Hausdorff distance between the two contours and
the loop counts are printed.
"""

import argparse
import math
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ocl_common  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
PARTS = os.path.join(HERE, "..", "..", "parts")
# name: (part, tessellation tolerance, tool, level as a fraction of the height range)
CASES = {
    "die-80k": ("die", 0.0008, "ball:d=8", 0.5),
    "wave-100k": ("wave", 0.0019, "bull:d=10,r=2", 0.5),
    "wave-1m": ("wave", 0.00018, "bull:d=10,r=2", 0.5),
}
SAMPLING = 0.1
THREADS = 2


def hausdorff(a, b):
    """Largest distance from a point of one set of loops to the other's polylines."""
    import bisect

    def segments(loops):
        segs = []
        for lp in loops:
            for k in range(len(lp)):
                segs.append((lp[k], lp[(k + 1) % len(lp)]))
        segs.sort(key=lambda s: min(s[0][0], s[1][0]))
        return segs

    def one_way(points, loops):
        segs = segments(loops)
        xs = [min(s[0][0], s[1][0]) for s in segs]
        worst = 0.0
        for p in points:
            best, reach = math.inf, 1.0
            while best == math.inf and reach < 1e4:
                lo = bisect.bisect_left(xs, p[0] - reach - 50.0)
                for s in segs[lo:]:
                    if min(s[0][0], s[1][0]) > p[0] + reach:
                        break
                    best = min(best, seg_dist(p, s))
                reach *= 4
            worst = max(worst, best)
        return worst

    pa = [p for lp in a for p in lp]
    pb = [p for lp in b for p in lp]
    return max(one_way(pa, b), one_way(pb, a))


def seg_dist(p, s):
    (ax, ay), (bx, by) = s
    dx, dy = bx - ax, by - ay
    l2 = dx * dx + dy * dy
    t = 0.0 if l2 == 0 else max(0.0, min(1.0, ((p[0] - ax) * dx + (p[1] - ay) * dy) / l2))
    return math.hypot(p[0] - ax - t * dx, p[1] - ay - t * dy)


def run_case(name, args):
    part, tol, tool, frac = CASES[name]
    stl = os.path.join(args.work, f"{name}.stl")
    if not os.path.exists(stl):
        subprocess.run(
            [args.swarf, "tessellate", os.path.join(PARTS, part + ".toml"),
             "--tol", str(tol), "-o", stl], check=True)
    tris = ocl_common.read_stl(stl)
    zs = [p[2] for t in tris for p in t]
    z = round(min(zs) + frac * (max(zs) - min(zs)), 3)
    z2 = round(z - 1.0, 3)
    out = os.path.join(args.work, f"{name}-swarf.csv")
    t0 = time.perf_counter()
    res = subprocess.run(
        [args.bench, stl, tool, "1.0", "0.01", str(THREADS), out, str(z), str(z2)],
        check=True, capture_output=True, text=True)
    swarf_s = time.perf_counter() - t0
    print(res.stdout.strip())
    lines = res.stdout.splitlines()
    prepare = float(lines[0].split("prepare ")[1].split()[0])
    first = float(lines[1].split("seconds ")[1])
    second = float(lines[2].split("seconds ")[1])
    ours = {}
    for line in open(out).read().splitlines()[1:]:
        zz, k, x, y = line.split(",")
        if float(zz) == z:
            ours.setdefault(int(k), []).append((float(x), float(y)))
    ours = list(ours.values())
    t0 = time.perf_counter()
    loops, ocl_s = ocl_common.waterline(tris, tool, z, SAMPLING, threads=THREADS)
    total_ocl = time.perf_counter() - t0
    one_level = prepare + first
    print(f"{name}: {len(tris)} triangles, {tool}, z = {z}")
    print(f"  OpenCAMLib Waterline 0.1 mm: run {ocl_s:.2f} s (with surface {total_ocl:.2f} s), "
          f"{len(loops)} loops, {sum(map(len, loops))} points")
    print(f"  swarf: index + field {prepare:.3f} s, first level {first:.3f} s, "
          f"next level {second:.3f} s (process {swarf_s:.2f} s), {len(ours)} loops, "
          f"{sum(map(len, ours))} points")
    print(f"  ratio one level (index + field + contour): {ocl_s / one_level:.0f}x; "
          f"per further level: {ocl_s / second:.0f}x")
    print(f"  Hausdorff distance {hausdorff(ours, loops):.4f} mm", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--swarf", required=True)
    ap.add_argument("--bench", required=True)
    ap.add_argument("--work", default="/tmp/swarf-wl")
    ap.add_argument("--cases", default="wave-100k,wave-1m")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    for name in args.cases.split(","):
        run_case(name, args)


if __name__ == "__main__":
    main()
