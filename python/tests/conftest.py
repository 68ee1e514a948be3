"""Shared fixtures: the repository, the `swarf` command line the package is checked
against, and helpers to run it.

The command line is `$SWARF_BIN`, else `target/debug/swarf` in the checkout
(`cargo build -p swarf`; the test suite builds it). Without it the comparisons skip, unless
`SWARF_REQUIRE_REFERENCES=1` (as `.ci/python` sets), when they fail.
"""

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import swarf

REPO = Path(__file__).resolve().parents[2]
REQUIRE = os.environ.get("SWARF_REQUIRE_REFERENCES") == "1"


def _missing(what):
    if REQUIRE:
        pytest.fail(f"{what} is required (SWARF_REQUIRE_REFERENCES=1) but missing")
    pytest.skip(f"{what} not available")


@pytest.fixture(scope="session")
def repo():
    return REPO


@pytest.fixture(scope="session")
def swarf_bin():
    path = Path(os.environ.get("SWARF_BIN", REPO / "target" / "debug" / "swarf"))
    if not path.is_file():
        _missing(f"the swarf command line ({path}; cargo build -p swarf)")
    return str(path)


class Cli:
    """Runs the command line; `run` checks success, `fail` expects a failure and
    returns the message after `swarf: error: `."""

    def __init__(self, exe):
        self.exe = exe

    def run(self, *args, cwd=None):
        r = subprocess.run([self.exe, *map(str, args)], capture_output=True, text=True, cwd=cwd)
        assert r.returncode == 0, f"swarf {' '.join(map(str, args))}: {r.stderr}"
        return r.stdout

    def fail(self, *args, cwd=None):
        r = subprocess.run([self.exe, *map(str, args)], capture_output=True, text=True, cwd=cwd)
        assert r.returncode != 0, f"swarf {' '.join(map(str, args))} succeeded"
        line = [l for l in r.stderr.splitlines() if l.startswith("swarf: error: ")][-1]
        return line[len("swarf: error: "):]

    def json(self, *args, cwd=None):
        return json.loads(self.run(*args, cwd=cwd))


@pytest.fixture(scope="session")
def ocl():
    """OpenCAMLib's module (``import opencamlib``; .ci/install-references installs it)."""
    try:
        import opencamlib
    except ImportError:
        _missing("opencamlib (pip install opencamlib==2023.1.11)")
    return opencamlib


@pytest.fixture(scope="session")
def cli(swarf_bin):
    return Cli(swarf_bin)


@pytest.fixture(scope="session")
def wave_mesh():
    """The wave part tessellated within 0.05 mm (about 5,000 triangles)."""
    return swarf.Part.load("builtin:wave").tessellate(0.05)


@pytest.fixture(scope="session")
def wave_stl(tmp_path_factory, wave_mesh, cli):
    """`swarf tessellate wave --tol 0.05` as a binary STL file."""
    path = tmp_path_factory.mktemp("stl") / "wave.stl"
    cli.run("tessellate", "builtin:wave", "--tol", 0.05, "-o", path)
    return path


def grid_points(lo, hi, n, seed=1):
    """`n` random points over the box [lo, hi] plus a few off it."""
    rng = np.random.default_rng(seed)
    pts = rng.uniform(lo, hi, size=(n, 2))
    pts[:5] = [[lo[0] - 50, lo[1]], [hi[0] + 50, hi[1]], [lo[0], lo[1] - 50], [-1e5, 0], [0, 1e5]]
    return pts
