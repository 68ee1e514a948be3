"""Jobs: planned from a file, TOML text or a dict, identical to `swarf plan` (G-code,
APT CL, pose CSV and summary); the plan as arrays; errors with the command line's
messages."""

import json
import shutil

import numpy as np
import pytest

import swarf

JOBS = ["wave-raster", "wave-iso-scallop", "fillet-pocket-finish", "die-inclined-3", "boss-raster"]
# The fixed lead gouges the die: its program is written only when allowed, labelled.
UNSAFE = {"die-inclined-3"}


def untimed(value):
    """`value` without its wall-clock fields (`elapsed_s`, `timings_s`)."""
    if isinstance(value, dict):
        return {k: untimed(v) for k, v in value.items() if not (k.endswith("elapsed_s") or k == "timings_s")}
    if isinstance(value, list):
        return [untimed(v) for v in value]
    return value


def pose_csv(passes, feed):
    """The pose CSV `swarf plan` writes (mm), from the plan's passes."""
    lines = ["x,y,z,i,j,k", "# units=mm", f"# feed={feed}"]
    for k, p in enumerate(passes):
        lines.append(f"# pass {k}")
        lines += [f"{x:.6f},{y:.6f},{z:.6f},{i:.9f},{j:.9f},{kk:.9f}" for x, y, z, i, j, kk in p]
    return "\n".join(lines) + "\n"


@pytest.fixture(scope="module")
def planned(cli, repo, tmp_path_factory):
    """Each job planned by the command line into its own folder."""
    out = {}
    for name in JOBS:
        d = tmp_path_factory.mktemp(name)
        allow = ["--allow-unsafe"] if name in UNSAFE else []
        cli.run("plan", repo / "jobs" / f"{name}.toml", "--out", d, *allow)
        out[name] = d
    return out


@pytest.mark.parametrize("name", JOBS)
def test_plan_matches_swarf_plan(planned, repo, name, tmp_path):
    job = swarf.Job.load(repo / "jobs" / f"{name}.toml")
    cli_dir = planned[name]
    text = job.toml
    unsafe = name in UNSAFE
    p = swarf.plan(repo / "jobs" / f"{name}.toml", allow_unsafe=unsafe)
    if unsafe:
        assert "UNSAFE, written with --allow-unsafe" in p.gcode
    outputs = {k: v for k, v in _output_table(text).items()}
    if "gcode" in outputs:
        assert p.gcode == (cli_dir / outputs["gcode"]).read_text()
    if "cl" in outputs:
        assert p.cl == (cli_dir / outputs["cl"]).read_text()
    if "csv" in outputs:
        csv = (cli_dir / outputs["csv"]).read_text()
        feed = csv.splitlines()[2].split("=", 1)[1]
        assert pose_csv(p.passes, feed) == csv
    if "summary" in outputs:
        theirs = json.loads((cli_dir / outputs["summary"]).read_text())
        assert untimed(p.summary) == untimed(theirs)
    # With `out`, the same files as the command line (the summary but for its times).
    py_dir = tmp_path / "py"
    swarf.plan(job, out=py_dir, allow_unsafe=unsafe)
    assert sorted(f.name for f in py_dir.iterdir()) == sorted(f.name for f in cli_dir.iterdir())
    for key, rel in outputs.items():
        if not (cli_dir / rel).exists():
            continue
        if key == "summary":
            a = json.loads((py_dir / rel).read_text())
            b = json.loads((cli_dir / rel).read_text())
            assert untimed(a) == untimed(b)
        elif key in ("gcode", "cl", "csv", "double_contacts", "contacts"):
            assert (py_dir / rel).read_bytes() == (cli_dir / rel).read_bytes(), rel


def _output_table(text):
    """The `[output]` file names of a job's TOML text."""
    tomllib = pytest.importorskip("tomllib")
    out = tomllib.loads(text).get("output", {})
    return {k: v for k, v in out.items() if k in ("gcode", "cl", "csv", "summary", "double_contacts", "contacts")}


