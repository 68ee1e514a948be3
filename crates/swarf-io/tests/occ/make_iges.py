"""Writes IGES reference files with OpenCASCADE (OCP) for swarf-io's IGES test.

Usage: python3 make_iges.py OUT_DIR

Writes OUT_DIR/occ.igs (mm) from four faces: a rational B-spline face (untrimmed), a plane plate with a
circular hole (trimmed; OCC writes a 108 plane with model-space curves), the same
plate converted to NURBS (128 with parameter-space curves) and a rational surface
periodic in u (unclamped knots); and OUT_DIR/solid.igs (inch) from the faces of a
solid (a box less a cylinder, fused with a sphere; converted to NURBS: seams and
poles). Both with IGESControl_Writer in BRep-faces mode (mode 0: 144/142/128/126),
each with a CSV (occ.csv, solid.csv, in mm) of one line per sample: face index, OCC (u, v), the OCC 3D point S(u, v), and the face
area (BRepGProp.SurfaceProperties_s). Samples lie inside each face (classified by
BRepClass_FaceClassifier).
"""

import math
import sys

from OCP.BRep import BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeWire, BRepBuilderAPI_MakeEdge
from OCP.BRepClass import BRepClass_FaceClassifier
from OCP.BRepGProp import BRepGProp
from OCP.GProp import GProp_GProps
from OCP.Geom import Geom_BSplineSurface
from OCP.IGESControl import IGESControl_Controller, IGESControl_Writer
from OCP.Interface import Interface_Static
from OCP.OCP.collections import Array1_double, Array1_int, Array2_double, Array2_gp_Pnt
from OCP.TopAbs import TopAbs_IN
from OCP.gp import gp_Ax2, gp_Circ, gp_Dir, gp_Pln, gp_Pnt, gp_Pnt2d
from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut, BRepAlgoAPI_Fuse
from OCP.BRepBuilderAPI import BRepBuilderAPI_NurbsConvert
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCylinder, BRepPrimAPI_MakeSphere
from OCP.TopExp import TopExp_Explorer
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS


def bspline_face():
    """A rational bicubic x biquadratic face, 5 x 4 poles, one interior knot in u."""
    nu, nv = 5, 4
    pts = Array2_gp_Pnt(1, nu, 1, nv)
    wts = Array2_double(1, nu, 1, nv)
    for i in range(1, nu + 1):
        for j in range(1, nv + 1):
            x, y = 10.0 * (i - 1), 8.0 * (j - 1)
            # three decimals: the IGES text (10 significant digits) holds it exactly
            z = round(3.0 * math.sin(0.1 * x) * math.cos(0.15 * y) + 0.05 * x, 3)
            pts.SetValue(i, j, gp_Pnt(x, y, z))
            wts.SetValue(i, j, 1.0 + 0.3 * ((i + 2 * j) % 3))
    uk, um = Array1_double(1, 3), Array1_int(1, 3)
    for k, (t, m) in enumerate([(0.0, 4), (0.4, 1), (1.0, 4)]):
        uk.SetValue(k + 1, t)
        um.SetValue(k + 1, m)
    vk, vm = Array1_double(1, 3), Array1_int(1, 3)
    for k, (t, m) in enumerate([(0.0, 3), (0.5, 1), (2.0, 3)]):
        vk.SetValue(k + 1, t)
        vm.SetValue(k + 1, m)
    surf = Geom_BSplineSurface(pts, wts, uk, vk, um, vm, 3, 2)
    return BRepBuilderAPI_MakeFace(surf, 1e-6).Face()


def periodic_face():
    """A rational surface periodic in u (a wavy tube): OCC writes its knots
    unclamped, -3 to 9 for the domain [0, 6]."""
    nu, nv = 6, 3
    pts = Array2_gp_Pnt(1, nu, 1, nv)
    wts = Array2_double(1, nu, 1, nv)
    for i in range(nu):
        for j in range(nv):
            a = 2.0 * math.pi * i / nu
            x, y = round(20.0 * math.cos(a), 3), round(20.0 * math.sin(a), 3)
            pts.SetValue(i + 1, j + 1, gp_Pnt(x + 200.0, y, 10.0 * j + (i % 2)))
            wts.SetValue(i + 1, j + 1, 1.0 + 0.5 * (i % 2))
    uk, um = Array1_double(1, nu + 1), Array1_int(1, nu + 1)
    for k in range(nu + 1):
        uk.SetValue(k + 1, float(k))
        um.SetValue(k + 1, 1)
    vk, vm = Array1_double(1, 2), Array1_int(1, 2)
    for k, t in enumerate([0.0, 1.0]):
        vk.SetValue(k + 1, t)
        vm.SetValue(k + 1, 3)
    surf = Geom_BSplineSurface(pts, wts, uk, vk, um, vm, 3, 2, True, False)
    return BRepBuilderAPI_MakeFace(surf, 1e-6).Face()


