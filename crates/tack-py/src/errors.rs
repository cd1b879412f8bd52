//! The exceptions of the Python package and the mapping of `tack`'s errors onto them.
//!
//! Every input error is a `ValueError` (`TackError` and its subclasses), with tack's own
//! message: it names the field, the value and the allowed range. Functions whose inputs are
//! Python arguments rather than a scene ([`crate::run::pull_off`], [`crate::contact`],
//! [`crate::surface`]) rename the scene's field names in those messages to their arguments
//! ([`rename`]; `material.gamma` → `gamma`, `grid.nx` → `heights.shape[0]`). A Rust panic
//! never reaches Python as such: [`crate::guard`] turns it into `InternalError` (a
//! `RuntimeError`).

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

/// `(field, argument)` pairs of one Python function: the field as tack's messages name it (the
/// scene, solver and geometry layers name fields as a scene writes them: `material.gamma`,
/// `grid.nx`) and the Python argument it stands for (`gamma`, `heights.shape[0]`).
pub type Names = &'static [(&'static str, &'static str)];

/// `message` with each field of `names` replaced by its Python argument. A field is replaced
/// where it stands as a whole name: not inside a longer dotted name or word
/// (`roughness.h` is not the start of `roughness.hurst`). Earlier entries win, so list a
/// name before its prefixes.
pub fn rename(message: &str, names: Names) -> String {
    let part_of_name = |c: char| c.is_alphanumeric() || c == '_';
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    let mut previous: Option<char> = None;
    'scan: while let Some(c) = rest.chars().next() {
        let starts_name = previous.is_none_or(|p| !(part_of_name(p) || p == '.' || p == ':'));
        if starts_name {
            for (field, argument) in names {
                let Some(after) = rest.strip_prefix(field) else {
                    continue;
                };
                let mut next = after.chars();
                let ends_name = match next.next() {
                    None => true,
                    Some('.' | ':') => !next.next().is_some_and(part_of_name),
                    Some(n) => !part_of_name(n),
                };
                if ends_name {
                    out.push_str(argument);
                    previous = field.chars().last();
                    rest = after;
                    continue 'scan;
                }
            }
        }
        out.push(c);
        previous = Some(c);
        rest = &rest[c.len_utf8()..];
    }
    out
}

/// The Python exception for a `tack` error (cancellation is handled by [`crate::guard`]).
pub fn to_py(err: &tack::Error) -> PyErr {
    to_py_named(err, &[])
}

/// [`to_py`] with the fields of `names` renamed to Python arguments ([`rename`]).
pub fn to_py_named(err: &tack::Error, names: Names) -> PyErr {
    let message = rename(&err.to_string(), names);
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

/// [`value_error`] with the fields of `names` renamed to Python arguments ([`rename`]).
pub fn value_error_named(message: impl std::fmt::Display, names: Names) -> PyErr {
    TackError::new_err(rename(&message.to_string(), names))
}