def test_plan_arrays(repo):
    p = swarf.plan(repo / "jobs" / "wave-raster.toml")
    poses, kinds, feeds, passes = p.poses, p.kinds, p.feeds, p.pass_index
    n = len(poses)
    assert poses.shape == (n, 6) and kinds.shape == (n,) and feeds.shape == (n,) and passes.shape == (n,)
    assert set(np.unique(kinds)) == {swarf.MOVE_RAPID, swarf.MOVE_FEED}
    assert (feeds[kinds == swarf.MOVE_RAPID] == 0).all()
    assert np.allclose(np.linalg.norm(poses[:, 3:], axis=1), 1.0)
    cutting = passes >= 0
    assert (kinds[cutting] == swarf.MOVE_FEED).all()
    assert (feeds[cutting] == 300).all()
    # Every pass's poses after its first are the cutting moves of that pass, in order.
    for k, pts in enumerate(p.passes):
        assert np.array_equal(poses[passes == k], pts[1:])
    g1 = sum(1 for line in p.gcode.splitlines() if line.startswith("G1"))
    assert g1 > 0 and p.summary["passes"] == len(p.passes)


def test_plan_from_toml_text_and_dict(repo, tmp_path):
    tomllib = pytest.importorskip("tomllib")
    path = repo / "jobs" / "wave-iso-scallop.toml"
    ref = swarf.plan(path)
    text = path.read_text()
    from_text = swarf.plan(swarf.Job.from_toml(text, base_dir=repo / "jobs"))
    assert from_text.gcode == ref.gcode and from_text.cl == ref.cl
    assert swarf.plan(text).gcode == ref.gcode, "a str with line breaks is TOML text"
    d = tomllib.loads(text)
    from_dict = swarf.plan(d)
    assert from_dict.gcode == ref.gcode
    assert untimed(from_dict.summary) == untimed(ref.summary)
    j = swarf.Job.from_dict(d)
    assert j.kind == "iso-scallop" and j.tool == swarf.Tool("ball:d=8") and j.part == "builtin:wave"
    p = tmp_path / "a.ngc"
    ref.write_gcode(p)
    ref.write_cl(tmp_path / "a.cl")
    assert p.read_text() == ref.gcode and (tmp_path / "a.cl").read_text() == ref.cl


def test_plan_is_verified_on_the_stock_unless_asked_not_to(repo):
    """The gate of `swarf plan`: the three-axis program simulated on the job's stock
    (a box 1 mm above the wave by default), its verdict in the summary and header."""
    path = repo / "jobs" / "wave-raster.toml"
    p = swarf.plan(path)
    v = p.summary["verification"]
    assert v["stock"] == "box, top 50.972 mm"
    assert v["rapid_cuts"] == [] and v["gouge_cells"] == 0 and not v["written_unsafe"]
    assert "(verified on box, top 50.972 mm, 0.2 mm cells: 0 rapids in material, 0 gouge cells" in p.gcode
    skipped = swarf.plan(path, verify=False)
    assert skipped.summary["verification"] == {"skipped": "--no-verify"}
    assert "(not verified: --no-verify)" in skipped.gcode
    assert swarf.plan(path, allow_unsafe=True).gcode == p.gcode, "a safe program is not labelled"


def test_plan_errors_match_swarf_plan(cli, tmp_path):
    good = 'name = "x"\npart = "builtin:wave"\ntool = "ball:d=8"\n[strategy]\nkind = "raster"\nscallop = 0.2\n'
    cases = [
        good.replace("scallop = 0.2", "scallop = 0.2\nfoo = 1"),
        good.replace("scallop = 0.2", "scallop = -1"),
        good.replace('"raster"', '"rasterx"'),
        good.replace("ball:d=8", "ball:d=0"),
        good.replace("builtin:wave", "nothing.toml"),
        good.replace("[strategy]", "[strategy\n"),
    ]
    for k, text in enumerate(cases):
        job = tmp_path / f"job{k}.toml"
        job.write_text(text)
        theirs = cli.fail("plan", job, "--out", tmp_path / "out")
        with pytest.raises(swarf.SwarfError) as e:
            swarf.plan(job, out=tmp_path / "py")
        assert str(e.value) == theirs, text
        with pytest.raises(swarf.SwarfError) as e:
            swarf.plan(job)
        assert str(e.value) == theirs, text
    missing = tmp_path / "missing.toml"
    theirs = cli.fail("plan", missing)
    with pytest.raises(swarf.SwarfError) as e:
        swarf.plan(missing)
    assert str(e.value) == theirs


