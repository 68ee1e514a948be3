"""OpenCAMLib's geometry classes: points, CL and CC points, triangles, surfaces,
STL files, lines, arcs and paths.

The arithmetic is OpenCAMLib's, operation for operation (``src/geo``: the rotation
matrices of ``Point``, a triangle's normal from ``(p0 - p1) x (p0 - p2)``, an arc's
length and points by rotating ``p1 - c`` in the XY plane), so points on a path and
rotated surfaces are the same doubles as OpenCAMLib's. Printing follows its
``operator<<`` (C++ streams with six significant digits, as ``%g``).
"""

import enum
import math

import numpy as np

from .. import _swarf


def _g(v):
    """A number as a C++ stream prints a double by default."""
    return "%g" % v


class Point:
    """A point or vector ``(x, y, z)``, mm: ``Point()``, ``Point(x, y)`` (z = 0),
    ``Point(x, y, z)`` or ``Point(other)``."""

    __slots__ = ("x", "y", "z")

    def __init__(self, *args):
        n = len(args)
        try:
            if n == 3:
                self.x, self.y, self.z = float(args[0]), float(args[1]), float(args[2])
                return
            if n == 1 and isinstance(args[0], Point):
                p = args[0]
                self.x, self.y, self.z = p.x, p.y, p.z
                return
            if n == 2:
                self.x, self.y, self.z = float(args[0]), float(args[1]), 0.0
                return
        except (TypeError, ValueError):
            raise TypeError(f"{type(self).__name__}(): expected numbers, found {args!r}") from None
        if n != 0:
            raise TypeError(
                f"{type(self).__name__}(): expected (), (x, y), (x, y, z) or (Point), "
                f"found {n} arguments"
            )
        self.x = self.y = self.z = 0.0

    def __str__(self):
        return f"({_g(self.x)}, {_g(self.y)}, {_g(self.z)})"

    def __repr__(self):
        return f"Point({self.x!r}, {self.y!r}, {self.z!r})"

    def __add__(self, o):
        return Point(self.x + o.x, self.y + o.y, self.z + o.z)

    def __sub__(self, o):
        return Point(self.x - o.x, self.y - o.y, self.z - o.z)

    def __mul__(self, a):
        a = float(a)
        return Point(self.x * a, self.y * a, self.z * a)

    __rmul__ = __mul__

    def __iadd__(self, o):
        self.x += o.x
        self.y += o.y
        self.z += o.z
        return self

    def __isub__(self, o):
        self.x -= o.x
        self.y -= o.y
        self.z -= o.z
        return self

    def norm(self):
        """Length, mm."""
        return math.sqrt(self.x * self.x + self.y * self.y + self.z * self.z)

    def xyNorm(self):
        """Length of the XY projection, mm."""
        return math.sqrt(self.x * self.x + self.y * self.y)

    def normalize(self):
        """Scales to unit length (a zero vector stays zero)."""
        n = self.norm()
        if n != 0.0:
            k = 1 / n
            self.x, self.y, self.z = self.x * k, self.y * k, self.z * k

    def dot(self, o):
        """Dot product."""
        return self.x * o.x + self.y * o.y + self.z * o.z

    def cross(self, o):
        """Cross product."""
        return Point(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )

    def _matrix(self, a, b, c, d, e, f, g, h, i):
        x, y, z = self.x, self.y, self.z
        self.x, self.y, self.z = a * x + b * y + c * z, d * x + e * y + f * z, g * x + h * y + i * z

    def xRotate(self, theta):
        """Rotates about the X axis by ``theta`` radians."""
        c, s = math.cos(theta), math.sin(theta)
        self._matrix(1, 0, 0, 0, c, -s, 0, s, c)

    def yRotate(self, theta):
        """Rotates about the Y axis by ``theta`` radians."""
        c, s = math.cos(theta), math.sin(theta)
        self._matrix(c, 0, s, 0, 1, 0, -s, 0, c)

    def zRotate(self, theta):
        """Rotates about the Z axis by ``theta`` radians."""
        c, s = math.cos(theta), math.sin(theta)
        self._matrix(c, -s, 0, s, c, 0, 0, 0, 1)

    def isRight(self, p1, p2):
        """True when this point lies right of the XY line ``p1 -> p2`` (by more than
        1e-14, OpenCAMLib's threshold)."""
        t = (p2.y - p1.y) * (self.x - p1.x) - (p2.x - p1.x) * (self.y - p1.y)
        return t > 1e-14

    def xyDistance(self, o):
        """Distance in the XY plane, mm."""
        return (self - o).xyNorm()


