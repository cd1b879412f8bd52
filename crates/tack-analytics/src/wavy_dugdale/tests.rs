//! Tests of the Maugis–Dugdale wavy contact: the limits, the quadrature and the branches.

use super::*;
use crate::johnson::{johnson_1d_mean_pressure_ratio, johnson_alpha};
use crate::quad::assert_close;
use crate::westergaard::westergaard_mean_pressure;

/// The Westergaard trough gap 2C − 2S² asinh(C/S) in units of h.
fn trough_gap(psi: f64) -> f64 {
    let (s, c) = psi.sin_cos();
    westergaard_zone_gap(s, c)
}

/// u(ξ)/h for the pressure of `p` by the periodic log kernel in x (no map to t):
/// u = −2 ∫ p̂(σ) ln|2 sin(π(ξ − σ))| dσ over the period centred on ξ, split at ξ and at
/// ±a, ±c (and their images), each piece by tanh-sinh with step 1/64 (513 nodes).
fn displacement(p: &WavyDugdalePoint, xi: f64, rule: &TanhSinh) -> f64 {
    let (lo, hi) = (xi - 0.5, xi + 0.5);
    let mut cuts = vec![lo, hi, xi];
    for edge in [p.psi_a / PI, p.psi_c / PI] {
        for e in [-edge - 1.0, 1.0 - edge, -edge, edge, edge - 1.0, edge + 1.0] {
            if e > lo && e < hi {
                cuts.push(e);
            }
        }
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    // In the offset d = σ − ξ, so that the node next to the log singularity is a tiny d,
    // never σ = ξ rounded.
    let kernel = |d: f64| p.pressure_ratio(xi + d) * (2.0 * (PI * d).sin()).abs().ln();
    -2.0 * cuts
        .windows(2)
        .map(|w| rule.integrate(kernel, w[0] - xi, w[1] - xi))
        .sum::<f64>()
}

/// f/h + u/h, the gap up to the constant approach.
fn gap_plus_approach(p: &WavyDugdalePoint, xi: f64, rule: &TanhSinh) -> f64 {
    1.0 - (2.0 * PI * xi).cos() + displacement(p, xi, rule)
}

/// Independent check of the whole solution in x, by superposition with the periodic
/// (Westergaard-type) log kernel instead of the t-map and the closed-form M: the pressure
/// of the point (closed-form contact pressure, −σ0 in the zone) must (i) average to p̄,
/// (ii) keep the gap constant (zero) over the contact, (iii) open it to exactly h0 at x = c,
/// (iv) be −σ0 at the contact edge (bounded stress), and (v) leave 0 < gap < h0 in the zone
/// and gap > h0 beyond. The quadrature (tanh-sinh, step 1/64, on pieces whose ends carry
/// the log and square-root singularities; an mpmath evaluation agrees) is good to rounding
/// here; tolerance 1e-12 in units
/// of h and p* (measured ≤ 4e-15). One saturated state: there the trough gap is ≤ h0.
#[test]
fn superposition_satisfies_contact_and_gap_conditions() {
    let rule = TanhSinh::new(1.0 / 64.0);
    for (alpha, lambda_w, psi) in [
        (0.3, 1.0, 0.4),
        (0.1, 0.5, 0.1),
        (0.5, 3.0, 0.8),
        (0.1, 0.5, 0.8),
        (0.3, 1.0, 0.9),
        (0.2, 20.0, 0.25),
        (0.3, 0.3, 1.0),
    ] {
        let p = wavy_dugdale_point(alpha, lambda_w, psi);
        let (a, c) = (p.psi_a / PI, p.psi_c / PI);
        let mean = rule.integrate(|x| p.pressure_ratio(x), -0.5, -c)
            + rule.integrate(|x| p.pressure_ratio(x), -c, -a)
            + rule.integrate(|x| p.pressure_ratio(x), -a, a)
            + rule.integrate(|x| p.pressure_ratio(x), a, c)
            + rule.integrate(|x| p.pressure_ratio(x), c, 0.5);
        assert!(
            (mean - p.mean_pressure_ratio).abs() < 1e-12,
            "{p:?}: {mean}"
        );
        let g0 = gap_plus_approach(&p, 0.0, &rule);
        for frac in [0.3, 0.7, 1.0] {
            let g = gap_plus_approach(&p, frac * a, &rule) - g0;
            assert!(g.abs() < 1e-12, "{p:?}: gap {g:e} at {frac} a");
        }
        let range = PI * alpha * alpha / (2.0 * p.stress_ratio);
        // 1e-12 a inside the edge the pressure is −s0 up to O(√1e-12) (measured 1.2e-5 s0).
        let edge = p.pressure_ratio(a * (1.0 - 1e-12));
        assert!(
            (edge + p.stress_ratio).abs() < 1e-4 * p.stress_ratio,
            "{edge}"
        );
        if p.saturated {
            // The whole gap is in the zone: the trough gap is at most h0.
            let trough = gap_plus_approach(&p, 0.5, &rule) - g0;
            assert!(
                trough <= range && trough > 0.0,
                "{p:?}: trough gap {trough}"
            );
            continue;
        }
        let gc = gap_plus_approach(&p, c, &rule) - g0;
        assert!(
            (gc - range).abs() < 1e-12,
            "{p:?}: gap(c) {gc} vs h0 {range}"
        );
        for frac in [0.25, 0.5, 0.75] {
            let g = gap_plus_approach(&p, a + frac * (c - a), &rule) - g0;
            assert!(g > 0.0 && g < range, "{p:?}: zone gap {g}");
            let g = gap_plus_approach(&p, c + frac * (0.5 - c), &rule) - g0;
            assert!(g > range, "{p:?}: free gap {g}");
        }
    }
}

/// JKR limit: p̄/p* → sin²ψ − α√tanψ (Johnson 1995) as λ_w → ∞, the error falling like
/// λ_w⁻² (ratio of the errors at λ_w = 100 and 1000 measured 99.96–100.24; accepted 90–110).
/// At λ_w = 1000 the measured error is at most 5.4e-7 (α = 0.5, ψ = 0.05); bound 1e-6.
#[test]
fn jkr_limit_is_johnson() {
    for alpha in [0.1, 0.3, 0.5] {
        for psi in [0.05, 0.3, 0.8, 1.2] {
            let j = johnson_1d_mean_pressure_ratio(alpha, psi);
            let e100 = wavy_dugdale_mean_pressure_ratio(alpha, 100.0, psi) - j;
            let e1000 = wavy_dugdale_mean_pressure_ratio(alpha, 1000.0, psi) - j;
            assert!(e1000.abs() < 1e-6, "α {alpha} ψ {psi}: {e1000:e}");
            let ratio = e100 / e1000;
            assert!((90.0..110.0).contains(&ratio), "α {alpha} ψ {psi}: {ratio}");
        }
    }
}

/// Westergaard limits. (a) γ → 0 at fixed σ0 (physical inputs): the adhesive term
/// p̄ − p* sin²ψ is negative and smaller than Johnson's α√tanψ p*, so it vanishes like √γ
/// (checked: falls by 10 ± 1 per 100× in γ; at γ = 1e-12, α ≈ 4e-5, it is at most 6.8e-5 p*,
/// bound 1e-4 p*). (b) λ_w → 0 at
/// fixed α: the range h0 exceeds 2h, the zone saturates and p̄/p* = sin²ψ − s0 with
/// s0 ∝ λ_w → 0 (rounding only).
#[test]
fn westergaard_limits() {
    let (e, h, l, sigma0) = (2.0, 0.01, 1.5, 0.05);
    let p_star = PI * e * h / l;
    for a in [0.05 * l, 0.2 * l, 0.4 * l] {
        let psi = PI * a / l;
        let mut prev = f64::NAN;
        for gamma in [1e-8, 1e-10, 1e-12] {
            let p = wavy_dugdale_mean_pressure(e, gamma, h, l, sigma0, a);
            let d = p - westergaard_mean_pressure(e, h, l, a);
            let johnson = johnson_alpha(e, gamma, h, l) * psi.tan().sqrt() * p_star;
            assert!(d < 0.0 && -d <= johnson, "a {a}: {d:e} vs {johnson:e}");
            if prev.is_finite() {
                assert!((9.0..11.0).contains(&(prev / d)), "a {a}: {}", prev / d);
            }
            prev = d;
        }
        assert!(prev.abs() < 1e-4 * p_star);
    }
    for lambda_w in [1e-2, 1e-4] {
        let alpha = 0.3;
        let s0 = wavy_dugdale_stress_ratio(alpha, lambda_w);
        assert!(PI * alpha * alpha / (2.0 * s0) > 2.0);
        for psi in [0.0, 0.3, 1.0] {
            let p = wavy_dugdale_point(alpha, lambda_w, psi);
            assert!(p.saturated && p.psi_c == FRAC_PI_2);
            assert_close(p.mean_pressure_ratio + s0, psi.sin().powi(2), 1e-14);
        }
    }
}

/// Baney & Hui (1997) Maugis cylinder, their Eq. 23 for m = b/a and P = ā² − λāμ, μ =
/// √(m² − 1): a small contact at the crest (α → 0) sees a cylinder of radius λ²/(4π²h),
/// and with λ_w their λ, ā = 2^(2/3) ψ/α^(2/3) and p̄/p* = P α^(4/3)/2^(4/3) (scales
/// worked out from their units 2(γR²/(πE*))^(1/3) and (πE*γ²R)^(1/3)). The difference comes
/// from the curvature of the map, O(ψ²) ∝ α^(4/3): measured relative errors up to 3.3e-3
/// at α = 1e-2 and 1.5e-4 at α = 1e-3 (largest at ā = 2), their ratio 21.56–21.60 for every
/// (λ, ā), i.e. 10^(4/3) = 21.54; bounds 1e-2 and 5e-4, ratio 20–23.
#[test]
fn cylinder_limit_is_baney_hui() {
    let baney_hui = |lam: f64, a: f64| {
        let f = |m: f64| {
            let mu = ((m - 1.0) * (m + 1.0)).sqrt();
            lam * a * a / 2.0 * (m * mu - (m + mu).ln())
                + lam * lam * a / 2.0 * (mu * (m + mu).ln() - m * m.ln())
                - 1.0
        };
        let (mut lo, mut hi) = (1.0, 2.0);
        while f(hi) < 0.0 {
            hi *= 2.0;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if f(mid) < 0.0 { lo = mid } else { hi = mid }
        }
        let m = 0.5 * (lo + hi);
        a * a - lam * a * ((m - 1.0) * (m + 1.0)).sqrt()
    };
    for lam in [0.3, 1.0, 5.0] {
        for a_bar in [0.3, 1.0, 2.0] {
            let mut errors = Vec::new();
            for alpha in [1e-2f64, 1e-3] {
                let psi = 2f64.powf(-2.0 / 3.0) * alpha.powf(2.0 / 3.0) * a_bar;
                let scale = alpha.powf(4.0 / 3.0) / 2f64.powf(4.0 / 3.0);
                let expected = baney_hui(lam, a_bar) * scale;
                let got = wavy_dugdale_mean_pressure_ratio(alpha, lam, psi);
                errors.push((got - expected).abs() / expected.abs().max(scale));
            }
            assert!(
                errors[0] < 1e-2 && errors[1] < 5e-4,
                "λ {lam} ā {a_bar}: {errors:?}"
            );
            let ratio = errors[0] / errors[1];
            assert!((20.0..23.0).contains(&ratio), "λ {lam} ā {a_bar}: {ratio}");
        }
    }
}

/// Regression pins against an independent evaluation of the same equations in Python with
/// mpmath (30 digits; its own tanh-sinh quadrature of M, scan and bisection): M to 1e-15
/// relative (measured ≤ 4.5e-16), θ and p̄ to 1e-14 absolute (measured ≤ 1.6e-16).
#[test]
fn matches_independent_mpmath_evaluation() {
    let w = Wave::new(0.3, 1.0);
    for (psi, th, m) in [
        (0.0, 0.7, 0.849_877_851_484_453_6),
        (0.3, 1e-3, 3.383_850_446_224_116e-6),
        (0.3, 0.9, 0.883_495_570_981_647_8),
        (1.2, 1.5, 0.377_987_501_436_165_7),
        (0.05, 0.4, 0.517_929_647_674_125_2),
    ] {
        let (s, c) = f64::sin_cos(psi);
        assert_close(w.m(s, c, th), m, 1e-15);
    }
    for (alpha, lambda_w, psi, th, p) in [
        (
            0.3,
            1.0,
            0.4,
            0.485_952_375_528_307_15,
            0.014_457_037_218_679_175,
        ),
        (
            0.1,
            0.5,
            0.1,
            0.279_009_127_613_651_6,
            -0.008_966_971_200_252_623,
        ),
        (
            0.5,
            3.0,
            0.8,
            0.406_966_890_315_417_7,
            0.030_085_008_798_453_673,
        ),
        (
            0.3,
            1.0,
            0.0,
            0.319_210_390_217_220_9,
            -0.090_116_543_396_273_1,
        ),
    ] {
        let q = wavy_dugdale_point(alpha, lambda_w, psi);
        assert!((q.theta_c - th).abs() < 1e-14, "{q:?}");
        assert!((q.mean_pressure_ratio - p).abs() < 1e-14, "{q:?}");
    }
}

/// The 129-node rule of M against a 1025-node one (step 1/128), including a point contact
/// (ψ = 0), a contact much narrower than the zone (ψ = 1e-8, where the weight
/// sinβ/√(S² + C² sin²β) turns over at β ~ 1e-8), a tiny zone and one near saturation:
/// measured ≤ 4e-16 relative; tolerance 1e-14.
#[test]
fn quadrature_of_m_is_converged() {
    let coarse = Wave::new(0.3, 1.0);
    let mut fine = Wave::new(0.3, 1.0);
    fine.rule = TanhSinh::new(1.0 / 128.0);
    for psi in [0.0, 1e-8, 0.01, 0.7, 1.5] {
        for th in [1e-9, 1e-3, 0.5, 1.2, 1.57] {
            let (s, c) = f64::sin_cos(psi);
            assert_close(coarse.m(s, c, th), fine.m(s, c, th), 1e-14);
        }
    }
}

/// The Westergaard part: the series of r√(1+r²) − asinh r against the direct form where
/// both are accurate (r = 0.5: the direct form loses ~1 digit; 1e-14), its leading term
/// (2/3)r³ for tiny r, and the ψ → 0 end 2w² (rounding).
#[test]
fn westergaard_gap_series() {
    let r: f64 = 0.5;
    assert_close(
        root_minus_asinh_series(r),
        r * r.hypot(1.0) - r.asinh(),
        1e-14,
    );
    assert_close(root_minus_asinh_series(1e-6), 2e-18 / 3.0, 1e-11);
    assert_close(westergaard_zone_gap(1e-300, 0.3), 0.18, 1e-14);
    assert_eq!(westergaard_zone_gap(0.0, 0.3), 2.0 * 0.3 * 0.3);
    // Full contact closes the trough gap; touching leaves the peak-to-valley 2h.
    assert!(trough_gap(FRAC_PI_2 - 1e-4) < 1e-7);
    assert_eq!(trough_gap(0.0), 2.0);
}

/// Saturation: where no partial zone satisfies the gap condition the state is saturated,
/// p̄/p* = sin²ψ − s0, and the Westergaard trough gap is then below h0 (rounding); where a
/// partial zone exists its zone-end gap is h0 (rounding: 1e-14 of h0).
#[test]
fn saturated_and_partial_states_are_consistent() {
    let mut seen = [false; 2];
    for (alpha, lambda_w) in [(0.3, 0.3), (0.5, 0.5), (0.8, 0.4)] {
        let w = Wave::new(alpha, lambda_w);
        for k in 0..40 {
            let psi = 1.5 * k as f64 / 39.0;
            let p = wavy_dugdale_point(alpha, lambda_w, psi);
            let (s, c) = psi.sin_cos();
            if p.saturated {
                seen[0] = true;
                assert!(trough_gap(psi) <= w.range, "{p:?}");
                assert_close(p.mean_pressure_ratio, s * s - w.s0, 1e-14);
            } else {
                seen[1] = true;
                assert_close(w.zone_end_gap(s, c, p.theta_c), w.range, 1e-14);
                assert!(p.psi_c > psi && p.psi_c < FRAC_PI_2);
            }
        }
    }
    assert!(seen[0] && seen[1]);
}

/// Pull-off under load control. JKR limit: the minimum of Johnson's law (golden section to
/// 1e-12 in ψ); the error falls like λ_w⁻⁴ (measured 1.9e-7…2.9e-6 at λ_w = 10, 1.9e-11…3.0e-10
/// at 100, ratio 9760–9840; accepted 9000–11000), and at λ_w = 1000 it is ≤ 3e-14 (bound 1e-12).
/// Table (regression pins of this implementation, 1e-9): for small λ_w the zone saturates at
/// ψ = 0 and the pull-off is −s0 (all of the period in tension), rising towards Johnson's
/// value as λ_w grows; between, it is not monotonic in λ_w for α = 0.5 (−s0 at 0.3 beats the
/// value at 1.0). For α = 1.5 Johnson's law has no local minimum (p̄ falls all the way) and
/// neither has the JKR-like Dugdale branch.
#[test]
fn pull_off_table_and_jkr_limit() {
    for alpha in [0.05, 0.1, 0.3, 0.5, 0.8] {
        let (_, johnson_min) = golden_min(
            |x| johnson_1d_mean_pressure_ratio(alpha, x),
            1e-12,
            1.0,
            1e-12,
        );
        let p = wavy_dugdale_pull_off_ratio(alpha, 1000.0).unwrap();
        assert!(
            (p - johnson_min).abs() < 1e-12,
            "α {alpha}: {p} vs {johnson_min}"
        );
        let e10 = wavy_dugdale_pull_off_ratio(alpha, 10.0).unwrap() - johnson_min;
        let e100 = wavy_dugdale_pull_off_ratio(alpha, 100.0).unwrap() - johnson_min;
        assert!(
            (9000.0..11000.0).contains(&(e10 / e100)),
            "α {alpha}: {}",
            e10 / e100
        );
    }
    for (alpha, lambda_w, expected) in [
        (0.1, 0.1, -0.008_775_460_103),
        (0.1, 1.0, -0.020_594_259_691),
        (0.1, 10.0, -0.021_983_768_155),
        (0.3, 0.1, -0.044_345_278_126),
        (0.3, 1.0, -0.090_525_660_010),
        (0.3, 10.0, -0.095_942_228_376),
        (0.5, 0.3, -0.187_011_280_619),
        (0.5, 1.0, -0.182_964_936_469),
    ] {
        let p = wavy_dugdale_pull_off_ratio(alpha, lambda_w).unwrap();
        assert!((p - expected).abs() < 1e-9, "α {alpha} λ_w {lambda_w}: {p}");
    }
    // Saturated at the junction: the pull-off is −s0.
    assert_close(
        wavy_dugdale_pull_off_ratio(0.3, 0.1).unwrap(),
        -wavy_dugdale_stress_ratio(0.3, 0.1),
        1e-14,
    );
    assert_eq!(wavy_dugdale_pull_off_ratio(1.5, 1000.0), None);
}

/// Hand value of the parameters: E* = 1, γ = 1e-4, h = 0.01, λ = 1, σ0 = 0.02 give
/// R = 1/(0.04π²) and λ_w = 0.08 (R/(π²·1e-4))^(1/3); and s0 = σ0/p* = 0.02/(0.01π)
/// from α and λ_w (rounding).
#[test]
fn parameters_hand_values() {
    let (e, gamma, h, l, sigma0) = (1.0, 1e-4, 0.01, 1.0, 0.02);
    let r = 1.0 / (0.04 * PI * PI);
    let lambda_w = wavy_dugdale_lambda(e, gamma, h, l, sigma0);
    assert_close(lambda_w, 0.08 * (r / (PI * PI * 1e-4)).cbrt(), 1e-15);
    let alpha = johnson_alpha(e, gamma, h, l);
    assert_close(
        wavy_dugdale_stress_ratio(alpha, lambda_w),
        sigma0 / (PI * e * h / l),
        1e-14,
    );
}

#[test]
#[should_panic(expected = "alpha")]
fn refuses_zero_alpha() {
    let _ = wavy_dugdale_point(0.0, 1.0, 0.3);
}

#[test]
#[should_panic(expected = "psi_a")]
fn refuses_full_contact() {
    let _ = wavy_dugdale_point(0.3, 1.0, FRAC_PI_2);
}
