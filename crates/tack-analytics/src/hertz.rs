//! Hertz (1882) non-adhesive contact of a paraboloid (sphere of radius R) with a half-space.

use std::f64::consts::PI;

/// Hertz contact radius a = sqrt(R d); zero for d ≤ 0 (Hertz 1882).
pub fn hertz_contact_radius(radius: f64, d: f64) -> f64 {
    if d > 0.0 { (radius * d).sqrt() } else { 0.0 }
}

/// Hertz normal force F = (4/3) E* sqrt(R) d^(3/2); zero for d ≤ 0 (Hertz 1882).
pub fn hertz_force(e_star: f64, radius: f64, d: f64) -> f64 {
    if d > 0.0 {
        4.0 / 3.0 * e_star * radius.sqrt() * d.powf(1.5)
    } else {
        0.0
    }
}

/// Hertz maximum (central) pressure p0 = 2 E* a / (π R) with a = sqrt(R d) (Hertz 1882).
pub fn hertz_max_pressure(e_star: f64, radius: f64, d: f64) -> f64 {
    2.0 * e_star * hertz_contact_radius(radius, d) / (PI * radius)
}

/// Hertz pressure p(r) = p0 sqrt(1 − r²/a²) for r < a, zero outside (Hertz 1882).
pub fn hertz_pressure(e_star: f64, radius: f64, d: f64, r: f64) -> f64 {
    let a = hertz_contact_radius(radius, d);
    if r.abs() < a {
        hertz_max_pressure(e_star, radius, d) * (1.0 - (r / a).powi(2)).sqrt()
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quad::{assert_close, derivative, simpson};

    const E: f64 = 2.0e3;
    const R: f64 = 7.5;

    /// F must equal ∫ p 2πr dr over the disc. With r = a sin θ the integrand is smooth, so
    /// Simpson with 400 panels is accurate to ~1e-12; 1e-9 leaves margin.
    #[test]
    fn force_is_integral_of_pressure() {
        for d in [1.0e-3, 0.1, 2.0] {
            let a = hertz_contact_radius(R, d);
            let integrand = |t: f64| {
                let r = a * t.sin();
                hertz_pressure(E, R, d, r) * 2.0 * PI * r * a * t.cos()
            };
            let f = simpson(integrand, 0.0, PI / 2.0, 400);
            assert_close(f, hertz_force(E, R, d), 1e-9);
        }
    }

    /// Normal contact stiffness dF/dd = 2 E* a holds for any axisymmetric frictionless contact
    /// (Johnson 1985). Central difference error O(h²) ~ 1e-8 relative; tolerance 1e-6.
    #[test]
    fn stiffness_is_two_e_star_a() {
        let d = 0.3;
        let k = derivative(|x| hertz_force(E, R, x), d, 1e-4 * d);
        assert_close(k, 2.0 * E * hertz_contact_radius(R, d), 1e-6);
    }

    /// Known ratio p0 = 3F/(2πa²) (mean pressure is 2/3 of the peak); exact up to rounding.
    #[test]
    fn max_pressure_is_three_halves_mean() {
        let d = 0.05;
        let a = hertz_contact_radius(R, d);
        assert_close(
            hertz_max_pressure(E, R, d),
            1.5 * hertz_force(E, R, d) / (PI * a * a),
            1e-12,
        );
        assert_close(
            hertz_pressure(E, R, d, 0.0),
            hertz_max_pressure(E, R, d),
            1e-15,
        );
    }

    #[test]
    fn no_contact_for_non_positive_approach() {
        for d in [0.0, -1.0] {
            assert_eq!(hertz_force(E, R, d), 0.0);
            assert_eq!(hertz_contact_radius(R, d), 0.0);
            assert_eq!(hertz_pressure(E, R, d, 0.0), 0.0);
        }
        assert_eq!(hertz_pressure(E, R, 1.0, 10.0), 0.0);
    }
}
