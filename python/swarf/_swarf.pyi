"""Type stubs of swarf's native module (the package ``swarf`` re-exports it).

Units: mm, mm/min, seconds; angles in degrees where the job file and the command
line take degrees (tool specs, strategy angles), radians elsewhere.
"""

import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

#: Names of the feature codes of ``DropContacts.feature`` (the ``feature`` column of
#: ``swarf drop --contact``), in code order.
FEATURES: List[str]
#: ``Plan.kinds`` of a rapid move (G0).
MOVE_RAPID: int
#: ``Plan.kinds`` of a feed move (G1: cutting or plunging).
MOVE_FEED: int

PathLike = Union[str, "os.PathLike[str]"]
FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]
ToolLike = Union["Tool", str]
ModelLike = Union["Part", "Mesh", PathLike]
JobLike = Union["Job", Dict[str, Any], PathLike]

class SwarfError(ValueError):
    """An error swarf reports about its input (file, job, tool, parameter, program),
    with the command line's message: it names the file, the line and the field."""

def load(source: PathLike) -> Union["Part", "Mesh"]:
    """Loads a part file (``.toml``), a mesh (``.stl``, ``.obj``), ``builtin:NAME``
    or a bare built-in name, as the command line does: a ``Part`` for patches, a
    ``Mesh`` for triangles. Lengths in mm."""

class Part:
    """Parametric patches (Bezier, B-spline, NURBS) of a part, mm."""

    @staticmethod
    def load(source: PathLike) -> "Part":
        """Loads a part file or a built-in part (``"builtin:wave"``)."""
    @property
    def name(self) -> str:
        """The part's name."""
    def __len__(self) -> int:
        """Number of patches."""
    def domain(self, patch: int) -> Tuple[Tuple[float, float], Tuple[float, float]]:
        """The parameter domain ``((u0, u1), (v0, v1))`` of patch ``patch``."""
    def eval(self, patch: int, uv: npt.ArrayLike) -> Dict[str, FloatArray]:
        """Evaluates patch ``patch`` at each row ``(u, v)`` of an ``(N, 2)`` float64
        array, as ``swarf eval``: ``point``, ``du``, ``dv``, ``normal``, ``dir1``,
        ``dir2`` as ``(N, 3)`` arrays (mm, mm per parameter unit, unit vectors) and
        ``k1``, ``k2`` as ``(N,)`` arrays (principal curvatures, 1/mm). NaN where the
        patch is degenerate. ``ValueError`` for a row outside the domain."""
    def tessellate(self, tol: float = 0.01) -> "Mesh":
        """A mesh within the chordal tolerance ``tol`` (mm) of the patches."""

class Mesh:
    """A triangle mesh, mm."""

    def __init__(self, vertices: npt.ArrayLike, faces: npt.ArrayLike, name: str = "mesh") -> None:
        """A mesh from an ``(N, 3)`` float64 array of positions (mm, finite, within
        1 km of the origin) and an ``(M, 3)`` integer array of vertex indices
        (counter-clockwise seen from outside). ``ValueError`` naming the argument and
        the first bad row for a wrong shape or dtype, a non-finite coordinate, an
        index out of range (or negative), or an empty mesh."""
    @staticmethod
    def load(source: PathLike) -> "Mesh":
        """Loads an STL (binary or ASCII) or OBJ file, or a built-in mesh."""
    @property
    def name(self) -> str: ...
    @property
    def vertices(self) -> FloatArray:
        """``(N, 3)`` vertex positions, mm (a copy)."""
    @property
    def faces(self) -> IntArray:
        """``(M, 3)`` vertex indices (a copy)."""
    def bounds(self) -> Tuple[Tuple[float, float, float], Tuple[float, float, float]]:
        """``((xmin, ymin, zmin), (xmax, ymax, zmax))`` of the usable triangles, mm."""
    def __len__(self) -> int:
        """Number of triangles."""

