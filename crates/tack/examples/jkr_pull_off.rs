//! The JKR pull-off of a smooth sphere: load, retract, compare the greatest tensile force
//! with F_JKR = −(3/2)πγR, and cancel the criterion's first-order mesh error by Richardson
//! extrapolation over Δx and 2Δx (`RunOptions::richardson`).
//!
//! Units: mm, N, MPa. R = 8 mm, E* = 1 MPa, γ = 0.125 N/mm: F_JKR = −4.712 N at the contact
//! radius a_c = 3.05 mm, resolved by 20 elements of 0.15 mm (the coarse run: 10 of 0.3 mm).
//!
//!     cargo run --release -p tack --example jkr_pull_off

use tack::analytics::{jkr_pull_off_approach, jkr_pull_off_force, jkr_pull_off_radius};
use tack::{RunOptions, Scene};

const SCENE: &str = r#"
version = 1

[material]
e_star = 1.0    # MPa
gamma = 0.125   # N/mm

[geometry]
shape = "sphere"
radius = 8.0    # mm

[grid]
n = 96
dx = 0.15       # mm

[protocol]
max_approach = 3.0          # mm: about 6 |d_JKR|, contact radius about 1.6 a_c
load_step = 0.15
unload_step = 0.005
coarse_unload_step = 0.1    # fast retraction while the force is still compressive
"#;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let scene = Scene::parse(SCENE, ".", &[])?;
    let (e_star, gamma, radius) = (1.0, 0.125, 8.0);
    let options = RunOptions {
        richardson: true,
        ..RunOptions::default()
    };
    let outcome = tack::run(&scene, &options, &mut ())?;

    let f_jkr = jkr_pull_off_force(gamma, radius);
    let a_c = jkr_pull_off_radius(e_star, gamma, radius);
    let dx = outcome.problem.grid.dx();
    let f = outcome.pull_off_force();
    let step = outcome.path.pull_off_step().expect("the path has steps");
    let d = outcome.path.records[step].approach;
    println!("smooth sphere R = {radius} mm, E* = {e_star} MPa, gamma = {gamma} N/mm");
    println!(
        "JKR:  F_JKR = {f_jkr:.4} N at d_JKR = {:.4} mm, a_c = {a_c:.3} mm",
        jkr_pull_off_approach(e_star, gamma, radius)
    );
    println!(
        "BEM:  F = {f:.4} N at d = {d:.4} mm (a_c/dx = {:.1}): F/F_JKR = {:.4} ({:+.1}%)",
        a_c / dx,
        outcome.pull_off_ratio(),
        100.0 * (outcome.pull_off_ratio() - 1.0)
    );
    let extra = &outcome.result.summary.extra;
    let coarse = extra["pull_off_force_coarse"];
    let richardson = extra["pull_off_force_richardson"];
    println!(
        "      2dx: F = {coarse:.4} N ({:+.1}%); Richardson 2F(dx) - F(2dx) = {richardson:.4} N ({:+.2}%)",
        100.0 * (coarse / f_jkr - 1.0),
        100.0 * (richardson / f_jkr - 1.0)
    );
    println!(
        "{} steps, all converged: {}, {:.2?} (coarse run {:.2?})",
        outcome.path.records.len(),
        outcome.path.all_converged(),
        outcome.wall_time,
        outcome.coarse_wall_time.unwrap_or_default()
    );
    Ok(())
}
