//! A rigid wave sliding over a standard linear solid (E0 = 1, E1 = 2, τ = 1) on a periodic strip
//! in plane strain, under the Dugdale law: the contact's trailing edge is an opening crack at
//! the sliding speed, and its cohesive zone `c` gives the toughening `G/G0 = c/c0` it needs
//! (`c0 = πE0γ/(4σ0²)`, the relaxed zone). Prints it beside Greenwood–Johnson's and
//! Persson–Brener's `G(v)/G0` (docs/theory.md §3.10; the CI test is `tests/steady_crack.rs`).
//!
//! `cargo run --release -p tack-solver --example sliding_crack -- [n] [v·τ_r/c0 ...]`

use std::f64::consts::PI;
use std::time::Instant;
use tack_analytics::{greenwood_johnson_toughening, persson_brener_toughening};
use tack_geometry::{Boundary, Grid, Surface};
use tack_kernels::operator_for;
use tack_solver::{AdhesionLaw, AdhesiveOptions, AdhesiveSolver, Dugdale, Prony, Rates};

/// The wave `A(1 − cos 2π(x − shift))` on the strip of period 1.
fn wave(grid: Grid, amplitude: f64, shift: f64) -> Result<Surface, Box<dyn std::error::Error>> {
    let heights = ndarray::Array2::from_shape_fn(grid.shape(), |(i, _)| {
        let x = (i as f64 + 0.5) * grid.dx();
        amplitude * (1.0 - (2.0 * PI * (x - shift)).cos())
    });
    Ok(Surface::new(grid, heights)?)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).map_or(Ok(4096), |s| s.parse())?;
    let speeds: Vec<f64> = if args.len() > 2 {
        args[2..]
            .iter()
            .map(|s| s.parse())
            .collect::<Result<_, _>>()?
    } else {
        vec![0.1, 1.0, 10.0]
    };
    // The relaxed zone spans n/256 elements (16 at 4096): 1/256 of the period.
    let (amplitude, approach, gamma) = (0.01, 0.004, 8e-5);
    let c0 = 1.0 / 256.0;
    let sigma0 = (PI * gamma / (4.0 * c0)).sqrt();
    let (e0, e1, tau) = (1.0, 2.0, 1.0);
    let tau_r = tau * (e0 + e1) / e0;
    let grid = Grid::new(n, 1, 1.0 / n as f64, Boundary::Periodic)?;
    println!(
        "strip of {n} elements, relaxed zone c0 = {:.1} elements, E∞/E0 = {}",
        c0 * n as f64,
        (e0 + e1) / e0
    );
    for v_over in speeds {
        let t = Instant::now();
        let speed = v_over * c0 / tau_r;
        let op = operator_for(grid, e0)?;
        let law = AdhesionLaw::Dugdale(Dugdale { sigma0 });
        let options = AdhesiveOptions::default();
        let mut s =
            AdhesiveSolver::with_law(op, &wave(grid, amplitude, 0.0)?, gamma, law, options)?;
        let rates = Rates {
            speed: 1.0,
            unload_speed: 1.0,
            dwell: 0.0,
            dwell_steps: 1,
        };
        s.set_viscoelastic(Prony::new(e0, &[(e1, tau)])?, rates)?;
        // Pressed instantly, relaxed at rest, then slid one element per time step over a
        // travel of 0.12 of the period (steady from about 0.1).
        s.step(approach)?;
        s.hold(1e3)?;
        let steps = (0.12 * n as f64).ceil() as usize;
        let mut converged = true;
        for k in 1..=steps {
            s.move_body(wave(grid, amplitude, k as f64 * grid.dx())?)?;
            converged &= s.hold(grid.dx() / speed)?.converged;
        }
        // The zone behind the contact (lower x: the trailing edge).
        let (bonded, zone) = (s.bonded(), s.cohesive_zone().ok_or("the Dugdale law")?);
        let at = |i: isize| i.rem_euclid(n as isize) as usize;
        let start = (0..n as isize)
            .find(|&i| bonded[[at(i), 0]] && !bonded[[at(i - 1), 0]])
            .ok_or("a contact that is not full")?;
        let behind = (1..n as isize)
            .take_while(|&k| zone[[at(start - k), 0]])
            .count();
        let g = behind as f64 / (c0 * n as f64);
        let gj = greenwood_johnson_toughening(e0, e1, tau, c0, speed);
        let pb = persson_brener_toughening(e0, e1, tau, c0, speed);
        println!(
            "v·τ_r/c0 = {v_over}: zone {behind} elements, G/G0 = {g:.3}; Greenwood–Johnson {gj:.3} \
             ({:+.1}%), Persson–Brener {pb:.3}; converged {converged}; {:.1} s",
            100.0 * (g / gj - 1.0),
            t.elapsed().as_secs_f64()
        );
    }
    Ok(())
}
