"""Closed forms (scalars and arrays) and the surface helpers."""

import math

import numpy as np
import pytest

import tack
from tack import analytics


def test_jkr_closed_forms():
    e, g, r = 1.0, 0.125, 8.0
    assert analytics.jkr_pull_off_force(g, r) == pytest.approx(-1.5 * math.pi * g * r)
    a_c = analytics.jkr_pull_off_radius(e, g, r)
    assert a_c == pytest.approx((9 * math.pi * g * r * r / (8 * e)) ** (1 / 3))
    # The pull-off is the least force on the JKR curve, at a_c.
    assert analytics.jkr_force_from_radius(e, g, r, a_c) == pytest.approx(
        analytics.jkr_pull_off_force(g, r)
    )
    assert analytics.jkr_approach_from_radius(e, g, r, a_c) == pytest.approx(
        analytics.jkr_pull_off_approach(e, g, r)
    )
    assert math.isnan(analytics.jkr_force_from_approach(e, g, r, -10.0))
    assert analytics.kendall_pull_off(1.0, 1 / (8 * math.pi), 1.0) == pytest.approx(1.0)


def test_fits():
    assert analytics.lambda_star(0.3619) == pytest.approx(1.023)
    assert analytics.lambda_fit(0.1) == pytest.approx(0.65 * 0.1 - 0.025)
    a = analytics.alpha_star(1.0, 1e-4, 0.002, 0.5, 2 * math.pi, 128 * math.pi)
    h = analytics.rms_height_from_alpha_star(1.0, 1e-4, a, 0.5, 2 * math.pi, 128 * math.pi)
    assert h == pytest.approx(0.002)
    assert analytics.johnson_alpha(1.0, 1.0, 1.0, math.pi**2 / 2) == pytest.approx(1.0)


def test_vectorised():
    d = np.linspace(0.0, 0.01, 5)
    f = analytics.hertz_force(1.0, 1.0, d)
    assert isinstance(f, np.ndarray) and f.shape == (5,)
    np.testing.assert_allclose(f, 4 / 3 * d**1.5)
    assert isinstance(analytics.hertz_force(1.0, 1.0, 0.01), float)
    grid = analytics.lambda_star(np.array([[0.1, 0.2], [0.3, 0.4]]))
    assert grid.shape == (2, 2)


def test_surfaces():
    x, y = tack.surface.coordinates((5, 4), dx=0.5)
    np.testing.assert_array_equal(x, [-1.0, -0.5, 0.0, 0.5, 1.0])
    np.testing.assert_array_equal(y, [-1.0, -0.5, 0.0, 0.5])
    s = tack.surface.sphere((5, 4), dx=0.5, radius=2.0)
    X, Y = np.meshgrid(x, y, indexing="ij")
    np.testing.assert_allclose(s, (X**2 + Y**2) / 4.0)
    cone = tack.surface.power_law((5, 4), dx=0.5, c=0.5, exponent=1.0)
    np.testing.assert_allclose(cone, 0.5 * np.hypot(X, Y))
    with pytest.raises(ValueError, match="exponent"):
        tack.surface.power_law(4, dx=0.5, c=0.5, exponent=0.5)
    # The cone's exact pull-off (E* = 1, gamma = 0.05, c = 0.5): the example's F_MDR.
    assert analytics.power_law_pull_off_force(1.0, 0.05, 0.5, 1.0) == pytest.approx(-0.343775, rel=1e-5)
    r = tack.surface.random(64, dx=1 / 64, rms=0.01, hurst=0.5, seed=7)
    assert r.shape == (64, 64)
    assert abs(r.mean()) < 1e-15 and r.std() == pytest.approx(0.01)
    np.testing.assert_array_equal(r, tack.surface.random(64, dx=1 / 64, rms=0.01, hurst=0.5, seed=7))
    assert not np.array_equal(r, tack.surface.random(64, dx=1 / 64, rms=0.01, hurst=0.5, seed=8))
    q0, q1 = tack.surface.band(64, dx=1 / 64)
    assert q0 == pytest.approx(2 * math.pi) and q1 == pytest.approx(64 * math.pi)
    by_alpha = tack.surface.random(64, dx=1 / 64, hurst=0.5, alpha_star=0.3, e_star=1.0,
                                   gamma=1e-4, seed=7)
    h = by_alpha.std()
    assert analytics.alpha_star(1.0, 1e-4, h, 0.5, q0, q1) == pytest.approx(0.3)
