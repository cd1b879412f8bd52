//! A smooth law of the caller's own ([`AdhesionLaw::custom`](super::AdhesionLaw::custom)):
//! the curve is checked once against what the solver assumes of it (its derivative and
//! continuity, its scaling with γ, its work, its peak, its reach and beyond, whether it
//! stiffens, whether it falls past its peak) and then shared.

use std::sync::Arc;

use super::{Curve, Law};
use crate::SolverError;

/// A number in a message as the scene fields print it (`tack_fields::num`: `1`, not `1e0`).
struct Num(f64);

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&tack_fields::num(self.0))
    }
}

/// Intervals of the graded sampling `g = ℓ(eᵗ − 1)`, `t ∈ [0, ln(1 + reach/ℓ)]`, on which a
/// curve is checked (even, for Simpson's rule): spacing about `1e-3(g + ℓ)` for a reach of
/// 10⁸ℓ, so a curve must vary on scales above `1e-3ℓ` near its wall, its [`Curve::length`]
/// being its smallest length. Simpson's error on the built-in laws is below 1e-10 here.
const SAMPLES: usize = 20_000;

/// Relative tolerance of the work `−∫p dg = γ` and of the sampled peak tension against
/// [`Curve::peak`]: a curve the solver and the references (JKR, DMT, Tabor's μ) read as a law
/// of work γ must be one to this accuracy; it refuses a scale that is off, not the sampling.
const WORK_TOLERANCE: f64 = 1e-3;

/// Relative tolerance of [`Curve::stiffness`] against differences of [`Curve::pressure`] (a
/// central difference of step 1e-6 of the local length scale, a one-sided one of second order
/// at the wall: errors near 1e-10), plus 1e-6 of the curve's stiffness scale `peak/ℓ` where
/// both vanish: it catches a wrong sign or a missing factor, which break Newton's steps.
const SLOPE_TOLERANCE: f64 = 1e-4;

/// Between neighbouring samples the pressure's change must be its slope's integral (Simpson on
/// the interval) within this fraction of the peak: it catches a jump of the pressure between
/// samples (a Dugdale step written as a curve), which Newton cannot follow.
const JUMP_TOLERANCE: f64 = 1e-6;

/// What is left of the peak tension at [`Curve::reach`] and beyond, at most: there the solver
/// crops the law away (the built-in laws leave [`super::REACH_FRACTION`], 1e-8).
const REACH_TOLERANCE: f64 = 1e-6;

/// Gaps beyond the reach, in reaches, where the pressure must still be finite and negligible
/// (the solver evaluates every element's gap, however far).
const BEYOND: [f64; 5] = [1.01, 2.0, 10.0, 1e3, 1e6];

/// Works of adhesion at which the curve must scale as `γ` times its value at 1 (relative
/// 1e-12: a rounding or two): the solver scales laws by γ maps and reads the peak, reach and
/// length at the scene's γ.
const GAMMAS: [f64; 2] = [0.37, 3.1];

/// A smooth law of the caller's own, shared between the solvers and results that use it: two
/// are equal when they are one curve (one allocation), so a saved solver state restores only
/// into a solver of the same curve.
#[derive(Debug, Clone)]
pub struct CustomCurve(pub(super) Arc<dyn Law>);

impl PartialEq for CustomCurve {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

impl CustomCurve {
    /// Checks `curve` ([`check`]) and shares it.
    pub(super) fn new<C: Curve + 'static>(curve: C) -> Result<Self, SolverError> {
        check(&curve)?;
        Ok(Self(Arc::new(curve)))
    }
}

/// The error of a curve that fails a check.
fn refuse(curve: &dyn Curve, method: &'static str, reason: String) -> SolverError {
    SolverError::Curve {
        name: curve.name(),
        method,
        reason,
    }
}

/// Checks a curve: its name is a new one ([`check_name`]) and its shape ([`check_shape`]).
pub(super) fn check(curve: &dyn Curve) -> Result<(), SolverError> {
    check_name(curve)?;
    check_shape(curve)
}

