"""Verification: the report and the deviation grid identical to `swarf verify`'s
report.json and flagged.csv; several programs on one stock; bad input."""

import json

import numpy as np
import pytest

import swarf
from test_plan import untimed


def flagged_rows(v):
    """flagged.csv's first six columns, from the arrays (gouges, then excess)."""
    s = v.report["deviation"]
    tol, allowed = s["tol"], s["allowed_excess"]
    dev, design, machined = v.deviation, v.design, v.machined
    rows = []
    with np.errstate(invalid="ignore"):
        masks = [("gouge", dev < -tol), ("excess", dev > allowed + tol)]
    for kind, mask in masks:
        for j, i in zip(*np.nonzero(mask)):
            rows.append(f"{v.x[i]:.4f},{v.y[j]:.4f},{design[j, i]:.6f},{machined[j, i]:.6f},"
                        f"{dev[j, i]:.6f},{kind}")
    return rows


@pytest.fixture(scope="module")
def wave_program(cli, repo, tmp_path_factory):
    d = tmp_path_factory.mktemp("wave")
    cli.run("plan", repo / "jobs" / "wave-raster.toml", "--out", d)
    return d / "wave-raster.ngc"


def plane_part(tmp_path):
    part = tmp_path / "plane.toml"
    part.write_text('name = "plane"\nunits = "mm"\n[[patch]]\ndegree = [1, 1]\n'
                    "points = [[0, 0, 0], [0, 10, 0], [20, 0, 0], [20, 10, 0]]\n")
    return part


def raster(step, r, gouge_at=None):
    g = "G21 G90 G17\nG0 Z5\n"
    for k in range(int(round(10 / step)) + 1):
        y = k * step
        g += f"G0 X{-(r + 1)} Y{y:.4f}\nG1 Z0 F300\n"
        if gouge_at == k:
            g += "G1 X10 Z-0.05 F600\n"
        g += f"G1 X{20 + r + 1} Z0 F600\nG0 Z5\n"
    return g


@pytest.mark.parametrize("mode", ["normal", "vertical"])
def test_verify_matches_swarf_verify(cli, wave_program, tmp_path, mode):
    out = tmp_path / "cli"
    cli.run("verify", "--part", "builtin:wave", "--program", wave_program, "--tool", "ball:d=8",
            "--cell", 0.25, "--deviation", mode, "-o", out)
    v = swarf.verify("builtin:wave", wave_program, "ball:d=8", cell=0.25, deviation=mode)
    theirs = json.loads((out / "report.json").read_text())
    assert untimed(v.report) == untimed(theirs)
    g = theirs["grid"]
    assert v.deviation.shape == (g["ny"], g["nx"]) == v.design.shape == v.machined.shape
    assert v.cell == 0.25 and v.extent[0] == g["origin_mm"][0] and v.complete
    csv = (out / "flagged.csv").read_text().splitlines()[1:]
    assert len(csv) > 1000
    assert flagged_rows(v) == [",".join(r.split(",")[:6]) for r in csv]
    assert any("scallop allowance 0.15 mm" in n for n in v.notes)
    # With `out`: the command's files (the report but for its times).
    py = tmp_path / "py"
    swarf.verify("builtin:wave", wave_program, swarf.Tool("ball:d=8"), cell=0.25, deviation=mode, out=py)
    assert untimed(json.loads((py / "report.json").read_text())) == untimed(theirs)
    for f in ["flagged.csv", "deviation.png", "toolpath.png"]:
        assert (py / f).read_bytes() == (out / f).read_bytes(), f


