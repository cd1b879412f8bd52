"""Patterned adhesion from Python: `pull_off(gamma=array)`, the pattern generators of
`tack.surface` (the scenes' `adhesion.pattern`), the ellipsoid, and their argument checks."""

import re

import numpy as np
import pytest

import tack

N, DX, R = 64, 0.05, 1.0
SPHERE = tack.surface.sphere(N, dx=DX, radius=R)
SCENE_OR_RUST = re.compile(r"material\.|adhesion\.|geometry\.|grid\.|::")


def test_a_uniform_array_is_the_uniform_run():
    plain = tack.pull_off(SPHERE, dx=DX, e_star=1.0, gamma=0.05, radius=R)
    mapped = tack.pull_off(
        SPHERE, dx=DX, e_star=1.0, gamma=np.full((N, N), 0.05), radius=R
    )
    # The criterion's inexact rounds keep a margin floor on a map: the same equilibria.
    assert abs(mapped.pull_off_force / plain.pull_off_force - 1.0) < 1e-9
    assert mapped.summary["gamma_mean"] == pytest.approx(0.05)
    assert "gamma" in mapped.surface and "gamma" not in plain.surface


def test_a_strong_core_holds_more_than_the_weak_surface_alone():
    rings = tack.surface.rings(N, dx=DX, gamma=0.02, gamma_b=0.08, period=4.0, fraction=0.2)
    assert rings[N // 2, N // 2] == 0.08 and rings[0, 0] == 0.02
    weak = tack.pull_off(SPHERE, dx=DX, e_star=1.0, gamma=0.02, radius=R)
    cored = tack.pull_off(SPHERE, dx=DX, e_star=1.0, gamma=rings, radius=R)
    assert cored.pull_off_force < weak.pull_off_force < 0.0
    s = cored.summary
    assert (s["gamma_min"], s["gamma_max"]) == (0.02, 0.08)
    np.testing.assert_array_equal(cored.surface["gamma"], rings)


def test_generators_match_their_definitions():
    x, y = tack.surface.coordinates(N, dx=DX)
    stripes = tack.surface.stripes(N, dx=DX, gamma=1.0, gamma_b=2.0, period=0.4, fraction=0.25)
    t = x / 0.4
    b = np.abs(t - np.round(t)) < 0.125 - 1e-9
    np.testing.assert_array_equal(stripes[:, 0], np.where(b, 2.0, 1.0))
    assert np.all(stripes == stripes[:, :1])
    board = tack.surface.checkerboard(N, dx=DX, gamma=1.0, gamma_b=2.0, period=0.5)
    assert board[N // 2, N // 2] == 1.0 and set(np.unique(board)) == {1.0, 2.0}
    field = tack.surface.gamma_random(
        128, dx=0.1, gamma=1.0, contrast=0.5, correlation_length=0.4, seed=3
    )
    assert np.all(field > 0.0)
    assert abs(field.mean() - 1.0) < 0.05 and abs(field.std() - 0.5) < 0.1
    again = tack.surface.gamma_random(
        128, dx=0.1, gamma=1.0, contrast=0.5, correlation_length=0.4, seed=3
    )
    np.testing.assert_array_equal(field, again)
    e = tack.surface.ellipsoid((5, 3), dx=1.0, radius_x=2.0, radius_y=0.5)
    assert e[0, 0] == pytest.approx(4.0 / 4.0 + 1.0 / 1.0)


@pytest.mark.parametrize(
    "gamma, named",
    [
        (np.full((N, N - 1), 0.05), "gamma.shape"),
        (np.where(np.eye(N, dtype=bool), -0.1, 0.05), "gamma[0, 0]"),
        (np.zeros((N, N)), "gamma.mean()"),
        (np.full((N, N), np.nan), "gamma[0, 0]"),
    ],
)
def test_bad_gamma_arrays_name_the_argument(gamma, named):
    with pytest.raises(tack.TackError) as info:
        tack.pull_off(SPHERE, dx=DX, e_star=1.0, gamma=gamma, radius=R)
    message = str(info.value)
    assert message.startswith(named), message
    assert not SCENE_OR_RUST.search(message), message


def test_a_gamma_array_of_strings_is_a_type_error():
    with pytest.raises(TypeError, match="^gamma: expected"):
        tack.pull_off(
            SPHERE, dx=DX, e_star=1.0, gamma=np.full((N, N), "a"), radius=R
        )


@pytest.mark.parametrize(
    "call, named",
    [
        (lambda: tack.surface.stripes(8, dx=0.1, gamma=1, gamma_b=2, period=0.1), "period"),
        (lambda: tack.surface.stripes(8, dx=0.1, gamma=1, gamma_b=-2, period=1), "gamma_b"),
        (
            lambda: tack.surface.rings(8, dx=0.1, gamma=1, gamma_b=2, period=1, fraction=2),
            "fraction",
        ),
        (
            lambda: tack.surface.gamma_random(
                8, dx=0.1, gamma=1, contrast=-1, correlation_length=1
            ),
            "contrast",
        ),
        (lambda: tack.surface.ellipsoid(8, dx=0.1, radius_x=0, radius_y=1), "radius_x"),
    ],
)
def test_bad_generator_arguments_name_the_argument(call, named):
    with pytest.raises(tack.TackError) as info:
        call()
    message = str(info.value)
    assert message.startswith(named), message
    assert not SCENE_OR_RUST.search(message), message
