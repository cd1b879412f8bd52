//! Empirical fits of Li, Pohrt & Popov (2019): adhesion enhancement of a wavy sphere Λ(α)
//! (Eq. 9), the adhesion parameter of random roughness α* (Eq. 11) and its fit Λ*(α*) (Eq. 12).

use std::f64::consts::PI;

/// Pull-off force of a sphere with 2D waviness relative to JKR, F_ad/F_JKR ≈ Λ(α) (Eq. 9):
/// 0.27/α² exp(−0.14/α²) + 1 for α ≥ 0.24 and 0.65α − 0.025 below (the paper's "compact
/// contact" and "point cloud" branches; the value at exactly 0.24 is taken from the upper one).
pub fn lambda_fit(alpha: f64) -> f64 {
    if alpha < 0.24 {
        0.65 * alpha - 0.025
    } else {
        let u = 1.0 / (alpha * alpha);
        0.27 * u * (-0.14 * u).exp() + 1.0
    }
}

/// Adhesion parameter of a randomly rough surface with rms height `h`, Hurst exponent `hurst`
/// and cut-off wave vectors `q0` ≤ `q1` (Eq. 11):
/// α* = sqrt(4γ q1^(0.8H − 1) / (π E* h² q0^(0.8H))).
pub fn alpha_star(e_star: f64, gamma: f64, h: f64, hurst: f64, q0: f64, q1: f64) -> f64 {
    (4.0 * gamma * q1.powf(0.8 * hurst - 1.0) / (PI * e_star * h * h * q0.powf(0.8 * hurst))).sqrt()
}

/// Rms height h of a randomly rough surface with adhesion parameter `alpha_star`, the inverse of
/// Eq. 11: h = sqrt(4γ q1^(0.8H − 1) / (π E* q0^(0.8H)))/α*, for α* > 0 (α* = 0 gives +∞).
///
/// Bit for bit `alpha_star(e_star, gamma, 1.0, hurst, q0, q1) / alpha_star`.
pub fn rms_height_from_alpha_star(
    e_star: f64,
    gamma: f64,
    alpha_star: f64,
    hurst: f64,
    q0: f64,
    q1: f64,
) -> f64 {
    (4.0 * gamma * q1.powf(0.8 * hurst - 1.0) / (PI * e_star * q0.powf(0.8 * hurst))).sqrt()
        / alpha_star
}

/// Pull-off force of a randomly rough sphere relative to JKR,
/// |F_ad/F_JKR| ≈ Λ*(α*) = 1.023 exp(−((α* − 0.3619)/0.1188)²) (Eq. 12).
pub fn lambda_star(alpha_star: f64) -> f64 {
    1.023 * (-((alpha_star - 0.3619) / 0.1188).powi(2)).exp()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::johnson::johnson_alpha;
    use crate::quad::assert_close;

    /// Paper: "maximum enhancement is by the factor 1.7". Grid maximum over α in (0.24, 5]
    /// (step 1e-5) must lie in 1.6–1.8; analytically 1 + 0.27/(0.14 e) at α = sqrt(0.14).
    #[test]
    fn eq9_maximum_enhancement_is_about_1_7() {
        let (best, arg) = (24_001..500_000)
            .map(|i| i as f64 * 1e-5)
            .map(|a| (lambda_fit(a), a))
            .fold(
                (f64::NEG_INFINITY, 0.0),
                |m, v| if v.0 > m.0 { v } else { m },
            );
        assert!((1.6..=1.8).contains(&best), "max Λ = {best}");
        assert_close(best, 1.0 + 0.27 / (0.14 * std::f64::consts::E), 1e-9);
        assert!((arg - 0.14f64.sqrt()).abs() < 1e-4);
    }

    /// Left branch: 0.65·0.24 − 0.025 = 0.131 just below the threshold; the force then drops
    /// from about 1.41 (upper branch) — the paper's "drastic" drop at α ≈ 0.24.
    #[test]
    fn eq9_branches_at_threshold() {
        assert!((lambda_fit(0.24 - 1e-12) - 0.131).abs() < 1e-10);
        assert!((lambda_fit(0.24) - 1.41).abs() < 0.01);
        assert!((lambda_fit(0.1) - 0.04).abs() < 1e-12);
        assert!((lambda_fit(100.0) - 1.0).abs() < 1e-4);
    }

    /// Paper: "If there is only one wave vector q0 = q1, Eq. 11 reduces to Eq. 3": with
    /// q = 2π/λ, q^(0.8H−1)/q^(0.8H) = λ/(2π) and α*² = 2λγ/(π²E*h²) exactly, for every H.
    /// (h is an rms height in Eq. 11 and an amplitude in Eq. 3; the identity is formal.)
    #[test]
    fn eq11_reduces_to_eq3_for_single_wave_vector() {
        let (e, gamma, h, l) = (7.0, 0.02, 0.01, 0.3);
        let q = 2.0 * PI / l;
        for hurst in [0.1, 0.3, 0.5, 0.7, 0.9] {
            assert_close(
                alpha_star(e, gamma, h, hurst, q, q),
                johnson_alpha(e, gamma, h, l),
                1e-12,
            );
        }
    }

    /// Inverse of Eq. 11: α*(h(α*)) = α* and h(α*(h)) = h to rounding (1e-12), over H and
    /// bands q0 = q1 up to q1/q0 = 2^10; and equal bits to the forward form at h = 1 divided by α*
    /// (how Fig. 7 computed h before).
    #[test]
    fn rms_height_from_alpha_star_inverts_eq11() {
        let (e, gamma) = (1.0, 5e-5);
        let q0 = 2.0 * PI;
        for hurst in [0.1, 0.5, 0.9] {
            for q1 in [q0, 16.0 * q0, 1024.0 * q0] {
                for a in [0.05, 0.3619, 0.7, 3.0] {
                    let h = rms_height_from_alpha_star(e, gamma, a, hurst, q0, q1);
                    assert_close(alpha_star(e, gamma, h, hurst, q0, q1), a, 1e-12);
                    let back = alpha_star(e, gamma, h, hurst, q0, q1);
                    assert_close(
                        rms_height_from_alpha_star(e, gamma, back, hurst, q0, q1),
                        h,
                        1e-12,
                    );
                    assert_eq!(
                        h.to_bits(),
                        (alpha_star(e, gamma, 1.0, hurst, q0, q1) / a).to_bits()
                    );
                }
            }
        }
    }

    /// Paper's reading points of Eq. 12: |F/F_JKR| ≈ 1 at α* = 0.344 and ≈ 0.5 at α* = 0.26;
    /// peak 1.023 at 0.3619.
    #[test]
    fn eq12_reading_points() {
        assert!((lambda_star(0.344) - 1.0).abs() < 0.03);
        assert!((lambda_star(0.26) - 0.5).abs() < 0.03);
        assert_close(lambda_star(0.3619), 1.023, 1e-15);
    }
}
