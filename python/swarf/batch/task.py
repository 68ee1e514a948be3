"""What a worker does with one task: plan (and verify) a job or verify a program,
write the output set atomically under the results folder and return its row.

An output set is ``tasks/KEY/`` under the results folder, complete when its
``row.json`` exists. On a local folder the set is built in ``.partial/KEY-RANDOM/``
and renamed into place in one step, so a worker that dies mid-task leaves only a
partial folder, which the next run removes, never a half-written set; on an fsspec
URL the set is built in a local temporary folder and uploaded with ``row.json``
last. A task whose set already exists returns the stored row (a retried task whose
first try finished, or a rerun). A job that fails gives an error row, stored as
``errors/KEY.json`` and redone by a rerun.

Input files are read where the task names them; a file named by an fsspec URL is
fetched once per worker into a cache folder named by its content hash, and every
input's hash is checked against the task's, so outputs always match their key.

Parts and meshes are read once per worker: a planned job's part (a file, keyed by
its content hash and path, or a ``builtin:`` part, by name) is read as the job reads
it (``Job.load_part()``, keyed by the job's ``[import]`` and ``faces`` too) and kept
for the worker's later tasks, which plan on it (``swarf.plan(job, part=...)``: the
same plan, bit for bit). :func:`part_cache_stats` says how many were read.
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
import time
import traceback
import uuid
from pathlib import Path
from typing import Any, Callable, Dict, Optional, Tuple

from .results import Results
from .row import plan_fields, sequence_fields, verify_fields

#: The program file of a planned job's output set.
PROGRAM = "program.ngc"
#: The summary file of a planned job's output set.
SUMMARY = "summary.json"
#: The job file of an output set (the job as planned, its paths absolute).
JOB_FILE = "job.toml"
#: The folder of a verification inside an output set.
VERIFY_DIR = "verify"

# Per worker process: input path or URL -> (stat or None, hash, local path).
_INPUTS: Dict[str, Tuple[Any, str, str]] = {}

# Per worker process: (part, content hash or "", reading options) -> Part or Mesh.
_PARTS: Dict[Tuple[str, str, str], Any] = {}
# Per worker process: parts read, tasks that found theirs read, seconds reading.
_PART_STATS: Dict[str, Any] = {"loads": 0, "hits": 0, "load_s": 0.0}


def _stat_key(path: str):
    st = os.stat(path)
    return (st.st_size, st.st_mtime_ns, st.st_ino)


def local_input(name: str, want: str) -> str:
    """A local path holding the input ``name`` (a path or fsspec URL) whose content
    hash is ``want``: a URL is fetched once per worker into a folder named by the
    hash; a local file is hashed once per change. ``ValueError`` when the contents
    differ from the hash the task was keyed by."""
    from .sweep import _is_url, file_hash

    hit = _INPUTS.get(name)
    if _is_url(name):
        if hit is None:
            cache = Path(tempfile.gettempdir()) / "swarf-batch-inputs" / want
            local = cache / (Path(name.split("?")[0]).name or "input")
            if not local.is_file():
                import fsspec

                cache.mkdir(parents=True, exist_ok=True)
                tmp = cache / f".{uuid.uuid4().hex}"
                with fsspec.open(name, "rb") as src, open(tmp, "wb") as dst:
                    shutil.copyfileobj(src, dst)
                os.replace(tmp, local)
            hit = (None, file_hash(str(local)), str(local))
            _INPUTS[name] = hit
    else:
        st = _stat_key(name)
        if hit is None or hit[0] != st:
            hit = (st, file_hash(name), name)
            _INPUTS[name] = hit
    if hit[1] != want:
        raise ValueError(f"the input {name} changed since the sweep was expanded (its contents no longer match)")
    return hit[2]


def _localise(value: Any, inputs: Dict[str, str]) -> Any:
    if isinstance(value, dict):
        return {k: _localise(v, inputs) for k, v in value.items()}
    if isinstance(value, list):
        return [_localise(v, inputs) for v in value]
    if isinstance(value, str) and value in inputs:
        return local_input(value, inputs[value])
    return value


def part_cache_stats() -> Dict[str, Any]:
    """This worker's part cache: ``loads`` (parts read), ``hits`` (tasks that
    planned on a part read before), ``load_s`` (seconds spent reading) and
    ``parts`` (how many are held). Ask every worker with
    ``client.run(part_cache_stats)``."""
    return dict(_PART_STATS, parts=len(_PARTS))


def clear_part_cache() -> None:
    """Forgets this worker's parts and zeroes its counts."""
    _PARTS.clear()
    _PART_STATS.update(loads=0, hits=0, load_s=0.0)


