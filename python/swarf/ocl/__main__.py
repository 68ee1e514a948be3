"""``python3 -m swarf.ocl shim``: prints the folder of the ``ocl`` shim module, to
put on ``PYTHONPATH`` so that ``import ocl`` (FreeCAD's CAM workbench, OpenCAMLib
scripts) gets :mod:`swarf.ocl`."""

import os
import sys

USAGE = "usage: python3 -m swarf.ocl shim   (prints the folder to put on PYTHONPATH)"


def main(argv):
    if argv != ["shim"]:
        print(USAGE, file=sys.stderr)
        return 2
    print(os.path.join(os.path.dirname(os.path.abspath(__file__)), "shim"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
