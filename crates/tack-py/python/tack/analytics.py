"""Closed forms of tack (the ``tack::analytics`` crate), numbered as in Li, Pohrt & Popov (2019).

Every function takes keyword arguments only (``jkr_pull_off_radius(e_star=1.0, gamma=0.125,
radius=8.0)``: the orders of the formulas differ, so a positional call could silently swap
them) and floats, and returns a float; give numpy arrays (or anything array-like)
for any argument and it is applied elementwise (numpy broadcasting), returning an array (an
empty array gives an empty array). Signs follow tack: approach positive = pressing, force
positive = compressive, so pull-off forces and approaches are negative. ``docs/theory.md``
derives each formula.

Arguments are checked before any formula runs: a wrong type (``str``, ``bytes``, ``None``,
``bool``, complex numbers, arrays of those or of objects) raises ``TypeError`` naming the
argument; a value outside the formula's domain raises :class:`tack.TackError` (a
``ValueError``) naming the argument (``radius[2] = -1 is invalid: must be a finite number >
0``): ``e_star``, ``radius``, ``wavelength``, ``dx``, ``kappa``, ``q0``, ``q1`` finite and > 0;
``gamma``, ``h``, ``a``, ``alpha``, ``alpha_star`` finite and >= 0 (``alpha_star`` > 0 in
:func:`rms_height_from_alpha_star`); ``hurst`` in (0, 1); ``d`` finite; and ``q1 > q0``;
for the Maugis-Dugdale forms ``sigma0`` and ``lam`` finite and > 0 and ``gamma`` > 0.

The Maugis-Dugdale closed forms (Maugis 1992; ``tack-analytics/src/maugis.rs``): the parameter
lambda = 2 sigma0 (R/(pi gamma K^2))^(1/3), K = 4E*/3 (:func:`maugis_lambda`, and back,
:func:`maugis_sigma0`), the pull-off force under approach control (from -1.5 pi gamma R, JKR,
as lambda -> inf, to -2 pi gamma R, DMT, as lambda -> 0), the force on the stable branches at an
approach, the jumps in and out, and the energy a load-retract cycle dissipates. They are the
Rust functions, bound, not formulas written again here.
"""

from __future__ import annotations

from typing import Any, Callable, Union

import numpy as np

from . import _check, _tack

__all__ = [
    "alpha_star",
    "critical_stress",
    "hertz_contact_radius",
    "hertz_force",
    "hertz_max_pressure",
    "jkr_approach_from_radius",
    "jkr_approach_scale",
    "jkr_force_from_approach",
    "jkr_force_from_radius",
    "jkr_pull_off_approach",
    "jkr_pull_off_force",
    "jkr_pull_off_radius",
    "johnson_2d_p_star",
    "johnson_alpha",
    "kendall_pull_off",
    "lambda_fit",
    "lambda_star",
    "power_law_pull_off_force",
    "rms_height_from_alpha_star",
    "westergaard_p_star",
    "MAUGIS_LAMBDA_CRITICAL",
    "maugis_dissipated_energy",
    "maugis_force_from_approach",
    "maugis_jump_in_approach",
    "maugis_jump_in_force",
    "maugis_jump_out_approach",
    "maugis_jump_out_force",
    "maugis_lambda",
    "maugis_pull_off_force",
    "maugis_sigma0",
]

#: Maugis' lambda_c = (9 pi / (16 (pi - 1)))^(1/3) = 0.937947...: above it the stable contact
#: branch ends at a jump-out with a > 0 and a cycle dissipates energy on it; at and below it the
#: branch continues onto the separated one.
MAUGIS_LAMBDA_CRITICAL: float = _tack.MAUGIS_LAMBDA_CRITICAL

ArrayLike = Union[float, "np.ndarray[Any, Any]", Any]


