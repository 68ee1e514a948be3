"""Drop-cutter: heights and contacts identical to `swarf drop` on the same mesh file
and points, for any thread count; the GIL released while it runs; bad input."""

import threading
import time

import numpy as np
import pytest

import swarf
from conftest import grid_points

SPECS = ["ball:d=8", "flat:d=6", "bull:d=10,r=2", "cone:d=10,angle=90", "taperball:d=6,angle=10,tip=1"]


def cli_drop(cli, stl, spec, pts, tmp_path, contact=False):
    """`swarf drop` on `pts`: rows of strings split at commas."""
    points = tmp_path / "points.csv"
    points.write_text("x,y\n" + "".join(f"{float(x)!r},{float(y)!r}\n" for x, y in pts))
    out = tmp_path / "out.csv"
    args = ["drop", "--mesh", stl, "--tool", spec, "--points", points, "-o", out]
    cli.run(*args, *(["--contact"] if contact else []))
    return [line.split(",") for line in out.read_text().splitlines()[1:]]


@pytest.mark.parametrize("spec", SPECS)
def test_heights_and_contacts_match_swarf_drop(cli, wave_stl, spec, tmp_path):
    mesh = swarf.Mesh.load(wave_stl)
    pts = grid_points((-10, -10), (210, 110), 3000)
    rows = cli_drop(cli, wave_stl, spec, pts, tmp_path, contact=True)
    got = swarf.drop(mesh, spec, pts, contacts=True)
    z = swarf.drop(mesh, swarf.Tool(spec), pts)
    assert np.array_equal(z, got.z, equal_nan=True)
    assert len(rows) == len(pts)
    for i, r in enumerate(rows):
        if r[2] == "":
            assert np.isnan(got.z[i]) and got.tri[i] == -1 and got.feature[i] == -1, i
            assert np.isnan(got.cc[i]).all()
            continue
        assert float(r[2]) == got.z[i], (i, r)
        assert int(r[3]) == got.tri[i], (i, r)
        assert r[4] == swarf.FEATURES[got.feature[i]], (i, r)
        assert [float(c) for c in r[5:8]] == got.cc[i].tolist(), (i, r)
    assert np.isnan(z[:5]).all(), "points off the mesh get NaN"
    assert np.isfinite(z[5:]).sum() > 2000


def test_same_heights_for_any_thread_count(wave_mesh):
    pts = grid_points((0, 0), (200, 100), 20000, seed=2)
    d = swarf.Dropper(wave_mesh, "bull:d=10,r=2")
    one = d.drop(pts, threads=1)
    two = d.drop(pts, threads=2)
    every = d.drop(pts)
    assert np.array_equal(one, two, equal_nan=True) and np.array_equal(one, every, equal_nan=True)
    assert len(d) == len(wave_mesh) and d.tool == swarf.Tool("bull:d=10,r=2")


def test_drop_accepts_lists_and_empty_arrays(wave_mesh):
    assert swarf.drop(wave_mesh, "ball:d=8", np.zeros((0, 2))).shape == (0,)
    z = swarf.drop(wave_mesh, "ball:d=8", [[100.0, 50.0]])
    assert z.shape == (1,) and np.isfinite(z[0])


def test_gil_released_during_a_long_drop(wave_mesh):
    """A Python thread keeps ticking while one drop call of 400,000 points runs (with
    the GIL held it could not tick at all until the call returned)."""
    d = swarf.Dropper(wave_mesh, "bull:d=10,r=2")
    pts = grid_points((0, 0), (200, 100), 400_000, seed=3)
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.002)

    t = threading.Thread(target=tick)
    t.start()
    time.sleep(0.02)
    start = time.perf_counter()
    d.drop(pts)
    end = time.perf_counter()
    stop.set()
    t.join()
    during = [x for x in ticks if start < x < end]
    assert end - start > 0.1, "the drop should take long enough to measure"
    assert len(during) >= 10, (len(during), end - start)


@pytest.mark.parametrize(
    "points, error, message",
    [
        (np.zeros((3, 2), dtype=np.float32), ValueError, r"points: expected a float64 array of shape \(N, 2\), found an array of dtype float32 and shape \(3, 2\)"),
        (np.zeros((3, 3)), ValueError, r"points: expected a float64 array of shape \(N, 2\), found an array of dtype float64 and shape \(3, 3\)"),
        (np.zeros(4), ValueError, r"points: .* shape \(4,\)"),
        (np.array([[1.0, 2.0], [np.nan, 0.0]]), ValueError, r"points\[1, 0\]: NaN is not a finite number"),
        (np.array([[1.0, 2.0], [3.0, -np.inf]]), ValueError, r"points\[1, 1\]: -inf is not a finite number"),
        (np.array([[1.0, 2e7]]), ValueError, r"points\[0, 1\]: expected a coordinate from -1000000 to 1000000 mm"),
        ([["a", "b"]], ValueError, r"points: expected an array of numbers"),
    ],
)
def test_drop_bad_points(wave_mesh, points, error, message):
    with pytest.raises(error, match=message):
        swarf.drop(wave_mesh, "ball:d=8", points)


def test_drop_bad_tool_mesh_and_threads(cli, wave_mesh, wave_stl, tmp_path):
    pts = np.array([[1.0, 2.0]])
    points = tmp_path / "p.csv"
    points.write_text("1,2\n")
    for spec in ["ball:d=-8", "ball:x=1", "blob:d=3", "bull:d=10,r=6"]:
        theirs = cli.fail("drop", "--mesh", wave_stl, "--tool", spec, "--points", points)
        with pytest.raises(swarf.SwarfError) as e:
            swarf.drop(wave_mesh, spec, pts)
        # The command line names its flag, Python the argument; the rest is the same.
        assert str(e.value).split(": ", 1)[1] == theirs.split(": ", 1)[1]
    with pytest.raises(swarf.SwarfError, match="drop-cutter needs a mesh"):
        swarf.drop(swarf.Part.load("builtin:wave"), "ball:d=8", pts)
    with pytest.raises(ValueError, match="threads: expected a thread count from 1 to 1024"):
        swarf.drop(wave_mesh, "ball:d=8", pts, threads=0)
    with pytest.raises(TypeError, match="tool: expected a Tool or a spec string"):
        swarf.drop(wave_mesh, 8, pts)
    missing = tmp_path / "none.stl"
    theirs = cli.fail("drop", "--mesh", missing, "--tool", "ball:d=8", "--points", points)
    with pytest.raises(swarf.SwarfError) as e:
        swarf.drop(str(missing), "ball:d=8", pts)
    assert str(e.value) == theirs
