//! Result files of tack: the HDF5 layout, its plain data model, and reading measured topographies;
//! the only crate that links the HDF5 library.
//!
//! # Layout of a result file
//!
//! | object | content |
//! |---|---|
//! | `/` attributes | `tack_version`, `git_revision`, `command_line`, `scene` (full TOML), `created` (RFC 3339): variable-length UTF-8 strings; `seed` (u64) when the run had one |
//! | `/curve/{approach, force, area}` | 1D f64, one entry per step of the approach path |
//! | `/curve/{n_bonded, n_clusters, iterations, active_set_iterations}` | 1D u64 (`iterations` counts CG iterations) |
//! | `/curve/converged` | 1D u8, 0 or 1 |
//! | `/curve/mean_pressure` | 1D f64, only when recorded |
//! | `/surface/heights` | 2D f64 `(nx, ny)` with f64 attribute `dx`, only when asked for |
//! | `/snapshots/<step>/{pressure, bonded}` | 2D f64 and 2D u8 (0/1); `<step>` is the index into the curve as a plain decimal (`0`, `17`, `250`), the group has the f64 attribute `approach` |
//! | `/summary` attributes | f64 `pull_off_force`, `f_jkr`, `pull_off_ratio`; `johnson_alpha` and `alpha_star` when known; any extra named scalars |
//!
//! Files are written to a temporary file beside the target and renamed onto it only on success
//! ([`write_result`]), so a failed or interrupted run never leaves a half-written result under
//! the final name. Everything is readable with `h5dump` or h5py, without tack.

mod error;
mod h5;
mod model;
mod read;
mod write;

pub use error::IoError;
pub use model::{Curve, Provenance, RunResult, Snapshot, Summary};
pub use read::{describe, read_height_map_h5, read_result};
pub use write::write_result;