#: The arguments of each closed form, in order (the names in messages).
_ARGS = {
    "hertz_force": ("e_star", "radius", "d"),
    "hertz_contact_radius": ("radius", "d"),
    "hertz_max_pressure": ("e_star", "radius", "d"),
    "jkr_pull_off_force": ("gamma", "radius"),
    "jkr_pull_off_approach": ("e_star", "gamma", "radius"),
    "jkr_pull_off_radius": ("e_star", "gamma", "radius"),
    "jkr_approach_scale": ("e_star", "gamma", "radius"),
    "jkr_force_from_radius": ("e_star", "gamma", "radius", "a"),
    "jkr_approach_from_radius": ("e_star", "gamma", "radius", "a"),
    "jkr_force_from_approach": ("e_star", "gamma", "radius", "d"),
    "kendall_pull_off": ("e_star", "gamma", "a"),
    "power_law_pull_off_force": ("e_star", "gamma", "c", "exponent"),
    "johnson_alpha": ("e_star", "gamma", "h", "wavelength"),
    "westergaard_p_star": ("e_star", "h", "wavelength"),
    "johnson_2d_p_star": ("e_star", "h", "wavelength"),
    "lambda_fit": ("alpha",),
    "alpha_star": ("e_star", "gamma", "h", "hurst", "q0", "q1"),
    "rms_height_from_alpha_star": ("e_star", "gamma", "alpha_star", "hurst", "q0", "q1"),
    "lambda_star": ("alpha_star",),
    "critical_stress": ("e_star", "gamma", "dx", "kappa"),
    "maugis_lambda": ("e_star", "gamma", "radius", "sigma0"),
    "maugis_pull_off_force": ("e_star", "gamma", "radius", "sigma0"),
    "maugis_pull_off_hat": ("lam",),
    "maugis_dissipated_energy": ("e_star", "gamma", "radius", "sigma0"),
    "maugis_force_contact": ("e_star", "gamma", "radius", "sigma0", "d"),
    "maugis_force_separated": ("e_star", "gamma", "radius", "sigma0", "d"),
    "maugis_jump_out_approach": ("e_star", "gamma", "radius", "sigma0"),
    "maugis_jump_out_force": ("e_star", "gamma", "radius", "sigma0"),
    "maugis_jump_in_approach": ("e_star", "gamma", "radius", "sigma0"),
    "maugis_jump_in_force": ("e_star", "gamma", "radius", "sigma0"),
}


def _apply(f: Callable[..., float], *args: Any) -> Any:
    """``f`` of the arguments (named as ``f``'s Python signature), checked by
    ``_check.closed_form_args``; elementwise over arrays."""
    name = f.__name__
    names = _ARGS[name]
    values, scalar = _check.closed_form_args(name, names, args)
    if name == "rms_height_from_alpha_star":
        _check.above(names, values, "alpha_star", 0.0)
    if "q0" in names:
        _check.above(names, values, "q1", "q0")
    if name.startswith("maugis") and "gamma" in names:
        _check.above(names, values, "gamma", 0.0)
    if scalar:
        return f(*values)
    return np.vectorize(f, otypes=[float])(*values)


def hertz_force(*, e_star: ArrayLike, radius: ArrayLike, d: ArrayLike) -> Any:
    """Hertz force F = (4/3) E* sqrt(R) d^(3/2) of a sphere pressed by d; 0 for d <= 0."""
    return _apply(_tack.hertz_force, e_star, radius, d)


def hertz_contact_radius(*, radius: ArrayLike, d: ArrayLike) -> Any:
    """Hertz contact radius a = sqrt(R d); 0 for d <= 0."""
    return _apply(_tack.hertz_contact_radius, radius, d)


def hertz_max_pressure(*, e_star: ArrayLike, radius: ArrayLike, d: ArrayLike) -> Any:
    """Hertz central pressure p0 = 2 E* a / (pi R), a = sqrt(R d)."""
    return _apply(_tack.hertz_max_pressure, e_star, radius, d)


def jkr_pull_off_force(*, gamma: ArrayLike, radius: ArrayLike) -> Any:
    """JKR pull-off force F_JKR = -(3/2) pi gamma R (Eq. 7; negative = tensile)."""
    return _apply(_tack.jkr_pull_off_force, gamma, radius)


