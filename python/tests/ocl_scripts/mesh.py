"""Writes the meshes the scripts read: ``write_mold(path)`` a mold-like height field
(a pocket with a boss in a tilted wavy plate, 20 x 15 mm, no two corners at one height, so that no drop touches two features at once and contact points are unique) as an ASCII STL, with plain
Python so that the scripts need nothing but ``ocl``."""

import math


def height(x, y):
    r = math.hypot((x - 10) / 6, (y - 7.5) / 4)
    pocket = 3 * max(0.0, min(1.0, 1.6 - 1.6 * r)) ** 0.7
    boss = 2 * math.exp(-((x - 11) ** 2 + (y - 7) ** 2) / 2)
    return 5 + 0.03 * x + 0.02 * y + 0.3 * math.sin(x / 1.5) * math.cos(y / 2) - pocket + boss


def write_mold(path, step=0.5):
    nx, ny = int(20 / step), int(15 / step)
    p = lambda i, j: (i * step, j * step, height(i * step, j * step))
    with open(path, "w") as f:
        f.write("solid mold\n")
        for j in range(ny):
            for i in range(nx):
                a, b, c, d = p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)
                for t in ((a, b, c), (a, c, d)):
                    f.write("facet normal 0 0 1\nouter loop\n")
                    for v in t:
                        f.write("vertex %.6f %.6f %.6f\n" % v)
                    f.write("endloop\nendfacet\n")
        f.write("endsolid mold\n")
