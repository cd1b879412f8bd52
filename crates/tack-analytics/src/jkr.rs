//! Johnson–Kendall–Roberts (1971) adhesive contact of a sphere: force, approach and contact
//! radius on the full equilibrium curve, its characteristic points and its scales (Eqs. 7–8).
//!
//! Dimensionless variables (hats): F̂ = F/(γR), â = a (E*/(R²γ))^(1/3), d̂ = d (E*²/(Rγ²))^(1/3),
//! in which F̂ = (4/3) â³ − sqrt(8π â³) and d̂ = â² − sqrt(2π â).

use crate::kendall::kendall_pull_off;
use std::f64::consts::PI;

/// A point (contact radius, approach, force) on the JKR equilibrium curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JkrPoint {
    /// Contact radius a.
    pub radius: f64,
    /// Approach d (positive = pressing).
    pub approach: f64,
    /// Normal force F (positive = compressive).
    pub force: f64,
}

/// JKR force scale γR, so that F̂ = F/(γR) (Johnson, Kendall & Roberts 1971).
pub fn jkr_force_scale(gamma: f64, radius: f64) -> f64 {
    gamma * radius
}

/// JKR contact-radius scale (R²γ/E*)^(1/3), so that â = a / scale
/// (Johnson, Kendall & Roberts 1971).
pub fn jkr_length_scale_radius(e_star: f64, gamma: f64, radius: f64) -> f64 {
    (radius * radius * gamma / e_star).cbrt()
}

/// JKR approach scale (Rγ²/E*²)^(1/3), so that d̂ = d / scale (Johnson, Kendall & Roberts 1971).
pub fn jkr_approach_scale(e_star: f64, gamma: f64, radius: f64) -> f64 {
    (radius * gamma * gamma / (e_star * e_star)).cbrt()
}

/// JKR force at contact radius `a`: F = 4E*a³/(3R) − sqrt(8πγE*a³), i.e. Hertz minus the
/// Kendall flat-punch term (Johnson, Kendall & Roberts 1971).
pub fn jkr_force_from_radius(e_star: f64, gamma: f64, radius: f64, a: f64) -> f64 {
    4.0 * e_star * a.powi(3) / (3.0 * radius) - kendall_pull_off(e_star, gamma, a)
}

/// JKR approach at contact radius `a`: d = a²/R − sqrt(2πγa/E*)
/// (Johnson, Kendall & Roberts 1971).
pub fn jkr_approach_from_radius(e_star: f64, gamma: f64, radius: f64, a: f64) -> f64 {
    a * a / radius - (2.0 * PI * gamma * a / e_star).sqrt()
}

/// Dimensionless JKR force F̂ = (4/3) â³ − sqrt(8π â³) (Johnson, Kendall & Roberts 1971).
pub fn jkr_force_hat(a_hat: f64) -> f64 {
    jkr_force_from_radius(1.0, 1.0, 1.0, a_hat)
}

/// Dimensionless JKR approach d̂ = â² − sqrt(2π â) (Johnson, Kendall & Roberts 1971).
pub fn jkr_approach_hat(a_hat: f64) -> f64 {
    jkr_approach_from_radius(1.0, 1.0, 1.0, a_hat)
}

/// Greatest tensile force under force control, F_JKR = −(3/2) π γ R (Eq. 7).
pub fn jkr_pull_off_force(gamma: f64, radius: f64) -> f64 {
    -1.5 * PI * gamma * radius
}

/// Approach at the force-controlled pull-off, d_JKR = −(3π²γ²R/(64E*²))^(1/3) (Eq. 8).
pub fn jkr_pull_off_approach(e_star: f64, gamma: f64, radius: f64) -> f64 {
    -(3.0 * PI * PI * gamma * gamma * radius / (64.0 * e_star * e_star)).cbrt()
}

/// Contact radius at the force-controlled pull-off, a_c = (9πγR²/(8E*))^(1/3), i.e.
/// â³ = 9π/8 where dF/da = 0 (Johnson, Kendall & Roberts 1971).
pub fn jkr_pull_off_radius(e_star: f64, gamma: f64, radius: f64) -> f64 {
    (9.0 * PI * gamma * radius * radius / (8.0 * e_star)).cbrt()
}

/// Jump-off point under approach control, at â³ = π/8 where dd/da = 0:
/// d̂ = −(3/4) π^(2/3), F = −(5/6) π γ R (Johnson, Kendall & Roberts 1971; Johnson 1985 §5.5).
pub fn jkr_jump_off(e_star: f64, gamma: f64, radius: f64) -> JkrPoint {
    let a = jump_off_radius_hat() * jkr_length_scale_radius(e_star, gamma, radius);
    JkrPoint {
        radius: a,
        approach: jkr_approach_from_radius(e_star, gamma, radius, a),
        force: jkr_force_from_radius(e_star, gamma, radius, a),
    }
}

