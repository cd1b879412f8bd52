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
