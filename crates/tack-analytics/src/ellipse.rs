//! Elliptic contacts of the paraboloid z = x²/(2Rx) + y²/(2Ry): Hertz exactly, JKR adhesion by the Johnson–Greenwood approximation.
//!
//! **Hertz** (Hertz 1882; Johnson 1985 §4.2). With A = 1/(2R_major), B = 1/(2R_minor) (A ≤ B:
//! the contact's *major* semi-axis a lies along the axis of the *larger* radius, the minor
//! semi-axis b = λa along the other), m = e² = 1 − λ², K = K(m) and D = (K − E)/m the complete
//! elliptic integrals (parameter m, `ellip` crate), the pressure p₀√(1 − x²/a² − y²/b²) displaces
//! the surface inside the ellipse by (p₀/E*)(bK − (bD/a²)x² − ((K − D)/b)y²). Matching the gap:
//!
//! ```text
//! B/A = (K − D)/(λ² D)          (the eccentricity; increasing in e from 1 at e = 0)
//! a² = d D/(K A),   b = λ a,   p₀ = E* d/(b K),   F = (2/3)π a b p₀
//! ```
//!
//! For λ = 1 (K = π/2, D = π/4) these are Hertz's a² = Rd, p₀ = 2E*a/(πR), F = 4E*a³/(3R).
//!
//! **JKR, approximately** (Johnson & Greenwood 2005, "An approximate JKR theory for elliptical
//! contacts", J. Phys. D 38). The contact is assumed to stay an ellipse (a, b), no longer of the
//! Hertz eccentricity. For any ellipse and any approach the pressure that matches the quadratic
//! gap inside it is unique and of the form (c₀ + c_x x²/a² + c_y y²/b²)/√(1 − x²/a² − y²/b²)
//! (Galin's theorem); its stress intensity factors at the ends of the axes are
//! K_I = −(c₀ + c_x)√(πa) at (±a, 0) and −(c₀ + c_y)√(πb) at (0, ±b). Johnson & Greenwood impose
//! Griffith's G = K_I²/(2E*) = γ at those four points only. The displacements of the two
//! non-uniform terms follow from the Hertz one by differentiating in a and b (a∂_a, b∂_b of
//! p₀√(1 − ρ²) give the x²/a² and y²/b² terms); with G(m) = (2D − K)/m they are, per a E*,
//!
//! ```text
//! x²/a² term: L = b(K − D),  M = −(b/a²)(D + G),  N = λ² G/b
//! y²/b² term: L = bD,        M = (b/a²) G,        N = −(K − D + λ² G)/b      (u = L − Mx² − Ny²)
//! ```
//!
//! and the flat-punch term c₀ gives a uniform 2bK c₀/E*. The two curvature equations fix c_x, c_y
//! ∝ aE* for a given λ; the two Griffith conditions then fix the size, explicitly:
//! a^(3/2) = √(2γ/(πE*)) (λ^(−1/2) − 1)/ĝ(λ) with ĝ = (c_x − c_y)/(aE*). The equilibrium states
//! are the one-parameter family λ ∈ (λ_Hertz, 1): large contacts have the Hertz eccentricity,
//! small ones turn circular. The construction and these formulas are derived here (the paper
//! itself was not at hand); they reduce to JKR for Rx = Ry. Stated accuracy: Johnson &
//! Greenwood's pull-off falls with the eccentricity from (3/2)πγR; Giudici, Vella & Griffiths
//! (2024, arXiv:2407.00378) find the construction in good agreement with numerical and
//! experimental results for quasi-circular contacts and increasingly off as the contact
//! elongates (they replace the two-point Griffith condition by an energy minimisation).
//!
//! ```
//! use tack_analytics::{elliptic_hertz_from_approach, elliptic_jkr_pull_off, hertz_force, jkr_pull_off_force};
//! let (e_star, gamma) = (1.0, 1e-3);
//! // A circle is Hertz and JKR.
//! let h = elliptic_hertz_from_approach(e_star, 2.0, 2.0, 0.01);
//! assert!((h.force / hertz_force(e_star, 2.0, 0.01) - 1.0).abs() < 1e-12);
//! let p = elliptic_jkr_pull_off(e_star, gamma, 2.0, 2.0);
//! assert!((p.force_control.force / jkr_pull_off_force(gamma, 2.0) - 1.0).abs() < 1e-12);
//! // Rx = 10 Ry: the contact is elongated along x, and it holds less than the sphere of √(RxRy).
//! let h = elliptic_hertz_from_approach(e_star, 10.0, 1.0, 0.01);
//! assert!(h.semi_axis_x > 2.0 * h.semi_axis_y);
//! let p = elliptic_jkr_pull_off(e_star, gamma, 10.0, 1.0);
//! assert!(p.force_control.force > jkr_pull_off_force(gamma, 10f64.sqrt()));
//! ```

