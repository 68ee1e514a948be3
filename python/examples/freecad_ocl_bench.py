#!/usr/bin/env python3
"""FreeCAD's CAM workbench on OpenCAMLib and on swarf.ocl: the job of
``tests/test_freecad.py`` (a STEP part written by OpenCASCADE; 3D Surface Line and
ZigZag, Waterline OCL Dropcutter) at finer settings, recomputed in ``freecadcmd``
with each library as ``ocl``. Prints each operation's seconds, the seconds inside
``ocl`` calls (PathDropCutter setSTL, setPath, run, getCLPoints), the ratios, and
whether the posted G-code is the same.

Usage: python3 examples/freecad_ocl_bench.py [--tolerance 0.01] [--sampling 0.25]
[--stepover 25]  (needs freecadcmd, opencamlib and OCP)
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

TESTS = Path(__file__).resolve().parents[1] / "tests"
sys.path.insert(0, str(TESTS))
from ocl_meshes import write_step  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tolerance", type=float, default=0.01, help="the job's geometry tolerance, mm")
    ap.add_argument("--sampling", type=float, default=0.25, help="the operations' sample interval, mm")
    ap.add_argument("--stepover", type=float, default=25, help="step over, percent of the tool")
    args = ap.parse_args()
    import opencamlib

    shim = subprocess.run([sys.executable, "-m", "swarf.ocl", "shim"], capture_output=True, text=True, check=True).stdout.strip()
    paths = {"OpenCAMLib": os.path.dirname(opencamlib.ocl.__file__), "swarf.ocl": shim}
    with tempfile.TemporaryDirectory() as tmp:
        step = Path(tmp) / "part.step"
        write_step(step)
        results = {}
        for name, path in paths.items():
            out = Path(tmp) / name
            out.mkdir()
            job = {"step": str(step), "out": str(out), "tolerance": args.tolerance, "sampling": args.sampling, "stepover": args.stepover}
            env = {**os.environ, "SWARF_FREECAD_JOB": json.dumps(job), "PYTHONPATH": path}
            r = subprocess.run(["freecadcmd", str(TESTS / "freecad_cam.py")], capture_output=True, text=True, env=env)
            if r.returncode != 0:
                sys.exit(f"{name}: {r.stdout[-2000:]}{r.stderr[-2000:]}")
            results[name] = json.loads((out / "result.json").read_text())
        print(f"tolerance {args.tolerance} mm, sampling {args.sampling} mm, step over {args.stepover} %")
        print("| operation | OpenCAMLib (in ocl) | swarf.ocl (in ocl) | ratio (in ocl) | G-code |\n|---|---|---|---|---|")
        for op in results["OpenCAMLib"]["ops"]:
            t, o = results["OpenCAMLib"]["ops"][op], results["swarf.ocl"]["ops"][op]
            same = (Path(tmp) / "OpenCAMLib" / f"{op}.ngc").read_bytes() == (Path(tmp) / "swarf.ocl" / f"{op}.ngc").read_bytes()
            print(f"| {op} | {t['seconds']:.2f} s ({t['ocl_seconds']:.2f} s) | {o['seconds']:.2f} s ({o['ocl_seconds']:.2f} s) "
                  f"| {t['seconds'] / o['seconds']:.1f}x ({t['ocl_seconds'] / o['ocl_seconds']:.1f}x) | "
                  f"{'the same' if same else 'different'}, {len(t['commands'])} commands; {t['triangles']} triangles |")


if __name__ == "__main__":
    main()