/// A custom law's name: lowercase ASCII letters, digits and `_`, not a built-in law's.
fn check_name(curve: &dyn Curve) -> Result<(), SolverError> {
    let name = curve.name();
    let fine = |c: char| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_';
    if name.is_empty() || !name.chars().all(fine) {
        return Err(refuse(
            curve,
            "Curve::name",
            "must be a non-empty name of lowercase ASCII letters, digits and '_' (it is written \
             to results as adhesion_model)"
                .into(),
        ));
    }
    if super::AdhesionLaw::models().any(|m| m == name) {
        return Err(refuse(
            curve,
            "Curve::name",
            format!(
                "is the name of a built-in law; a custom law needs its own (the built-ins: {})",
                super::AdhesionLaw::models().collect::<Vec<_>>().join(", ")
            ),
        ));
    }
    Ok(())
}

/// Whether `x` is within `tol` (false for NaN).
fn within(x: f64, tol: f64) -> bool {
    x.abs() <= tol
}

/// Checks a curve of work of adhesion 1 on `SAMPLES` graded gaps up to its reach and a few
/// beyond: its length, peak and reach are finite and positive; it scales as γ (`GAMMAS`); its
/// pressure and stiffness are finite, the stiffness the pressure's derivative
/// (`SLOPE_TOLERANCE`), with no jump between samples (`JUMP_TOLERANCE`), and the pair of
/// [`Curve::pressure_and_stiffness`] the two calls' values (1e-12); a negative stiffness only
/// when [`Curve::stiffens`] says so; the work `−∫₀^reach p dg` and the greatest tension within
/// `WORK_TOLERANCE` of 1 and of [`Curve::peak`]; the tension at and beyond the reach below
/// `REACH_TOLERANCE` of the peak; a tension that only falls past the peak when
/// [`Curve::falls_past_peak`] says so (`check_falls`).
pub(super) fn check_shape(curve: &dyn Curve) -> Result<(), SolverError> {
    let positive = |method: &'static str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(refuse(
                curve,
                method,
                format!("= {v} at γ = 1: must be finite and > 0"),
            ))
        }
    };
    let length = positive("Curve::length", curve.length())?;
    let peak = positive("Curve::peak", curve.peak(1.0))?;
    let reach = positive("Curve::reach", curve.reach())?;
    let top = (1.0 + reach / length).ln();
    let dt = top / SAMPLES as f64;
    let gap = |i: usize| {
        if i == SAMPLES {
            reach
        } else {
            length * (i as f64 * dt).exp_m1()
        }
    };
    let mut samples = Vec::with_capacity(SAMPLES + 1);
    for i in 0..=SAMPLES {
        let g = gap(i);
        samples.push((g, point(curve, g, length, peak)?));
    }
    // After the samples up to the reach: a curve that fails inside its reach is named at the
    // gap where it fails, not at the reach.
    check_tail(curve, peak, reach)?;
    check_scaling(curve, &samples, peak)?;
    let (mut work, mut most) = (0.0, f64::NEG_INFINITY);
    for (i, &(g, (p, _))) in samples.iter().enumerate() {
        most = most.max(-p);
        // Simpson's rule in t: dg = ℓ eᵗ dt = (g + ℓ) dt.
        let weight = if i == 0 || i == SAMPLES {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        work -= weight * p * (g + length);
    }
    work *= dt / 3.0;
    for pair in samples.windows(3).step_by(2) {
        let [(g0, (p0, k0)), (g1, (_, k1)), (g2, (p2, k2))] = [pair[0], pair[1], pair[2]];
        let integral =
            dt / 3.0 * (k0 * (g0 + length) + 4.0 * k1 * (g1 + length) + k2 * (g2 + length));
        if !within(p2 - p0 - integral, JUMP_TOLERANCE * peak) {
            return Err(refuse(
                curve,
                "Curve::pressure",
                format!(
                    "changes by {} from g = {g0} to {g2} but its slope integrates to \
                     {integral}: the pressure must be continuous, its slope dp/dg, and the \
                     curve must vary on scales above about 1e-3 of its length {length} \
                     (length() is its smallest length)",
                    Num(p2 - p0),
                    g0 = Num(g0),
                    g2 = Num(g2),
                    integral = Num(integral),
                    length = Num(length)
                ),
            ));
        }
    }
    if !within(work - 1.0, WORK_TOLERANCE) {
        return Err(refuse(
            curve,
            "Curve::pressure",
            format!(
                "has work −∫p dg = {work:.6}·γ from the wall to the reach: a law must spread \
                 exactly γ (within {WORK_TOLERANCE}) before its reach, the references and the \
                 γ scaling read it so",
                WORK_TOLERANCE = Num(WORK_TOLERANCE)
            ),
        ));
    }
    if curve.falls_past_peak() {
        check_falls(curve, &samples, peak)?;
    }
    if !within(most - peak, WORK_TOLERANCE * peak) {
        return Err(refuse(
            curve,
            "Curve::peak",
            format!(
                "= {peak} at γ = 1 but the greatest tension sampled is {most}: it sets the \
                 process zone, the mesh rule and the landing's step",
                peak = Num(peak),
                most = Num(most)
            ),
        ));
    }
    Ok(())
}

