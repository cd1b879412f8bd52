//! The program of the top-level README's library section (kept identical by `tests/readme.rs`):
//! both entry points, a scene file and a height array held in memory. Run from the repository
//! root, where the scene's relative path points: `cargo run --release -p tack --example library`.
use tack::geometry::{Boundary, Grid, Sphere, Surface};
use tack::heights::{PullOffSpec, pull_off};
use tack::{RunOptions, Scene};

fn main() -> Result<(), tack::Error> {
    // A scene file (docs/scenes.md); the path is relative to the working directory.
    let scene = Scene::load("data/examples/smooth_jkr_sphere.toml".as_ref(), &[])?;
    let outcome = tack::run(&scene, &RunOptions::default(), &mut ())?;
    println!("scene: F/F_JKR = {:.4}", outcome.pull_off_ratio()); // 1.1343 at a_c/Δx = 10
    outcome.write(&std::env::temp_dir().join("jkr.h5"))?; // only if you want the HDF5 file

    // A body held in memory as heights (a measured map, another program's surface), pulled off
    // by the default path: its radius fitted, one load step, retraction until contact is lost.
    let grid = Grid::square(64, 0.3, Boundary::Free)?;
    let heights = Surface::from_shape(grid, &Sphere::new(8.0)?).into_heights();
    let spec = PullOffSpec::new(0.3, 1.0, 0.125); // Δx, E*, γ
    let options = RunOptions {
        threads: Some(2), // bit-identical on any count
        ..RunOptions::default()
    };
    let array = pull_off(&heights, &spec, &options, &mut ())?;
    println!(
        "array: F/F_JKR = {:.4} over {} steps",
        array.pull_off_ratio(),
        array.path.records.len()
    );
    Ok(())
}
