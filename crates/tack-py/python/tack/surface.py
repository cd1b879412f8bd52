"""Height arrays on tack's grids: seeded random roughness, spheres, coordinates.

Arrays are ``(nx, ny)``; element ``(i, j)`` is centred at ``((i - nx//2)*dx, (j - ny//2)*dx)``,
so the origin (a sphere's apex) is an element centre. Heights add: ``sphere(...) +
random(...)`` is a rough sphere, ready for :func:`tack.pull_off`.

``shape`` is ``n`` or ``(nx, ny)`` (ints in 1..65536), ``dx`` a number > 0; a wrong type
raises ``TypeError`` and a bad value :class:`tack.TackError`, each naming the argument.
"""

from __future__ import annotations

from typing import Any, Optional, Tuple, Union

import numpy as np

from . import _check, _tack
from . import analytics

__all__ = [
    "band",
    "checkerboard",
    "coordinates",
    "ellipsoid",
    "gamma_random",
    "power_law",
    "random",
    "rings",
    "sphere",
    "stripes",
]

Shape = Union[int, Tuple[int, int]]


def _shape(shape: Shape) -> Tuple[int, int]:
    return _check.shape(shape)


def random(
    shape: Shape,
    *,
    dx: float,
    hurst: float,
    rms: Optional[float] = None,
    alpha_star: Optional[float] = None,
    e_star: Optional[float] = None,
    gamma: Optional[float] = None,
    seed: int = 0,
    q0: Optional[float] = None,
    q1: Optional[float] = None,
) -> np.ndarray:
    """Seeded random roughness (Fourier-filtered, ``tack::geometry::rough_surface``).

    Zero mean, rms height ``rms``, amplitude ~ |q|^-(H+1) on the band ``q0 <= |q| <= q1``
    (default the paper's 2 pi/L .. pi/dx, L the longer side), uniform random phases from
    ``seed``. The same seed on the same shape gives the same surface on every machine (and the
    same as a scene's ``roughness.kind = "random"``). The array is one period of a periodic
    pattern.

    Give either ``rms`` (>= 0), or ``alpha_star`` (> 0) with ``e_star`` and ``gamma`` (> 0):
    the rms height that gives that adhesion parameter on this band (Eq. 11 inverted);
    ``e_star`` and ``gamma`` without ``alpha_star`` are refused. ``hurst`` is in (0, 1),
    ``seed`` an int in 0..2**64 - 1, ``q0 < q1`` positive and on the grid's band.

    Raises:
        TypeError: an argument of the wrong type (the message names it).
        TackError: a bad value (a ``ValueError``; the message names the argument).
    """
    nx, ny = _shape(shape)
    dx_ = _check.positive("dx", dx)
    hurst_ = _check.real("hurst", hurst)
    if not 0.0 < hurst_ < 1.0:
        raise _check.invalid("hurst", hurst_, "a number in the open interval (0, 1)")
    seed_ = _check.count("seed", seed, low=0, high=2**64 - 1)
    band_q0, band_q1 = band((nx, ny), dx=dx_)
    q0_ = band_q0 if q0 is None else _check.positive("q0", q0)
    q1_ = band_q1 if q1 is None else _check.positive("q1", q1)
    if (rms is None) == (alpha_star is None):
        raise _tack.TackError(
            "random: give exactly one of rms (the rms height) and alpha_star (with e_star and "
            "gamma)"
        )
    if alpha_star is not None:
        alpha = _check.positive("alpha_star", alpha_star)
        if e_star is None or gamma is None:
            raise _tack.TackError("random: alpha_star needs e_star and gamma")
        e_star_ = _check.positive("e_star", e_star)
        gamma_ = _check.positive("gamma", gamma)
        if not q1_ > q0_:
            raise _check.invalid("q1", q1_, f"> q0 = {_check.num(q0_)}")
        rms_ = analytics.rms_height_from_alpha_star(
            e_star=e_star_, gamma=gamma_, alpha_star=alpha, hurst=hurst_, q0=q0_, q1=q1_
        )
    else:
        if e_star is not None or gamma is not None:
            raise _tack.TackError(
                "random: e_star and gamma are only used with alpha_star; with rms give neither"
            )
        rms_ = _check.non_negative("rms", rms)
    return _tack.rough(nx, ny, dx=dx_, rms=rms_, hurst=hurst_, seed=seed_, q0=q0_, q1=q1_)


def sphere(shape: Shape, *, dx: float, radius: float) -> np.ndarray:
    """The sphere (paraboloid) ``(x^2 + y^2) / (2R)`` at the element centres, apex 0 at the
    origin."""
    nx, ny = _shape(shape)
    dx_ = _check.positive("dx", dx)
    return _tack.sphere(nx, ny, dx=dx_, radius=_check.positive("radius", radius))


