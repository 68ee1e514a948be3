"""OpenCAMLib's drop-cutter operations over swarf's :class:`~swarf.Dropper`.

A CL point's ``z`` is its floor: the drop lifts it to the height where the cutter
touches the surface when that is higher, and records the contact; otherwise it stays
with the contact ``NONE`` (OpenCAMLib's ``CLPoint::liftZ``). The drops of a run go
to swarf in one call, on ``getThreads()`` workers.

- :class:`BatchDropCutter`: the points appended, as they are.
- :class:`PathDropCutter`: each span of the path sampled as OpenCAMLib samples it
  (``n = int(length2d / sampling + 1)`` steps, the points at ``i / n``), every point
  at the floor ``getZ()``.
- :class:`AdaptivePathDropCutter`: OpenCAMLib's subdivision. A span's ends are
  dropped (their floor is the path's z, as in OpenCAMLib, where ``setZ`` has no
  effect); an interval is halved while its ends are more than ``sampling`` apart in
  XY, or while the turn at its dropped midpoint is sharper than the cosine limit
  and its ends are more than ``min_sampling`` apart. The intervals of all spans are
  halved a level at a time, each level's midpoints dropped in one call; the points
  come out in path order.
"""

import math
import os

import numpy as np

from .. import _swarf
from ._cutters import MillingCutter
from ._geometry import STLSurf
from ._path import Line, Path
from ._points import CCPoint, CCType, CLPoint

#: Most points one run may drop (each costs a few hundred bytes in Python).
MAX_POINTS = 20_000_000


def _dropper(call, surf, cutter):
    """The surface's :class:`~swarf.Dropper` for ``cutter`` (cached with the surface)."""
    return _prepared(call, surf, cutter)[0]


def _prepared(call, surf, cutter):
    """The surface's :class:`~swarf.Dropper` for ``cutter`` and its ``(M, 3, 3)``
    triangle corners."""
    _, mesh, _, cache = surf._state()
    if mesh is None:
        raise ValueError(f"{call}: the surface has no triangles (OpenCAMLib crashes on an empty surface)")
    key = ("drop", cutter._tool.spec)
    if key not in cache:
        cache[key] = _swarf.Dropper(mesh, cutter._tool)
    return cache[key], cache["tris"]


def _contact_codes(codes, tris, tri, cc):
    """swarf's feature codes with a facet contact on its triangle's border named as
    the edge (or corner) it lies on: OpenCAMLib counts only contacts strictly inside
    a facet as facet contacts."""
    facet = np.nonzero(codes == 6)[0]
    if len(facet) == 0:
        return codes
    t = tris[tri[facet]]
    r = t[:, :, :2] - cc[facet, None, :2]
    cross = lambda a, b: a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    e = np.stack([cross(r[:, (k + 1) % 3], r[:, (k + 2) % 3]) for k in range(3)], axis=1)
    total = e.sum(axis=1, keepdims=True)
    on = np.abs(e) <= 1e-12 * np.maximum(np.abs(total), 1e-300)
    codes = codes.copy()
    codes[facet[on.sum(axis=1) == 1]] = 3
    codes[facet[on.sum(axis=1) >= 2]] = 0
    return codes


class _Drops:
    """Dropped CL points as arrays: ``xyz`` ``(N, 3)``, ``cc`` ``(N, 3)``, ``types``
    ``(N,)`` (CCType numbers)."""

    def __init__(self, xyz, cc, types):
        self.xyz, self.cc, self.types = xyz, cc, types

    @staticmethod
    def run(call, surf, cutter, xyz, threads):
        """Drops ``cutter`` at the points ``xyz`` (``(N, 3)``: XY, floor z)."""
        d, tris = _prepared(call, surf, cutter)
        xyz = np.array(xyz, dtype=np.float64).reshape(-1, 3)
        if len(xyz) == 0:
            return _Drops(xyz, np.zeros((0, 3)), np.zeros(0, dtype=np.int64))
        r = d.drop(np.ascontiguousarray(xyz[:, :2]), contacts=True, threads=threads)
        lifted = (r.tri >= 0) & (r.z > xyz[:, 2])
        xyz[:, 2] = np.where(lifted, r.z, xyz[:, 2])
        cc = np.where(lifted[:, None], r.cc, 0.0)
        codes = _contact_codes(r.feature.astype(np.int64), tris, np.maximum(r.tri, 0), r.cc)
        types = np.where(lifted, cutter._cc_types(np.maximum(codes, 0), r.cc, xyz[:, :2]), 0)
        return _Drops(xyz, cc, types)

    def clpoints(self):
        """The points as a list of new :class:`CLPoint` objects."""
        out = []
        names = list(CCType)
        for (x, y, z), (cx, cy, cz), t in zip(self.xyz.tolist(), self.cc.tolist(), self.types.tolist()):
            cc = CCPoint.__new__(CCPoint)
            cc.x, cc.y, cc.z, cc.type = cx, cy, cz, names[t]
            p = CLPoint.__new__(CLPoint)
            p.x, p.y, p.z, p._cc = x, y, z, cc
            out.append(p)
        return out


