//! A smooth adhesion law of the caller's own: the Morse law (`morse.rs`, written outside
//! tack) on a sphere R = 1 on E* = 1, γ = 1, run through [`AdhesionLaw::custom`] across Tabor's
//! μ = 1/ρ; prints the pull-off against DMT (2πγR) and JKR (1.5πγR), and what a curve that
//! breaks a statement is told.
//!
//! `cargo run --release -p tack-solver --example custom_law -- [n]` (default n = 96)

mod morse;

use std::f64::consts::PI;
use std::time::Instant;
use tack_geometry::{Boundary, Grid, Sphere, Surface};
use tack_kernels::operator_for;
use tack_solver::{
    AdhesionLaw, AdhesiveOptions, AdhesiveSolver, ApproachPath, Curve, SnapshotRequest,
};

use morse::Morse;

/// A Morse law whose stiffness has the wrong sign: [`AdhesionLaw::custom`] refuses it.
#[derive(Debug)]
struct WrongSign(Morse);

impl Curve for WrongSign {
    fn name(&self) -> &'static str {
        "morse_wrong_sign"
    }
    fn label(&self) -> &'static str {
        "Morse with dp/dg of the wrong sign, range rho"
    }
    fn length(&self) -> f64 {
        self.0.length()
    }
    fn meaning(&self) -> &'static str {
        Curve::meaning(&self.0)
    }
    fn pressure(&self, gamma: f64, g: f64) -> f64 {
        self.0.pressure(gamma, g)
    }
    fn stiffness(&self, gamma: f64, g: f64) -> f64 {
        -self.0.stiffness(gamma, g)
    }
    fn stiffens(&self) -> bool {
        true
    }
    fn peak(&self, gamma: f64) -> f64 {
        self.0.peak(gamma)
    }
    fn reach(&self) -> f64 {
        Curve::reach(&self.0)
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = std::env::args().nth(1).map_or(Ok(96), |s| s.parse())?;
    let (radius, e_star, gamma) = (1.0, 1.0, 1.0);
    println!(
        "Morse law p = −(2γ/ρ)(e^(−g/ρ) − e^(−2g/ρ)) on a sphere, {n}² elements; \
         F/(πγR) is 2 in the DMT limit, 1.5 in the JKR limit"
    );
    println!("    μ      ρ  elements/zone    F/(πγR)  steps  converged    time");
    for mu in [0.1, 0.3, 1.0, 3.0] {
        let range = 1.0 / mu;
        let law = AdhesionLaw::custom(Morse { range })?;
        // The domain holds the law's reach around the pull-off contact (gap r²/2R at radius r).
        let reach = law.reach(gamma).expect("a finite-range law");
        let half = (2.0 * radius * reach).sqrt().max(3.0);
        let dx = 2.0 * half / n as f64;
        let grid = Grid::square(n, dx, Boundary::Free)?;
        let surface = Surface::from_shape(grid, &Sphere::new(radius)?);
        let op = operator_for(grid, e_star)?;
        let zone = law.zone_length(e_star, gamma).expect("a process zone") / dx;
        let mut solver =
            AdhesiveSolver::with_law(op, &surface, gamma, law, AdhesiveOptions::default())?;
        let step = (range / 4.0).min(0.1);
        let path = ApproachPath {
            start: -(3.0 * range + 1.0),
            max_approach: 1.5,
            load_step: step,
            unload_step: step,
            coarse_unload_step: None,
            refine_pull_off: false,
            retract_to: Some(-(3.0 * range + 3.0)),
            max_steps: 100_000,
        };
        let t = Instant::now();
        let result = solver.run_path(&path, &SnapshotRequest::None, &mut ())?;
        println!(
            "{mu:>5} {range:>6.2} {zone:>14.1} {:>10.4} {:>6} {:>10} {:>6.2} s",
            -result.pull_off_force() / (PI * gamma * radius),
            result.records.len(),
            result.all_converged(),
            t.elapsed().as_secs_f64()
        );
    }
    match AdhesionLaw::custom(WrongSign(Morse { range: 1.0 })) {
        Ok(_) => println!("a wrong-signed stiffness was accepted"),
        Err(e) => println!("refused: {e}"),
    }
    Ok(())
}
