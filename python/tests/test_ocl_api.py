"""swarf.ocl on its own: OpenCAMLib's behaviours that have closed forms (a CL point's
floor, contact types, printing, arc points), the inputs OpenCAMLib crashes or hangs
on raising an exception that names the call and the argument, the calls not
implemented raising NotImplementedError, the STL reader, and the ``ocl`` shim."""

import math
import os
import subprocess
import sys

import numpy as np
import pytest

import swarf.ocl as ocl
from ocl_meshes import hole, write_ascii_stl, write_binary_stl


def square(z=2.0):
    s = ocl.STLSurf()
    p = lambda x, y: ocl.Point(x, y, z)
    s.addTriangle(ocl.Triangle(p(0, 0), p(10, 0), p(10, 10)))
    s.addTriangle(ocl.Triangle(p(0, 0), p(10, 10), p(0, 10)))
    return s


def batch(s, cutter, points):
    b = ocl.BatchDropCutter()
    b.setSTL(s)
    b.setCutter(cutter)
    for p in points:
        b.appendPoint(ocl.CLPoint(*p))
    b.run()
    return b.getCLPoints()


def test_point_arithmetic_and_printing():
    p, q = ocl.Point(1, 2, 3), ocl.Point(4, 5)
    assert (str(p + q), str(p - q), str(2 * p), str(p * 0.5)) == ("(5, 7, 3)", "(-3, -3, 3)", "(2, 4, 6)", "(0.5, 1, 1.5)")
    assert p.dot(q) == 14 and str(p.cross(q)) == "(-15, 12, -3)"
    assert p.norm() == math.sqrt(14) and q.xyNorm() == math.sqrt(41)
    r = ocl.Point(3, 4, 0)
    r.normalize()
    assert (r.x, r.y) == (3 * 0.2, 4 * 0.2), "scaled by 1 / norm, as OpenCAMLib does"
    r += ocl.Point(1, 1, 1)
    assert str(r) == "(1.6, 1.8, 1)"
    z = ocl.Point(1, 0, 0)
    z.zRotate(math.pi / 2)
    assert abs(z.x) < 1e-16 and z.y == 1.0
    assert ocl.Point(0, -1).isRight(ocl.Point(0, 0), ocl.Point(1, 0))
    assert str(ocl.Point(1234567, 1e-5, -0.0)) == "(1.23457e+06, 1e-05, -0)"


def test_cl_point_floor_and_contact_types():
    """The floor is kept where the surface is below it; the contact says what was touched."""
    s = square()
    below, above, off = batch(s, ocl.CylCutter(2, 10), [(3, 6, -10), (3, 6, 7), (50, 5, -10)])
    assert (below.z, str(below.getCC().type)) == (2.0, "FACET")
    assert (above.z, above.getCC().type) == (7.0, ocl.CCType.NONE)
    assert (off.z, str(off)) == (-10.0, "CL(50, 5, -10) cc=CC(0, 0, 0, t=0)")
    (seam,) = batch(s, ocl.CylCutter(2, 10), [(5, 5, -10)])
    assert seam.getCC().type == ocl.CCType.EDGE, "on the triangles' common edge: an edge contact, as OpenCAMLib counts it"
    corner, edge = batch(s, ocl.BallCutter(2, 10), [(-0.6, -0.8, -10), (-0.6, 5, -10)])
    assert corner.getCC().type == ocl.CCType.VERTEX and abs(corner.z - 1.0) < 1e-15
    assert edge.getCC().type == ocl.CCType.EDGE and abs(edge.z - 1.8) < 1e-15
    tip, rim = batch(s, ocl.ConeCutter(4, math.pi / 4), [(3, 6, -10), (-1, 5, -10)])
    assert tip.getCC().type == ocl.CCType.FACET_TIP
    assert rim.getCC().type == ocl.CCType.EDGE and abs(rim.z - 1.0) < 1e-15