def _check_xyz(call, xyz):
    """Refuses points with a non-finite x or y, or a NaN floor."""
    bad = ~np.isfinite(xyz[:, :2]).all(axis=1) | np.isnan(xyz[:, 2])
    if bad.any():
        k = int(np.argmax(bad))
        raise ValueError(f"{call}: point {k} {tuple(xyz[k].tolist())}: expected finite x, y and a z that is not NaN")


class _Operation:
    """What the operations share: surface, cutter, threads."""

    def __init__(self):
        self._surf = None
        self._cutter = None
        self._threads = os.cpu_count() or 1

    def setSTL(self, s):
        """Sets the surface (its triangles are read when the operation runs)."""
        if not isinstance(s, STLSurf):
            raise TypeError(f"{type(self).__name__}.setSTL(s): expected an STLSurf, found {type(s).__name__}")
        if s.size() == 0:
            raise ValueError(
                f"{type(self).__name__}.setSTL(s): the surface has no triangles "
                "(OpenCAMLib crashes on an empty surface)"
            )
        self._surf = s

    def setCutter(self, c):
        """Sets the cutter."""
        if not isinstance(c, MillingCutter):
            raise TypeError(f"{type(self).__name__}.setCutter(c): expected a cutter, found {type(c).__name__}")
        self._cutter = c

    def setThreads(self, n):
        """Sets the number of workers (1 to 1024)."""
        n = int(n)
        if not 1 <= n <= 1024:
            raise ValueError(f"{type(self).__name__}.setThreads(n): n = {n}: expected 1 to 1024")
        self._threads = n

    def getThreads(self):
        """The number of workers (default: one per core)."""
        return self._threads

    def _ready(self):
        name = type(self).__name__
        if self._surf is None:
            raise ValueError(f"{name}.run(): no surface (setSTL)")
        if self._cutter is None:
            raise ValueError(f"{name}.run(): no cutter (setCutter)")
        return f"{name}.run()"


class BatchDropCutter(_Operation):
    """Drops a cutter at many CL points: ``appendPoint``, ``run``, ``getCLPoints``."""

    def __init__(self):
        super().__init__()
        self._points = []
        self._drops = None
        self._bucket = 1

    def appendPoint(self, p):
        """Appends a copy of the CL point ``p`` (its z is the floor)."""
        if not isinstance(p, CLPoint):
            raise TypeError(f"BatchDropCutter.appendPoint(p): expected a CLPoint, found {type(p).__name__}")
        if not (math.isfinite(p.x) and math.isfinite(p.y)) or math.isnan(p.z):
            raise ValueError(f"BatchDropCutter.appendPoint(p): p = {p}: expected finite x, y and a z that is not NaN")
        self._points.append((p.x, p.y, p.z))
        self._drops = None

    def run(self):
        """Drops the cutter at every point appended."""
        call = self._ready()
        self._drops = _Drops.run(call, self._surf, self._cutter, self._points, self._threads)

    def getCLPoints(self):
        """The points: dropped ones after ``run``, else as appended."""
        if self._drops is None:
            xyz = np.array(self._points, dtype=np.float64).reshape(-1, 3)
            return _Drops(xyz, np.zeros_like(xyz), np.zeros(len(xyz), dtype=np.int64)).clpoints()
        return self._drops.clpoints()

    def setBucketSize(self, n):
        """Kept for OpenCAMLib's scripts: the size of its kd-tree's buckets, which
        swarf's index does not have (no effect)."""
        self._bucket = int(n)

    def getBucketSize(self):
        """The value given to :meth:`setBucketSize` (default 1)."""
        return self._bucket

    def getCalls(self):
        """Not implemented: OpenCAMLib's count of triangle drops."""
        raise NotImplementedError("swarf.ocl: BatchDropCutter.getCalls() is not implemented")

    def getTrianglesUnderCutter(self, cl, cutter):
        """Not implemented: OpenCAMLib's kd-tree query."""
        raise NotImplementedError("swarf.ocl: BatchDropCutter.getTrianglesUnderCutter() is not implemented")


