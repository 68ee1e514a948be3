# BatchDropCutter on a grid of CL points, in the manner of OpenCAMLib's
# examples/python/drop-cutter/batchdropcutter_test_1.py (without the VTK view).
from opencamlib import ocl

from mesh import write_mold

write_mold("mold.stl")
s = ocl.STLSurf()
ocl.STLReader("mold.stl", s)
print("STL surface read,", s.size(), "triangles")
for cutter in [ocl.BallCutter(1.4321, 5), ocl.CylCutter(1.123, 5), ocl.BullCutter(1.123, 0.2, 5)]:
    print(cutter)
    clpoints = []
    x = -1.0
    while x <= 21.0:
        y = -1.0
        while y <= 16.0:
            clpoints.append(ocl.CLPoint(x, y, 2.0))
            y += 0.7
        x += 0.9
    bdc = ocl.BatchDropCutter()
    bdc.setSTL(s)
    bdc.setCutter(cutter)
    bdc.setThreads(2)
    for p in clpoints:
        bdc.appendPoint(p)
    bdc.run()
    out = bdc.getCLPoints()
    print(len(out), "cl points evaluated")
    for p in out:
        print(p)
