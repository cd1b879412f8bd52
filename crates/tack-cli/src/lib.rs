//! The `tack` command line's own parts: progress bars, the printed report and plots. Scenes,
//! runs and result files live in the [`tack`] library, sweeps in [`tack_sweep`]; this crate only
//! shows them.
//!
//! - [`progress`]: spinners and bars on stderr, as solver and sweep observers;
//! - [`report`]: the one-screen account of a run, number formatting;
//! - [`plot`]: force–approach figures with contact snapshots.

pub mod plot;
pub mod progress;
pub mod report;