use crate::jkr::{jkr_jump_off, jkr_pull_off_approach, jkr_pull_off_force, jkr_pull_off_radius};
use crate::minimize::golden_min;
use std::f64::consts::PI;

/// The complete elliptic integrals of parameter m = 1 − λ² that the module needs:
/// K(m), D(m) = (K − E)/m and G(m) = (2D − K)/m.
#[derive(Debug, Clone, Copy)]
struct Integrals {
    k: f64,
    d: f64,
    g: f64,
}

/// K, D from `ellip` (Carlson's forms, to rounding); G by its power series for m < 1/2, where the
/// difference 2D − K cancels (π/2 Σ_{k≥1} c_k² k/(k+1) m^(k−1), c_k = (2k−1)!!/(2k)!!, from the
/// series of K and E), and directly above.
fn integrals(lambda: f64) -> Integrals {
    let m = (1.0 - lambda) * (1.0 + lambda);
    let k = ellip::ellipk(m).expect("ellipk: m in [0, 1)");
    let d = ellip::ellipd(m).expect("ellipd: m in [0, 1)");
    let g = if m < 0.5 {
        let (mut c2, mut power, mut sum) = (0.25, 1.0, 0.0);
        for n in 1..400 {
            let term = c2 * n as f64 / (n as f64 + 1.0) * power;
            sum += term;
            if term < 1e-18 * sum {
                break;
            }
            let nf = n as f64;
            c2 *= ((2.0 * nf + 1.0) / (2.0 * nf + 2.0)).powi(2);
            power *= m;
        }
        0.5 * PI * sum
    } else {
        (2.0 * d - k) / m
    };
    Integrals { k, d, g }
}

/// Hertz's B/A = (K − D)/(λ²D) for the axis ratio λ = b/a.
fn hertz_curvature_ratio(lambda: f64) -> f64 {
    let i = integrals(lambda);
    (i.k - i.d) / (lambda * lambda * i.d)
}

/// The Hertz axis ratio λ = b/a ∈ (0, 1] for the curvature ratio B/A = `ratio` ≥ 1, by bisection
/// (B/A decreases in λ) to the last bit.
fn hertz_axis_ratio(ratio: f64) -> f64 {
    if ratio <= 1.0 {
        return 1.0;
    }
    let mut lo = 0.5;
    while hertz_curvature_ratio(lo) <= ratio {
        lo *= 0.5;
        assert!(
            lo > 1e-150,
            "elliptic Hertz: curvature ratio {ratio} out of reach"
        );
    }
    let mut hi = 1.0;
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            return mid;
        }
        if hertz_curvature_ratio(mid) > ratio {
            lo = mid;
        } else {
            hi = mid;
        }
    }
}

/// Orders the radii: (R_major, R_minor, major axis along x).
fn ordered(radius_x: f64, radius_y: f64) -> (f64, f64, bool) {
    assert!(
        radius_x > 0.0 && radius_y > 0.0 && radius_x.is_finite() && radius_y.is_finite(),
        "elliptic contact: radii must be finite and > 0, got {radius_x}, {radius_y}"
    );
    if radius_x >= radius_y {
        (radius_x, radius_y, true)
    } else {
        (radius_y, radius_x, false)
    }
}