/// â at the jump-off point, (π/8)^(1/3) (Johnson, Kendall & Roberts 1971).
fn jump_off_radius_hat() -> f64 {
    (PI / 8.0).cbrt()
}

/// Dimensionless contact radius â on the stable branch (â ≥ (π/8)^(1/3)) for approach `d_hat`;
/// `None` below the jump-off approach d̂ = −(3/4)π^(2/3) (Johnson, Kendall & Roberts 1971).
///
/// d̂(â) is increasing on that branch; the root lies in [max(â_j, √d̂⁺), √d̂⁺ + 2] because
/// d̂(â) < â² and (s + 2)² − sqrt(2π(s + 2)) ≥ s² for s ≥ 0. Bisection to machine precision.
pub fn jkr_radius_hat_from_approach_hat(d_hat: f64) -> Option<f64> {
    let a_jump = jump_off_radius_hat();
    if d_hat.is_nan() || d_hat < jkr_approach_hat(a_jump) {
        return None;
    }
    let s = d_hat.max(0.0).sqrt();
    let (mut lo, mut hi) = (a_jump.max(s), s + 2.0);
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            return Some(mid);
        }
        if jkr_approach_hat(mid) < d_hat {
            lo = mid;
        } else {
            hi = mid;
        }
    }
}

/// Contact radius on the stable JKR branch for approach `d` under approach control; `None`
/// below the jump-off approach (Johnson, Kendall & Roberts 1971). For γ = 0 this is the Hertz
/// radius sqrt(R d) for d ≥ 0 (Hertz 1882).
pub fn jkr_radius_from_approach(e_star: f64, gamma: f64, radius: f64, d: f64) -> Option<f64> {
    if gamma <= 0.0 {
        return (d >= 0.0).then(|| (radius * d).sqrt());
    }
    jkr_radius_hat_from_approach_hat(d / jkr_approach_scale(e_star, gamma, radius))
        .map(|a_hat| a_hat * jkr_length_scale_radius(e_star, gamma, radius))
}

/// Force on the stable JKR branch for approach `d` under approach control; `None` below the
/// jump-off approach, where the sphere has detached (Johnson, Kendall & Roberts 1971).
pub fn jkr_force_from_approach(e_star: f64, gamma: f64, radius: f64, d: f64) -> Option<f64> {
    jkr_radius_from_approach(e_star, gamma, radius, d)
        .map(|a| jkr_force_from_radius(e_star, gamma, radius, a))
}

/// Most points [`jkr_curve_normalised`] returns: a guard for a huge, infinite or NaN `x_max`
/// (with the step 0.005 the cap is reached near d/|d_JKR| ≈ 850).
pub const JKR_CURVE_MAX_POINTS: usize = 5000;

