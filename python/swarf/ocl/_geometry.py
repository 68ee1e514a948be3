"""OpenCAMLib's triangles, surfaces and STL files.

A triangle's normal is OpenCAMLib's ``(p0 - p1) x (p0 - p2)``, normalised; a
surface's rotation applies ``Point``'s matrices in its order (X, then Y, then Z), so
rotated surfaces are the same doubles as OpenCAMLib's.
"""

import math

import numpy as np

from .. import _swarf
from ._points import Point


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
