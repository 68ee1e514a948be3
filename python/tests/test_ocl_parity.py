"""swarf.ocl against OpenCAMLib 2023.1.11, the same calls on the same meshes in one
run (``ocl_meshes``: a mold-like height field, the die, an open V-groove, a plate
with a hole):

- drops (``BatchDropCutter``, each cutter, random points with random floors): the
  same heights within 1e-6 mm, no contact where OpenCAMLib has none, the same
  contact type where the contact point is the same. Where the heights differ by
  more (OpenCAMLib's cone edge drops), the brute-force drop (``ocl_brute``, sharing
  no code with either) agrees with swarf within 1e-6 mm and not with OpenCAMLib;
- paths (``PathDropCutter``, ``AdaptivePathDropCutter``, lines and arcs): the same
  points, XY bit for bit, heights within 1e-6 mm;
- waterlines (``Waterline``, ``AdaptiveWaterline``) at 0.1 mm sampling: as many
  loops, the same way round and of the same area within 0.1 %, within 0.02 mm of
  each other (Hausdorff), except where an exact reference shows
  swarf right: a swarf point farther from OpenCAMLib's loops is on the contour by
  OpenCAMLib's own drops (they straddle the level 1e-6 mm to either side across the
  loop; OpenCAMLib's chords cut across the contour's corners there, or its loops
  miss a part), and an OpenCAMLib point farther from swarf's is not on it (where
  the material rises above the level plus the cutter's length OpenCAMLib's waterline
  ignores those triangles and loops inside the material; the die at z = 5 shows it,
  a run of minutes left out of these tests);
- STL files, binary and ASCII, read into the same triangles; printing; rotation.

The ratio of the run times is printed (a figure, not a check)."""

import math
import time

import numpy as np
import pytest

import swarf.ocl as sw
from ocl_brute import mesh_drop, profile
from ocl_meshes import MESHES, distance_to, surface, write_ascii_stl, write_binary_stl

CUTTERS = {
    "flat-d6": (lambda L: L.CylCutter(6, 30), profile("flat", 3)),
    "ball-d8": (lambda L: L.BallCutter(8, 30), profile("ball", 4)),
    "bull-d10-r2": (lambda L: L.BullCutter(10, 2, 30), profile("bull", 5, corner=2)),
    "cone-d8-a30": (lambda L: L.ConeCutter(8, math.radians(30), 30), profile("cone", 4, half_angle=math.radians(30))),
}
TRIS = {}


def tris(name):
    if name not in TRIS:
        TRIS[name] = MESHES[name]()
    return TRIS[name]


def run_batch(lib, t, make, pts):
    s, c, b = surface(lib, t), make(lib), lib.BatchDropCutter()
    b.setSTL(s)
    b.setCutter(c)
    b.setThreads(2)
    for p in pts:
        b.appendPoint(lib.CLPoint(*p))
    start = time.perf_counter()
    b.run()
    seconds = time.perf_counter() - start
    out = b.getCLPoints()
    cc = [p.getCC() for p in out]
    return (
        np.array([p.z for p in out]),
        np.array([(q.x, q.y, q.z) for q in cc]),
        np.array([int(q.type) for q in cc]),
        seconds,
    )


@pytest.mark.parametrize("mesh", list(MESHES))
@pytest.mark.parametrize("cutter", list(CUTTERS))
def test_drops_match_opencamlib(ocl, mesh, cutter, capsys):
    t = tris(mesh)
    lo, hi = t.reshape(-1, 3).min(axis=0), t.reshape(-1, 3).max(axis=0)
    rng = np.random.default_rng(len(mesh) * 7 + len(cutter))
    n = 400
    floors = np.where(rng.random(n) < 0.3, rng.uniform(lo[2] - 1, hi[2] + 1, n), -100.0)
    pts = np.column_stack([rng.uniform(lo[0] - 6, hi[0] + 6, n), rng.uniform(lo[1] - 6, hi[1] + 6, n), floors])
    make, h = CUTTERS[cutter]
    tz, tcc, ttype, ts = run_batch(ocl, t, make, pts)
    oz, occ, otype, os_ = run_batch(sw, t, make, pts)
    assert np.array_equal(ttype == 0, otype == 0), "contact (lifted above the floor) at the same points"
    same = np.all(np.abs(tcc - occ) <= 1e-9, axis=1) & (ttype != 0)
    assert np.array_equal(ttype[same], otype[same]), "the same contact type at the same contact"
    off = np.nonzero(np.abs(tz - oz) > 1e-6)[0]
    radius = make(sw).getRadius()
    for k in rng.permutation(off)[:15]:
        exact = mesh_drop(h, radius, pts[k, :2], t)
        assert abs(oz[k] - exact) <= 1e-6 < abs(tz[k] - exact), (pts[k], tz[k], oz[k], exact)
    with capsys.disabled():
        print(f"\n  {cutter} on {mesh} ({len(t)} triangles), {n} points: max |dz| "
              f"{np.abs(tz - oz).max():.1e} mm, {len(off)} beyond 1e-6 (brute force: swarf right), "
              f"{int(same.sum())} contacts compared; OpenCAMLib {ts:.3f} s, swarf {os_:.3f} s")


