"""Shared fixtures: the repository root (for data/examples) and a small sphere scene."""

from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]

SMALL_SPHERE = """
version = 1
[material]
e_star = 1.0
gamma = 0.125
[geometry]
shape = "sphere"
radius = 8.0
[grid]
n = 32
dx = 0.45
[protocol]
max_approach = 3.0
load_step = 0.5
unload_step = 0.02
"""


@pytest.fixture
def repo() -> Path:
    return REPO


@pytest.fixture
def small_sphere() -> str:
    return SMALL_SPHERE


@pytest.fixture(autouse=True)
def _every_warning_has_its_class(monkeypatch):
    """Every sentence a run issues, in any test, maps to a warning class of its kind: a new
    warning of the Rust side without its prefix in ``tack._warnings._KINDS`` would reach users
    as a bare ``TackWarning``, which no filter of a kind catches."""
    import tack
    import tack._warnings as kinds

    original = kinds.kind

    def checked(sentence: str):
        cls = original(sentence)
        assert cls is not tack.TackWarning, f"no warning class for the sentence: {sentence}"
        return cls

    monkeypatch.setattr(kinds, "kind", checked)
