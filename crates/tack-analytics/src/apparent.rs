//! The apparent work of adhesion of a measured force–approach branch: the γ whose JKR curve
//! fits the branch best in least squares (a rough or finite-range sphere's effective γ, per
//! branch, so that approach and retraction can be compared).
//!
//! The model is the JKR sphere under approach control (Johnson, Kendall & Roberts 1971):
//! loading, no force before the first touch (d < 0) and the stable branch after it;
//! retraction, the stable branch down to the jump-off approach and no force below it.

use crate::jkr::jkr_force_from_approach;
use crate::minimize::golden_min;

/// Which branch of an approach-controlled cycle the points come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CycleBranch {
    /// Loading: the JKR sphere snaps in at d = 0.
    Approach,
    /// Retraction: the JKR sphere lets go at the jump-off approach.
    Retraction,
}

/// Force of the JKR sphere of work of adhesion `gamma` at approach `d` on `branch` under
/// approach control (module docs).
pub fn jkr_branch_force(e_star: f64, gamma: f64, radius: f64, d: f64, branch: CycleBranch) -> f64 {
    if branch == CycleBranch::Approach && d < 0.0 {
        return 0.0;
    }
    jkr_force_from_approach(e_star, gamma, radius, d).unwrap_or(0.0)
}

/// Candidate values of the scan in [`apparent_work_of_adhesion`], per decade.
const SCAN_PER_DECADE: usize = 40;

/// The work of adhesion γ ≥ 0 of the JKR sphere (E* `e_star`, radius `radius`) whose force on
/// `branch` fits `points` (approach, force; force positive when compressive) best in least
/// squares, searched over `[gamma_lo, gamma_hi]` (0 < lo < hi): a scan of
/// 40 values per decade in ln γ, then golden-section refinement around the best one to a
/// relative 1e-10. The residual is not smooth in γ (points cross the jump-off), hence the scan.
/// `None` without points, or with a bad interval.
///
/// ```
/// use tack_analytics::{CycleBranch, apparent_work_of_adhesion, jkr_branch_force};
/// let (e, r, gamma) = (1.0, 1.0, 0.3);
/// let points: Vec<(f64, f64)> = (0..40)
///     .map(|k| -0.5 + 0.05 * k as f64)
///     .map(|d| (d, jkr_branch_force(e, gamma, r, d, CycleBranch::Retraction)))
///     .collect();
/// let fit = apparent_work_of_adhesion(e, r, &points, CycleBranch::Retraction, 1e-3, 10.0);
/// assert!((fit.unwrap() / gamma - 1.0).abs() < 1e-8);
/// ```
pub fn apparent_work_of_adhesion(
    e_star: f64,
    radius: f64,
    points: &[(f64, f64)],
    branch: CycleBranch,
    gamma_lo: f64,
    gamma_hi: f64,
) -> Option<f64> {
    if points.is_empty() || !(gamma_lo > 0.0 && gamma_hi > gamma_lo && gamma_hi.is_finite()) {
        return None;
    }
    let cost = |ln_g: f64| -> f64 {
        let g = ln_g.exp();
        points
            .iter()
            .map(|&(d, f)| (f - jkr_branch_force(e_star, g, radius, d, branch)).powi(2))
            .sum()
    };
    let (lo, hi) = (gamma_lo.ln(), gamma_hi.ln());
    let n = ((hi - lo) / std::f64::consts::LN_10 * SCAN_PER_DECADE as f64).ceil() as usize + 1;
    let h = (hi - lo) / (n - 1) as f64;
    let best = (0..n)
        .map(|k| (k, cost(lo + h * k as f64)))
        .min_by(|a, b| a.1.total_cmp(&b.1))?
        .0;
    // Golden section on the bracket of the best scan point.
    let lo_k = lo + h * best.saturating_sub(1) as f64;
    let hi_k = lo + h * (best + 1).min(n - 1) as f64;
    let (x, _) = golden_min(cost, lo_k, hi_k, 1e-10);
    Some(x.exp())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::jkr::jkr_pull_off_approach;

    #[test]
    fn recovers_gamma_on_both_branches() {
        for gamma in [1e-4, 0.01, 2.0] {
            let (e, r) = (3.0, 0.5);
            let d_off = jkr_pull_off_approach(e, gamma, r);
            for branch in [CycleBranch::Approach, CycleBranch::Retraction] {
                let points: Vec<(f64, f64)> = (0..60)
                    .map(|k| 1.3 * d_off + 0.05 * k as f64 * d_off.abs())
                    .map(|d| (d, jkr_branch_force(e, gamma, r, d, branch)))
                    .collect();
                let fit =
                    apparent_work_of_adhesion(e, r, &points, branch, gamma / 50.0, gamma * 50.0)
                        .unwrap();
                // Exact data: only the golden section's 1e-10 in ln γ remains.
                assert!(
                    (fit / gamma - 1.0).abs() < 1e-8,
                    "{branch:?}: {fit} vs {gamma}"
                );
            }
        }
    }

    #[test]
    fn hertz_data_fit_a_vanishing_gamma_and_bad_input_none() {
        let (e, r) = (1.0, 1.0);
        // A Hertz loading (γ = 0) fits the smallest γ of the interval.
        let points: Vec<(f64, f64)> = (1..30)
            .map(|k| 0.1 * k as f64)
            .map(|d| (d, crate::hertz::hertz_force(e, r, d)))
            .collect();
        let fit =
            apparent_work_of_adhesion(e, r, &points, CycleBranch::Approach, 1e-6, 1.0).unwrap();
        assert!(fit < 1e-5, "{fit}");
        assert_eq!(
            apparent_work_of_adhesion(e, r, &[], CycleBranch::Approach, 1e-6, 1.0),
            None
        );
        assert_eq!(
            apparent_work_of_adhesion(e, r, &points, CycleBranch::Approach, 1.0, 1.0),
            None
        );
    }
}
