#!/usr/bin/env python3
"""swarf.ocl against OpenCAMLib through the same OpenCAMLib calls: one workload,
written once against the API, run with each module in one run, 2 threads.

- BatchDropCutter: ball d=8 on the die tessellated within 0.005 mm, a grid of points;
- PathDropCutter: a raster of lines across the mold-like height field of the tests
  (0.25 mm cells), one PathDropCutter reused line after line (setPath, run,
  getCLPoints) as FreeCAD's 3D Surface does, 0.1 mm sampling, bull d=6 r=1;
- AdaptivePathDropCutter: the same lines, sampling 0.4, min sampling 0.02;
- Waterline: ball d=6 on the mold at 1 mm cells (OpenCAMLib's waterline takes
  minutes on the finer one) at three levels, 0.1 mm sampling, each level a reset,
  setZ, run, getLoops;
- AdaptiveWaterline: the same mesh, one level, sampling 0.1, min sampling 0.02.

Times cover the calls (building the surface with addTriangle is timed apart); the
heights of the drop workloads are compared where both touch.

Usage: python3 examples/ocl_api_bench.py [--quick]  (needs opencamlib==2023.1.11)
"""

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from ocl_meshes import die, mold, surface  # noqa: E402


def clock(f):
    t = time.perf_counter()
    out = f()
    return out, time.perf_counter() - t


def batch(lib, s, pts):
    c = lib.BallCutter(8, 40)
    b = lib.BatchDropCutter()
    b.setSTL(s)
    b.setCutter(c)
    b.setThreads(2)
    for x, y in pts:
        b.appendPoint(lib.CLPoint(x, y, -100))
    b.run()
    return np.array([p.z for p in b.getCLPoints()])


def lines(lib, s, n, adaptive):
    c = lib.BullCutter(6, 1, 40)
    d = lib.AdaptivePathDropCutter() if adaptive else lib.PathDropCutter()
    d.setSTL(s)
    d.setCutter(c)
    if adaptive:
        d.setSampling(0.4)
        d.setMinSampling(0.02)
    else:
        d.setSampling(0.1)
        d.setZ(-10)
    out = []
    for y in np.linspace(0.5, 29.5, n):
        p = lib.Path()
        p.append(lib.Line(lib.Point(-2, float(y), 0), lib.Point(42, float(y), 0)))
        d.setPath(p)
        d.run()
        out.extend(q.z for q in d.getCLPoints())
    return np.array(out)


def waterline(lib, s, levels, adaptive):
    c = lib.BallCutter(6, 40)
    w = lib.AdaptiveWaterline() if adaptive else lib.Waterline()
    w.setSTL(s)
    w.setCutter(c)
    w.setSampling(0.1)
    w.setThreads(2)
    if adaptive:
        w.setMinSampling(0.02)
    points = 0
    for z in levels:
        w.reset()
        w.setZ(z)
        w.run()
        points += sum(len(lp) for lp in w.getLoops())
    return points


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="coarser meshes, fewer points")
    args = ap.parse_args()
    import opencamlib
    import swarf.ocl

    libs = {"OpenCAMLib": opencamlib.ocl, "swarf.ocl": swarf.ocl}
    d_tris = die(0.02 if args.quick else 0.005)
    m_tris = mold(0.5 if args.quick else 0.25)
    w_tris = mold(2.0 if args.quick else 1.0)
    (x0, y0, _), (x1, y1, _) = d_tris.reshape(-1, 3).min(0), d_tris.reshape(-1, 3).max(0)
    k = 30 if args.quick else 70
    gx, gy = np.meshgrid(np.linspace(x0, x1, k), np.linspace(y0, y1, k))
    pts = np.column_stack([gx.ravel(), gy.ravel()]).tolist()
    n_lines = 10 if args.quick else 30
    print(f"OpenCAMLib {opencamlib.ocl.version()}, swarf.ocl {swarf.ocl.version()}; die {len(d_tris)} triangles, "
          f"mold {len(m_tris)} triangles")
    rows = []
    for name, tris, work in [
        (f"BatchDropCutter, {len(pts)} points on the die", d_tris, lambda L, s: batch(L, s, pts)),
        (f"PathDropCutter, {n_lines} lines on the mold", m_tris, lambda L, s: lines(L, s, n_lines, False)),
        (f"AdaptivePathDropCutter, {n_lines} lines on the mold", m_tris, lambda L, s: lines(L, s, n_lines, True)),
        (f"Waterline, 3 levels on the mold ({len(w_tris)} triangles)", w_tris,
         lambda L, s: waterline(L, s, [6.0, 8.5, 10.2], False)),
        (f"AdaptiveWaterline, 1 level on the mold ({len(w_tris)} triangles)", w_tris,
         lambda L, s: waterline(L, s, [8.5], True)),
    ]:
        out, secs, build = {}, {}, {}
        for label, lib in libs.items():
            s, build[label] = clock(lambda: surface(lib, tris))
            out[label], secs[label] = clock(lambda: work(lib, s))
        a, b = out["OpenCAMLib"], out["swarf.ocl"]
        agree = f"max |dz| {np.abs(a - b).max():.1e} mm" if isinstance(a, np.ndarray) else f"{a} and {b} loop points"
        ratio = secs["OpenCAMLib"] / secs["swarf.ocl"]
        rows.append((name, secs["OpenCAMLib"], secs["swarf.ocl"], ratio, agree, build))
        print(f"{name}: OpenCAMLib {secs['OpenCAMLib']:.3f} s, swarf.ocl {secs['swarf.ocl']:.3f} s: {ratio:,.1f}x "
              f"({agree}; addTriangle loop {build['OpenCAMLib']:.2f} s and {build['swarf.ocl']:.2f} s)")
    print("\n| workload | OpenCAMLib | swarf.ocl | ratio |\n|---|---|---|---|")
    for name, t, o, r, _, _ in rows:
        print(f"| {name} | {t:.2f} s | {o:.3f} s | {r:,.1f}x |")


if __name__ == "__main__":
    main()
