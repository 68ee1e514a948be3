"""Parts and meshes: loading as the command line does, patch evaluation against
`swarf eval`, tessellation against `swarf tessellate`, meshes from arrays."""

import struct

import numpy as np
import pytest

import swarf


def read_binary_stl(path):
    """The float32 triangles of a binary STL as a (T, 3, 3) float64 array."""
    data = path.read_bytes()
    (count,) = struct.unpack_from("<I", data, 80)
    tris = np.frombuffer(data, dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]),
                         count=count, offset=84)
    return tris["v"].astype(np.float64)


def test_load_builtin_file_and_mesh(repo):
    wave = swarf.load("builtin:wave")
    assert isinstance(wave, swarf.Part) and wave.name == "wave" and len(wave) == 1
    same = swarf.load(repo / "parts" / "wave.toml")
    assert isinstance(same, swarf.Part) and len(same) == len(wave)
    assert isinstance(swarf.load("die"), swarf.Part)
    pocket = swarf.load("builtin:fillet-pocket")
    assert isinstance(pocket, swarf.Mesh) and len(pocket) > 1000
    assert swarf.Mesh.load("builtin:fillet-pocket").faces.shape == pocket.faces.shape
    with pytest.raises(swarf.SwarfError, match="no such file and no built-in part"):
        swarf.load("builtin:nothing")
    with pytest.raises(swarf.SwarfError, match="a parametric part, not a mesh"):
        swarf.Mesh.load("builtin:wave")


def test_eval_matches_swarf_eval(cli):
    part = swarf.Part.load("builtin:die")
    for patch in range(len(part)):
        (u0, u1), (v0, v1) = part.domain(patch)
        uv = np.array([[u0, v0], [u1, v1], [0.3 * u0 + 0.7 * u1, 0.6 * v0 + 0.4 * v1],
                       [0.5 * (u0 + u1), 0.5 * (v0 + v1)]])
        got = part.eval(patch, uv)
        for i, (u, v) in enumerate(uv):
            ref = cli.json("eval", "builtin:die", "--patch", patch, "--uv", f"{float(u)!r},{float(v)!r}")
            for key in ("point", "du", "dv", "normal", "dir1", "dir2"):
                assert got[key][i].tolist() == ref[key], (patch, i, key)
            for key in ("k1", "k2"):
                assert got[key][i] == ref[key], (patch, i, key)


def test_eval_bad_input():
    part = swarf.Part.load("builtin:wave")
    with pytest.raises(ValueError, match=r"uv\[1\]: \(0.5, 1.5\) is outside the patch's domain"):
        part.eval(0, np.array([[0.5, 0.5], [0.5, 1.5]]))
    with pytest.raises(ValueError, match=r"patch: index 3 is out of range: part wave has 1 patch \(index 0\)"):
        part.eval(3, np.array([[0.5, 0.5]]))
    with pytest.raises(ValueError, match=r"uv: expected a float64 array of shape \(N, 2\), found an array of dtype float64 and shape \(3,\)"):
        part.eval(0, np.array([0.5, 0.5, 0.5]))
    with pytest.raises(ValueError, match=r"uv\[0, 1\]: NaN is not a finite number"):
        part.eval(0, np.array([[0.5, np.nan]]))


def test_tessellate_matches_swarf_tessellate(cli, tmp_path):
    stl = tmp_path / "die.stl"
    cli.run("tessellate", "builtin:die", "--tol", 0.05, "-o", stl)
    mesh = swarf.Part.load("builtin:die").tessellate(0.05)
    ours = mesh.vertices[mesh.faces].astype(np.float32).astype(np.float64)
    theirs = read_binary_stl(stl)
    assert ours.shape == theirs.shape
    assert np.array_equal(ours, theirs)
    loaded = swarf.Mesh.load(stl)
    assert np.array_equal(loaded.vertices[loaded.faces], theirs)
    with pytest.raises(ValueError, match="tol: expected a tolerance"):
        swarf.Part.load("builtin:die").tessellate(0.0)


def test_mesh_from_arrays_round_trip(wave_mesh):
    again = swarf.Mesh(wave_mesh.vertices, wave_mesh.faces, name="copy")
    assert np.array_equal(again.vertices, wave_mesh.vertices)
    assert np.array_equal(again.faces, wave_mesh.faces)
    assert again.bounds() == wave_mesh.bounds() and again.name == "copy"
    small = swarf.Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    assert len(small) == 1
    for dtype in (np.int32, np.uint32, np.int64, np.uint64, np.int16):
        assert len(swarf.Mesh(wave_mesh.vertices, wave_mesh.faces.astype(dtype))) == len(wave_mesh)


def test_obj_mesh_loads(tmp_path):
    obj = tmp_path / "square.obj"
    obj.write_text("v 0 0 0\nv 10 0 0\nv 10 10 1\nv 0 10 1\nf 1 2 3\nf 1 3 4\n")
    mesh = swarf.load(obj)
    assert isinstance(mesh, swarf.Mesh) and len(mesh) == 2 and mesh.name == "square"
    assert mesh.bounds() == ((0.0, 0.0, 0.0), (10.0, 10.0, 1.0))


V = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 1]])
F = np.array([[0, 1, 2], [1, 3, 2]])


@pytest.mark.parametrize(
    "vertices, faces, message",
    [
        (V.astype(np.float32), F, r"vertices: expected a float64 array of shape \(N, 3\), found an array of dtype float32 and shape \(4, 3\)"),
        (V[:, :2].copy(), F, r"vertices: expected a float64 array of shape \(N, 3\), found an array of dtype float64 and shape \(4, 2\)"),
        (V.astype(np.int64), F, r"vertices: expected a float64 array .* dtype int64"),
        (np.where(np.arange(12).reshape(4, 3) == 7, np.inf, V), F, r"vertices\[2, 1\]: inf is not a finite number"),
        (np.where(np.arange(12).reshape(4, 3) == 9, np.nan, V), F, r"vertices\[3, 0\]: NaN is not a finite number"),
        (V * 1e7, F, r"vertices\[1, 0\]: expected a coordinate"),
        (V, np.array([[0, 1, 2], [1, 4, 2]]), r"faces\[1, 1\]: vertex index 4 out of range: expected 0 to 3 \(4 vertices\)"),
        (V, np.array([[0, 1, 2], [1, 3, -1]]), r"faces\[1, 2\]: vertex index -1 out of range"),
        (V, F.astype(np.float64), r"faces: expected an integer array of shape \(M, 3\), found an array of dtype float64"),
        (V, F[:, :2].copy(), r"faces: expected an integer array of shape \(M, 3\), found an array of dtype int64 and shape \(2, 2\)"),
        (V, np.zeros((0, 3), dtype=np.int64), r"faces: an empty mesh: expected at least one triangle"),
        (np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64), r"vertices: an empty mesh"),
        (V, np.array([[0, 1, 2]], dtype=np.uint64) + np.uint64(2**63), r"faces\[0, 0\]: vertex index 9223372036854775808 out of range"),
        (V, [[0, 1, 2], [1, 3, "x"]], r"faces"),
    ],
)
def test_mesh_bad_arrays(vertices, faces, message):
    with pytest.raises(ValueError, match=message):
        swarf.Mesh(vertices, faces)
