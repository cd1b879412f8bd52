//! Runs a small smooth-sphere scene in memory, writes the HDF5 result file to a temporary
//! directory, reads it back with `tack::io::read_result` and prints what came back (and
//! `tack::io::describe`, the text of `tack info`).
//!
//!     cargo run --release -p tack --example hdf5_roundtrip

use tack::{RunOptions, Scene};

const SCENE: &str = r#"
version = 1

[material]
e_star = 1.0
gamma = 0.125

[geometry]
shape = "sphere"
radius = 8.0

[grid]
n = 48
dx = 0.3

[protocol]
max_approach = 3.0
load_step = 0.15
unload_step = 0.01

[output]
snapshots = "pull_off"    # the pull-off step and the last contact
surface = true
"#;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let scene = Scene::parse(SCENE, ".", &[])?;
    let outcome = tack::run(&scene, &RunOptions::default(), &mut ())?;

    let dir = std::env::temp_dir().join(format!("tack-hdf5-roundtrip-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let file = dir.join("jkr.h5");
    outcome.write(&file)?;
    let bytes = std::fs::metadata(&file)?.len();
    let back = tack::io::read_result(&file)?;
    let description = tack::io::describe(&file)?;
    std::fs::remove_dir_all(&dir)?;

    println!("wrote {} ({bytes} bytes) and read it back:", file.display());
    println!(
        "  provenance: tack {}, git {}, scene of {} lines, created {}",
        back.provenance.tack_version,
        back.provenance.git_revision,
        back.provenance.scene.lines().count(),
        back.provenance.created
    );
    let steps: Vec<usize> = back.snapshots.iter().map(|s| s.step).collect();
    println!(
        "  curve: {} steps; snapshots at steps {steps:?}; surface {:?}",
        back.curve.len(),
        back.surface.as_ref().map(|(h, dx)| (h.dim(), *dx)),
    );
    let s = &back.summary;
    println!(
        "  summary: pull_off_force = {:.4}, f_jkr = {:.4}, pull_off_ratio = {:.4}, {} extras",
        s.pull_off_force,
        s.f_jkr,
        s.pull_off_ratio,
        s.extra.len()
    );
    // Bit for bit (a NaN summary field, such as f_jkr of a body other than a sphere, would
    // compare unequal to itself; this scene has none).
    println!(
        "  identical to the in-memory result: {}",
        back == outcome.result
    );
    println!("tack::io::describe:\n{description}");
    Ok(())
}
