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
//! - [`problem`]: validation into grid, surface, crop window, path and closed-form references;
//! - [`run()`](run::run): the solve in memory, with progress and cancellation through a
//!   [`solver::Observer`], the summary and the Richardson coarse run;
//! - [`heights`]: runs on a body given as a height array in memory, with a default pull-off
//!   path (what the Python package's `tack.pull_off` calls);
//! - [`provenance`]: git revision, timestamps, command line.
//!
//! Parameter sweeps (sharded, parallel, resumable) and their merge into one table are the
//! `tack-sweep` crate's, built on this one.
//!
//! The numerical crates are re-exported ([`geometry`], [`kernels`], [`solver`], [`analytics`],
//! [`io`]) with [`ndarray`], so a program depending on `tack` alone reaches every type its API
//! uses.

pub mod error;
pub mod heights;
pub mod memory;
pub mod overrides;
pub mod problem;
pub mod provenance;
pub mod run;
pub mod scene;

pub use error::Error;
pub use overrides::set_value;
pub use problem::Problem;
pub use provenance::{GIT_REVISION, VERSION, command_line, now_rfc3339};
pub use run::{
    MAX_THREADS, RunOptions, RunOutcome, SUMMARY_QUANTITIES, run, run_file, run_to_file,
    summary_quantity,
};
pub use scene::{SCENE_VERSION, Scene, SceneError, SceneFile};

pub use ndarray;
pub use tack_analytics as analytics;
pub use tack_geometry as geometry;
pub use tack_io as io;
pub use tack_kernels as kernels;
pub use tack_solver as solver;
