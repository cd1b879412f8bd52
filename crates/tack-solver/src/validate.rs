//! Input checks of the solvers, each written once: ranges of numbers and counts, the approach,
//! the adhesion inputs (γ, κ) and the agreement of surface and operator grids. Errors name the
//! field, the value and the allowed range ([`SolverError::OutOfRange`]).
//!
//! `E*` is checked where the operator is built (`tack_kernels::operator_for`): a solver only
//! ever sees a valid one.

use tack_fields as fields;
use tack_geometry::Surface;
use tack_kernels::ElasticOperator;

use crate::{AdhesiveOptions, SolverError};

fn out_of_range<T>(
    field: &'static str,
    value: f64,
    allowed: &'static str,
) -> Result<T, SolverError> {
    Err(SolverError::OutOfRange {
        field,
        value,
        allowed,
    })
}

/// `v` is finite.
pub(crate) fn finite(field: &'static str, v: f64) -> Result<f64, SolverError> {
    if v.is_finite() {
        Ok(v)
    } else {
        out_of_range(field, v, "a finite number")
    }
}

/// `v` is finite and `> 0`.
pub(crate) fn positive(field: &'static str, v: f64) -> Result<f64, SolverError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        out_of_range(field, v, "a finite number > 0")
    }
}

/// `v` is finite and `≥ 0`.
pub(crate) fn non_negative(field: &'static str, v: f64) -> Result<f64, SolverError> {
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        out_of_range(field, v, "a finite number ≥ 0")
    }
}

/// `0 < v < 1`.
pub(crate) fn fraction(field: &'static str, v: f64) -> Result<f64, SolverError> {
    if v > 0.0 && v < 1.0 {
        Ok(v)
    } else {
        out_of_range(field, v, "a number in (0, 1)")
    }
}

/// A count (iterations, rounds, steps) of at least one.
pub(crate) fn at_least_one(field: &'static str, n: usize) -> Result<usize, SolverError> {
    if n >= 1 {
        Ok(n)
    } else {
        out_of_range(field, n as f64, "an integer ≥ 1")
    }
}

/// A bound `v` at most `limit` (`v ≤ limit`, finite), e.g. `protocol.retract_to`.
pub(crate) fn at_most(
    field: &'static str,
    v: f64,
    limit: f64,
    allowed: &'static str,
) -> Result<f64, SolverError> {
    if v.is_finite() && v <= limit {
        Ok(v)
    } else {
        out_of_range(field, v, allowed)
    }
}

/// The prescribed approach of one solve (field `approach`).
pub(crate) fn approach(d: f64) -> Result<f64, SolverError> {
    finite("approach", d)
}

/// The surface lives on the operator's grid; returns the common shape.
pub(crate) fn same_grid(
    op: &dyn ElasticOperator,
    surface: &Surface,
) -> Result<(usize, usize), SolverError> {
    let shape = op.grid().shape();
    if surface.grid().shape() != shape {
        return Err(SolverError::GridMismatch {
            surface: surface.grid().shape(),
            operator: shape,
        });
    }
    Ok(shape)
}

/// The inputs of the adhesive law besides the grids, in this order: the CG options, the work of
/// adhesion `γ ≥ 0` (`material.gamma`), the Pohrt–Popov constant `κ > 0` (`solver.kappa`) and
/// the cap on detach/attach rounds (`solver.max_active_set_iterations`).
pub(crate) fn adhesion(
    gamma: f64,
    kappa: f64,
    options: &AdhesiveOptions,
) -> Result<(), SolverError> {
    options.cg.validate()?;
    non_negative(fields::MATERIAL_GAMMA, gamma)?;
    positive(fields::SOLVER_KAPPA, kappa)?;
    at_least_one(
        fields::SOLVER_MAX_ACTIVE_SET_ITERATIONS,
        options.max_active_set_iterations,
    )?;
    if let Some(t) = options.round_tolerance {
        fraction(fields::SOLVER_ROUND_TOLERANCE, t)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::SolverOptions;

    fn message<T: std::fmt::Debug>(r: Result<T, SolverError>) -> String {
        r.unwrap_err().to_string()
    }

    #[test]
    fn messages_name_field_value_and_range() {
        assert_eq!(
            message(approach(f64::NAN)),
            "approach = NaN is invalid: must be a finite number"
        );
        assert_eq!(
            message(positive("solver.kappa", -1.0)),
            "solver.kappa = -1 is invalid: must be a finite number > 0"
        );
        assert_eq!(
            message(non_negative("material.gamma", -0.5)),
            "material.gamma = -0.5 is invalid: must be a finite number ≥ 0"
        );
        assert_eq!(
            message(fraction("solver.tolerance", 1.0)),
            "solver.tolerance = 1 is invalid: must be a number in (0, 1)"
        );
        assert_eq!(
            message(at_least_one("solver.max_iterations", 0)),
            "solver.max_iterations = 0 is invalid: must be an integer ≥ 1"
        );
        assert_eq!(positive("x", 2.0), Ok(2.0));
        assert_eq!(non_negative("x", 0.0), Ok(0.0));
        assert!(positive("x", f64::INFINITY).is_err() && positive("x", 0.0).is_err());
    }

    #[test]
    fn adhesion_inputs_are_checked_in_order() {
        let ok = AdhesiveOptions::default();
        assert!(adhesion(0.0, 0.5, &ok).is_ok());
        let bad_cg = AdhesiveOptions {
            cg: SolverOptions {
                tolerance: 0.0,
                ..ok.cg
            },
            max_active_set_iterations: 0,
            ..ok
        };
        // Everything wrong: the CG options are reported first.
        assert!(message(adhesion(-1.0, 0.0, &bad_cg)).starts_with("solver.tolerance = 0 "));
        assert!(message(adhesion(-1.0, 0.0, &ok)).starts_with("material.gamma = -1 "));
        assert!(message(adhesion(1.0, f64::NAN, &ok)).starts_with("solver.kappa = NaN "));
        let no_rounds = AdhesiveOptions {
            max_active_set_iterations: 0,
            ..ok
        };
        assert!(
            message(adhesion(1.0, 1.0, &no_rounds))
                .starts_with("solver.max_active_set_iterations = 0 ")
        );
    }
}
