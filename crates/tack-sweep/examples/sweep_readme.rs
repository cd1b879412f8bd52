//! The program that opens `crates/tack-sweep/README.md` (kept identical by `tests/readme.rs`):
//! run the 12-point JKR sweep of `data/sweeps/` and merge it into one table. Run from the
//! repository root: `cargo run --release -p tack-sweep --example sweep_readme`.
use tack_sweep::{MergeOptions, Sweep, SweepError, SweepOptions};

fn main() -> Result<(), SweepError> {
    // Sweep files are TOML (docs/sweeps.md): a base scene, the fields to vary, what to collect.
    let sweep = Sweep::load("data/sweeps/jkr_sphere_gamma.toml".as_ref())?;
    println!(
        "{} points, the last: {}",
        sweep.len(),
        sweep.label(sweep.len() - 1)
    );
    // One HDF5 result per point in DIR/points/, on every core; a rerun resumes.
    let dir = std::env::temp_dir().join("tack-sweep-readme");
    let report = tack_sweep::run_sweep(&sweep, &dir, &SweepOptions::default(), &())?;
    println!("{report}");
    // The varied parameters and the collected quantities of every point, in one table.
    let table = std::env::temp_dir().join("tack-sweep-readme.h5");
    let merged = tack_sweep::merge(&dir, &table, &MergeOptions::default())?;
    println!("{merged}");
    Ok(())
}
