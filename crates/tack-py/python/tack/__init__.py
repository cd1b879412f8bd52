"""tack: the adhesive strength of rough elastic contacts, from Python.

A boundary-element solver for an elastic half-space (or film) pressed against, and pulled off,
a rigid rough body, with JKR-limit adhesion (the Pohrt-Popov detachment criterion; Li, Pohrt &
Popov 2019), a Dugdale cohesive zone or a smooth law (exponential, Lennard-Jones). The
numerical work runs in Rust (the ``tack`` crates) with the GIL released; arrays go in and come
out as numpy arrays.

- :func:`run` runs a scene (a TOML file or text, ``docs/scenes.md``) and returns a
  :class:`Result`; :func:`read` reads a result file.
- :func:`pull_off` pulls a body given as a numpy height array off the half-space, with a
  default load-then-retract path.
- :func:`contact` solves non-adhesive contact of a height array at one approach,
  :func:`contact_sweep` at several in turn.
- The adhesion law and the elastic body are objects (:mod:`tack.models`): ``law=``
  :class:`JkrLimit`, :class:`Dugdale`, :class:`SmoothedDugdale`, :class:`Exponential` or
  :class:`LennardJones`, ``body=`` :class:`HalfSpace` or :class:`Layer`.
- A result that may not be trusted issues a :class:`TackWarning` of its kind
  (:class:`UnderResolvedWarning`, :class:`ReferenceWarning`, ...) when the run returns.
- :mod:`tack.surface` makes height arrays (seeded random roughness, spheres);
  :mod:`tack.analytics` holds the closed forms, keyword-only (Hertz, JKR, Kendall, Johnson,
  the paper's fits, Maugis-Dugdale).

Conventions (as in the Rust crates): arrays are ``(nx, ny)``; element ``(i, j)`` is centred at
``((i - nx//2)*dx, (j - ny//2)*dx)``; a height is the gap at zero approach (higher = farther
from the half-space); the approach is positive when pressing; pressure and force are positive
when compressive, so the pull-off force is negative. Units are any consistent set.

An argument of the wrong type raises ``TypeError`` naming the argument and the type it
expects (numbers are ``int``, ``float`` or numpy integer/float scalars; ``str``, ``bytes``,
``None``, ``bool`` and complex numbers are not). A bad value raises :class:`TackError` (a
``ValueError``) or a subclass, with a message that names the argument (for scenes, the scene's
field), the value and the allowed range. Ctrl-C stops a running solve within about 0.1 s with
``KeyboardInterrupt``.
"""

from __future__ import annotations

import os
import sys
import warnings
from typing import Any, Callable, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _check, _tack
from ._tack import (
    ContactResult,
    InternalError,
    Result,
    ResultFileError,
    SceneError,
    SolverError,
    TackError,
)
from . import _warnings, analytics, surface
from ._warnings import (
    ConvergenceWarning,
    EdgeContactWarning,
    FullContactWarning,
    LoadingHistoryWarning,
    ReferenceWarning,
    RichardsonWarning,
    TackWarning,
    UnderResolvedWarning,
)
from .models import (
    Dugdale,
    Exponential,
    HalfSpace,
    JkrLimit,
    Layer,
    LennardJones,
    SmoothedDugdale,
    Viscoelastic,
    body_arguments,
    law_arguments,
    material_arguments,
)

__version__: str = _tack.__version__

#: Largest value accepted for ``threads``.
MAX_THREADS: int = _tack.MAX_THREADS

__all__ = [
    "ContactResult",
    "ConvergenceWarning",
    "Dugdale",
    "EdgeContactWarning",
    "Exponential",
    "FullContactWarning",
    "HalfSpace",
    "InternalError",
    "JkrLimit",
    "Layer",
    "LennardJones",
    "LoadingHistoryWarning",
    "MAX_THREADS",
    "ReferenceWarning",
    "Result",
    "ResultFileError",
    "RichardsonWarning",
    "SceneError",
    "SmoothedDugdale",
    "SolverError",
    "TackError",
    "Viscoelastic",
    "TackWarning",
    "UnderResolvedWarning",
    "analytics",
    "contact",
    "contact_sweep",
    "pull_off",
    "read",
    "run",
    "surface",
]