def test_single_triangle_drops():
    t = ocl.Triangle(ocl.Point(0, 0, 0), ocl.Point(10, 0, 0), ocl.Point(0, 10, 0))
    c = ocl.CylCutter(2, 5)
    cl = ocl.CLPoint(-0.5, 3, -5)
    assert not c.vertexDrop(cl, t) and cl.z == -5
    assert not c.facetDrop(cl, t)
    assert c.edgeDrop(cl, t) and cl.z == 0 and cl.getCC().type == ocl.CCType.EDGE
    cl = ocl.CLPoint(2, 2, -5)
    assert c.dropCutter(cl, t) and str(cl.getCC().type) == "FACET"
    assert not c.dropCutter(cl, t), "a second drop finds nothing higher"


def test_path_sampling_is_opencamlibs():
    """PathDropCutter samples a span at i / n, n = int(length / sampling + 1)."""
    p = ocl.Path()
    p.append(ocl.Line(ocl.Point(0, 1, 0), ocl.Point(2.05, 1, 0)))
    p.append(ocl.Arc(ocl.Point(0, 1, 0), ocl.Point(0, -1, 0), ocl.Point(0, 0, 0), True))
    d = ocl.PathDropCutter()
    d.setSTL(square(0.0))
    d.setCutter(ocl.BallCutter(1, 5))
    d.setPath(p)
    d.setSampling(0.5)
    d.setZ(-3)
    d.run()
    pts = d.getCLPoints()
    assert len(pts) == (5 + 1) + (7 + 1)
    assert [q.x for q in pts[:6]] == [2.05 * (i / 5) + 0.0 for i in range(6)]
    arc = pts[6:]
    assert all(abs(math.hypot(q.x, q.y) - 1) < 1e-15 for q in arc)
    assert arc[1].x < 0 and arc[-1].y == -1.0, "counter-clockwise from +Y through -X, to its end"
    assert pts[0].z == 0.0 and arc[3].z == -3.0, "on the square, and off it at the floor"


def test_adaptive_path_refines_where_the_path_turns():
    s = ocl.STLSurf()
    for t in hole():
        s.addTriangle(ocl.Triangle(*(ocl.Point(*p) for p in t)))
    p = ocl.Path()
    p.append(ocl.Line(ocl.Point(1, 15, 0), ocl.Point(29, 15, 0)))
    d = ocl.AdaptivePathDropCutter()
    d.setSTL(s)
    d.setCutter(ocl.CylCutter(2, 5))
    d.setPath(p)
    d.setSampling(1.0)
    d.setMinSampling(0.01)
    d.run()
    xs = np.array([q.x for q in d.getCLPoints()])
    steps = np.diff(xs)
    assert (steps > 0).all() and steps.max() <= 1.0
    assert steps.min() < 0.02, "refined at the hole's edges"
    assert (steps[(xs[1:] < 9) | ((xs[:-1] > 13) & (xs[1:] < 17))] > 0.5).all(), "coarse where flat"


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: ocl.CylCutter(0, 5), "CylCutter(diameter, length): diameter = 0.0"),
        (lambda: ocl.CylCutter(2, 0), "length = 0.0"),
        (lambda: ocl.BallCutter(float("nan"), 5), "BallCutter(diameter, length): diameter = nan"),
        (lambda: ocl.BullCutter(4, 2, 5), "radius = 2.0: expected a corner radius in [0, diameter/2)"),
        (lambda: ocl.ConeCutter(4, 45, 0), "angle = 45.0: expected a half-angle in radians in (0, pi/2)"),
        (lambda: ocl.BatchDropCutter().setSTL(ocl.STLSurf()), "setSTL(s): the surface has no triangles"),
        (lambda: ocl.Waterline().setSTL(ocl.STLSurf()), "Waterline.setSTL(s): the surface has no triangles"),
        (lambda: ocl.BatchDropCutter().run(), "BatchDropCutter.run(): no surface (setSTL)"),
        (lambda: _with_stl(ocl.PathDropCutter()).run(), "PathDropCutter.run(): no cutter (setCutter)"),
        (lambda: _with_cutter(_with_stl(ocl.PathDropCutter())).run(), "PathDropCutter.run(): no path (setPath)"),
        (lambda: ocl.BatchDropCutter().appendPoint(ocl.CLPoint(math.nan, 0, 0)), "appendPoint(p): p = CL(nan"),
        (lambda: ocl.STLSurf().addTriangle(ocl.Triangle(ocl.Point(0, 0, math.inf), ocl.Point(1, 0), ocl.Point(0, 1))),
         "addTriangle(t): corner t.p[0] = (0, 0, inf)"),
        (lambda: ocl.PathDropCutter().setSampling(0), "PathDropCutter.setSampling(s): 0.0"),
        (lambda: ocl.AdaptivePathDropCutter().setMinSampling(-1), "setMinSampling(s): -1.0"),
        (lambda: ocl.Waterline().setSampling(math.nan), "Waterline.setSampling(s): nan"),
        (lambda: _with_cutter(_with_stl(ocl.Waterline())).run(), "Waterline.run(): no sampling (setSampling)"),
        (lambda: ocl.Waterline().setZ(math.inf), "Waterline.setZ(z): z = inf"),
        (lambda: ocl.BatchDropCutter().setThreads(0), "setThreads(n): n = 0"),
        (lambda: _with_path(math.nan).run(), "span 0 of the path has a non-finite point"),
    ],
)
def test_what_opencamlib_crashes_on_raises_naming_the_argument(call, message):
    with pytest.raises(ValueError) as e:
        call()
    assert message in str(e.value)


