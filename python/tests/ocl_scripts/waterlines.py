# Waterline and AdaptiveWaterline at several levels over an STL, G-code style, in the
# manner of OpenCAMLib's examples/python (test.py, toolpath_examples/waterline_simple.py).
from opencamlib import ocl

from mesh import write_mold


def xyz(p):
    f = lambda v: "{:.5f}".format(v).rstrip("0").rstrip(".")
    return "X" + f(p.x) + " Y" + f(p.y) + " Z" + f(p.z)


write_mold("mold.stl")
surface = ocl.STLSurf()
ocl.STLReader("mold.stl", surface)
for cutter, levels in [(ocl.CylCutter(2, 20), [5.1]), (ocl.BallCutter(2, 20), [4.0])]:
    for z in levels:
        print("Waterline", cutter, "z =", z)
        wl = ocl.Waterline()
        wl.setSTL(surface)
        wl.setCutter(cutter)
        wl.setZ(z)
        wl.setSampling(0.1)
        wl.run()
        for loop in wl.getLoops():
            print("loop")
            for point in loop:
                print("G01 " + xyz(point))
cutter = ocl.CylCutter(2, 20)
print("AdaptiveWaterline", cutter, "z =", 4.0)
awl = ocl.AdaptiveWaterline()
awl.setSTL(surface)
awl.setCutter(cutter)
awl.setZ(4.0)
awl.setSampling(0.5)
awl.setMinSampling(0.05)
awl.run()
for loop in awl.getLoops():
    print("loop")
    for point in loop:
        print("G01 " + xyz(point))
