//! The facade's error: one enum over what a scene, a run or a result file can raise.

use std::path::PathBuf;

use thiserror::Error;

/// Everything [`crate::run()`] and its neighbours can fail with. Every message names the field,
/// the value and the allowed range, or the file.
#[derive(Debug, Error)]
pub enum Error {
    /// The scene is unreadable or invalid (the message names the field).
    #[error(transparent)]
    Scene(#[from] crate::scene::SceneError),
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

impl Error {
    /// Whether the run was stopped by its observer ([`tack_solver::Observer::cancelled`]).
    pub fn is_cancelled(&self) -> bool {
        matches!(
            self,
            Error::Solver(tack_solver::SolverError::Cancelled { .. })
                | Error::Scene(crate::scene::SceneError::Solver(
                    tack_solver::SolverError::Cancelled { .. }
                ))
        )
    }
}
