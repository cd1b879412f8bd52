//! The exponential law of the potential `V(g) = −γ e^(−g/ρ)` with a hard wall.

use super::{Curve, REACH_FRACTION};

/// The scene name.
pub(super) const NAME: &str = "exponential";

/// The exponential law of the potential `V(g) = −γ e^(−g/ρ)` with a hard wall at `g = 0`: out
/// of contact `p(g) = −(γ/ρ) e^(−g/ρ)`, peak tension `γ/ρ` at the wall (the law of Tamaas,
/// ContactMechanics and the contact-mechanics challenge). Solved by `smooth.rs`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exponential {
    /// The range ρ > 0.
    pub range: f64,
}

impl Curve for Exponential {
    fn name(&self) -> &'static str {
        NAME
    }

    fn label(&self) -> &'static str {
        "exponential, range rho"
    }

    fn length(&self) -> f64 {
        self.range
    }

    fn meaning(&self) -> &'static str {
        "the range ρ > 0 of p = −(γ/ρ) e^(−g/ρ)"
    }

    #[inline]
    fn pressure(&self, gamma: f64, g: f64) -> f64 {
        let r = self.range;
        -(gamma / r) * (-g / r).exp()
    }

    #[inline]
    fn stiffness(&self, gamma: f64, g: f64) -> f64 {
        let r = self.range;
        (gamma / (r * r)) * (-g / r).exp()
    }

    /// One `exp` for both.
    #[inline]
    fn pressure_and_stiffness(&self, gamma: f64, g: f64) -> (f64, f64) {
        let r = self.range;
        let e = (-g / r).exp();
        (-(gamma / r) * e, (gamma / (r * r)) * e)
    }

    fn stiffens(&self) -> bool {
        false
    }

    /// `γ/ρ`, at the wall.
    fn peak(&self, gamma: f64) -> f64 {
        gamma / self.range
    }

    /// `ρ ln 10⁸ ≈ 18.4ρ`.
    fn reach(&self) -> f64 {
        self.range * (1.0 / REACH_FRACTION).ln()
    }

    /// Its tension is greatest at the wall and falls from there.
    fn falls_past_peak(&self) -> bool {
        true
    }
}