class CCType(enum.IntEnum):
    """The kind of a cutter contact, numbered as OpenCAMLib's ``CCType``."""

    NONE = 0
    VERTEX = 1
    VERTEX_CYL = 2
    EDGE = 3
    EDGE_HORIZ = 4
    EDGE_SHAFT = 5
    EDGE_HORIZ_CYL = 6
    EDGE_HORIZ_TOR = 7
    EDGE_BALL = 8
    EDGE_POS = 9
    EDGE_NEG = 10
    EDGE_CYL = 11
    EDGE_CONE = 12
    EDGE_CONE_BASE = 13
    FACET = 14
    FACET_TIP = 15
    FACET_CYL = 16
    ERROR = 17

    def __str__(self):
        return self.name


class CCPoint(Point):
    """A cutter contact point: ``x``, ``y``, ``z`` (mm) and its ``type``
    (:class:`CCType`, ``NONE`` until a drop touches)."""

    __slots__ = ("type",)

    def __init__(self, *args):
        super().__init__(*args)
        self.type = args[0].type if len(args) == 1 and isinstance(args[0], CCPoint) else CCType.NONE

    def __str__(self):
        return f"CC({_g(self.x)}, {_g(self.y)}, {_g(self.z)}, t={int(self.type)})"

    def __repr__(self):
        return f"CCPoint({self.x!r}, {self.y!r}, {self.z!r}, {self.type.name})"


class CLPoint(Point):
    """A cutter location (the tool tip on the axis), mm, and its contact:
    ``CLPoint()``, ``CLPoint(x, y, z)``, ``CLPoint(x, y, z, cc)`` or
    ``CLPoint(other)``. A drop raises ``z`` to where the cutter touches, never
    lowers it: ``z`` is the floor."""

    __slots__ = ("_cc",)

    def __init__(self, *args):
        if len(args) == 1 and isinstance(args[0], CLPoint):
            super().__init__(args[0])
            self._cc = CCPoint(args[0]._cc)
        elif len(args) == 4:
            if not isinstance(args[3], CCPoint):
                raise TypeError("CLPoint(x, y, z, cc): cc must be a CCPoint")
            super().__init__(*args[:3])
            self._cc = CCPoint(args[3])
        else:
            super().__init__(*args)
            self._cc = CCPoint()

    def getCC(self):
        """A copy of the contact point."""
        return CCPoint(self._cc)

    cc = getCC

    def __str__(self):
        return f"CL({_g(self.x)}, {_g(self.y)}, {_g(self.z)}) cc={self._cc}"

    def __repr__(self):
        return f"CLPoint({self.x!r}, {self.y!r}, {self.z!r}, {self._cc!r})"


class Bbox:
    """An axis-aligned box: ``minpt``, ``maxpt`` (zero until something is added)."""

    def __init__(self, lo=(0.0, 0.0, 0.0), hi=(0.0, 0.0, 0.0)):
        self.minpt = Point(*lo)
        self.maxpt = Point(*hi)

    def isInside(self, p):
        """True when ``p`` lies in the box (its faces included)."""
        lo, hi = self.minpt, self.maxpt
        return lo.x <= p.x <= hi.x and lo.y <= p.y <= hi.y and lo.z <= p.z <= hi.z

    def __str__(self):
        return f" Bbox \n min= {self.minpt}\n max= {self.maxpt}\n"


class Triangle:
    """A triangle of three corners: ``Triangle(p1, p2, p3)`` (``Triangle()`` is
    OpenCAMLib's default, the corners (1, 0, 0), (0, 1, 0), (0, 0, 1))."""

    __slots__ = ("_c",)

    def __init__(self, *args):
        if not args:
            args = (Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, 1))
        if len(args) != 3 or not all(isinstance(p, Point) for p in args):
            raise TypeError("Triangle(): expected () or three Points")
        a, b, c = args
        self._c = (a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z)

    @property
    def p(self):
        """The corners, a list of three Points (copies)."""
        c = self._c
        return [Point(c[0], c[1], c[2]), Point(c[3], c[4], c[5]), Point(c[6], c[7], c[8])]

    def getPoints(self):
        """The corners, a list of three Points."""
        return self.p

    @property
    def n(self):
        """The unit normal ``(p0 - p1) x (p0 - p2)`` (zero for a degenerate
        triangle)."""
        p0, p1, p2 = self.p
        n = (p0 - p1).cross(p0 - p2)
        n.normalize()
        return n

    def __str__(self):
        p0, p1, p2 = self.p
        return f"T: {p0} {p1} {p2}n={self.n}"


