"""swarf: a CAM kernel for sculptured surfaces, from Python with numpy arrays.

Lengths are millimetres, angles radians inside (degrees where the job file and the
command line take degrees: tool specs, strategy angles). Everything here calls the
library the ``swarf`` command line uses, so results are the command line's, bit for
bit, and errors carry its messages (``SwarfError``, a ``ValueError``).

- parts: :func:`load`, :class:`Part` (patches; ``eval``, ``tessellate``),
  :class:`Mesh` (from files or numpy arrays);
- tools: :class:`Tool` (``Tool("ball:d=8")`` or ``Tool(shape="bull", d=10, r=2)``);
- drop-cutter: :func:`drop`, :class:`Dropper` (heights for an ``(N, 2)`` array, NaN
  off the part; the GIL is released and every core used);
- paths: :func:`waterline`, :func:`raster` (lists of ``(K, 3)`` arrays);
- jobs: :class:`Job`, :func:`plan` (poses ``(N, 6)``, move kinds, summary dict,
  G-code and APT CL); a sequence job (``[[operation]]`` tables, stock to part)
  gives a :class:`SequencePlan` (report and per-operation dicts, the whole program,
  rest cells ``(N, 3)``);
- verification: :func:`verify` (report dict, deviation grid ``(ny, nx)``);
- rest material: :func:`rest` (regions as arrays of polygons).
"""

from ._swarf import (
    FEATURES,
    MOVE_FEED,
    MOVE_RAPID,
    DropContacts,
    Dropper,
    Job,
    Mesh,
    Part,
    Plan,
    Rest,
    RestRegion,
    SequencePlan,
    SwarfError,
    Tool,
    Verification,
    __version__,
    drop,
    load,
    plan,
    raster,
    rest,
    verify,
    waterline,
)

__all__ = [
    "FEATURES",
    "MOVE_FEED",
    "MOVE_RAPID",
    "DropContacts",
    "Dropper",
    "Job",
    "Mesh",
    "Part",
    "Plan",
    "Rest",
    "RestRegion",
    "SequencePlan",
    "SwarfError",
    "Tool",
    "Verification",
    "__version__",
    "drop",
    "load",
    "plan",
    "raster",
    "rest",
    "verify",
    "waterline",
]
