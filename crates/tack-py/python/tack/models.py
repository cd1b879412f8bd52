"""The adhesion laws and elastic bodies that :func:`tack.pull_off` and :func:`tack.contact`
take as ``law=`` and ``body=``: the laws :class:`JkrLimit` (zero range), :class:`Dugdale` (a
cohesive zone) and the smooth laws :class:`Exponential` and :class:`LennardJones` (made from
their ``range``, or from Tabor's mu with ``from_tabor``); the bodies :class:`HalfSpace` and
:class:`Layer`.

Each object checks its arguments when it is made (``TypeError`` naming the argument and the
type expected, :class:`tack.TackError` naming the argument, the value and the allowed range),
is immutable, compares by value and has a repr that makes it again. They stand for a scene's
``[adhesion]`` and ``[body]`` tables (``docs/scenes.md``).

A viscoelastic solid is one more object of this family, :class:`Viscoelastic`, passed to
:func:`tack.pull_off` as ``material=`` beside ``e_star`` (then the relaxed modulus E0).
"""

from __future__ import annotations

import math
import sys
from typing import Any, Optional, Tuple

from . import _check

__all__ = [
    "Dugdale",
    "Exponential",
    "HalfSpace",
    "JkrLimit",
    "Layer",
    "LennardJones",
    "Viscoelastic",
]


class _Value:
    """Immutable, compared by value; ``_fields`` names the attributes in repr order."""

    _fields: Tuple[str, ...] = ()

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(f"{type(self).__name__} is immutable; make a new one")

    def _set(self, name: str, value: Any) -> None:
        object.__setattr__(self, name, value)

    def _key(self) -> Tuple[Any, ...]:
        return tuple(getattr(self, f) for f in self._fields)

    def __eq__(self, other: Any) -> bool:
        return type(other) is type(self) and other._key() == self._key()

    def __hash__(self) -> int:
        return hash((type(self).__name__,) + self._key())

    def __repr__(self) -> str:
        shown = ", ".join(f"{f}={getattr(self, f)!r}" for f in self._fields)
        return f"tack.{type(self).__name__}({shown})"


class JkrLimit(_Value):
    """The zero-range adhesion law (the default): an element detaches when its tension exceeds
    the Pohrt-Popov stress sigma_c = sqrt(E* gamma / (kappa dx)) (a scene's ``[adhesion] model
    = "jkr_limit"``).

    Args:
        kappa: the Pohrt-Popov constant (finite, > 0); None: tack's 0.473201 (curved crack
            fronts).
    """

    _fields = ("kappa",)
    model = "jkr_limit"

    def __init__(self, kappa: Optional[float] = None) -> None:
        self._set("kappa", _check.optional(_check.positive, "kappa", kappa))

    def _arguments(self) -> dict:
        return {"model": self.model, "kappa": self.kappa, "sigma0": None, "range": None}


class Dugdale(_Value):
    """A Dugdale cohesive zone (Maugis 1992): a constant tension ``sigma0`` wherever the gap is
    below the range h0 = gamma/sigma0 (a scene's ``[adhesion] model = "dugdale"``). The path
    approaches from out of range, so the curve has both branches, and the summary holds the
    Maugis parameter, F_Maugis, the dissipated energy and the jumps.

    Args:
        sigma0: the cohesive tension (finite, > 0).
    """

    _fields = ("sigma0",)
    model = "dugdale"

    def __init__(self, sigma0: float) -> None:
        self._set("sigma0", _check.positive("sigma0", sigma0))

    @classmethod
    def from_lambda(
        cls, lam: float, *, radius: float, e_star: float, gamma: float
    ) -> "Dugdale":
        """The law whose Maugis parameter is ``lam`` for a sphere of ``radius`` (all finite, >
        0): sigma0 = lam / (2 (R/(pi gamma K^2))^(1/3)), K = 4E*/3
        (:func:`tack.analytics.maugis_sigma0`)."""
        from . import analytics

        return cls(analytics.maugis_sigma0(lam=lam, radius=radius, e_star=e_star, gamma=gamma))

    def maugis_lambda(self, *, radius: float, e_star: float, gamma: float) -> float:
        """Maugis' parameter of this law for a sphere of ``radius``
        (:func:`tack.analytics.maugis_lambda`)."""
        from . import analytics

        return analytics.maugis_lambda(
            e_star=e_star, gamma=gamma, radius=radius, sigma0=self.sigma0
        )

    def _arguments(self) -> dict:
        return {"model": self.model, "kappa": None, "sigma0": self.sigma0, "range": None}


