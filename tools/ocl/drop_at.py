#!/usr/bin/env python3
"""OpenCAMLib BatchDropCutter heights at given points, for tests.

Usage: python3 tools/ocl/drop_at.py --stl MESH.stl --spec ball:d=8 < points

Reads `x,y` lines on standard input and prints one line per point: OpenCAMLib's tip
height, or an empty line where it reports no contact.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ocl_common  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--stl", required=True)
    ap.add_argument("--spec", required=True)
    args = ap.parse_args()
    points = []
    for line in sys.stdin:
        if line.strip():
            x, y = line.split(",")
            points.append((float(x), float(y)))
    tris = ocl_common.read_stl(args.stl)
    for z, _ in ocl_common.batch_drop(tris, args.spec, points):
        print("" if z is None else repr(z))


if __name__ == "__main__":
    main()
