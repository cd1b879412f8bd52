//! A smooth sphere on a standard linear solid (E0 = 1, E∞ = 10, τ = 1) under the exponential
//! law (γ = 1e-3, Tabor μ = 1 at E0): loaded slowly (relaxed), then pulled off at retraction
//! speeds over five decades; prints the pull-off against the elastic ones at E0 and E∞ and the
//! apparent work of adhesion `F/(1.5πR)` beside γ.
//!
//! `cargo run --release -p tack-solver --example viscoelastic_pull_off -- [n] [speeds per decade]`

use std::f64::consts::PI;
use std::time::Instant;
use tack_geometry::{Boundary, Grid, Sphere, Surface};
use tack_kernels::operator_for;
use tack_solver::{
    AdhesionLaw, AdhesiveOptions, AdhesiveSolver, ApproachPath, Exponential, Prony, Rates,
    SnapshotRequest,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).map_or(Ok(48), |s| s.parse())?;
    let per_decade: usize = args.get(2).map_or(Ok(1), |s| s.parse())?;
    let (radius, gamma, range, side) = (1.0, 1e-3, 0.01, 1.2);
    let law = AdhesionLaw::Exponential(Exponential { range });
    let grid = Grid::square(n, side / n as f64, Boundary::Free)?;
    let surface = Surface::from_shape(grid, &Sphere::new(radius)?);
    let solver = |e_star: f64| -> Result<AdhesiveSolver, Box<dyn std::error::Error>> {
        let op = operator_for(grid, e_star)?;
        let options = AdhesiveOptions::default();
        Ok(AdhesiveSolver::with_law(
            op,
            &surface,
            gamma,
            law.clone(),
            options,
        )?)
    };
    let path = ApproachPath {
        start: -10.0 * range,
        max_approach: 0.02,
        load_step: 0.001,
        unload_step: 0.0005,
        coarse_unload_step: None,
        refine_pull_off: false,
        retract_to: None,
        max_steps: 100_000,
    };
    let none = SnapshotRequest::None;
    let f_jkr = 1.5 * PI * gamma * radius;
    let elastic = |e: f64| -> Result<f64, Box<dyn std::error::Error>> {
        Ok(-solver(e)?.run_path(&path, &none, &mut ())?.pull_off_force())
    };
    let t0 = Instant::now();
    let low = elastic(1.0)?;
    let elastic_time = t0.elapsed().as_secs_f64();
    let high = elastic(10.0)?;
    println!(
        "elastic pull-off / F_JKR: E0 {:.4} ({elastic_time:.2} s), E∞ {:.4}",
        low / f_jkr,
        high / f_jkr
    );
    println!("retraction speed  pull-off/F_JKR  apparent γ/γ  steps  converged  time");
    let prony = Prony::new(1.0, &[(9.0, 1.0)])?;
    for k in 0..=5 * per_decade {
        let speed = 1e-4 * 10f64.powf(k as f64 / per_decade as f64);
        let t0 = Instant::now();
        let mut s = solver(1.0)?;
        let rates = Rates {
            speed: 1e-4,
            unload_speed: speed,
            dwell: 0.0,
            dwell_steps: 1,
        };
        s.set_viscoelastic(prony.clone(), rates)?;
        let r = s.run_path(&path, &none, &mut ())?;
        let pull = -r.pull_off_force();
        println!(
            "{speed:16.1e}  {:14.4}  {:12.4}  {:5}  {:9}  {:.2} s",
            pull / f_jkr,
            pull / (1.5 * PI * radius) / gamma,
            r.records.len(),
            r.all_converged(),
            t0.elapsed().as_secs_f64()
        );
    }
    Ok(())
}
