//! Exact zero-range (JKR-limit) answers for a work of adhesion that varies over the surface:
//! axisymmetric bodies with `γ(r)` and the periodic strip punch with stripes parallel to its
//! front (docs/theory.md §3.8).
//!
//! A crack front in the JKR limit does not move while its energy release rate `G` stays at or
//! below the work of adhesion of the bond it would break, and recedes while `G` exceeds it.
//! Under approach control the front at radius `a` of an axisymmetric body pulled to approach
//! `d` has (Johnson, Kendall, Roberts 1971; Maugis 2000, §5)
//!
//! `G(a, d) = E*(a²/R − d)²/(2πa)`,   `F(a, d) = 4E*a³/(3R) − 2E*a(a²/R − d)`,
//!
//! with `R = ∞` for a flat punch (`G = E*d²/(2πa)`, `F = 2E*ad`: Kendall). With `γ(r)`, the
//! front recedes from where it was to the first radius inward where `G ≤ γ(a⁻)` (the bond just
//! inside the front); where no such radius exists the body detaches. This gives the whole
//! retraction path, its stick-slip jumps included ([`axisymmetric_retraction`]).

/// The energy release rate `E*(a²/R − d)²/(2πa)` at the edge of an axisymmetric contact of
/// radius `a > 0` of a sphere of radius `R` (`f64::INFINITY`: a flat punch) at approach `d`,
/// for a front under tension (`a²/R ≥ d`).
pub fn axisymmetric_release_rate(e_star: f64, radius: f64, a: f64, d: f64) -> f64 {
    let s = a * a / radius - d;
    e_star * s * s / (2.0 * std::f64::consts::PI * a)
}

/// The force `4E*a³/(3R) − 2E*a(a²/R − d)` on an axisymmetric contact of radius `a` of a sphere
/// of radius `R` (`f64::INFINITY`: a flat punch, `2E*ad`) at approach `d`; compressive positive.
pub fn axisymmetric_force(e_star: f64, radius: f64, a: f64, d: f64) -> f64 {
    4.0 * e_star * a * a * a / (3.0 * radius) - 2.0 * e_star * a * (a * a / radius - d)
}

/// Scan steps per `a_start` of [`receding_front`]: a stable stretch of the front narrower than
/// `a_start/RECEDE_SCAN` can be stepped over.
pub const RECEDE_SCAN: usize = 1 << 14;

/// Where a front at `a_start` comes to rest when `excess(a) = G(a) − γ(a⁻)` is what drives it:
/// `a_start` itself when `excess(a_start) ≤ 0`, else the largest `a < a_start` with
/// `excess(a) ≤ 0` (scanned inward in steps of `a_start/`[`RECEDE_SCAN`], then bisected to
/// round-off), or `None` when there is none above zero (the body detaches).
pub fn receding_front(a_start: f64, excess: impl Fn(f64) -> f64) -> Option<f64> {
    if excess(a_start) <= 0.0 {
        return Some(a_start);
    }
    let h = a_start / RECEDE_SCAN as f64;
    let mut outer = a_start;
    for k in (1..RECEDE_SCAN).rev() {
        let a = h * k as f64;
        if excess(a) <= 0.0 {
            // Bisect (a, outer]: excess(a) ≤ 0 < excess(outer).
            let mut inner = a;
            for _ in 0..200 {
                let mid = 0.5 * (inner + outer);
                if mid <= inner || mid >= outer {
                    break;
                }
                if excess(mid) <= 0.0 {
                    inner = mid;
                } else {
                    outer = mid;
                }
            }
            return Some(inner);
        }
        outer = a;
    }
    None
}

/// One state of [`axisymmetric_retraction`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatternedState {
    /// The approach.
    pub approach: f64,
    /// The contact radius, `None` once detached.
    pub radius: Option<f64>,
    /// The force (0 once detached; tensile negative).
    pub force: f64,
}

/// The exact zero-range retraction of an axisymmetric body (sphere of radius `radius`, or a
/// flat punch with `f64::INFINITY`) bonded over a disc of radius `a_start`, with the work of
/// adhesion `gamma(r)`, through the non-increasing `approaches`: at each the front recedes by
/// [`receding_front`] from where the previous one left it. A front the approach puts under
/// compression (`a²/R < d`) does not move.
pub fn axisymmetric_retraction(
    e_star: f64,
    radius: f64,
    gamma: impl Fn(f64) -> f64,
    a_start: f64,
    approaches: &[f64],
) -> Vec<PatternedState> {
    let mut a = Some(a_start);
    approaches
        .iter()
        .map(|&d| {
            a = a.and_then(|a0| {
                receding_front(a0, |r| {
                    if r * r / radius < d {
                        return -1.0;
                    }
                    axisymmetric_release_rate(e_star, radius, r, d) - gamma(r)
                })
            });
            PatternedState {
                approach: d,
                radius: a,
                force: a.map_or(0.0, |r| axisymmetric_force(e_star, radius, r, d)),
            }
        })
        .collect()
}

