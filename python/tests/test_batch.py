"""swarf.batch on Dask: a sweep of 252 jobs (paper 004's strategies on wave, die and
a generated mold) on a LocalCluster of 2 workers, its rows equal field by field
those of `swarf plan` and `swarf verify` run alone on each job; a worker killed
mid-sweep; an interrupted sweep rerun; bad input."""

import json
import os
import signal
import subprocess
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from conftest import REPO, REQUIRE
from batch_sweep import STRATEGIES, mold_part, write_sweep

for module in ("dask.distributed", "pandas", "pyarrow", "matplotlib"):
    try:
        __import__(module)
    except ImportError:
        if REQUIRE:
            raise
        pytest.skip(f"{module} not installed (pip install 'swarf[batch]')", allow_module_level=True)

import pandas as pd  # noqa: E402

import swarf  # noqa: E402
from swarf import batch  # noqa: E402
from swarf.batch.row import RUN_COLUMNS, frame, plan_fields, verify_fields  # noqa: E402
from swarf.batch.task import clear_part_cache, part_cache_stats  # noqa: E402

N_SWEEP = 3 * 4 * 5 * 2 * 2 + 3 * 4


@pytest.fixture(scope="module")
def client():
    c = batch.local_client(2)
    yield c
    cluster = c.cluster
    c.close()
    cluster.close()


@pytest.fixture(scope="module")
def swept(tmp_path_factory, client):
    """The sweep run once on the 2 workers: (table, results folder, seconds)."""
    folder = tmp_path_factory.mktemp("sweep")
    path = write_sweep(folder / "in")
    out = folder / "out"
    t0 = time.perf_counter()
    df = batch.run_sweep(path, out, client, progress=False)
    return df, out, time.perf_counter() - t0


def test_the_sweep_has_one_complete_row_per_task(swept):
    df, out, seconds = swept
    print(f"{len(df)} tasks in {seconds:.1f} s on 2 workers")
    assert len(df) == N_SWEEP and df["key"].is_unique
    assert (df["status"] == "ok").all(), df[df["status"] != "ok"][["label", "error"]].to_string()
    assert set(df["strategy"]) == set(STRATEGIES)
    assert sorted(set(df["mode"])) == ["compare", "plan"]
    assert (df["mode"] == "compare").sum() == 12
    assert sorted(p.name for p in (out / "tasks").iterdir()) == sorted(df["key"])
    assert not any((out / ".partial").iterdir())
    for name in ("table.parquet", "table.csv", "time_vs_scallop.png", "deviation_maps.png"):
        assert (out / name).stat().st_size > 0, name
    # The files hold the table returned.
    pd.testing.assert_frame_equal(pd.read_parquet(out / "table.parquet"), df, check_dtype=False)
    assert len(pd.read_csv(out / "table.csv")) == len(df)
    compared = df[df["mode"] == "compare"]
    assert compared["scallop_max_mm"].notna().all() and compared["gate_gouge_cells"].notna().all()
    assert df[df["mode"] == "plan"]["scallop_max_mm"].isna().all()
    # A finer scallop costs time: per strategy, part, tool and order, time falls
    # as the scallop grows.
    plan = df[df["mode"] == "plan"]
    for _, g in plan.groupby(["strategy", "part", "tool", "param.strategy.zigzag"]):
        t = g.sort_values("param.strategy.scallop")["machining_time_s"].to_numpy()
        assert (t[:-1] >= t[1:]).all(), t


def _cli_row(cli, out, row, tmp):
    """The row's figures from `swarf plan` (and `swarf verify`) run on the task's
    job file, and whether its G-code is byte for byte the batch's."""
    task = out / row["outputs"]
    d = tmp / row["key"][:16]
    flags = [] if row["mode"] == "compare" else ["--no-verify"]
    cli.run("plan", task / "job.toml", "-o", d, *flags)
    summary = json.loads((d / "summary.json").read_text())
    fields = plan_fields(summary)
    if row["mode"] == "compare":
        part = json.loads((task / "row.json").read_text())["part"]
        cli.run("verify", "--part", part, "--program", d / "program.ngc", "--cell", 1.0, "-o", d / "verify")
        fields.update(verify_fields(json.loads((d / "verify" / "report.json").read_text())))
    same = (d / "program.ngc").read_bytes() == (task / "program.ngc").read_bytes()
    return {**dict(row), **fields}, summary["strategy"], same


