//! The Lennard-Jones 9–3 law of two half-spaces with a hard wall at its equilibrium
//! separation.

use super::{Curve, REACH_FRACTION};

/// The scene name.
pub(super) const NAME: &str = "lennard_jones";

/// The Lennard-Jones 9–3 law with a hard wall at its equilibrium separation ε: with
/// `h = g + ε`, `p(g) = −(8γ/3ε)[(ε/h)³ − (ε/h)⁹]`, zero at the wall, peak tension
/// `16γ/(9√3 ε) ≈ 1.026 γ/ε` at `h = 3^(1/6) ε`, work `γ` (Derjaguin–Muller–Toporov's and
/// Greenwood's law of two half-spaces). Solved by `smooth.rs`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LennardJones {
    /// The equilibrium separation ε > 0.
    pub range: f64,
}

impl Curve for LennardJones {
    fn name(&self) -> &'static str {
        NAME
    }

    fn label(&self) -> &'static str {
        "Lennard-Jones 9-3, range epsilon"
    }

    fn length(&self) -> f64 {
        self.range
    }

    fn meaning(&self) -> &'static str {
        "the equilibrium separation ε > 0 of the 9–3 law"
    }

    fn symbol(&self) -> &'static str {
        "ε"
    }

    #[inline]
    fn pressure(&self, gamma: f64, g: f64) -> f64 {
        let r = self.range;
        let t = r / (g + r);
        let t3 = t * t * t;
        -(8.0 * gamma / (3.0 * r)) * (t3 - t3 * t3 * t3)
    }

    #[inline]
    fn stiffness(&self, gamma: f64, g: f64) -> f64 {
        let r = self.range;
        let h = g + r;
        let t = r / h;
        let t3 = t * t * t;
        (8.0 * gamma / (r * h)) * (t3 - 3.0 * t3 * t3 * t3)
    }

    /// Next to its wall (`h < 3^(1/6) ε`).
    fn stiffens(&self) -> bool {
        true
    }

    /// `16γ/(9√3 ε)`.
    fn peak(&self, gamma: f64) -> f64 {
        16.0 * gamma / (9.0 * 3f64.sqrt() * self.range)
    }

    /// About `640ε`: `(8/3)(t³ − t⁹)/(16/(9√3))` = fraction with `t = ε/h`, so
    /// `t³ ≈ fraction·2/(3√3)`.
    fn reach(&self) -> f64 {
        let r = self.range;
        let t = (REACH_FRACTION * 2.0 / (3.0 * 3f64.sqrt())).cbrt();
        r / t - r
    }

    /// Its tension falls past its greatest, at `h = 3^(1/6) ε`.
    fn falls_past_peak(&self) -> bool {
        true
    }
}
