"""Pictures of a sweep, saved beside its table (matplotlib, Agg): machining time
against the scallop measured (or planned) per strategy, and the deviation maps of
the verified tasks as thumbnails in a grid (red: gouge, blue: material left)."""

from __future__ import annotations

import io
import json
import math
from typing import Callable

#: The scatter plot of machining time against scallop.
TIME_PLOT = "time_vs_scallop.png"
#: The grid of deviation thumbnails.
MAPS_PLOT = "deviation_maps.png"
#: Thumbnails at most in the grid.
MAX_THUMBNAILS = 48


def _scallop(df):
    """The scallop per row: measured (the largest crest) where verified, else the
    planned limit (``strategy.scallop``)."""
    import numpy as np

    measured = df["scallop_max_mm"].to_numpy(dtype=float, na_value=np.nan)
    planned = np.array([json.loads(p or "{}").get("strategy.scallop", np.nan) for p in df["params"]], dtype=float)
    return np.where(np.isnan(measured), planned, measured), bool(np.isfinite(measured).any())


def save_plots(df, res, log: Callable[[str], None]) -> None:
    """Writes :data:`TIME_PLOT` and, where tasks were verified, :data:`MAPS_PLOT`
    into the results folder ``res``; says so when matplotlib is missing."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        log("swarf batch: no plots: matplotlib is not installed (pip install swarf[batch])")
        return
    ok = df[df["status"] == "ok"]
    timed = ok[ok["machining_time_s"].notna()]
    if len(timed):
        _time_plot(timed, res, plt)
    _maps(ok, res, plt)


def _time_plot(ok, res, plt) -> None:
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=100)
    scallop, measured = _scallop(ok)
    for strategy in sorted(set(ok["strategy"])):
        sel = (ok["strategy"] == strategy).to_numpy()
        ax.scatter(scallop[sel], ok["machining_time_s"].to_numpy(dtype=float)[sel] / 60, label=strategy or "(none)", s=14)
    ax.set_xlabel("scallop, mm (" + ("largest measured" if measured else "planned") + ")")
    ax.set_ylabel("machining time, min")
    ax.set_title("machining time against scallop, per strategy")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    _save(fig, res, TIME_PLOT)


def _maps(ok, res, plt) -> None:
    import numpy as np

    verified = ok[ok["verify_s"].notna()].head(MAX_THUMBNAILS)
    grids = []
    for _, r in verified.iterrows():
        path = res.open_local(f"{r['outputs']}/verify/deviation.npy")
        if path is None or not path.is_file():
            continue
        grids.append((r, np.load(path)))
    if not grids:
        return
    cols = min(8, len(grids))
    rows = math.ceil(len(grids) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(2 * cols, 1.6 * rows + 0.4), dpi=100, squeeze=False)
    limit = 0.0
    for _, g in grids:
        finite = g[np.isfinite(g)]
        if finite.size:
            limit = max(limit, float(np.percentile(np.abs(finite), 99)))
    limit = limit or 1.0
    for ax in axes.flat:
        ax.axis("off")
    for ax, (r, g) in zip(axes.flat, grids):
        ax.imshow(g, origin="lower", cmap="RdBu", vmin=-limit, vmax=limit, interpolation="nearest")
        ax.set_title(f"{r['strategy']}\n{r['part'].rsplit('/', 1)[-1]} {r['tool']}", fontsize=6)
    fig.suptitle(f"deviation, mm (red: gouge, blue: left; scale +-{limit:.3g})", fontsize=8)
    _save(fig, res, MAPS_PLOT)


def _save(fig, res, name: str) -> None:
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    fig.tight_layout()
    fig.savefig(buf, format="png")
    plt.close(fig)
    res.write_bytes(name, buf.getvalue())
