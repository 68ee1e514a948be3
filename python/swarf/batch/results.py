"""The results folder of a batch: a local path or an fsspec URL.

Layout: ``tasks/KEY/`` (one complete output set per finished task, ``row.json``
inside), ``errors/KEY.json`` (the row of a task that failed), ``.partial/``
(output sets being built on a local folder; removed by every run) and the table
and plots at the top.
"""

from __future__ import annotations

import io
import json
import os
import shutil
import tempfile
import uuid
from pathlib import Path
from typing import Any, Dict, Optional

from .errors import BatchError

ROW = "row.json"


def _is_url(s: str) -> bool:
    return "://" in s and not s.startswith("file://")


class Results:
    """A results folder (module doc)."""

    def __init__(self, where: str):
        self.where = str(where)
        if _is_url(self.where):
            import fsspec

            self.fs, self.root = fsspec.core.url_to_fs(self.where)
            self.local: Optional[Path] = None
        else:
            self.fs = None
            self.root = self.where[len("file://"):] if self.where.startswith("file://") else self.where
            self.local = Path(self.root)

    # -- paths -------------------------------------------------------------
    def _join(self, *parts: str) -> str:
        return "/".join([self.root.rstrip("/"), *parts])

    def task_dir(self, key: str) -> str:
        return self._join("tasks", key)

    # -- checks ------------------------------------------------------------
    def check_writable(self) -> None:
        """``BatchError`` naming the folder when it cannot be created or written."""
        probe = f".probe-{uuid.uuid4().hex}"
        try:
            if self.local is not None:
                for sub in ("", "tasks", "errors", ".partial"):
                    (self.local / sub).mkdir(parents=True, exist_ok=True)
                (self.local / probe).write_bytes(b"")
                (self.local / probe).unlink()
            else:
                self.fs.makedirs(self.root, exist_ok=True)
                with self.fs.open(self._join(probe), "wb") as f:
                    f.write(b"")
                self.fs.rm(self._join(probe))
        except (OSError, PermissionError, ValueError) as e:
            reason = getattr(e, "strerror", None) or str(e)
            raise BatchError(f"the results folder {self.where} is not writable: {reason}") from None

    # -- rows ----------------------------------------------------------------
    def _read_json(self, path: str) -> Optional[Dict[str, Any]]:
        try:
            if self.local is not None:
                return json.loads(Path(path).read_text(encoding="utf-8"))
            with self.fs.open(path, "rb") as f:
                return json.loads(f.read().decode())
        except (OSError, ValueError):
            return None

    def complete_row(self, key: str) -> Optional[Dict[str, Any]]:
        """The row of a finished task, or None."""
        return self._read_json(self._join("tasks", key, ROW))

    def error_row(self, key: str) -> Optional[Dict[str, Any]]:
        return self._read_json(self._join("errors", f"{key}.json"))

    # -- writing an output set -------------------------------------------------
    def staging(self, key: str) -> Path:
        """A new, empty local folder to build the output set of ``key`` in."""
        if self.local is not None:
            path = self.local / ".partial" / f"{key}-{uuid.uuid4().hex[:12]}"
            path.mkdir(parents=True)
            return path
        return Path(tempfile.mkdtemp(prefix=f"swarf-batch-{key[:12]}-"))

    def discard(self, staging: Path) -> None:
        shutil.rmtree(staging, ignore_errors=True)

    def commit(self, key: str, staging: Path, row: Dict[str, Any]) -> Dict[str, Any]:
        """Writes ``row.json`` and moves the set into place in one step (local) or
        uploads it with ``row.json`` last (URL); returns the row that is stored (an
        earlier try's, where one finished first)."""
        (staging / ROW).write_text(json.dumps(row, sort_keys=True, indent=1), encoding="utf-8")
        if self.local is not None:
            final = self.local / "tasks" / key
            final.parent.mkdir(parents=True, exist_ok=True)
            try:
                os.rename(staging, final)
            except OSError:
                # Another try of the same task finished first: keep its set.
                self.discard(staging)
                stored = self.complete_row(key)
                if stored is None:
                    raise
                return stored
        else:
            final_url = self.task_dir(key)
            files = [p for p in sorted(staging.rglob("*")) if p.is_file() and p != staging / ROW]
            for p in files:
                self.fs.put_file(str(p), final_url + "/" + p.relative_to(staging).as_posix())
            self.fs.put_file(str(staging / ROW), final_url + "/" + ROW)
            self.discard(staging)
        self.remove_error(key)
        return row

    def write_error(self, key: str, row: Dict[str, Any]) -> None:
        data = json.dumps(row, sort_keys=True, indent=1)
        self.write_bytes(f"errors/{key}.json", data.encode())

    def remove_error(self, key: str) -> None:
        path = self._join("errors", f"{key}.json")
        try:
            if self.local is not None:
                Path(path).unlink()
            else:
                self.fs.rm(path)
        except (OSError, FileNotFoundError):
            pass

    def write_bytes(self, rel: str, data: bytes) -> None:
        """Writes ``rel`` whole or not at all (a temporary file renamed, locally)."""
        if self.local is not None:
            path = self.local / rel
            path.parent.mkdir(parents=True, exist_ok=True)
            tmp = path.parent / f".{path.name}.{uuid.uuid4().hex[:8]}"
            tmp.write_bytes(data)
            os.replace(tmp, path)
        else:
            with self.fs.open(self._join(rel), "wb") as f:
                f.write(data)

    def write_frame(self, rel: str, writer) -> None:
        """Writes what ``writer(buffer)`` writes into ``rel`` (whole or not at all)."""
        buf = io.BytesIO()
        writer(buf)
        self.write_bytes(rel, buf.getvalue())

    def clean_partial(self) -> None:
        """Removes the output sets that tries which never finished left."""
        if self.local is not None:
            shutil.rmtree(self.local / ".partial", ignore_errors=True)
            (self.local / ".partial").mkdir(parents=True, exist_ok=True)

    def open_local(self, rel: str) -> Optional[Path]:
        """A local path of ``rel`` to read (None for a URL folder)."""
        return None if self.local is None else self.local / rel
