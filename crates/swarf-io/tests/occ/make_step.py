#!/usr/bin/env python3
"""Reference STEP files for swarf's STEP reader, written by OpenCASCADE (cadquery-ocp).

Usage: make_step.py OUT_DIR [WAVE_TOML] [--bench N]

For each case NAME writes OUT_DIR/NAME.step (STEPControl_Writer, AP214) and
OUT_DIR/NAME.csv with one row per sample point inside a face:
    face,kind,u,v,x,y,z
where (u, v) are OCC's face parameters and (x, y, z) OCC's own evaluation of the face's
surface there (BRepAdaptor_Surface, which applies the face's location), in mm.
Cases: bspline, rational, periodic (unclamped knots in the file), extrusion, plate_hole, fillet, cylinder, cone (with its apex),
sphere (part, with a pole), torus, wave;
plate_inch (AP203, inches) and fillet_ap242 (AP242) (from WAVE_TOML).
With --bench N, writes only bench.step: N copies of the filleted, drilled plate.
"""

import math
import sys

from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_Transform
from OCP.BRepClass import BRepClass_FaceClassifier
from OCP.BRepFilletAPI import BRepFilletAPI_MakeFillet
from OCP.BRepPrimAPI import (
    BRepPrimAPI_MakeBox,
    BRepPrimAPI_MakeCone,
    BRepPrimAPI_MakeSphere,
    BRepPrimAPI_MakeCylinder,
    BRepPrimAPI_MakeTorus,
)
from OCP.BRepTools import BRepTools
from OCP.BRep import BRep_Builder
from OCP.Geom import Geom_BSplineSurface
from OCP.GeomAbs import GeomAbs_SurfaceType
from OCP.IFSelect import IFSelect_RetDone
from OCP.Interface import Interface_Static
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer
from OCP.OCP.collections import Array1_double, Array1_int, Array2_double, Array2_gp_Pnt
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_IN
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Compound
from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt, gp_Pnt2d, gp_Trsf, gp_Vec

KINDS = {
    GeomAbs_SurfaceType.GeomAbs_Plane: "plane",
    GeomAbs_SurfaceType.GeomAbs_Cylinder: "cylinder",
    GeomAbs_SurfaceType.GeomAbs_Cone: "cone",
    GeomAbs_SurfaceType.GeomAbs_Sphere: "sphere",
    GeomAbs_SurfaceType.GeomAbs_Torus: "torus",
    GeomAbs_SurfaceType.GeomAbs_BSplineSurface: "bspline",
    GeomAbs_SurfaceType.GeomAbs_BezierSurface: "bezier",
    GeomAbs_SurfaceType.GeomAbs_SurfaceOfExtrusion: "extrusion",
}


def bspline_face(poles, knots_u, knots_v, deg, weights=None):
    """A face on the whole of a clamped B-spline surface; knots with repeats listed."""
    nu, nv = len(poles), len(poles[0])
    arr = Array2_gp_Pnt(1, nu, 1, nv)
    for i in range(nu):
        for j in range(nv):
            arr.SetValue(i + 1, j + 1, gp_Pnt(*poles[i][j]))

    def flat(ks):
        uniq, mult = [], []
        for k in ks:
            if uniq and k == uniq[-1]:
                mult[-1] += 1
            else:
                uniq.append(k)
                mult.append(1)
        a = Array1_double(1, len(uniq))
        m = Array1_int(1, len(uniq))
        for i, (k, c) in enumerate(zip(uniq, mult)):
            a.SetValue(i + 1, k)
            m.SetValue(i + 1, c)
        return a, m

    ku, mu = flat(knots_u)
    kv, mv = flat(knots_v)
    if weights is None:
        s = Geom_BSplineSurface(arr, ku, kv, mu, mv, deg[0], deg[1])
    else:
        w = Array2_double(1, nu, 1, nv)
        for i in range(nu):
            for j in range(nv):
                w.SetValue(i + 1, j + 1, weights[i][j])
        s = Geom_BSplineSurface(arr, w, ku, kv, mu, mv, deg[0], deg[1])
    return BRepBuilderAPI_MakeFace(s, 1e-9).Face()