def _cached_part(task: Dict[str, Any], job: Dict[str, Any], j):
    """The part of the planned job ``job`` (its paths local; ``j`` its
    ``swarf.Job``) from this worker's cache, read on first use; None where it is not
    cached (a sequence, a file the sweep did not hash, a part that cannot be read:
    the job then reads it itself, with its own message)."""
    import swarf

    name = task["job"].get("part")
    if "operation" in job or not isinstance(name, str):
        return None
    digest = task["inputs"].get(name)
    if digest is None and not name.startswith("builtin:"):
        return None
    reading = json.dumps([job.get("import"), job.get("faces")], sort_keys=True, default=str)
    key = (str(job["part"]), digest or "", reading)
    hit = _PARTS.get(key)
    if hit is not None:
        _PART_STATS["hits"] += 1
        return hit
    t0 = time.perf_counter()
    try:
        hit = j.load_part()
    except swarf.SwarfError:
        return None
    _PART_STATS["load_s"] += time.perf_counter() - t0
    _PART_STATS["loads"] += 1
    _PARTS[key] = hit
    return hit


def _plan(task: Dict[str, Any], out: Path) -> Dict[str, Any]:
    import swarf

    job = _localise(task["job"], task["inputs"])
    output = dict(job.get("output", {}))
    output.update(gcode=PROGRAM, summary=SUMMARY)
    job["output"] = output
    opts = task["options"]
    j = swarf.Job.from_dict(job, base_dir=str(out))
    (out / JOB_FILE).write_text(j.toml, encoding="utf-8")
    t0 = time.perf_counter()
    part = _cached_part(task, job, j)
    p = swarf.plan(j, part=part, out=str(out), verify=opts.get("gate", True), allow_unsafe=opts.get("allow_unsafe", False))
    fields: Dict[str, Any] = {"plan_s": time.perf_counter() - t0}
    if isinstance(p, swarf.SequencePlan):
        fields.update(sequence_fields(p.report))
    else:
        fields.update(plan_fields(p.summary))
    if task["mode"] == "compare":
        program = out / PROGRAM
        if not program.is_file():
            raise ValueError(f"the job wrote no G-code to verify ({PROGRAM})")
        fields.update(_verify(job["part"], [str(program)], None, opts.get("verify", {}), out / VERIFY_DIR))
    return fields


def _verify(part: str, programs, tool, opts: Dict[str, Any], out: Path) -> Dict[str, Any]:
    import numpy as np

    import swarf

    t0 = time.perf_counter()
    v = swarf.verify(part, programs, tool, out=str(out), **opts)
    elapsed = time.perf_counter() - t0
    np.save(out / "deviation.npy", v.deviation.astype(np.float32))
    fields = verify_fields(v.report)
    fields["verify_s"] = elapsed
    return fields


def _verify_task(task: Dict[str, Any], out: Path) -> Dict[str, Any]:
    spec = _localise(task["job"], task["inputs"])
    spec = dict(spec)
    part = spec.pop("part")
    program = spec.pop("program")
    tool = spec.pop("tool", None)
    opts = dict(task["options"].get("verify", {}))
    opts.update(spec)
    return _verify(part, program if isinstance(program, list) else [program], tool, opts, out)


def _base_row(task: Dict[str, Any]) -> Dict[str, Any]:
    job = task["job"]
    strategy = job.get("strategy", {})
    return {
        "key": task["key"],
        "mode": task["mode"],
        "label": task["label"],
        "job": job.get("name") or "",
        "part": job.get("part", ""),
        "tool": str(job.get("tool", "")),
        "strategy": strategy.get("kind", "sequence" if "operation" in job else "") if isinstance(strategy, dict) else "",
        "params": json.dumps(task["params"], sort_keys=True),
        "outputs": f"tasks/{task['key']}",
    }


def run_task(task: Dict[str, Any], results: str, fn: Optional[Callable] = None) -> Dict[str, Any]:
    """Runs one task (``Task.to_dict()``) and returns its row; the output set is
    written under ``results``. Never raises for a failing job: the row has
    ``status = "error"`` and the message."""
    res = Results(results)
    stored = res.complete_row(task["key"])
    if stored is not None:
        return stored
    row = _base_row(task)
    staging = res.staging(task["key"])
    try:
        start = time.perf_counter()
        if fn is not None:
            fields = fn(task, staging)
        elif task["mode"] == "verify":
            fields = _verify_task(task, staging)
        else:
            fields = _plan(task, staging)
        row.update(fields or {})
        row["status"] = "ok"
        row["error"] = ""
        row["task_s"] = time.perf_counter() - start
        row["worker_pid"] = os.getpid()
        return res.commit(task["key"], staging, row)
    except Exception as e:  # a failing job becomes an error row, never a lost result
        res.discard(staging)
        row["status"] = "error"
        row["error"] = _message(e)
        row["worker_pid"] = os.getpid()
        res.write_error(task["key"], row)
        return row


def _message(e: BaseException) -> str:
    import swarf

    if isinstance(e, (swarf.SwarfError, ValueError, OSError)):
        return f"{type(e).__name__}: {e}" if not isinstance(e, swarf.SwarfError) else str(e)
    tb = traceback.extract_tb(e.__traceback__)
    where = f" at {Path(tb[-1].filename).name}:{tb[-1].lineno}" if tb else ""
    return f"{type(e).__name__}{where}: {e}"
