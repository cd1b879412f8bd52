//! The program that opens `crates/tack/README.md` (kept identical by `tests/readme.rs`): run the
//! smooth JKR sphere scene in memory and print the pull-off ratio. Run from the repository root:
//! `cargo run --release -p tack --example readme`.
use tack::{RunOptions, Scene};

fn main() -> Result<(), tack::Error> {
    // Scene files are TOML (docs/scenes.md); `--set`-style overrides go in the second argument.
    let scene = Scene::load("data/examples/smooth_jkr_sphere.toml".as_ref(), &[])?;
    // Solve the load–retract path in memory: no file is written, no progress is drawn.
    let outcome = tack::run(&scene, &RunOptions::default(), &mut ())?;
    println!(
        "pull-off F = {:.4}, F/F_JKR = {:.4} ({} steps, all converged: {})",
        outcome.pull_off_force(),
        outcome.pull_off_ratio(),
        outcome.path.records.len(),
        outcome.path.all_converged()
    );
    Ok(())
}
