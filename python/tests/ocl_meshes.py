"""Meshes the OpenCAMLib comparisons generate, as ``(M, 3, 3)`` float64 arrays of
triangle corners (counter-clockwise seen from above), and the ways to hand them to
either library.

- ``mold``: a height field with a pocket, a boss in it and a gentle wave outside,
  the shape of a mold cavity (40 x 30 mm);
- ``die``: swarf's built-in die, tessellated;
- ``vgroove``: an open V-groove, two planes at 30 degrees meeting along X (the mesh
  ends at its borders: a cutter there falls off its edges);
- ``hole``: a flat plate with a square hole through it (no walls: a small cutter
  falls through, a large one bridges it);
- ``write_step``: a STEP solid for FreeCAD's CAM jobs.

``distance_to`` measures points against waterline loops.
"""

import struct

import numpy as np


def grid_surface(xs, ys, f):
    """The triangles of ``z = f(x, y)`` over the grid ``xs`` x ``ys`` (two per cell)."""
    X, Y = np.meshgrid(xs, ys)
    Z = f(X, Y)
    P = np.stack([X, Y, Z], axis=-1)
    a, b, c, d = P[:-1, :-1], P[:-1, 1:], P[1:, 1:], P[1:, :-1]
    t1 = np.stack([a, b, c], axis=-2).reshape(-1, 3, 3)
    t2 = np.stack([a, c, d], axis=-2).reshape(-1, 3, 3)
    return np.concatenate([t1, t2])


def mold_height(x, y):
    """The mold's height: 10 mm, a pocket 6 mm deep with a boss, a wave outside."""
    r = np.hypot((x - 20) / 12, (y - 15) / 8)
    pocket = 6 * np.clip(1.6 - 1.6 * r, 0, 1) ** 0.7
    boss = 3.5 * np.exp(-((x - 22) ** 2 + (y - 14) ** 2) / 4)
    return 10 + 0.6 * np.sin(x / 3) * np.cos(y / 4) - pocket + boss


def mold(step=1.0):
    """The mold height field, 40 x 30 mm, ``step`` mm cells."""
    return grid_surface(np.arange(0, 40 + 1e-9, step), np.arange(0, 30 + 1e-9, step), mold_height)


def die(tol=0.05):
    """swarf's built-in die tessellated within ``tol`` mm."""
    import swarf  # the built module; the other meshes need only numpy

    m = swarf.Part.load("builtin:die").tessellate(tol)
    return m.vertices[m.faces]


def vgroove():
    """An open V-groove along X: ``z = 10 + |y| tan(30 deg)`` for |y| <= 8, x in [0, 25]."""
    k = np.tan(np.radians(30))
    return grid_surface(np.linspace(0, 25, 6), np.linspace(-8, 8, 5), lambda x, y: 10 + np.abs(y) * k)


def hole():
    """A plate at z = 5 over [0, 30]^2 with the square hole [11, 19]^2 through it."""
    xs = np.array([0.0, 11.0, 19.0, 30.0])
    tris = grid_surface(xs, xs, lambda x, y: 5 + 0 * x)
    centre = tris[:, :, :2].mean(axis=1)
    inside = (np.abs(centre - 15) < 4).all(axis=1)
    return tris[~inside]


MESHES = {"mold": mold, "die": die, "vgroove": vgroove, "hole": hole}


def write_binary_stl(path, tris, header=b"swarf test mesh"):
    """Writes ``tris`` as a binary STL (normals zero) with the given 80-byte header."""
    with open(path, "wb") as f:
        f.write(header.ljust(80, b" ")[:80])
        f.write(struct.pack("<I", len(tris)))
        for t in np.asarray(tris, dtype=np.float32):
            f.write(struct.pack("<3f", 0, 0, 0))
            f.write(t.tobytes())
            f.write(b"\0\0")


def write_ascii_stl(path, tris):
    """Writes ``tris`` as an ASCII STL, nine significant digits."""
    with open(path, "w") as f:
        f.write("solid test\n")
        for t in tris:
            f.write("facet normal 0 0 0\nouter loop\n")
            for p in t:
                f.write("vertex %.9g %.9g %.9g\n" % tuple(p))
            f.write("endloop\nendfacet\n")
        f.write("endsolid test\n")


def surface(lib, tris):
    """An ``STLSurf`` of ``lib`` (``opencamlib.ocl`` or ``swarf.ocl``) holding ``tris``."""
    s = lib.STLSurf()
    for a, b, c in np.asarray(tris, dtype=np.float64).tolist():
        s.addTriangle(lib.Triangle(lib.Point(*a), lib.Point(*b), lib.Point(*c)))
    return s


def write_step(path):
    """Writes a STEP solid with OpenCASCADE (OCP): a 50 x 40 x 4 mm plate with a
    dome 7 mm high, a round boss 10 mm high and a square pocket 2 mm deep, so that
    waterlines at levels between 4 and 10 mm loop around the dome and the boss."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Common, BRepAlgoAPI_Cut, BRepAlgoAPI_Fuse
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCylinder, BRepPrimAPI_MakeSphere
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer

    plate = BRepPrimAPI_MakeBox(50.0, 40.0, 4.0).Shape()
    ball = BRepPrimAPI_MakeSphere(gp_Pnt(18, 20, -3), 10.0).Shape()
    dome = BRepAlgoAPI_Common(ball, BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 50.0, 40.0, 20.0).Shape()).Shape()
    boss = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(38, 20, 0), gp_Dir(0, 0, 1)), 4.0, 10.0).Shape()
    pocket = BRepPrimAPI_MakeBox(gp_Pnt(36, 4, 2), 10.0, 8.0, 3.0).Shape()
    solid = BRepAlgoAPI_Cut(BRepAlgoAPI_Fuse(BRepAlgoAPI_Fuse(plate, dome).Shape(), boss).Shape(), pocket).Shape()
    writer = STEPControl_Writer()
    writer.Transfer(solid, STEPControl_AsIs)
    if writer.Write(str(path)) != IFSelect_RetDone:
        raise OSError(f"{path}: OpenCASCADE could not write the STEP file")


def distance_to(points, loops):
    """Each point's distance to the closed polylines ``loops`` and the nearest point
    on them."""
    best = np.full(len(points), np.inf)
    near = np.zeros_like(points)
    for lp in loops:
        a, d = lp, np.roll(lp, -1, axis=0) - lp
        l2 = np.where((d * d).sum(1) > 0, (d * d).sum(1), 1.0)
        for k in range(0, len(points), 500):
            q = points[k:k + 500, None, :] - a[None]
            t = np.clip((q * d[None]).sum(2) / l2[None], 0, 1)
            foot = a[None] + t[..., None] * d[None]
            dist = np.hypot(*(points[k:k + 500, None, :] - foot).transpose(2, 0, 1))
            j = dist.argmin(axis=1)
            dj = dist[np.arange(len(j)), j]
            better = dj < best[k:k + 500]
            best[k:k + 500] = np.where(better, dj, best[k:k + 500])
            near[k:k + 500][better] = foot[np.arange(len(j)), j][better]
    return best, near