def test_rows_equal_the_command_line_job_by_job(swept, cli, tmp_path):
    df, out, _ = swept
    rows = df.to_dict("records")
    t0 = time.perf_counter()
    with ThreadPoolExecutor(2) as pool:
        got = list(pool.map(lambda r: _cli_row(cli, out, r, tmp_path), rows))
    print(f"{len(rows)} jobs through the command line in {time.perf_counter() - t0:.1f} s (2 at a time)")
    assert all(same for _, _, same in got), "a program differs from the command line's"
    assert [s for _, s, _ in got] == list(df["strategy"])
    theirs = frame([r for r, _, _ in got], [c[len("param."):] for c in df.columns if c.startswith("param.")])
    keep = [c for c in df.columns if c not in RUN_COLUMNS]
    pd.testing.assert_frame_equal(df[keep], theirs[keep], check_exact=True)


MESH = REPO / "crates" / "swarf-tool" / "tests" / "data" / "ocl" / "die.stl"
STEP = REPO / "parts" / "cad" / "plate-hole.step"


def test_a_plan_on_a_loaded_part_is_the_plan_of_the_job(tmp_path):
    (tmp_path / "mold.toml").write_text(mold_part())
    raster = {"kind": "raster", "scallop": 0.5, "tolerance": 0.1}
    cases = [
        ("mold.toml", swarf.Part.load, {}),
        (str(MESH), swarf.Mesh.load, {}),
        ("builtin:wave", swarf.load, {}),
        # A part read whole gets the job's faces; a CAD file read as the job reads it.
        (str(STEP), swarf.Part.load, {"faces": [0]}),
        (str(STEP), None, {"import": {"trim_chord": 0.001}}),
    ]
    for part, load, extra in cases:
        job = swarf.Job.from_dict({"part": part, "tool": "ball:d=6", "strategy": raster, **extra}, base_dir=tmp_path)
        alone = swarf.plan(job, verify=False)
        source = part if part.startswith("builtin:") else tmp_path / part
        loaded = job.load_part() if load is None else load(source)
        given = swarf.plan(job, part=loaded, verify=False)
        assert given.gcode == alone.gcode and given.cl == alone.cl, part
        assert given.summary == alone.summary, part
    # What the job would not read so is refused, naming `part`.
    chord = swarf.Job.from_dict({"part": str(STEP), "tool": "ball:d=6", "import": {"trim_chord": 0.001}, "strategy": raster})
    with pytest.raises(swarf.SwarfError, match=r"part: the Part was read .*trim_chord = 0\.0001 mm.*the job reads it with import\.trim_chord = 0\.001 mm"):
        swarf.plan(chord, part=swarf.Part.load(STEP), verify=False)
    faces = swarf.Job.from_dict({"part": str(MESH), "tool": "ball:d=6", "faces": [0], "strategy": raster})
    with pytest.raises(swarf.SwarfError, match="part: a Mesh has no faces to select"):
        swarf.plan(faces, part=swarf.Mesh.load(MESH), verify=False)
    with pytest.raises(TypeError, match="part: expected a Part or a Mesh .* found str"):
        swarf.plan(chord, part=str(STEP))


def test_each_worker_reads_each_part_once(client, tmp_path):
    (tmp_path / "mold.toml").write_text(mold_part())
    sweep = {
        "base": {"name": "cache", "part": "builtin:die", "tool": "ball:d=10", "strategy": {"kind": "raster", "scallop": 0.5, "tolerance": 0.1}},
        "sweep": {"part": ["builtin:die", str(tmp_path / "mold.toml"), str(MESH)], "strategy.scallop": [0.4, 0.5, 0.6, 0.7]},
    }
    client.run(clear_part_cache)
    df = batch.plan_many(sweep, tmp_path / "out", client, gate=False, progress=False, plots=False)
    assert (df["status"] == "ok").all(), df["error"].tolist()
    stats = client.run(part_cache_stats)
    pids = client.run(os.getpid)
    for addr, st in stats.items():
        mine = df[df["worker_pid"] == pids[addr]]
        assert st["loads"] == mine["part"].nunique() == st["parts"], (addr, st)
        assert st["hits"] == len(mine) - st["loads"], (addr, st)
    assert sum(st["loads"] + st["hits"] for st in stats.values()) == len(df) == 12


def _kill_a_busy_worker(client, out, killed, min_done=6):
    tasks = out / "tasks"
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        if tasks.is_dir() and sum(1 for _ in tasks.iterdir()) >= min_done:
            busy = {a: ks for a, ks in client.processing().items() if ks}
            if busy:
                addr, keys = next(iter(busy.items()))
                pid = client.run(os.getpid, workers=[addr])[addr]
                os.kill(pid, signal.SIGKILL)
                killed.append((pid, list(keys)))
                return
        time.sleep(0.02)


