"""FreeCAD's CAM workbench, headless (``freecadcmd``, Debian's ``freecad``), on a
STEP part written by OpenCASCADE: 3D Surface (Line, ZigZag) and Waterline (OCL
Dropcutter) recomputed once with OpenCAMLib as ``ocl`` and once with swarf.ocl
through its shim (``python3 -m swarf.ocl shim`` on ``PYTHONPATH``). Their G-code
moves are the same within 1e-4 mm (FreeCAD posts four decimals here), and
``swarf verify`` finds the same gouge and excess in both programs. The operation
times and their ratio are printed (``examples/freecad_ocl_bench.py`` is the
benchmark). Skipped without ``freecadcmd``, unless ``SWARF_REQUIRE_REFERENCES=1``.
"""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import REQUIRE, _missing
from ocl_meshes import write_step

HERE = Path(__file__).resolve().parent
TOOLS = {"surface_line": "ball:d=6", "surface_zigzag": "flat:d=5", "waterline": "ball:d=6"}
MOVES = ("G0", "G1", "G2", "G3")


def freecad_run(step, out, pythonpath, **settings):
    """Runs ``freecad_cam.py`` in ``freecadcmd`` with ``ocl`` found on ``pythonpath``."""
    out.mkdir()
    job = {"step": str(step), "out": str(out), "tolerance": 0.05, "sampling": 1.0, "stepover": 50, **settings}
    env = {**os.environ, "SWARF_FREECAD_JOB": json.dumps(job), "PYTHONPATH": pythonpath}
    r = subprocess.run(["freecadcmd", str(HERE / "freecad_cam.py")], capture_output=True, text=True, env=env, timeout=1200)
    assert r.returncode == 0 and (out / "result.json").is_file(), r.stdout[-3000:] + r.stderr[-3000:]
    return json.loads((out / "result.json").read_text())


@pytest.fixture(scope="module")
def runs(ocl, tmp_path_factory):
    if shutil.which("freecadcmd") is None:
        _missing("freecadcmd (apt-get install freecad)")
    try:
        import OCP  # noqa: F401
    except ImportError:
        _missing("OCP (cadquery-ocp) to write the STEP part")
    probe = subprocess.run(["freecadcmd", "-c", "import sys; print('PY', sys.version_info[:2])"], capture_output=True, text=True)
    if f"PY {sys.version_info[:2]}" not in probe.stdout:
        _missing(f"a FreeCAD whose Python is {sys.version_info[0]}.{sys.version_info[1]}, as the one OpenCAMLib and swarf are installed in")
    tmp = tmp_path_factory.mktemp("freecad")
    step = tmp / "part.step"
    write_step(step)
    shim = subprocess.run(
        [sys.executable, "-m", "swarf.ocl", "shim"], capture_output=True, text=True, check=True
    ).stdout.strip()
    theirs = freecad_run(step, tmp / "opencamlib", os.path.dirname(ocl.ocl.__file__))
    ours = freecad_run(step, tmp / "swarf", shim)
    return tmp, theirs, ours


def moves(op):
    return [c for c in op["commands"] if c[0] in MOVES]


def test_freecad_used_each_library(runs):
    _, theirs, ours = runs
    assert "opencamlib" in theirs["ocl"] and "swarf" not in theirs["version"]
    assert "swarf" in ours["ocl"] and "swarf" in ours["version"]


@pytest.mark.parametrize("op", list(TOOLS))
def test_gcode_moves_are_the_same(runs, op, capsys):
    _, theirs, ours = runs
    a, b = moves(theirs["ops"][op]), moves(ours["ops"][op])
    assert len(a) > 20 and sum(c[0] == "G1" for c in a) > 10, f"{op}: the operation cuts"
    assert [c[0] for c in a] == [c[0] for c in b], f"{op}: {len(a)} moves, swarf {len(b)}"
    worst = 0.0
    for (_, pa), (_, pb) in zip(a, b):
        assert set(pa) == set(pb)
        worst = max([worst] + [abs(pa[k] - pb[k]) for k in pa])
    assert worst <= 1e-4, f"{op}: end points differ by {worst} mm"
    t, o = theirs["ops"][op], ours["ops"][op]
    tmp = runs[0]
    same = (tmp / "opencamlib" / f"{op}.ngc").read_bytes() == (tmp / "swarf" / f"{op}.ngc").read_bytes()
    with capsys.disabled():
        print(f"\n  FreeCAD {op}: {len(a)} moves, max difference {worst:.1e} mm, posted G-code "
              f"{'byte for byte the same' if same else 'different text'}; operation "
              f"{t['seconds']:.2f} s with OpenCAMLib, {o['seconds']:.2f} s with swarf ({t['seconds'] / o['seconds']:.1f}x); "
              f"in ocl calls {t['ocl_seconds']:.2f} s and {o['ocl_seconds']:.2f} s ({t['ocl_seconds'] / o['ocl_seconds']:.1f}x)")


@pytest.mark.parametrize("op", list(TOOLS))
def test_verify_finds_the_same(runs, cli, op):
    tmp, _, _ = runs
    reports = []
    for lib in ("opencamlib", "swarf"):
        out = tmp / f"verify-{lib}-{op}"
        cli.run("verify", "--part", tmp / "opencamlib" / "part.stl", "--program", tmp / lib / f"{op}.ngc",
                "--tool", TOOLS[op], "--stock", "box", "--tol", 0.05, "-o", out)
        reports.append(json.loads((out / "report.json").read_text()))
    figures = [
        {kind: {k: r["deviation"][kind][k] for k in ("cells", "worst", "volume_mm3", "regions")} for kind in ("gouge", "excess")}
        for r in reports
    ]
    assert figures[0] == figures[1], figures
    assert figures[0]["excess"]["cells"] > 0 and reports[0]["complete"]
