"""The Python guide's example (docs/python.md) runs as a doctest (from the repository root)."""

import doctest
import os
import re


def test_python_guide_example(repo):
    text = (repo / "docs" / "python.md").read_text()
    blocks = re.findall(r"```pycon\n(.*?)```", text, re.S)
    assert blocks, "docs/python.md has a pycon example"
    parser = doctest.DocTestParser()
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    cwd = os.getcwd()
    os.chdir(repo)
    try:
        for k, block in enumerate(blocks):
            name = f"docs/python.md example {k + 1}"
            test = parser.get_doctest(block, {}, name, "docs/python.md", 0)
            runner.run(test)
    finally:
        os.chdir(cwd)
    result = runner.summarize(verbose=False)
    assert result.failed == 0 and result.attempted >= 5