PathLike = Union[str, "os.PathLike[str]"]
Progress = Union[bool, Callable[[Dict[str, Any]], Any], None]


class _StderrProgress:
    """``progress=True``: one line on ``sys.stderr``, rewritten in place."""

    def __init__(self) -> None:
        self.width = 0

    def __call__(self, info: Dict[str, Any]) -> None:
        line = (
            f"tack: step {info['step']} ({info['phase']}), d = {info['approach']:.6g}, "
            f"F = {info['force']:.6g}, bonded = {info['n_bonded']}"
        )
        pad = max(self.width - len(line), 0)
        self.width = len(line)
        sys.stderr.write("\r" + line + " " * pad)
        sys.stderr.flush()

    def close(self) -> None:
        if self.width:
            sys.stderr.write("\n")
            sys.stderr.flush()


def _progress(progress: Progress) -> Optional[Callable[[Dict[str, Any]], Any]]:
    if progress is None or (_check.is_bool(progress) and not progress):
        return None
    if _check.is_bool(progress):
        return _StderrProgress()
    if callable(progress):
        return progress
    raise TypeError(
        "progress: expected True/False or a callable taking one dict, got "
        f"{_check.describe(progress)}"
    )


def _threads(threads: Optional[int]) -> Optional[int]:
    return _check.threads(threads, MAX_THREADS)


def _snapshots(snapshots: Union[str, int, Sequence[int]]) -> Any:
    what = "'pull_off', 'all', 'none', an int k ≥ 1 (every k-th step) or a list of step indices"
    if isinstance(snapshots, str):
        if snapshots not in ("pull_off", "all", "none"):
            raise _check.invalid("snapshots", repr(snapshots), what)
        return snapshots
    if _check.is_integer(snapshots):
        if int(snapshots) < 1:
            raise _check.invalid("snapshots", int(snapshots), what)
        return {"every": int(snapshots)}
    if isinstance(snapshots, (list, tuple, np.ndarray)):
        steps = []
        for k, step in enumerate(snapshots):
            steps.append(_check.count(f"snapshots[{k}]", step, low=0))
        return {"steps": steps}
    raise TypeError(f"snapshots: expected {what}, got {_check.describe(snapshots)}")


def _closing(callback: Optional[Callable[[Dict[str, Any]], Any]]) -> None:
    if isinstance(callback, _StderrProgress):
        callback.close()


