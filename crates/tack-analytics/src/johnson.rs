//! Johnson (1995) adhesive contact of periodic waviness: the Johnson parameter α (Eq. 3), the 1D
//! mean-pressure law (Eq. 2) and its critical α, and the 2D near-complete-contact law (Eq. 5).

use crate::const_math;
use crate::westergaard::westergaard_p_star;
use std::f64::consts::{FRAC_PI_3, PI};

/// Johnson parameter α = sqrt(2λγ/(π² h² E*)) for waviness amplitude `h` and wavelength
/// `lambda` (Eq. 3; Johnson 1995).
pub fn johnson_alpha(e_star: f64, gamma: f64, h: f64, lambda: f64) -> f64 {
    (2.0 * lambda * gamma / (PI * PI * h * h * e_star)).sqrt()
}

/// Waviness amplitude h of Johnson parameter `alpha` at wavelength `lambda`, the inverse of
/// Eq. 3 (Johnson 1995): h = sqrt(2λγ/(π² E*))/α, for α > 0 (α = 0 gives +∞).
pub fn waviness_amplitude_from_alpha(e_star: f64, gamma: f64, alpha: f64, lambda: f64) -> f64 {
    (2.0 * lambda * gamma / (PI * PI * e_star)).sqrt() / alpha
}

/// 1D adhesive waviness: p̄/p*_1D = sin²ψ − α sqrt(tan ψ) with ψ = πa/λ in (0, π/2)
/// (Eq. 2; Johnson 1995).
pub fn johnson_1d_mean_pressure_ratio(alpha: f64, psi: f64) -> f64 {
    psi.sin().powi(2) - alpha * psi.tan().sqrt()
}

/// ψ = πa/λ at which the maximum of Eq. 2 touches zero for α = α_c: π/3 (Johnson 1995).
///
/// Both p̄ = 0 (α = sin²ψ/√tanψ) and dp̄/dψ = 0 (α = 4 sinψ cos³ψ √tanψ) hold there; equating
/// the two gives cos²ψ = 1/4.
pub const JOHNSON_1D_CRITICAL_PSI: f64 = FRAC_PI_3;

/// Critical Johnson parameter of Eq. 2, α_c = sin²(π/3)/sqrt(tan(π/3)) = (3/4)·3^(−1/4)
/// ≈ 0.5699: for α ≥ α_c the maximum of p̄(a) is ≤ 0 and the surfaces jump into complete
/// contact at first touch (Eq. 2; Johnson 1995; the paper's 0.57). See
/// [`JOHNSON_1D_CRITICAL_PSI`] for the derivation.
pub const fn johnson_1d_critical_alpha() -> f64 {
    0.75 / const_math::sqrt(const_math::sqrt(3.0))
}

/// Critical Johnson parameter of the 1D waviness, the value of [`johnson_1d_critical_alpha`].
pub const JOHNSON_1D_CRITICAL_ALPHA: f64 = johnson_1d_critical_alpha();

/// Mean pressure for complete contact of the 2D waviness h[1 − cos(2πx/λ) cos(2πy/λ)],
/// p*_2D = √2 π E* h/λ (Eq. 5 text; Johnson 1995).
pub fn johnson_2d_p_star(e_star: f64, h: f64, lambda: f64) -> f64 {
    std::f64::consts::SQRT_2 * westergaard_p_star(e_star, h, lambda)
}

