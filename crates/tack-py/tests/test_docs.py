"""The Python programs of README.md (section "Python") and docs/python.md (worked example) run
as written."""

import os
import re

import pytest


def python_block(text: str, start: str, end: str) -> str:
    section = text[text.index(start) : text.index(end)]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def test_readme_example(repo, capsys, monkeypatch):
    code = python_block(
        (repo / "README.md").read_text(), "## Python", "## The `tack` command line"
    )
    monkeypatch.chdir(repo)  # "from the repository root"
    exec(compile(code, "README.md", "exec"), {})
    out = capsys.readouterr().out
    assert "F/F_JKR = 1.1343 over 805 steps" in out
    assert "rough sphere: |F/F_JKR| = " in out


def test_worked_example(repo, capsys, monkeypatch, tmp_path):
    code = python_block(
        (repo / "docs/python.md").read_text(), "## Worked example", "## Tests"
    )
    monkeypatch.chdir(tmp_path)  # the plot, if matplotlib is installed, goes here
    exec(compile(code, "docs/python.md", "exec"), {})
    out = capsys.readouterr().out
    assert re.search(r"mean \|F/F_JKR\| = \d\.\d+; Eq\. 12: 0\.780", out), out
    documented = (repo / "docs/python.md").read_text()
    for line in out.splitlines():
        if line.startswith("seed"):
            # The forces, ratios and step counts are as documented (times vary).
            assert line.split(" steps in ")[0] in documented, line
