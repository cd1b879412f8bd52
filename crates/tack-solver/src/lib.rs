//! Contact solvers for an elastic half-space under approach (displacement) control.
//!
//! [`ContactSolver`] solves frictionless non-adhesive contact with a constrained conjugate
//! gradient (Polonsky & Keer 1999, gap-controlled form). Solvers own their operator and scratch
//! and warm-start from the previous solve. They always terminate (an iteration cap) and report
//! whether they converged. Nothing in this crate does IO or prints.

mod contact;
mod options;
mod state;

pub use contact::ContactSolver;
pub use options::{SolverError, SolverOptions};
pub use state::ContactState;
