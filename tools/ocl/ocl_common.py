"""Shared helpers for driving OpenCAMLib (pip package `opencamlib`, 2023.1.11).

Only OpenCAMLib's public Python API is used; no OpenCAMLib code is copied.

- `read_stl(path)`: triangles of a binary or ASCII STL, as float tuples (OpenCAMLib's
  own STLReader crashes on binary STL, so the surface is built with
  `STLSurf.addTriangle`).
- `cutter(spec)`: an OpenCAMLib cutter from a swarf tool spec (`ball:d=8`,
  `flat:d=6`, `bull:d=10,r=2`, `cone:d=10,angle=90`). Conventions: OpenCAMLib's
  CL point is the tool tip (as swarf's); `BullCutter(d, r, L)` takes the corner
  radius r; `ConeCutter(d, a, L)` takes the half-angle a from the axis in radians,
  while swarf's `angle=` is the included angle in degrees, so a = radians(angle) / 2.
- `write_points(path, points)`, `read_z(path)`: the points CSV `swarf drop` reads and
  the heights of the CSV it writes.
- `batch_drop(triangles, spec, points, threads)`: BatchDropCutter heights, `None`
  where OpenCAMLib reports no contact (CC type NONE).
"""

import math
import struct

import opencamlib as ocl

#: Lower bound of the drop: OpenCAMLib only raises the CL point's initial z.
FLOOR = -1.0e4
#: Flute length given to OpenCAMLib cutters (long enough never to matter here).
LENGTH = 100.0


def read_stl(path):
    """Triangles of an STL file as ((x, y, z), (x, y, z), (x, y, z)) tuples."""
    data = open(path, "rb").read()
    if len(data) >= 84:
        (count,) = struct.unpack_from("<I", data, 80)
        if 84 + 50 * count == len(data):
            tris = []
            for i in range(count):
                v = struct.unpack_from("<12f", data, 84 + 50 * i)
                tris.append((v[3:6], v[6:9], v[9:12]))
            return tris
    tris, cur = [], []
    for line in data.decode("ascii").splitlines():
        words = line.split()
        if words and words[0] == "vertex":
            cur.append(tuple(float(w) for w in words[1:4]))
            if len(cur) == 3:
                tris.append(tuple(cur))
                cur = []
    return tris


def parse_spec(spec):
    """('ball', {'d': 8.0}) from 'ball:d=8'."""
    shape, _, rest = spec.partition(":")
    params = {}
    for item in rest.split(","):
        if item:
            k, _, v = item.partition("=")
            params[k.strip()] = float(v)
    return shape.strip(), params


def cutter(spec):
    """The OpenCAMLib cutter for a swarf spec (see the module doc)."""
    shape, p = parse_spec(spec)
    d = p["d"]
    if shape == "ball":
        return ocl.BallCutter(d, LENGTH)
    if shape == "flat":
        return ocl.CylCutter(d, LENGTH)
    if shape == "bull":
        return ocl.BullCutter(d, p["r"], LENGTH)
    if shape == "cone":
        return ocl.ConeCutter(d, math.radians(p["angle"]) / 2.0, LENGTH)
    raise ValueError(f"no OpenCAMLib cutter for {spec}")


def surface(triangles):
    """An STLSurf holding the triangles."""
    surf = ocl.STLSurf()
    for a, b, c in triangles:
        surf.addTriangle(ocl.Triangle(ocl.Point(*a), ocl.Point(*b), ocl.Point(*c)))
    return surf


def batch_drop(triangles, spec, points, threads=2, surf=None):
    """BatchDropCutter over `points`: list of (z or None, cc type name) in input order.

    Every OpenCAMLib object stays referenced until the run is over (the Python
    bindings do not keep the cutter or surface alive on their own).
    """
    surf = surf if surf is not None else surface(triangles)
    cut = cutter(spec)
    bdc = ocl.BatchDropCutter()
    bdc.setSTL(surf)
    bdc.setCutter(cut)
    bdc.setThreads(threads)
    for x, y in points:
        bdc.appendPoint(ocl.CLPoint(x, y, FLOOR))
    bdc.run()
    out = []
    for p in bdc.getCLPoints():
        cc = p.getCC()
        kind = str(cc.type)
        out.append((None if kind == "NONE" else p.z, kind))
    del bdc, cut
    return out


def waterline(triangles, spec, z, sampling, adaptive=False, threads=2, surf=None):
    """OpenCAMLib's Waterline (or AdaptiveWaterline, minimum sampling a tenth of
    `sampling`) at tip height `z`: (loops as lists of (x, y), seconds in `run()`)."""
    import time

    surf = surf if surf is not None else surface(triangles)
    cut = cutter(spec)
    wl = ocl.AdaptiveWaterline() if adaptive else ocl.Waterline()
    wl.setSTL(surf)
    wl.setCutter(cut)
    wl.setSampling(sampling)
    if adaptive:
        wl.setMinSampling(sampling / 10.0)
    wl.setThreads(threads)
    wl.setZ(z)
    t0 = time.perf_counter()
    wl.run()
    elapsed = time.perf_counter() - t0
    loops = [[(p.x, p.y) for p in lp] for lp in wl.getLoops()]
    del wl, cut
    return loops, elapsed


def write_points(path, pts):
    """Writes points as `swarf drop --points` reads them (`x,y` per line)."""
    with open(path, "w") as f:
        f.write("x,y\n")
        for x, y in pts:
            f.write(f"{x!r},{y!r}\n")


def read_z(path):
    """The heights of a `swarf drop` output CSV, `None` where there is no contact."""
    out = []
    with open(path) as f:
        next(f)
        for line in f:
            z = line.rstrip("\n").split(",")[2]
            out.append(float(z) if z else None)
    return out