class STLSurf:
    """A triangle surface: ``addTriangle``, ``size``, ``getBounds``, ``rotate``.

    Triangles with a non-finite corner are refused (``ValueError`` naming the call
    and the corner); degenerate ones are kept, as in OpenCAMLib, and never touched.
    The swarf mesh and drop indexes built from it are cached until the surface
    changes."""

    def __init__(self):
        self._tris = []
        self._version = 0
        self._cache = None

    def addTriangle(self, t):
        """Appends the triangle ``t``."""
        if not isinstance(t, Triangle):
            raise TypeError(f"STLSurf.addTriangle(t): expected a Triangle, found {type(t).__name__}")
        c = t._c
        if not all(math.isfinite(v) for v in c):
            k = next(k for k in range(3) if not all(math.isfinite(v) for v in c[3 * k:3 * k + 3]))
            raise ValueError(
                f"STLSurf.addTriangle(t): corner t.p[{k}] = {t.p[k]} has a non-finite coordinate"
            )
        self._tris.append(c)
        self._version += 1

    def _extend(self, corners):
        """Appends an ``(M, 9)`` float64 array of triangles (checked finite)."""
        self._tris.extend(map(tuple, corners.tolist()))
        self._version += 1

    def size(self):
        """Number of triangles."""
        return len(self._tris)

    def __len__(self):
        return len(self._tris)

    def __str__(self):
        return f"STLSurf(N={len(self._tris)})"

    def _array(self):
        """The triangles as an ``(M, 3, 3)`` float64 array."""
        return np.array(self._tris, dtype=np.float64).reshape(-1, 3, 3)

    def _state(self):
        """``(version, swarf.Mesh or None, bounds, cache)`` for the current triangles;
        the cache dict holds the ``(M, 3, 3)`` corners under ``"tris"`` and the drop
        indexes and waterline fields made for them."""
        if self._cache is None or self._cache[0] != self._version:
            tris = self._array()
            if len(tris):
                v = tris.reshape(-1, 3)
                mesh = _swarf.Mesh(v, np.arange(len(v), dtype=np.int64).reshape(-1, 3), "STLSurf")
                lo, hi = v.min(axis=0), v.max(axis=0)
            else:
                mesh, lo, hi = None, np.zeros(3), np.zeros(3)
            self._cache = (self._version, mesh, (lo, hi), {"tris": tris})
        return self._cache

    def getBounds(self):
        """``[minx, maxx, miny, maxy, minz, maxz]``, mm (zeros when empty)."""
        lo, hi = self._state()[2]
        return [float(lo[0]), float(hi[0]), float(lo[1]), float(hi[1]), float(lo[2]), float(hi[2])]

    @property
    def bb(self):
        """The bounding :class:`Bbox`."""
        lo, hi = self._state()[2]
        return Bbox(lo.tolist(), hi.tolist())

    def getTriangles(self):
        """The triangles, a list of :class:`Triangle`."""
        out = []
        for c in self._tris:
            t = Triangle.__new__(Triangle)
            t._c = c
            out.append(t)
        return out

    @property
    def tris(self):
        """The triangles, as :meth:`getTriangles`."""
        return self.getTriangles()

    def rotate(self, xr, yr, zr):
        """Rotates every corner about X by ``xr``, then Y by ``yr``, then Z by ``zr``
        (radians), as ``Point.xRotate`` ... do."""
        if not self._tris:
            return
        x, y, z = self._array().reshape(-1, 3).T
        for theta, axis in ((xr, 0), (yr, 1), (zr, 2)):
            c, s = math.cos(theta), math.sin(theta)
            m = {
                0: (1, 0, 0, 0, c, -s, 0, s, c),
                1: (c, 0, s, 0, 1, 0, -s, 0, c),
                2: (c, -s, 0, s, c, 0, 0, 0, 1),
            }[axis]
            x, y, z = (
                m[0] * x + m[1] * y + m[2] * z,
                m[3] * x + m[4] * y + m[5] * z,
                m[6] * x + m[7] * y + m[8] * z,
            )
        self._tris = []
        self._extend(np.column_stack([x, y, z]).reshape(-1, 9))


class STLReader:
    """Reads an STL file (binary or ASCII) into a surface: ``STLReader(path, surf)``
    appends its triangles to ``surf``. Corners are rounded to single precision, as
    OpenCAMLib reads them. Unlike OpenCAMLib, which reads a binary file whose header
    begins with ``solid`` as an empty ASCII one and a missing file as empty, every
    binary file is read and a file that cannot be read raises ``SwarfError`` naming
    it."""

    def __init__(self, *args):
        if not args:
            return
        if len(args) != 2 or not isinstance(args[1], STLSurf):
            raise TypeError("STLReader(filepath, surface): expected a path and an STLSurf")
        path, surf = args
        mesh = _swarf.Mesh.load(str(path))
        corners = mesh.vertices[mesh.faces].astype(np.float32).astype(np.float64)
        surf._extend(corners.reshape(-1, 9))