def run(
    scene: PathLike,
    *,
    overrides: Optional[Mapping[str, Any]] = None,
    threads: Optional[int] = None,
    progress: Progress = False,
    richardson: bool = False,
) -> Result:
    """Runs a scene in memory and returns its :class:`Result` (no file is written).

    Args:
        scene: the scene, as a path (``str`` or ``os.PathLike``) of a TOML scene file, or as
            TOML text (a ``str`` containing a newline; relative paths in it, such as
            ``roughness.path``, resolve against the current directory). The schema is
            ``docs/scenes.md``.
        overrides: ``{"dotted.key": value}`` applied before validation, exactly as the CLI's
            ``--set dotted.key=value``; values are written as TOML literals (bool, int, float,
            str, lists and dicts of them), e.g. ``{"grid.n": 96, "material.gamma": 0.1,
            "output.snapshots": "pull_off"}``.
        threads: threads for the solve, 1..``MAX_THREADS`` (default: all cores). Its FFTs are
            split into lanes across them; the result is bit-identical for any count.
        progress: ``True`` draws a progress line on ``sys.stderr``; a callable is called with a
            dict (``step``, ``phase``, ``approach``, ``force``, ``area``, ``n_bonded``,
            ``converged``) at most every 0.1 s and after the last step, from a worker thread
            during the run (the calling thread watches for Ctrl-C meanwhile). An exception it
            raises stops the run and propagates.
        richardson: also run the scene at twice the element size and record the Richardson
            extrapolation at the law's order in the summary (``pull_off_force_richardson``,
            ``richardson_order``: ``2F(dx) - F(2dx)`` for the criterion and the Dugdale law,
            ``F(dx) + (F(dx) - F(2dx))/3`` for the smooth laws) with the error estimate of the
            fine force (``pull_off_error_estimate``). Random
            roughness needs an explicit ``roughness.q1 <= pi/(2 dx)``.

    Raises:
        TypeError: an argument of the wrong type (``scene`` not a str or os.PathLike,
            ``overrides`` not a dict or with a value that has no TOML form, ``threads`` not an
            int, ``richardson`` not a bool, ``progress`` neither a bool nor a callable).
        SceneError: the scene is unreadable or invalid (the message names the scene's field;
            an override that cannot be applied is named ``overrides["key"] = value``).
        TackError: ``threads`` outside 1..``MAX_THREADS``.
        KeyboardInterrupt: Ctrl-C during the run.

    Warns:
        TackWarning: one per sentence of ``summary["warnings"]``, in the class of its kind
            (:class:`UnderResolvedWarning`, :class:`ReferenceWarning`,
            :class:`LoadingHistoryWarning`, :class:`FullContactWarning`, ...), naming the
            scene's fields.
    """
    if isinstance(scene, os.PathLike):
        where: Dict[str, Any] = {"path": _check.path("scene", scene)}
    elif isinstance(scene, str):
        if "\n" in scene:
            where = {"text": scene, "base_dir": os.getcwd()}
        else:
            where = {"path": scene}
    else:
        raise TypeError(
            "scene: expected a path (str or os.PathLike) or TOML text (str), got "
            f"{_check.describe(scene)}"
        )
    if overrides is not None and not isinstance(overrides, Mapping):
        raise TypeError(
            "overrides: expected a dict of dotted keys to values, got "
            f"{_check.describe(overrides)}"
        )
    n_threads = _threads(threads)
    fine_and_coarse = _check.flag("richardson", richardson)
    callback = _progress(progress)
    try:
        result = _tack.run_scene(
            **where,
            overrides=dict(overrides) if overrides is not None else None,
            richardson=fine_and_coarse,
            threads=n_threads,
            progress=callback,
        )
    finally:
        _closing(callback)
    _warnings.issue(result.summary["warnings"], "run")
    return result


def read(path: PathLike) -> Result:
    """Reads a result file (written by :meth:`Result.write`, ``tack run`` or ``tack surface``).

    Raises:
        ResultFileError: the file is missing, not HDF5, or not a tack result.
        TypeError: ``path`` is not a ``str`` or ``os.PathLike``.
    """
    return _tack.read(_check.path("path", path))


def _gamma(
    value: Any, shape: Tuple[int, ...], reference: Any
) -> Tuple[float, Optional[np.ndarray]]:
    """``pull_off``'s ``gamma`` and ``gamma_reference``: a number > 0 (the reference), or an
    array of the heights' shape (finite, >= 0, mean > 0) whose reference is ``gamma_reference``
    when given, else its mean; returns the reference and the array (or None)."""
    note = " (a pull-off needs adhesion; for contact without it use tack.contact)"
    if _check._ndim(value) == 2:
        g = _check.heights(value, "gamma")
        if g.shape != tuple(shape):
            raise _check.invalid(
                "gamma.shape", g.shape, f"the heights' shape {tuple(shape)}"
            )
        bad = g < 0.0
        if bad.any():
            index, shown = _check._first_bad(bad)
            raise _check.invalid(f"gamma{shown}", float(g[index]), "a finite number >= 0")
        mean = float(g.mean())
        if not mean > 0.0:
            raise _check.invalid("gamma.mean()", mean, "a number > 0" + note)
        if reference is not None:
            return _check.positive("gamma_reference", reference), g
        return mean, g
    if _check._ndim(value) > 0 and not isinstance(value, (str, bytes)):
        raise TypeError(
            "gamma: expected a real number (int or float) or a 2-D array of the heights' shape, "
            f"got {_check.describe(value)}"
        )
    if reference is not None:
        raise TackError(
            "gamma_reference is given with a uniform gamma: it is the reference of a gamma "
            "array only (a uniform gamma is its own reference); leave it out"
        )
    return _check.positive("gamma", value, note), None


