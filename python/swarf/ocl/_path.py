"""OpenCAMLib's paths: ``Line``, ``Arc`` (its length and points by rotating
``p1 - c`` in the XY plane, as ``src/geo/arc.cpp``), ``Path`` and ``SpanType``; so
the points sampled on a path are the same doubles as OpenCAMLib's.
"""

import enum
import math

from ._points import Point


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
