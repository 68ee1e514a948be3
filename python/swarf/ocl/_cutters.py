"""OpenCAMLib's cutters, each a swarf :class:`~swarf.Tool` of the same shape.

``CylCutter(d, L)`` is ``flat:d``, ``BallCutter(d, L)`` ``ball:d``,
``BullCutter(d, r, L)`` ``bull:d,r`` (``r`` the corner radius), ``ConeCutter(d, a,
L)`` ``cone:d`` with the included angle ``2 a`` (``a`` the half-angle, radians) and
``BallConeCutter(d1, d2, a)`` the tapered ball of tip radius ``d1 / 2``, taper ``a``
per side and shank ``d2``. Drops are swarf's exact ones (:mod:`swarf.ocl`); the
length ``L`` is kept for ``getLength`` and printing, and, as in OpenCAMLib, the
cutter is its cutting surface extended upward.

Arguments outside the shape's domain (which OpenCAMLib asserts in debug builds and
computes nonsense from, or crashes on, in release builds) raise ``ValueError``
naming the argument.
"""

import math

import numpy as np

from .. import _swarf
from ._geometry import STLSurf, Triangle
from ._points import CCPoint, CCType, CLPoint, _g

#: Kinds of drop contacts by swarf feature code (``swarf.FEATURES``).
_VERTEX, _EDGE, _FACET = range(3)


def _length(call, name, v, *, zero=False):
    v = float(v)
    if not (math.isfinite(v) and (v >= 0.0 if zero else v > 0.0)):
        domain = "a length >= 0 in mm" if zero else "a positive length in mm"
        raise ValueError(f"{call}: {name} = {v!r}: expected {domain}")
    return v


def _angle(call, name, v):
    v = float(v)
    if not (0.0 < v < math.pi / 2):
        raise ValueError(f"{call}: {name} = {v!r}: expected a half-angle in radians in (0, pi/2)")
    return v


class MillingCutter:
    """The base of the cutters: drops onto one triangle or a surface, sizes,
    ``offsetCutter``."""

    def __init__(self, *args):
        raise TypeError("MillingCutter is abstract: use CylCutter, BallCutter, BullCutter, ConeCutter")

    def _setup(self, tool, diameter, length):
        self._tool = tool
        self._d = diameter
        self._length = length

    def getDiameter(self):
        """Diameter, mm."""
        return self._d

    def getRadius(self):
        """Radius, mm."""
        return self._d / 2.0

    def getLength(self):
        """Length, mm (OpenCAMLib's: a cone's includes its conical part)."""
        return self._length

    #: OpenCAMLib's names of vertex, edge and facet contacts.
    _TYPES = (CCType.VERTEX, CCType.EDGE, CCType.FACET)

    def _cc_types(self, codes, cc, cl):
        """OpenCAMLib's contact types (an int array) of contacts with swarf feature
        codes ``codes`` (``(N,)``) at CC points ``cc`` (``(N, 3)``) of a cutter at
        ``cl`` (``(N, 2)``)."""
        return np.array([int(t) for t in self._TYPES])[_kinds(codes)]

    def _lift(self, cl, hit):
        """Raises ``cl`` to the drop ``hit`` (``(z, cc, code)`` or None) when it is
        higher; True when it was."""
        if hit is None or not hit[0] > cl.z:
            return False
        z, (x, y, zc), code = hit
        cl.z = z
        cc = CCPoint(x, y, zc)
        cc.type = CCType(int(self._cc_types(np.array([code]), np.array([[x, y, zc]]), np.array([[cl.x, cl.y]]))[0]))
        cl._cc = cc
        return True

    def _drop(self, kind, cl, t):
        if not isinstance(cl, CLPoint) or not isinstance(t, Triangle):
            raise TypeError(f"{type(self).__name__}: expected (CLPoint, Triangle)")
        _finite_xy("cl", cl)
        c = t._c
        hit = _swarf.triangle_drop_at(self._tool, cl.x, cl.y, (c[0:3], c[3:6], c[6:9]), kind)
        return self._lift(cl, hit)

    def vertexDrop(self, cl, t):
        """Lifts ``cl`` onto the corners of ``t``; True when it moved."""
        return self._drop("vertex", cl, t)

    def edgeDrop(self, cl, t):
        """Lifts ``cl`` onto the edges of ``t``; True when it moved."""
        return self._drop("edge", cl, t)

    def facetDrop(self, cl, t):
        """Lifts ``cl`` onto the facet of ``t``; True when it moved."""
        return self._drop("facet", cl, t)

    def dropCutter(self, cl, t):
        """Lifts ``cl`` onto ``t`` (corners, edges, facet); True when it moved."""
        return self._drop("all", cl, t)

    def dropCutterSTL(self, cl, s):
        """Lifts ``cl`` onto the surface ``s``; True when it moved."""
        if not isinstance(s, STLSurf):
            raise TypeError("dropCutterSTL(cl, s): s must be an STLSurf")
        from ._dropcutter import _dropper

        _finite_xy("cl", cl)
        r = _dropper("dropCutterSTL", s, self).drop([[cl.x, cl.y]], contacts=True, threads=1)
        if r.tri[0] < 0:
            return False
        return self._lift(cl, (float(r.z[0]), tuple(r.cc[0].tolist()), int(r.feature[0])))

    def pushCutter(self, *args):
        """Not implemented: OpenCAMLib's push-cutter on a fiber (swarf's waterline
        finds contours by drops)."""
        raise NotImplementedError("swarf.ocl: MillingCutter.pushCutter() is not implemented")

    def offsetCutter(self, d):
        """This cutter grown by ``d`` mm all round."""
        raise NotImplementedError(f"swarf.ocl: {type(self).__name__}.offsetCutter() is not implemented")

    def __repr__(self):
        return str(self)


