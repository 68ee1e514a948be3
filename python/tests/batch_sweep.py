"""The sweep the batch tests and the scaling benchmark run: paper 004's three iso
strategies and the raster on wave, die and a generated mold, five scallop heights,
two tools and both cutting orders (240 jobs), coarse enough for a debug build, and a
block of 12 jobs verified on the part (paper 004's Table 1).
"""

from pathlib import Path

STRATEGIES = ["iso-parametric", "iso-planar", "iso-scallop", "raster"]
SCALLOPS = [0.2, 0.3, 0.4, 0.5, 0.6]
TOOLS = ["ball:d=10", "ball:d=16"]


def mold_part(width=120.0, depth_y=80.0, top=30.0, floor=6.0):
    """A mold cavity as one bicubic Bezier patch (part file TOML): a dish whose rim
    is at ``top`` and whose four inner control points are at ``floor``."""
    pts = []
    for i in range(4):
        for j in range(4):
            x, y = width * i / 3, depth_y * j / 3
            inner = 0 < i < 3 and 0 < j < 3
            pts.append(f"  [{x:.3f}, {y:.3f}, {floor if inner else top:.3f}],")
    return 'name = "mold"\nunits = "mm"\n\n[[patch]]\ndegree = [3, 3]\npoints = [\n' + "\n".join(pts) + "\n]\n"


def write_sweep(folder, parts=None, scallops=SCALLOPS, compare_block=True, max_tasks=None):
    """Writes ``mold.toml`` and ``sweep.toml`` into ``folder``; returns the sweep's path."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "mold.toml").write_text(mold_part())
    parts = parts or ["builtin:wave", "builtin:die", "mold.toml"]
    q = lambda xs: "[" + ", ".join(f'"{x}"' if isinstance(x, str) else repr(x) for x in xs) + "]"
    text = f"""# paper 004's comparison, coarse: plans without the gate, a block verified
[batch]
mode = "plan"
gate = false
{f"max_tasks = {max_tasks}" if max_tasks else ""}

[batch.verify]
cell = 1.0

[base]
name = "sweep"
part = "builtin:wave"
tool = "ball:d=10"

[base.strategy]
kind = "raster"
scallop = 0.5
tolerance = 0.1

[base.feeds]
feed = 1200

[[sweep]]
part = {q(parts)}
"strategy.kind" = {q(STRATEGIES)}
"strategy.scallop" = {q(scallops)}
tool = {q(TOOLS)}
"strategy.zigzag" = [true, false]
"""
    if compare_block:
        text += f"""
[[sweep]]
"batch.mode" = "compare"
part = {q(parts)}
"strategy.kind" = {q(STRATEGIES)}
"strategy.scallop" = 0.4
"batch.gate" = true
"""
    path = folder / "sweep.toml"
    path.write_text(text)
    return path
