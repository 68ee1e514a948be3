"""OpenCAMLib scripts run twice, as written (``from opencamlib import ocl``) and with
that import replaced by ``import swarf.ocl as ocl``, nothing else changed: the two
outputs match.

- ``ocl_scripts/``: scripts written for these tests in the manner of OpenCAMLib's
  ``examples/python`` (points and cutters, paths with PathDropCutter and
  AdaptivePathDropCutter, BatchDropCutter, waterlines), run always;
- OpenCAMLib's own ``examples/python`` from a checkout of its sources named by
  ``$SWARF_OCL_EXAMPLES`` (its ``stl/`` folder beside them), those that need no VTK
  window: skipped without the checkout (the sources are on GitHub only, not in a
  registry CI installs from).

Matching: line by line, the words equal and every number equal within 1.5e-5 of
its size (six significant digits are printed) or 1e-6 mm; lines of the form
``G01 X.. Y.. Z..`` in a section whose heading names a waterline are compared as
loops instead (OpenCAMLib's points are fiber crossings, swarf's exact contour points
joined within a tolerance): every OpenCAMLib point within 0.02 mm of swarf's loops,
every swarf point within OpenCAMLib's sampling (0.1 mm) of OpenCAMLib's loops. The
second is looser because OpenCAMLib's chords cut across the contour's corners
(``test_ocl_parity.py`` checks those places against exact drops). OpenCAMLib's
destructor messages (``~Waterline_py()``) and swarf's name in ``version()`` are left
out.
"""

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from conftest import _missing
from ocl_meshes import distance_to

HERE = Path(__file__).resolve().parent
SCRIPTS = sorted((HERE / "ocl_scripts").glob("[!m]*.py"))
IMPORT = "from opencamlib import ocl"
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|nan|inf")
UPSTREAM = [
    "ocl_test0.py",
    "ocl_clpoint.py",
    "ocl_offsetCutter_1.py",
    "path_example_1.py",
    "drop-cutter/drop_cutter_tst_1.py",
    "drop-cutter/drop_cutter_tst_2.py",
    "issues/issue08_bug2010-04-02.py",
]


def run(script, swarf, cwd, extra_path=()):
    """The script's output, run from ``cwd`` with the import replaced for swarf."""
    text = Path(script).read_text()
    assert IMPORT in text, f"{script} does not import OpenCAMLib as its examples do"
    if swarf:
        text = text.replace(IMPORT, "import swarf.ocl as ocl")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([*extra_path, os.environ.get("PYTHONPATH", "")])}
    r = subprocess.run([sys.executable, "-c", text], capture_output=True, text=True, cwd=cwd, env=env, timeout=600)
    assert r.returncode == 0, f"{script} ({'swarf' if swarf else 'OpenCAMLib'}): {r.stderr[-2000:]}"
    lines = [l for l in r.stdout.splitlines() if not re.fullmatch(r"~\w+_py\(\)", l.strip())]
    return [re.sub(r" \(swarf [^)]*\)", "", l) for l in lines]


def sections(lines):
    """``[(heading, [lines])]``: a heading is a line that is not a G01 move."""
    out = [("", [])]
    for l in lines:
        if l.startswith("G01 ") or l == "loop":
            out[-1][1].append(l)
        else:
            out.append((l, []))
    return out


def numbers_match(a, b):
    na, nb = NUMBER.findall(a), NUMBER.findall(b)
    if NUMBER.sub("#", a) != NUMBER.sub("#", b) or len(na) != len(nb):
        return False
    for x, y in zip(map(float, na), map(float, nb)):
        if not (x == y or abs(x - y) <= max(1e-6, 1.5e-5 * max(abs(x), abs(y)))):
            return False
    return True


def loops(lines):
    out, cur = [], None
    for l in lines:
        if l == "loop":
            cur = []
            out.append(cur)
        else:
            cur.append([float(v[1:]) for v in l.split()[1:3]])
    return [np.array(lp) for lp in out if lp]


def assert_outputs_match(theirs, ours, name):
    st, so = sections(theirs), sections(ours)
    assert len(st) == len(so), f"{name}: {len(st)} sections, swarf {len(so)}"
    for (ht, bt), (ho, bo) in zip(st, so):
        assert numbers_match(ht, ho), f"{name}:\n  OpenCAMLib: {ht}\n  swarf:      {ho}"
        if "aterline" in ht:
            lt, lo = loops(bt), loops(bo)
            assert bool(lt) == bool(lo), f"{name}: {ht}: {len(lt)} loops, swarf {len(lo)}"
            if lt:
                theirs_off = distance_to(np.concatenate(lt), lo)[0].max()
                ours_off = distance_to(np.concatenate(lo), lt)[0].max()
                assert theirs_off <= 0.02, f"{name}: {ht}: an OpenCAMLib point {theirs_off:.4f} mm off swarf's loops"
                assert ours_off <= 0.1, f"{name}: {ht}: a swarf point {ours_off:.4f} mm off OpenCAMLib's loops"
            continue
        assert len(bt) == len(bo), f"{name}: {ht}: {len(bt)} lines, swarf {len(bo)}"
        for a, b in zip(bt, bo):
            assert numbers_match(a, b), f"{name}: {ht}:\n  OpenCAMLib: {a}\n  swarf:      {b}"


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.stem)
def test_scripts_run_unchanged_on_swarf(ocl, script, tmp_path):
    extra = [str(HERE / "ocl_scripts")]
    (tmp_path / "ocl").mkdir()
    (tmp_path / "swarf").mkdir()
    theirs = run(script, False, tmp_path / "ocl", extra)
    ours = run(script, True, tmp_path / "swarf", extra)
    assert len(theirs) > 5
    assert_outputs_match(theirs, ours, script.name)


@pytest.mark.parametrize("example", UPSTREAM)
def test_opencamlib_examples_run_unchanged_on_swarf(ocl, example):
    root = os.environ.get("SWARF_OCL_EXAMPLES")
    if not root or not (Path(root) / "examples/python" / example).is_file():
        pytest.skip(f"OpenCAMLib's example {example}: $SWARF_OCL_EXAMPLES names no checkout of its sources")
    script = Path(root) / "examples/python" / example
    theirs = run(script, False, script.parent)
    ours = run(script, True, script.parent)
    assert_outputs_match(theirs, ours, example)
