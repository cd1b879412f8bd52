//! The Dugdale law against its smoothed variant (`SmoothedDugdale`: the step spread over two
//! openings of an element under σ0) on a smooth sphere R = E* = γ = 1, both against Maugis
//! (1992), at the Maugis parameter λ and element sizes given: the smoothed law's front no
//! longer moves by whole elements.
//!
//! `cargo run --release -p tack-solver --example smoothed_dugdale -- [λ] [Δx ...]`
//! (default λ = 1, Δx = 0.2 0.1: zones of 5 and 10 elements)

use std::f64::consts::PI;
use std::time::Instant;
use tack_analytics::{maugis_lambda, maugis_pull_off_hat};
use tack_geometry::{Boundary, Grid, Sphere, Surface};
use tack_kernels::operator_for;
use tack_solver::{
    AdhesionLaw, AdhesiveOptions, AdhesiveSolver, ApproachPath, Dugdale, SmoothedDugdale,
    SnapshotRequest,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = std::env::args()
        .skip(1)
        .map(|s| s.parse::<f64>())
        .collect::<Result<Vec<_>, _>>()?;
    let lambda = args.first().copied().unwrap_or(1.0);
    let sizes = if args.len() > 1 {
        args[1..].to_vec()
    } else {
        vec![0.2, 0.1]
    };
    let sigma0 = lambda / maugis_lambda(1.0, 1.0, 1.0, 1.0);
    let zone = PI / (4.0 * sigma0 * sigma0);
    let f_md = PI * maugis_pull_off_hat(lambda);
    // The domain holds the zone at pull-off (its contact radius is at most about R^(2/3)).
    let half = 2.4_f64.max(3.4 / lambda.sqrt());
    println!(
        "smooth sphere, Maugis λ = {lambda}: σ0 = {sigma0:.4}, h0 = {:.4}, zone l = {zone:.4}, \
         F_MD/(πγR) = {:.4}",
        1.0 / sigma0,
        f_md / PI
    );
    println!("      Δx   l/Δx  law        F/F_MD − 1   steps  converged    time");
    for dx in sizes {
        // Steps of Δx/16: finer than the error either law leaves.
        let step = dx / 16.0;
        let n = 2 * (half / dx).round() as usize + 1;
        for smoothed in [false, true] {
            let grid = Grid::square(n, dx, Boundary::Free)?;
            let surface = Surface::from_shape(grid, &Sphere::new(1.0)?);
            let op = operator_for(grid, 1.0)?;
            let law = if smoothed {
                AdhesionLaw::from(SmoothedDugdale::on_mesh(sigma0, 1.0, 1.0, dx)?)
            } else {
                AdhesionLaw::Dugdale(Dugdale { sigma0 })
            };
            let reach = law.reach(1.0).expect("a finite range");
            let mut solver =
                AdhesiveSolver::with_law(op, &surface, 1.0, law, AdhesiveOptions::default())?;
            let path = ApproachPath {
                start: -reach - step,
                max_approach: 1.0,
                load_step: step,
                unload_step: step,
                coarse_unload_step: None,
                refine_pull_off: false,
                retract_to: None,
                max_steps: 100_000,
            };
            let t = Instant::now();
            let r = solver.run_path(&path, &SnapshotRequest::None, &mut ())?;
            println!(
                "{dx:>8} {:>6.1}  {:<9} {:>+10.3}% {:>7} {:>10} {:>6.1} s",
                zone / dx,
                if smoothed { "smoothed" } else { "Dugdale" },
                100.0 * (r.pull_off_force() / f_md - 1.0),
                r.records.len(),
                r.all_converged(),
                t.elapsed().as_secs_f64()
            );
        }
    }
    Ok(())
}