def test_a_worker_killed_mid_sweep_loses_nothing(swept, tmp_path):
    big, _, _ = swept
    path = write_sweep(tmp_path / "in", parts=["builtin:wave"], compare_block=False)
    out = tmp_path / "out"
    c = batch.local_client(2)
    killed = []
    try:
        killer = threading.Thread(target=_kill_a_busy_worker, args=(c, out, killed))
        killer.start()
        df = batch.run_sweep(path, out, c, progress=False)
        killer.join()
    finally:
        cluster = c.cluster
        c.close()
        cluster.close()
    assert killed, "no worker was killed"
    assert len(df) == 80 and df["key"].is_unique and (df["status"] == "ok").all()
    sets = sorted(p.name for p in (out / "tasks").iterdir())
    assert sets == sorted(df["key"]), "one output set per task"
    for key in df["key"]:
        files = sorted(p.name for p in (out / "tasks" / key).iterdir())
        assert files == ["job.toml", "program.ngc", "program.record.json", "row.json", "summary.json"], files
    assert not any((out / ".partial").iterdir()), "a partial output set was kept"
    assert not any((out / "errors").iterdir())
    # The tasks are the big sweep's wave tasks (same inputs, same keys): same rows.
    keep = [c for c in df.columns if c not in RUN_COLUMNS]
    theirs = big.set_index("key").loc[df["key"]].reset_index()
    pd.testing.assert_frame_equal(df[keep], theirs[keep], check_exact=True)