def jkr_pull_off_approach(*, e_star: ArrayLike, gamma: ArrayLike, radius: ArrayLike) -> Any:
    """Approach at the JKR pull-off, d_JKR = -(3 pi^2 gamma^2 R / (64 E*^2))^(1/3) (Eq. 8)."""
    return _apply(_tack.jkr_pull_off_approach, e_star, gamma, radius)


def jkr_pull_off_radius(*, e_star: ArrayLike, gamma: ArrayLike, radius: ArrayLike) -> Any:
    """Contact radius at the JKR pull-off, a_c = (9 pi gamma R^2 / (8 E*))^(1/3)."""
    return _apply(_tack.jkr_pull_off_radius, e_star, gamma, radius)


def jkr_approach_scale(*, e_star: ArrayLike, gamma: ArrayLike, radius: ArrayLike) -> Any:
    """JKR approach scale d_s = (R gamma^2 / E*^2)^(1/3)."""
    return _apply(_tack.jkr_approach_scale, e_star, gamma, radius)


def jkr_force_from_radius(
    *, e_star: ArrayLike, gamma: ArrayLike, radius: ArrayLike, a: ArrayLike
) -> Any:
    """JKR force at contact radius a: F = 4 E* a^3 / (3 R) - sqrt(8 pi gamma E* a^3)."""
    return _apply(_tack.jkr_force_from_radius, e_star, gamma, radius, a)


def jkr_approach_from_radius(
    *, e_star: ArrayLike, gamma: ArrayLike, radius: ArrayLike, a: ArrayLike
) -> Any:
    """JKR approach at contact radius a: d = a^2 / R - sqrt(2 pi gamma a / E*)."""
    return _apply(_tack.jkr_approach_from_radius, e_star, gamma, radius, a)


def jkr_force_from_approach(
    *, e_star: ArrayLike, gamma: ArrayLike, radius: ArrayLike, d: ArrayLike
) -> Any:
    """JKR force on the stable branch at approach d (approach control); NaN below the
    jump-off approach, where the sphere has detached."""
    return _apply(_tack.jkr_force_from_approach, e_star, gamma, radius, d)


def power_law_pull_off_force(
    *, e_star: ArrayLike, gamma: ArrayLike, c: ArrayLike, exponent: ArrayLike
) -> Any:
    """Exact JKR-limit pull-off force (negative: tensile) of the axisymmetric body c*r^m
    (exponent m >= 1; a cone for m = 1), by the method of dimensionality reduction."""
    return _apply(_tack.power_law_pull_off_force, e_star, gamma, c, exponent)


def kendall_pull_off(*, e_star: ArrayLike, gamma: ArrayLike, a: ArrayLike) -> Any:
    """Kendall pull-off force magnitude of a flat circular punch of radius a,
    sqrt(8 pi a^3 E* gamma) (positive number; the force itself is tensile)."""
    return _apply(_tack.kendall_pull_off, e_star, gamma, a)


def johnson_alpha(
    *, e_star: ArrayLike, gamma: ArrayLike, h: ArrayLike, wavelength: ArrayLike
) -> Any:
    """Johnson's adhesion parameter of a waviness of amplitude h and wavelength lambda,
    alpha = sqrt(2 lambda gamma / (pi^2 h^2 E*)) (Eq. 3)."""
    return _apply(_tack.johnson_alpha, e_star, gamma, h, wavelength)


def westergaard_p_star(*, e_star: ArrayLike, h: ArrayLike, wavelength: ArrayLike) -> Any:
    """Mean pressure of complete contact of a 1D waviness, p*_1D = pi E* h / lambda."""
    return _apply(_tack.westergaard_p_star, e_star, h, wavelength)


def johnson_2d_p_star(*, e_star: ArrayLike, h: ArrayLike, wavelength: ArrayLike) -> Any:
    """Mean pressure of complete contact of a 2D waviness, p*_2D = sqrt(2) pi E* h / lambda
    (Eq. 5)."""
    return _apply(_tack.johnson_2d_p_star, e_star, h, wavelength)