class Tool:
    """A cutter: ``Tool("ball:d=8")`` or ``Tool(shape="bull", d=10, r=2)``.

    Spec keys (lengths mm, angles degrees): ``flat:d``, ``ball:d``, ``bull:d,r``,
    ``cone:d,angle`` (included), ``taperball:d,angle,tip``, ``apt:d,r,e,f,alpha,
    beta,h``; each takes ``length``."""

    def __init__(self, spec: Optional[str] = None, /, **kwargs: Union[str, float]) -> None: ...
    @property
    def spec(self) -> str:
        """The canonical spec string."""
    @property
    def radius(self) -> float:
        """Radius of the cutting part (d/2), mm."""

class DropContacts:
    """Drop heights with their contacts (``swarf drop --contact``)."""

    @property
    def z(self) -> FloatArray:
        """``(N,)`` tool tip heights, mm; NaN off the mesh."""
    @property
    def tri(self) -> IntArray:
        """``(N,)`` index of the touched triangle; -1 off the mesh."""
    @property
    def feature(self) -> npt.NDArray[np.int8]:
        """``(N,)`` feature touched, an index into ``FEATURES``; -1 off the mesh."""
    @property
    def cc(self) -> FloatArray:
        """``(N, 3)`` CC points, mm; NaN off the mesh."""
    def __len__(self) -> int: ...

class Dropper:
    """A cutter prepared for drops on one mesh (the index is built once)."""

    def __init__(self, mesh: ModelLike, tool: ToolLike) -> None: ...
    @property
    def tool(self) -> Tool: ...
    def __len__(self) -> int:
        """Number of triangles the drops use."""
    def drop(
        self, points: npt.ArrayLike, *, contacts: bool = False, threads: Optional[int] = None
    ) -> Union[FloatArray, DropContacts]:
        """Tool tip heights (mm) at each row ``(x, y)`` of an ``(N, 2)`` float64 array:
        ``(N,)``, NaN off the mesh; a ``DropContacts`` with ``contacts=True``. Runs on
        ``threads`` workers (default: every core) with the GIL released."""
    def _drop_timed(
        self, points: npt.ArrayLike, *, threads: Optional[int] = None
    ) -> Tuple[FloatArray, Tuple[float, float]]:
        """Benchmark support: ``drop(points, threads=threads)`` and the ``(wall, cpu)``
        seconds of its drops alone (CPU: the process's, as ``time.process_time``)."""

def drop(
    mesh: ModelLike,
    tool: ToolLike,
    points: npt.ArrayLike,
    *,
    contacts: bool = False,
    threads: Optional[int] = None,
) -> Union[FloatArray, DropContacts]:
    """``Dropper(mesh, tool).drop(points, contacts=..., threads=...)``."""

def waterline(part: ModelLike, tool: ToolLike, **params: Any) -> List[FloatArray]:
    """Waterline passes (closed loops at constant heights) as ``(K, 3)`` arrays of
    tool tips, mm; keyword arguments are the job file's ``[strategy]`` keys
    (``scallop``, ``steep_angle``, ``flat_angle``, ``level_step``, ``sampling``,
    ``tolerance``, ``adaptive``, ``direction``)."""

def raster(part: ModelLike, tool: ToolLike, **params: Any) -> List[FloatArray]:
    """Drop-cutter raster passes as ``(K, 3)`` arrays of tool tips, mm; keyword
    arguments are the job file's ``[strategy]`` keys (``scallop`` or ``stepover``,
    ``angle``, ``tolerance``, ``zigzag``, ``boundary``, ``max_slope``, ``max_ramp``,
    ``start``)."""

class Job:
    """A job in the job file's schema, with the folder its relative paths start from."""

    @staticmethod
    def load(path: PathLike) -> "Job": ...
    @staticmethod
    def from_toml(text: str, base_dir: Optional[PathLike] = None) -> "Job": ...
    @staticmethod
    def from_dict(job: Dict[str, Any], base_dir: Optional[PathLike] = None) -> "Job": ...
    @property
    def name(self) -> Optional[str]: ...
    @property
    def part(self) -> str: ...
    def load_part(self) -> Union["Part", "Mesh"]:
        """The job's part read as ``swarf.plan(job)`` reads it (its ``[import]``
        options and ``faces``), to pass as ``plan(job, part=...)`` to the jobs on
        it. ``SwarfError`` naming the job and the part for one that cannot be read."""
    @property
    def tool(self) -> Tool: ...
    @property
    def kind(self) -> str: ...
    @property
    def base_dir(self) -> str: ...
    @property
    def toml(self) -> str: ...

