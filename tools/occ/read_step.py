#!/usr/bin/env python3
"""OpenCASCADE's own reading of a STEP file, as a reference for swarf's tests.

Usage: read_step.py PART.step OUT.stl DEFLECTION

Reads PART.step with STEPControl_Reader, meshes it with BRepMesh_IncrementalMesh
(linear deflection DEFLECTION mm, 0.1 rad angular) and writes a binary STL of every
face to OUT.stl. Prints one line per face in the order TopExp_Explorer visits them:
    area,<mm^2>
computed by BRepGProp.SurfaceProperties_s on the exact trimmed face.
"""

import sys

from OCP.BRepGProp import BRepGProp
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.GProp import GProp_GProps
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_Reader
from OCP.StlAPI import StlAPI_Writer
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS


def main():
    path, stl, deflection = sys.argv[1], sys.argv[2], float(sys.argv[3])
    reader = STEPControl_Reader()
    if reader.ReadFile(path) != IFSelect_RetDone:
        sys.exit(f"{path}: OpenCASCADE cannot read it")
    reader.TransferRoots()
    shape = reader.OneShape()
    BRepMesh_IncrementalMesh(shape, deflection, False, 0.1, True)
    writer = StlAPI_Writer()
    writer.ASCIIMode = False
    if not writer.Write(shape, stl):
        sys.exit(f"{stl}: cannot write")
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        props = GProp_GProps()
        BRepGProp.SurfaceProperties_s(TopoDS.Face(explorer.Current()), props, 1e-12)
        print(f"area,{props.Mass():.17g}")
        explorer.Next()


if __name__ == "__main__":
    main()
