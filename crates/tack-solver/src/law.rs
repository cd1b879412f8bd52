//! The adhesion laws an [`AdhesiveSolver`](crate::AdhesiveSolver) can run, and the state the
//! Dugdale law keeps on the solver's grid (its algorithm is in `dugdale.rs`).

use ndarray::Array2;
use tack_fields as fields;
use tack_geometry::Surface;

use crate::SolverError;

/// The adhesion law of an [`AdhesiveSolver`](crate::AdhesiveSolver).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AdhesionLaw {
    /// The zero-range (JKR) limit: the Pohrt–Popov detachment criterion
    /// `σ_c = sqrt(E*γ/(κΔx))`; an element bonds when it penetrates (see [`crate::KAPPA`]).
    JkrLimit {
        /// The Pohrt–Popov constant κ.
        kappa: f64,
    },
    /// A Dugdale cohesive zone: tension `σ0` wherever `0 < gap < h0 = γ/σ0` (the module docs of
    /// `dugdale.rs` and docs/theory.md give the three-set algorithm).
    Dugdale {
        /// The cohesive tension σ0 > 0.
        sigma0: f64,
    },
}

/// The smallest range allowed, relative to the largest height: below it the gap test
/// `g < h0` is decided by the round-off of `f − d + u`.
pub const RANGE_ROUND_OFF: f64 = 1e-12;

impl AdhesionLaw {
    /// Checks the law's own inputs for work of adhesion `gamma` on `surface`: κ > 0 for the
    /// criterion; for the Dugdale law σ0 > 0, γ > 0 and a range γ/σ0 above the round-off of
    /// the heights ([`RANGE_ROUND_OFF`]). Errors name the field.
    pub fn check(&self, gamma: f64, surface: &Surface) -> Result<(), SolverError> {
        let sigma0 = match *self {
            AdhesionLaw::JkrLimit { kappa } => {
                return crate::validate::positive(fields::SOLVER_KAPPA, kappa).map(|_| ());
            }
            AdhesionLaw::Dugdale { sigma0 } => sigma0,
        };
        crate::validate::positive(fields::ADHESION_SIGMA0, sigma0)?;
        if gamma <= 0.0 {
            return Err(SolverError::OutOfRange {
                field: fields::MATERIAL_GAMMA,
                value: gamma,
                allowed: "a finite number > 0 under the Dugdale law (the range is γ/σ0)",
            });
        }
        let range = gamma / sigma0;
        let top = surface
            .heights()
            .iter()
            .fold(0.0f64, |m, &f| m.max(f.abs()));
        if range.is_nan() || range <= RANGE_ROUND_OFF * top {
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

/// The Dugdale law's state on the solver's grid: σ0, the range and the cohesive zone.
pub(crate) struct Cohesive {
    pub(crate) sigma0: f64,
    pub(crate) range: f64,
    pub(crate) zone: Array2<bool>,
    /// Contact or zone: the loaded elements that fix the sub-grid.
    pub(crate) loaded: Array2<bool>,
}

impl Cohesive {
    /// Checks the law ([`AdhesionLaw::check`]) and makes the empty zone.
    pub(crate) fn new(
        gamma: f64,
        sigma0: f64,
        surface: &Surface,
        shape: (usize, usize),
    ) -> Result<Self, SolverError> {
        AdhesionLaw::Dugdale { sigma0 }.check(gamma, surface)?;
        Ok(Self {
            sigma0,
            range: gamma / sigma0,
            zone: Array2::from_elem(shape, false),
            loaded: Array2::from_elem(shape, false),
        })
    }
}
