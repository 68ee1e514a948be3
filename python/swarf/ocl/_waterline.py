"""OpenCAMLib's waterlines over swarf's (:class:`swarf._swarf.OclWaterline`).

OpenCAMLib pushes the cutter along X and Y fibers ``sampling`` apart at the level
and weaves the interval ends into loops. swarf drops the cutter on a grid of
``sampling`` mm once and, at each level, follows the contour ``drop(x, y) = z``
through it: every loop point is an exact contour point (root finding on the drop
height), and points are added until every chord is within a tolerance of the
contour: ``sampling / 100`` for :class:`Waterline`, ``min_sampling / 10`` for
:class:`AdaptiveWaterline`. Loops smaller than the grid can be missed, as between
OpenCAMLib's fibers. Loops keep the material on their left (counter-clockwise
around an island, clockwise inside a pocket), the first point not repeated, as
OpenCAMLib's. The grid is cached with the surface, so running level after level
(``reset``, ``setZ``, ``run``) costs each level its contour only.
"""

import math

from .. import _swarf
from ._dropcutter import _Operation, _positive
from ._points import Point


class Waterline(_Operation):
    """Loops at one height: ``setSTL``, ``setCutter``, ``setZ``, ``setSampling``,
    ``run``, ``getLoops``, ``reset``."""

    def __init__(self):
        super().__init__()
        self._z = 0.0
        self._sampling = None
        self._loops = []

    def setZ(self, z):
        """Sets the level (the tool tip's height), mm."""
        z = float(z)
        if not math.isfinite(z):
            raise ValueError(f"{type(self).__name__}.setZ(z): z = {z}: expected a finite height in mm")
        self._z = z

    def setSampling(self, s):
        """Sets the grid step, mm: details smaller than it can be missed."""
        self._sampling = _positive(f"{type(self).__name__}.setSampling(s)", s)

    def _tolerance(self):
        return self._sampling / 100.0

    def run(self):
        """Finds the loops at the level."""
        call = self._ready()
        if self._sampling is None:
            raise ValueError(f"{call}: no sampling (setSampling)")
        tol = self._tolerance()
        _, mesh, _, cache = self._surf._state()
        key = ("waterline", self._cutter._tool.spec, self._sampling, tol)
        if key not in cache:
            try:
                cache[key] = _swarf.OclWaterline(mesh, self._cutter._tool, self._sampling, tol, self._threads)
            except ValueError as e:
                raise ValueError(f"{type(self).__name__}.setSampling: {e}") from None
        z = self._z
        self._loops = [[Point(x, y, z) for x, y in lp.tolist()] for lp in cache[key].loops(z)]

    run2 = run

    def reset(self):
        """Forgets the loops."""
        self._loops = []

    def getLoops(self):
        """The loops of the last ``run``: a list of lists of :class:`Point`."""
        return [[Point(p) for p in lp] for lp in self._loops]

    def getXFibers(self):
        """Not implemented: swarf's waterline has no fibers."""
        raise NotImplementedError(f"swarf.ocl: {type(self).__name__}.getXFibers() is not implemented")

    def getYFibers(self):
        """Not implemented: swarf's waterline has no fibers."""
        raise NotImplementedError(f"swarf.ocl: {type(self).__name__}.getYFibers() is not implemented")


class AdaptiveWaterline(Waterline):
    """:class:`Waterline` with a finer tolerance: ``setSampling`` (the grid step,
    default 1 mm, OpenCAMLib's) and ``setMinSampling`` (default 0.1 mm; chords are
    kept within a tenth of it)."""

    def __init__(self):
        super().__init__()
        self._sampling = 1.0
        self._min_sampling = 0.1

    def setMinSampling(self, s):
        """Sets the smallest step, mm: chords stay within a tenth of it."""
        self._min_sampling = _positive("AdaptiveWaterline.setMinSampling(s)", s)

    def _tolerance(self):
        return self._min_sampling / 10.0
