//! Westergaard (1939) non-adhesive contact of a 1D sinusoidal waviness f = h[1 − cos(2πx/λ)]
//! with an elastic half-space (Eq. 1; the α = 0 case of Johnson 1995).

use std::f64::consts::PI;

/// Mean pressure for complete contact, p*_1D = π E* h / λ (Westergaard 1939; Eq. 2 text).
pub fn westergaard_p_star(e_star: f64, h: f64, lambda: f64) -> f64 {
    PI * e_star * h / lambda
}

/// sin²(πa/λ) with the half-width clamped to [0, λ/2] (contact cannot exceed one period).
fn sin2_psi(a: f64, lambda: f64) -> f64 {
    (PI * a.clamp(0.0, 0.5 * lambda) / lambda).sin().powi(2)
}

/// Mean pressure at contact half-width `a`, p̄ = p*_1D sin²(πa/λ); `a ≥ λ/2` gives p*_1D and
/// `a ≤ 0` gives 0 (Westergaard 1939; Johnson 1995, Eq. 2 with α = 0).
pub fn westergaard_mean_pressure(e_star: f64, h: f64, lambda: f64, a: f64) -> f64 {
    westergaard_p_star(e_star, h, lambda) * sin2_psi(a, lambda)
}

/// Pressure at `x` for contact half-width `a` (Westergaard 1939):
/// p(x) = 2 p*_1D cos(πx/λ) sqrt(sin²(πa/λ) − sin²(πx/λ)) for |x| < a, zero elsewhere, with
/// `x` first reduced to the period centred on a contact (−λ/2 ≤ x < λ/2). For `a ≥ λ/2` this is
/// the onset of complete contact, p = p*_1D (1 + cos 2πx/λ).
pub fn westergaard_pressure(e_star: f64, h: f64, lambda: f64, a: f64, x: f64) -> f64 {
    let x = x - lambda * (x / lambda).round();
    if a < 0.5 * lambda && x.abs() >= a {
        return 0.0;
    }
    let c = (PI * x / lambda).cos();
    let s2 = 1.0 - c * c;
    2.0 * westergaard_p_star(e_star, h, lambda) * c * (sin2_psi(a, lambda) - s2).max(0.0).sqrt()
}

/// Contact half-width for mean pressure `p_mean`, a = (λ/π) asin(sqrt(p̄/p*_1D)), clamped to
/// [0, λ/2] (inverse of Westergaard 1939).
pub fn westergaard_half_width(e_star: f64, h: f64, lambda: f64, p_mean: f64) -> f64 {
    let ratio = (p_mean / westergaard_p_star(e_star, h, lambda)).clamp(0.0, 1.0);
    lambda / PI * ratio.sqrt().asin()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quad::assert_close;

    const E: f64 = 5.0;
    const H: f64 = 0.02;
    const L: f64 = 1.5;

    /// The mean pressure must be the period average of the profile. Plain trapezoid over one
    /// period (N = 200 000) without any singularity treatment: the sqrt edge of the profile makes
    /// the error O(N^-1.5) ≈ 1e-8 relative; tolerance 1e-6. The grid is offset from ±a.
    #[test]
    fn mean_pressure_is_period_average_of_profile() {
        let n = 200_000;
        for a in [0.05 * L, 0.2 * L, 0.37 * L, 0.5 * L] {
            let dx = L / n as f64;
            let avg: f64 = (0..n)
                .map(|i| westergaard_pressure(E, H, L, a, -0.5 * L + (i as f64 + 0.5) * dx))
                .sum::<f64>()
                / n as f64;
            assert_close(avg, westergaard_mean_pressure(E, H, L, a), 1e-6);
        }
    }

    /// Profile is periodic and vanishes outside the contact and at its edge.
    #[test]
    fn profile_is_periodic_and_compact() {
        let a = 0.3 * L;
        for x in [0.0, 0.1, -0.25] {
            assert_close(
                westergaard_pressure(E, H, L, a, x + 3.0 * L),
                westergaard_pressure(E, H, L, a, x),
                1e-9,
            );
        }
        assert_eq!(westergaard_pressure(E, H, L, a, 0.4 * L), 0.0);
        assert!(westergaard_pressure(E, H, L, a, a * (1.0 - 1e-12)) < 1e-5);
    }

    #[test]
    fn half_width_inverts_mean_pressure() {
        for a in [1e-3 * L, 0.1 * L, 0.25 * L, 0.49 * L] {
            let p = westergaard_mean_pressure(E, H, L, a);
            assert_close(westergaard_half_width(E, H, L, p), a, 1e-9);
        }
        assert_eq!(westergaard_half_width(E, H, L, -1.0), 0.0);
        assert_close(westergaard_half_width(E, H, L, 1e9), 0.5 * L, 1e-15);
        assert_close(
            westergaard_mean_pressure(E, H, L, 2.0 * L),
            westergaard_p_star(E, H, L),
            1e-15,
        );
    }
}