def _with_stl(op):
    op.setSTL(square())
    return op


def _with_cutter(op):
    op.setCutter(ocl.BallCutter(2, 5))
    return op


def _with_path(x):
    op = _with_cutter(_with_stl(ocl.PathDropCutter()))
    p = ocl.Path()
    p.append(ocl.Line(ocl.Point(x, 0, 0), ocl.Point(1, 1, 0)))
    op.setPath(p)
    return op


def test_wrong_types_raise_type_error():
    with pytest.raises(TypeError, match="Point"):
        ocl.Point(1)
    with pytest.raises(TypeError, match="addTriangle"):
        ocl.STLSurf().addTriangle((0, 0, 0))
    with pytest.raises(TypeError, match="setCutter"):
        ocl.BatchDropCutter().setCutter("ball:d=6")


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: ocl.LineCLFilter(), "LineCLFilter()"),
        (lambda: ocl.BatchPushCutter(), "BatchPushCutter()"),
        (lambda: ocl.Fiber(ocl.Point(), ocl.Point(1, 0)), "Fiber()"),
        (lambda: ocl.ZigZag(), "ZigZag()"),
        (lambda: ocl.CylConeCutter(1, 2, 0.5), "CylConeCutter()"),
        (lambda: ocl.BatchDropCutter().getCalls(), "BatchDropCutter.getCalls()"),
        (lambda: ocl.Waterline().getXFibers(), "Waterline.getXFibers()"),
        (lambda: ocl.CylCutter(2, 5).pushCutter(), "MillingCutter.pushCutter()"),
        (lambda: ocl.BallConeCutter(1, 4, 0.5).offsetCutter(0.1), "BallConeCutter.offsetCutter()"),
    ],
)
def test_unimplemented_calls_raise_naming_the_call(call, name):
    with pytest.raises(NotImplementedError, match=name.replace("(", r"\(").replace(")", r"\)")):
        call()