def pull_off(
    heights: Any,
    *,
    dx: float,
    e_star: float,
    gamma: Any,
    law: Union[JkrLimit, Dugdale, SmoothedDugdale, Exponential, LennardJones] = JkrLimit(),
    body: Union[HalfSpace, Layer] = HalfSpace(),
    material: Optional[Viscoelastic] = None,
    gamma_reference: Optional[float] = None,
    periodic: bool = False,
    radius: Optional[float] = None,
    max_approach: Optional[float] = None,
    load_step: Optional[float] = None,
    unload_step: Optional[float] = None,
    coarse_unload_step: Optional[float] = None,
    refine_pull_off: bool = False,
    richardson: bool = False,
    snapshots: Union[str, int, Sequence[int]] = "pull_off",
    threads: Optional[int] = None,
    progress: Progress = False,
) -> Result:
    """Pulls a rigid body given as a height array off an elastic body (the half-space, or a
    film) and returns the :class:`Result` of the run.

    Args:
        heights: 2-D array ``(nx, ny)`` of the body's heights, the gap at zero approach
            (higher = farther from the half-space), element ``(i, j)`` centred at
            ``((i - nx//2)*dx, (j - ny//2)*dx)``; e.g. ``tack.surface.sphere(...) +
            tack.surface.random(...)``.
        dx: element size (> 0).
        e_star: effective modulus E* (> 0).
        gamma: work of adhesion (> 0; without adhesion use :func:`contact`), or a 2-D array
            of the heights' shape with one gamma per element (finite, >= 0, mean > 0):
            patterned adhesion (e.g. ``tack.surface.stripes(...)``; the summary then holds
            ``gamma_min``, ``gamma_mean``, ``gamma_max`` and ``result.surface["gamma"]`` the
            array).
        law: the adhesion law, :class:`tack.JkrLimit` (default: the zero-range Pohrt-Popov
            criterion, ``kappa`` its constant) or :class:`tack.Dugdale` (a cohesive zone of
            tension ``sigma0``; the path approaches from out of range, so the curve has both
            branches, and the summary holds ``maugis_lambda`` and ``f_maugis`` (spheres),
            ``dissipated_energy`` with ``dissipated_energy_sampling``, the jumps in and out and
            the apparent work of adhesion of each branch), :class:`tack.SmoothedDugdale` (the
            same with its step smoothed over about an element), or a smooth law,
            :class:`tack.Exponential` or :class:`tack.LennardJones` (every element carries the
            traction of its gap; the
            summary holds ``tabor_mu`` (spheres), ``range``, ``peak_tension`` and
            ``process_zone_elements``).
        body: :class:`tack.HalfSpace` (default) or :class:`tack.Layer` (a film on a rigid
            base; the closed-form references such as ``f_jkr`` stay the half-space's, and a
            :class:`tack.ReferenceWarning` says so).
        material: None (the elastic solid ``e_star``) or :class:`tack.Viscoelastic` (a
            Prony series whose relaxed modulus is ``e_star``, and the path's speeds): the path
            runs in time and ``result.curve["time"]`` holds it. It needs a finite-range
            ``law``, ``max_approach`` and ``load_step``; ``refine_pull_off`` is refused.
        gamma_reference: with a gamma array only: the reference work of adhesion of ``f_jkr``,
            the ratios and the default path (> 0). The rule, the same as a scene's: the
            reference is the gamma given explicitly as a number (``gamma`` when uniform; a
            scene's ``material.gamma``, phase a of its pattern); an array alone is referred to
            its mean. Give ``gamma_reference=0.1`` with ``gamma=tack.surface.stripes(...,
            gamma=0.1, ...)`` for the numbers of the scene with ``material.gamma = 0.1``.
        periodic: the array is one period of a periodic body (default: free, non-periodic).
            On a periodic grid the approach is measured from the deformed mean plane (see
            :func:`contact`), and steps in full contact (approach >= mean of the heights) are
            flagged in ``curve["full_contact"]`` and left out of the pull-off force.
        radius: radius R of the sphere the body approximates; default: fitted by least squares
            (a paraboloid with free vertex), accepted when its rise over the grid is at least
            half the roughness range.
        max_approach, load_step, unload_step, coarse_unload_step: the path, instead of the
            default rule (``max_approach`` finite, the steps > 0; ``load_step`` needs
            ``max_approach``, and the load then starts one step past the first touch).
        refine_pull_off: the refined retraction: coarse steps (``coarse_unload_step``, default
            0.2 d_s) all the way, and every stretch of two coarse steps that may hold the
            pull-off (and the last one when the tension still grew before contact was lost)
            retraced in steps of ``unload_step`` from the solver state saved at its start. The
            same pull-off as the fine path on the same approaches, in a quarter to two thirds
            of the steps (``docs/theory.md`` section 3.5).
        richardson: also pull off the array sampled at the centres of the grid of twice the
            element size (even sides needed) along the same path, and extrapolate
            at the law's order: ``2F(dx) - F(2dx)`` for the criterion and the Dugdale law (first
            order), ``F(dx) + (F(dx) - F(2dx))/3`` for the smooth laws (second).
            ``result.richardson`` holds ``fine``, ``coarse``, ``extrapolated``, ``order``,
            ``error_estimate``, ``ratio``, ``aliased_rms``. Exact for a
            smooth body and for roughness band-limited to ``q1 <= pi/(2 dx)``; with content
            above it the coarse run samples another body and a
            :class:`tack.RichardsonWarning` says so. A gamma array is refused.
        snapshots: which steps keep pressure and bonded fields: ``"pull_off"`` (the pull-off
            step and the last contact), ``"all"``, ``"none"``, every k-th step (an int) or a
            list of step indices.
        threads, progress: as for :func:`run`.

    The default path (the paper's rough-sphere runs): with d_s = (R gamma^2/E*^2)^(1/3), a
    load to ``max_approach = apex + top of the roughness + 3 d_s`` (apex and roughness
    relative to the fitted paraboloid; a smooth sphere bonds a disc of about 1.6 a_c, deep
    enough for the JKR pull-off), then retraction by 0.2 d_s while the force is compressive
    and by min(0.02, 0.2 dx/a_c) d_s through the tensile part (a_c the JKR pull-off radius)
    until nothing is bonded. Under the zero-range law (:class:`tack.JkrLimit`) the load is one
    step from the first touch. Under a finite-range law (:class:`tack.Dugdale`,
    :class:`tack.Exponential`, :class:`tack.LennardJones`) it starts out of the law's reach
    (the Dugdale range gamma/sigma0; under a smooth law where its tension has fallen to 1e-4
    of the peak) before the first touch and steps in by the fine retraction step, under a
    smooth law by ``range``/50 where that is longer (up to the coarse step), so the curve holds the approach branch and the
    jump in. A reach so long that this load would take 100 000 steps or more (the path's cap;
    ``pull_off`` has no argument to raise it) is refused with a :class:`tack.SceneError`: give
    a path of your own (``max_approach``, ``load_step`` and ``unload_step``) or a shorter
    range (a scene run by :func:`tack.run` may set its own ``[protocol] max_steps``). On a
    free grid the Hertz radius at that depth plus 30% must fit in the array. A body without a
    radius (flat, wavy) needs ``max_approach`` and ``unload_step``. The summary's ``f_jkr``
    and ``pull_off_ratio`` refer to the sphere of radius R; ``provenance["scene"]`` records
    the rule's numbers, and the heights are stored in ``result.surface``.

    Raises:
        TypeError: an argument of the wrong type (a str, bytes, None, bool or complex number
            where a number is expected; an array of strings, objects, booleans or complex
            numbers; a ``law`` or ``body`` that is not one of tack's objects); the message
            names the argument.
        TackError: a bad value (a ``ValueError``; the message names the argument, the value and
            the allowed range), or a path that cannot work (e.g. an array too small for the
            contact at ``max_approach``).
        KeyboardInterrupt: Ctrl-C during the run.

    Warns:
        TackWarning: one per sentence of ``summary["warnings"]``, in the class of its kind
            (:class:`UnderResolvedWarning`, :class:`ReferenceWarning`,
            :class:`EdgeContactWarning`, :class:`ConvergenceWarning`, ...), naming the
            arguments.
    """
    array = _check.heights(heights)
    gamma, gamma_map = _gamma(gamma, array.shape, gamma_reference)
    args = dict(
        dx=_check.positive("dx", dx),
        e_star=_check.positive("e_star", e_star),
        gamma=gamma,
        gamma_map=gamma_map,
        periodic=_check.flag("periodic", periodic),
        radius=_check.optional(_check.positive, "radius", radius),
        max_approach=_check.optional(_check.finite, "max_approach", max_approach),
        load_step=_check.optional(_check.positive, "load_step", load_step),
        unload_step=_check.optional(_check.positive, "unload_step", unload_step),
        coarse_unload_step=_check.optional(
            _check.positive, "coarse_unload_step", coarse_unload_step
        ),
        refine_pull_off=_check.flag("refine_pull_off", refine_pull_off),
        richardson=_check.flag("richardson", richardson),
        snapshots=_snapshots(snapshots),
        threads=_threads(threads),
        **law_arguments(law),
        **body_arguments(body),
        **material_arguments(material),
    )
    callback = _progress(progress)
    try:
        result = _tack.pull_off(array, **args, progress=callback)
    finally:
        _closing(callback)
    _warnings.issue(result.summary["warnings"], "pull_off")
    return result