class _PathOperation(_Operation):
    """A path, a floor and a sampling."""

    def __init__(self):
        super().__init__()
        self._path = None
        self._z = 0.0
        self._sampling = 0.1
        self._drops = None

    def setPath(self, p):
        """Sets the path (its spans are read when the operation runs)."""
        if not isinstance(p, Path):
            raise TypeError(f"{type(self).__name__}.setPath(p): expected a Path, found {type(p).__name__}")
        self._path = p
        self._drops = None

    def setZ(self, z):
        """Sets the floor ``z``, mm."""
        z = float(z)
        if math.isnan(z):
            raise ValueError(f"{type(self).__name__}.setZ(z): z = nan: expected a height in mm")
        self._z = z

    def getZ(self):
        """The floor, mm (default 0)."""
        return self._z

    def setSampling(self, s):
        """Sets the step along the path, mm (a positive length)."""
        self._sampling = _positive(f"{type(self).__name__}.setSampling(s)", s)

    def getSampling(self):
        """The step along the path, mm."""
        return self._sampling

    def getCLPoints(self):
        """The CL points of the last ``run``."""
        return [] if self._drops is None else self._drops.clpoints()

    def _spans(self, call):
        if self._path is None:
            raise ValueError(f"{call}: no path (setPath)")
        spans = self._path._spans
        for k, s in enumerate(spans):
            ends = (s.p1, s.p2) if isinstance(s, Line) else (s.p1, s.p2, s.c)
            if not all(math.isfinite(v) for p in ends for v in (p.x, p.y, p.z)):
                raise ValueError(f"{call}: span {k} of the path has a non-finite point")
        return spans


def _positive(call, v):
    v = float(v)
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{call}: {v!r}: expected a positive length in mm")
    return v


def _span_points(span, t):
    """The points of ``span`` at the parameters ``t`` (``(N,)``), ``(N, 3)``, by the
    span's own arithmetic."""
    if isinstance(span, Line):
        p1, p2 = span.p1, span.p2
        d = np.array([p2.x - p1.x, p2.y - p1.y, p2.z - p1.z])
        return d[None, :] * t[:, None] + np.array([p1.x, p1.y, p1.z])[None, :]
    return np.array([(q.x, q.y, q.z) for q in map(span.getPoint, t.tolist())]).reshape(-1, 3)


class PathDropCutter(_PathOperation):
    """Drops a cutter along a path at a uniform step: ``setPath``, ``setSampling``
    (default 0.1 mm), ``setZ`` (the floor, default 0), ``run``, ``getCLPoints``."""

    def run(self):
        """Samples the path and drops the cutter at every sample."""
        call = self._ready()
        spans = self._spans(call)
        counts = [int(s.length2d() / self._sampling + 1) for s in spans]
        total = sum(n + 1 for n in counts)
        if total > MAX_POINTS:
            raise ValueError(
                f"PathDropCutter.setSampling: {self._sampling} mm makes {total} points on this "
                f"path, more than {MAX_POINTS}: expected a coarser sampling"
            )
        parts = [_span_points(s, np.arange(n + 1, dtype=np.float64) / n) for s, n in zip(spans, counts)]
        xyz = np.concatenate(parts) if parts else np.zeros((0, 3))
        xyz[:, 2] = self._z
        self._drops = _Drops.run(call, self._surf, self._cutter, xyz, self._threads)