class SmoothedDugdale(Dugdale):
    """The Dugdale law with its step smoothed over about an element (a scene's ``[adhesion]
    model = "smoothed_dugdale"``, docs/theory.md section 3.7): the tension ``sigma0`` falls to
    0 across h0 +- s (h0 = gamma/sigma0) by a quintic smoothstep that keeps the work gamma, with
    s two elastic openings of an element under sigma0 (at most h0/2), so the run binds the law
    to its mesh. The Dugdale law's front moves by whole elements; this one's does not, and its
    pull-off is 11 to 62 times closer to Maugis' on the same mesh (for 4-7 times the time). The
    summary holds the Maugis parameter and F_Maugis as the Dugdale law's.

    Args:
        sigma0: the cohesive tension (finite, > 0).
    """

    model = "smoothed_dugdale"


class _Smooth(_Value):
    _fields = ("range",)

    def __init__(self, range: float) -> None:  # noqa: A002 (the scene field's name)
        self._set("range", _check.positive("range", range))

    def tabor(self, *, radius: float, e_star: float, gamma: float) -> float:
        """Tabor's parameter mu = (R gamma^2 / (E*^2 range^3))^(1/3) of this law for a sphere of
        ``radius`` (all finite, > 0). A mu beyond the floats (above 1.8e308, or below the
        normal floats' 2.2e-308) raises :class:`tack.TackError` naming the arguments that make
        it so."""
        radius = _check.positive("radius", radius)
        e_star = _check.positive("e_star", e_star)
        gamma = _check.positive("gamma", gamma)
        return _tabor_length(
            ("range", self.range, "this law's "), radius, e_star, gamma, "Tabor's mu"
        )

    @classmethod
    def from_tabor(
        cls, mu: float, *, radius: float, e_star: float, gamma: float
    ) -> "_Smooth":
        """The law whose Tabor parameter is ``mu`` for a sphere of ``radius`` (all finite, >
        0): range = (R gamma^2 / (E*^2 mu^3))^(1/3). A range beyond the floats (above 1.8e308,
        or below the normal floats' 2.2e-308) raises :class:`tack.TackError` naming the
        arguments that make it so."""
        mu = _check.positive("mu", mu)
        radius = _check.positive("radius", radius)
        e_star = _check.positive("e_star", e_star)
        gamma = _check.positive("gamma", gamma)
        return cls(_tabor_length(("mu", mu, ""), radius, e_star, gamma, "the range"))

    def _arguments(self) -> dict:
        return {"model": self.model, "kappa": None, "sigma0": None, "range": self.range}


def _tabor_length(
    x: Tuple[str, float, str], radius: float, e_star: float, gamma: float, result: str
) -> float:
    """(R gamma^2 / (E*^2 x^3))^(1/3), Tabor's relation read either way (x the range: mu; x
    mu: the range), for finite positive arguments. It equals R^(1/3) (gamma/E*)^(2/3) / x, so
    it is a float whenever that is, whatever its factors' powers: the mantissas and the powers
    of two are taken apart (exactly), so no intermediate overflows or underflows and the cube
    root is taken of a number near 1. ``x`` is (name, value, what the name is: "" for an
    argument); ``result`` the name of what is computed. A result that is inf, or below the
    normal floats (whose digits it would lose, down to 0), raises ``TackError`` naming the
    arguments that push it there."""
    name, value, whose = x
    # v = m 2^k with m in [0.5, 1): the mantissas' quotient lies in [1/8, 32].
    (m_r, k_r), (m_g, k_g), (m_e, k_e), (m_x, k_x) = (
        math.frexp(v) for v in (radius, gamma, e_star, value)
    )
    q, r = divmod(k_r + 2 * k_g - 2 * k_e - 3 * k_x, 3)
    root = (m_r * m_g**2 / (m_e**2 * m_x**3) * 2.0**r) ** (1.0 / 3.0)
    try:
        out = math.ldexp(root, q)
    except OverflowError:
        out = math.inf
    if sys.float_info.min <= out < math.inf:
        return out
    # Name the arguments whose factors push the result out of the floats, largest first.
    logs = {
        "radius": (radius, math.log(radius) / 3.0),
        "gamma": (gamma, 2.0 * math.log(gamma) / 3.0),
        "e_star": (e_star, -2.0 * math.log(e_star) / 3.0),
        name: (value, -math.log(value)),
    }
    log_out = sum(term for _, term in logs.values())
    above = out == math.inf
    sign = 1.0 if above else -1.0
    pushing = sorted(
        ((n, v) for n, (v, term) in logs.items() if sign * term > 0.0),
        key=lambda item: -sign * logs[item[0]][1],
    )
    shown = [f"{whose if n == name else ''}{n} = {_check.num(v)}" for n, v in pushing]
    listed = shown[0] if len(shown) == 1 else ", ".join(shown[:-1]) + " and " + shown[-1]
    formula = f"(radius gamma^2 / (e_star^2 {name}^3))^(1/3)"
    edge = (
        f"above the largest float ({sys.float_info.max:.3g})"
        if above
        else f"below the least normal float ({sys.float_info.min:.3g}; below it floats lose "
        "their digits, down to 0)"
    )
    about = f"1e{log_out / math.log(10.0):+.0f}"
    raise _check.TackError(
        f"{listed} {'puts' if len(shown) == 1 else 'put'} {result} beyond what a float holds: "
        f"{formula} would be about {about}, {edge}"
    )


