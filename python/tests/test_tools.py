"""Tools from spec strings and keyword arguments, with the command line's messages."""

import pytest

import swarf


def test_spec_and_keywords_give_the_same_cutter():
    assert swarf.Tool("bull:d=10,r=2") == swarf.Tool(shape="bull", d=10, r=2)
    assert swarf.Tool("cone:d=10,angle=90") == swarf.Tool(shape="cone", d=10.0, angle=90)
    assert swarf.Tool(" BALL : d=8 ").spec == "ball:d=8"
    t = swarf.Tool("taperball:d=6,angle=10,tip=1")
    assert swarf.Tool(t.spec) == t and str(t) == t.spec and repr(t) == f"Tool({t.spec!r})"
    assert swarf.Tool("flat:d=6").radius == 3.0
    assert swarf.Tool("ball:d=8") != swarf.Tool("ball:d=6")


def test_tool_errors(cli, tmp_path):
    points = tmp_path / "p.csv"
    points.write_text("1,2\n")
    for spec in ["ball:d=-8", "bull:d=10", "cone:d=10,angle=180", "apt:d=10,alpha=95", "", "ball:d=8,d=9"]:
        theirs = cli.fail("drop", "--mesh", "x.stl", "--tool", spec, "--points", points)
        with pytest.raises(swarf.SwarfError) as e:
            swarf.Tool(spec)
        assert str(e.value).split(": ", 1)[1] == theirs.split(": ", 1)[1], spec
    with pytest.raises(swarf.SwarfError, match="bull"):
        swarf.Tool(shape="bull", d=10)
    with pytest.raises(swarf.SwarfError, match="not both"):
        swarf.Tool("ball:d=8", d=8)
    with pytest.raises(swarf.SwarfError, match="expected a spec string"):
        swarf.Tool()
    with pytest.raises(TypeError):
        swarf.Tool(8)
