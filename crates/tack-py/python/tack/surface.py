"""Height arrays on tack's grids: seeded random roughness, spheres, coordinates.

Arrays are ``(nx, ny)``; element ``(i, j)`` is centred at ``((i - nx//2)*dx, (j - ny//2)*dx)``,
so the origin (a sphere's apex) is an element centre. Heights add: ``sphere(...) +
random(...)`` is a rough sphere, ready for :func:`tack.pull_off`.
"""

from __future__ import annotations

import numbers
from typing import Optional, Tuple, Union

import numpy as np

from . import _tack
from . import analytics

__all__ = ["band", "coordinates", "random", "sphere"]

Shape = Union[int, Tuple[int, int]]


def _shape(shape: Shape) -> Tuple[int, int]:
    if isinstance(shape, numbers.Integral) and not isinstance(shape, bool):
        n = int(shape)
        return n, n
    try:
        nx, ny = shape  # type: ignore[misc]
    except (TypeError, ValueError):
        raise TypeError(f"shape: expected n or (nx, ny), got {shape!r}") from None
    return int(nx), int(ny)


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

    Give either ``rms``, or ``alpha_star`` with ``e_star`` and ``gamma``: the rms height that
    gives that adhesion parameter on this band (Eq. 11 inverted).
    """
    nx, ny = _shape(shape)
    band_q0, band_q1 = band((nx, ny), dx=dx)
    q0_ = band_q0 if q0 is None else float(q0)
    q1_ = band_q1 if q1 is None else float(q1)
    if (rms is None) == (alpha_star is None):
        raise _tack.TackError(
            "random: give exactly one of rms (the rms height) and alpha_star (with e_star and "
            "gamma)"
        )
    if alpha_star is not None:
        if e_star is None or gamma is None:
            raise _tack.TackError("random: alpha_star needs e_star and gamma")
        if not float(alpha_star) > 0.0:
            raise _tack.TackError(
                f"alpha_star = {alpha_star} is invalid: must be a finite number > 0"
            )
        rms = analytics.rms_height_from_alpha_star(
            e_star, gamma, alpha_star, hurst, q0_, q1_
        )
    return _tack.rough(
        nx,
        ny,
        dx=float(dx),
        rms=float(rms),  # type: ignore[arg-type]
        hurst=float(hurst),
        seed=int(seed),
        q0=q0_,
        q1=q1_,
    )


def sphere(shape: Shape, *, dx: float, radius: float) -> np.ndarray:
    """The sphere (paraboloid) ``(x^2 + y^2) / (2R)`` at the element centres, apex 0 at the
    origin."""
    nx, ny = _shape(shape)
    return _tack.sphere(nx, ny, dx=float(dx), radius=float(radius))


def coordinates(shape: Shape, *, dx: float) -> Tuple[np.ndarray, np.ndarray]:
    """Element-centre coordinates ``(x, y)`` (1-D arrays of length nx and ny):
    ``x[i] = (i - nx//2)*dx``; ``np.meshgrid(x, y, indexing="ij")`` gives 2-D fields."""
    nx, ny = _shape(shape)
    return _tack.coordinates(nx, ny, dx=float(dx))


def band(shape: Shape, *, dx: float) -> Tuple[float, float]:
    """The paper's roughness band on the grid, ``(q0, q1) = (2 pi/L, pi/dx)``, L the longer
    side."""
    nx, ny = _shape(shape)
    return _tack.band(nx, ny, dx=float(dx))