class Exponential(_Smooth):
    """The exponential adhesion law of the potential V(g) = -gamma exp(-g/range) with a hard
    wall (a scene's ``[adhesion] model = "exponential"``): out of contact the pressure is
    -(gamma/range) exp(-g/range), peak tension gamma/range at the wall. The law of Tamaas,
    ContactMechanics and the contact-mechanics challenge. Every element carries the traction of
    its own gap, so the pull-off converges on meshes whose process zone (8/3 pi) E* range^2 /
    gamma spans about one element (docs/theory.md section 3.9).

    Args:
        range: the range rho (finite, > 0).
    """

    model = "exponential"


class LennardJones(_Smooth):
    """The Lennard-Jones 9-3 law with a hard wall at its equilibrium separation ``range`` = eps
    (a scene's ``[adhesion] model = "lennard_jones"``): with h = g + eps the pressure is
    -(8 gamma / 3 eps) [(eps/h)^3 - (eps/h)^9], zero at the wall, peak tension
    16 gamma / (9 sqrt(3) eps) at h = 3^(1/6) eps, work gamma.

    Args:
        range: the equilibrium separation eps (finite, > 0).
    """

    model = "lennard_jones"


class HalfSpace(_Value):
    """The elastic half-space of effective modulus ``e_star`` (the default body; a scene's
    ``[body] kind = "half_space"``)."""

    _fields = ()

    def _arguments(self) -> dict:
        return {"thickness": None, "poisson": None, "interface": None}


class Layer(_Value):
    """An elastic film of ``thickness`` on a rigid base in place of the half-space (a scene's
    ``[body] kind = "layer"``, docs/theory.md section 2.5); ``e_star`` is then the film's
    E/(1 - nu^2). The closed-form references (F_JKR, ...) stay the half-space's, and results say
    so in a :class:`tack.ReferenceWarning`.

    Args:
        thickness: the film's thickness (finite, > 0).
        poisson: its Poisson ratio nu, in (-1, 0.5].
        interface: ``"bonded"`` (welded to the base, the default) or ``"frictionless"``.
    """

    _fields = ("thickness", "poisson", "interface")

    def __init__(
        self, *, thickness: float, poisson: float, interface: str = "bonded"
    ) -> None:
        self._set("thickness", _check.positive("thickness", thickness))
        nu = _check.real("poisson", poisson)
        if not (-1.0 < nu <= 0.5):
            raise _check.invalid("poisson", nu, "a number in (-1, 0.5]")
        self._set("poisson", nu)
        if not isinstance(interface, str):
            raise TypeError(f"interface: expected a str, got {_check.describe(interface)}")
        if interface not in ("bonded", "frictionless"):
            raise _check.invalid("interface", repr(interface), '"bonded" or "frictionless"')
        self._set("interface", interface)

    def _arguments(self) -> dict:
        return {
            "thickness": self.thickness,
            "poisson": self.poisson,
            "interface": self.interface,
        }