def contact(
    heights: Any,
    *,
    dx: float,
    e_star: float,
    approach: float,
    body: Union[HalfSpace, Layer] = HalfSpace(),
    periodic: bool = False,
    tolerance: Optional[float] = None,
    max_iterations: Optional[int] = None,
    threads: Optional[int] = None,
) -> ContactResult:
    """Frictionless non-adhesive contact of a height array pressed by ``approach``; one
    :class:`ContactResult` (for several approaches in turn, :func:`contact_sweep`).

    Args:
        heights: 2-D array ``(nx, ny)`` of the rigid body's heights (the gap at zero approach).
        dx: element size (> 0).
        e_star: effective modulus E* (> 0; of a :class:`tack.Layer`, its E/(1 - nu^2)).
        approach: the prescribed approach d, a number (positive = pressing; see *Periodic
            grids*).
        body: :class:`tack.HalfSpace` (default) or :class:`tack.Layer` (an elastic film on a
            rigid base, docs/theory.md section 2.5).
        periodic: the array is one period of a periodic body (default: free, non-periodic).
        tolerance, max_iterations: the conjugate-gradient stopping rule (``0 < tolerance <
            1``, default 1e-10; ``max_iterations >= 1``, default 5000).
        threads: threads of the solve, 1..``MAX_THREADS`` (default: every core); the result is
            the same bits on any count.

    Returns:
        A :class:`ContactResult` (``pressure`` and ``gap`` arrays of the heights' shape,
        ``force``, ``mean_pressure``, ``area``, ``n_contact`` (an int), ``converged``,
        ``iterations``, ``full_contact``, ...).

    Periodic grids: the periodic half-space has no rigid-body mode, so the approach is measured
    from the mean plane of the *deformed* surface, not from the first touch: the mean gap is
    ``mean(heights) - approach``. Contact is partial only for ``min(heights) < approach <
    mean(heights)``, so for zero-mean heights (``tack.surface.random``) the approaches of
    partial contact are *negative*. At ``approach >= mean(heights)`` every gap is closed (full
    contact) and the approach no longer sets the load: the pressure is then fixed only up to
    its mean, and the result (``full_contact = True``) is the state in which contact has just
    become full, the least mean pressure that keeps every element compressive (its least
    element pressure is 0), the same for every approach beyond ``mean(heights)``. It is
    computed in closed form (``iterations = 0``, ``converged = True``). Free grids are
    measured from the undeformed body (contact starts at ``approach = min(heights)``) and are
    never flagged as full contact.

    Raises:
        TypeError: an argument of the wrong type (a str, bytes, None, bool or complex number
            where a number is expected, a sequence of approaches (use
            :func:`contact_sweep`); an array of strings, objects, booleans or complex
            numbers); the message names the argument.
        TackError: a bad value (a ``ValueError``; the message names the argument, the value and
            the allowed range).

    Warns:
        FullContactWarning: a periodic contact is full (the message gives the range of
            approaches of partial contact).
    """
    if _check._ndim(approach) != 0 or isinstance(approach, (str, bytes)):
        hint = " (for several approaches in turn use tack.contact_sweep(..., approaches=...))"
        if isinstance(approach, (str, bytes)) or approach is None:
            hint = ""
        raise TypeError(
            f"approach: expected a real number, got {_check.describe(approach)}{hint}"
        )
    d = _check.finite_as("approach", approach, "a real number")
    return _contact(heights, [d], True, dx, e_star, body, periodic, tolerance,
                    max_iterations, threads)[0]


