//! The peers' adhesion case under the exponential law: a sphere R = 1 on E* = 1, γ = 1e-3,
//! a free 1 × 1 domain, Tabor μ = 3 (ρ = 3.33e-3); prints the pull-off against JKR and DMT.
//!
//! `cargo run --release -p tack-solver --example smooth_pull_off -- 128 3 [exp|lj] [fine] [free|periodic]`
//! (`TOP=0` in the environment loads only to d = 0, as `cargo xtask bench-laws` does; the default
//! is 2 d_c)

use std::f64::consts::PI;
use std::time::Instant;
use tack_geometry::{Boundary, Grid, Sphere, Surface};
use tack_kernels::operator_for;
use tack_solver::{
    AdhesionLaw, AdhesiveOptions, AdhesiveSolver, ApproachPath, Exponential, LennardJones,
    SnapshotRequest,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).map_or(Ok(64), |s| s.parse())?;
    let mu: f64 = args.get(2).map_or(Ok(3.0), |s| s.parse())?;
    let law_name = args.get(3).map_or("exponential", |s| s.as_str());
    // Retraction steps per d_c near the pull-off (coarse steps are d_c/4).
    let fine: f64 = args.get(4).map_or(Ok(100.0), |s| s.parse())?;
    let boundary = match args.get(5).map(String::as_str) {
        Some("periodic") => Boundary::Periodic,
        _ => Boundary::Free,
    };
    // The deepest approach of the path, in units of d_c (default 2).
    let top: f64 = std::env::var("TOP").map_or(Ok(2.0), |s| s.parse())?;
    let (radius, e_star, gamma, side) = (1.0, 1.0, 1e-3, 1.0);
    let range = (radius * gamma * gamma / (e_star * e_star * mu * mu * mu)).cbrt();
    let law = match law_name {
        "lj" => AdhesionLaw::LennardJones(LennardJones { range }),
        _ => AdhesionLaw::Exponential(Exponential { range }),
    };
    let dx = side / n as f64;
    let grid = Grid::square(n, dx, boundary)?;
    let surface = Surface::from_shape(grid, &Sphere::new(radius)?);
    let op = operator_for(grid, e_star)?;
    let mut solver =
        AdhesiveSolver::with_law(op, &surface, gamma, law, AdhesiveOptions::default())?;
    // JKR scales: the pull-off approach d_c = −(3/4)(π²γ²R/E*²)^(1/3).
    let d_c = 0.75 * (PI * PI * gamma * gamma * radius / (e_star * e_star)).cbrt();
    let path = ApproachPath {
        start: -3.0 * d_c,
        max_approach: top * d_c,
        load_step: d_c / 2.0,
        unload_step: d_c / fine,
        coarse_unload_step: Some(d_c / 4.0),
        refine_pull_off: true,
        retract_to: Some(-4.0 * d_c),
        max_steps: 10_000,
    };
    let t = Instant::now();
    let result = solver.run_path(&path, &SnapshotRequest::None, &mut ())?;
    let secs = t.elapsed().as_secs_f64();
    let f = result.pull_off_force();
    let steps = &result.records;
    let fft: usize = steps.iter().map(|s| s.cg_iterations).sum();
    let newton: usize = steps.iter().map(|s| s.active_set_iterations).sum();
    let bad = steps.iter().filter(|s| !s.converged).count();
    println!(
        "n = {n}, μ = {mu}, law {law_name}: F/(πγR) = {:.5}  (JKR 1.5, DMT 2)  steps {} (not converged {bad}), Newton {newton}, products {fft}, {secs:.2} s",
        -f / (PI * gamma * radius),
        steps.len()
    );
    if args.get(6).is_some() {
        for s in steps {
            println!(
                "{:.6e} {:.6e} {} {} {} {}",
                s.approach, s.force, s.n_bonded, s.n_cohesive, s.active_set_iterations, s.converged
            );
        }
    }
    Ok(())
}