def bspline_case(rational):
    poles = [
        [(10.0 * i, 12.0 * j, 3.0 * math.sin(i + 0.7 * j)) for j in range(4)]
        for i in range(5)
    ]
    ku = [0.0] * 4 + [0.4] + [1.0] * 4
    kv = [0.0] * 3 + [0.5] + [1.0] * 3
    w = [[1.0 + 0.3 * ((i + 2 * j) % 3) for j in range(4)] for i in range(5)] if rational else None
    return bspline_face(poles, ku, kv, (3, 2), w)


def periodic_case():
    """A B-spline surface periodic in u (OCC writes it with unclamped knots)."""
    nu, nv = 6, 3
    arr = Array2_gp_Pnt(1, nu, 1, nv)
    for i in range(nu):
        for j in range(nv):
            a = 2 * math.pi * i / nu
            r = 10 + 2 * math.sin(3 * a) + j
            arr.SetValue(i + 1, j + 1, gp_Pnt(r * math.cos(a), r * math.sin(a), 8.0 * j))
    ku, mu = Array1_double(1, 7), Array1_int(1, 7)
    for i in range(7):
        ku.SetValue(i + 1, float(i))
        mu.SetValue(i + 1, 1)
    kv, mv = Array1_double(1, 2), Array1_int(1, 2)
    kv.SetValue(1, 0.0)
    kv.SetValue(2, 1.0)
    mv.SetValue(1, 3)
    mv.SetValue(2, 3)
    s = Geom_BSplineSurface(arr, ku, kv, mu, mv, 3, 2, True, False)
    return BRepBuilderAPI_MakeFace(s, 1e-9).Face()


