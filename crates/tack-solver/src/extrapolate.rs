//! Richardson extrapolation of mesh-dependent results: the Pohrt–Popov criterion converges at
//! first order in Δx, so two resolutions cancel the leading error term.

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

/// An estimate of how far the pull-off force `fine` (element size Δx) is from converged, from
/// the same run at 2Δx (`coarse`): `|fine − coarse|`, the first-order error of `fine`.
///
/// For a first-order error `c·Δx` this is exact, and it bounds the error of the Richardson value
/// `2·fine − coarse` by a wide margin (smooth sphere: 6.9% estimated where Richardson is off by
/// 0.3%). On rough fronts the error is not first order: the estimate is the honest scale of
/// the remaining error, not a bound (`cargo xtask convergence`, the README's table).
pub fn pull_off_error_estimate(fine: f64, coarse: f64) -> f64 {
    (fine - coarse).abs()
}

#[cfg(test)]
mod tests {
    use super::{pull_off_error_estimate, richardson_first_order};

    #[test]
    fn the_error_estimate_is_the_first_order_error_of_the_fine_value() {
        let (exact, c, h) = (-2.5, 0.4, 0.05);
        let q = |h: f64| exact + c * h;
        let estimate = pull_off_error_estimate(q(h), q(2.0 * h));
        assert!(
            (estimate - (q(h) - exact).abs()).abs() < 1e-14,
            "{estimate}"
        );
        assert_eq!(
            pull_off_error_estimate(-1.0, -1.2),
            pull_off_error_estimate(-1.2, -1.0)
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
}
