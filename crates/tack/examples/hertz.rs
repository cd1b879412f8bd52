//! Non-adhesive Hertz contact through the library: a sphere scene with `gamma = 0` run by
//! `tack::run`, its loading forces compared with `tack::analytics::hertz_force`.
//!
//! Units: mm, N, MPa. R = 8 mm, E* = 1 MPa, pressed to d = 0.5 mm (Hertz contact radius
//! a = √(Rd) = 2 mm, resolved by 20 elements of 0.1 mm at the deepest step).
//!
//!     cargo run --release -p tack --example hertz

use std::f64::consts::PI;

use tack::analytics::{hertz_contact_radius, hertz_force};
use tack::solver::Phase;
use tack::{RunOptions, Scene};

const SCENE: &str = r#"
version = 1

[material]
e_star = 1.0    # MPa
gamma = 0.0     # no adhesion: the adhesive solver reduces to non-adhesive contact

[geometry]
shape = "sphere"
radius = 8.0    # mm

[grid]
n = 64
dx = 0.1        # mm

[protocol]
start = 0.1
max_approach = 0.5
load_step = 0.1
unload_step = 0.1
"#;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let scene = Scene::parse(SCENE, ".", &[])?;
    let (e_star, radius) = (scene.file.material.e_star, 8.0);
    let outcome = tack::run(&scene, &RunOptions::default(), &mut ())?;
    let dx = outcome.problem.grid.dx();

    println!("Hertz: sphere R = {radius} mm, E* = {e_star} MPa, dx = {dx} mm (gamma = 0)");
    println!("   d [mm]   F [N]     F_Hertz [N]  error    a [mm]  a_Hertz [mm]");
    for (record, phase) in outcome.path.records.iter().zip(&outcome.path.phases) {
        if *phase != Phase::Load {
            continue;
        }
        let d = record.approach;
        let f_hertz = hertz_force(e_star, radius, d);
        let a = (record.area / PI).sqrt(); // area-equivalent contact radius
        println!(
            "   {d:.3}    {:.5}   {f_hertz:.5}      {:+.3}%  {a:.3}   {:.3}",
            record.force,
            100.0 * (record.force / f_hertz - 1.0),
            hertz_contact_radius(radius, d),
        );
    }
    let worst_unload = outcome
        .path
        .records
        .iter()
        .zip(&outcome.path.phases)
        .filter(|(r, p)| **p == Phase::Unload && r.approach > 0.0)
        .map(|(r, _)| (r.force / hertz_force(e_star, radius, r.approach) - 1.0).abs())
        .fold(0.0, f64::max);
    println!(
        "unloading retraces the loading curve (no adhesion, no hysteresis): worst |error| {:.3}%",
        100.0 * worst_unload
    );
    println!(
        "{} steps in {:.2?}, all converged: {}",
        outcome.path.records.len(),
        outcome.wall_time,
        outcome.path.all_converged()
    );
    Ok(())
}
