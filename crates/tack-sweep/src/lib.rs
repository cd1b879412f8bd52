//! tack-sweep: parameter sweeps over [`tack`] scenes and their merge into one table.
//!
//! A *sweep file* (TOML, `docs/sweeps.md`) names a base scene, the scene fields to vary (lists,
//! ranges, zipped entries that set several fields together; the points are the Cartesian
//! product of the entries in file order) and the summary quantities to collect. [`run_sweep`]
//! runs the points, or one [`Shard`] of them, in parallel into a directory of per-point HDF5
//! result files that a rerun resumes; [`merge()`] gathers the directory into one HDF5 sweep
//! table (`tack_io::SweepTable`), with the status of every point. The `tack sweep` and
//! `tack merge` commands are thin shells over these two functions.
//!
//! ```
//! use std::path::Path;
//! use tack_sweep::{MergeOptions, Sweep, SweepOptions};
//!
//! // Two points: a smooth sphere at two works of adhesion (the base scene inline).
//! let sweep = Sweep::parse_text(
//!     r#"
//!     version = 1
//!     collect = ["pull_off_ratio"]
//!     [vary]
//!     material.gamma = [0.1, 0.2]
//!     [scene]
//!     material = { e_star = 1.0 }
//!     geometry = { shape = "sphere", radius = 8.0 }
//!     grid = { n = 24, dx = 0.6 }
//!     protocol = { max_approach = 3.0, load_step = 0.15 }
//!     "#,
//!     Path::new("inline.toml"),
//! )?;
//! assert_eq!(sweep.len(), 2);
//! assert_eq!(sweep.label(1), "material.gamma = 0.2");
//!
//! let dir = std::env::temp_dir().join(format!("tack-sweep-doc-{}", std::process::id()));
//! let report = tack_sweep::run_sweep(&sweep, &dir, &SweepOptions::default(), &())?;
//! assert_eq!((report.ran, report.failed.len()), (2, 0));
//! // A rerun finds both points complete and runs nothing.
//! let again = tack_sweep::run_sweep(&sweep, &dir, &SweepOptions::default(), &())?;
//! assert_eq!((again.already_complete, again.ran), (2, 0));
//!
//! let table = dir.join("sweep.h5");
//! let merged = tack_sweep::merge(&dir, &table, &MergeOptions::default())?;
//! assert!(merged.written && merged.ok == 2, "{merged}");
//! # std::fs::remove_dir_all(&dir).ok();
//! # Ok::<(), tack_sweep::SweepError>(())
//! ```
//!
//! - [`sweep`]: the sweep file ([`Sweep`]), its points, [`Shard`]s, the output directory and
//!   [`run_sweep`] with a [`SweepObserver`] for progress and cancellation;
//! - [`merge`](mod@merge): [`merge()`] into one table, [`MergeReport`].
//!
//! Each point is solved by [`tack::run_to_file`] on the sweep's thread pool, its transforms
//! split across the pool's threads; every transform gives the same bits on any thread count
//! (`tack_kernels`), so results do not depend on the number of threads or shards.

pub mod merge;
pub mod sweep;

pub use merge::{MergeOptions, MergeReport, PointIssue, merge};
pub use sweep::{
    Axis, DEFAULT_COLLECT, MAX_POINTS, MAX_THREADS, POINTS_DIR, PointFailure, SCENE_COPY,
    SWEEP_COPY, SWEEP_VERSION, Shard, Sweep, SweepError, SweepObserver, SweepOptions, SweepReport,
    index_width, point_path, prepare_dir, run_sweep, verify_point, write_text_atomically,
};
