"""An exact drop-cutter by brute force, sharing nothing with swarf's or OpenCAMLib's:
the tip height of a cutter dropped onto a triangle is the maximum of
``q.z - h(|q.xy - p|)`` over the triangle's points ``q`` within the cutter's radius
``R`` of the axis at ``p`` (``h``: the height of the cutter's lower surface above its
tip at radius ``rho``). That function is concave on the convex set it is maximised
over, so searching grids in barycentric coordinates, each zoomed about the best
point of the last, converges to the maximum: 16 grids of 32 x 32, each 4 of its
predecessor's steps across, pin it to well below 1e-9 mm.
"""

import math

import numpy as np


def profile(shape, radius, corner=0.0, half_angle=0.0):
    """``h(rho)`` of a flat, ball, bull (corner radius ``corner``) or cone (half-angle
    ``half_angle``, radians) cutter of radius ``radius``, mm."""
    if shape == "flat":
        return lambda rho: np.zeros_like(rho)
    if shape == "ball":
        return lambda rho: radius - np.sqrt(np.maximum(radius * radius - rho * rho, 0.0))
    if shape == "bull":
        a = radius - corner
        return lambda rho: np.where(rho <= a, 0.0, corner - np.sqrt(np.maximum(corner**2 - (rho - a) ** 2, 0.0)))
    if shape == "cone":
        return lambda rho: rho / math.tan(half_angle)
    raise ValueError(shape)


def triangle_drop(h, radius, p, tri, grids=16, n=32):
    """The exact drop onto one triangle (``(3, 3)`` corners) at ``p``, or None when
    no point of it is within reach."""
    p0, p1, p2 = np.asarray(tri, dtype=np.float64)
    best, centre, half = -np.inf, (1 / 3, 1 / 3), 1.0
    for k in range(grids):
        u, v = np.meshgrid(np.linspace(centre[0] - half, centre[0] + half, n), np.linspace(centre[1] - half, centre[1] + half, n))
        u, v = np.clip(u.ravel(), 0, 1), np.clip(v.ravel(), 0, 1)
        s = u + v
        over = s > 1
        u[over], v[over] = u[over] / s[over], v[over] / s[over]
        q = p0 + u[:, None] * (p1 - p0) + v[:, None] * (p2 - p0)
        rho = np.hypot(q[:, 0] - p[0], q[:, 1] - p[1])
        f = np.where(rho <= radius, q[:, 2] - h(np.minimum(rho, radius)), -np.inf)
        i = int(np.argmax(f))
        if f[i] == -np.inf:
            if k == 0:
                return None
            break
        if f[i] > best:
            best, centre = f[i], (u[i], v[i])
        half *= 8.0 / n
    return best


def mesh_drop(h, radius, p, tris):
    """The exact drop onto the triangles ``tris`` (``(M, 3, 3)``) at ``p``: the
    highest triangle drop, None off the mesh."""
    tris = np.asarray(tris, dtype=np.float64)
    lo, hi = tris[:, :, :2].min(axis=1), tris[:, :, :2].max(axis=1)
    near = np.all((lo <= np.asarray(p) + radius) & (hi >= np.asarray(p) - radius), axis=1)
    drops = [d for d in (triangle_drop(h, radius, p, t) for t in tris[near]) if d is not None]
    return max(drops) if drops else None