/// Eccentricity e = √(1 − b²/a²) of the Hertz contact ellipse of the paraboloid
/// z = x²/(2Rx) + y²/(2Ry) (Johnson 1985 §4.2; independent of load and modulus; 0 for Rx = Ry).
pub fn elliptic_hertz_eccentricity(radius_x: f64, radius_y: f64) -> f64 {
    let (big, small, _) = ordered(radius_x, radius_y);
    let lambda = hertz_axis_ratio(big / small);
    ((1.0 - lambda) * (1.0 + lambda)).sqrt()
}

/// The Hertz contact of the paraboloid z = x²/(2Rx) + y²/(2Ry) at one approach (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipticHertz {
    /// Semi-axis of the contact ellipse along x (the major one when Rx ≥ Ry).
    pub semi_axis_x: f64,
    /// Semi-axis of the contact ellipse along y (the major one when Ry > Rx).
    pub semi_axis_y: f64,
    /// Eccentricity e = √(1 − minor²/major²).
    pub eccentricity: f64,
    /// Approach d (positive = pressing).
    pub approach: f64,
    /// Normal force F (positive = compressive).
    pub force: f64,
    /// Central (peak) pressure p₀ = 3F/(2π a b).
    pub max_pressure: f64,
}

impl EllipticHertz {
    /// Pressure p₀√(1 − x²/a_x² − y²/a_y²) inside the ellipse, zero outside.
    pub fn pressure(&self, x: f64, y: f64) -> f64 {
        if self.semi_axis_x <= 0.0 {
            return 0.0;
        }
        let s = 1.0 - (x / self.semi_axis_x).powi(2) - (y / self.semi_axis_y).powi(2);
        if s > 0.0 {
            self.max_pressure * s.sqrt()
        } else {
            0.0
        }
    }
}

/// Elliptic Hertz contact of z = x²/(2Rx) + y²/(2Ry) on a half-space of modulus E* at approach
/// `d` (Hertz 1882; Johnson 1985 §4.2; module docs); no contact (all zero) for d ≤ 0.
///
/// # Panics
///
/// If a radius is not finite and > 0.
pub fn elliptic_hertz_from_approach(
    e_star: f64,
    radius_x: f64,
    radius_y: f64,
    d: f64,
) -> EllipticHertz {
    let (big, small, major_x) = ordered(radius_x, radius_y);
    let lambda = hertz_axis_ratio(big / small);
    let eccentricity = ((1.0 - lambda) * (1.0 + lambda)).sqrt();
    if d <= 0.0 {
        return EllipticHertz {
            semi_axis_x: 0.0,
            semi_axis_y: 0.0,
            eccentricity,
            approach: d,
            force: 0.0,
            max_pressure: 0.0,
        };
    }
    let i = integrals(lambda);
    // A = 1/(2 R_major): a² = d D/(K A) = 2 R_major d D/K.
    let a = (2.0 * big * d * i.d / i.k).sqrt();
    let b = lambda * a;
    let p0 = e_star * d / (b * i.k);
    let force = 2.0 / 3.0 * PI * a * b * p0;
    let (semi_axis_x, semi_axis_y) = if major_x { (a, b) } else { (b, a) };
    EllipticHertz {
        semi_axis_x,
        semi_axis_y,
        eccentricity,
        approach: d,
        force,
        max_pressure: p0,
    }
}

/// Elliptic Hertz contact at the compressive force `force` (module docs:
/// d^(3/2) = 3FK√(KA/D)/(2πE*)); no contact for F ≤ 0.
///
/// # Panics
///
/// If a radius is not finite and > 0.
pub fn elliptic_hertz_from_force(
    e_star: f64,
    radius_x: f64,
    radius_y: f64,
    force: f64,
) -> EllipticHertz {
    let (big, small, _) = ordered(radius_x, radius_y);
    if force <= 0.0 {
        return elliptic_hertz_from_approach(e_star, radius_x, radius_y, 0.0);
    }
    let i = integrals(hertz_axis_ratio(big / small));
    let a_curv = 1.0 / (2.0 * big);
    let d = (3.0 * force * i.k * (i.k * a_curv / i.d).sqrt() / (2.0 * PI * e_star)).powf(2.0 / 3.0);
    elliptic_hertz_from_approach(e_star, radius_x, radius_y, d)
}