/// 2D waviness near complete contact, with a circular gap of radius b, ψ_b = πb/λ:
/// p̄/p*_2D = 1 − (4/3)ψ_b² − π/(2√2) α ψ_b^(−1/2) (Eq. 5; Johnson 1995).
pub fn johnson_2d_near_full_ratio(alpha: f64, psi_b: f64) -> f64 {
    1.0 - 4.0 / 3.0 * psi_b * psi_b - PI / (2.0 * std::f64::consts::SQRT_2) * alpha / psi_b.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quad::{assert_close, simpson};
    use crate::westergaard::westergaard_mean_pressure;

    /// Maximum of Eq. 2 over ψ on a fine grid (step 1e-5 in (0, π/2)) and its location.
    fn max_of_eq2(alpha: f64) -> (f64, f64) {
        (1..157_079)
            .map(|i| i as f64 * 1e-5)
            .map(|psi| (johnson_1d_mean_pressure_ratio(alpha, psi), psi))
            .fold(
                (f64::NEG_INFINITY, 0.0),
                |m, v| if v.0 > m.0 { v } else { m },
            )
    }

    /// α = 0 must reproduce Westergaard's p̄ = p* sin²(πa/λ) (independent module).
    #[test]
    fn eq2_without_adhesion_is_westergaard() {
        let (e, h, l) = (2.0, 0.01, 0.7);
        for a in [0.01, 0.1, 0.2, 0.3] {
            assert_close(
                johnson_1d_mean_pressure_ratio(0.0, PI * a / l),
                westergaard_mean_pressure(e, h, l, a) / westergaard_p_star(e, h, l),
                1e-13,
            );
        }
    }

    /// Find α_c by bisection on "max over ψ of Eq. 2 is zero" (grid maximum) and compare with the
    /// closed form (grid step 1e-5 limits the max to ~1e-10, so 1e-7 on α) and with 0.5699
    /// (paper, 4 digits); the argmax must be π/3 to the grid resolution.
    #[test]
    fn critical_alpha_numerically() {
        let (mut lo, mut hi) = (0.3, 0.8);
        for _ in 0..40 {
            let mid = 0.5 * (lo + hi);
            if max_of_eq2(mid).0 > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let alpha_c = 0.5 * (lo + hi);
        assert_close(alpha_c, JOHNSON_1D_CRITICAL_ALPHA, 1e-7);
        assert!((JOHNSON_1D_CRITICAL_ALPHA - 0.5699).abs() < 5e-5);
        assert!((johnson_1d_critical_alpha() - 0.75 * 3f64.powf(-0.25)).abs() < 1e-15);
        let (_, psi) = max_of_eq2(JOHNSON_1D_CRITICAL_ALPHA);
        assert!((psi - JOHNSON_1D_CRITICAL_PSI).abs() < 2e-5, "argmax {psi}");
    }

    /// Eq. 3 against a hand-computed value.
    #[test]
    fn alpha_hand_value() {
        // 2λγ/(π²h²E*) = 2·π²·1/(π²·1·2) = 1.
        assert_close(johnson_alpha(2.0, 1.0, 1.0, PI * PI), 1.0, 1e-15);
    }

    /// Inverse of Eq. 3: α(h(α)) = α and h(α(h)) = h to rounding (a few ulps; 1e-12).
    #[test]
    fn amplitude_from_alpha_inverts_eq3() {
        for (e, gamma, lambda) in [(2.0, 1.0, PI * PI), (1.0, 5e-5, 1.0), (3.0e4, 0.7, 2.5e-3)] {
            for alpha in [1e-3, 0.1, 0.24, JOHNSON_1D_CRITICAL_ALPHA, 1.0, 37.0] {
                let h = waviness_amplitude_from_alpha(e, gamma, alpha, lambda);
                assert_close(johnson_alpha(e, gamma, h, lambda), alpha, 1e-12);
                assert_close(
                    waviness_amplitude_from_alpha(
                        e,
                        gamma,
                        johnson_alpha(e, gamma, h, lambda),
                        lambda,
                    ),
                    h,
                    1e-12,
                );
            }
        }
        // Hand value: 2λγ/(π²E*) = 1 for E* = 2, γ = 1, λ = π², so h = 1/α.
        assert_close(
            waviness_amplitude_from_alpha(2.0, 1.0, 0.25, PI * PI),
            4.0,
            1e-15,
        );
    }

    /// Eq. 5 from first principles (Johnson 1995 reasoning): near the trough the complete-contact
    /// pressure is p̄ − p* + p*·2π²r²/λ² (expansion of p̄ − p* cos cos), so the circular gap of
    /// radius b is a penny crack opened by q(r) = (p* − p̄) − 2π²p* r²/λ². Its stress intensity
    /// K = 2/sqrt(πb) ∫₀ᵇ q r/sqrt(b² − r²) dr (Tada et al.) must satisfy K²/(2E*) = γ (and 0 for
    /// α = 0). With r = b sin θ the integral is smooth; Simpson (200 panels) is exact to ~1e-12.
    #[test]
    fn eq5_is_griffith_balance_of_penny_gap() {
        let (e, h, l) = (3.0, 0.05, 2.0);
        for gamma in [0.0, 1e-4, 3e-3] {
            let alpha = johnson_alpha(e, gamma, h, l);
            let p_star = johnson_2d_p_star(e, h, l);
            for psi_b in [0.05, 0.2, 0.4] {
                let b = psi_b * l / PI;
                let p = p_star * johnson_2d_near_full_ratio(alpha, psi_b);
                let q = |r: f64| (p_star - p) - 2.0 * PI * PI * p_star * r * r / (l * l);
                let moment = simpson(|t| q(b * t.sin()) * b * t.sin(), 0.0, PI / 2.0, 200);
                let k = 2.0 / (PI * b).sqrt() * moment;
                assert!((k * k / (2.0 * e) - gamma).abs() < 1e-9 * p_star * p_star / e);
                assert!(k >= -1e-12 * p_star);
            }
        }
    }
}
