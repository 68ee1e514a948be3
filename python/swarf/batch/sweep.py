"""Tasks of a batch: jobs from files, TOML texts, dicts or a sweep spec, each with
the key that addresses its outputs.

A sweep spec is a base job and parameter ranges, expanded as a cross product; the
ranges are dotted keys into the job (``"strategy.scallop" = [0.05, 0.1]``). Several
``[[sweep]]`` blocks are expanded one after the other and concatenated. A task's
key is the SHA-256 of what its result depends on: the mode, the job as a table,
the contents of every input file it names, the options and swarf's version; two
tasks with the same key would compute the same thing, so a rerun finds the outputs
of a finished task by its key.
"""

from __future__ import annotations

import copy
import hashlib
import itertools
import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, Iterable, List, Optional, Sequence, Tuple

from .errors import BatchError

try:  # Python 3.11 and later
    import tomllib as _toml
except ImportError:  # pragma: no cover - Python 3.9 and 3.10
    import tomli as _toml  # type: ignore[no-redef]

#: Tasks a sweep may expand to without a larger ``max_tasks``.
DEFAULT_MAX_TASKS = 1000
#: The modes a task can run in.
MODES = ("plan", "compare", "verify")
#: Job tables whose strings name outputs, not inputs (they take no part in the key).
_OUTPUT_TABLES = ("output",)


@dataclass
class Task:
    """One unit of work: a job (``mode`` plan or compare) or a verification
    (``mode`` verify) with the parameters that made it.

    ``job`` is the job as a table with its paths made absolute (``base_dir``
    resolved); ``inputs`` maps each input file the job names to the SHA-256 of its
    contents; ``label`` names the task in messages."""

    mode: str
    job: Dict[str, Any]
    params: Dict[str, Any] = field(default_factory=dict)
    options: Dict[str, Any] = field(default_factory=dict)
    label: str = ""
    inputs: Dict[str, str] = field(default_factory=dict)
    key: str = ""

    def to_dict(self) -> Dict[str, Any]:
        return {
            "mode": self.mode,
            "job": self.job,
            "params": self.params,
            "options": self.options,
            "label": self.label,
            "inputs": self.inputs,
            "key": self.key,
        }


def load_toml(path: Path) -> Dict[str, Any]:
    """The table of a TOML file; ``BatchError`` naming the file and line otherwise."""
    try:
        text = Path(path).read_text(encoding="utf-8")
    except OSError as e:
        raise BatchError(f"{path}: cannot read it ({e.strerror or e})") from None
    except UnicodeDecodeError as e:
        raise BatchError(f"{path}: not UTF-8 text ({e.reason} at byte {e.start})") from None
    return parse_toml(text, str(path))


def parse_toml(text: str, where: str) -> Dict[str, Any]:
    try:
        return _toml.loads(text)
    except _toml.TOMLDecodeError as e:
        raise BatchError(f"{where}: not valid TOML: {e}") from None


def job_table(job: Any, where: str) -> Tuple[Dict[str, Any], Path]:
    """A job given as a path, TOML text, a dict or a ``swarf.Job``, as a table and
    the folder its relative paths start from."""
    if isinstance(job, dict):
        return copy.deepcopy(job), Path.cwd()
    if hasattr(job, "toml") and hasattr(job, "base_dir"):
        return parse_toml(job.toml, where), Path(job.base_dir)
    if isinstance(job, str) and "\n" in job:
        return parse_toml(job, where), Path.cwd()
    if isinstance(job, (str, os.PathLike)):
        path = Path(job)
        if not path.is_file():
            raise BatchError(f"{where}: the job file {path} does not exist")
        return load_toml(path), path.resolve().parent
    raise BatchError(
        f"{where}: a job is a file path, TOML text, a dict or a swarf.Job, not {type(job).__name__}"
    )


def _is_url(s: str) -> bool:
    return "://" in s and not s.startswith("file://")


def _resolve_paths(table: Dict[str, Any], base: Path, inputs: Dict[str, str], hasher) -> None:
    """Makes every string of ``table`` that names an existing file under ``base``
    absolute, and records the file's hash in ``inputs``."""
    for k, v in table.items():
        if isinstance(v, dict):
            if k not in _OUTPUT_TABLES:
                _resolve_paths(v, base, inputs, hasher)
        elif isinstance(v, list):
            for i, item in enumerate(v):
                if isinstance(item, dict):
                    _resolve_paths(item, base, inputs, hasher)
                elif isinstance(item, str):
                    v[i] = _resolve_one(item, base, inputs, hasher)
        elif isinstance(v, str):
            table[k] = _resolve_one(v, base, inputs, hasher)


