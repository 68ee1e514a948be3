#!/usr/bin/env python3
"""Plan a job, verify its program on a dexel stock and plot the deviation grid.

Plans jobs/wave-raster.toml (ball d=8, scallop limit 0.15 mm), verifies its G-code on
the wave with 0.25 mm cells along the design normals, and draws the deviation
(machined minus design, mm: blue material left, red below the design) with
matplotlib if it is installed; without it, prints the figures only.

Usage: python3 examples/plot_deviation.py [--job jobs/wave-raster.toml] [--cell 0.25]
           [-o deviation.png]   (run from the repository root)
"""

import argparse
import os
import tempfile

import numpy as np

import swarf


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--job", default="jobs/wave-raster.toml")
    ap.add_argument("--cell", type=float, default=0.25)
    ap.add_argument("-o", "--output", default="deviation.png")
    args = ap.parse_args()

    job = swarf.Job.load(args.job)
    plan = swarf.plan(job)
    with tempfile.TemporaryDirectory() as d:
        program = os.path.join(d, "program.ngc")
        plan.write_gcode(program)
        part = job.part if job.part.startswith("builtin:") else os.path.join(job.base_dir, job.part)
        v = swarf.verify(part, program, job.tool, cell=args.cell)
    s = v.report["deviation"]
    print(f"{args.job}: {plan.summary['passes']} passes, {len(plan.poses)} moves")
    print(f"deviation from {np.nanmin(v.deviation):.3f} to {np.nanmax(v.deviation):.3f} mm "
          f"over {v.deviation.shape[1]} x {v.deviation.shape[0]} cells of {v.cell} mm; "
          f"gouge cells {s['gouge']['cells']}, excess cells {s['excess']['cells']}")
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no picture (pip install matplotlib)")
        return
    fig, ax = plt.subplots(figsize=(10, 5.5))
    lim = float(np.nanmax(np.abs(v.deviation)))
    im = ax.imshow(v.deviation, origin="lower", extent=v.extent, cmap="coolwarm_r", vmin=-lim, vmax=lim)
    ax.set_xlabel("x, mm")
    ax.set_ylabel("y, mm")
    ax.set_title(f"{v.report['deviation_mode']} deviation: {job.name or args.job}, {job.tool}")
    fig.colorbar(im, ax=ax, label="machined - design, mm")
    fig.savefig(args.output, dpi=120, bbox_inches="tight")
    print(f"picture: {args.output}")


if __name__ == "__main__":
    main()
