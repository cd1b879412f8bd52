//! The non-adhesive validation tables of `results/validation.md`: Hertz (free boundaries) and
//! Westergaard (periodic 1D waviness), the baseline under every adhesive figure.

use anyhow::Result;
use std::f64::consts::PI;
use std::fmt::Write as _;
use std::time::Instant;
use tack_analytics::{hertz_contact_radius, hertz_force, westergaard_p_star};
use tack_geometry::{Boundary, Grid, Sphere, Surface};
use tack_kernels::operator_for;
use tack_solver::{ContactSolver, SolverOptions};

/// The markdown of `validation.md`: both tables.
pub fn report() -> Result<String> {
    let mut report = String::from("# tack validation report\n\n");
    report += &hertz_table()?;
    report += &westergaard_table()?;
    Ok(report)
}

fn hertz_table() -> Result<String> {
    let (r, e, d) = (1.0, 1.0, 0.01);
    let a = hertz_contact_radius(r, d);
    let mut s = String::from(
        "## Hertz sphere, free boundaries\n\n| a/Δx | grid | force error | iterations | time [s] |\n|---|---|---|---|---|\n",
    );
    for ratio in [10.0f64, 20.0, 40.0, 80.0] {
        let n = 2 * (1.25 * ratio).ceil() as usize + 1;
        let grid = Grid::square(n, a / ratio, Boundary::Free)?;
        let surface = Surface::from_shape(grid, &Sphere::new(r)?);
        let t = Instant::now();
        let st = ContactSolver::new(operator_for(grid, e)?, &surface, SolverOptions::default())?
            .solve(d)?;
        let err = st.force / hertz_force(e, r, d) - 1.0;
        writeln!(
            s,
            "| {ratio} | {n}² | {err:+.3e} | {} | {:.3} |",
            st.iterations,
            t.elapsed().as_secs_f64()
        )?;
    }
    Ok(s + "\n")
}

fn westergaard_table() -> Result<String> {
    let (e, h, lambda) = (1.0, 0.01, 1.0);
    let p_star = westergaard_p_star(e, h, lambda);
    let mut s = String::from(
        "## Westergaard 1D waviness, periodic\n\nmax |p̄ − p* sin²(πa/λ)|/p* over πa/λ ∈ [0.2, 1.4]\n\n| λ/Δx | max deviation |\n|---|---|\n",
    );
    for nx in [128usize, 256, 512, 1024] {
        let grid = Grid::new(nx, 1, lambda / nx as f64, Boundary::Periodic)?;
        let heights = ndarray::Array2::from_shape_fn((nx, 1), |(i, _)| {
            h * (1.0 - (2.0 * PI * grid.x(i) / lambda).cos())
        });
        let surface = Surface::new(grid, heights)?;
        let mut solver =
            ContactSolver::new(operator_for(grid, e)?, &surface, SolverOptions::default())?;
        let mut worst: f64 = 0.0;
        for k in 1..60 {
            let st = solver.solve(h * (1.0 - ((60 - k) as f64 / 60.0).powi(4)))?;
            let psi = PI * st.n_contact as f64 * grid.dx() / (2.0 * lambda);
            if (0.2..=1.4).contains(&psi) {
                worst = worst.max((st.mean_pressure - p_star * psi.sin().powi(2)).abs() / p_star);
            }
        }
        writeln!(s, "| {nx} | {worst:.3e} |")?;
    }
    Ok(s)
}
