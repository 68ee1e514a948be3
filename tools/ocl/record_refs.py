#!/usr/bin/env python3
"""Record OpenCAMLib BatchDropCutter heights as references for swarf's drop-cutter.

Usage: python3 tools/ocl/record_refs.py --swarf target/debug/swarf \
           --out crates/swarf-tool/tests/data/ocl

For each shared part it tessellates a small mesh with `swarf tessellate` (binary STL,
committed beside the references), draws a few hundred random XY points over the
mesh's box grown by 6 mm (so some points are off the mesh), and writes, per cutter,
`<mesh>__<tag>.csv`: a `# spec: ...` line, the header `x,y,z,cc`, then one line per
point with OpenCAMLib's tip height (empty where it reports no contact) and its CC
type. The test `drop_ocl` compares swarf's heights with these.
"""

import argparse
import os
import random
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ocl_common  # noqa: E402

MESHES = [("die", 0.02), ("wave", 0.05), ("edge-concave", 0.02), ("edge-convex", 0.02)]
CUTTERS = [
    ("ball-d8", "ball:d=8"),
    ("flat-d6", "flat:d=6"),
    ("bull-d10-r2", "bull:d=10,r=2"),
    ("cone-d10-a90", "cone:d=10,angle=90"),
    ("cone-d8-a60", "cone:d=8,angle=60"),
]
POINTS = 300
MARGIN = 6.0
SEED = 20240604


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--swarf", required=True, help="the swarf binary (for tessellate)")
    ap.add_argument("--out", required=True, help="output directory")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rng = random.Random(SEED)
    for name, tol in MESHES:
        stl = os.path.join(args.out, f"{name}.stl")
        subprocess.run([args.swarf, "tessellate", name, "--tol", str(tol), "-o", stl], check=True)
        tris = ocl_common.read_stl(stl)
        xs = [p[0] for t in tris for p in t]
        ys = [p[1] for t in tris for p in t]
        box = (min(xs) - MARGIN, min(ys) - MARGIN, max(xs) + MARGIN, max(ys) + MARGIN)
        pts = [
            (round(rng.uniform(box[0], box[2]), 4), round(rng.uniform(box[1], box[3]), 4))
            for _ in range(POINTS)
        ]
        surf = ocl_common.surface(tris)
        for tag, spec in CUTTERS:
            res = ocl_common.batch_drop(tris, spec, pts, threads=2, surf=surf)
            path = os.path.join(args.out, f"{name}__{tag}.csv")
            with open(path, "w") as f:
                f.write(f"# spec: {spec}\n# OpenCAMLib {ocl_common.ocl.version()} BatchDropCutter\n")
                f.write("x,y,z,cc\n")
                for (x, y), (z, kind) in zip(pts, res):
                    zs = "" if z is None else repr(z)
                    f.write(f"{x!r},{y!r},{zs},{kind}\n")
            hits = sum(1 for z, _ in res if z is not None)
            print(f"{path}: {len(pts)} points, {hits} with contact")


if __name__ == "__main__":
    main()
