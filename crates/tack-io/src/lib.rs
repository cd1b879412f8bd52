//! Result files of tack: the HDF5 layout, its plain data model, and reading measured topographies;
//! the only crate that links the HDF5 library.
//!
//! # Layout of a result file
//!
//! | object | content |
//! |---|---|
//! | `/` attributes | `tack_version`, `git_revision`, `command_line`, `scene` (full TOML), `created` (RFC 3339): variable-length UTF-8 strings; `seed` (u64) when the run had one |
//! | `/curve/{approach, force, area}` | 1D f64, one entry per step of the approach path |
//! | `/curve/{n_bonded, n_clusters, iterations, active_set_iterations}` | 1D u64 (`iterations` counts CG iterations; under a smooth law, operator products) |
//! | `/curve/converged` | 1D u8, 0 or 1 |
//! | `/curve/mean_pressure` | 1D f64, only when recorded |
//! | `/curve/full_contact` | 1D u8, 1 where the step is in periodic full contact (its force and mean pressure are a bound, not a state's); only when recorded |
//! | `/curve/time` | 1D f64, a viscoelastic solid's time at the end of each step; only then |
//! | `/curve/<law column>` | 1D u64, the adhesion law's per-step column ([`LawColumn`]: `n_cohesive`, the Dugdale cohesive zone's or a smooth law's process zone's elements), with the string attribute `law_column` saying what it counts; none under the zero-range criterion |
//! | `/surface/heights` | 2D f64 `(nx, ny)` with f64 attribute `dx`, only when asked for |
//! | `/snapshots/<step>/{pressure, bonded}` | 2D f64 and 2D u8 (0/1); `<step>` is the index into the curve as a plain decimal (`0`, `17`, `250`), the group has the f64 attribute `approach` |
//! | `/summary` attributes | f64 `pull_off_force`, `f_jkr`, `pull_off_ratio`; `johnson_alpha` and `alpha_star` when known; any extra named scalars |
//!
//! Files are written to a temporary file beside the target and renamed onto it only on success
//! ([`write_result`]), so a failed or interrupted run never leaves a half-written result under
//! the final name. Everything is readable with `h5dump` or h5py, without tack.
//!
//! Parameter sweeps merge the summaries of their points into one *sweep table*
//! ([`write_sweep_table`], [`read_sweep_table`]).
//!
//! # Layout of a sweep table
//!
//! | object | content |
//! |---|---|
//! | `/` attributes | `sweep` (the sweep file's TOML), `scene` (the base scene's TOML), `tack_version`, `git_revision`, `command_line`, `created`: variable-length UTF-8 strings |
//! | `/point/index` | 1D u64, the point index (row `k` holds point `k`) |
//! | `/point/status` | 1D u8: 0 ok, 1 failed, 2 missing, 3 incomplete: a result whose `/summary` status is not `complete` ([`POINT_OK`], [`POINT_FAILED`], [`POINT_MISSING`], [`POINT_INCOMPLETE`]) |
//! | `/point/error` | 1D variable-length UTF-8 strings: the error of a failed point, why a point is missing, else empty |
//! | `/point/result_status` | 1D variable-length UTF-8 strings: the `/summary` status of the point's result (`complete`, `stopped at protocol.max_steps`), empty without a result |
//! | `/point/warnings` | 1D variable-length UTF-8 strings: the `/summary` warnings of the point's result, one per line, empty when none |
//! | `/parameters/<field>` | 1D i64, f64 or variable-length UTF-8 strings: the value of a varied scene field (dotted name, e.g. `roughness.h`) at every point |
//! | `/parameters` attribute `fields` | 1D strings: the varied fields in sweep order (first = outermost loop) |
//! | `/results/<name>` | 1D f64: a collected summary quantity, NaN where the point has none (failed, missing, or not defined for it) |
//! | `/results` attribute `names` | 1D strings: the collected quantities in the sweep's order |
//!
//! HDF5 lists group members alphabetically; the `fields` and `names` attributes keep the
//! order of the sweep file. Written atomically, like result files.
//!
//! # Example: a round trip
//!
//! The data model ([`RunResult`]) is plain data; `tack::run` fills it from a solve, but any
//! program can write one and read it back unchanged.
//!
//! ```
//! use tack_io::{Curve, Provenance, RunResult, Snapshot, Summary, read_result, write_result};
//! use ndarray::{Array2, array};
//!
//! let curve = Curve {
//!     approach: vec![0.5, 1.0, 0.5, 0.0],
//!     force: vec![0.8, 2.4, 0.3, -1.1],
//!     area: vec![0.2, 0.5, 0.3, 0.1],
//!     n_bonded: vec![20, 50, 30, 10],
//!     n_clusters: vec![1, 1, 1, 1],
//!     iterations: vec![12, 9, 7, 15],
//!     active_set_iterations: vec![2, 2, 3, 4],
//!     converged: vec![true; 4],
//!     mean_pressure: None,
//!     full_contact: None,
//!     law_columns: Vec::new(),
//!     time: None,
//! };
//! let result = RunResult {
//!     provenance: Provenance {
//!         scene: "version = 1\n".into(),
//!         ..Provenance::current("unknown", "2026-01-01T00:00:00Z")
//!     },
//!     curve,
//!     surface: Some((Array2::from_elem((3, 2), 0.25), 0.1)),
//!     gamma: None,
//!     snapshots: vec![Snapshot {
//!         step: 3,
//!         approach: 0.0,
//!         pressure: array![[0.0, -0.5], [1.0, 0.0], [0.0, 0.0]],
//!         bonded: array![[false, true], [true, false], [false, false]],
//!     }],
//!     summary: Summary {
//!         pull_off_force: -1.1,
//!         f_jkr: -1.0,
//!         pull_off_ratio: 1.1,
//!         ..Summary::default()
//!     },
//! };
//!
//! let path = std::env::temp_dir().join(format!("tack-io-doctest-{}.h5", std::process::id()));
//! write_result(&path, &result)?;
//! let back = read_result(&path);
//! std::fs::remove_file(&path)?;
//! assert_eq!(back?, result); // every field, bit for bit
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod error;
mod h5;
mod model;
mod read;
mod sweep;
mod write;

pub use error::IoError;
pub use h5::MAX_DATASET_BYTES;
pub use model::{Curve, LawColumn, Provenance, RunResult, Snapshot, Summary};
pub use read::{describe, read_gamma_map_h5, read_height_map_h5, read_result};
pub use sweep::{
    POINT_FAILED, POINT_INCOMPLETE, POINT_MISSING, POINT_OK, ParameterColumn, SweepTable,
    read_sweep_table, write_sweep_table,
};
pub use write::{not_a_regular_file, write_atomically, write_result, write_text_atomically};

/// The example of README.md, run as a doctest (it writes and removes a file in the temporary
/// directory).
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctest;
