"""The README's Python example runs as a doctest (from the repository root)."""

import doctest
import os
import re


def test_readme_python_example(repo):
    text = (repo / "README.md").read_text()
    section = text.split("\n## Python\n", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"```pycon\n(.*?)```", section, re.S)
    assert blocks, "the Python section has a pycon example"
    parser = doctest.DocTestParser()
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    cwd = os.getcwd()
    os.chdir(repo)
    try:
        for k, block in enumerate(blocks):
            test = parser.get_doctest(block, {}, f"README.md Python example {k + 1}", "README.md", 0)
            runner.run(test)
    finally:
        os.chdir(cwd)
    result = runner.summarize(verbose=False)
    assert result.failed == 0 and result.attempted >= 5