def test_stl_reader_reads_every_binary_file_and_ascii(tmp_path):
    tris = np.array(hole(), dtype=np.float64)
    tris[:, :, 2] += np.linspace(0, 1, len(tris))[:, None] / 3  # not single-precision numbers
    single = tris.astype(np.float32).astype(np.float64)
    for name, write in [
        ("plain.stl", lambda p: write_binary_stl(p, tris)),
        ("solid.stl", lambda p: write_binary_stl(p, tris, header=b"solid in a binary header")),
        ("text.stl", lambda p: write_ascii_stl(p, tris)),
    ]:
        write(tmp_path / name)
        s = ocl.STLSurf()
        ocl.STLReader(str(tmp_path / name), s)
        got = np.array([[(q.x, q.y, q.z) for q in t.getPoints()] for t in s.getTriangles()])
        assert s.size() == len(tris) and np.array_equal(got, single), name
    with pytest.raises(ValueError, match="nope.stl"):
        ocl.STLReader(str(tmp_path / "nope.stl"), ocl.STLSurf())


def test_surface_bounds_rotation_and_triangles():
    s = square(2.0)
    assert s.getBounds() == [0, 10, 0, 10, 2, 2] and str(s) == "STLSurf(N=2)"
    assert str(s.bb.maxpt) == "(10, 10, 2)" and s.bb.isInside(ocl.Point(5, 5, 2))
    s.rotate(0, 0, math.pi / 2)
    lo = s.getBounds()
    assert abs(lo[0] + 10) < 1e-12 and abs(lo[1]) < 1e-12 and lo[4:] == [2, 2]
    t = s.getTriangles()[0]
    assert str(ocl.Triangle()) == "T: (1, 0, 0) (0, 1, 0) (0, 0, 1)n=(0.57735, 0.57735, 0.57735)"
    assert abs(t.n.z - 1) < 1e-15


def test_waterline_loops_a_square_plateau():
    """A flat end of radius 1 around a 10 mm square at its height less a hair: one loop,
    the square grown by 1 mm with round corners (area 100 + 40 + pi)."""
    w = ocl.Waterline()
    w.setSTL(square(2.0))
    w.setCutter(ocl.CylCutter(2, 5))
    w.setSampling(0.2)
    w.setZ(1.999)
    w.run()
    (loop,) = w.getLoops()
    xy = np.array([(p.x, p.y) for p in loop])
    area = 0.5 * np.sum(xy[:, 0] * np.roll(xy[:, 1], -1) - np.roll(xy[:, 0], -1) * xy[:, 1])
    assert abs(area - (140 + math.pi)) < 0.01 and area > 0, "counter-clockwise"
    r = np.hypot(np.clip(xy[:, 0], 0, 10) - xy[:, 0], np.clip(xy[:, 1], 0, 10) - xy[:, 1])
    assert np.abs(r - 1).max() < 1e-6, "every point on the offset contour"
    assert all(p.z == 1.999 for p in loop)
    w.reset()
    assert w.getLoops() == []


def test_cutter_sizes_and_printing():
    assert str(ocl.CylCutter(2.345, 5)) == "CylCutter (d=2.345, L=5)"
    assert str(ocl.BallCutter(2, 5)) == "BallCutter(d=2, r=1, L=5)"
    assert str(ocl.BullCutter(2.345, 0.123, 6).offsetCutter(0.1)) == "BullCutter(d=2.545, r1=1.0495 r2=0.223, L=6.1)"
    c = ocl.ConeCutter(2, 0.6, 5)
    assert (str(c), c.getRadius(), c.getDiameter()) == ("ConeCutter (d=2, angle=0.6, L=6.4617)", 1.0, 2.0)
    assert str(ocl.CylCutter(2.345, 5).offsetCutter(0.1)) == "BullCutter(d=2.545, r1=1.1725 r2=0.1, L=5.1)"
    assert ocl.version().startswith("2023.01.11 (swarf ")


def test_shim_makes_import_ocl_swarf(tmp_path):
    shim = subprocess.run(
        [sys.executable, "-m", "swarf.ocl", "shim"], capture_output=True, text=True, check=True
    ).stdout.strip()
    assert os.path.isfile(os.path.join(shim, "ocl.py"))
    code = "import ocl, swarf.ocl; assert ocl is swarf.ocl; print(ocl.version())"
    r = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path,
        env={**os.environ, "PYTHONPATH": shim},
    )
    assert r.returncode == 0 and "swarf" in r.stdout, r.stderr