class Viscoelastic(_Value):
    """A viscoelastic half-space, a generalised Maxwell solid of relaxation modulus
    E(t) = E0 + sum_k E_k exp(-t/tau_k) in plane-strain moduli, with ``e_star`` its relaxed E0
    (a scene's ``[material] prony`` and the path's ``[protocol] speed``, ``unload_speed``,
    ``dwell``, ``dwell_steps``; ``docs/theory.md`` section 3.10). The path runs in time: a step
    of the approach lasts its length over the speed, the first step is instantaneous (the
    solid starts at rest), and ``result.curve["time"]`` holds the time. It needs a
    finite-range law (:class:`Dugdale`, :class:`Exponential`, :class:`LennardJones`) and the
    path's ``max_approach`` and ``load_step``.

    Args:
        prony: the arms, a non-empty sequence of pairs ``(E_k, tau_k)`` (each finite, > 0); one
            arm is the standard linear solid of instantaneous modulus E0 + E_1.
        speed: the approach rate of the loading, and of the retraction unless
            ``unload_speed`` (finite, > 0).
        unload_speed: the approach rate of the retraction (finite, > 0); None: ``speed``.
        dwell: time held at the deepest approach (finite, >= 0); None: no hold.
        dwell_steps: the hold's time steps (an int >= 1); None: 20.
    """

    _fields = ("prony", "speed", "unload_speed", "dwell", "dwell_steps")

    def __init__(
        self,
        prony: Any,
        *,
        speed: float,
        unload_speed: Optional[float] = None,
        dwell: Optional[float] = None,
        dwell_steps: Optional[int] = None,
    ) -> None:
        what = "a non-empty sequence of (E_k, tau_k) pairs"
        if isinstance(prony, (str, bytes)) or not hasattr(prony, "__len__"):
            raise TypeError(f"prony: expected {what}, got {_check.describe(prony)}")
        arms = []
        for k, arm in enumerate(prony):
            if isinstance(arm, (str, bytes)) or not hasattr(arm, "__len__") or len(arm) != 2:
                raise TypeError(f"prony[{k}]: expected a pair (E_k, tau_k), got {_check.describe(arm)}")
            arms.append(
                (
                    _check.positive(f"prony[{k}][0]", arm[0]),
                    _check.positive(f"prony[{k}][1]", arm[1]),
                )
            )
        if not arms:
            raise _check.invalid("prony", "[]", what)
        self._set("prony", tuple(arms))
        self._set("speed", _check.positive("speed", speed))
        self._set("unload_speed", _check.optional(_check.positive, "unload_speed", unload_speed))
        self._set("dwell", _check.optional(_check.non_negative, "dwell", dwell))
        self._set(
            "dwell_steps", _check.optional(_check.count, "dwell_steps", dwell_steps)
        )

    def _arguments(self) -> dict:
        return {
            "prony": list(self.prony),
            "speed": self.speed,
            "unload_speed": self.unload_speed,
            "dwell": self.dwell,
            "dwell_steps": self.dwell_steps,
        }


def material_arguments(material: Any) -> dict:
    """``material=`` of :func:`tack.pull_off`: None (the elastic solid ``e_star``) or a
    :class:`Viscoelastic`."""
    if material is None:
        return {}
    if not isinstance(material, Viscoelastic):
        raise TypeError(
            "material: expected None (elastic) or tack.Viscoelastic(prony=..., speed=...), "
            f"got {_check.describe(material)}"
        )
    return material._arguments()


def law_arguments(law: Any) -> dict:
    """``law=`` of :func:`tack.pull_off`: a :class:`JkrLimit`, :class:`Dugdale`,
    :class:`SmoothedDugdale`, :class:`Exponential` or :class:`LennardJones`."""
    if law is None:
        law = JkrLimit()
    if not isinstance(law, (JkrLimit, Dugdale, Exponential, LennardJones)):
        raise TypeError(
            "law: expected tack.JkrLimit(...), tack.Dugdale(sigma0=...), "
            "tack.SmoothedDugdale(sigma0=...), tack.Exponential(range=...) or "
            "tack.LennardJones(range=...), got "
            f"{_check.describe(law)}"
        )
    return law._arguments()


def body_arguments(body: Any) -> dict:
    """``body=`` of :func:`tack.pull_off` and :func:`tack.contact`: a :class:`HalfSpace` or
    :class:`Layer`."""
    if body is None:
        body = HalfSpace()
    if not isinstance(body, (HalfSpace, Layer)):
        raise TypeError(
            "body: expected tack.HalfSpace() or tack.Layer(thickness=..., poisson=...), got "
            f"{_check.describe(body)}"
        )
    return body._arguments()