class AdaptivePathDropCutter(_PathOperation):
    """Drops a cutter along a path, subdividing where the path turns: ``setSampling``
    (the largest step, default 0.1 mm), ``setMinSampling`` (the smallest, default
    0.01 mm), ``setCosLimit`` (default 0.999), ``run``, ``getCLPoints``."""

    def __init__(self):
        super().__init__()
        self._min_sampling = 0.01
        self._cos_limit = 0.999

    def setMinSampling(self, s):
        """Sets the smallest step, mm (a positive length)."""
        self._min_sampling = _positive("AdaptivePathDropCutter.setMinSampling(s)", s)

    def setCosLimit(self, c):
        """Sets the cosine of the largest turn at a sample left unrefined."""
        c = float(c)
        if math.isnan(c):
            raise ValueError("AdaptivePathDropCutter.setCosLimit(c): c = nan: expected a number")
        self._cos_limit = c

    def run(self):
        """Samples and drops the path adaptively (module doc)."""
        call = self._ready()
        spans = self._spans(call)
        step = min(self._sampling, self._min_sampling)
        bound = sum(2 * int(s.length2d() / step + 2) for s in spans)
        if bound > MAX_POINTS:
            raise ValueError(
                f"AdaptivePathDropCutter.setMinSampling: {step} mm may make {bound} points on "
                f"this path, more than {MAX_POINTS}: expected a coarser sampling"
            )
        self._drops = self._subdivide(call, spans)

    def _drop(self, call, xyz):
        return _Drops.run(call, self._surf, self._cutter, xyz, self._threads)

    def _subdivide(self, call, spans):
        n = len(spans)
        ends = np.concatenate([_span_points(s, np.array([0.0, 1.0])) for s in spans]) if n else np.zeros((0, 3))
        e = self._drop(call, ends)
        idx = np.arange(n)
        # Pending intervals: span, t0, t1 and the rows of their dropped ends in `pool`.
        pool = [e]
        all_xyz = e.xyz
        lo, hi = 2 * idx, 2 * idx + 1
        span, t0, t1 = idx, np.zeros(n), np.ones(n)
        keys = [(idx, np.full(n, -1.0), lo)]
        base = 2 * n
        while len(span):
            mid_t = t0 + (t1 - t0) / 2.0
            mids = np.concatenate([_span_points(spans[s], mid_t[span == s]) for s in np.unique(span)])
            order = np.argsort(span, kind="stable")
            m = np.empty_like(mids)
            m[order] = mids
            md = self._drop(call, m)
            pool.append(md)
            all_xyz = np.concatenate([all_xyz, md.xyz])
            a, b, c = all_xyz[lo], md.xyz, all_xyz[hi]
            fw = np.sqrt((c[:, 0] - a[:, 0]) ** 2 + (c[:, 1] - a[:, 1]) ** 2)
            split = (fw > self._sampling) | (~self._flat(a, b, c) & (fw > self._min_sampling))
            # An interval too short to halve in double precision (an arc whose end
            # is off its circle never closes up; OpenCAMLib's recursion overflows
            # the stack there) ends where it is.
            split &= (t0 < mid_t) & (mid_t < t1)
            keys.append((span[~split], t1[~split], hi[~split]))
            mid_rows = base + np.arange(len(span))
            base += len(span)
            s = split
            span = np.concatenate([span[s], span[s]])
            t0, t1 = np.concatenate([t0[s], mid_t[s]]), np.concatenate([mid_t[s], t1[s]])
            lo, hi = np.concatenate([lo[s], mid_rows[s]]), np.concatenate([mid_rows[s], hi[s]])
        drops = _Drops(*(np.concatenate([getattr(d, f) for d in pool]) for f in ("xyz", "cc", "types")))
        ks, kt, rows = (np.concatenate(k) for k in zip(*keys))
        pick = rows[np.lexsort((kt, ks))]
        return _Drops(drops.xyz[pick], drops.cc[pick], drops.types[pick])

    def _flat(self, a, b, c):
        """True where the turn ``a -> b -> c`` has a cosine above the limit (each
        leg normalised as ``Point.normalize`` does)."""

        def unit(v):
            n = np.sqrt(v[:, 0] * v[:, 0] + v[:, 1] * v[:, 1] + v[:, 2] * v[:, 2])
            k = np.where(n != 0.0, 1 / np.where(n != 0.0, n, 1.0), 1.0)
            return v * k[:, None]

        v1, v2 = unit(b - a), unit(c - b)
        return v1[:, 0] * v2[:, 0] + v1[:, 1] * v2[:, 1] + v1[:, 2] * v2[:, 2] > self._cos_limit