def _resolve_one(s: str, base: Path, inputs: Dict[str, str], hasher) -> str:
    if s.startswith("builtin:") or "\n" in s or not s or len(s) > 4096:
        return s
    if _is_url(s):
        inputs[s] = hasher(s)
        return s
    p = Path(s) if Path(s).is_absolute() else base / s
    try:
        if not p.is_file():
            return s
    except OSError:
        return s
    p = p.resolve()
    inputs[str(p)] = hasher(str(p))
    return str(p)


def file_hash(path: str) -> str:
    """SHA-256 of a file's contents (a local path or an fsspec URL)."""
    h = hashlib.sha256()
    if _is_url(path):
        import fsspec

        with fsspec.open(path, "rb") as f:
            for chunk in iter(lambda: f.read(1 << 20), b""):
                h.update(chunk)
    else:
        with open(path, "rb") as f:
            for chunk in iter(lambda: f.read(1 << 20), b""):
                h.update(chunk)
    return h.hexdigest()


def _set_dotted(table: Dict[str, Any], key: str, value: Any, where: str) -> None:
    parts = key.split(".")
    if not all(parts):
        raise BatchError(f"{where}: `{key}` is not a dotted key into the job (like strategy.scallop)")
    t = table
    for p in parts[:-1]:
        nxt = t.setdefault(p, {})
        if not isinstance(nxt, dict):
            raise BatchError(f"{where}: `{key}`: the job's `{p}` is a value, not a table")
        t = nxt
    t[parts[-1]] = copy.deepcopy(value)


def expand(
    base: Dict[str, Any], blocks: Sequence[Dict[str, Any]], where: str
) -> List[Tuple[Dict[str, Any], Dict[str, Any], Dict[str, Any]]]:
    """The jobs of a sweep: for each block, the cross product of its ranges (lists)
    applied to ``base``, its scalars set on every job of the block. Gives ``(job,
    params, settings)`` triples: ``params`` the swept values by dotted key,
    ``settings`` the block's ``batch.*`` keys (``mode``, ``verify.*``)."""
    out = []
    for b, block in enumerate(blocks):
        at = f"{where}: sweep[{b}]" if len(blocks) > 1 else f"{where}: [sweep]"
        if not isinstance(block, dict):
            raise BatchError(f"{at}: a sweep block is a table of dotted keys")
        ranges = {}
        fixed = {}
        for k, v in block.items():
            if isinstance(v, list):
                if not v:
                    raise BatchError(f"{at}: `{k}` is an empty range")
                ranges[k] = v
            else:
                fixed[k] = v
        names = list(ranges)
        for combo in itertools.product(*(ranges[n] for n in names)):
            job = copy.deepcopy(base)
            settings: Dict[str, Any] = {}
            for k, v in fixed.items():
                if k.startswith("batch."):
                    settings[k[len("batch."):]] = v
                else:
                    _set_dotted(job, k, v, at)
            params = dict(zip(names, combo))
            for k, v in params.items():
                _set_dotted(job, k, v, at)
            out.append((job, params, settings))
    return out


def count(blocks: Sequence[Dict[str, Any]]) -> int:
    """Tasks a sweep expands to, without expanding it."""
    total = 0
    for block in blocks:
        n = 1
        for v in block.values() if isinstance(block, dict) else ():
            if isinstance(v, list):
                n *= len(v)
        total += n
    return total


def check_limit(n: int, max_tasks: Optional[int], where: str) -> None:
    limit = DEFAULT_MAX_TASKS if max_tasks is None else max_tasks
    if n > limit:
        hint = "--max-tasks " if where.endswith("toml") else "max_tasks="
        raise BatchError(
            f"{where}: the sweep expands to {n} tasks, more than the limit of {limit}; "
            f"give {hint}{n} (or more) to run them all"
        )


def make_key(task: Task, version: str) -> str:
    doc = {
        "mode": task.mode,
        "job": task.job,
        "inputs": dict(sorted(task.inputs.items())),
        "options": task.options,
        "swarf": version,
    }
    text = json.dumps(doc, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode()).hexdigest()


