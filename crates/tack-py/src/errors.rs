//! The exceptions of the Python package and the mapping of `tack`'s errors onto them.
//!
//! Every input error is a `ValueError` (`TackError` and its subclasses), with tack's own
//! message: it names the field, the value and the allowed range. A Rust panic never reaches
//! Python as such: [`crate::guard`] turns it into `InternalError` (a `RuntimeError`).

use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

create_exception!(
    tack,
    TackError,
    PyValueError,
    "Invalid input to tack: the message names the field, the value and the allowed range."
);
create_exception!(
    tack,
    SceneError,
    TackError,
    "A scene that cannot be read, parsed or validated (the message names the field)."
);
create_exception!(
    tack,
    SolverError,
    TackError,
    "The solver refused its input (the message names the field)."
);
create_exception!(
    tack,
    ResultFileError,
    TackError,
    "A result file that cannot be written or read (the message names the file)."
);
create_exception!(
    tack,
    InternalError,
    PyRuntimeError,
    "A bug in tack (a Rust panic, caught before it reached Python); please report it."
);

/// The Python exception for a `tack` error (cancellation is handled by [`crate::guard`]).
pub fn to_py(err: &tack::Error) -> PyErr {
    let message = err.to_string();
    match err {
        tack::Error::Scene(_) => SceneError::new_err(message),
        tack::Error::Solver(_) => SolverError::new_err(message),
        tack::Error::Io(_) | tack::Error::Output { .. } => ResultFileError::new_err(message),
        _ => TackError::new_err(message),
    }
}

/// A `TackError` with `message`, for errors of the numerical crates and of the bindings'
/// own argument checks.
pub fn value_error(message: impl std::fmt::Display) -> PyErr {
    TackError::new_err(message.to_string())
}
