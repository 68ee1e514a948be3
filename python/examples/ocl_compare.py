#!/usr/bin/env python3
"""Drop-cutter from Python: swarf against OpenCAMLib, same mesh, same points, same threads.

The comparison of tools/ocl/bench_drop.py, run through the two Python APIs: ball d=8
on die.toml tessellated to about 80,000 triangles and bull d=10 r=2 on wave.toml
tessellated to about 180,000 triangles, over a 0.5 mm grid of points covering the
mesh's XY box. swarf drops the whole grid (one call, an (N, 2) array in, an (N,)
array out); OpenCAMLib's BatchDropCutter runs every k-th point of it (about
--ocl-points: at its rate the whole grid would take an hour), on a surface built
with STLSurf.addTriangle from the very same float64 triangles. Rates cover the drops
only (swarf's call; OpenCAMLib's run()), not building the surfaces. Heights are
compared where both touch the mesh. Last, the Python boundary: a call's time beyond its
drops (Dropper._drop_timed times both within one call), best of three, by the
process's CPU time (steady when other work shares the machine) and wall time.

Usage: python3 examples/ocl_compare.py [--ocl-points 3000] [--threads 2] [--quick]
(needs `pip install opencamlib==2023.1.11`; --quick uses coarser meshes).
"""

import argparse
import math
import time

import numpy as np

import swarf

CASES = [("die", 0.0008, "ball:d=8"), ("wave", 0.001, "bull:d=10,r=2")]
QUICK = [("die", 0.01, "ball:d=8"), ("wave", 0.02, "bull:d=10,r=2")]
STEP = 0.5


def ocl_cutter(ocl, spec):
    tool = swarf.Tool(spec)
    shape, _, rest = tool.spec.partition(":")
    p = {k: float(v) for k, v in (item.split("=") for item in rest.split(","))}
    if shape == "ball":
        return ocl.BallCutter(p["d"], 100.0)
    if shape == "flat":
        return ocl.CylCutter(p["d"], 100.0)
    if shape == "bull":
        return ocl.BullCutter(p["d"], p["r"], 100.0)
    raise ValueError(f"no OpenCAMLib cutter for {spec} here")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ocl-points", type=int, default=3000)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    import opencamlib as ocl

    print(f"swarf {swarf.__version__}, OpenCAMLib {ocl.version()}, {args.threads} threads, grid {STEP} mm")
    for part, tol, spec in QUICK if args.quick else CASES:
        mesh = swarf.Part.load(f"builtin:{part}").tessellate(tol)
        (x0, y0, _), (x1, y1, _) = mesh.bounds()
        xs = np.arange(x0, x1 + 1e-9, STEP)
        ys = np.arange(y0, y1 + 1e-9, STEP)
        gx, gy = np.meshgrid(xs, ys)
        grid = np.column_stack([gx.ravel(), gy.ravel()])
        k = max(1, len(grid) // args.ocl_points)
        sub = np.ascontiguousarray(grid[::k])

        t = time.perf_counter()
        dropper = swarf.Dropper(mesh, spec)
        index_s = time.perf_counter() - t
        t = time.perf_counter()
        z_grid = dropper.drop(grid, threads=args.threads)
        grid_s = time.perf_counter() - t
        t = time.perf_counter()
        z_sub = dropper.drop(sub, threads=args.threads)
        sub_s = time.perf_counter() - t

        t = time.perf_counter()
        surf = ocl.STLSurf()
        for a, b, c in mesh.vertices[mesh.faces]:
            surf.addTriangle(ocl.Triangle(ocl.Point(*a), ocl.Point(*b), ocl.Point(*c)))
        surf_s = time.perf_counter() - t
        cutter = ocl_cutter(ocl, spec)
        bdc = ocl.BatchDropCutter()
        bdc.setSTL(surf)
        bdc.setCutter(cutter)
        bdc.setThreads(args.threads)
        for x, y in sub:
            bdc.appendPoint(ocl.CLPoint(float(x), float(y), -1.0e4))
        t = time.perf_counter()
        bdc.run()
        ocl_s = time.perf_counter() - t
        theirs = np.array([math.nan if str(p.getCC().type) == "NONE" else p.z for p in bdc.getCLPoints()])
        del bdc, cutter

        both = ~np.isnan(z_sub) & ~np.isnan(theirs)
        mismatch = int(np.sum(np.isnan(z_sub) != np.isnan(theirs)))
        worst = float(np.max(np.abs(z_sub[both] - theirs[both]))) if both.any() else 0.0
        rate_grid, rate_sub, rate_ocl = len(grid) / grid_s, len(sub) / sub_s, len(sub) / ocl_s
        runs = [_boundary(dropper, grid, args.threads) for _ in range(3)]
        cost_cpu, cost_wall, drops_cpu = min(runs)
        print(f"\n{spec} on {part} ({len(mesh)} triangles), {len(grid)} grid points "
              f"({int(np.sum(~np.isnan(z_grid)))} with contact)")
        print(f"  swarf: whole grid {rate_grid:,.0f} points/s ({grid_s:.3f} s); on OpenCAMLib's "
              f"{len(sub)} points {rate_sub:,.0f} points/s (index {index_s:.3f} s)")
        print(f"  OpenCAMLib: {rate_ocl:,.1f} points/s on {len(sub)} points (run {ocl_s:.2f} s, surface {surf_s:.2f} s)")
        print(f"  ratio swarf/OpenCAMLib: {rate_grid / rate_ocl:,.0f}x (whole grid), {rate_sub / rate_ocl:,.0f}x (same points)")
        print(f"  heights: max |difference| {worst:.3g} mm over {int(both.sum())} points, {mismatch} contact mismatches")
        print(f"  Python boundary, whole grid: drops {drops_cpu:.3f} s CPU; the call beyond them "
              f"{100 * cost_cpu:.2f} % CPU, {100 * cost_wall:+.2f} % wall")


def _boundary(dropper, pts, threads):
    """One call's cost beyond its drops, as fractions of the drops' CPU and wall time,
    and the drops' CPU seconds (CPU: the process's, all threads)."""
    cpu, wall = time.process_time(), time.perf_counter()
    _, (inner_wall, inner_cpu) = dropper._drop_timed(pts, threads=threads)
    outer_wall, outer_cpu = time.perf_counter() - wall, time.process_time() - cpu
    return (outer_cpu - inner_cpu) / inner_cpu, (outer_wall - inner_wall) / inner_wall, inner_cpu


if __name__ == "__main__":
    main()
