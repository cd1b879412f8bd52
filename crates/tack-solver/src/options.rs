//! Solver settings (tolerance, iteration caps) and the errors raised for invalid ones.

use tack_fields::num;
use thiserror::Error;

/// Invalid solver input; messages name the field, the value and the allowed range.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SolverError {
    /// A parameter is outside its allowed range.
    #[error("{field} = {} is invalid: must be {allowed}", num(*value))]
    OutOfRange {
        /// The offending field.
        field: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range.
        allowed: &'static str,
    },
    /// A parameter below the least value this problem can honour (the least depends on the
    /// problem: its mesh, modulus and work of adhesion).
    #[error("{field} = {} is invalid: must be at least {} here: {why}", num(*value), rounded_up(*least))]
    BelowLeast {
        /// The offending field.
        field: &'static str,
        /// The value given.
        value: f64,
        /// The least value this problem accepts.
        least: f64,
        /// Why, and what to give instead.
        why: String,
    },
    /// An [`Observer`](crate::Observer) asked the path to stop.
    #[error("cancelled after {steps} steps")]
    Cancelled {
        /// Steps completed before the stop.
        steps: usize,
    },
    /// A per-element map does not have the grid's shape.
    #[error("{field}: the map is {} × {} but the grid is {} × {}; the map must have the grid's shape", map.0, map.1, grid.0, grid.1)]
    MapShape {
        /// The field of the map.
        field: &'static str,
        /// Shape of the map.
        map: (usize, usize),
        /// Shape of the grid.
        grid: (usize, usize),
    },
    /// A setting that only works together with another one.
    #[error("{field} = true needs {needs}")]
    Needs {
        /// The setting given.
        field: &'static str,
        /// What it needs.
        needs: &'static str,
    },
    /// A setting the solver cannot honour with the others given, and why.
    #[error("{field}: {reason}")]
    Refused {
        /// The setting refused.
        field: &'static str,
        /// Why, and what to give instead.
        reason: &'static str,
    },
    /// A [`SolverState`](crate::SolverState) restored into a solver it does not fit.
    #[error(
        "the saved solver state ({state}) does not fit this solver ({solver}): restore a state saved from the same grid and adhesion law"
    )]
    StateMismatch {
        /// The saved state's grid shape and law.
        state: String,
        /// The solver's grid shape and law.
        solver: String,
    },
    /// A custom adhesion law's curve ([`AdhesionLaw::custom`](crate::AdhesionLaw::custom))
    /// that fails a check.
    #[error("custom adhesion law \"{name}\": {method} {reason}")]
    Curve {
        /// The curve's name.
        name: &'static str,
        /// The method of [`Curve`](crate::Curve) at fault.
        method: &'static str,
        /// What it gives and what it must give.
        reason: String,
    },
    /// The surface and the operator live on different grids.
    #[error("the surface grid {surface:?} does not match the operator grid {operator:?}")]
    GridMismatch {
        /// Shape of the surface.
        surface: (usize, usize),
        /// Shape of the operator.
        operator: (usize, usize),
    },
}

/// Stopping rule and caps shared by the solvers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverOptions {
    /// Converged when the rms gap residual (gap on the contact set, penetration elsewhere)
    /// falls below `tolerance` times the displacement scale of the problem.
    pub tolerance: f64,
    /// Cap on conjugate-gradient iterations per solve.
    pub max_iterations: usize,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 5_000,
        }
    }
}

impl SolverOptions {
    /// Checks `0 < tolerance < 1` and `max_iterations ≥ 1`.
    pub fn validate(&self) -> Result<(), SolverError> {
        crate::validate::fraction(tack_fields::SOLVER_TOLERANCE, self.tolerance)?;
        crate::validate::at_least_one(tack_fields::SOLVER_MAX_ITERATIONS, self.max_iterations)?;
        Ok(())
    }
}

/// `x > 0` rounded up to four significant digits, for a least value a user may type back.
fn rounded_up(x: f64) -> String {
    let unit = 10f64.powf(x.log10().floor() - 3.0);
    tack_fields::rounded((x / unit).ceil() * unit)
}
