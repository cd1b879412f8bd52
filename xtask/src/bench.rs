//! Benchmarks that print ratios measured in the same run (operator time / bare FFT floor).

use anyhow::Result;
use ndarray::Array2;
use std::time::Instant;
use tack_geometry::{Boundary, Grid};
use tack_kernels::operator_for;

/// Median wall time in seconds of `f` over enough repetitions to fill ~0.5 s (at least 5).
pub fn median_time(mut f: impl FnMut()) -> f64 {
    f();
    let probe = Instant::now();
    f();
    let once = probe.elapsed().as_secs_f64().max(1e-9);
    let reps = ((0.5 / once) as usize).clamp(5, 200);
    let mut times: Vec<f64> = (0..reps)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[reps / 2]
}

/// Forward + inverse real 2D FFT of an `mx × my` array with the operators' own engine and
/// nothing skipped: the floor any FFT operator pays.
fn bare_fft_pair(mx: usize, my: usize) -> impl FnMut() {
    let mut fft = tack_kernels::Fft2::new(mx, my);
    move || fft.round_trip()
}

/// `cargo xtask bench-kernels`: operator application vs the bare FFT pair of its padded size.
pub fn kernels() -> Result<()> {
    println!("operator application vs bare forward+inverse r2c FFT pair of the same padded size");
    println!(
        "{:>6} {:>10} {:>12} {:>12} {:>8}",
        "N", "boundary", "apply [ms]", "fft [ms]", "ratio"
    );
    for n in [256usize, 512, 1024] {
        for boundary in [Boundary::Free, Boundary::Periodic] {
            let grid = Grid::square(n, 1.0, boundary)?;
            let mut op = operator_for(grid, 1.0)?;
            let p = Array2::from_shape_fn((n, n), |(i, j)| ((i + 2 * j) % 5) as f64);
            let mut u = Array2::zeros((n, n));
            let t_op = median_time(|| op.apply(p.view(), u.view_mut()));
            let m = if boundary == Boundary::Free {
                tack_kernels::padded_size(n)
            } else {
                n
            };
            let t_fft = median_time(bare_fft_pair(m, m));
            println!(
                "{n:>6} {:>10} {:>12.3} {:>12.3} {:>8.2}",
                format!("{boundary:?}").to_lowercase(),
                t_op * 1e3,
                t_fft * 1e3,
                t_op / t_fft
            );
        }
    }
    Ok(())
}

/// `cargo xtask bench-jkr`: speed against error on the smooth JKR sphere (paper's criterion).
pub fn jkr(args: &[String]) -> Result<()> {
    let ratios: Vec<f64> = if args.is_empty() {
        vec![5.0, 10.0, 20.0, 40.0, 80.0]
    } else {
        args.iter()
            .map(|a| {
                a.parse()
                    .map_err(|_| anyhow::anyhow!("ratio `{a}` is not a number"))
            })
            .collect::<Result<_>>()?
    };
    println!(
        "smooth sphere, free boundaries, κ = 0.473201, load to d̂ = 6, retract in steps of 0.01"
    );
    println!(
        "{:>8} {:>8} {:>7} {:>10} {:>10} {:>12} {:>12}",
        "a_c/Δx", "grid", "steps", "CG iters", "time [s]", "F/F_JKR − 1", "jump-off d̂"
    );
    for ratio in ratios {
        let t = Instant::now();
        let run = tack_tests::JkrSphere::new(ratio, tack_solver::KAPPA).run();
        let secs = t.elapsed().as_secs_f64();
        println!(
            "{ratio:>8} {:>8} {:>7} {:>10} {secs:>10.2} {:>+12.4} {:>12.3}",
            format!("{}²", run.grid.nx()),
            run.result.records.len(),
            run.result.cg_iterations(),
            run.pull_off_error,
            run.last_contact_approach
        );
    }
    Ok(())
}
