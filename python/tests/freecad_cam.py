"""FreeCAD CAM headless: a job on a STEP part with 3D Surface (Line, ZigZag) and
Waterline (OCL Dropcutter) operations, recomputed with whatever ``import ocl``
gives (OpenCAMLib, or swarf.ocl through its shim). Run by ``freecadcmd``, which
passes no arguments to scripts: the settings come as JSON in ``$SWARF_FREECAD_JOB``
(``step``, the part; ``out``, a folder; ``tolerance``, the job's geometry tolerance,
mm; ``sampling``, the operations' sample interval, mm; ``stepover``, percent).

Writes ``out/result.json``: per operation its seconds, the seconds spent in ``ocl``
calls (``PathDropCutter`` ``setSTL``, ``run``, ``getCLPoints``), and its commands
(name and parameters); and ``out/<operation>.ngc``, each operation posted by FreeCAD's
LinuxCNC post-processor at four decimals; and ``out/part.stl``, the part
tessellated within the job's tolerance (for ``swarf verify``).
"""

import json
import os
import sys
import time
import traceback


def timed_ocl(ocl, clock):
    """Replaces ``ocl.PathDropCutter`` with a subclass adding the time of its calls to
    ``clock["s"]`` and keeping the CL points of every run in ``clock["runs"]``."""
    base = ocl.PathDropCutter

    def timing(name):
        method = getattr(base, name)

        def call(self, *args):
            t = time.perf_counter()
            try:
                out = method(self, *args)
            finally:
                clock["s"] += time.perf_counter() - t
            if name == "setSTL":
                clock["triangles"] = args[0].size()
            if name == "getCLPoints" and clock["keep"]:
                clock["runs"].append([(p.x, p.y, p.z) for p in out])
            return out

        return call

    ocl.PathDropCutter = type(
        "PathDropCutter", (base,), {n: timing(n) for n in ("setSTL", "setPath", "run", "getCLPoints")}
    )


def tool_controller(doc, job, bit_file, number):
    import PathScripts.PathToolBit as PathToolBit
    import PathScripts.PathToolController as PathToolController

    bit = PathToolBit.Factory.CreateFrom(os.path.join(FreeCAD_home(), "Mod/Path/Tools/Bit", bit_file))
    tc = PathToolController.Create(f"TC{number}", bit, number)
    job.Proxy.addToolController(tc)
    return tc


def FreeCAD_home():
    import FreeCAD

    return FreeCAD.getHomePath()


def commands(path):
    return [[c.Name, {k: float(v) for k, v in c.Parameters.items()}] for c in path.Commands]


def main():
    settings = json.loads(os.environ["SWARF_FREECAD_JOB"])
    import FreeCAD
    import Part
    import ocl

    clock = {"s": 0.0, "runs": [], "keep": settings.get("scans", False)}
    timed_ocl(ocl, clock)
    import PathScripts.PathJob as PathJob
    import PathScripts.PathSurface as PathSurface
    import PathScripts.PathWaterline as PathWaterline
    from PathScripts.post import linuxcnc_post

    doc = FreeCAD.newDocument("swarf")
    part = doc.addObject("Part::Feature", "Part")
    part.Shape = Part.read(settings["step"])
    doc.recompute()
    import MeshPart

    MeshPart.meshFromShape(Shape=part.Shape, LinearDeflection=settings["tolerance"]).write(
        os.path.join(settings["out"], "part.stl")
    )
    job = PathJob.Create("Job", [part], None)
    job.GeometryTolerance = settings["tolerance"]
    flat = job.Tools.Group[0]
    # Operations made while the job has one tool controller take it without asking.
    ops = [
        ("surface_line", PathSurface.Create("surface_line"), {"CutPattern": "Line"}),
        ("surface_zigzag", PathSurface.Create("surface_zigzag"), {"CutPattern": "ZigZag"}),
        ("waterline", PathWaterline.Create("waterline"), {"Algorithm": "OCL Dropcutter", "LayerMode": "Multi-pass", "StepDown": 1.5}),
    ]
    ball = tool_controller(doc, job, "6mm_Ball_End.fctb", 2)
    tools = {"surface_line": ball, "surface_zigzag": flat, "waterline": ball}
    for tc in (ball, flat):
        tc.HorizFeed, tc.VertFeed, tc.SpindleSpeed = 1200.0, 400.0, 12000.0
    result = {"ocl": getattr(sys.modules["ocl"], "__file__", "?"), "version": ocl.version(), "ops": {}}
    for name, op, props in ops:
        op.ToolController = tools[name]
        op.SampleInterval = settings["sampling"]
        op.StepOver = settings["stepover"]
        for k, v in props.items():
            setattr(op, k, v)
        clock["s"], clock["runs"] = 0.0, []
        t = time.perf_counter()
        op.recompute()
        seconds = time.perf_counter() - t
        result["ops"][name] = {"seconds": seconds, "ocl_seconds": clock["s"], "commands": commands(op.Path), "scans": clock["runs"], "triangles": clock.get("triangles")}
        gcode = os.path.join(settings["out"], name + ".ngc")
        linuxcnc_post.export([tools[name], op], gcode, "--no-show-editor --precision=4 --no-header --no-comments")
    with open(os.path.join(settings["out"], "result.json"), "w") as f:
        json.dump(result, f)


try:
    main()
except Exception:
    traceback.print_exc()
    sys.stdout.flush()
    os._exit(1)
os._exit(0)
