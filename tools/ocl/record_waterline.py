#!/usr/bin/env python3
"""Record OpenCAMLib Waterline and AdaptiveWaterline loops as references for swarf's
waterline.

Usage: python3 tools/ocl/record_waterline.py --out crates/swarf-path/tests/data/ocl

Meshes are the small tessellations of the shared parts that the drop-cutter
references use (crates/swarf-tool/tests/data/ocl/*.stl). For each case (mesh, cutter,
level) it writes `waterline__<mesh>__<tag>__<k>.csv`: `# spec: ...`, `# z: ...`,
`# sampling: ...`, `# kind: waterline|adaptive`, then `loop,x,y` per point. The test
`waterline_ocl` compares swarf's loops with these.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ocl_common  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
MESHES = os.path.join(HERE, "..", "..", "crates", "swarf-tool", "tests", "data", "ocl")
SAMPLING = 0.1
# (mesh, cutter tag, spec, levels as fractions of the mesh's height range)
CASES = [
    ("die", "ball-d8", "ball:d=8", [0.3, 0.6]),
    ("die", "bull-d10-r2", "bull:d=10,r=2", [0.5]),
    ("die", "flat-d6", "flat:d=6", [0.45]),
    ("wave", "ball-d8", "ball:d=8", [0.25, 0.7]),
    ("edge-concave", "ball-d8", "ball:d=8", [0.5]),
]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True, help="output directory")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    for mesh, tag, spec, fractions in CASES:
        tris = ocl_common.read_stl(os.path.join(MESHES, mesh + ".stl"))
        zs = [p[2] for t in tris for p in t]
        surf = ocl_common.surface(tris)
        for k, f in enumerate(fractions):
            z = round(min(zs) + f * (max(zs) - min(zs)), 3)
            for kind in ("waterline", "adaptive"):
                loops, dt = ocl_common.waterline(
                    tris, spec, z, SAMPLING, kind == "adaptive", surf=surf
                )
                name = f"{kind}__{mesh}__{tag}__{k}.csv"
                with open(os.path.join(args.out, name), "w") as out:
                    out.write(f"# spec: {spec}\n# z: {z}\n# sampling: {SAMPLING}\n")
                    out.write(f"# kind: {kind}\n# seconds: {dt:.3f}\nloop,x,y\n")
                    for i, lp in enumerate(loops):
                        for x, y in lp:
                            out.write(f"{i},{x:.9f},{y:.9f}\n")
                print(name, len(loops), f"{dt:.2f} s", flush=True)


if __name__ == "__main__":
    main()
