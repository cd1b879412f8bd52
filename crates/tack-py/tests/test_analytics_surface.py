"""Closed forms (scalars and arrays) and the surface helpers."""

import math

import numpy as np
import pytest

import tack
from tack import analytics


def test_jkr_closed_forms():
    e, g, r = 1.0, 0.125, 8.0
    assert analytics.jkr_pull_off_force(gamma=g, radius=r) == pytest.approx(-1.5 * math.pi * g * r)
    a_c = analytics.jkr_pull_off_radius(e_star=e, gamma=g, radius=r)
    assert a_c == pytest.approx((9 * math.pi * g * r * r / (8 * e)) ** (1 / 3))
    # The pull-off is the least force on the JKR curve, at a_c.
    assert analytics.jkr_force_from_radius(e_star=e, gamma=g, radius=r, a=a_c) == pytest.approx(
        analytics.jkr_pull_off_force(gamma=g, radius=r)
    )
    assert analytics.jkr_approach_from_radius(e_star=e, gamma=g, radius=r, a=a_c) == pytest.approx(
        analytics.jkr_pull_off_approach(e_star=e, gamma=g, radius=r)
    )
    assert math.isnan(analytics.jkr_force_from_approach(e_star=e, gamma=g, radius=r, d=-10.0))
    assert analytics.kendall_pull_off(e_star=1.0, gamma=1 / (8 * math.pi), a=1.0) == pytest.approx(1.0)


def test_fits():
    assert analytics.lambda_star(alpha_star=0.3619) == pytest.approx(1.023)
    assert analytics.lambda_fit(alpha=0.1) == pytest.approx(0.65 * 0.1 - 0.025)
    a = analytics.alpha_star(
        e_star=1.0, gamma=1e-4, h=0.002, hurst=0.5, q0=2 * math.pi, q1=128 * math.pi
    )
    h = analytics.rms_height_from_alpha_star(
        e_star=1.0, gamma=1e-4, alpha_star=a, hurst=0.5, q0=2 * math.pi, q1=128 * math.pi
    )
    assert h == pytest.approx(0.002)
    assert analytics.johnson_alpha(e_star=1.0, gamma=1.0, h=1.0, wavelength=math.pi**2 / 2) == pytest.approx(1.0)


def test_vectorised():
    d = np.linspace(0.0, 0.01, 5)
    f = analytics.hertz_force(e_star=1.0, radius=1.0, d=d)
    assert isinstance(f, np.ndarray) and f.shape == (5,)
    np.testing.assert_allclose(f, 4 / 3 * d**1.5)
    assert isinstance(analytics.hertz_force(e_star=1.0, radius=1.0, d=0.01), float)
    grid = analytics.lambda_star(alpha_star=np.array([[0.1, 0.2], [0.3, 0.4]]))
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
    assert analytics.power_law_pull_off_force(e_star=1.0, gamma=0.05, c=0.5, exponent=1.0) == pytest.approx(-0.343775, rel=1e-5)
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
    assert analytics.alpha_star(e_star=1.0, gamma=1e-4, h=h, hurst=0.5, q0=q0, q1=q1) == pytest.approx(0.3)


def test_jkr_pull_off_radius_takes_keywords_only():
    # The user's trap: jkr_pull_off_radius(R, E, g) = 0.19 where a_c = 3.05.
    with pytest.raises(TypeError, match="positional"):
        analytics.jkr_pull_off_radius(8.0, 1.0, 0.125)
    a_c = analytics.jkr_pull_off_radius(radius=8.0, e_star=1.0, gamma=0.125)
    assert a_c == pytest.approx(3.05, abs=0.005)


def test_maugis_limits_jkr_and_dmt():
    e, g, r = 1.0, 0.1, 1.0
    sigma = lambda lam: analytics.maugis_sigma0(lam=lam, e_star=e, gamma=g, radius=r)
    # sigma0 <-> lambda round trip, and lambda = 2 sigma0 (R/(pi gamma K^2))^(1/3).
    k = 4 / 3 * e
    assert sigma(2.0) == pytest.approx(2.0 / (2 * (r / (math.pi * g * k * k)) ** (1 / 3)))
    assert analytics.maugis_lambda(e_star=e, gamma=g, radius=r, sigma0=sigma(2.0)) == (
        pytest.approx(2.0)
    )
    # lambda -> inf: JKR, -1.5 pi gamma R (about -1.5 - 0.164/lambda^2 in pi gamma R).
    jkr = analytics.maugis_pull_off_force(e_star=e, gamma=g, radius=r, sigma0=sigma(1e3))
    assert jkr == pytest.approx(-1.5 * math.pi * g * r, rel=1e-5)
    # lambda -> 0: DMT, -2 pi gamma R (about -2 + 1.72 lambda^1.5).
    dmt = analytics.maugis_pull_off_force(e_star=e, gamma=g, radius=r, sigma0=sigma(1e-4))
    assert dmt == pytest.approx(-2.0 * math.pi * g * r, rel=1e-5)
    # The jump-out tends to JKR's (-(3/4)^(1/3) D, -5/6 pi gamma R); D = (pi^2 g^2 R/K^2)^(1/3).
    big = sigma(1e3)
    d_scale = (math.pi**2 * g * g * r / k**2) ** (1 / 3)
    out_d = analytics.maugis_jump_out_approach(e_star=e, gamma=g, radius=r, sigma0=big)
    out_f = analytics.maugis_jump_out_force(e_star=e, gamma=g, radius=r, sigma0=big)
    assert out_d == pytest.approx(-(0.75 ** (1 / 3)) * d_scale, rel=1e-3)
    assert out_f == pytest.approx(-5 / 6 * math.pi * g * r, rel=1e-3)
    # The jump-in is at d = -h0 = -gamma/sigma0.
    s2 = sigma(2.0)
    d_in = analytics.maugis_jump_in_approach(e_star=e, gamma=g, radius=r, sigma0=s2)
    assert d_in == pytest.approx(-g / s2)
    assert analytics.maugis_jump_in_force(e_star=e, gamma=g, radius=r, sigma0=s2) < 0
    # The loop dissipates energy above lambda_c, none is evaluated below (NaN).
    w = analytics.maugis_dissipated_energy(e_star=e, gamma=g, radius=r, sigma0=s2)
    assert w > 0
    assert math.isnan(analytics.maugis_dissipated_energy(e_star=e, gamma=g, radius=r,
                                                         sigma0=sigma(0.5)))
    assert analytics.MAUGIS_LAMBDA_CRITICAL == pytest.approx(0.937947, abs=1e-6)
    # The curve: compressive at a deep approach, no stable contact state far out.
    f = analytics.maugis_force_from_approach(e_star=e, gamma=g, radius=r, sigma0=s2,
                                             d=np.array([0.5, -10.0]))
    assert f[0] > 0 and math.isnan(f[1])
    with pytest.raises(ValueError, match=r'^branch = \'x\' is invalid'):
        analytics.maugis_force_from_approach(e_star=e, gamma=g, radius=r, sigma0=s2, d=0.0,
                                             branch="x")
    with pytest.raises(ValueError, match=r"^gamma = 0 is invalid"):
        analytics.maugis_lambda(e_star=e, gamma=0.0, radius=r, sigma0=1.0)
    # The law object built from lambda carries the same sigma0.
    assert tack.Dugdale.from_lambda(2.0, radius=r, e_star=e, gamma=g).sigma0 == pytest.approx(s2)