/// A point (contact ellipse, approach, force) of the approximate elliptic JKR equilibrium.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipticJkrPoint {
    /// Semi-axis of the contact ellipse along x.
    pub semi_axis_x: f64,
    /// Semi-axis of the contact ellipse along y.
    pub semi_axis_y: f64,
    /// Approach d (positive = pressing).
    pub approach: f64,
    /// Normal force F (positive = compressive).
    pub force: f64,
}

/// The characteristic points of the approximate elliptic JKR contact
/// ([`elliptic_jkr_pull_off`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipticJkrPullOff {
    /// The least force on the whole equilibrium family: the pull-off under force control
    /// (JKR: −(3/2)πγR).
    pub force_control: EllipticJkrPoint,
    /// The least approach: where the contact jumps off under approach control (JKR: F =
    /// −(5/6)πγR).
    pub jump_off: EllipticJkrPoint,
    /// The least force on the part stable under approach control (from large contacts down to
    /// the jump-off): the pull-off a run under approach control records. It is
    /// `force_control` when that lies on the stable part (as for JKR), else `jump_off`.
    pub approach_control: EllipticJkrPoint,
}

/// The elliptic JKR state of axis ratio λ ∈ (λ_Hertz, 1), in major/minor coordinates:
/// (a, b, d, F), with A = 1/(2R_major) ≤ B = 1/(2R_minor) (module docs).
fn jg_state(
    e_star: f64,
    gamma: f64,
    curv_a: f64,
    curv_b: f64,
    lambda: f64,
) -> (f64, f64, f64, f64) {
    let Integrals { k, d, g } = integrals(lambda);
    let l2 = lambda * lambda;
    // Curvature equations per a E*: [[−λ(D+G), λG], [λG, −(K − D + λ²G)/λ]]·(ĉx, ĉy) = (A, B).
    let (m11, m12, m21, m22) = (
        -lambda * (d + g),
        lambda * g,
        lambda * g,
        -(k - d + l2 * g) / lambda,
    );
    let det = m11 * m22 - m12 * m21;
    let cx_hat = (m22 * curv_a - m12 * curv_b) / det;
    let cy_hat = (m11 * curv_b - m21 * curv_a) / det;
    let g_hat = cx_hat - cy_hat;
    let a = ((2.0 * gamma / (PI * e_star)).sqrt() * (1.0 / lambda.sqrt() - 1.0) / g_hat)
        .powf(2.0 / 3.0);
    let b = lambda * a;
    let (cx, cy) = (a * e_star * cx_hat, a * e_star * cy_hat);
    let c0 = -(2.0 * e_star * gamma / (PI * a)).sqrt() - cx;
    let approach = (2.0 * b * k * c0 + cx * b * (k - d) + cy * b * d) / e_star;
    let force = PI * a * b * (2.0 * c0 + 2.0 / 3.0 * (cx + cy));
    (a, b, approach, force)
}

/// Relative difference of the radii below which the contact is taken as circular (JKR with
/// R = √(RxRy)); the elliptic result differs from it by O(ln²(Rx/Ry)) there.
const CIRCLE_TOLERANCE: f64 = 1e-9;

