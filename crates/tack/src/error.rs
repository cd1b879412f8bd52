//! The facade's error: one enum over what a scene, a run or a result file can raise.

use std::fmt;
use std::path::PathBuf;

pub use tack_fields::num;
use thiserror::Error;

/// Everything [`crate::run()`] and its neighbours can fail with. Every message names the field,
/// the value and the allowed range, or the file.
#[derive(Debug, Error)]
pub enum Error {
    /// The scene is unreadable or invalid (the message names the field).
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The solver refused its input or was cancelled.
    #[error(transparent)]
    Solver(#[from] tack_solver::SolverError),
    /// A result file could not be written or read.
    #[error(transparent)]
    Io(#[from] tack_io::IoError),
    /// A thread count is out of range or its pool could not be built.
    #[error("{0}")]
    Threads(String),
    /// The output path cannot be written.
    #[error("{}: {reason}", path.display())]
    Output {
        /// The output path as given.
        path: PathBuf,
        /// Why it cannot be used.
        reason: String,
    },
}

impl From<tack_geometry::GeometryError> for Error {
    fn from(e: tack_geometry::GeometryError) -> Self {
        Error::Scene(e.into())
    }
}

impl From<tack_kernels::KernelError> for Error {
    fn from(e: tack_kernels::KernelError) -> Self {
        Error::Scene(e.into())
    }
}

impl Error {
    /// Whether the run was stopped by its observer ([`tack_solver::Observer::cancelled`]).
    pub fn is_cancelled(&self) -> bool {
        matches!(
            self,
            Error::Solver(tack_solver::SolverError::Cancelled { .. })
                | Error::Scene(SceneError::Solver(
                    tack_solver::SolverError::Cancelled { .. }
                ))
        )
    }
}

/// Everything that can be wrong with a scene; messages name the field, the value and the
/// allowed range, or the file.
#[derive(Debug, Error)]
pub enum SceneError {
    /// The scene file could not be read.
    #[error("cannot read scene `{}`: {cause}", path.display())]
    Read {
        /// The scene file.
        path: PathBuf,
        /// The operating system's error.
        cause: std::io::Error,
    },
    /// The TOML is malformed or does not fit the schema (unknown field, wrong type, missing field).
    #[error("scene{}: {message}", origin.as_ref().map(|p| format!(" `{}`", p.display())).unwrap_or_default())]
    Syntax {
        /// The scene file, when the scene came from one.
        origin: Option<PathBuf>,
        /// The parser's message (it names the line and the field).
        message: String,
    },
    /// The `version` key is missing or not supported.
    #[error("version = {0} is not supported: this tack reads scene files with version = {1}")]
    Version(String, i64),
    /// A `--set key=value` override cannot be applied.
    #[error("--set {assignment}: {reason}")]
    Override {
        /// The override as given.
        assignment: String,
        /// Why it cannot be applied.
        reason: String,
    },
    /// A value outside its allowed range.
    #[error("{field} = {value} is invalid: must be {allowed}")]
    OutOfRange {
        /// The offending field, e.g. `material.e_star`.
        field: String,
        /// The value given, as written in the message.
        value: String,
        /// The allowed range.
        allowed: String,
    },
    /// A combination of fields that cannot work (the message names the fields).
    #[error("{0}")]
    Inconsistent(String),
    /// A geometry error (grid, shape, roughness, height map); names the field.
    #[error(transparent)]
    Geometry(#[from] tack_geometry::GeometryError),
    /// An elastic-operator error; names the field.
    #[error(transparent)]
    Kernel(#[from] tack_kernels::KernelError),
    /// A solver or approach-path error; names the field.
    #[error(transparent)]
    Solver(#[from] tack_solver::SolverError),
}

impl SceneError {
    /// An [`SceneError::OutOfRange`] from anything printable.
    pub fn out_of_range(
        field: impl Into<String>,
        value: impl fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        let value = value.to_string();
        // A huge or tiny f64 displays as hundreds of digits: show it as 1.797e308 instead.
        let value = match value.parse::<f64>() {
            Ok(x) if value.len() > 17 => num(x),
            _ => value,
        };
        Self::OutOfRange {
            field: field.into(),
            value,
            allowed: allowed.into(),
        }
    }
}