def _kinds(codes):
    """Vertex (0), edge (1) or facet (2) for swarf feature codes (``swarf.FEATURES``)."""
    return np.minimum(np.asarray(codes) // 3, 2)


def _finite_xy(name, p):
    if not (math.isfinite(p.x) and math.isfinite(p.y)):
        raise ValueError(f"{name} = {p}: expected finite x and y")


class CylCutter(MillingCutter):
    """Flat end mill: ``CylCutter(diameter, length)``."""

    def __init__(self, diameter, length):
        call = "CylCutter(diameter, length)"
        d, length = _length(call, "diameter", diameter), _length(call, "length", length)
        self._setup(_swarf.Tool(shape="flat", d=d), d, length)

    def offsetCutter(self, d):
        return BullCutter(self._d + 2 * d, d, self._length + d)

    def __str__(self):
        return f"CylCutter (d={_g(self._d)}, L={_g(self._length)})"


class BallCutter(MillingCutter):
    """Ball end mill: ``BallCutter(diameter, length)``."""

    def __init__(self, diameter, length):
        call = "BallCutter(diameter, length)"
        d, length = _length(call, "diameter", diameter), _length(call, "length", length)
        self._setup(_swarf.Tool(shape="ball", d=d), d, length)

    def offsetCutter(self, d):
        return BallCutter(self._d + 2 * d, self._length + d)

    def __str__(self):
        return f"BallCutter(d={_g(self._d)}, r={_g(self._d / 2.0)}, L={_g(self._length)})"


class BullCutter(MillingCutter):
    """Bull-nose end mill: ``BullCutter(diameter, corner_radius, length)``, the
    corner radius in ``[0, diameter / 2)``."""

    def __init__(self, diameter, radius, length):
        call = "BullCutter(diameter, radius, length)"
        d = _length(call, "diameter", diameter)
        length = _length(call, "length", length)
        r = float(radius)
        if not (0.0 <= r < d / 2.0):
            raise ValueError(f"{call}: radius = {r!r}: expected a corner radius in [0, diameter/2) mm")
        self._r = r
        self._setup(_swarf.Tool(shape="bull", d=d, r=r), d, length)

    def offsetCutter(self, d):
        return BullCutter(self._d + 2 * d, self._r + d, self._length + d)

    def __str__(self):
        r1 = self._d / 2.0 - self._r
        return f"BullCutter(d={_g(self._d)}, r1={_g(r1)} r2={_g(self._r)}, L={_g(self._length)})"


class ConeCutter(MillingCutter):
    """Conical cutter: ``ConeCutter(diameter, angle, length=10)``, ``angle`` the
    half-angle from the axis in radians, ``length`` the cylinder above the cone
    (``getLength`` adds the cone's height, as OpenCAMLib's)."""

    def __init__(self, diameter, angle, length=10.0):
        call = "ConeCutter(diameter, angle, length)"
        d = _length(call, "diameter", diameter)
        a = _angle(call, "angle", angle)
        extra = _length(call, "length", length, zero=True)
        self._angle = a
        self._setup(_swarf.Tool(shape="cone", d=d, angle=math.degrees(2 * a)), d, d / 2.0 / math.tan(a) + extra)

    def _cc_types(self, codes, cc, cl):
        """A cone touches a facet with its tip (``FACET_TIP``) or its rim
        (``FACET_CYL``)."""
        kinds = _kinds(codes)
        rim = np.hypot(cc[:, 0] - cl[:, 0], cc[:, 1] - cl[:, 1]) >= 0.5 * self._d * (1 - 1e-9)
        facet = np.where(rim, int(CCType.FACET_CYL), int(CCType.FACET_TIP))
        return np.where(kinds == _FACET, facet, super()._cc_types(codes, cc, cl))

    def offsetCutter(self, d):
        return BallConeCutter(2 * d, self._d + 2 * d, self._angle)

    def __str__(self):
        return f"ConeCutter (d={_g(self._d)}, angle={_g(self._angle)}, L={_g(self._length)})"


class BallConeCutter(MillingCutter):
    """Tapered ball: ``BallConeCutter(diameter1, diameter2, angle)``, a ball of
    ``diameter1`` with a cone of half-angle ``angle`` (radians) tangent to it up to
    ``diameter2``."""

    def __init__(self, diameter1, diameter2, angle):
        call = "BallConeCutter(diameter1, diameter2, angle)"
        d1 = _length(call, "diameter1", diameter1)
        d2 = _length(call, "diameter2", diameter2)
        a = _angle(call, "angle", angle)
        try:
            tool = _swarf.Tool(shape="taperball", d=d2, angle=math.degrees(a), tip=d1 / 2.0)
        except ValueError as e:
            raise ValueError(f"{call}: {e}") from None
        self._d1, self._angle = d1, a
        self._setup(tool, d2, 30.0)

    def __str__(self):
        r1, r2, a = self._d1 / 2.0, self._d / 2.0, self._angle
        rc = r1 * math.cos(a)
        h1 = r1 - math.sqrt(r1 * r1 - rc * rc)
        cone_offset = -(rc / math.tan(a) - h1)
        h2 = r2 / math.tan(a) + cone_offset
        parts = [
            (f"BallCutter(d={_g(self._d1)}, r={_g(r1)}, L=1)", rc, h1, 0.0),
            (f"ConeCutter (d={_g(self._d)}, angle={_g(a)}, L={_g(r2 / math.tan(a) + 10)})", r2, h2, cone_offset),
            (f"CylCutter (d={_g(self._d)}, L=20)", r2, h2 + 20, h2),
        ]
        text = "CompositeCutter with 3 cutters:\n"
        for n, (s, r, h, z) in enumerate(parts):
            text += f" {n}:{s}\n  radius[{n}]={_g(r)}\n  height[{n}]={_g(h)}\n  zoffset[{n}]={_g(z)}\n"
        return text