def contact_sweep(
    heights: Any,
    *,
    dx: float,
    e_star: float,
    approaches: Sequence[float],
    body: Union[HalfSpace, Layer] = HalfSpace(),
    periodic: bool = False,
    tolerance: Optional[float] = None,
    max_iterations: Optional[int] = None,
    threads: Optional[int] = None,
) -> "list[ContactResult]":
    """:func:`contact` at each of ``approaches`` (a non-empty 1-D sequence of finite numbers)
    in turn, each solve warm-started from the previous; Ctrl-C is checked between them.
    Returns a list of :class:`ContactResult`, one per approach, always a list (also for one
    approach). The other arguments, the errors and :class:`FullContactWarning` are
    :func:`contact`'s."""
    if _check._ndim(approaches) == 0 and not isinstance(approaches, np.ndarray):
        raise TypeError(
            "approaches: expected a 1-D sequence of real numbers, got "
            f"{_check.describe(approaches)} (for one approach use tack.contact(..., "
            "approach=...))"
        )
    values, _ = _check.approaches(approaches, "approaches")
    return _contact(heights, values, False, dx, e_star, body, periodic, tolerance,
                    max_iterations, threads)


def _contact(heights, approaches, single, dx, e_star, body, periodic, tolerance,
             max_iterations, threads):  # type: ignore[no-untyped-def]
    array = _check.heights(heights)
    args = dict(
        dx=_check.positive("dx", dx),
        e_star=_check.positive("e_star", e_star),
        periodic=_check.flag("periodic", periodic),
        tolerance=_check.optional(_check.fraction, "tolerance", tolerance),
        max_iterations=_check.optional(_check.count, "max_iterations", max_iterations),
        threads=_threads(threads),
        **body_arguments(body),
    )
    states = _tack.contact(array, approaches=approaches, **args)
    _warn_full_contact(states, array, single)
    return states