def plate_with_hole():
    plate = BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(100, 0, 5), gp_Dir(0, 0, 1)), 0.0, 60.0, 0.0, 40.0).Face()
    cyl = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(125, 18, -10), gp_Dir(0, 0, 1)), 9.0, 40.0).Shape()
    cut = BRepAlgoAPI_Cut(plate, cyl).Shape()
    exp = TopExp_Explorer(cut, TopAbs_FACE)
    return TopoDS.Face(exp.Current())


def nurbs_plate():
    """The plate with a hole, its plane and edges converted to NURBS (OCC then writes
    128 with parameter-space trimming curves)."""
    moved = plate_with_hole().Moved(__import__("OCP.TopLoc", fromlist=["TopLoc_Location"]).TopLoc_Location(
        __import__("OCP.gp", fromlist=["gp_Trsf"]).gp_Trsf()))
    conv = BRepBuilderAPI_NurbsConvert(moved, True).Shape()
    exp = TopExp_Explorer(conv, TopAbs_FACE)
    return TopoDS.Face(exp.Current())


def samples(face, n=9):
    surf = BRep_Tool.Surface_s(face)
    from OCP.BRepTools import BRepTools
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    out = []
    for a in range(n):
        for b in range(n):
            u = u0 + (u1 - u0) * (a + 0.5) / n
            v = v0 + (v1 - v0) * (b + 0.5) / n
            c = BRepClass_FaceClassifier(face, gp_Pnt2d(u, v), 1e-9)
            if c.State() != TopAbs_IN:
                continue
            p = surf.Value(u, v)
            out.append((u, v, p.X(), p.Y(), p.Z()))
    return out


def solid_faces():
    """The faces of a box less a cylinder, fused with a sphere at a corner, all
    converted to NURBS: closed surfaces with seams (cylinder, sphere) and poles."""
    box = BRepPrimAPI_MakeBox(40, 30, 20).Shape()
    cyl = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(20, 15, -5), gp_Dir(0, 0, 1)), 6, 40).Shape()
    sph = BRepPrimAPI_MakeSphere(gp_Pnt(40, 30, 20), 8).Shape()
    shape = BRepAlgoAPI_Fuse(BRepAlgoAPI_Cut(box, cyl).Shape(), sph).Shape()
    conv = BRepBuilderAPI_NurbsConvert(shape, True).Shape()
    out = []
    exp = TopExp_Explorer(conv, TopAbs_FACE)
    while exp.More():
        out.append(TopoDS.Face(exp.Current()))
        exp.Next()
    return out


def write(faces, out_dir, name, unit):
    """Writes OUT_DIR/NAME.igs in UNIT and OUT_DIR/NAME.csv (samples in mm)."""
    IGESControl_Controller.Init_s()
    Interface_Static.SetCVal_s("write.iges.unit", unit)
    w = IGESControl_Writer(unit, 0)
    for f in faces:
        w.AddShape(f)
    w.ComputeModel()
    if not w.Write(f"{out_dir}/{name}.igs"):
        sys.exit("IGES write failed")
    with open(f"{out_dir}/{name}.csv", "w") as csv:
        csv.write("face,u,v,x,y,z,area\n")
        for k, f in enumerate(faces):
            props = GProp_GProps()
            BRepGProp.SurfaceProperties_s(f, props)
            for u, v, x, y, z in samples(f):
                csv.write(f"{k},{u!r},{v!r},{x!r},{y!r},{z!r},{props.Mass()!r}\n")


def main(out_dir):
    write([bspline_face(), plate_with_hole(), nurbs_plate(), periodic_face()], out_dir, "occ", "MM")
    write(solid_faces(), out_dir, "solid", "IN")


if __name__ == "__main__":
    main(sys.argv[1])