def power_law(shape: Shape, *, dx: float, c: float, exponent: float) -> np.ndarray:
    """The axisymmetric body ``c * r^m`` at the element centres, apex 0 at the origin: a cone
    for ``exponent = 1`` (tip included), the paraboloid of R = 1/(2c) for 2 (exponent in
    [1, 16])."""
    nx, ny = _shape(shape)
    dx_ = _check.positive("dx", dx)
    c_ = _check.positive("c", c)
    m = _check.positive("exponent", exponent)
    if not 1.0 <= m <= 16.0:
        raise _check.invalid("exponent", m, "a number in [1, 16]")
    return _tack.power_law(nx, ny, dx=dx_, c=c_, exponent=m)


def ellipsoid(shape: Shape, *, dx: float, radius_x: float, radius_y: float) -> np.ndarray:
    """The elliptic paraboloid ``x^2/(2 Rx) + y^2/(2 Ry)`` at the element centres, apex 0 at
    the origin (a scene's ``geometry.shape = "ellipsoid"``)."""
    nx, ny = _shape(shape)
    dx_ = _check.positive("dx", dx)
    return _tack.ellipsoid(
        nx,
        ny,
        dx=dx_,
        radius_x=_check.positive("radius_x", radius_x),
        radius_y=_check.positive("radius_y", radius_y),
    )


def _two_phase(
    kind: str, shape: Shape, dx: float, gamma: float, gamma_b: float, period: float, **extra: Any
) -> np.ndarray:
    """The two-phase pattern ``kind`` (``tack::geometry::AdhesionPattern``), its arguments
    checked in order (``extra``: real numbers)."""
    nx, ny = _shape(shape)
    return _tack.gamma_pattern(
        nx,
        ny,
        dx=_check.positive("dx", dx),
        kind=kind,
        gamma_a=_check.non_negative("gamma", gamma),
        gamma_b=_check.non_negative("gamma_b", gamma_b),
        period=_check.positive("period", period),
        **{name: _check.real(name, value) for name, value in extra.items()},
    )


def stripes(
    shape: Shape,
    *,
    dx: float,
    gamma: float,
    gamma_b: float,
    period: float,
    fraction: float = 0.5,
) -> np.ndarray:
    """A work of adhesion in stripes across x (bands parallel to y), for
    :func:`tack.pull_off`'s ``gamma``: ``gamma_b`` on the share ``fraction`` of each ``period``
    centred on x = k*period, ``gamma`` elsewhere (a scene's ``adhesion.pattern = "stripes"``;
    an element takes the value at its centre)."""
    return _two_phase("stripes", shape, dx, gamma, gamma_b, period, fraction=fraction)


def rings(
    shape: Shape,
    *,
    dx: float,
    gamma: float,
    gamma_b: float,
    period: float,
    fraction: float = 0.5,
) -> np.ndarray:
    """A work of adhesion in rings about the origin: ``gamma_b`` on a central disc of radius
    ``fraction*period/2`` and on rings about r = k*period, ``gamma`` elsewhere
    (``adhesion.pattern = "rings"``)."""
    return _two_phase("rings", shape, dx, gamma, gamma_b, period, fraction=fraction)


def checkerboard(
    shape: Shape, *, dx: float, gamma: float, gamma_b: float, period: float
) -> np.ndarray:
    """A work of adhesion in squares of side ``period/2``, ``gamma`` on the one centred at the
    origin, ``gamma_b`` on its neighbours (``adhesion.pattern = "checkerboard"``)."""
    return _two_phase("checkerboard", shape, dx, gamma, gamma_b, period)


def gamma_random(
    shape: Shape,
    *,
    dx: float,
    gamma: float,
    contrast: float,
    correlation_length: float,
    seed: int = 1,
) -> np.ndarray:
    """A seeded log-normal work of adhesion of mean ``gamma`` and coefficient of variation
    ``contrast``, Gaussian correlation length ``correlation_length`` (one continuous field per
    seed, periodic over the array; ``adhesion.pattern = "random"``)."""
    nx, ny = _shape(shape)
    return _tack.gamma_pattern(
        nx,
        ny,
        dx=_check.positive("dx", dx),
        kind="random",
        gamma_a=_check.positive("gamma", gamma),
        contrast=_check.non_negative("contrast", contrast),
        correlation_length=_check.positive("correlation_length", correlation_length),
        seed=_check.count("seed", seed, low=0, high=2**64 - 1),
    )


def coordinates(shape: Shape, *, dx: float) -> Tuple[np.ndarray, np.ndarray]:
    """Element-centre coordinates ``(x, y)`` (1-D arrays of length nx and ny):
    ``x[i] = (i - nx//2)*dx``; ``np.meshgrid(x, y, indexing="ij")`` gives 2-D fields."""
    nx, ny = _shape(shape)
    return _tack.coordinates(nx, ny, dx=_check.positive("dx", dx))


def band(shape: Shape, *, dx: float) -> Tuple[float, float]:
    """The paper's roughness band on the grid, ``(q0, q1) = (2 pi/L, pi/dx)``, L the longer
    side."""
    nx, ny = _shape(shape)
    return _tack.band(nx, ny, dx=_check.positive("dx", dx))