def path(lib):
    P = lib.Point
    p = lib.Path()
    p.append(lib.Line(P(-3, 2, 0), P(43, 28, 0)))
    p.append(lib.Line(P(43, 28, 0), P(43, 5, 0)))
    p.append(lib.Arc(P(43, 5, 0), P(5, 5, 0), P(24, 5, 0), True))
    p.append(lib.Arc(P(5, 5, 0), P(20, 5, 0), P(12.5, 12.5, 0), False))
    return p


def run_path(lib, t, make, adaptive):
    s, c, p = surface(lib, t), make(lib), path(lib)
    d = lib.AdaptivePathDropCutter() if adaptive else lib.PathDropCutter()
    d.setSTL(s)
    d.setCutter(c)
    d.setPath(p)
    d.setZ(-5)
    if adaptive:
        d.setSampling(0.5)
        d.setMinSampling(0.02)
    else:
        d.setSampling(0.25)
    d.run()
    return np.array([(q.x, q.y, q.z) for q in d.getCLPoints()])


@pytest.mark.parametrize("mesh", list(MESHES))
@pytest.mark.parametrize("adaptive", [False, True], ids=["PathDropCutter", "AdaptivePathDropCutter"])
def test_paths_match_opencamlib(ocl, mesh, adaptive):
    for cutter in ("flat-d6", "ball-d8", "bull-d10-r2"):
        make = CUTTERS[cutter][0]
        theirs = run_path(ocl, tris(mesh), make, adaptive)
        ours = run_path(sw, tris(mesh), make, adaptive)
        assert theirs.shape == ours.shape and len(ours) > 400, cutter
        assert np.array_equal(theirs[:, :2], ours[:, :2]), f"{cutter}: the same XY, bit for bit"
        assert np.abs(theirs[:, 2] - ours[:, 2]).max() <= 1e-6, cutter


def run_waterline(lib, t, make, z, adaptive):
    s, c = surface(lib, t), make(lib)
    w = lib.AdaptiveWaterline() if adaptive else lib.Waterline()
    w.setSTL(s)
    w.setCutter(c)
    w.setZ(z)
    w.setSampling(0.1)
    if adaptive:
        w.setMinSampling(0.01)
    w.setThreads(2)
    start = time.perf_counter()
    w.run()
    seconds = time.perf_counter() - start
    loops = [np.array([(p.x, p.y) for p in lp]) for lp in w.getLoops() if len(lp) > 2]
    assert all(p.z == z for lp in w.getLoops() for p in lp)
    return loops, seconds


def on_contour(ocl, t, make, z, points, normals):
    """True where OpenCAMLib's drops 1e-6 mm to either side of each point along its
    normal straddle the level (no contact counts as below it)."""
    probes = np.concatenate([points + 1e-6 * normals, points - 1e-6 * normals])
    lo = np.min(t.reshape(-1, 3)[:, 2]) - 100
    heights, _, types, _ = run_batch(ocl, t, make, np.column_stack([probes, np.full(len(probes), lo)]))
    heights = np.where(types == 0, -np.inf, heights)
    a, b = heights[: len(points)], heights[len(points):]
    return (np.maximum(a, b) >= z - 1e-6) & (np.minimum(a, b) <= z + 1e-6)


def normals(loop):
    d = np.roll(loop, -1, axis=0) - np.roll(loop, 1, axis=0)
    n = np.column_stack([-d[:, 1], d[:, 0]])
    return n / np.maximum(np.hypot(n[:, 0], n[:, 1]), 1e-300)[:, None]


