//! Kendall (1971) pull-off of a flat-ended circular punch adhering to an elastic half-space.

use std::f64::consts::PI;

/// Magnitude of the pull-off force of a flat circular punch of radius `a`,
/// F_c = sqrt(8π a³ E* γ) (Kendall 1971; positive number, the force itself is tensile).
pub fn kendall_pull_off(e_star: f64, gamma: f64, a: f64) -> f64 {
    (8.0 * PI * a.powi(3) * e_star * gamma).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quad::{assert_close, derivative};

    /// Griffith balance: at fixed load the energy release rate of the punch is
    /// G = d/dA [F²/(2k)] with flat-punch stiffness k = 2E*a (Boussinesq/Sneddon) and A = πa².
    /// At F = F_c it must equal γ. Central difference in a: O(h²) ≈ 1e-9 relative; tol 1e-6.
    #[test]
    fn pull_off_satisfies_griffith_balance() {
        let (e, gamma, a) = (3.0e4, 0.7, 0.2);
        let f = kendall_pull_off(e, gamma, a);
        let complementary = |r: f64| f * f / (2.0 * 2.0 * e * r);
        let g = -derivative(complementary, a, 1e-5 * a) / (2.0 * PI * a);
        assert_close(g, gamma, 1e-6);
    }

    /// Hand value: E* = 1, γ = 1/(8π), a = 1 ⇒ F_c = 1; and F_c ∝ a^(3/2).
    #[test]
    fn hand_value_and_scaling() {
        assert_close(kendall_pull_off(1.0, 1.0 / (8.0 * PI), 1.0), 1.0, 1e-15);
        assert_close(
            kendall_pull_off(2.0, 0.3, 4.0) / kendall_pull_off(2.0, 0.3, 1.0),
            8.0,
            1e-14,
        );
    }
}
