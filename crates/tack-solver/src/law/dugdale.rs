//! The Dugdale cohesive zone (Maugis 1992): a constant tension σ0 wherever `0 < gap < γ/σ0`.

use tack_fields as fields;
use tack_geometry::Surface;

use super::{Family, Law, MIN_COHESIVE_ZONE_ELEMENTS, RANGE_ROUND_OFF, StepColumn, ZONE_COLUMN};
use crate::SolverError;

/// The scene name.
pub(super) const NAME: &str = "dugdale";

/// A Dugdale cohesive zone: tension `σ0` wherever `0 < gap < h0 = γ/σ0` (the module docs of
/// `dugdale.rs` and docs/theory.md give the three-set algorithm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dugdale {
    /// The cohesive tension σ0 > 0.
    pub sigma0: f64,
}

impl Dugdale {
    /// The range `h0 = γ/σ0` for work of adhesion `gamma`: where the tension ends.
    pub(crate) fn h0(&self, gamma: f64) -> f64 {
        gamma / self.sigma0
    }
}

impl Law for Dugdale {
    fn name(&self) -> &'static str {
        NAME
    }

    fn parameter(&self) -> (&'static str, f64) {
        (fields::ADHESION_SIGMA0, self.sigma0)
    }

    fn meaning(&self) -> &'static str {
        "the cohesive tension σ0 > 0 (the range is γ/σ0)"
    }

    fn family(&self) -> Family<'_> {
        Family::Cohesive {
            sigma0: self.sigma0,
        }
    }

    /// The range `h0 = γ/σ0`.
    fn range(&self, gamma: f64) -> Option<f64> {
        Some(self.h0(gamma))
    }

    /// The range: the tension ends there.
    fn reach(&self, gamma: f64) -> Option<f64> {
        Some(self.h0(gamma))
    }

    fn peak_tension(&self, _gamma: f64, _e_star: f64, _dx: f64) -> f64 {
        self.sigma0
    }

    /// The law keeps its range `h0 = γ_ref/σ0` and scales σ0 by `γ/γ_ref`.
    fn element_tension(&self, gamma: f64, reference: f64, _e_star: f64, _dx: f64) -> f64 {
        self.sigma0 * (gamma / reference)
    }

    /// The cohesive zone `πE*γ/(4σ0²)` ahead of a straight crack (Griffith's `K² = 2E*γ` in
    /// `l = (π/8)(K/σ0)²`).
    fn zone_length(&self, e_star: f64, gamma: f64) -> Option<f64> {
        Some(std::f64::consts::PI * e_star * gamma / (4.0 * self.sigma0 * self.sigma0))
    }

    fn min_zone_elements(&self) -> f64 {
        MIN_COHESIVE_ZONE_ELEMENTS
    }

    /// First order: the zone's edge moves by whole elements (docs/theory.md §3.7).
    fn convergence_order(&self) -> f64 {
        1.0
    }

    fn mesh_warning(&self, e_star: f64, gamma: f64, dx: f64) -> Option<String> {
        let zone = self.zone_length(e_star, gamma)?;
        let shown = super::under_resolved(zone / dx, self.min_zone_elements())?;
        let strength = format!("σ0 = {}", fields::num(self.sigma0));
        Some(format!(
            "under-resolved cohesive zone: its length πE*γ/(4σ0²) = {} spans {shown} elements \
             (at least {} needed); the Dugdale law then acts element by element and the forces \
             depend on the mesh (refine {} or lower {}){}",
            fields::rounded(zone),
            self.min_zone_elements(),
            fields::GRID_DX,
            fields::ADHESION_SIGMA0,
            super::glued(zone / dx, &strength),
        ))
    }

    /// `sigma0`, `range` and `cohesive_zone_elements`.
    fn summary_entries(&self, gamma: f64, e_star: f64, dx: f64) -> Vec<(&'static str, f64)> {
        vec![
            ("sigma0", self.sigma0),
            ("range", self.h0(gamma)),
            (
                "cohesive_zone_elements",
                self.zone_length(e_star, gamma).unwrap_or(0.0) / dx,
            ),
        ]
    }

    /// The cohesive zone's elements: out of contact, carrying σ0.
    fn step_column(&self) -> Option<StepColumn> {
        Some(StepColumn {
            name: ZONE_COLUMN,
            meaning: "elements of the cohesive zone: out of contact, carrying the tension sigma0"
                .to_owned(),
        })
    }

    fn describe(&self, gamma: f64, _e_star: f64, _dx: f64) -> String {
        let r = fields::rounded;
        format!(
            "Dugdale, sigma0 = {}, range = {}",
            r(self.sigma0),
            r(self.h0(gamma))
        )
    }

    /// σ0 > 0, γ > 0 and a range γ/σ0 above the round-off of the heights
    /// ([`RANGE_ROUND_OFF`]).
    fn check(&self, gamma: f64, surface: &Surface) -> Result<(), SolverError> {
        let sigma0 = self.sigma0;
        crate::validate::positive(fields::ADHESION_SIGMA0, sigma0)?;
        if gamma <= 0.0 {
            return Err(SolverError::OutOfRange {
                field: fields::MATERIAL_GAMMA,
                value: gamma,
                allowed: "a finite number > 0 under the Dugdale law (the range is γ/σ0)",
            });
        }
        let range = self.h0(gamma);
        if range.is_nan() || range <= RANGE_ROUND_OFF * super::largest_height(surface) {
            return Err(SolverError::OutOfRange {
                field: fields::ADHESION_SIGMA0,
                value: sigma0,
                allowed: "small enough that the range γ/σ0 exceeds 1e-12 of the largest height \
                          (below it the gap test is round-off)",
            });
        }
        Ok(())
    }
}