/// The mean tension `|p̄| = sqrt(2E*γ·tan(πc/λ)/λ)` at which the straight fronts of a periodic
/// strip punch of contact half-width `c` and period `λ` move against the work of adhesion `γ`
/// (the edge field `K = |p̄|·sqrt(λ/tan(πc/λ))` with Griffith's `K² = 2E*γ`).
pub fn strip_punch_release_tension(e_star: f64, gamma: f64, period: f64, c: f64) -> f64 {
    let psi = std::f64::consts::PI * c / period;
    (2.0 * e_star * gamma * psi.tan() / period).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{jkr_force_from_approach, jkr_pull_off_approach, jkr_pull_off_force};

    #[test]
    fn uniform_gamma_gives_the_jkr_curve_under_approach_control() {
        // Loaded to a_0 = 2 a_c (no adhesion on the way in: the zero-range model's Hertz
        // loading), the front is pinned until G = γ, then follows the JKR curve exactly.
        let (e, g, r) = (1.0, 0.05, 1.0);
        let a_c = crate::jkr_pull_off_radius(e, g, r);
        let d_pin = (2.0 * a_c) * (2.0 * a_c) / r;
        let d_jkr = jkr_pull_off_approach(e, g, r);
        let ds: Vec<f64> = (0..400)
            .map(|k| d_pin - (d_pin - 1.2 * d_jkr) * k as f64 / 399.0)
            .collect();
        let path = axisymmetric_retraction(e, r, |_| g, 2.0 * a_c, &ds);
        let mut f_min = 0.0f64;
        for s in &path {
            f_min = f_min.min(s.force);
            let a = s
                .radius
                .expect("attached down to the JKR pull-off approach");
            if a < 2.0 * a_c * (1.0 - 1e-9) {
                let f = jkr_force_from_approach(e, g, r, s.approach).unwrap();
                assert!(
                    (s.force - f).abs() < 1e-9 * jkr_pull_off_force(g, r).abs(),
                    "{s:?} vs {f}"
                );
            } else {
                // Pinned: the force is Hertz's bonded disc, linear in d.
                let f = axisymmetric_force(e, r, a, s.approach);
                assert_eq!(s.force, f);
            }
        }
        assert!(
            (f_min / jkr_pull_off_force(g, r) - 1.0).abs() < 1e-4,
            "{f_min}"
        );
    }

    #[test]
    fn a_flat_punch_lets_go_at_kendall_and_a_strong_core_holds_it() {
        let (e, a) = (1.0, 1.0);
        let (g_rim, g_core, r1) = (0.01, 0.08, 0.7);
        let kendall = |g: f64, a: f64| (8.0 * std::f64::consts::PI * a.powi(3) * e * g).sqrt();
        // Uniform: detaches at the Kendall approach with force √(8πa³E*γ).
        let d_k = -(2.0 * std::f64::consts::PI * a * g_rim / e).sqrt();
        let ds = [0.0, 0.999 * d_k, 1.001 * d_k];
        let path = axisymmetric_retraction(e, f64::INFINITY, |_| g_rim, a, &ds);
        assert_eq!(path[1].radius, Some(a));
        assert!((path[1].force / (0.999 * -kendall(g_rim, a)) - 1.0).abs() < 1e-12);
        assert_eq!(path[2].radius, None);
        // A weak rim r > r1: the front jumps to r1 and holds until √(8π r1³E*γ_core).
        let gamma = |r: f64| if r < r1 { g_core } else { g_rim };
        let d_core = -(2.0 * std::f64::consts::PI * r1 * g_core / e).sqrt();
        let ds = [1.001 * d_k, 0.999 * d_core, 1.001 * d_core];
        let path = axisymmetric_retraction(e, f64::INFINITY, gamma, a, &ds);
        assert!((path[0].radius.unwrap() - r1).abs() < 1e-12, "{path:?}");
        assert!((path[1].force / (0.999 * -kendall(g_core, r1)) - 1.0).abs() < 1e-9);
        assert_eq!(path[2].radius, None);
    }

    #[test]
    fn receding_front_stops_on_the_inner_side_of_a_step_and_detaches_without_one() {
        // excess > 0 outside 0.3, ≤ 0 inside: the front stops at 0.3 from below.
        let a = receding_front(1.0, |r| if r < 0.3 { -1.0 } else { 1.0 }).unwrap();
        assert!(a < 0.3 && 0.3 - a < 1e-14, "{a}");
        assert_eq!(receding_front(1.0, |_| 1.0), None);
        assert_eq!(receding_front(1.0, |_| 0.0), Some(1.0));
    }

    #[test]
    fn strip_punch_tension_is_griffith_on_the_closed_form_edge_field() {
        let (e, g, l, c) = (2.0, 0.1, 1.0, 0.2);
        let p = strip_punch_release_tension(e, g, l, c);
        let psi = std::f64::consts::PI * c / l;
        let k = p * (l / psi.tan()).sqrt();
        assert!((k * k / (2.0 * e) / g - 1.0).abs() < 1e-14);
    }
}
