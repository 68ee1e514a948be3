"""OpenCAMLib's Python API on swarf: ``import swarf.ocl as ocl`` in place of
``import ocl`` or ``from opencamlib import ocl``.

The part of OpenCAMLib 2023.1's API that FreeCAD's CAM workbench (3D Surface,
Waterline) and typical scripts use, with its names, argument orders, defaults and
return types, over swarf's own drop-cutter and waterline (no second drop-cutter):

- geometry: :class:`Point`, :class:`CLPoint` (``getCC()``), :class:`CCPoint`,
  :class:`CCType`, :class:`Triangle`, :class:`STLSurf` (``addTriangle``, ``size``,
  ``getBounds``, ``rotate``), :class:`STLReader`, :class:`Bbox`, :class:`Line`,
  :class:`Arc`, :class:`Path`;
- cutters: :class:`CylCutter`, :class:`BallCutter`, :class:`BullCutter`,
  :class:`ConeCutter`, :class:`BallConeCutter` (drops onto a triangle, sizes,
  ``offsetCutter``);
- drop-cutter: :class:`BatchDropCutter`, :class:`PathDropCutter`,
  :class:`AdaptivePathDropCutter` (``setSampling``, ``setMinSampling``,
  ``setCosLimit``);
- waterline: :class:`Waterline`, :class:`AdaptiveWaterline` (``setZ``,
  ``setSampling``, ``getLoops``);
- ``setThreads`` on every operation, :func:`version`, :func:`max_threads`.

Differences from OpenCAMLib, on purpose:

- heights are swarf's exact drops (OpenCAMLib's are off by up to a few 1e-8 mm on
  near-flat facets); contact types are OpenCAMLib's names for the feature touched
  (vertex, edge, facet; a cone's tip or rim), which can differ from OpenCAMLib's at
  ties between features;
- waterline loops are exact contour points joined by chords within a tolerance
  (:mod:`swarf.ocl._waterline`), not fiber crossings; the cutter is its cutting
  surface extended upward at every level (OpenCAMLib's waterline ignores triangles
  above the level plus the cutter's length);
- :class:`STLReader` reads every binary STL (OpenCAMLib reads one whose header
  begins with ``solid`` as an empty ASCII file) and raises for a file it cannot
  read;
- what OpenCAMLib crashes or hangs on raises a Python exception naming the call and
  the argument: an empty surface, no surface, cutter or path at ``run``, a cutter
  outside its shape's domain (a diameter or length that is not positive, a corner
  radius of half the diameter or more, an angle outside (0, pi/2)), a triangle or
  point with a NaN or infinite coordinate, a sampling that is not positive;
- a surface's triangles are read when an operation runs, not when ``setSTL`` is
  called.

Everything else of OpenCAMLib's API raises ``NotImplementedError`` naming the call
(push-cutter, fibers, weaves, ``LineCLFilter``, ``ZigZag``, the composite cutters
swarf has no profile for), never a wrong answer.

``python3 -m swarf.ocl shim`` prints a folder holding an ``ocl`` module that is this
one: with it on ``PYTHONPATH``, FreeCAD's ``import ocl`` gets swarf
(``docs/opencamlib.md``).
"""

import os

import numpy as np

from .. import __version__ as _swarf_version
from ._cutters import BallConeCutter, BallCutter, BullCutter, ConeCutter, CylCutter, MillingCutter
from ._dropcutter import AdaptivePathDropCutter, BatchDropCutter, PathDropCutter
from ._geometry import Bbox, STLReader, STLSurf, Triangle
from ._path import Arc, ArcSpanType, Line, LineSpanType, Path, SpanType
from ._points import CCPoint, CCType, CLPoint, Point
from ._waterline import AdaptiveWaterline, Waterline

#: The OpenCAMLib release whose API this module follows.
OPENCAMLIB_VERSION = "2023.01.11"


def version():
    """The OpenCAMLib version whose API this is and swarf's: ``"2023.01.11 (swarf
    0.1.0)"``."""
    return f"{OPENCAMLIB_VERSION} (swarf {_swarf_version})"


def max_threads():
    """The number of cores (the default of every operation's ``setThreads``)."""
    return os.cpu_count() or 1


def eps():
    """Machine epsilon of double precision."""
    r = 1.0
    while 1.0 < 1.0 + r:
        r /= 2.0
    return r


def _unimplemented(name, what):
    def init(self, *args, **kwargs):
        raise NotImplementedError(f"swarf.ocl: {name}() is not implemented ({what})")

    return type(name, (), {"__init__": init, "__doc__": f"Not implemented: {what}."})


BatchPushCutter = _unimplemented("BatchPushCutter", "push-cutter; swarf's waterline finds contours by drops")
Fiber = _unimplemented("Fiber", "push-cutter fibers")
Interval = _unimplemented("Interval", "push-cutter intervals")
LineCLFilter = _unimplemented("LineCLFilter", "OpenCAMLib's CL point filter")
ZigZag = _unimplemented("ZigZag", "OpenCAMLib's zig-zag generator")
CutterLocationSurface = _unimplemented("CutterLocationSurface", "OpenCAMLib's CL surface")
Ellipse = _unimplemented("Ellipse", "OpenCAMLib's torus edge-drop internals")
EllipsePosition = _unimplemented("EllipsePosition", "OpenCAMLib's torus edge-drop internals")
CompCylCutter = _unimplemented("CompCylCutter", "composite cutter; CylCutter is the same shape")
CompBallCutter = _unimplemented("CompBallCutter", "composite cutter; BallCutter is the same shape")
CylConeCutter = _unimplemented("CylConeCutter", "composite cutter without a swarf profile")
BullConeCutter = _unimplemented("BullConeCutter", "composite cutter without a swarf profile")
ConeConeCutter = _unimplemented("ConeConeCutter", "composite cutter without a swarf profile")


def epsD(x):
    """The largest power of two, from 1000 down, whose sum with ``x`` rounds to
    ``x`` in double precision."""
    x, r = float(x), 1000.0
    while x < x + r:
        r /= 2.0
    return r


def epsF(x):
    """:func:`epsD` in single precision."""
    x, r, two = np.float32(x), np.float32(1000.0), np.float32(2.0)
    while x < x + r:
        r = r / two
    return float(r)


__all__ = [
    "AdaptivePathDropCutter",
    "AdaptiveWaterline",
    "Arc",
    "ArcSpanType",
    "BallConeCutter",
    "BallCutter",
    "BatchDropCutter",
    "BatchPushCutter",
    "Bbox",
    "BullConeCutter",
    "BullCutter",
    "CCPoint",
    "CCType",
    "CLPoint",
    "CompBallCutter",
    "CompCylCutter",
    "ConeConeCutter",
    "ConeCutter",
    "CutterLocationSurface",
    "CylConeCutter",
    "CylCutter",
    "Ellipse",
    "EllipsePosition",
    "Fiber",
    "Interval",
    "Line",
    "LineCLFilter",
    "LineSpanType",
    "MillingCutter",
    "OPENCAMLIB_VERSION",
    "Path",
    "PathDropCutter",
    "Point",
    "STLReader",
    "STLSurf",
    "SpanType",
    "Triangle",
    "Waterline",
    "ZigZag",
    "eps",
    "epsD",
    "epsF",
    "max_threads",
    "version",
]
