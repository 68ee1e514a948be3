"""``import ocl`` answered by ``swarf.ocl``: with this folder on ``sys.path`` (for
FreeCAD: ``PYTHONPATH="$(python3 -m swarf.ocl shim)" freecad``), programs written
for OpenCAMLib's ``ocl`` module run on swarf unchanged.

When the Python that imports this is not the one swarf is installed in (FreeCAD's
own), the folder holding the ``swarf`` package is appended to ``sys.path``: after
that Python's own packages, so its numpy wins.
"""

import os
import sys

try:
    import swarf.ocl as _ocl
except ImportError:
    _site = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
    if _site not in sys.path:
        sys.path.append(_site)
    import swarf.ocl as _ocl

sys.modules[__name__] = _ocl