def test_two_programs_on_one_stock_and_a_gouge(cli, tmp_path):
    part = plane_part(tmp_path)
    finish, cleanup = tmp_path / "finish.ngc", tmp_path / "cleanup.ngc"
    finish.write_text(raster(2.5, 3.0, gouge_at=2))
    cleanup.write_text(raster(0.5, 1.0))
    out = tmp_path / "cli"
    cli.run("verify", "--part", part, "--program", finish, "--tool", "ball:d=6", "--program", cleanup,
            "--tool", "ball:d=2", "--cell", 0.05, "--floor", 0, "-o", out)
    v = swarf.verify(part, [finish, cleanup], ["ball:d=6", "ball:d=2"], cell=0.05, floor=0.0)
    theirs = json.loads((out / "report.json").read_text())
    assert untimed(v.report) == untimed(theirs)
    assert v.report["tool"] == "ball:d=6 + ball:d=2"
    # The gouging move goes below the floor at the plane, named with its program.
    below = v.report["floor"]["below"]
    assert below and all(b["program"].endswith("finish.ngc") and b["amount"] > 0.01 for b in below)
    assert np.nanmin(v.deviation) < -0.04, "the gouge is in the grid"
    csv = (out / "flagged.csv").read_text().splitlines()[1:]
    assert flagged_rows(v) == [",".join(r.split(",")[:6]) for r in csv]


def test_stopped_program(cli, tmp_path):
    part = plane_part(tmp_path)
    prog = tmp_path / "stopped.ngc"
    prog.write_text("".join(raster(2.5, 3.0).splitlines(True)[:10]) + "G1 X4 Y\n")
    with pytest.raises(swarf.SwarfError, match=r"the program stopped at .*stopped.ngc:11"):
        swarf.verify(part, prog, "ball:d=6", cell=0.1)
    v = swarf.verify(part, prog, "ball:d=6", cell=0.1, partial=True)
    assert not v.complete and v.report["complete"] is False
    out = tmp_path / "cli"
    msg = cli.fail("verify", "--part", part, "--program", prog, "--tool", "ball:d=6", "--cell", 0.1,
                   "--partial", "-o", out)
    assert "stopped.ngc:11" in msg
    assert untimed(v.report) == untimed(json.loads((out / "report.json").read_text()))


def test_verify_errors_match_swarf_verify(cli, wave_program, tmp_path):
    cases = [
        (dict(tool="ball:q=8"), ["--tool", "ball:q=8"]),
        (dict(tool="ball:d=8", stock="cylinder"), ["--tool", "ball:d=8", "--stock", "cylinder"]),
        (dict(tool="ball:d=8", cell=0.0), ["--tool", "ball:d=8", "--cell", "0"]),
        (dict(tool="ball:d=8", tol=50.0), ["--tool", "ball:d=8", "--tol", "50"]),
        (dict(tool="ball:d=8", cell=0.0001), ["--tool", "ball:d=8", "--cell", "0.0001"]),
        (dict(tool=["ball:d=8", "ball:d=4"]), ["--tool", "ball:d=8", "--tool", "ball:d=4"]),
        (dict(tool="ball:d=8", tool_table=tmp_path / "none.tbl"), ["--tool", "ball:d=8", "--tool-table", tmp_path / "none.tbl"]),
    ]
    for kwargs, flags in cases:
        theirs = cli.fail("verify", "--part", "builtin:wave", "--program", wave_program, *flags, "-o", tmp_path / "o")
        with pytest.raises(swarf.SwarfError) as e:
            swarf.verify("builtin:wave", wave_program, **kwargs)
        assert str(e.value) == theirs, kwargs
    missing = tmp_path / "none.ngc"
    theirs = cli.fail("verify", "--part", "builtin:wave", "--program", missing, "-o", tmp_path / "o")
    with pytest.raises(swarf.SwarfError) as e:
        swarf.verify("builtin:wave", missing)
    assert str(e.value) == theirs
    with pytest.raises(swarf.SwarfError, match="--deviation sideways: expected normal or vertical"):
        swarf.verify("builtin:wave", wave_program, "ball:d=8", deviation="sideways")
    with pytest.raises(TypeError):
        swarf.verify("builtin:wave", 42)
