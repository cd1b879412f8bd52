//! Axisymmetric power-law bodies z = c·r^m (m ≥ 1: m = 1 a cone, m = 2 the paraboloid of a
//! sphere) in the JKR limit, exactly, by the method of dimensionality reduction (MDR; Popov &
//! Heß 2015): the contact of radius a behaves as a 1D profile g(x) = κ_m c |x|^m on a row of
//! springs of stiffness E*Δx, with
//!
//! ```text
//! κ_m = √π Γ(m/2 + 1) / Γ(m/2 + 1/2)          (κ_1 = π/2, κ_2 = 2)
//! d(a) = κ_m c a^m − √(2πγa/E*)
//! F(a) = (2m/(m+1)) E* κ_m c a^(m+1) − √(8πγE* a³)
//! ```
//!
//! (Hertz's force less Kendall's punch term, the JKR construction for any axisymmetric body;
//! with c = 1/(2R), m = 2 they are JKR's sphere). Under approach control the sphere-like bodies
//! are stable where dd/da > 0; the least force, dF/da = 0 at
//! `a_F^(m − 1/2) = 3√(8πγE*)/(4 m E* κ_m c)`, always lies on that stable branch (there dd/da = 0
//! would need a^(m − 1/2) three times smaller), so it is the pull-off force under approach and
//! force control alike.
//!
//! ```
//! use tack_analytics::{jkr_pull_off_force, power_law_pull_off_force};
//! // m = 2, c = 1/(2R): JKR's −(3/2)πγR.
//! let (e, gamma, r) = (1.0, 0.01, 2.0);
//! let f = power_law_pull_off_force(e, gamma, 1.0 / (2.0 * r), 2.0);
//! assert!((f / jkr_pull_off_force(gamma, r) - 1.0).abs() < 1e-12);
//! ```

use std::f64::consts::PI;

/// The MDR shape factor κ_m = √π Γ(m/2 + 1)/Γ(m/2 + 1/2) of the power law c·r^m (Popov & Heß
/// 2015): the equivalent 1D profile is κ_m c |x|^m.
pub fn mdr_shape_factor(m: f64) -> f64 {
    PI.sqrt() * (libm::lgamma(0.5 * m + 1.0) - libm::lgamma(0.5 * m + 0.5)).exp()
}

/// Approach at contact radius `a` of the power-law body c·r^m in the JKR limit (module docs).
pub fn power_law_jkr_approach(e_star: f64, gamma: f64, c: f64, m: f64, a: f64) -> f64 {
    mdr_shape_factor(m) * c * a.powf(m) - (2.0 * PI * gamma * a / e_star).sqrt()
}

/// Force (positive when compressive) at contact radius `a` of the power-law body c·r^m in the
/// JKR limit (module docs).
pub fn power_law_jkr_force(e_star: f64, gamma: f64, c: f64, m: f64, a: f64) -> f64 {
    2.0 * m / (m + 1.0) * e_star * mdr_shape_factor(m) * c * a.powf(m + 1.0)
        - (8.0 * PI * gamma * e_star * a.powi(3)).sqrt()
}

/// Contact radius at the pull-off (the least force) of the power-law body c·r^m:
/// `a_F = (3√(8πγE*)/(4 m E* κ_m c))^(1/(m − 1/2))`, for m > 1/2 (the scene allows m ≥ 1).
pub fn power_law_pull_off_radius(e_star: f64, gamma: f64, c: f64, m: f64) -> f64 {
    let k = mdr_shape_factor(m);
    (3.0 * (8.0 * PI * gamma * e_star).sqrt() / (4.0 * m * e_star * k * c)).powf(1.0 / (m - 0.5))
}

/// Pull-off force (negative: tensile) of the power-law body c·r^m in the JKR limit, the same
/// under approach and force control (module docs).
pub fn power_law_pull_off_force(e_star: f64, gamma: f64, c: f64, m: f64) -> f64 {
    let a = power_law_pull_off_radius(e_star, gamma, c, m);
    power_law_jkr_force(e_star, gamma, c, m, a)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::jkr::{jkr_approach_from_radius, jkr_force_from_radius};

    #[test]
    fn shape_factor_known_values_and_the_integral() {
        // κ_1 = π/2, κ_2 = 2, κ_4 = 8/3; and the MDR integral m ∫₀¹ t^(m−1)/√(1 − t²) dt
        // (substituted t = sin θ: m ∫₀^{π/2} sin^(m−1)θ dθ), by Simpson with 20000 intervals:
        // to 1e-9 for integer m, to 1e-5 for m = 1.5, whose integrand √(sin θ) has an
        // unbounded slope at 0 (Simpson's error then falls only like h^1.5).
        assert!((mdr_shape_factor(1.0) - PI / 2.0).abs() < 1e-14);
        assert!((mdr_shape_factor(2.0) - 2.0).abs() < 1e-14);
        assert!((mdr_shape_factor(4.0) - 8.0 / 3.0).abs() < 1e-13);
        for m in [1.0, 1.5, 3.0, 5.5] {
            let n = 20_000;
            let h = PI / 2.0 / n as f64;
            let f = |k: usize| (k as f64 * h).sin().powf(m - 1.0);
            let mut sum = f(0) + f(n);
            for k in 1..n {
                sum += if k % 2 == 1 { 4.0 } else { 2.0 } * f(k);
            }
            let integral = m * sum * h / 3.0;
            let tol = if m.fract() == 0.0 { 1e-9 } else { 1e-5 };
            assert!(
                (mdr_shape_factor(m) / integral - 1.0).abs() < tol,
                "m = {m}"
            );
        }
    }

    #[test]
    fn the_sphere_is_jkr_and_the_pull_off_is_a_stable_minimum() {
        let (e, gamma, r) = (2.0, 0.03, 1.5);
        for a in [0.1, 0.5, 2.0] {
            let c = 1.0 / (2.0 * r);
            let f = power_law_jkr_force(e, gamma, c, 2.0, a);
            let d = power_law_jkr_approach(e, gamma, c, 2.0, a);
            assert!((f - jkr_force_from_radius(e, gamma, r, a)).abs() < 1e-12 * f.abs().max(1.0));
            assert!((d - jkr_approach_from_radius(e, gamma, r, a)).abs() < 1e-12);
        }
        // For any m ≥ 1 the pull-off radius is the force's minimum (F' = 0, F'' > 0) and lies
        // where dd/da > 0 (stable under approach control). Central differences, relative 1e-5.
        for m in [1.0, 1.5, 2.0, 3.0, 6.0] {
            let c = 0.7;
            let a = power_law_pull_off_radius(e, gamma, c, m);
            let h = 1e-5 * a;
            let f = |x| power_law_jkr_force(e, gamma, c, m, x);
            let d = |x| power_law_jkr_approach(e, gamma, c, m, x);
            let slope = (f(a + h) - f(a - h)) / (2.0 * h);
            assert!(slope.abs() < 1e-6 * f(a).abs() / a, "m = {m}: F' = {slope}");
            assert!(f(a + 10.0 * h) > f(a) && f(a - 10.0 * h) > f(a));
            assert!(d(a + h) > d(a - h), "m = {m}: unstable");
            assert!(power_law_pull_off_force(e, gamma, c, m) < 0.0);
        }
    }
}