class Plan:
    """A planned tool path (``swarf plan``)."""

    @property
    def poses(self) -> FloatArray:
        """``(N, 6)`` poses ``x, y, z, i, j, k`` of the program's moves (tool tip in
        mm, unit tool axis), links included."""
    @property
    def kinds(self) -> npt.NDArray[np.int8]:
        """``(N,)`` ``MOVE_RAPID`` or ``MOVE_FEED``."""
    @property
    def feeds(self) -> FloatArray:
        """``(N,)`` feed rates, mm/min (0 for rapids)."""
    @property
    def pass_index(self) -> IntArray:
        """``(N,)`` the pass each move cuts in; -1 for links."""
    @property
    def passes(self) -> List[FloatArray]:
        """The cutting passes as ``(K, 6)`` arrays of poses."""
    @property
    def summary(self) -> Dict[str, Any]:
        """``swarf plan``'s JSON summary."""
    @property
    def gcode(self) -> Optional[str]:
        """The G-code the job writes (None: a five-axis job without a machine)."""
    @property
    def cl(self) -> Optional[str]:
        """The APT CL the job writes."""
    def write_gcode(self, path: PathLike) -> None: ...
    def write_cl(self, path: PathLike) -> None: ...

class SequencePlan:
    """A planned sequence job (``[[operation]]`` tables: operations in order on one
    stock, a tool change each), as ``swarf plan`` plans it."""

    @property
    def report(self) -> Dict[str, Any]:
        """The sequence's report (``output.summary``'s JSON): ``name``, ``grid``,
        ``operations``, ``time_s``."""
    @property
    def operations(self) -> List[Dict[str, Any]]:
        """Each operation's report: ``name``, ``number``, ``tool``, ``strategy``,
        ``motions``, ``cutting_length_mm``, ``time_s``, ``engagement`` (roughing),
        ``gouge_cells``, ``worst_gouge_mm``, ``rest_cells``, ``rest_limit_mm``,
        ``max_rest_mm``, ``holder``."""
    @property
    def program(self) -> str:
        """The whole program's G-code, a tool change per operation."""
    @property
    def programs(self) -> List[str]:
        """Each operation's own G-code, in order."""
    @property
    def rest(self) -> FloatArray:
        """``(N, 3)`` cells left more than the last operation's limit above the
        design: centre ``x, y`` and the material above it, mm."""
    def lines(self) -> List[str]:
        """The lines ``swarf plan`` prints: one per operation, then the total."""
    def write_gcode(self, path: PathLike) -> None: ...

def plan(
    job: JobLike,
    *,
    part: Optional[Union["Part", "Mesh"]] = None,
    out: Optional[PathLike] = None,
    allow_unsafe: bool = False,
    verify: bool = True,
) -> Union[Plan, SequencePlan]:
    """Plans a job (a ``Job``, a dict, TOML text or a job file path) as
    ``swarf plan`` does; with ``out`` writes the job's outputs there. A sequence
    job (``[[operation]]`` tables; a path, TOML text or a dict) gives a
    ``SequencePlan``; errors name ``operation[k]``. The program is verified on
    the job's stock first: an unsafe one raises ``SwarfError`` naming its lines;
    ``allow_unsafe=True`` returns it labelled, ``verify=False`` skips the check.

    ``part``: the job's part already loaded (``Job.load_part()``, or
    ``Part.load`` / ``Mesh.load`` of its file), planned on instead of reading it
    again: the same plan, bit for bit. ``SwarfError`` naming ``part`` for a part
    read with other ``[import]`` options or another face selection than the job's
    (a part read whole gets the job's ``faces``), a mesh for a job with ``faces``,
    or a sequence job; ``TypeError`` for anything but a ``Part`` or a ``Mesh``."""

