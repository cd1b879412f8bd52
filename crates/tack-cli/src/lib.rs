//! The `tack` command line as a library: scene files, validation, runs, result files and plots,
//! so other tools (xtask) can build and run scenes programmatically.
//!
//! - [`scene`]: the TOML schema (`version = 1`), loading, `--set` overrides;
//! - [`problem`]: validation and construction of grid, surface, path and references;
//! - [`run`]: solving, the result file (HDF5 via `tack-io`) and the one-screen report;
//! - [`plot`]: force–approach figures with contact snapshots;
//! - [`provenance`]: git revision, timestamps, command line;
//! - [`sweep`]: parameter sweeps (sweep files, sharded parallel runs that resume);
//! - [`merge`]: a sweep's points gathered into one table.

pub mod merge;
pub mod overrides;
pub mod plot;
pub mod problem;
pub mod provenance;
pub mod run;
pub mod scene;
pub mod sweep;

pub use problem::Problem;
pub use run::{RunOptions, RunOutcome, run_loaded, run_scene};
pub use scene::{Scene, SceneError, SceneFile};
