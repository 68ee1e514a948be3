"""The row of a task: its job and parameters, the plan's figures (from the summary
``swarf plan`` writes), the verification's (from ``report.json``), the times and
the status. The same functions turn the command line's files into rows, so a
batch's table can be checked against ``swarf plan`` and ``swarf verify`` run alone.
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional

#: The table's columns, in order (the swept parameters follow as ``param.KEY``).
COLUMNS: List[str] = [
    "key",
    "mode",
    "label",
    "job",
    "part",
    "tool",
    "strategy",
    "params",
    "status",
    "error",
    "passes",
    "poses",
    "cutting_length_mm",
    "machining_time_s",
    "gate_gouge_cells",
    "gate_excess_cells",
    "gate_rapid_cuts",
    "scallop_min_mm",
    "scallop_max_mm",
    "scallop_p50_mm",
    "gouge_cells",
    "worst_gouge_mm",
    "excess_cells",
    "worst_excess_mm",
    "rest_mm3",
    "verify_complete",
    "plan_s",
    "verify_s",
    "task_s",
    "worker_pid",
    "outputs",
]
#: Columns that depend on the run (wall-clock times, the worker), not the job.
RUN_COLUMNS = ("plan_s", "verify_s", "task_s", "worker_pid")
#: Float columns (missing: NaN in the table).
FLOAT_COLUMNS = (
    "cutting_length_mm",
    "machining_time_s",
    "scallop_min_mm",
    "scallop_max_mm",
    "scallop_p50_mm",
    "worst_gouge_mm",
    "worst_excess_mm",
    "rest_mm3",
    "plan_s",
    "verify_s",
    "task_s",
)
#: Count columns (missing: <NA> in the table).
INT_COLUMNS = (
    "passes",
    "poses",
    "gate_gouge_cells",
    "gate_excess_cells",
    "gate_rapid_cuts",
    "gouge_cells",
    "excess_cells",
    "worker_pid",
)


def plan_fields(summary: Dict[str, Any]) -> Dict[str, Any]:
    """The plan's fields of a row, from ``swarf plan``'s JSON summary."""
    gate = summary.get("verification", {})
    skipped = "skipped" in gate
    return {
        "passes": summary.get("passes"),
        "poses": summary.get("poses"),
        "cutting_length_mm": summary.get("cutting_length_mm"),
        "machining_time_s": summary.get("estimated_time_s"),
        "gate_gouge_cells": None if skipped else gate.get("gouge_cells"),
        "gate_excess_cells": None if skipped else gate.get("excess_cells"),
        "gate_rapid_cuts": None if skipped else len(gate.get("rapid_cuts", [])),
    }


def sequence_fields(report: Dict[str, Any]) -> Dict[str, Any]:
    """The plan's fields of a sequence job's row, from its report."""
    ops = report.get("operations", [])
    return {
        "passes": None,
        "poses": None,
        "cutting_length_mm": sum(o.get("cutting_length_mm", 0.0) for o in ops),
        "machining_time_s": report.get("time_s"),
        "gate_gouge_cells": sum(o.get("gouge_cells", 0) for o in ops),
        "gate_excess_cells": ops[-1].get("rest_cells") if ops else None,
        "gate_rapid_cuts": None,
    }


def verify_fields(report: Dict[str, Any]) -> Dict[str, Any]:
    """The verification's fields of a row, from ``report.json``."""
    d = report.get("deviation", {})
    scallop = d.get("scallop", {})
    gouge = d.get("gouge", {})
    excess = d.get("excess", {})
    return {
        "scallop_min_mm": scallop.get("min"),
        "scallop_max_mm": scallop.get("max"),
        "scallop_p50_mm": scallop.get("p50"),
        "gouge_cells": gouge.get("cells"),
        "worst_gouge_mm": gouge.get("worst"),
        "excess_cells": excess.get("cells"),
        "worst_excess_mm": excess.get("worst"),
        "rest_mm3": excess.get("volume_mm3"),
        "verify_complete": report.get("complete"),
    }


def frame(rows: List[Dict[str, Any]], param_names: Optional[List[str]] = None):
    """The rows as a pandas DataFrame: the columns of :data:`COLUMNS` in order (a
    missing figure NaN or <NA>), then one ``param.KEY`` column per swept
    parameter."""
    import json

    import pandas as pd

    names = list(param_names or [])
    if param_names is None:
        for r in rows:
            for k in json.loads(r.get("params") or "{}"):
                if k not in names:
                    names.append(k)
    data: Dict[str, Any] = {}
    for c in COLUMNS:
        values = [r.get(c) for r in rows]
        if c in FLOAT_COLUMNS:
            data[c] = pd.array([float("nan") if v is None else float(v) for v in values], dtype="float64")
        elif c in INT_COLUMNS:
            data[c] = pd.array(values, dtype="Int64")
        elif c == "verify_complete":
            data[c] = pd.array(values, dtype="boolean")
        else:
            data[c] = pd.array(["" if v is None else str(v) for v in values], dtype="string")
    for n in names:
        values = [json.loads(r.get("params") or "{}").get(n) for r in rows]
        kinds = {type(v) for v in values if v is not None}
        if kinds <= {int, float} and kinds:
            data[f"param.{n}"] = pd.array([float("nan") if v is None else float(v) for v in values], dtype="float64")
        elif kinds <= {bool} and kinds:
            data[f"param.{n}"] = pd.array(values, dtype="boolean")
        else:
            data[f"param.{n}"] = pd.array(["" if v is None else str(v) for v in values], dtype="string")
    return pd.DataFrame(data)