class Verification:
    """What a verification found, over the dexel grid (``ny`` rows, ``nx`` columns)."""

    @property
    def report(self) -> Dict[str, Any]:
        """``report.json`` as a dict."""
    @property
    def deviation(self) -> FloatArray:
        """``(ny, nx)`` machined minus design, mm (negative: gouge); NaN unmeasured."""
    @property
    def design(self) -> FloatArray:
        """``(ny, nx)`` design heights, mm; NaN off the design."""
    @property
    def machined(self) -> FloatArray:
        """``(ny, nx)`` machined stock heights, mm."""
    @property
    def x(self) -> FloatArray:
        """``(nx,)`` x of the cell centres, mm."""
    @property
    def y(self) -> FloatArray:
        """``(ny,)`` y of the cell centres, mm."""
    @property
    def extent(self) -> Tuple[float, float, float, float]:
        """``(xmin, xmax, ymin, ymax)`` of the grid, mm."""
    @property
    def cell(self) -> float:
        """Cell side, mm."""
    @property
    def complete(self) -> bool: ...
    @property
    def notes(self) -> List[str]: ...

def verify(
    part: PathLike,
    program: Union[PathLike, Sequence[PathLike]],
    tool: Union[ToolLike, Sequence[ToolLike], None] = None,
    *,
    machine: Optional[str] = None,
    tool_length: Optional[float] = None,
    stock: str = "offset:0.5",
    cell: Optional[float] = None,
    tol: Optional[float] = None,
    scallop: Optional[float] = None,
    rapid: Optional[float] = None,
    sample_tol: Optional[float] = None,
    max_memory: int = 4096,
    deviation: Optional[str] = None,
    dialect: str = "linuxcnc",
    tool_table: Optional[PathLike] = None,
    params: Optional[PathLike] = None,
    sub_path: Sequence[PathLike] = (),
    machine_units: str = "mm",
    out: Optional[PathLike] = None,
    partial: bool = False,
    first_order_sweep: bool = False,
    floor: Optional[float] = None,
) -> Verification:
    """Simulates programs on a dexel stock and measures them against the design, as
    ``swarf verify`` does (the keyword arguments are its flags)."""

class RestRegion:
    """A rest region: figures and boundary polygons."""

    @property
    def area(self) -> float:
        """mm²."""
    @property
    def raw_area(self) -> float:
        """mm²."""
    @property
    def depth(self) -> float:
        """Largest rest thickness, mm."""
    @property
    def deepest(self) -> Tuple[float, float, float]: ...
    @property
    def kinds(self) -> List[str]: ...
    @property
    def boundary(self) -> List[FloatArray]:
        """Rings (outer first, then holes), each a closed ``(K, 2)`` array, mm."""
    @property
    def raw(self) -> List[List[FloatArray]]:
        """The raw polygons, each a list of rings."""

class Rest:
    """Rest regions (``swarf rest``)."""

    @property
    def report(self) -> Dict[str, Any]:
        """``rest.json`` as a dict."""
    @property
    def regions(self) -> List[RestRegion]: ...
    def __len__(self) -> int: ...

def rest(
    part: Optional[PathLike] = None,
    *,
    reference: Optional[ToolLike] = None,
    job: Optional[PathLike] = None,
    source: str = "reference",
    threshold: float = 0.01,
    merge: float = 2.0,
    overlap: float = 1.0,
    min_area: float = 0.5,
    smoothness: float = 0.5,
    tol: float = 0.01,
    out: Optional[PathLike] = None,
) -> Rest:
    """The rest material a finishing tool (``reference``) or job (``job``) leaves, as
    ``swarf rest`` finds it."""

class OclWaterline:
    """swarf.ocl's waterline: the drop field of ``tool`` over ``mesh`` on a grid of
    ``sampling`` mm, ready for any level."""

    def __init__(
        self, mesh: Mesh, tool: ToolLike, sampling: float, tolerance: float, threads: Optional[int] = None
    ) -> None: ...
    def loops(self, z: float) -> List[FloatArray]:
        """The loops at tip height ``z``: ``(K, 2)`` arrays, the material on their
        left, every chord within ``tolerance`` of the contour."""

def triangle_drop_at(
    tool: ToolLike, x: float, y: float, tri: Tuple[Tuple[float, float, float], ...], kind: str
) -> Optional[Tuple[float, Tuple[float, float, float], int]]:
    """The ``"vertex"``, ``"edge"``, ``"facet"`` or ``"all"`` drop of ``tool`` at
    ``(x, y)`` onto one triangle: ``(z, cc, feature)`` or None."""
