"""Periodic full contact is flagged (`ContactResult.full_contact`) and warned about
(`tack.FullContactWarning`), with the approach measured from the deformed mean plane."""

import math
import warnings

import numpy as np
import pytest

import tack

N = 64
DX = 1.0 / N


def rough():
    # Zero-mean heights: partial contact needs min(heights) < approach < 0.
    return tack.surface.random(N, dx=DX, rms=1e-3, hurst=0.8, seed=3)


def waviness(h=0.01):
    # The paper's 2-D waviness (Eq. 4), one wavelength per cell: h[1 - cos(2 pi x) cos(2 pi y)].
    x, y = tack.surface.coordinates(N, dx=DX)
    X, Y = np.meshgrid(x, y, indexing="ij")
    return h * (1 - np.cos(2 * np.pi * X) * np.cos(2 * np.pi * Y))


def test_full_contact_is_flagged_and_warned():
    heights = rough()
    assert abs(heights.mean()) < 1e-15
    with pytest.warns(tack.FullContactWarning) as record:
        state = tack.contact(heights, dx=DX, e_star=1.0, approach=0.01, periodic=True)
    assert state.full_contact and state.converged
    assert state.iterations == 0  # closed form, not iterated
    assert state.n_contact == N * N and state.area == pytest.approx(1.0)
    assert np.all(state.gap == 0.0)
    # The least mean pressure that keeps every element compressive: its least pressure is 0.
    assert state.pressure.min() == 0.0
    assert "full_contact = True" in repr(state)
    [warning] = record
    message = str(warning.message)
    assert warning.filename == __file__  # points at the caller
    assert "approach = 0.01" in message
    assert "deformed mean plane" in message
    assert f"min(heights) = {heights.min():.6g} < approach < mean(heights)" in message
    assert "negative approaches for zero-mean heights" in message
    assert f"mean_pressure = {state.mean_pressure:.6g}" in message


def test_the_mean_pressure_of_full_contact_does_not_follow_the_approach():
    heights = rough()
    with pytest.warns(tack.FullContactWarning, match=r"full contact at 2 of 3 approaches "
                      r"\(approaches\[1\] = 0.01, approaches\[2\] = 1\)"):
        partial, full, deeper = tack.contact_sweep(
            heights, dx=DX, e_star=1.0, approaches=[-1e-3, 0.01, 1.0], periodic=True
        )
    assert not partial.full_contact and 0 < partial.n_contact < N * N
    assert full.full_contact and deeper.full_contact
    # The state in which contact has just become full, whatever the approach beyond the mean.
    assert full.mean_pressure == deeper.mean_pressure > partial.mean_pressure
    np.testing.assert_array_equal(full.pressure, deeper.pressure)


def test_full_contact_starts_at_the_mean_height():
    heights = waviness() + 0.5  # a rigid offset moves the mean plane with it
    mean = heights.mean()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # partial contact: no warning
        below = tack.contact(heights, dx=DX, e_star=1.0, approach=mean - 1e-4, periodic=True)
    assert not below.full_contact and below.n_contact < N * N
    with pytest.warns(tack.FullContactWarning):
        at = tack.contact(heights, dx=DX, e_star=1.0, approach=mean, periodic=True)
    assert at.full_contact
    # For one Fourier mode the periodic operator is exact: full contact takes Johnson's
    # p*_2D = sqrt(2) pi E* h / lambda (Eq. 5), and that is the reported mean pressure.
    p_star = tack.analytics.johnson_2d_p_star(e_star=1.0, h=0.01, wavelength=1.0)
    assert at.mean_pressure == pytest.approx(p_star, rel=1e-9)
    assert below.mean_pressure < p_star


def test_free_grids_are_never_full_contact():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        state = tack.contact(np.zeros((8, 8)), dx=0.1, e_star=1.0, approach=0.01)
    assert state.n_contact == 64 and not state.full_contact


def test_the_warning_is_exported_and_documented(repo):
    assert issubclass(tack.FullContactWarning, UserWarning)
    assert "FullContactWarning" in tack.__all__
    doc = tack.contact.__doc__
    assert "deformed" in doc and "min(heights) < approach <" in doc and "negative" in doc
    guide = " ".join((repo / "docs/python.md").read_text().split())
    assert "FullContactWarning" in guide and "deformed mean plane" in guide
    assert "min(heights) < approach < mean(heights)" in guide