/// The pressure and stiffness at gap `g` for γ = 1, checked: finite, the pair call's values,
/// no negative stiffness unless the curve stiffens, the stiffness the pressure's slope.
fn point(curve: &dyn Curve, g: f64, length: f64, peak: f64) -> Result<(f64, f64), SolverError> {
    let (p, k) = (curve.pressure(1.0, g), curve.stiffness(1.0, g));
    if !(p.is_finite() && k.is_finite()) {
        return Err(refuse(
            curve,
            "Curve::pressure",
            format!(
                "or Curve::stiffness is not finite at g = {g} (p = {p}, dp/dg = {k})",
                g = Num(g)
            ),
        ));
    }
    let both = curve.pressure_and_stiffness(1.0, g);
    let near = |a: f64, b: f64| within(a - b, 1e-12 * b.abs());
    if !(near(both.0, p) && near(both.1, k)) {
        return Err(refuse(
            curve,
            "Curve::pressure_and_stiffness",
            format!(
                "gives ({}, {}) at g = {g} but the two calls give ({p}, {k}): it must return \
                 their values",
                both.0,
                both.1,
                g = Num(g)
            ),
        ));
    }
    if k < 0.0 && !curve.stiffens() {
        return Err(refuse(
            curve,
            "Curve::stiffens",
            format!(
                "is false but the stiffness is {k} < 0 at g = {g}: the landing then leaves \
                 the stiff elements out of its contact solve",
                k = Num(k),
                g = Num(g)
            ),
        ));
    }
    let step = 1e-6 * (g + length);
    let at = |g: f64| curve.pressure(1.0, g);
    let slope = if g >= 2.0 * step {
        (at(g + step) - at(g - step)) / (2.0 * step)
    } else {
        // One-sided, second order, at the wall.
        (-3.0 * at(g) + 4.0 * at(g + step) - at(g + 2.0 * step)) / (2.0 * step)
    };
    if !within(k - slope, SLOPE_TOLERANCE * k.abs() + 1e-6 * peak / length) {
        return Err(refuse(
            curve,
            "Curve::stiffness",
            format!(
                "= {k} at g = {g} but the pressure's slope there is {slope}: it must be \
                 dp/dg (positive where the tension falls with the gap)",
                k = Num(k),
                g = Num(g),
                slope = Num(slope)
            ),
        ));
    }
    Ok((p, k))
}

