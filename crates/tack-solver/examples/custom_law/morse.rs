//! The Morse law, a smooth adhesion law of the caller's own: written outside tack and run by
//! its solver through [`tack_solver::AdhesionLaw::custom`] (the example `custom_law` and the
//! test `tests/custom_law.rs` share it).

use tack_solver::Curve;

/// The Morse law with the wall at the potential's minimum: with `x = g/ρ`,
/// `p(g) = −(2γ/ρ)(e^(−x) − e^(−2x))`, zero at the wall, stiffening for `x < ln 2`, peak
/// tension `γ/(2ρ)` at `x = ln 2`, work `γ`.
#[derive(Debug, Clone, Copy)]
pub struct Morse {
    /// The range ρ > 0.
    pub range: f64,
}

impl Curve for Morse {
    fn name(&self) -> &'static str {
        "morse"
    }
    fn label(&self) -> &'static str {
        "Morse, range rho"
    }
    fn length(&self) -> f64 {
        self.range
    }
    fn meaning(&self) -> &'static str {
        "the range ρ > 0 of p = −(2γ/ρ)(e^(−g/ρ) − e^(−2g/ρ))"
    }
    fn pressure(&self, gamma: f64, g: f64) -> f64 {
        let e = (-g / self.range).exp();
        -(2.0 * gamma / self.range) * (e - e * e)
    }
    fn stiffness(&self, gamma: f64, g: f64) -> f64 {
        let e = (-g / self.range).exp();
        (2.0 * gamma / (self.range * self.range)) * (e - 2.0 * e * e)
    }
    fn stiffens(&self) -> bool {
        true
    }
    fn peak(&self, gamma: f64) -> f64 {
        gamma / (2.0 * self.range)
    }
    /// `4e^(−x) = 1e-8` of the peak: `x = ln(4e8)`.
    fn reach(&self) -> f64 {
        self.range * 4e8f64.ln()
    }
    /// Past `x = ln 2` the tension only falls (checked when the law is made).
    fn falls_past_peak(&self) -> bool {
        true
    }
}
