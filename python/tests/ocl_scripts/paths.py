# Paths of lines and arcs, then PathDropCutter and AdaptivePathDropCutter over an
# STL, G-code style, in the manner of OpenCAMLib's examples/python (path_example_1,
# pathdropcutter_test_1, test.py).
from opencamlib import ocl

from mesh import write_mold


def xyz(p):
    f = lambda v: "{:.5f}".format(v).rstrip("0").rstrip(".")
    return "X" + f(p.x) + " Y" + f(p.y) + " Z" + f(p.z)


print(ocl.version())
path = ocl.Path()
path.append(ocl.Line(ocl.Point(-2, 3), ocl.Point(22, 3)))
path.append(ocl.Arc(ocl.Point(22, 3, 0), ocl.Point(22, 12, 0), ocl.Point(22, 7.5, 0), True))
path.append(ocl.Line(ocl.Point(22, 12, 0), ocl.Point(-2, 12, 0)))
path.append(ocl.Arc(ocl.Point(-2, 12, 0), ocl.Point(1, 9, 0), ocl.Point(1, 12, 0), False))
for kind, span in path.getTypeSpanPairs():
    if kind == ocl.ArcSpanType:
        print("Arc(start=" + str(span.p1) + ", centre=" + str(span.c) + " end=" + str(span.p2) + ")")
    if kind == ocl.LineSpanType:
        print("Line(start=" + str(span.p1) + ", end=" + str(span.p2) + ")")

write_mold("mold.stl")
surface = ocl.STLSurf()
ocl.STLReader("mold.stl", surface)
print(surface, surface.getBounds())
for cutter in [ocl.CylCutter(2, 20), ocl.BallCutter(3, 20), ocl.BullCutter(4, 1, 20)]:
    print("PathDropCutter", cutter)
    pdc = ocl.PathDropCutter()
    pdc.setSTL(surface)
    pdc.setCutter(cutter)
    pdc.setPath(path)
    pdc.setZ(1)
    pdc.setSampling(0.25)
    pdc.run()
    for p in pdc.getCLPoints():
        print("G01 " + xyz(p))
    print("AdaptivePathDropCutter", cutter)
    apdc = ocl.AdaptivePathDropCutter()
    apdc.setSTL(surface)
    apdc.setCutter(cutter)
    apdc.setPath(path)
    apdc.setSampling(0.4)
    apdc.setMinSampling(0.02)
    apdc.run()
    points = apdc.getCLPoints()
    print(len(points), "points")
    for p in points:
        print("G01 " + xyz(p))