def extrusion_case():
    """A B-spline curve swept along a vector (SURFACE_OF_LINEAR_EXTRUSION)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
    from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
    from OCP.Geom import Geom_BSplineCurve
    from OCP.OCP.collections import Array1_gp_Pnt

    poles = [(0, 0, 0), (5, 8, 1), (12, -3, 0), (18, 4, 2), (25, 0, 0)]
    arr = Array1_gp_Pnt(1, len(poles))
    for i, p in enumerate(poles):
        arr.SetValue(i + 1, gp_Pnt(*p))
    k, m = Array1_double(1, 3), Array1_int(1, 3)
    for i, (kk, mm) in enumerate([(0.0, 4), (0.5, 1), (1.0, 4)]):
        k.SetValue(i + 1, kk)
        m.SetValue(i + 1, mm)
    edge = BRepBuilderAPI_MakeEdge(Geom_BSplineCurve(arr, k, m, 3)).Edge()
    return BRepPrimAPI_MakePrism(edge, gp_Vec(1.0, 2.0, 10.0)).Shape()


def plate_hole():
    box = BRepPrimAPI_MakeBox(40.0, 30.0, 5.0).Shape()
    cyl = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(15.0, 14.0, -1.0), gp_Dir(0, 0, 1)), 6.0, 7.0).Shape()
    return BRepAlgoAPI_Cut(box, cyl).Shape()


def fillet():
    box = BRepPrimAPI_MakeBox(20.0, 16.0, 10.0).Shape()
    mk = BRepFilletAPI_MakeFillet(box)
    ex = TopExp_Explorer(box, TopAbs_EDGE)
    mk.Add(3.0, TopoDS.Edge(ex.Current()))
    return mk.Shape()


def wave(path):
    import tomllib

    with open(path, "rb") as f:
        part = tomllib.load(f)
    p = part["patch"][0]
    du, dv = p["degree"]
    ku = p.get("knots_u") or [0.0] * (du + 1) + [1.0] * (du + 1)
    kv = p.get("knots_v") or [0.0] * (dv + 1) + [1.0] * (dv + 1)
    nu, nv = len(ku) - du - 1, len(kv) - dv - 1
    pts = p["points"]
    poles = [[tuple(float(c) for c in pts[i * nv + j]) for j in range(nv)] for i in range(nu)]
    w = p.get("weights")
    weights = [[w[i * nv + j] for j in range(nv)] for i in range(nu)] if w else None
    return bspline_face(poles, [float(k) for k in ku], [float(k) for k in kv], (du, dv), weights)


def write_step(shape, path, schema="AP214", unit="MM"):
    Interface_Static.SetCVal_s("write.step.schema", schema)
    Interface_Static.SetCVal_s("write.step.unit", unit)
    w = STEPControl_Writer()
    w.Transfer(shape, STEPControl_AsIs)
    if w.Write(path) != IFSelect_RetDone:
        raise SystemExit(f"cannot write {path}")


def write_csv(shape, path, n=9):
    rows = []
    ex = TopExp_Explorer(shape, TopAbs_FACE)
    k = 0
    while ex.More():
        face = TopoDS.Face(ex.Current())
        ad = BRepAdaptor_Surface(face)
        kind = KINDS.get(ad.GetType(), "other")
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        for i in range(n):
            for j in range(n):
                u = u0 + (u1 - u0) * (i + 0.5) / n
                v = v0 + (v1 - v0) * (j + 0.5) / n
                c = BRepClass_FaceClassifier(face, gp_Pnt2d(u, v), 1e-7)
                if c.State() != TopAbs_IN:
                    continue
                p = ad.Value(u, v)
                rows.append(f"{k},{kind},{u!r},{v!r},{p.X()!r},{p.Y()!r},{p.Z()!r}")
        k += 1
        ex.Next()
    with open(path, "w") as f:
        f.write("face,kind,u,v,x,y,z\n")
        f.write("\n".join(rows) + "\n")


def bench(n):
    base = plate_hole()
    mk = BRepFilletAPI_MakeFillet(base)
    ex = TopExp_Explorer(base, TopAbs_EDGE)
    mk.Add(2.0, TopoDS.Edge(ex.Current()))
    base = mk.Shape()
    comp = TopoDS_Compound()
    b = BRep_Builder()
    b.MakeCompound(comp)
    side = math.ceil(math.sqrt(n))
    for k in range(n):
        t = gp_Trsf()
        t.SetTranslation(gp_Vec(50.0 * (k % side), 40.0 * (k // side), 0.0))
        b.Add(comp, BRepBuilderAPI_Transform(base, t, True).Shape())
    return comp


def main():
    args = sys.argv[1:]
    out = args[0]
    if "--bench" in args:
        n = int(args[args.index("--bench") + 1])
        write_step(bench(n), f"{out}/bench.step")
        return
    cases = {
        "bspline": bspline_case(False),
        "rational": bspline_case(True),
        "periodic": periodic_case(),
        "extrusion": extrusion_case(),
        "plate_hole": plate_hole(),
        "fillet": fillet(),
        "cylinder": BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(1, 2, 3), gp_Dir(0.3, 0.4, 1.0)), 4.0, 9.0).Shape(),
        "cone": BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(3, 0, 1), gp_Dir(1, 0, 1)), 5.0, 0.0, 8.0).Shape(),
        "sphere": BRepPrimAPI_MakeSphere(gp_Pnt(1, 1, 1), 6.0, -0.4, math.pi / 2, 4.0).Shape(),
        "torus": BRepPrimAPI_MakeTorus(gp_Ax2(gp_Pnt(-2, 1, 0), gp_Dir(0, 1, 1)), 10.0, 3.0).Shape(),
    }
    if len(args) > 1:
        cases["wave"] = wave(args[1])
    for name, shape in cases.items():
        write_step(shape, f"{out}/{name}.step")
        write_csv(shape, f"{out}/{name}.csv")
    # The same shapes in inches (AP203) and as AP242: OCC's points stay in mm.
    write_step(cases["plate_hole"], f"{out}/plate_inch.step", "AP203", "INCH")
    write_csv(cases["plate_hole"], f"{out}/plate_inch.csv")
    write_step(cases["fillet"], f"{out}/fillet_ap242.step", "AP242DIS")
    write_csv(cases["fillet"], f"{out}/fillet_ap242.csv")


if __name__ == "__main__":
    main()