/// The tension at and beyond the reach (`BEYOND`): finite and below `REACH_TOLERANCE` of the
/// peak.
fn check_tail(curve: &dyn Curve, peak: f64, reach: f64) -> Result<(), SolverError> {
    for g in std::iter::once(reach).chain(BEYOND.iter().map(|b| b * reach)) {
        let (p, k) = (curve.pressure(1.0, g), curve.stiffness(1.0, g));
        if !(within(p, REACH_TOLERANCE * peak) && k.is_finite()) {
            return Err(refuse(
                curve,
                "Curve::reach",
                format!(
                    "= {reach}: at g = {g} the pressure is {p} (dp/dg {k}), more than \
                     {REACH_TOLERANCE} of the peak {peak} or not finite; the solver crops \
                     the law beyond its reach and evaluates it at every gap",
                    reach = Num(reach),
                    g = Num(g),
                    p = Num(p),
                    k = Num(k),
                    REACH_TOLERANCE = Num(REACH_TOLERANCE),
                    peak = Num(peak)
                ),
            ));
        }
    }
    Ok(())
}

/// A curve that says it falls past its peak ([`Curve::falls_past_peak`]): past its greatest
/// tension ([`super::peak_gap_of`]) its slope is not negative beyond the slope check's floor
/// (1e-6 of `peak/ℓ`, `point`) and the magnitude of its pressure does not grow from one sample
/// to the next, nor from the reach on over `BEYOND` (beyond 1e-12 of the peak: round-off).
fn check_falls(
    curve: &dyn Curve,
    samples: &[(f64, (f64, f64))],
    peak: f64,
) -> Result<(), SolverError> {
    let from = super::peak_gap_of(curve);
    let length = curve.length();
    let reach = curve.reach();
    let tail = BEYOND.iter().map(|b| {
        let g = b * reach;
        (g, (curve.pressure(1.0, g), curve.stiffness(1.0, g)))
    });
    let past: Vec<_> = samples
        .iter()
        .copied()
        .filter(|&(g, _)| g > from)
        .chain(tail)
        .collect();
    let promise = |reason: String| {
        Err(refuse(
            curve,
            "Curve::falls_past_peak",
            format!(
                "is true but {reason}, past the greatest tension at g = {from}: return false, \
                 or mend the curve",
                from = Num(from)
            ),
        ))
    };
    for &(g, (_, k)) in &past {
        if k < -1e-6 * peak / length {
            return promise(format!(
                "the stiffness is {k} < 0 at g = {g}",
                k = Num(k),
                g = Num(g)
            ));
        }
    }
    for pair in past.windows(2) {
        let [(g0, (p0, _)), (g1, (p1, _))] = [pair[0], pair[1]];
        if p1.abs() > p0.abs() + 1e-12 * peak {
            return promise(format!(
                "the pressure grows from {p0} at g = {g0} to {p1} at g = {g1}",
                p0 = Num(p0),
                g0 = Num(g0),
                p1 = Num(p1),
                g1 = Num(g1)
            ));
        }
    }
    Ok(())
}

/// The curve at the works `GAMMAS` against γ times its values at 1: pressure and stiffness on
/// every 100th sample, and the peak.
fn check_scaling(
    curve: &dyn Curve,
    samples: &[(f64, (f64, f64))],
    peak: f64,
) -> Result<(), SolverError> {
    for gamma in GAMMAS {
        let off = |method: &'static str, at: String, got: f64, want: f64| {
            refuse(
                curve,
                method,
                format!(
                    "at γ = {gamma}{at} gives {got}, not γ times its value at γ = 1 ({want}): \
                     a law scales as γ (its gamma argument) at one range",
                    got = Num(got),
                    want = Num(want)
                ),
            )
        };
        let linear = |got: f64, one: f64| within(got - gamma * one, 1e-12 * gamma * one.abs());
        let got = curve.peak(gamma);
        if !linear(got, peak) {
            return Err(off("Curve::peak", String::new(), got, gamma * peak));
        }
        for &(g, (p, k)) in samples.iter().step_by(100) {
            let got = (curve.pressure(gamma, g), curve.stiffness(gamma, g));
            if !linear(got.0, p) {
                return Err(off(
                    "Curve::pressure",
                    format!(", g = {g},", g = Num(g)),
                    got.0,
                    gamma * p,
                ));
            }
            if !linear(got.1, k) {
                return Err(off(
                    "Curve::stiffness",
                    format!(", g = {g},", g = Num(g)),
                    got.1,
                    gamma * k,
                ));
            }
        }
    }
    Ok(())
}
