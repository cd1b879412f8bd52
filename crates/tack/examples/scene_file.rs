//! Loads the committed scene `data/examples/smooth_jkr_sphere.toml` (found from the repository
//! root, `CARGO_MANIFEST_DIR/../..`), shows what it validates into, runs it in memory and
//! prints the summary; a second run applies a `--set`-style override.
//!
//!     cargo run --release -p tack --example scene_file

use std::path::Path;

use tack::{Problem, RunOptions, Scene};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let path = root.join("data/examples/smooth_jkr_sphere.toml");
    let scene = Scene::load(&path, &[])?;
    let problem = Problem::from_scene(&scene)?;
    println!(
        "{}: {} lines of TOML",
        path.strip_prefix(&root).unwrap_or(&path).display(),
        scene.text.lines().count()
    );
    println!(
        "  grid {}x{}, dx = {} ({:?}), crop window {:?}",
        problem.grid.nx(),
        problem.grid.ny(),
        problem.grid.dx(),
        problem.grid.boundary(),
        problem.window.map(|w| w.shape()),
    );
    println!(
        "  path: d from {} to {} (load step {}), retract by {}; F_JKR = {:.4}, d_JKR = {:.4}",
        problem.path.start,
        problem.path.max_approach,
        problem.path.load_step,
        problem.path.unload_step,
        problem.references.f_jkr.unwrap_or(f64::NAN),
        problem.references.d_jkr.unwrap_or(f64::NAN),
    );

    let outcome = tack::run(&scene, &RunOptions::default(), &mut ())?;
    println!(
        "  run: {} steps in {:.2?}, {} snapshots; pull-off F = {:.4} N, F/F_JKR = {:.4}",
        outcome.path.records.len(),
        outcome.wall_time,
        outcome.result.snapshots.len(),
        outcome.pull_off_force(),
        outcome.pull_off_ratio(),
    );

    // The same file with an override, as `tack run --set grid.dx=0.15 --set grid.n=96`.
    let overrides = ["grid.dx=0.15".to_owned(), "grid.n=96".to_owned()];
    let finer = Scene::load(&path, &overrides)?;
    let outcome = tack::run(&finer, &RunOptions::default(), &mut ())?;
    println!(
        "  with --set {}: F/F_JKR = {:.4} in {:.2?}",
        overrides.join(" --set "),
        outcome.pull_off_ratio(),
        outcome.wall_time,
    );
    Ok(())
}
