//! tack: the adhesive strength of rough elastic contacts (Li, Pohrt & Popov 2019) as a library.
//!
//! A *scene* (TOML, `docs/scenes.md`) describes the material, the rigid body (sphere, flat
//! punch, waviness, random roughness, a measured height map), the grid and the approach path;
//! [`run()`] validates it into a [`Problem`], solves the path in memory with the FFT-accelerated
//! boundary-element solvers of [`solver`] and returns the force–approach curve, the snapshots,
//! the summary (pull-off force against the closed forms of [`analytics`]) and provenance.
//! Writing the HDF5 result file is an explicit step ([`RunOutcome::write`]).
//!
//! ```
//! use tack::{RunOptions, Scene};
//!
//! let scene = Scene::parse(
//!     r#"
//!     version = 1
//!     [material]
//!     e_star = 1.0
//!     gamma = 0.125
//!     [geometry]
//!     shape = "sphere"
//!     radius = 8.0
//!     [grid]
//!     n = 32
//!     dx = 0.45
//!     [protocol]
//!     max_approach = 3.0
//!     load_step = 0.5
//!     unload_step = 0.02
//!     "#,
//!     ".",
//!     &[],
//! )?;
//! let outcome = tack::run(&scene, &RunOptions::default(), &mut ())?;
//! let ratio = outcome.pull_off_ratio(); // F / F_JKR, F_JKR = -(3/2)·π·γ·R
//! assert!((1.0..1.4).contains(&ratio), "{ratio}"); // a_c/Δx ≈ 7: the criterion's +20%
//! # Ok::<(), tack::Error>(())
//! ```
//!
//! - [`scene`]: the TOML schema (`version = 1`), loading, [`overrides`] (`--set key=value`);
//! - [`problem`]: the one builder that validates a scene into grid, surface, crop window, path
//!   and closed-form references ([`pull_off_path`]: the default pull-off path);
//! - [`engine`]: the run engine ([`engine::execute`]: thread pool, timing, the solve with
//!   progress and cancellation through a [`solver::Observer`], Richardson, provenance, result);
//!   [`run()`] runs a scene through it;
//! - [`summary`]: the result's summary, warnings and curve; [`coarse`]: the Richardson grid;
//! - [`heights`]: runs on a body given as a height array in memory, with a default pull-off
//!   path (what the Python package's `tack.pull_off` calls); [`heights_richardson`]: their
//!   Richardson extrapolation (the array sampled at the coarse centres);
//! - [`provenance`]: git revision, timestamps, command line; [`memory`]: the memory bound.
//!
//! Parameter sweeps (sharded, parallel, resumable) and their merge into one table are the
//! `tack-sweep` crate's, built on this one.
//!
//! The numerical crates are re-exported ([`geometry`], [`kernels`], [`solver`], [`analytics`],
//! [`io`]) with [`ndarray`], so a program depending on `tack` alone reaches every type its API
//! uses; so is [`fields`], the names of the scene fields (`tack::fields::GRID_DX`) and the table
//! of what each holds.

pub mod coarse;
pub mod engine;
pub mod error;
pub mod gamma_map;
pub mod heights;
pub mod heights_richardson;
pub mod layer;
mod map_file;
pub mod memory;
pub mod overrides;
pub mod problem;
pub mod provenance;
pub mod pull_off_path;
pub mod references;
pub mod scene;
pub mod shape;
pub mod summary;

pub use engine::{
    MAX_THREADS, RunOptions, RunOutcome, check_threads, execute, run, run_file, run_to_file,
};
pub use error::{Error, SceneError};
pub use overrides::set_value;
pub use problem::Problem;
pub use provenance::{GIT_REVISION, VERSION, command_line, now_rfc3339};
pub use scene::{
    AdhesionModel, AdhesionSpec, BodyKind, BodySpec, InterfaceKind, PatternKind, SCENE_VERSION,
    Scene, SceneSchema,
};
pub use summary::{SUMMARY_QUANTITIES, summary_quantity};

pub use ndarray;
pub use tack_analytics as analytics;
pub use tack_fields as fields;
pub use tack_geometry as geometry;
pub use tack_io as io;
pub use tack_kernels as kernels;
pub use tack_solver as solver;
