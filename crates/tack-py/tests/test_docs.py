"""The Python programs of README.md (section "Python") and every ```python block of
docs/python.md run as written; the worked examples print what the page says they print."""

import os
import re

import pytest


def python_block(text: str, start: str, end: str) -> str:
    section = text[text.index(start) : text.index(end)]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def python_blocks(text: str):
    return re.findall(r"^```python\n(.*?)^```", text, re.S | re.M)


def test_readme_example(repo, capsys, monkeypatch):
    code = python_block(
        (repo / "README.md").read_text(), "## Python", "## The `tack` command line"
    )
    monkeypatch.chdir(repo)  # "from the repository root"
    exec(compile(code, "README.md", "exec"), {})
    out = capsys.readouterr().out
    assert "F/F_JKR = 1.1343 over 805 steps" in out
    assert "rough sphere: |F/F_JKR| = " in out


def test_every_block_of_the_python_guide(repo, capsys, monkeypatch, tmp_path):
    text = (repo / "docs/python.md").read_text()
    head, examples = text.split("## Worked examples", 1)
    # "From the repository root", without writing into it: data/ is linked into a scratch
    # directory (the quick start writes jkr.h5, the rough sphere its plot, if matplotlib is
    # installed).
    os.symlink(repo / "data", tmp_path / "data")
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    for k, code in enumerate(python_blocks(head)):
        exec(compile(code, f"docs/python.md (block {k})", "exec"), namespace)
    capsys.readouterr()
    blocks = python_blocks(examples)
    assert len(blocks) >= 7, "the worked examples: rough sphere, Dugdale pull-off, cycle, film, pattern, ellipsoid, Richardson"
    for k, code in enumerate(blocks):
        exec(compile(code, f"docs/python.md (example {k})", "exec"), namespace)
        out = capsys.readouterr().out
        assert out.strip(), f"example {k} prints nothing"
        for line in out.splitlines():
            # The numbers are as documented (times vary).
            shown = line.split(" steps in ")[0]
            assert shown in examples, f"example {k}: {line!r} is not in docs/python.md"
    assert re.search(r"mean \|F/F_JKR\| = \d\.\d+; Eq\. 12: 0\.780", examples)
