//! Contact solvers for an elastic half-space under approach (displacement) control.
//!
//! [`ContactSolver`] solves frictionless non-adhesive contact with a constrained conjugate
//! gradient (Polonsky & Keer 1999, gap-controlled form). [`AdhesiveSolver`] adds JKR-limit
//! adhesion through the Pohrt–Popov detachment criterion and walks load–unload
//! [`ApproachPath`]s. Solvers own their operator and scratch and warm-start from the previous
//! solve. They always terminate (iteration caps) and report whether they converged. Nothing in
//! this crate does IO or prints.

mod adhesive;
mod cg;
mod clusters;
mod contact;
mod crop;
mod extrapolate;
mod options;
mod path;
mod state;

pub use adhesive::{AdhesiveOptions, AdhesiveSolver, KAPPA, KAPPA_LINE, StepRecord};
pub use clusters::count_clusters;
pub use contact::ContactSolver;
pub use crop::{contact_window, touches_edge};
pub use extrapolate::richardson_first_order;
pub use options::{SolverError, SolverOptions};
pub use path::{ApproachPath, Observer, PathResult, Phase, Snapshot, SnapshotRequest};
pub use state::ContactState;
