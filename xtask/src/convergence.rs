//! `cargo xtask convergence`: how the pull-off force converges with Δx on smooth, wavy and
//! band-limited rough spheres, with Richardson values and the honesty of the error estimate.
//!
//! Every body is one continuous surface sampled at each resolution (analytic shapes, and random
//! roughness on a fixed band, `tack_geometry::rough_surface`), so the levels differ only in Δx.
//! The path is `tack::heights::pull_off`'s (one load step, retraction through the tensile part in
//! steps of the figures' full mode, [`FULL_UNLOAD_STEP`] = 0.01 d_s) with the same deepest
//! approach at every level. Writes
//! `results/convergence.json`.

use std::f64::consts::{PI, TAU};

use anyhow::{Result, ensure};
use ndarray::Array2;
use tack::geometry::{Boundary, Grid, RoughSpec, Sphere, Surface, Waviness2d, rough_surface};
use tack::heights::{LOAD_DEPTH, PullOffSpec, pull_off};
use tack::solver::{observed_order, richardson_first_order};

use crate::figures::FULL_UNLOAD_STEP;

/// Material and sphere: E* = R = 1, γ such that a_c = 0.080 R (the paper's rough spheres).
const GAMMA: f64 = 1.44868e-4;
/// Wavelength of the wavy spheres (0.78 a_c; 4Δx at n = 64).
const LAMBDA: f64 = 0.0625;
/// Band of the rough spheres: q0 = 2π/L, q1 = 32π (π/(2Δx) at n = 64, so every pair from
/// (64, 32) on samples one surface).
const Q1: f64 = 32.0 * PI;
/// Adhesion parameter α* (Eq. 11) of the rough spheres.
const ALPHA_STAR: f64 = 0.4;

/// One body of the study.
#[derive(Clone, Copy, Debug)]
enum Body {
    Smooth,
    Wavy { alpha: f64 },
    Rough { hurst: f64, seed: u64 },
}

impl Body {
    fn label(&self) -> String {
        match *self {
            Body::Smooth => "smooth sphere".into(),
            Body::Wavy { alpha } => format!("wavy sphere α = {alpha}"),
            Body::Rough { hurst, seed } => format!("rough sphere H = {hurst}, seed {seed}"),
        }
    }

    /// The body's heights on an `n × n` grid over L = R = 1.
    fn heights(&self, n: usize) -> Result<Array2<f64>> {
        let grid = Grid::square(n, 1.0 / n as f64, Boundary::Free)?;
        let mut surface = Surface::from_shape(grid, &Sphere::new(1.0)?);
        match *self {
            Body::Smooth => {}
            Body::Wavy { alpha } => {
                let h = tack::analytics::waviness_amplitude_from_alpha(1.0, GAMMA, alpha, LAMBDA);
                surface.add(&Surface::from_shape(grid, &Waviness2d::new(h, LAMBDA)?))?;
            }
            Body::Rough { hurst, seed } => {
                let (q0, q1) = (TAU, Q1);
                let rms = tack::analytics::rms_height_from_alpha_star(
                    1.0, GAMMA, ALPHA_STAR, hurst, q0, q1,
                );
                let spec = RoughSpec {
                    rms,
                    hurst,
                    q0,
                    q1,
                    seed,
                };
                surface.add(&rough_surface(grid, &spec)?)?;
            }
        }
        Ok(surface.into_heights())
    }
}

/// One resolution of one body.
struct Level {
    n: usize,
    ratio: f64,
    seconds: f64,
    steps: usize,
}

/// Runs `body` at every `n` of `levels` (ascending), the same deepest approach for all.
fn study(body: Body, levels: &[usize]) -> Result<Vec<Level>> {
    let d_s = tack::analytics::jkr_approach_scale(1.0, GAMMA, 1.0);
    let finest = body.heights(*levels.last().expect("levels"))?;
    let top = finest.iter().copied().fold(f64::INFINITY, f64::min);
    let mut out = Vec::new();
    for &n in levels {
        let heights = body.heights(n)?;
        let spec = PullOffSpec {
            radius: Some(1.0),
            max_approach: Some(top + LOAD_DEPTH * d_s),
            unload_step: Some(FULL_UNLOAD_STEP * d_s),
            ..PullOffSpec::new(1.0 / n as f64, 1.0, GAMMA)
        };
        let outcome = pull_off(&heights, &spec, &tack::RunOptions::default(), &mut ())?;
        ensure!(
            outcome.path.completed && outcome.path.all_converged(),
            "{} at n = {n}: the path did not complete and converge",
            body.label()
        );
        out.push(Level {
            n,
            ratio: outcome.pull_off_ratio().abs(),
            seconds: outcome.wall_time.as_secs_f64(),
            steps: outcome.path.records.len(),
        });
    }
    Ok(out)
}

