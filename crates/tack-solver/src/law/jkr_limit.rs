//! The zero-range (JKR) limit: the Pohrt–Popov detachment criterion, the paper's model.

use tack_fields as fields;
use tack_geometry::Surface;

use super::{Family, Law, StepColumn};
use crate::SolverError;

/// The scene name.
pub(super) const NAME: &str = "jkr_limit";

/// The zero-range (JKR) limit: an element bonds when it penetrates and detaches when its
/// tension exceeds the Pohrt–Popov criterion `σ_c = sqrt(E*γ/(κΔx))` (see [`crate::KAPPA`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JkrLimit {
    /// The Pohrt–Popov constant κ.
    pub kappa: f64,
}

impl Law for JkrLimit {
    fn name(&self) -> &'static str {
        NAME
    }

    fn parameter(&self) -> (&'static str, f64) {
        (fields::SOLVER_KAPPA, self.kappa)
    }

    fn meaning(&self) -> &'static str {
        "the Pohrt–Popov constant κ > 0"
    }

    fn family(&self) -> Family<'_> {
        Family::Criterion { kappa: self.kappa }
    }

    fn range(&self, _gamma: f64) -> Option<f64> {
        None
    }

    fn reach(&self, _gamma: f64) -> Option<f64> {
        None
    }

    /// The criterion's `σ_c = sqrt(E*γ/(κΔx))`.
    fn peak_tension(&self, gamma: f64, e_star: f64, dx: f64) -> f64 {
        (e_star * gamma / (self.kappa * dx)).sqrt()
    }

    /// The criterion's own `σ_c(γ)`.
    fn element_tension(&self, gamma: f64, _reference: f64, e_star: f64, dx: f64) -> f64 {
        (e_star / (self.kappa * dx) * gamma).sqrt()
    }

    /// `None`: the criterion's mesh rule is the contact's own size.
    fn zone_length(&self, _e_star: f64, _gamma: f64) -> Option<f64> {
        None
    }

    fn min_zone_elements(&self) -> f64 {
        0.0
    }

    /// First order: the Pohrt–Popov criterion's error is 1.4·Δx/a_c on the smooth sphere.
    fn convergence_order(&self) -> f64 {
        1.0
    }

    /// `None`: the criterion's mesh rules are the contact's, checked with the body.
    fn mesh_warning(&self, _e_star: f64, _gamma: f64, _dx: f64) -> Option<String> {
        None
    }

    /// `sigma_c` and `kappa`.
    fn summary_entries(&self, gamma: f64, e_star: f64, dx: f64) -> Vec<(&'static str, f64)> {
        vec![
            ("sigma_c", self.peak_tension(gamma, e_star, dx)),
            ("kappa", self.kappa),
        ]
    }

    /// The criterion has bonded elements only: no zone ahead of the contact.
    fn step_column(&self) -> Option<StepColumn> {
        None
    }

    fn describe(&self, _gamma: f64, _e_star: f64, _dx: f64) -> String {
        format!("zero-range limit, kappa = {}", fields::rounded(self.kappa))
    }

    /// κ > 0.
    fn check(&self, _gamma: f64, _surface: &Surface) -> Result<(), SolverError> {
        crate::validate::positive(fields::SOLVER_KAPPA, self.kappa).map(|_| ())
    }
}