def lambda_fit(*, alpha: ArrayLike) -> Any:
    """Pull-off enhancement of a sphere with 2D waviness, F_ad/F_JKR = Lambda(alpha) (Eq. 9):
    0.27/alpha^2 exp(-0.14/alpha^2) + 1 for alpha >= 0.24, 0.65 alpha - 0.025 below."""
    return _apply(_tack.lambda_fit, alpha)


def alpha_star(
    *,
    e_star: ArrayLike,
    gamma: ArrayLike,
    h: ArrayLike,
    hurst: ArrayLike,
    q0: ArrayLike,
    q1: ArrayLike,
) -> Any:
    """Adhesion parameter of random roughness of rms height h, Hurst exponent H on the band
    q0..q1: alpha* = sqrt(4 gamma q1^(0.8H - 1) / (pi E* h^2 q0^(0.8H))) (Eq. 11)."""
    return _apply(_tack.alpha_star, e_star, gamma, h, hurst, q0, q1)


def rms_height_from_alpha_star(
    *,
    e_star: ArrayLike,
    gamma: ArrayLike,
    alpha_star: ArrayLike,
    hurst: ArrayLike,
    q0: ArrayLike,
    q1: ArrayLike,
) -> Any:
    """The rms height h of random roughness with adhesion parameter alpha* (Eq. 11 inverted)."""
    return _apply(_tack.rms_height_from_alpha_star, e_star, gamma, alpha_star, hurst, q0, q1)


def lambda_star(*, alpha_star: ArrayLike) -> Any:
    """Pull-off of a randomly rough sphere relative to JKR, |F_ad/F_JKR| ~ Lambda*(alpha*) =
    1.023 exp(-((alpha* - 0.3619)/0.1188)^2) (Eq. 12)."""
    return _apply(_tack.lambda_star, alpha_star)


def critical_stress(
    *, e_star: ArrayLike, gamma: ArrayLike, dx: ArrayLike, kappa: ArrayLike = 0.473201
) -> Any:
    """Detachment stress of a bonded element of size dx, sigma_c = sqrt(E* gamma / (kappa dx))
    (Pohrt & Popov; kappa defaults to tack's 0.473201)."""
    return _apply(_tack.critical_stress, e_star, gamma, dx, kappa)


def maugis_lambda(
    *, e_star: ArrayLike, gamma: ArrayLike, radius: ArrayLike, sigma0: ArrayLike
) -> Any:
    """Maugis' parameter lambda = 2 sigma0 (R / (pi gamma K^2))^(1/3), K = 4E*/3 (Maugis 1992):
    lambda -> inf is JKR, lambda -> 0 is DMT."""
    return _apply(_tack.maugis_lambda, e_star, gamma, radius, sigma0)


def maugis_sigma0(
    *, lam: ArrayLike, e_star: ArrayLike, gamma: ArrayLike, radius: ArrayLike
) -> Any:
    """The Dugdale tension sigma0 of Maugis' parameter ``lam`` (the inverse of
    :func:`maugis_lambda`, which is proportional to sigma0: ``lam / maugis_lambda(...,
    sigma0=1)``)."""
    values, _ = _check.closed_form_args("maugis_sigma0", ("lam",), (lam,))
    unit = maugis_lambda(e_star=e_star, gamma=gamma, radius=radius, sigma0=1.0)
    # lambda per unit sigma0, 2 (R / (pi gamma K^2))^(1/3), leaves the floats for extreme
    # materials (E* = 1e200: K^2 overflows, the unit is 0): a ValueError naming them, not a
    # ZeroDivisionError.
    if not np.all(np.isfinite(unit) & (np.asarray(unit) > 0.0)):

        def shown(v: ArrayLike) -> str:
            return _check.num(float(v)) if np.ndim(v) == 0 else "(an array)"

        raise _check.TackError(
            f"e_star = {shown(e_star)}, gamma = {shown(gamma)} and radius = {shown(radius)} "
            "put Maugis' lambda per unit sigma0, 2 (R / (pi gamma K^2))^(1/3) with K = "
            "4 e_star / 3, beyond the floats (0 or not finite); scale the units of the "
            "material"
        )
    return values[0] / unit