class SpanType(enum.IntEnum):
    """The kind of a path's span."""

    LineSpanType = 0
    ArcSpanType = 1


LineSpanType = SpanType.LineSpanType
ArcSpanType = SpanType.ArcSpanType


class Line:
    """A straight span from ``p1`` to ``p2``."""

    def __init__(self, *args):
        if len(args) == 1 and isinstance(args[0], Line):
            args = (args[0].p1, args[0].p2)
        if len(args) == 0:
            args = (Point(), Point())
        if len(args) != 2 or not all(isinstance(p, Point) for p in args):
            raise TypeError("Line(): expected (p1, p2) or (Line)")
        self.p1, self.p2 = Point(args[0]), Point(args[1])

    def length2d(self):
        """XY length, mm."""
        return (self.p2 - self.p1).xyNorm()

    def getPoint(self, t):
        """The point at ``t`` in [0, 1]."""
        return (self.p2 - self.p1) * t + self.p1

    def __str__(self):
        return f"({self.p1}, {self.p2})"


def _arc_property(name, doc):
    """A read-write attribute of an Arc that recomputes its radius and length."""

    def get(self):
        return getattr(self, name)

    def put(self, v):
        setattr(self, name, bool(v) if name == "_dir" else Point(v))
        self._properties()

    return property(get, put, doc=doc)


class Arc:
    """A circular span in the XY plane from ``p1`` to ``p2`` about the centre ``c``,
    counter-clockwise when ``dir`` is true."""

    def __init__(self, *args):
        if len(args) == 1 and isinstance(args[0], Arc):
            a = args[0]
            args = (a.p1, a.p2, a.c, a.dir)
        if len(args) != 4 or not all(isinstance(p, Point) for p in args[:3]):
            raise TypeError("Arc(): expected (p1, p2, c, dir) or (Arc)")
        self._p1, self._p2, self._c = Point(args[0]), Point(args[1]), Point(args[2])
        self._dir = bool(args[3])
        self._properties()

    def _properties(self):
        vs, ve = self._p1 - self._c, self._p2 - self._c
        vs, ve = Point(-vs.y, vs.x, vs.z), Point(-ve.y, ve.x, ve.z)
        self.radius = vs.xyNorm()
        vs.normalize()
        ve.normalize()
        self.length = abs(_included_angle(vs, ve, self._dir)) * self.radius

    p1 = _arc_property("_p1", "The start point.")
    p2 = _arc_property("_p2", "The end point.")
    c = _arc_property("_c", "The centre.")
    dir = _arc_property("_dir", "True for counter-clockwise.")

    def length2d(self):
        """XY length, mm."""
        return self.length

    def getPoint(self, t):
        """The point at ``t`` in [0, 1] along the arc."""
        if abs(t) < 1e-14:
            return Point(self._p1)
        if abs(t - 1.0) < 1e-14:
            return Point(self._p2)
        d = t * self.length
        if not self._dir:
            d = -d
        v = self._p1 - self._c
        a = d / self.radius
        cosa, sina = math.cos(a), math.sin(a)
        v.x, v.y = -v.y * sina + v.x * cosa, v.x * sina + cosa * v.y
        return v + self._c

    def __str__(self):
        return f"({self._p1}, {self._p2}, {self._c}, {int(self._dir)})"


def _included_angle(v1, v2, ccw):
    """The angle from ``v1`` to ``v2`` about +Z (radians, negative clockwise)."""
    d = 1 if ccw else -1
    inc = v1.dot(v2)
    if inc > 1.0 - 1.0e-10:
        return 0.0
    if inc < -1.0 + 1.0e-10:
        inc = math.pi
    else:
        inc = math.acos(min(inc, 1.0))
        if d * (v1.x * v2.y - v1.y * v2.x) < 0:
            inc = 2 * math.pi - inc
    return d * inc


class Path:
    """A sequence of :class:`Line` and :class:`Arc` spans: ``append``,
    ``getSpans``, ``getTypeSpanPairs``."""

    def __init__(self, other=None):
        self._spans = list(other._spans) if isinstance(other, Path) else []

    def append(self, span):
        """Appends a copy of a Line or an Arc."""
        if isinstance(span, Line):
            self._spans.append(Line(span))
        elif isinstance(span, Arc):
            self._spans.append(Arc(span))
        else:
            raise TypeError(f"Path.append: expected a Line or an Arc, found {type(span).__name__}")

    def getSpans(self):
        """The spans, a list of Line and Arc objects."""
        return list(self._spans)

    def getTypeSpanPairs(self):
        """``[(SpanType, span), ...]``."""
        return [(LineSpanType if isinstance(s, Line) else ArcSpanType, s) for s in self._spans]
