"""Sequence jobs (`[[operation]]` tables, stock to part): planned from a path, TOML
text or a dict into a `SequencePlan`, identical to `swarf plan` (program, report,
printed lines, output files); errors naming `operation[k]`."""

import json

import numpy as np
import pytest

import swarf

# A quick sequence: one raster operation from a box on the deep pocket (a 60 x 60
# block, a 10 x 40 pocket 40 deep at x 25 to 35), no tool library: the pocket's
# material is left as rest.
DEEP_POCKET = {
    "name": "deep pocket",
    "part": "builtin:deep-pocket",
    "stock": {"kind": "box", "cell": 0.5},
    "operation": [
        {"name": "finish", "tool": "ball:d=6", "strategy": {"kind": "raster", "scallop": 0.5, "tolerance": 0.01}},
    ],
}


@pytest.fixture(scope="module")
def fillet_pocket(cli, repo, tmp_path_factory):
    """jobs/fillet-pocket-sequence.toml planned by the command line and by
    `swarf.plan`, each into its own folder: (plan, printed lines, cli dir, py dir)."""
    job = repo / "jobs" / "fillet-pocket-sequence.toml"
    cli_dir = tmp_path_factory.mktemp("cli")
    printed = cli.run("plan", job, "--out", cli_dir).splitlines()
    py_dir = tmp_path_factory.mktemp("py")
    return swarf.plan(job, out=py_dir), printed, cli_dir, py_dir


def test_fillet_pocket_sequence_stock_to_part(fillet_pocket):
    p, _, _, _ = fillet_pocket
    assert isinstance(p, swarf.SequencePlan)
    ops = p.operations
    assert [op["name"] for op in ops] == ["rough", "rest-rough", "finish", "cleanup"]
    assert p.report["operations"] == ops
    assert all(op["gouge_cells"] == 0 for op in ops), [op["gouge_cells"] for op in ops]
    assert ops[-1]["rest_cells"] == 0
    rough = ops[0]["engagement"]
    assert rough is not None and rough["max_deg"] <= rough["limit_deg"] + 1, rough
    tool_changes = [l for l in p.program.splitlines() if "M6" in l.split(";")[0].split()]
    assert len(tool_changes) == 4, tool_changes
    assert len(p.programs) == 4
    assert p.rest.shape == (0, 3) and p.rest.dtype == np.float64
    assert p.report["time_s"] == pytest.approx(sum(op["time_s"] for op in ops))
    assert repr(p).startswith("SequencePlan(4 operations")


def test_fillet_pocket_sequence_matches_swarf_plan(fillet_pocket, repo):
    p, printed, cli_dir, py_dir = fillet_pocket
    assert p.lines() == printed
    assert len(p.lines()) == len(p.operations) + 1
    for op, line in zip(p.operations, p.lines()):
        assert line.startswith(f"T{op['number']} {op['name']} ({op['strategy']}, {op['tool']})"), line
    # With `out`, the files the command line writes, byte for byte.
    assert sorted(f.name for f in py_dir.iterdir()) == sorted(f.name for f in cli_dir.iterdir())
    for f in cli_dir.iterdir():
        assert (py_dir / f.name).read_bytes() == f.read_bytes(), f.name
    assert p.program == (cli_dir / "fillet-pocket-sequence.ngc").read_text()
    assert p.report == json.loads((cli_dir / "fillet-pocket-sequence.json").read_text())


def test_sequence_from_dict_and_text(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    tomllib = pytest.importorskip("tomllib")
    d = swarf.plan(DEEP_POCKET)
    assert isinstance(d, swarf.SequencePlan) and len(d.operations) == 1
    op = d.operations[0]
    assert op["strategy"] == "raster" and op["tool"] == "ball:d=6" and op["gouge_cells"] == 0
    rest = d.rest
    assert op["rest_cells"] > 0 and rest.shape == (op["rest_cells"], 3)
    assert (rest[:, 2] > op["rest_limit_mm"]).all() and rest[:, 2].max() > 30
    assert (rest[:, 0] > 25).all() and (rest[:, 0] < 35).all(), "rest lies in the pocket"
    # The same sequence as TOML text plans the same program.
    text = 'name = "deep pocket"\npart = "builtin:deep-pocket"\n' \
           '[stock]\nkind = "box"\ncell = 0.5\n' \
           '[[operation]]\nname = "finish"\ntool = "ball:d=6"\n' \
           'strategy = { kind = "raster", scallop = 0.5, tolerance = 0.01 }\n'
    assert tomllib.loads(text) == DEEP_POCKET
    t = swarf.plan(text)
    assert t.program == d.program and t.report == d.report and t.lines() == d.lines()
    # Without `out` nothing is written.
    assert list(tmp_path.iterdir()) == []
    path = tmp_path / "g.ngc"
    t.write_gcode(path)
    assert path.read_text() == t.program


def test_bad_sequences_name_the_operation(cli, repo, tmp_path):
    library = (repo / "tooling" / "library.toml").as_posix()
    good = (repo / "jobs" / "fillet-pocket-sequence.toml").read_text()
    cleanup_first = good.replace('kind = "roughing", allowance = 0.5, step_down = 4, max_engagement = 60, '
                                 'ramp_angle = 3, tolerance = 0.01 }\nfeeds = { feed = 1500, plunge = 400, '
                                 'spindle = 9000 }',
                                 'kind = "cleanup", scallop = 0.01 }', 1)
    assert cleanup_first != good
    no_such_tool = good.replace('part = "builtin:fillet-pocket"',
                                f'part = "builtin:fillet-pocket"\ntools = "{library}"', 1) \
        .replace('tool = "flat:d=10"', "tool = 99", 1)
    assert no_such_tool != good
    for k, text in enumerate([cleanup_first, no_such_tool]):
        job = tmp_path / f"seq{k}.toml"
        job.write_text(text)
        theirs = cli.fail("plan", job, "--out", tmp_path / "out")
        assert "operation[0]: " in theirs, theirs
        with pytest.raises(swarf.SwarfError) as e:
            swarf.plan(job)
        assert str(e.value) == theirs
        with pytest.raises(swarf.SwarfError, match=r"^<toml>: operation\[0\]: "):
            swarf.plan(text)
    with pytest.raises(swarf.SwarfError, match=r"^job dict: operation\[0\]: strategy.kind: a cleanup cannot be"):
        swarf.plan({**DEEP_POCKET, "operation": [{"tool": "ball:d=6", "strategy": {"kind": "cleanup"}}]})
    with pytest.raises(swarf.SwarfError, match=r"^job dict: stock.cell: "):
        swarf.plan({**DEEP_POCKET, "stock": {"cell": 0.0}})
    # A Job holds a single job: a sequence is refused with where it goes instead.
    with pytest.raises(swarf.SwarfError, match=r"a sequence job .*swarf.plan takes a sequence"):
        swarf.Job.load(repo / "jobs" / "fillet-pocket-sequence.toml")
    with pytest.raises(swarf.SwarfError, match=r"^job dict: a sequence job"):
        swarf.Job.from_dict(DEEP_POCKET)
