"""OpenCAMLib's points: ``Point`` (its arithmetic, operation for operation, as
``src/geo/point.cpp``: the rotation matrices, ``normalize`` scaling by ``1 / norm``),
``CLPoint``, ``CCPoint`` and ``CCType``. Printing follows OpenCAMLib's
``operator<<`` (C++ streams with six significant digits, as ``%g``).
"""

import enum
import math


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