def test_an_interrupted_sweep_reruns_only_the_unfinished_tasks(tmp_path, swarf_bin):
    path = write_sweep(tmp_path / "in", parts=["builtin:die"], scallops=[0.2, 0.3, 0.4], compare_block=False)
    out = tmp_path / "out"
    args = [str(path), "--out", str(out), "--workers", "2", "--quiet", "--no-plots"]
    p = subprocess.Popen([sys.executable, "-m", "swarf.batch", *args], stderr=subprocess.PIPE, text=True)
    tasks = out / "tasks"
    deadline = time.monotonic() + 120
    while not (tasks.is_dir() and sum(1 for _ in tasks.iterdir()) >= 8) and time.monotonic() < deadline:
        time.sleep(0.02)
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 130, err
    assert "interrupted" in err
    before = {d.name: (d / "row.json").stat().st_mtime_ns for d in tasks.iterdir()}
    assert 8 <= len(before) < 48, len(before)
    r = subprocess.run([swarf_bin, "batch", *args, "--python", sys.executable], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert f"48 tasks, {len(before)} complete already, {48 - len(before)} to run" in r.stderr
    after = {d.name: (d / "row.json").stat().st_mtime_ns for d in tasks.iterdir()}
    assert len(after) == 48 and all(after[k] == v for k, v in before.items())
    assert not any((out / ".partial").iterdir())
    df = pd.read_parquet(out / "table.parquet")
    assert len(df) == 48 and (df["status"] == "ok").all()
    # A third run finds everything done.
    r = subprocess.run([swarf_bin, "batch", *args, "--python", sys.executable], capture_output=True, text=True)
    assert r.returncode == 0 and "48 complete already, 0 to run" in r.stderr, r.stderr


def test_a_failing_job_is_an_error_row_and_is_redone(client, tmp_path):
    good = {"name": "ok", "part": "builtin:die", "tool": "ball:d=10", "strategy": {"kind": "raster", "scallop": 0.5, "tolerance": 0.1}}
    bad = json.loads(json.dumps(good))
    bad["strategy"]["scallop"] = -1
    text = 'name = "text"\npart = "builtin:wave"\ntool = "ball:d=10"\n[strategy]\nkind = "iso-planar"\nscallop = 0.5\ntolerance = 0.1\n'
    jobs = [good, bad, text]
    df = batch.plan_many(jobs, tmp_path / "out", client, gate=False, progress=False)
    assert list(df["status"]) == ["ok", "error", "ok"]
    assert "scallop" in df["error"][1], df["error"][1]
    assert df["error"][0] == "" and df["strategy"][2] == "iso-planar"
    assert (tmp_path / "out" / "errors" / f"{df['key'][1]}.json").is_file()
    assert len(list((tmp_path / "out" / "tasks").iterdir())) == 2
    # A rerun redoes only the failed task (the others' rows are the stored ones).
    again = batch.plan_many(jobs, tmp_path / "out", client, gate=False, progress=False)
    assert list(again["status"]) == ["ok", "error", "ok"]
    assert list(again["task_s"][[0, 2]]) == list(df["task_s"][[0, 2]])


def test_map_jobs_and_verify_many(client, swept, cli, tmp_path):
    _, out, _ = swept
    df, _, _ = swept
    some = df[df["mode"] == "plan"].head(3)

    def passes(task, folder):
        p = swarf.plan(task["job"], verify=False)
        (folder / "n.txt").write_text(str(len(p.passes)))
        return {"passes": len(p.passes)}

    jobs = [str(out / k / "job.toml") for k in some["outputs"]]
    m = batch.map_jobs(passes, jobs, tmp_path / "map", client, progress=False)
    assert list(m["passes"]) == list(some["passes"])
    assert all((tmp_path / "map" / k / "n.txt").is_file() for k in m["outputs"])
    programs = [{"part": r["part"], "program": str(out / r["outputs"] / "program.ngc")} for _, r in some.iterrows()]
    v = batch.verify_many(programs, tmp_path / "verify", client, cell=1.0, progress=False)
    assert (v["status"] == "ok").all(), v["error"].tolist()
    for (_, r), item in zip(v.iterrows(), programs):
        d = tmp_path / f"cli-{r['key'][:8]}"
        cli.run("verify", "--part", item["part"], "--program", item["program"], "--cell", 1.0, "-o", d)
        theirs = verify_fields(json.loads((d / "report.json").read_text()))
        assert {k: r[k] for k in theirs} == theirs


def test_results_on_an_fsspec_url(tmp_path):
    """A results folder given as a URL: each output set uploaded with row.json last
    (fsspec's memory file system, workers as threads of this process)."""
    c = batch.local_client(1, processes=False)
    try:
        jobs = [{"name": "m", "part": "builtin:die", "tool": "ball:d=10", "strategy": {"kind": k, "scallop": 0.5, "tolerance": 0.1}} for k in ("raster", "iso-planar")]
        df = batch.plan_many(jobs, "memory://swarf-batch", c, gate=False, progress=False)
        assert (df["status"] == "ok").all(), df["error"].tolist()
        import fsspec

        fs = fsspec.filesystem("memory")
        for key in df["key"]:
            assert fs.exists(f"/swarf-batch/tasks/{key}/row.json")
            assert fs.exists(f"/swarf-batch/tasks/{key}/program.ngc")
        assert fs.exists("/swarf-batch/table.parquet")
        again = batch.plan_many(jobs, "memory://swarf-batch", c, gate=False, progress=False, plots=False)
        assert list(again["task_s"]) == list(df["task_s"])
    finally:
        cluster = c.cluster
        c.close()
        cluster.close()


def test_bad_input_is_refused_with_its_place(tmp_path, swarf_bin):
    path = write_sweep(tmp_path / "in", max_tasks=100)
    with pytest.raises(batch.BatchError, match=r"sweep.toml: the sweep expands to 252 tasks, more than the limit of 100; give --max-tasks 252"):
        batch.load_sweep(path)
    assert len(batch.load_sweep(path, max_tasks=300)[0]) == 252
    r = subprocess.run([swarf_bin, "batch", path, "--out", tmp_path / "o", "--python", sys.executable], capture_output=True, text=True)
    assert r.returncode != 0 and "more than the limit of 100" in r.stderr and not (tmp_path / "o").exists()
    # An unwritable results folder: under a file.
    (tmp_path / "file").write_text("x")
    with pytest.raises(batch.BatchError, match="the results folder .*file/out is not writable"):
        batch.plan_many([{"part": "builtin:die", "tool": "ball:d=10", "strategy": {"kind": "raster", "scallop": 0.5}}], tmp_path / "file" / "out")
    cases = {
        'bogus = 1\n': "unknown table `bogus`",
        '[batch]\nmode = "fly"\n': "mode = `fly`",
        '[batch]\nspeed = 1\n': "[batch] has no field `speed`",
        '[batch.verify]\ncel = 1\n[base]\npart = "builtin:die"\n': "`verify.cel` is not a setting of swarf verify",
        '[sweep]\n"strategy.scallop" = [0.1]\n': "[sweep] needs a [base] job",
        '[base]\npart = "builtin:die"\n[sweep]\n"strategy.scallop" = []\n': "`strategy.scallop` is an empty range",
        '[base]\npart = "builtin:die"\n[sweep]\n"part.x" = [1]\n': "`part.x`: the job's `part` is a value",
        'jobs = ["nope.toml"]\n': "jobs[0]: the job file",
        "[batch\n": "not valid TOML",
    }
    for text, message in cases.items():
        p = tmp_path / "bad.toml"
        p.write_text(text)
        with pytest.raises(batch.BatchError, match=None) as e:
            batch.load_sweep(p)
        assert message in str(e.value) and "bad.toml" in str(e.value), (text, str(e.value))


def test_swarf_batch_names_what_is_missing(tmp_path, swarf_bin, cli):
    path = write_sweep(tmp_path / "in")
    msg = cli.fail("batch", path, "--out", tmp_path / "o", "--python", tmp_path / "no-python")
    assert "the interpreter" in msg and "no-python" in msg and "--python or SWARF_PYTHON" in msg
    bare = tmp_path / "bare-python"
    bare.write_text(f'#!/bin/sh\nexec {sys.base_prefix}/bin/python3 -I -S "$@"\n')
    bare.chmod(0o755)
    msg = cli.fail("batch", path, "--out", tmp_path / "o", "--python", bare)
    assert "cannot import `swarf`" in msg and "pip install './python[batch]'" in msg, msg
