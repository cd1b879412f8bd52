//! Errors raised when a grid, surface or shape is given values outside their allowed range.

use thiserror::Error;

/// Invalid geometry input; every message names the field, the value and the allowed range.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum GeometryError {
    /// A real-valued parameter is not finite or outside its range.
    #[error("{field} = {value} is invalid: must be {allowed}")]
    OutOfRange {
        /// Name of the offending field, e.g. `grid.dx`.
        field: &'static str,
        /// The value that was given.
        value: f64,
        /// Human-readable description of the allowed range.
        allowed: &'static str,
    },
    /// An element count is outside its range.
    #[error("{field} = {value} is invalid: must be {allowed}")]
    BadCount {
        /// Name of the offending field, e.g. `grid.nx`.
        field: &'static str,
        /// The value that was given.
        value: usize,
        /// Human-readable description of the allowed range.
        allowed: &'static str,
    },
    /// Two arrays or grids that must agree do not.
    #[error("shape mismatch: {0}")]
    Mismatch(String),
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn positive(field: &'static str, value: f64) -> Result<f64, GeometryError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(GeometryError::OutOfRange {
            field,
            value,
            allowed: "a finite number > 0",
        })
    }
}

/// Checks that `value` is finite.
pub(crate) fn finite(field: &'static str, value: f64) -> Result<f64, GeometryError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(GeometryError::OutOfRange {
            field,
            value,
            allowed: "a finite number",
        })
    }
}