/// The approximate JKR elliptic contact of z = x²/(2Rx) + y²/(2Ry) in the zero-range limit:
/// force-controlled pull-off, jump-off and approach-controlled pull-off (Johnson & Greenwood
/// 2005; module docs for the construction and its accuracy). For Rx = Ry (to 1e-9 relative) it
/// is JKR's sphere of radius √(RxRy) exactly: −(3/2)πγR, the jump-off at −(5/6)πγR.
///
/// The states are searched (golden section, to 1e-12 of the family's parameter) in
/// λ = λ_H + t(1 − λ_H), t ∈ (0, 1), from the Hertz eccentricity (infinite contact) to the
/// circle (vanishing contact).
///
/// # Panics
///
/// If a radius is not finite and > 0, or `gamma`, `e_star` are not > 0.
pub fn elliptic_jkr_pull_off(
    e_star: f64,
    gamma: f64,
    radius_x: f64,
    radius_y: f64,
) -> EllipticJkrPullOff {
    assert!(
        gamma > 0.0 && e_star > 0.0,
        "elliptic JKR: E* and γ must be > 0, got {e_star}, {gamma}"
    );
    let (big, small, major_x) = ordered(radius_x, radius_y);
    let place = |a: f64, b: f64, approach: f64, force: f64| {
        let (semi_axis_x, semi_axis_y) = if major_x { (a, b) } else { (b, a) };
        EllipticJkrPoint {
            semi_axis_x,
            semi_axis_y,
            approach,
            force,
        }
    };
    if big / small - 1.0 <= CIRCLE_TOLERANCE {
        let r = (big * small).sqrt();
        let a_c = jkr_pull_off_radius(e_star, gamma, r);
        let force_control = place(
            a_c,
            a_c,
            jkr_pull_off_approach(e_star, gamma, r),
            jkr_pull_off_force(gamma, r),
        );
        let j = jkr_jump_off(e_star, gamma, r);
        return EllipticJkrPullOff {
            force_control,
            jump_off: place(j.radius, j.radius, j.approach, j.force),
            approach_control: force_control,
        };
    }
    let (curv_a, curv_b) = (0.5 / big, 0.5 / small);
    let lambda_h = hertz_axis_ratio(big / small);
    let state = |t: f64| {
        jg_state(
            e_star,
            gamma,
            curv_a,
            curv_b,
            lambda_h + t * (1.0 - lambda_h),
        )
    };
    let (t_force, _) = golden_min(|t| state(t).3, 0.0, 1.0, 1e-12);
    let (t_jump, _) = golden_min(|t| state(t).2, 0.0, 1.0, 1e-12);
    let at = |t: f64| {
        let (a, b, d, f) = state(t);
        place(a, b, d, f)
    };
    let force_control = at(t_force);
    let jump_off = at(t_jump);
    // Stable under approach control: t < t_jump (larger contacts, d decreasing with size).
    let approach_control = if t_force <= t_jump {
        force_control
    } else {
        jump_off
    };
    EllipticJkrPullOff {
        force_control,
        jump_off,
        approach_control,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hertz::{hertz_contact_radius, hertz_force, hertz_max_pressure};
    use crate::quad::{assert_close, derivative, simpson};

    const E: f64 = 3.0e3;

    /// K(1/2) = Γ(1/4)²/(4√π) and Legendre's relation 2EK − K² = π/2 at m = 1/2: checks that
    /// `ellip` takes the parameter m = e² (not the modulus). To rounding: 1e-14.
    #[test]
    fn elliptic_integrals_known_values() {
        let lambda = 0.5f64.sqrt();
        let i = integrals(lambda);
        let k_half = libm::tgamma(0.25).powi(2) / (4.0 * PI.sqrt());
        assert_close(i.k, k_half, 1e-14);
        let e = i.k - 0.5 * i.d;
        assert_close(2.0 * e * i.k - i.k * i.k, PI / 2.0, 1e-14);
        // The series and the direct form of G agree across m = 1/2 (continuity, 1e-12).
        let below = integrals((1.0f64 - 0.4999999).sqrt());
        let above = integrals((1.0f64 - 0.5000001).sqrt());
        assert!((below.g - above.g).abs() < 1e-6 * above.g);
        let direct = (2.0 * below.d - below.k) / 0.4999999;
        assert_close(below.g, direct, 1e-12);
        // m → 0: G → π/16, D → π/4, K → π/2.
        let zero = integrals(1.0);
        assert_close(zero.g, PI / 16.0, 1e-15);
        assert_close(zero.d, PI / 4.0, 1e-15);
        assert_close(zero.k, PI / 2.0, 1e-15);
    }

    /// Surface displacement (times πE*) at (x0, y0) inside the ellipse (a, b) of a pressure
    /// q(x, y)/√(1 − x²/a² − y²/b²), by polar integration about the point: on each ray the
    /// square root vanishes at the rim, removed by s = s_max − t²; Simpson in t and in θ
    /// (periodic, smooth). An independent route to the closed forms.
    fn displacement(q: impl Fn(f64, f64) -> f64, a: f64, b: f64, x0: f64, y0: f64) -> f64 {
        let rho0 = 1.0 - (x0 / a).powi(2) - (y0 / b).powi(2);
        simpson(
            |theta| {
                let (s, c) = theta.sin_cos();
                let cc = (c / a).powi(2) + (s / b).powi(2);
                let beta = x0 * c / (a * a) + y0 * s / (b * b);
                let root = (beta * beta + cc * rho0).sqrt();
                let (s_max, s_min) = ((root - beta) / cc, (root + beta) / cc);
                simpson(
                    |t| {
                        let r = s_max - t * t;
                        let w = 2.0 / (cc * (r + s_min)).sqrt();
                        q(x0 + r * c, y0 + r * s) * w
                    },
                    0.0,
                    s_max.sqrt(),
                    800,
                )
            },
            0.0,
            2.0 * PI,
            800,
        )
    }

    /// A pressure numerator q(x, y).
    type Load<'a> = dyn Fn(f64, f64) -> f64 + 'a;

    /// The displacement coefficients (L, M, N) of the Hertz term and of the x²/a², y²/b² terms
    /// (module docs), against the polar integration at three points per term, for a circle and
    /// two ellipses. Simpson on smooth integrands: 1e-9.
    #[test]
    fn displacement_coefficients_match_direct_integration() {
        for lambda in [1.0, 0.6, 0.15] {
            let (a, b) = (1.3, 1.3 * lambda);
            let Integrals { k, d, g } = integrals(lambda);
            let l2 = lambda * lambda;
            let terms: [(&Load<'_>, [f64; 3]); 3] = [
                (
                    &|x: f64, y: f64| 1.0 - (x / a).powi(2) - (y / b).powi(2),
                    [b * k, b * d / (a * a), (k - d) / b],
                ),
                (
                    &|x: f64, _y: f64| (x / a).powi(2),
                    [b * (k - d), -(b / (a * a)) * (d + g), l2 * g / b],
                ),
                (
                    &|_x: f64, y: f64| (y / b).powi(2),
                    [b * d, b * g / (a * a), -(k - d + l2 * g) / b],
                ),
            ];
            for (q, [l, m, n]) in terms {
                for (x, y) in [(0.0, 0.0), (0.5 * a, 0.0), (0.2 * a, 0.6 * b)] {
                    let u = displacement(q, a, b, x, y) / PI;
                    let expected = l - m * x * x - n * y * y;
                    assert!(
                        (u - expected).abs() < 1e-9 * l.abs(),
                        "λ = {lambda} at ({x}, {y}): {u} vs {expected}"
                    );
                }
            }
        }
    }

    /// Rx = Ry: Hertz's sphere to rounding (1e-12), e = 0.
    #[test]
    fn circle_is_hertz() {
        let r = 4.0;
        for d in [1e-4, 0.3] {
            let h = elliptic_hertz_from_approach(E, r, r, d);
            assert_eq!(h.eccentricity, 0.0);
            assert_close(h.semi_axis_x, hertz_contact_radius(r, d), 1e-12);
            assert_close(h.semi_axis_y, hertz_contact_radius(r, d), 1e-12);
            assert_close(h.force, hertz_force(E, r, d), 1e-12);
            assert_close(h.max_pressure, hertz_max_pressure(E, r, d), 1e-12);
            let back = elliptic_hertz_from_force(E, r, r, h.force);
            assert_close(back.approach, d, 1e-12);
        }
    }

    /// F equals the integral of the pressure over the ellipse, p₀ = 3F/(2πab), the force
    /// inverts to the approach, and the stiffness dF/dd is the elliptic flat punch's πaE*/K
    /// (the unloading stiffness of any elliptic contact). Both orderings, Rx/Ry up to 1e3.
    /// Quadrature 1e-9, central difference 1e-6, inversion 1e-12.
    #[test]
    fn hertz_identities() {
        for (rx, ry) in [
            (3.0, 1.0),
            (1.0, 3.0),
            (10.0, 1.0),
            (1.0, 100.0),
            (1e3, 1.0),
        ] {
            let d = 0.02;
            let h = elliptic_hertz_from_approach(E, rx, ry, d);
            let (ax, ay) = (h.semi_axis_x, h.semi_axis_y);
            assert_eq!(
                ax > ay,
                rx > ry,
                "the major axis lies along the larger radius"
            );
            // ∫∫ p over the ellipse with x = ax r cos θ, y = ay r sin θ, r = sin φ.
            let f = simpson(
                |phi| {
                    let r = phi.sin();
                    let p = h.pressure(ax * r, 0.0);
                    2.0 * PI * ax * ay * r * phi.cos() * p
                },
                0.0,
                PI / 2.0,
                400,
            );
            assert_close(f, h.force, 1e-9);
            assert_close(h.max_pressure, 1.5 * h.force / (PI * ax * ay), 1e-12);
            assert_close(h.pressure(0.0, 0.0), h.max_pressure, 1e-15);
            assert_eq!(h.pressure(1.01 * ax, 0.0), 0.0);
            assert_eq!(h.pressure(0.0, 1.01 * ay), 0.0);
            let back = elliptic_hertz_from_force(E, rx, ry, h.force);
            assert_close(back.approach, d, 1e-12);
            let k = derivative(
                |x| elliptic_hertz_from_approach(E, rx, ry, x).force,
                d,
                1e-4 * d,
            );
            let lambda = ax.min(ay) / ax.max(ay);
            assert_close(k, PI * ax.max(ay) * E / integrals(lambda).k, 1e-6);
        }
    }

    /// The eccentricity against Greenwood's (1985) estimate b/a ≈ (A/B)^(2/3) for moderate
    /// ellipticity (within 4% up to Rx/Ry = 10; it is 18% high at 100, beyond its range), and
    /// b/a at Rx/Ry = 10 and 100 pinned to this evaluation (regression, 1e-9; the displacement
    /// test above is the independent check of the formula).
    #[test]
    fn axis_ratio_against_the_two_thirds_rule() {
        for ratio in [1.5, 3.0, 10.0] {
            let lambda = hertz_axis_ratio(ratio);
            let approx = ratio.powf(-2.0 / 3.0);
            assert!(
                (lambda / approx - 1.0).abs() < 0.04,
                "ratio {ratio}: {lambda} vs {approx}"
            );
            let e = elliptic_hertz_eccentricity(ratio, 1.0);
            assert_close(e, (1.0 - lambda * lambda).sqrt(), 1e-12);
            assert_close(elliptic_hertz_eccentricity(1.0, ratio), e, 1e-15);
        }
        assert_close(hertz_curvature_ratio(hertz_axis_ratio(10.0)), 10.0, 1e-12);
        assert_close(hertz_axis_ratio(10.0), 0.222249519246, 1e-9);
        assert_close(hertz_axis_ratio(100.0), 0.054984018057, 1e-9);
    }

    #[test]
    fn no_contact_for_non_positive_load() {
        let h = elliptic_hertz_from_approach(E, 2.0, 1.0, -0.1);
        assert_eq!(
            (h.force, h.semi_axis_x, h.pressure(0.0, 0.0)),
            (0.0, 0.0, 0.0)
        );
        assert!(h.eccentricity > 0.0);
        assert_eq!(elliptic_hertz_from_force(E, 2.0, 1.0, 0.0).force, 0.0);
    }

    /// Rx = Ry: JKR exactly; Rx/Ry = 1 + 1e-4: the elliptic construction lands on JKR with
    /// R = √(RxRy) (the difference is O(ln²(Rx/Ry)) ≈ 1e-8; tolerance 1e-6).
    #[test]
    fn jkr_circle_limit() {
        let (gamma, r) = (0.02, 3.0);
        let p = elliptic_jkr_pull_off(E, gamma, r, r);
        assert_close(p.force_control.force, -1.5 * PI * gamma * r, 1e-12);
        assert_close(p.jump_off.force, -5.0 / 6.0 * PI * gamma * r, 1e-12);
        assert_close(p.approach_control.force, -1.5 * PI * gamma * r, 1e-12);
        for ratio in [1.0f64 + 1e-4, 1.0 / (1.0 + 1e-4)] {
            let (rx, ry) = (r * ratio.sqrt(), r / ratio.sqrt());
            let q = elliptic_jkr_pull_off(E, gamma, rx, ry);
            assert_close(q.force_control.force, -1.5 * PI * gamma * r, 1e-6);
            assert_close(q.approach_control.force, -1.5 * PI * gamma * r, 1e-6);
            assert_close(q.jump_off.force, -5.0 / 6.0 * PI * gamma * r, 1e-6);
            assert_close(
                q.jump_off.approach,
                jkr_jump_off(E, gamma, r).approach,
                1e-6,
            );
            assert_close(
                q.force_control.semi_axis_x,
                jkr_pull_off_radius(E, gamma, r),
                1e-4,
            );
        }
    }

    /// Vanishing adhesion: the family's large contacts are Hertz's (eccentricity and force at
    /// the same approach, 1e-6 at γ → 1e-9 of the scale).
    #[test]
    fn jkr_states_tend_to_hertz() {
        let (rx, ry) = (5.0, 1.0);
        let (big, small) = (rx, ry);
        let lambda_h = hertz_axis_ratio(big / small);
        let gamma = 1e-12;
        let (a, b, d, f) = jg_state(
            E,
            gamma,
            0.5 / big,
            0.5 / small,
            lambda_h + 1e-7 * (1.0 - lambda_h),
        );
        let h = elliptic_hertz_from_approach(E, rx, ry, d);
        assert_close(b / a, lambda_h, 1e-6);
        assert_close(a, h.semi_axis_x, 1e-3);
        assert_close(f, h.force, 1e-3);
    }

    /// The pull-off points are what they claim: the force is stationary in the family at the
    /// force-controlled pull-off, the approach at the jump-off, and both orderings agree.
    /// The pull-off per πγ√(RxRy) falls monotonically with Rx/Ry from 3/2 (Johnson &
    /// Greenwood), and so does the approach-controlled one, which here equals it.
    #[test]
    fn jkr_pull_off_falls_with_eccentricity() {
        let gamma = 0.01;
        let mut last = (1.5, 1.5);
        for ratio in [1.0, 1.5, 3.0, 10.0, 100.0, 1e3] {
            let (rx, ry) = (ratio, 1.0);
            let p = elliptic_jkr_pull_off(E, gamma, rx, ry);
            let q = elliptic_jkr_pull_off(E, gamma, ry, rx);
            assert_close(q.force_control.force, p.force_control.force, 1e-12);
            assert_close(
                q.force_control.semi_axis_y,
                p.force_control.semi_axis_x,
                1e-12,
            );
            assert!(p.force_control.semi_axis_x >= p.force_control.semi_axis_y);
            let scale = PI * gamma * (rx * ry).sqrt();
            let now = (
                -p.force_control.force / scale,
                -p.approach_control.force / scale,
            );
            assert!(
                now.0 <= last.0 + 1e-12 && now.1 <= last.1 + 1e-12,
                "ratio {ratio}: {now:?}"
            );
            assert!(now.0 > 0.0 && p.jump_off.approach < p.force_control.approach);
            assert!(p.jump_off.force > p.force_control.force);
            last = now;
        }
        // This evaluation's values (regression, 1e-5): |F|/(πγ√(RxRy)) = 1.2913 at Rx/Ry = 10,
        // 0.9160 at 100.
        for (ratio, value) in [(10.0, 1.291295), (100.0, 0.915999)] {
            let f = elliptic_jkr_pull_off(E, gamma, ratio, 1.0)
                .approach_control
                .force;
            assert_close(-f / (PI * gamma * ratio.sqrt()), value, 1e-5);
        }
    }
}