WATERLINES = [
    ("mold", "ball-d8", 9.5),
    ("vgroove", "ball-d8", 12.0),
    ("vgroove", "bull-d10-r2", 11.5),
    ("hole", "flat-d6", 4.0),
]
#: OpenCAMLib's AdaptiveWaterline takes minutes on the mold (ocl_api_bench.py runs it).
ADAPTIVE = ("vgroove", "hole")


@pytest.mark.parametrize(
    "adaptive, mesh, cutter, z",
    [(False, *case) for case in WATERLINES] + [(True, *case) for case in WATERLINES if case[0] in ADAPTIVE],
    ids=lambda v: {False: "Waterline", True: "AdaptiveWaterline"}.get(v, str(v)) if isinstance(v, bool) else str(v),
)
def test_waterlines_match_opencamlib(ocl, adaptive, mesh, cutter, z, capsys):
    t, make = tris(mesh), CUTTERS[cutter][0]
    theirs, ts = run_waterline(ocl, t, make, z, adaptive)
    ours, os_ = run_waterline(sw, t, make, z, adaptive)
    assert theirs and ours
    tp, op = np.concatenate(theirs), np.concatenate(ours)
    tn = np.concatenate([normals(lp) for lp in theirs])
    on = np.concatenate([normals(lp) for lp in ours])
    theirs_off, _ = distance_to(tp, ours)
    ours_off, _ = distance_to(op, theirs)
    t_far, o_far = np.nonzero(theirs_off > 0.02)[0], np.nonzero(ours_off > 0.02)[0]
    if len(o_far):
        assert on_contour(ocl, t, make, z, op[o_far], on[o_far]).all(), "swarf's points away from OpenCAMLib's are on the contour"
    if len(t_far):
        assert not on_contour(ocl, t, make, z, tp[t_far], tn[t_far]).any(), "OpenCAMLib's points away from swarf's are not"
    area = lambda lp: 0.5 * np.sum(lp[:, 0] * np.roll(lp[:, 1], -1) - np.roll(lp[:, 0], -1) * lp[:, 1])
    ta, oa = sorted(map(area, theirs)), sorted(map(area, ours))
    assert len(ta) == len(oa) and np.allclose(ta, oa, rtol=1e-3, atol=0.1), ("signed areas: the same loops, the same way round", ta, oa)
    with capsys.disabled():
        print(f"\n  {'Adaptive' if adaptive else ''}Waterline {cutter} on {mesh} at z = {z}: {len(theirs)} and "
              f"{len(ours)} loops, {len(tp)} and {len(op)} points; OpenCAMLib's points beyond 0.02 mm of swarf's "
              f"loops: {len(t_far)} (off the contour), swarf's beyond 0.02 mm of OpenCAMLib's: {len(o_far)} "
              f"(on it), at most {ours_off.max():.3f} mm; OpenCAMLib {ts:.2f} s, swarf {os_:.2f} s")


def test_stl_files_read_the_same(ocl, tmp_path):
    t = tris("mold") + np.array([0.1234567, 0.7654321, 0.3333333])
    for name, write in [("b.stl", write_binary_stl), ("a.stl", write_ascii_stl)]:
        write(tmp_path / name, t)
        got = []
        for lib in (ocl, sw):
            s = lib.STLSurf()
            lib.STLReader(str(tmp_path / name), s)
            got.append((s.size(), s.getBounds(), [(p.x, p.y, p.z) for tri in s.getTriangles() for p in tri.getPoints()]))
        assert got[0] == got[1], name


def test_printing_and_rotation_match(ocl):
    def text(lib):
        p = lib.Point(1.5, -2.25, 1e-7)
        s = surface(lib, tris("vgroove")[:6])
        s.rotate(0.3, -0.2, 1.1)
        cutters = [lib.CylCutter(3.3, 7), lib.BallCutter(2, 9), lib.BullCutter(6, 1.25, 12), lib.ConeCutter(5, 0.4, 3)]
        return [str(p), str(p * 3), str(lib.CLPoint(1, 2, 3)), str(lib.CCPoint(4, 5, 6)), str(s), str(s.getBounds()),
                *[str(t) for t in s.getTriangles()], *[str(c) for c in cutters], *[str(c.offsetCutter(0.2)) for c in cutters],
                *[repr((c.getLength(), c.getRadius())) for c in cutters], str(lib.ConeCutter(4, 0.5, 1).offsetCutter(0.25))]

    assert text(ocl) == text(sw)
