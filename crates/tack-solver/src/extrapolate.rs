//! Richardson extrapolation of mesh-dependent results: the Pohrt–Popov criterion and the
//! Dugdale law converge at first order in Δx, the smooth laws at second, so two resolutions
//! cancel the leading error term at the law's order. Also the observed order of convergence
//! from three resolutions, and an error estimate for the pull-off force.

/// `2·fine − coarse`: the first-order Richardson extrapolation of a quantity computed at
/// element size Δx (`fine`) and 2Δx (`coarse`) on the same geometry.
///
/// Measured on the smooth sphere with the paper's criterion (`cargo xtask bench-jkr`): the
/// pull-off force errors +14.1% (a_c/Δx = 10) and +6.9% (20) extrapolate to −0.33%; +16.7% (8)
/// and +8.1% (16) to −0.51%; +6.9% (20) and +3.5% (40) to +0.16%. Only meaningful when the
/// geometry does not change with the mesh (spheres, waviness, punches; not random roughness
/// whose cut-off follows the grid, q1 = π/Δx).
pub fn richardson_first_order(fine: f64, coarse: f64) -> f64 {
    2.0 * fine - coarse
}

/// The Richardson extrapolation of a quantity whose error is `c·Δxᵖ` (`order` p), computed at
/// element size Δx (`fine`) and 2Δx (`coarse`): `fine + (fine − coarse)/(2ᵖ − 1)`, exactly
/// [`richardson_first_order`] for p = 1 (its bits too). The laws' own orders:
/// [`crate::Law::convergence_order`].
pub fn richardson(fine: f64, coarse: f64, order: f64) -> f64 {
    if order == 1.0 {
        richardson_first_order(fine, coarse)
    } else {
        fine + (fine - coarse) / (2f64.powf(order) - 1.0)
    }
}

/// Observed order of convergence p of a quantity computed at element sizes 4Δx (`coarse`),
/// 2Δx (`medium`) and Δx (`fine`) on the same geometry (docs/theory.md §9):
/// `p = log2(|coarse − medium| / |medium − fine|)`.
///
/// An error c·Δx^p makes the two differences c(2^p − 1)(2Δx)^p and c(2^p − 1)Δx^p, whose ratio
/// is 2^p; [`richardson_first_order`] assumes p = 1. The absolute values ignore the sign of the
/// error, so a sequence that alternates about its limit gives the order of its envelope. A
/// negative p means the changes grow with refinement (not yet asymptotic, or not converging).
/// Two equal levels give ±∞ (one difference zero) or NaN (both zero).
pub fn observed_order(coarse: f64, medium: f64, fine: f64) -> f64 {
    ((coarse - medium).abs() / (medium - fine).abs()).log2()
}

/// First-order error coefficient of the paper's criterion on the smooth sphere:
/// `F/F_JKR − 1 ≈ 1.4·Δx/a_c` (+14.1%, +6.9%, +3.5% at a_c/Δx = 10, 20, 40; docs/theory.md §9).
pub const CRITERION_ERROR_COEFFICIENT: f64 = 1.4;

/// An estimate of how far the pull-off force `fine` (element size Δx) is from converged, from
/// the same run at 2Δx (`coarse`) and, for a sphere, `dx_over_a_c` = Δx/a_c:
/// `max(|fine − coarse|, 1.4·(Δx/a_c)·|fine|)`; without a sphere `|fine − coarse|`.
///
/// `|fine − coarse|` alone is the error of `fine` when the error is first order in Δx, as on
/// the smooth sphere; at second order (the smooth laws) it is three times the asymptotic error,
/// kept so because their pull-offs are not always asymptotic on the grids used. Rough and wavy fronts do not converge that cleanly: their pull-off
/// changes by fits and starts between levels (observed orders from −3.8 to +5.8), so two levels
/// may agree by accident. Measured on 9 bodies at n = 128, 256, 512 against n = 1024
/// (`cargo xtask convergence`, README): `|fine − coarse|` covered the actual error in 14 of 27
/// cases (worst: 28× too small), this estimate in 26 (the miss: a wavy sphere whose pull-off
/// changed branch between λ = 8Δx and 16Δx). The second term is the criterion's smooth-sphere
/// bias at the same a_c/Δx, a floor that rough fronts did not beat.
pub fn pull_off_error_estimate(fine: f64, coarse: f64, dx_over_a_c: Option<f64>) -> f64 {
    let change = (fine - coarse).abs();
    match dx_over_a_c {
        Some(r) if r.is_finite() && r > 0.0 => {
            change.max(CRITERION_ERROR_COEFFICIENT * r * fine.abs())
        }
        _ => change,
    }
}

#[cfg(test)]
mod tests {
    use super::{observed_order, pull_off_error_estimate, richardson, richardson_first_order};