/// The smooth sphere's JKR force–approach curve in the normalised units of plots, as points
/// (d/|d_JKR|, F/|F_JKR|) (Eqs. 7, 8) on the stable branch under approach control
/// (Johnson, Kendall & Roberts 1971; `docs/theory.md` §5.2). The same for every E*, γ, R.
///
/// The points are the parametric curve (d̂(â), F̂(â)) divided by |d̂_JKR| and |F̂_JKR| at
/// â = â_j, â_j + `a_hat_step`, â_j + 2·`a_hat_step`, … (the step accumulated by addition), from
/// the jump-off â_j = (π/8)^(1/3), at (−3^(2/3), −5/9), up to and including the first point with
/// d/|d_JKR| ≥ `x_max`, and at most [`JKR_CURVE_MAX_POINTS`] points (a NaN `x_max` gives the
/// jump-off point alone). The curve passes through the force-controlled pull-off (−1, −1), its
/// minimum, and approaches the Hertz curve F/|F_JKR| = x^(3/2)/(3√3) at large x = d/|d_JKR|.
///
/// # Panics
///
/// If `a_hat_step` is not a finite number > 0.
///
/// ```
/// let curve = tack_analytics::jkr_curve_normalised(3.0, 0.005);
/// let lowest = curve.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
/// assert!((lowest + 1.0).abs() < 1e-4); // the pull-off F = F_JKR
/// assert!(curve.last().unwrap().0 >= 3.0);
/// ```
pub fn jkr_curve_normalised(x_max: f64, a_hat_step: f64) -> Vec<(f64, f64)> {
    assert!(
        a_hat_step.is_finite() && a_hat_step > 0.0,
        "jkr_curve_normalised: a_hat_step must be a finite number > 0, got {a_hat_step}"
    );
    let f_scale = jkr_pull_off_force(1.0, 1.0).abs();
    let d_scale = jkr_pull_off_approach(1.0, 1.0, 1.0).abs();
    let mut a = jump_off_radius_hat();
    let mut points: Vec<(f64, f64)> = Vec::new();
    while points.last().is_none_or(|&(x, _)| x < x_max) && points.len() < JKR_CURVE_MAX_POINTS {
        points.push((jkr_approach_hat(a) / d_scale, jkr_force_hat(a) / f_scale));
        a += a_hat_step;
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hertz::hertz_force;
    use crate::quad::{assert_close, derivative};

    const E: f64 = 1.3e3;
    const G: f64 = 0.04;
    const R: f64 = 25.0;

    /// At a_c (â³ = 9π/8) the parametric curve must give Eq. 7 and Eq. 8, which are written
    /// independently of it, and F(a) must be stationary there. Rounding only: 1e-12.
    #[test]
    fn pull_off_point_matches_eqs_7_and_8() {
        let a_c = jkr_pull_off_radius(E, G, R);
        assert_close(
            a_c / jkr_length_scale_radius(E, G, R),
            (9.0 * PI / 8.0).cbrt(),
            1e-12,
        );
        assert_close(
            jkr_force_from_radius(E, G, R, a_c),
            jkr_pull_off_force(G, R),
            1e-12,
        );
        assert_close(
            jkr_approach_from_radius(E, G, R, a_c),
            jkr_pull_off_approach(E, G, R),
            1e-12,
        );
        // Eq. 8 in JKR units: d̂ = −(3π²/64)^(1/3) = −0.77342 (docs/theory.md §5.2); the
        // rounded −0.7735 quoted elsewhere lies within the 2e-4 checked here.
        let d_hat = jkr_pull_off_approach(E, G, R) / jkr_approach_scale(E, G, R);
        assert!((d_hat + 0.7735).abs() < 2e-4, "d_hat = {d_hat}");
        let slope = derivative(|a| jkr_force_from_radius(E, G, R, a), a_c, 1e-4 * a_c);
        assert!(slope.abs() < 1e-6 * G * R / a_c, "dF/da = {slope}");
    }

    /// Jump-off: dd/da = 0 (finite difference, O(h²) ≈ 1e-8 of the scale), d̂ = −1.609 and
    /// F = −(5/6)πγR (Johnson 1985).
    #[test]
    fn jump_off_point() {
        let p = jkr_jump_off(E, G, R);
        let scale = jkr_approach_scale(E, G, R);
        let slope = derivative(
            |a| jkr_approach_from_radius(E, G, R, a),
            p.radius,
            1e-4 * p.radius,
        );
        assert!(slope.abs() < 1e-6 * scale / p.radius, "dd/da = {slope}");
        assert_close(p.force, -5.0 / 6.0 * PI * G * R, 1e-12);
        assert_close(p.approach / scale, -1.609, 1e-3);
        assert_close(p.approach / scale, -0.75 * PI.powf(2.0 / 3.0), 1e-12);
    }

    /// Dimensionless and dimensional forms agree through the scales.
    #[test]
    fn dimensionless_forms_agree_with_dimensional() {
        let a = 0.8;
        let a_hat = a / jkr_length_scale_radius(E, G, R);
        assert_close(
            jkr_force_from_radius(E, G, R, a) / jkr_force_scale(G, R),
            jkr_force_hat(a_hat),
            1e-12,
        );
        assert_close(
            jkr_approach_from_radius(E, G, R, a) / jkr_approach_scale(E, G, R),
            jkr_approach_hat(a_hat),
            1e-12,
        );
    }

    /// γ → 0 recovers Hertz at the same approach. The O(√γ) terms cancel (the Kendall term and
    /// the radius shift), so the gap is O(γ/(E* d)) ≈ 1e-9 here; tolerance 1e-6.
    #[test]
    fn vanishing_adhesion_recovers_hertz() {
        let d = 0.1;
        let f = jkr_force_from_approach(E, 1.0e-6, R, d).unwrap();
        assert_close(f, hertz_force(E, R, d), 1e-6);
        assert_close(
            jkr_force_from_approach(E, 0.0, R, d).unwrap(),
            hertz_force(E, R, d),
            1e-12,
        );
        assert_eq!(jkr_force_from_approach(E, 0.0, R, -d), None);
    }

    /// Solving for a from d inverts the parametric curve on the stable branch (bisection to
    /// machine precision; 1e-12 allows for conditioning near the turning point).
    #[test]
    fn force_from_approach_round_trips() {
        let a_j = jkr_jump_off(E, G, R).radius;
        for factor in [1.0, 1.001, 1.3, 2.0, 5.0, 40.0, 1.0e3] {
            let a = factor * a_j;
            let d = jkr_approach_from_radius(E, G, R, a);
            let a_back = jkr_radius_from_approach(E, G, R, d).unwrap();
            let tol = if factor == 1.0 { 1e-6 } else { 1e-10 };
            assert_close(a_back, a, tol);
            assert_close(
                jkr_force_from_approach(E, G, R, d).unwrap(),
                jkr_force_from_radius(E, G, R, a),
                tol,
            );
        }
    }

    #[test]
    fn below_jump_off_detaches() {
        let d_j = jkr_jump_off(E, G, R).approach;
        assert_eq!(jkr_force_from_approach(E, G, R, d_j * 1.0001), None);
        assert_eq!(jkr_force_from_approach(E, G, R, f64::NAN), None);
        assert!(jkr_force_from_approach(E, G, R, d_j * 0.9999).is_some());
    }

    /// Huge approach: finite, and Hertz-like since the adhesive correction is O(γ/(E* d)).
    #[test]
    fn huge_approach_is_robust() {
        let d_hat = 1.0e20;
        let d = d_hat * jkr_approach_scale(E, G, R);
        let f = jkr_force_from_approach(E, G, R, d).unwrap();
        assert!(f.is_finite());
        assert_close(f, hertz_force(E, R, d), 1e-9);
    }
    /// The normalised curve: starts at the jump-off (−3^(2/3), −5/9), its lowest point is the
    /// force-controlled pull-off (−1, −1) to the step's resolution (F is stationary there, so
    /// the force misses it by O(step²), the approach by O(step)), d increases along it, it
    /// stops at the first point past `x_max`, and far out it is the Hertz curve.
    #[test]
    fn normalised_curve_known_points() {
        let c = jkr_curve_normalised(5.0, 0.005);
        assert_close(c[0].0, -(3.0f64.powf(2.0 / 3.0)), 1e-12);
        assert_close(c[0].1, -5.0 / 9.0, 1e-12);
        // Independent of the material: the jump-off of any E*, γ, R in the same units.
        let j = jkr_jump_off(E, G, R);
        assert_close(
            c[0].0,
            j.approach / jkr_pull_off_approach(E, G, R).abs(),
            1e-12,
        );
        assert_close(c[0].1, j.force / jkr_pull_off_force(G, R).abs(), 1e-12);
        let lowest = c
            .iter()
            .copied()
            .min_by(|p, q| p.1.total_cmp(&q.1))
            .unwrap();
        assert!((lowest.1 + 1.0).abs() < 1e-4, "F/|F_JKR| = {}", lowest.1);
        assert!(lowest.1 + 1.0 > -1e-12, "below the pull-off: {}", lowest.1);
        assert!((lowest.0 + 1.0).abs() < 0.02, "d/|d_JKR| = {}", lowest.0);
        assert!(c.windows(2).all(|w| w[1].0 > w[0].0), "d not increasing");
        let n = c.len();
        assert!(c[n - 1].0 >= 5.0 && c[n - 2].0 < 5.0);
        // Hertz at the same approach: (4/3) d̂^(3/2) over 3π/2. The adhesive terms cancel to
        // leading order (see vanishing_adhesion_recovers_hertz): a relative gap of O(d̂^(-3/2)).
        let far = jkr_curve_normalised(500.0, 0.01);
        let (x, y) = *far.last().unwrap();
        assert!(x >= 500.0 && far.len() < JKR_CURVE_MAX_POINTS);
        let hertz = hertz_force(E, R, x * jkr_pull_off_approach(E, G, R).abs())
            / jkr_pull_off_force(G, R).abs();
        assert!((y / hertz - 1.0).abs() < 1e-3, "{y} vs Hertz {hertz}");
        assert_close(hertz, x.powf(1.5) / 27.0f64.sqrt(), 1e-9);
    }

    /// The point cap and the degenerate limits.
    #[test]
    fn normalised_curve_limits() {
        assert_eq!(jkr_curve_normalised(f64::NAN, 0.01).len(), 1);
        assert_eq!(jkr_curve_normalised(-10.0, 0.01).len(), 1);
        assert_eq!(
            jkr_curve_normalised(f64::INFINITY, 0.01).len(),
            JKR_CURVE_MAX_POINTS
        );
    }

    #[test]
    #[should_panic(expected = "a_hat_step")]
    fn normalised_curve_refuses_a_zero_step() {
        let _ = jkr_curve_normalised(1.0, 0.0);
    }
}
