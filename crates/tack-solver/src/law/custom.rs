//! A smooth law of the caller's own ([`AdhesionLaw::custom`](super::AdhesionLaw::custom)):
//! the curve is checked once against what the solver assumes of it (its derivative, its
//! work, its peak, its reach, whether it stiffens) and then shared.

use std::sync::Arc;

use super::{Curve, Law};
use crate::SolverError;

/// Intervals of the graded sampling `g = ℓ(eᵗ − 1)`, `t ∈ [0, ln(1 + reach/ℓ)]`, on which a
/// curve is checked (Simpson's rule for its work: an error below 1e-8 on the built-in laws).
const SAMPLES: usize = 4000;

/// Relative tolerance of the work `−∫p dg = γ` and of the sampled peak tension against
/// [`Curve::peak`]: a curve the solver and the references (JKR, DMT, Tabor's μ) read as a law
/// of work γ must be one to this accuracy; 1e-3 is 10⁵ times Simpson's error here, so it
/// refuses only curves whose scaling is off.
const WORK_TOLERANCE: f64 = 1e-3;

/// Relative tolerance of [`Curve::stiffness`] against a central difference of
/// [`Curve::pressure`] (step 1e-6 of the local length scale: a difference error near 1e-10),
/// plus 1e-6 of the curve's stiffness scale `peak/ℓ` where both vanish: it catches a wrong sign,
/// a missing factor or a jump of the pressure, which break Newton's steps.
const SLOPE_TOLERANCE: f64 = 1e-4;

/// What is left of the peak tension at [`Curve::reach`], at most: beyond it the solver crops
/// the law away (the built-in laws leave [`super::REACH_FRACTION`], 1e-8).
const REACH_TOLERANCE: f64 = 1e-6;

/// A smooth law of the caller's own, shared between the solvers and results that use it: two
/// are equal when they are one curve (one allocation), so a solver's saved state restores only
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

/// Checks a curve of work of adhesion 1 on `SAMPLES` graded gaps up to its reach: its
/// length, peak and reach are finite and positive; its pressure and stiffness finite, the
/// stiffness a derivative of the pressure (`SLOPE_TOLERANCE`) and the pair of
/// [`Curve::pressure_and_stiffness`] the two calls' bits; a negative stiffness only when
/// [`Curve::stiffens`] says so; the work `−∫₀^reach p dg` and the greatest tension within
/// `WORK_TOLERANCE` of 1 and of [`Curve::peak`]; the tension at the reach below
/// `REACH_TOLERANCE` of the peak.
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
    let tail = -curve.pressure(1.0, reach);
    if tail.is_nan() || tail.abs() > REACH_TOLERANCE * peak {
        return Err(refuse(
            curve,
            "Curve::reach",
            format!(
                "= {reach}: the tension there is {tail:e}, more than {REACH_TOLERANCE:e} of the \
                 peak {peak:e}; the solver crops the law beyond its reach"
            ),
        ));
    }
    let top = (1.0 + reach / length).ln();
    let dt = top / SAMPLES as f64;
    let (mut work, mut most) = (0.0, f64::NEG_INFINITY);
    for i in 0..=SAMPLES {
        let t = i as f64 * dt;
        let g = if i == SAMPLES {
            reach
        } else {
            length * t.exp_m1()
        };
        let (p, k) = (curve.pressure(1.0, g), curve.stiffness(1.0, g));
        if !(p.is_finite() && k.is_finite()) {
            return Err(refuse(
                curve,
                "Curve::pressure",
                format!("or Curve::stiffness is not finite at g = {g:e} (p = {p}, dp/dg = {k})"),
            ));
        }
        let both = curve.pressure_and_stiffness(1.0, g);
        if both.0.to_bits() != p.to_bits() || both.1.to_bits() != k.to_bits() {
            return Err(refuse(
                curve,
                "Curve::pressure_and_stiffness",
                format!(
                    "gives ({}, {}) at g = {g:e} but the two calls give ({p}, {k}): it must \
                     return their bits",
                    both.0, both.1
                ),
            ));
        }
        if k < 0.0 && !curve.stiffens() {
            return Err(refuse(
                curve,
                "Curve::stiffens",
                format!(
                    "is false but the stiffness is {k:e} < 0 at g = {g:e}: the landing then \
                     leaves the stiff elements out of its contact solve"
                ),
            ));
        }
        let step = 1e-6 * (g + length);
        if g >= 2.0 * step {
            let slope =
                (curve.pressure(1.0, g + step) - curve.pressure(1.0, g - step)) / (2.0 * step);
            if (k - slope).abs() > SLOPE_TOLERANCE * k.abs() + 1e-6 * peak / length {
                return Err(refuse(
                    curve,
                    "Curve::stiffness",
                    format!(
                        "= {k:e} at g = {g:e} but the pressure's slope there is {slope:e}: it \
                         must be dp/dg (positive where the tension falls with the gap)"
                    ),
                ));
            }
        }
        most = most.max(-p);
        // Simpson's rule in t: dg = ℓ eᵗ dt.
        let weight = if i == 0 || i == SAMPLES {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        work -= weight * p * length * t.exp();
    }
    work *= dt / 3.0;
    if (work - 1.0).abs() > WORK_TOLERANCE {
        return Err(refuse(
            curve,
            "Curve::pressure",
            format!(
                "has work −∫p dg = {work:.6}·γ from the wall to the reach: a law must spread \
                 exactly γ (within {WORK_TOLERANCE:e}), the references and the γ scaling read it so"
            ),
        ));
    }
    if (most - peak).abs() > WORK_TOLERANCE * peak {
        return Err(refuse(
            curve,
            "Curve::peak",
            format!(
                "= {peak:e} at γ = 1 but the greatest tension sampled is {most:e}: it sets the \
                 process zone, the mesh rule and the landing's step"
            ),
        ));
    }
    Ok(())
}