def _warn_full_contact(
    states: "list[ContactResult]", heights: np.ndarray, single: bool
) -> None:
    full = [k for k, s in enumerate(states) if s.full_contact]
    if not full:
        return
    if single:
        where = f"approach = {states[0].approach:.6g}"
        function = "contact"
    else:
        listed = ", ".join(f"approaches[{k}] = {states[k].approach:.6g}" for k in full[:3])
        more = ", ..." if len(full) > 3 else ""
        where = f"{len(full)} of {len(states)} approaches ({listed}{more})"
        function = "contact_sweep"
    first = states[full[0]]
    warnings.warn(
        f"tack.{function}: full contact at {where}. On a periodic grid the approach is measured "
        "from the deformed mean plane: contact is partial only for min(heights) = "
        f"{float(heights.min()):.6g} < approach < mean(heights) = {float(heights.mean()):.6g} "
        "(negative approaches for zero-mean heights such as tack.surface.random), and full "
        "for approach >= mean(heights). In full contact every gap is closed and the approach "
        "no longer sets the load: the result is the state in which contact has just become "
        "full (the least mean pressure that keeps every element compressive, mean_pressure = "
        f"{first.mean_pressure:.6g}), the same for every approach >= mean(heights), computed "
        "in closed form (iterations = 0). Check result.full_contact.",
        FullContactWarning,
        stacklevel=4,
    )