def verify_keywords() -> List[str]:
    """The keywords of :func:`swarf.verify` a batch may set (not the part, the
    programs, the tool or the output folder, which each task gives)."""
    import inspect

    import swarf

    try:
        names = list(inspect.signature(swarf.verify).parameters)
    except (TypeError, ValueError):  # pragma: no cover - a native function without a signature
        return []
    return [n for n in names if n not in ("part", "program", "tool", "out")]


def check_verify_options(opts: Dict[str, Any], where: str) -> None:
    """``BatchError`` naming the first key of ``opts`` that is not a keyword of
    :func:`swarf.verify`."""
    if not isinstance(opts, dict):
        raise BatchError(f"{where}: the verification's options are a table of swarf.verify keywords")
    known = verify_keywords()
    for k in opts:
        if known and k not in known:
            raise BatchError(f"{where}: `verify.{k}` is not a setting of swarf verify (known: {', '.join(known)})")


def make_tasks(
    entries: Iterable[Tuple[Dict[str, Any], Path, Dict[str, Any], Dict[str, Any], str]],
    mode: str,
    options: Dict[str, Any],
    version: str,
) -> List[Task]:
    """Tasks from ``(table, base_dir, params, settings, label)`` entries: paths
    resolved, inputs hashed (each file once), keys made."""
    hashes: Dict[str, str] = {}

    def hasher(p: str) -> str:
        if p not in hashes:
            try:
                hashes[p] = file_hash(p)
            except (OSError, ValueError) as e:
                raise BatchError(f"cannot read the input {p}: {e}") from None
        return hashes[p]

    tasks = []
    for table, base, params, settings, label in entries:
        m = settings.get("mode", mode)
        if m not in MODES:
            raise BatchError(f"{label}: mode `{m}` is not one of {', '.join(MODES)}")
        opts = copy.deepcopy(options)
        for k, v in settings.items():
            if k.startswith("verify."):
                opts.setdefault("verify", {})[k[len("verify."):]] = v
            elif k != "mode":
                opts[k] = v
        if m == "compare":
            opts.setdefault("verify", {})
        elif m == "plan":
            opts.pop("verify", None)
        check_verify_options(opts.get("verify", {}), label)
        inputs: Dict[str, str] = {}
        table = copy.deepcopy(table)
        _resolve_paths(table, base, inputs, hasher)
        t = Task(mode=m, job=table, params=params, options=opts, label=label, inputs=inputs)
        t.key = make_key(t, version)
        tasks.append(t)
    return tasks


def sweep_entries(spec: Dict[str, Any], base_dir: Path, where: str, max_tasks: Optional[int]):
    """The ``(table, base_dir, params, settings, label)`` entries of a sweep spec's
    ``jobs`` list and its ``[base]`` with ``[sweep]`` blocks; the limit checked
    before anything is expanded."""
    batch = spec.get("batch", {})
    unknown = set(spec) - {"batch", "base", "sweep", "jobs"}
    if unknown:
        raise BatchError(
            f"{where}: unknown table `{sorted(unknown)[0]}` (a sweep has [batch], [base], [sweep] or [[sweep]], and jobs)"
        )
    jobs = spec.get("jobs", [])
    if not isinstance(jobs, list):
        raise BatchError(f"{where}: `jobs` is a list of job files")
    blocks = spec.get("sweep", [])
    if isinstance(blocks, dict):
        blocks = [blocks]
    if blocks and "base" not in spec:
        raise BatchError(f"{where}: [sweep] needs a [base] job to vary")
    if "base" in spec and not blocks:
        blocks = [{}]
    if max_tasks is None:
        max_tasks = batch.get("max_tasks")
    check_limit(len(jobs) + count(blocks), max_tasks, where)
    entries = []
    for i, j in enumerate(jobs):
        at = f"{where}: jobs[{i}]"
        path = Path(j) if Path(j).is_absolute() else base_dir / j
        table, base = job_table(path, at)
        entries.append((table, base, {}, {}, str(path)))
    if blocks:
        if not isinstance(spec["base"], dict):
            raise BatchError(f"{where}: [base] is a job table")
        for k, (job, params, settings) in enumerate(expand(spec["base"], blocks, where)):
            label = ", ".join(f"{n}={v}" for n, v in params.items()) or f"{where}: base"
            entries.append((job, base_dir, params, settings, label))
    return entries
