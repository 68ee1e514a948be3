"""Error messages read as the user wrote the input: the field a dict job lacks, the
Tool call as written, a patch index against the part's patches; the command line
says the same where it takes the same input."""

import numpy as np
import pytest

import swarf


def test_a_dict_job_without_a_strategy_names_the_missing_field_at_the_top(cli, tmp_path):
    with pytest.raises(swarf.SwarfError) as e:
        swarf.Job.from_dict({"part": "builtin:wave", "tool": "ball:d=8"})
    assert str(e.value) == "job dict: missing field `strategy`"
    with pytest.raises(swarf.SwarfError) as e:
        swarf.plan({"part": "builtin:wave", "tool": "ball:d=8", "feeds": {"feed": 900}})
    assert str(e.value) == "job dict: missing field `strategy`"
    # In a sequence, the operation that lacks it.
    with pytest.raises(swarf.SwarfError) as e:
        swarf.plan({"part": "builtin:wave", "operation": [{"tool": "ball:d=8"}]})
    assert str(e.value) == "job dict: operation[0]: missing field `strategy`"
    job = tmp_path / "job.toml"
    job.write_text('part = "builtin:wave"\ntool = "ball:d=8"\n')
    assert cli.fail("plan", job, "-o", tmp_path).endswith(": missing field `strategy`")


def test_a_tool_from_keywords_names_the_call_once():
    with pytest.raises(swarf.SwarfError) as e:
        swarf.Tool(shape="bull", d=10)
    assert str(e.value) == "Tool(shape='bull', d=10): bull tool: missing `r` (corner radius, mm)"
    with pytest.raises(swarf.SwarfError) as e:
        swarf.Tool(shape="blob", d=10)
    assert str(e.value).startswith("Tool(shape='blob', d=10): unknown tool shape `blob`")
    assert "{" not in str(e.value)


def test_a_patch_index_past_the_last_patch_says_how_many_there_are(cli):
    wave = swarf.Part.load("builtin:wave")
    with pytest.raises(ValueError) as e:
        wave.eval(3, np.array([[0.5, 0.5]]))
    message = "index 3 is out of range: part wave has 1 patch (index 0)"
    assert str(e.value) == f"patch: {message}"
    assert cli.fail("eval", "wave", "--patch", "3", "--uv", "0.5,0.5") == f"--patch: {message}"
