"""Rest material: the regions and report identical to `swarf rest`."""

import json

import numpy as np
import pytest

import swarf


def boundaries_csv(rest):
    lines = ["region,ring,x,y"]
    for k, region in enumerate(rest.regions):
        for j, ring in enumerate(region.boundary):
            lines += [f"{k + 1},{j},{x:.6f},{y:.6f}" for x, y in ring]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize(
    "kwargs, flags",
    [
        (dict(part="builtin:v-grooves", reference="ball:d=12"), ["--part", "builtin:v-grooves", "--reference", "ball:d=12"]),
        (dict(part="builtin:fillet-pocket", reference=swarf.Tool("ball:d=12"), merge=3.0),
         ["--part", "builtin:fillet-pocket", "--reference", "ball:d=12", "--merge", "3"]),
        (dict(job="JOBS/fillet-pocket-finish.toml"), ["--job", "JOBS/fillet-pocket-finish.toml"]),
    ],
)
def test_rest_matches_swarf_rest(cli, repo, tmp_path, kwargs, flags):
    kwargs = {k: (str(v).replace("JOBS", str(repo / "jobs")) if k == "job" else v) for k, v in kwargs.items()}
    flags = [f.replace("JOBS", str(repo / "jobs")) for f in flags]
    out = tmp_path / "cli"
    cli.run("rest", *flags, "-o", out)
    r = swarf.rest(**kwargs)
    assert r.report == json.loads((out / "rest.json").read_text())
    assert boundaries_csv(r) == (out / "rest.csv").read_text()
    assert len(r) == len(r.regions) > 0
    for region, ref in zip(r.regions, r.report["regions"]):
        assert region.area == ref["area_mm2"] and region.depth == ref["depth_mm"]
        assert list(region.deepest) == ref["deepest"] and region.kinds == ref["kinds"]
        outer = region.boundary[0]
        assert outer.shape == (ref["boundary_points"], 2) and np.array_equal(outer[0], outer[-1])
        assert region.raw and all(ring.shape[1] == 2 for poly in region.raw for ring in poly)
    py = tmp_path / "py"
    swarf.rest(**kwargs, out=py)
    for f in ["rest.json", "rest.csv", "rest.png"]:
        assert (py / f).read_bytes() == (out / f).read_bytes(), f


def test_rest_errors_match_swarf_rest(cli, tmp_path):
    cases = [
        (dict(part="v-grooves", reference="ball:d=12", merge=0.0), ["--part", "v-grooves", "--reference", "ball:d=12", "--merge", "0"]),
        (dict(part="v-grooves", reference="ball:x=1"), ["--part", "v-grooves", "--reference", "ball:x=1"]),
        (dict(part="v-grooves"), ["--part", "v-grooves"]),
        (dict(part="v-grooves", reference="ball:d=12", source="stock"), ["--part", "v-grooves", "--reference", "ball:d=12", "--source", "stock"]),
        (dict(job="/nonexistent/finish.toml"), ["--job", "/nonexistent/finish.toml"]),
        (dict(part="v-grooves", reference="ball:d=12", threshold=-1.0), ["--part", "v-grooves", "--reference", "ball:d=12", "--threshold=-1"]),
    ]
    for kwargs, flags in cases:
        theirs = cli.fail("rest", *flags, "-o", tmp_path / "o")
        with pytest.raises(swarf.SwarfError) as e:
            swarf.rest(**kwargs)
        assert str(e.value) == theirs, kwargs
    with pytest.raises(swarf.SwarfError, match="--source sideways: expected reference, contacts or stock"):
        swarf.rest("v-grooves", reference="ball:d=12", source="sideways")
