//! Contact solvers for an elastic half-space under approach (displacement) control.
//!
//! [`ContactSolver`] solves frictionless non-adhesive contact, by default with the active-set
//! engine of the adhesive solver at σ_c = 0 ([`ContactMethod::ActiveSet`]), or with the
//! constrained conjugate gradient of Polonsky & Keer (1999, gap-controlled form;
//! [`ContactMethod::PolonskyKeer`]). [`AdhesiveSolver`] adds JKR-limit
//! adhesion through the Pohrt–Popov detachment criterion and walks load–unload
//! [`ApproachPath`]s. Solvers own their operator and scratch and warm-start from the previous
//! solve. They always terminate (iteration caps) and report whether they converged. Nothing in
//! this crate does IO or prints.
//!
//! Signs: the approach `d` is positive when pressing, pressure and force are positive when
//! compressive (an adhesive pull is negative), and the gap is `g = f − d + u ≥ 0`.
//!
//! # Non-adhesive contact: Hertz
//!
//! A sphere of radius `R` pressed by `d` carries `F = (4/3)E*√R·d^{3/2}` over a contact of
//! radius `a = √(Rd)`. Resolved by ten elements, the discrete contact edge lies within one
//! element of the true one; the force error is about 3·10⁻⁴ here and falls further with
//! refinement (`tests/nonadhesive.rs`). The check allows 1%, a margin that does not depend on
//! how the edge elements happen to fall.
//!
//! ```
//! use std::f64::consts::PI;
//! use tack_geometry::{Boundary, Grid, Sphere, Surface};
//! use tack_kernels::operator_for;
//! use tack_solver::{ContactSolver, SolverOptions};
//!
//! let (e_star, radius, d): (f64, f64, f64) = (1.0, 1.0, 0.01);
//! let a = (radius * d).sqrt(); // Hertz contact radius 0.1
//! let dx = a / 10.0;
//! let grid = Grid::square(27, dx, Boundary::Free)?; // 13 elements (1.3 a) each side
//! let surface = Surface::from_shape(grid, &Sphere::new(radius)?);
//! let op = operator_for(grid, e_star)?;
//! let mut solver = ContactSolver::new(op, &surface, SolverOptions::default())?;
//!
//! let state = solver.solve(d)?;
//! assert!(state.converged);
//! let hertz = 4.0 / 3.0 * e_star * radius.sqrt() * d.powf(1.5);
//! assert!((state.force / hertz - 1.0).abs() < 0.01, "{} vs {hertz}", state.force);
//! let a_num = (state.area / PI).sqrt();
//! assert!((a_num - a).abs() < dx, "contact radius {a_num} vs {a}");
//! assert!(state.pressure.iter().all(|&p| p >= 0.0)); // no tension without adhesion
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Adhesive contact: the JKR pull-off of a smooth sphere
//!
//! In units `R = E* = γ = 1` JKR predicts the pull-off force `F_JKR = −(3/2)π` at a contact
//! radius `a_c = (9π/8)^{1/3} ≈ 1.52`. The Pohrt–Popov criterion with [`KAPPA`] overshoots
//! `|F_JKR|` by a first-order discretisation error: +32.6% at `a_c/Δx = 5` (+3.5% at
//! `a_c/Δx = 40`). The coarse grid below keeps the example to a fraction of a second; it gives
//! +32%.
//!
//! ```
//! use std::f64::consts::PI;
//! use tack_geometry::{Boundary, Grid, Sphere, Surface};
//! use tack_kernels::operator_for;
//! use tack_solver::{AdhesiveOptions, AdhesiveSolver, ApproachPath, KAPPA, SnapshotRequest};
//!
//! let a_c = (9.0 * PI / 8.0_f64).powf(1.0 / 3.0);
//! let dx = a_c / 5.0;
//! let grid = Grid::square(23, dx, Boundary::Free)?; // half-width 11 Δx = 3.3 > 1.25 √6
//! let surface = Surface::from_shape(grid, &Sphere::new(1.0)?);
//! let op = operator_for(grid, 1.0)?;
//! let mut solver = AdhesiveSolver::new(op, &surface, 1.0, KAPPA, AdhesiveOptions::default())?;
//!
//! // Load to d = 6 (contact well beyond a_c), then retract until the contact lets go.
//! let path = ApproachPath {
//!     start: 0.3,
//!     max_approach: 6.0,
//!     load_step: 0.3,
//!     unload_step: 0.02,
//!     coarse_unload_step: Some(0.3),
//!     refine_pull_off: false,
//!     retract_to: None,
//!     max_steps: 10_000,
//! };
//! let result = solver.run_path(&path, &SnapshotRequest::None, &mut ())?;
//! assert!(result.completed && result.all_converged());
//! let f_jkr = -1.5 * PI;
//! let ratio = result.pull_off_force() / f_jkr;
//! assert!((1.2..1.45).contains(&ratio), "F/F_JKR = {ratio}");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod adhesive;
mod base;
mod cg;
mod checkpoint;
mod clusters;
mod contact;
mod criterion;
mod crop;
mod cycle;
mod dugdale;
mod extrapolate;
mod law;
mod options;
mod path;
mod relax;
mod rounds;
mod smooth;
mod state;
mod subgrid;
mod validate;
mod viscoelastic;

pub use adhesive::{AdhesiveOptions, AdhesiveSolver, KAPPA, KAPPA_LINE};
pub use checkpoint::SolverState;
pub use clusters::count_clusters;
pub use contact::{ContactMethod, ContactSolver};
pub use crop::{adhesive_reach, contact_window, touches_edge};
pub use cycle::{Cycle, CycleStep, cycle};
pub use extrapolate::{
    CRITERION_ERROR_COEFFICIENT, observed_order, pull_off_error_estimate, richardson,
    richardson_first_order,
};
pub use law::{
    APPROACH_FRACTION, AdhesionLaw, Curve, CustomCurve, Dugdale, Exponential, Family, JkrLimit,
    LEAST_SMOOTHING, Law, LennardJones, MIN_COHESIVE_ZONE_ELEMENTS, MIN_PROCESS_ZONE_ELEMENTS,
    RANGE_ROUND_OFF, REACH_FRACTION, SMOOTHING_OPENINGS, STEPS_PER_LENGTH, SmoothedDugdale,
    StepColumn, ZONE_COLUMN,
};
pub use options::{SolverError, SolverOptions};
pub use path::{
    ApproachPath, Observer, PathResult, Phase, RELEASE_MARGIN, SnapshotRequest, StepFields,
    pull_off_step,
};
pub use rounds::{CASCADE_GENERATIONS, CASCADE_MARGIN, LOOSE_ATTACH_MARGIN, LOOSE_DETACH_MARGIN};
pub use state::{ContactState, StepRecord};
pub use viscoelastic::{Prony, PronyArm, Rates};

/// The example of README.md, run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctest;