def test_plan_dict_errors_name_the_key():
    base = {"part": "builtin:wave", "tool": "ball:d=8", "strategy": {"kind": "raster", "scallop": 0.2}}
    with pytest.raises(swarf.SwarfError, match=r"^job dict: strategy.foo: unknown field `foo`"):
        swarf.plan({**base, "strategy": {**base["strategy"], "foo": 1}})
    with pytest.raises(swarf.SwarfError, match=r"^job dict: strategy.scallop: expected a scallop height"):
        swarf.plan({**base, "strategy": {**base["strategy"], "scallop": -1.0}})
    with pytest.raises(swarf.SwarfError, match=r"^job dict: feeds.feed: "):
        swarf.plan({**base, "feeds": {"feed": "fast"}})
    with pytest.raises(swarf.SwarfError, match=r"strategy.boundary\[1\]: a object cannot be written|strategy.boundary\[1\]: a .* cannot be written"):
        swarf.plan({**base, "strategy": {**base["strategy"], "boundary": [0, object(), 1, 2]}})
    with pytest.raises(TypeError, match="job: expected a Job, a dict, TOML text or a path"):
        swarf.plan(3)


def test_drop_spin_job_with_and_without_a_machine(cli, repo, tmp_path):
    """jobs/edge-concave-drop-spin.toml with fewer stations and passes: five-axis
    G-code for its machine as `swarf plan` writes it; without a machine, APT CL and
    no G-code (a tilted path needs a machine)."""
    tomllib = pytest.importorskip("tomllib")
    d = tomllib.loads((repo / "jobs" / "edge-concave-drop-spin.toml").read_text())
    d["strategy"].update(step=20, passes=2, bands="first")
    job = swarf.Job.from_dict(d)
    path = tmp_path / "ds.toml"
    path.write_text(job.toml)
    cli.run("plan", path, "--out", tmp_path / "cli")
    p = swarf.plan(job)
    assert p.gcode == (tmp_path / "cli" / d["output"]["gcode"]).read_text()
    assert p.cl == (tmp_path / "cli" / d["output"]["cl"]).read_text()
    assert untimed(p.summary) == untimed(json.loads((tmp_path / "cli" / d["output"]["summary"]).read_text()))
    assert not np.allclose(p.poses[:, 5], 1.0), "the drop-spin tool is tilted"
    d["output"] = {"cl": "x.cl"}
    bare = swarf.plan(d)
    assert bare.gcode is None and bare.cl == p.cl
    with pytest.raises(swarf.SwarfError, match="this plan has no G-code"):
        bare.write_gcode(tmp_path / "never.ngc")


def test_raster_and_waterline_match_swarf_plan(cli, tmp_path):
    """The strategy functions give the passes of a job with that strategy."""
    cases = [
        ("raster", "builtin:boss", "ball:d=6", {"scallop": 0.2, "angle": 30}),
        ("waterline", "builtin:boss", "ball:d=6", {"scallop": 0.2, "steep_angle": 45}),
        ("waterline", "builtin:wave", "bull:d=10,r=2", {"level_step": 5.0, "direction": "conventional"}),
    ]
    for k, (kind, part, tool, params) in enumerate(cases):
        fn = getattr(swarf, kind)
        ours = fn(part, tool, **params)
        strategy = "".join(f"{key} = {json.dumps(v)}\n" for key, v in params.items())
        job = tmp_path / f"job{k}.toml"
        job.write_text(f'part = "{part}"\ntool = "{tool}"\n[strategy]\nkind = "{kind}"\n{strategy}'
                       f'[output]\ncsv = "p{k}.csv"\n')
        # The passes are compared; the raster on the boss at 30 degrees gouges 4 cells
        # by up to 0.0167 mm at the ribs' edges, which the gate refuses.
        cli.run("plan", job, "--no-verify")
        csv = (tmp_path / f"p{k}.csv").read_text()
        feed = csv.splitlines()[2].split("=", 1)[1]
        axis = [np.column_stack([p, np.tile([0.0, 0.0, 1.0], (len(p), 1))]) for p in ours]
        assert pose_csv(axis, feed) == csv, (kind, part)
        assert all(p.shape[1] == 3 for p in ours) and len(ours) > 3
    loops = swarf.waterline(swarf.Part.load("builtin:wave").tessellate(0.05), "ball:d=8", scallop=0.3)
    assert all(np.array_equal(p[0], p[-1]) or len(p) > 2 for p in loops)
    with pytest.raises(swarf.SwarfError, match=r"^waterline\(\): strategy.scalop: unknown field"):
        swarf.waterline("builtin:boss", "ball:d=6", scalop=0.2)
    with pytest.raises(swarf.SwarfError, match=r"^raster\(\): strategy.scallop: expected a scallop height"):
        swarf.raster("builtin:boss", "ball:d=6", scallop=1000.0)
