//! Steady cracks in a standard linear solid: the energy release rate `G(v)/G0` a front running
//! at speed `v` needs, Greenwood & Johnson (1981) for a Dugdale zone and Persson & Brener (2005)
//! with a fixed cut-off. Both run from 1 (slow) to `E∞/E0` (fast).
//!
//! The solid: `E(t) = E0 + E1 e^(−t/τ)` in plane-strain moduli, `E∞ = E0 + E1`, its creep
//! compliance `J(t) = 1/E0 − (1/E0 − 1/E∞) e^(−t/τ_r)` with the retardation time
//! `τ_r = τE∞/E0`. `G` is referred to the relaxed modulus, `G = K²/(2E0)` for a half-space
//! against a rigid face.

use std::f64::consts::PI;

/// `∫₀¹ g(s) ds` by Simpson's rule on intervals graded geometrically towards both ends
/// (breakpoints 2^−k and 1 − 2^−k, k ≤ 60, 32 panels each): the integrands below have their
/// scale at `s ~ 1/β` (as small as 1e-12 in the tests) and root singularities at the ends.
fn graded(g: impl Fn(f64) -> f64) -> f64 {
    let mut points: Vec<f64> = vec![0.0, 1.0, 0.5];
    for k in 2..=60 {
        let p = 0.5f64.powi(k);
        points.extend([p, 1.0 - p]);
    }
    points.sort_by(f64::total_cmp);
    points.dedup();
    points
        .windows(2)
        .map(|w| crate::quad::simpson(&g, w[0], w[1], 32))
        .sum()
}

/// The Dugdale zone's opening over its opening at the crack tip, at `s` from the tip (0) to
/// the zone's head (1): `f(s) = √(1−s) − (s/2) ln[(1+√(1−s))/(1−√(1−s))]`; f(0) = 1, f(1) = 0,
/// `f ≈ (2/3)(1−s)^(3/2)` at the head.
pub fn dugdale_zone_opening(s: f64) -> f64 {
    if s >= 1.0 {
        return 0.0;
    }
    if s <= 0.0 {
        return 1.0;
    }
    // (1+r)/(1−r) = (1+r)²/s: stable where r → 1 (at the tip).
    let r = (1.0 - s).sqrt();
    r - s * (1.0 + r).ln() + 0.5 * s * s.ln()
}

/// `φ(β) = ∫₀¹ e^(−βs)(−f′(s)) ds = 1 − β∫₀¹ e^(−βs) f(s) ds` (by parts).
fn creep_weight(beta: f64) -> f64 {
    1.0 - beta * graded(|s| (-beta * s).exp() * dugdale_zone_opening(s))
}

/// Greenwood & Johnson's `g = G(v)/G0` of a Dugdale zone (tension σ0, critical opening
/// `γ/σ0`) at a front running at `speed` in the standard linear solid `(e0, e1, tau)`; `c0` is
/// the relaxed zone's length `πE0γ/(4σ0²)`. The stresses of an opening crack are the elastic
/// ones (the zone's length `c = g·c0` follows from `K = σ0√(8c/π)`), and a material point that
/// crosses the zone in `c/v` opens by `J` acting on the elastic opening `f`, so
/// `g·[1 − (1 − E0/E∞) φ(g c0/(v τ_r))] = 1` with `φ(β) = ∫₀¹ e^(−βs)(−f′(s)) ds`, solved by
/// bisection on `[1, E∞/E0]`.
pub fn greenwood_johnson_toughening(e0: f64, e1: f64, tau: f64, c0: f64, speed: f64) -> f64 {
    let e_inf = e0 + e1;
    let (k, tau_r) = (1.0 - e0 / e_inf, tau * e_inf / e0);
    let residual = |g: f64| g * (1.0 - k * creep_weight(c0 * g / (speed * tau_r))) - 1.0;
    let (mut lo, mut hi) = (1.0, e_inf / e0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if residual(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Persson & Brener's `G(v)/G0 = 1/[1 − (2/π)∫₀^(2πv/a) dω F(ω)/ω |Im E0/E(ω)|]`,
/// `F(ω) = √(1 − (ωa/(2πv))²)`, with the fixed cut-off length `cutoff = a`, for the standard
/// linear solid `E(ω) = E0 + E1·iωτ/(1 + iωτ)`; the integral runs in `x = ωa/(2πv)`.
pub fn persson_brener_toughening(e0: f64, e1: f64, tau: f64, cutoff: f64, speed: f64) -> f64 {
    let im = |x: f64| {
        if x <= 0.0 || x >= 1.0 {
            return 0.0;
        }
        let wt = 2.0 * PI * speed * x / cutoff * tau;
        // Im[E0/E] = Im[E0(1 + iωτ)/(E0 + iωτE∞)] = −E0·E1·ωτ/(E0² + (ωτE∞)²).
        let im = e0 * e1 * wt / (e0 * e0 + (wt * (e0 + e1)).powi(2));
        (1.0 - x * x).sqrt() / x * im
    };
    1.0 / (1.0 - 2.0 / PI * graded(im))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_zone_opening_closes_smoothly_at_the_head_and_is_one_at_the_tip() {
        assert_eq!(dugdale_zone_opening(0.0), 1.0);
        for s in [0.999, 0.9999] {
            let f = dugdale_zone_opening(s);
            let head = 2.0 / 3.0 * (1.0 - s).powf(1.5);
            assert!((f / head - 1.0).abs() < 2.0 * (1.0 - s), "{f} {head}");
        }
        // Decreasing from the tip to the head.
        let f: Vec<f64> = (0..=100)
            .map(|k| dugdale_zone_opening(k as f64 / 100.0))
            .collect();
        assert!(f.windows(2).all(|w| w[1] < w[0]));
    }

    #[test]
    fn the_creep_weight_by_parts_matches_the_derivative_form() {
        // φ(β) by the midpoint rule on −f′ from central differences, an independent route.
        for beta in [0.1, 1.0, 10.0] {
            let n = 200_000;
            let h = 1.0 / n as f64;
            let direct: f64 = (0..n)
                .map(|k| {
                    let s = (k as f64 + 0.5) * h;
                    let df =
                        (dugdale_zone_opening(s + 0.5 * h) - dugdale_zone_opening(s - 0.5 * h)) / h;
                    (-beta * s).exp() * (-df) * h
                })
                .sum();
            assert!((direct - creep_weight(beta)).abs() < 1e-4, "β = {beta}");
        }
        assert!((creep_weight(0.0) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn both_toughenings_run_from_one_to_the_modulus_ratio() {
        let (e0, e1, tau, a) = (1.0, 9.0, 1.0, 0.01);
        for f in [greenwood_johnson_toughening, persson_brener_toughening] {
            let slow = f(e0, e1, tau, a, 1e-9);
            let fast = f(e0, e1, tau, a, 1e9);
            assert!((slow - 1.0).abs() < 1e-3, "slow {slow}");
            assert!((fast / 10.0 - 1.0).abs() < 2e-3, "fast {fast}");
            let g: Vec<f64> = (-6..=6)
                .map(|k| f(e0, e1, tau, a, a * 10f64.powi(k)))
                .collect();
            assert!(g.windows(2).all(|w| w[1] >= w[0]), "{g:?}");
        }
    }
}
