//! Love's (1929) closed form for the surface displacement under a uniformly loaded rectangle.

/// Centre displacement of a square element under its own unit pressure, in units of `Δx/E*`:
/// `4 ln(1 + √2)/π ≈ 1.1222`.
pub const SELF_COMPLIANCE: f64 = 1.122_199_704_678_360_3;

/// Mean displacement over a square element under its own unit pressure, in units of `Δx/E*`:
/// `(4/π)[ln(1 + √2) − (√2 − 1)/3] ≈ 0.946402` (twice the Pohrt–Popov κ).
pub const MEAN_SELF_COMPLIANCE: f64 = 0.946_402_008_818_677;

/// Vertical surface displacement at `(x, y)` times `E*/p` for a uniform pressure `p` on the
/// rectangle `|x'| ≤ a, |y'| ≤ b` (Love 1929; Johnson, *Contact Mechanics*, §3.2).
///
/// Multiply by `p/E*` to get the displacement. Evaluated with `|x|, |y|` (the kernel is even in
/// both), which keeps every logarithm argument away from cancellation.
pub fn love_rectangle(x: f64, y: f64, a: f64, b: f64) -> f64 {
    let (x, y) = (x.abs(), y.abs());
    let (k, l, m, n) = (x + a, x - a, y + b, y - b);
    let r = |s: f64, t: f64| s.hypot(t);
    (k * ((m + r(k, m)) / (n + r(k, n))).ln()
        + l * ((n + r(l, n)) / (m + r(l, m))).ln()
        + m * ((k + r(k, m)) / (l + r(l, m))).ln()
        + n * ((l + r(l, n)) / (k + r(k, n))).ln())
        / std::f64::consts::PI
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn constants_match_their_closed_forms() {
        let s2 = 2f64.sqrt();
        assert!((SELF_COMPLIANCE - 4.0 * (1.0 + s2).ln() / PI).abs() < 1e-15);
        assert!(
            (MEAN_SELF_COMPLIANCE - 4.0 / PI * ((1.0 + s2).ln() - (s2 - 1.0) / 3.0)).abs() < 1e-15
        );
    }

    #[test]
    fn self_influence_is_1_1222() {
        // Centre of a unit square (a = b = 1/2): 4 ln(1+√2)/π = 1.1222 (docs/theory.md §2.1).
        let w = love_rectangle(0.0, 0.0, 0.5, 0.5);
        assert!((w - 1.1222).abs() < 1e-4, "{w}");
        assert!((w - SELF_COMPLIANCE).abs() < 1e-14, "{w}");
    }

    #[test]
    fn mean_over_element_is_0_946402() {
        // Gauss–Legendre-free check: midpoint rule on a fine sub-grid converges to the mean
        // displacement; the integrable log singularity at the centre limits it to ~1e-4.
        let m = 400;
        let mut sum = 0.0;
        for i in 0..m {
            for j in 0..m {
                let x = (i as f64 + 0.5) / m as f64 - 0.5;
                let y = (j as f64 + 0.5) / m as f64 - 0.5;
                sum += love_rectangle(x, y, 0.5, 0.5);
            }
        }
        let mean = sum / (m * m) as f64;
        assert!((mean - MEAN_SELF_COMPLIANCE).abs() < 1e-4, "{mean}");
    }

    #[test]
    fn far_field_tends_to_point_load() {
        // u → F/(π E* r) with F = p·(2a)(2b); relative correction O((a/r)²).
        for r in [10.0, 30.0, 100.0] {
            let w = love_rectangle(r * 0.6, r * 0.8, 0.5, 0.5);
            let point = 1.0 / (PI * r);
            let rel = (w - point).abs() / point;
            assert!(rel < 0.1 / (r * r), "r = {r}: rel = {rel}");
        }
    }

    #[test]
    fn symmetric_in_both_axes_and_rectangles_swap() {
        let w = love_rectangle(1.3, -2.1, 0.5, 0.7);
        assert_eq!(w, love_rectangle(-1.3, 2.1, 0.5, 0.7));
        assert!((w - love_rectangle(-2.1, 1.3, 0.7, 0.5)).abs() < 1e-14);
    }
}