/// `cargo xtask convergence [N...]`: the table for levels N (default 64 128 256 512 1024).
pub fn run(args: &[String]) -> Result<()> {
    let mut levels: Vec<usize> = args
        .iter()
        .map(|a| a.parse())
        .collect::<Result<_, _>>()
        .map_err(|e| anyhow::anyhow!("levels must be grid sizes: {e}"))?;
    if levels.is_empty() {
        levels = vec![64, 128, 256, 512, 1024];
    }
    levels.sort_unstable();
    ensure!(levels.len() >= 2, "give at least two levels");
    let mut bodies = vec![
        Body::Smooth,
        Body::Wavy { alpha: 0.5 },
        Body::Wavy { alpha: 1.0 },
    ];
    for hurst in [0.3, 0.7] {
        for seed in 1..=3 {
            bodies.push(Body::Rough { hurst, seed });
        }
    }
    let a_c = tack::analytics::jkr_pull_off_radius(1.0, GAMMA, 1.0);
    println!(
        "pull-off |F/F_JKR| against n (L = R, a_c/Δx = {a_c:.4} n), Richardson 2F(n) − F(n/2), \
         observed order from three levels; the first-order estimate |F(n) − F(n/2)| and tack's \
         estimate max(|F(n) − F(n/2)|, 1.4·(Δx/a_c)·F) against the distance to the finest level"
    );
    let mut json = Vec::new();
    // Over the levels that have a coarser one and are not the finest: (covered by the
    // first-order estimate, covered by tack's, Richardson closer to the finest, cases).
    let mut tally = (0, 0, 0, 0);
    for body in bodies {
        let rows = study(body, &levels)?;
        let finest = rows[rows.len() - 1].ratio;
        println!("\n{}", body.label());
        println!(
            "   {:>5} {:>7} {:>9} {:>11} {:>7} {:>9} {:>9} {:>10} {:>8} {:>6}",
            "n",
            "a_c/Δx",
            "|F/F_JKR|",
            "Richardson",
            "order",
            "|ΔF|",
            "estimate",
            "|F − F_N|",
            "time [s]",
            "steps"
        );
        for (k, r) in rows.iter().enumerate() {
            let coarse = (k > 0).then(|| rows[k - 1].ratio);
            let richardson = coarse.map_or(f64::NAN, |c| richardson_first_order(r.ratio, c));
            let change = coarse.map_or(f64::NAN, |c| (r.ratio - c).abs());
            let estimate = coarse.map_or(f64::NAN, |c| {
                tack::solver::pull_off_error_estimate(r.ratio, c, Some(1.0 / (a_c * r.n as f64)))
            });
            let p = if k > 1 {
                observed_order(rows[k - 2].ratio, rows[k - 1].ratio, r.ratio)
            } else {
                f64::NAN
            };
            let distance = (r.ratio - finest).abs();
            if k > 0 && k + 1 < rows.len() {
                tally.0 += usize::from(distance <= change);
                tally.1 += usize::from(distance <= estimate);
                tally.2 += usize::from((richardson - finest).abs() < distance);
                tally.3 += 1;
            }
            println!(
                "   {:>5} {:>7.1} {:>9.4} {:>11.4} {:>7.2} {:>9.4} {:>9.4} {:>10.4} {:>8.2} {:>6}",
                r.n,
                a_c * r.n as f64,
                r.ratio,
                richardson,
                p,
                change,
                estimate,
                distance,
                r.seconds,
                r.steps
            );
            let num = |x: f64| {
                if x.is_finite() {
                    format!("{x}")
                } else {
                    "null".into()
                }
            };
            json.push(format!(
                "  {{\"body\": \"{}\", \"n\": {}, \"ratio\": {}, \"richardson\": {}, \"order\": {}, \
                 \"change\": {}, \"estimate\": {}, \"distance_to_finest\": {}, \"seconds\": {}, \
                 \"steps\": {}}}",
                body.label(),
                r.n,
                num(r.ratio),
                num(richardson),
                num(p),
                num(change),
                num(estimate),
                num(distance),
                num(r.seconds),
                r.steps
            ));
        }
    }
    let (first, ours, closer, cases) = tally;
    println!(
        "\nagainst the finest level, over {cases} levels between the coarsest and the finest: \
         |ΔF| covered {first}, tack's estimate {ours}; Richardson was closer than F in {closer}"
    );
    std::fs::create_dir_all("results")?;
    tack_io::write_text_atomically(
        "results/convergence.json".as_ref(),
        &format!("[\n{}\n]\n", json.join(",\n")),
    )?;
    println!("\nwrote results/convergence.json");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_body_is_one_surface_at_every_level() {
        // Coarse centre i is fine centre 2i on these even grids (L = 1, origin at n/2).
        for body in [
            Body::Smooth,
            Body::Wavy { alpha: 0.5 },
            Body::Rough {
                hurst: 0.3,
                seed: 2,
            },
        ] {
            let (c, f) = (body.heights(64).unwrap(), body.heights(128).unwrap());
            let worst = c
                .indexed_iter()
                .map(|((i, j), h)| (h - f[[2 * i, 2 * j]]).abs())
                .fold(0.0, f64::max);
            assert!(worst < 1e-15, "{}: {worst:e}", body.label());
        }
    }

    #[test]
    fn a_two_level_study_runs_and_converges() {
        let rows = study(Body::Smooth, &[64, 128]).unwrap();
        // a_c/Δx = 5.1 and 10.2: the criterion overshoots F_JKR, less on the finer grid.
        assert!(rows[0].ratio > rows[1].ratio && rows[1].ratio > 1.0);
    }
}