def maugis_pull_off_force(
    *, e_star: ArrayLike, gamma: ArrayLike, radius: ArrayLike, sigma0: ArrayLike
) -> Any:
    """The Maugis-Dugdale pull-off force under approach control (negative = tensile; Maugis
    1992): -1.5 pi gamma R (JKR) as lambda -> inf, -2 pi gamma R (DMT) as lambda -> 0."""
    return _apply(_tack.maugis_pull_off_force, e_star, gamma, radius, sigma0)


def maugis_force_from_approach(
    *,
    e_star: ArrayLike,
    gamma: ArrayLike,
    radius: ArrayLike,
    sigma0: ArrayLike,
    d: ArrayLike,
    branch: str = "contact",
) -> Any:
    """The force at approach ``d`` on the stable part (under approach control) of the Maugis
    curve's ``branch``: ``"contact"`` (contact radius a > 0, the branch of large loads) or
    ``"separated"`` (a = 0: only the cohesive zone pulls; lambda < lambda_c only). NaN where that
    branch has no stable state at ``d`` (below its jump-out; the free sphere, F = 0, belongs
    to neither)."""
    if not isinstance(branch, str):
        raise TypeError(f"branch: expected a str, got {_check.describe(branch)}")
    if branch == "contact":
        f = _tack.maugis_force_contact
    elif branch == "separated":
        f = _tack.maugis_force_separated
    else:
        raise _check.invalid("branch", repr(branch), '"contact" or "separated"')
    return _apply(f, e_star, gamma, radius, sigma0, d)


def maugis_dissipated_energy(
    *, e_star: ArrayLike, gamma: ArrayLike, radius: ArrayLike, sigma0: ArrayLike
) -> Any:
    """The energy an approach-controlled load-retract cycle of the Maugis-Dugdale sphere
    dissipates, the area of its loop (positive), for lambda > :data:`MAUGIS_LAMBDA_CRITICAL`;
    NaN at and below it (the separated branch takes part; not evaluated)."""
    return _apply(_tack.maugis_dissipated_energy, e_star, gamma, radius, sigma0)


def maugis_jump_out_approach(
    *, e_star: ArrayLike, gamma: ArrayLike, radius: ArrayLike, sigma0: ArrayLike
) -> Any:
    """The approach at which the retracting Maugis-Dugdale sphere jumps out to the free state
    (the end of the stable contact branch for lambda > lambda_c, of the stable separated
    branch below; the JKR jump-off -(3/4)^(1/3) D as lambda -> inf)."""
    return _apply(_tack.maugis_jump_out_approach, e_star, gamma, radius, sigma0)


def maugis_jump_out_force(
    *, e_star: ArrayLike, gamma: ArrayLike, radius: ArrayLike, sigma0: ArrayLike
) -> Any:
    """The force just before the jump-out of :func:`maugis_jump_out_approach` (-5/6 pi gamma R
    as lambda -> inf)."""
    return _apply(_tack.maugis_jump_out_force, e_star, gamma, radius, sigma0)


def maugis_jump_in_approach(
    *, e_star: ArrayLike, gamma: ArrayLike, radius: ArrayLike, sigma0: ArrayLike
) -> Any:
    """The approach at which the approaching free sphere is caught: d = -h0 = -gamma/sigma0
    (the least gap reaches the range)."""
    return _apply(_tack.maugis_jump_in_approach, e_star, gamma, radius, sigma0)


def maugis_jump_in_force(
    *, e_star: ArrayLike, gamma: ArrayLike, radius: ArrayLike, sigma0: ArrayLike
) -> Any:
    """The force just after the jump-in (tensile; on the separated branch for lambda <=
    (9/32)^(1/3), on the contact branch above)."""
    return _apply(_tack.maugis_jump_in_force, e_star, gamma, radius, sigma0)
