# Points, CL and CC points, triangles, surfaces, cutters and single-triangle drops,
# in the manner of OpenCAMLib's examples/python (ocl_test0, ocl_clpoint,
# ocl_offsetCutter_1, drop_cutter_tst_1 and _2).
import math

from opencamlib import ocl

print(ocl.version())
p = ocl.Point()
p.x = 7
p.y = 8
p.z = -3
q = ocl.Point(1, 2, 3)
r = p + q
s = ocl.Point(66, 66, 66)
s += r
print(p, q, r, s)
print("2*s=", s * 2, "s-q=", s - q, "0.5*q=", 0.5 * q)
print("s.norm=", s.norm(), "xyNorm=", s.xyNorm())
s.normalize()
print("normalized", s, s.norm())
print("dot", s.dot(r), "cross", s.cross(r), "isRight", q.isRight(p, r), "xyDistance", p.xyDistance(q))
for turn in (q.xRotate, q.yRotate, q.zRotate):
    turn(0.3)
    print("rotated", q)
cc = ocl.CCPoint(4, 5, 6)
print(cc, ocl.CLPoint(), ocl.CLPoint(7, 8, 9))
cl3 = ocl.CLPoint(10, 11, 12, cc)
cc.x = 77
print(cl3, cl3.getCC(), cl3.getCC().type)
t = ocl.Triangle(p, ocl.Point(1, 2, 3), r)
print(t)
surf = ocl.STLSurf()
surf.addTriangle(t)
surf.addTriangle(ocl.Triangle(ocl.Point(0, 0, 0), ocl.Point(10, 0, 1), ocl.Point(0, 10, 2)))
print(surf, surf.size(), surf.getBounds())
cutters = [
    ocl.CylCutter(2.345, 5),
    ocl.BallCutter(2.345, 6),
    ocl.BullCutter(2.345, 0.123, 6),
    ocl.ConeCutter(2.345, math.pi / 6, 5),
]
for c in cutters:
    print(c, c.getDiameter(), c.getRadius(), c.getLength())
    print("offset:", c.offsetCutter(0.1))
tri = ocl.Triangle(ocl.Point(1, 0, 0), ocl.Point(0, 1, 0), ocl.Point(0, 0, 1))
for c in [ocl.CylCutter(0.1, 5), ocl.BallCutter(0.4, 5), ocl.BullCutter(0.4, 0.1, 5)]:
    cl = ocl.CLPoint(0.2, 0.2, -5)
    for drop in (c.vertexDrop, c.facetDrop, c.edgeDrop):
        print(drop(cl, tri), cl)
    for x, y in [(0.9, 0.4), (-0.05, 0.5), (1.1, -0.1), (0.3, 0.3)]:
        cl = ocl.CLPoint(x, y, -5)
        print(c.dropCutter(cl, tri), cl)
