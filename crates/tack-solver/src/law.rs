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

/// The Dugdale law's state on the solver's grid: σ0, the range, the cohesive zone and scratch.
pub(crate) struct Cohesive {
    pub(crate) sigma0: f64,
    pub(crate) range: f64,
    pub(crate) zone: Array2<bool>,
    /// Contact or zone: the loaded elements that fix the sub-grid.
    pub(crate) loaded: Array2<bool>,
    pub(crate) scratch: ZoneScratch,
}

impl Cohesive {
    /// Checks `σ0 > 0`, `γ > 0` and a range above the round-off of the heights.
    pub(crate) fn new(
        gamma: f64,
        sigma0: f64,
        surface: &Surface,
        shape: (usize, usize),
    ) -> Result<Self, SolverError> {
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
                allowed: "small enough that the range γ/σ0 exceeds 1e-12 of the largest height",
            });
        }
        Ok(Self {
            sigma0,
            range,
            zone: Array2::from_elem(shape, false),
            loaded: Array2::from_elem(shape, false),
            scratch: ZoneScratch::new(shape),
        })
    }
}

/// The zone on one (sub-)grid.
pub(crate) struct ZoneScratch {
    pub(crate) zone: Array2<bool>,
}

impl ZoneScratch {
    pub(crate) fn new(shape: (usize, usize)) -> Self {
        Self {
            zone: Array2::from_elem(shape, false),
        }
    }
}