    #[test]
    fn richardson_cancels_an_error_of_its_order() {
        let (exact, c, h) = (-2.5, 0.4, 0.05);
        for p in [1.0, 2.0, 3.0] {
            let q = |h: f64| exact + c * h.powf(p);
            let x = richardson(q(h), q(2.0 * h), p);
            assert!((x - exact).abs() < 1e-14, "order {p}: {x}");
        }
        assert_eq!(
            richardson(-1.1, -1.3, 1.0).to_bits(),
            richardson_first_order(-1.1, -1.3).to_bits()
        );
        // A second-order error extrapolated at first order overshoots by twice the fine one.
        let q = |h: f64| exact + c * h * h;
        let first = richardson_first_order(q(h), q(2.0 * h));
        assert!(((first - exact) + 2.0 * (q(h) - exact)).abs() < 1e-14);
    }

    #[test]
    fn the_error_estimate_covers_the_first_order_error_and_the_criterion_floor() {
        // First-order error c·Δx: |fine − coarse| is exactly the error of the fine value.
        let (exact, c, h) = (-2.5, 0.4, 0.05);
        let q = |h: f64| exact + c * h;
        let estimate = pull_off_error_estimate(q(h), q(2.0 * h), None);
        assert!(
            (estimate - (q(h) - exact).abs()).abs() < 1e-14,
            "{estimate}"
        );
        assert_eq!(
            pull_off_error_estimate(-1.0, -1.2, None),
            pull_off_error_estimate(-1.2, -1.0, None)
        );
        // Two levels that agree by accident still get the criterion's floor: at a_c/Δx = 20,
        // 1.4/20 = 7% of |F|, the smooth sphere's measured +6.9%.
        let floor = pull_off_error_estimate(-1.0, -1.001, Some(1.0 / 20.0));
        assert!((floor - 0.07).abs() < 1e-12, "{floor}");
        // A larger change between the levels wins.
        assert!((pull_off_error_estimate(-1.0, -1.3, Some(0.05)) - 0.3).abs() < 1e-12);
        // No usable sphere scale: the change alone.
        assert_eq!(
            pull_off_error_estimate(-1.0, -1.001, Some(f64::NAN)),
            (-1.0f64 + 1.001).abs()
        );
    }

    #[test]
    fn cancels_a_first_order_error_exactly() {
        // q(h) = q* + c·h: exact for any c.
        let (exact, c, h) = (3.25, -0.7, 0.1);
        let q = |h: f64| exact + c * h;
        assert!((richardson_first_order(q(h), q(2.0 * h)) - exact).abs() < 1e-14);
        // A second-order term survives, scaled by −2: q = q* + c·h + e·h².
        let e = 5.0;
        let q2 = |h: f64| exact + c * h + e * h * h;
        let r = richardson_first_order(q2(h), q2(2.0 * h));
        assert!((r - (exact - 2.0 * e * h * h)).abs() < 1e-12, "{r}");
    }
    /// q(Δx) = q* + c·Δx^p at Δx = 4h, 2h, h gives p back, for either sign of c, for an error
    /// that alternates in sign, and (reversed) −p for a sequence that diverges at that rate.
    #[test]
    fn observed_order_recovers_a_known_order() {
        let (exact, h) = (-1.75, 0.01);
        for p in [0.5, 1.0, 2.0, 3.7] {
            for c in [0.3, -2.0] {
                let q = |dx: f64| exact + c * dx.powf(p);
                let got = observed_order(q(4.0 * h), q(2.0 * h), q(h));
                assert!((got - p).abs() < 1e-9, "p = {p}, c = {c}: {got}");
                let back = observed_order(q(h), q(2.0 * h), q(4.0 * h));
                assert!((back + p).abs() < 1e-9, "reversed, p = {p}: {back}");
            }
            // Alternating error c·(−1)^k·Δx^p over the levels k = 0, 1, 2: |differences| are
            // (2^p + 1)(2h)^p·|c| and (2^p + 1)h^p·|c|, so the ratio is again 2^p.
            let (c, dx) = (0.8, |k: i32| h * 2f64.powi(2 - k));
            let q = |k: i32| exact + c * f64::from(1 - 2 * (k % 2)) * dx(k).powf(p);
            let got = observed_order(q(0), q(1), q(2));
            assert!((got - p).abs() < 1e-9, "alternating, p = {p}: {got}");
        }
        // A second-order term on top of a first-order one raises the observed order on coarse
        // levels; it tends to 1 as Δx shrinks.
        let q = |dx: f64| exact + dx + 50.0 * dx * dx;
        let (big, small) = (
            observed_order(q(0.04), q(0.02), q(0.01)),
            observed_order(q(0.004), q(0.002), q(0.001)),
        );
        assert!(
            big > small && small > 1.0 && (small - 1.0).abs() < 0.2,
            "{big} {small}"
        );
        assert_eq!(observed_order(1.0, 2.0, 2.0), f64::INFINITY);
        assert_eq!(observed_order(2.0, 2.0, 1.0), f64::NEG_INFINITY);
        assert!(observed_order(2.0, 2.0, 2.0).is_nan());
    }
}
