//! Errors raised when a grid, surface or shape is given values outside their allowed range.

use tack_fields::num;
use thiserror::Error;

/// Invalid geometry input; every message names the field, the value and the allowed range.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum GeometryError {
    /// A real-valued parameter is not finite or outside its range.
    #[error("{field} = {} is invalid: must be {allowed}", num(*value))]
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
    /// A roughness band `[q0, q1]` the grid cannot represent.
    #[error(
        "{q0_field}/q1 = [{q0}, {q1}] is invalid: the band must contain at least one grid wave \
         vector; the grid holds wave vectors from 2π/L = {q_min} to π/Δx = {q_nyquist} \
         (diagonal up to √2·π/Δx)",
        q0_field = tack_fields::ROUGHNESS_Q0
    )]
    RoughnessBand {
        /// The lower cut-off that was given.
        q0: f64,
        /// The upper cut-off that was given.
        q1: f64,
        /// The smallest non-zero grid wave vector, `2π/max(Lx, Ly)`.
        q_min: f64,
        /// The Nyquist wave vector along an axis, `π/Δx`.
        q_nyquist: f64,
    },
    /// A height map has content above the Nyquist wave of the grid of twice its element size.
    #[error(
        "the height map is not band-limited to the grid of twice its element size: a share {} of \
         its rms lies above that grid's Nyquist wave π/(2Δx), where at most {} is allowed (filter \
         the map to wave vectors |q| ≤ π/(2Δx), or run without the coarse grid)",
        num(*share),
        num(*allowed)
    )]
    AboveNyquist {
        /// The measured share (rms of the content above over the rms of the map).
        share: f64,
        /// The largest share allowed.
        allowed: f64,
    },
    /// A height map could not be read; the message names the file, line and column.
    #[error("height map: {0}")]
    Parse(String),
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

/// Checks that `value` is finite and not negative.
pub(crate) fn non_negative(field: &'static str, value: f64) -> Result<f64, GeometryError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(GeometryError::OutOfRange {
            field,
            value,
            allowed: "a finite number ≥ 0",
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
