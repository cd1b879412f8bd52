//! A sphere with seeded random roughness at a chosen adhesion parameter α* (Eq. 11 of Li,
//! Pohrt & Popov 2019), in the setting of the paper's Figure 7 (quick mode of
//! `cargo xtask reproduce`): R = E* = 1, γ such that a_c = 0.08 R, a free grid of side L = R
//! with 128² elements (a_c/Δx = 10), the band q0 = 2π/L, q1 = π/Δx.
//!
//! The rms height h follows from α* through `tack::analytics::rms_height_from_alpha_star`
//! (the inverse of Eq. 11); the surface is generated once with `tack::geometry` to place the
//! load depth 3 (Rγ²/E*²)^(1/3) below its highest point (one load step bonds a compact disc of
//! about 1.6 a_c), and the scene is written as TOML text. A few realizations (seeds) are
//! pulled off and their mean |F/F_JKR| is compared with the fit Λ*(α*) of Eq. 12. Eq. 12
//! describes the rise up to its peak near α* = 0.36; beyond it the simulated force levels off
//! near the smooth sphere's (README, Figure 7).
//!
//!     cargo run --release -p tack --example rough_sphere                # α* = 0.3, H = 0.5
//!     cargo run --release -p tack --example rough_sphere -- 0.2 0.9     # α*, H

use tack::analytics::{
    alpha_star, jkr_approach_scale, jkr_pull_off_radius, lambda_star, rms_height_from_alpha_star,
};
use tack::geometry::{Boundary, Grid, RoughSpec, rough_surface};
use tack::{RunOptions, Scene};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let target: f64 = args.next().map_or(Ok(0.3), |a| a.parse())?;
    let hurst: f64 = args.next().map_or(Ok(0.5), |a| a.parse())?;

    let (e_star, gamma, radius) = (1.0, 1.44868e-4, 1.0);
    let n = 128;
    let grid = Grid::square(n, radius / n as f64, Boundary::Free)?;
    let band = RoughSpec::paper_defaults(grid, 1.0, hurst, 0); // q0 = 2π/L, q1 = π/Δx
    let h = rms_height_from_alpha_star(e_star, gamma, target, hurst, band.q0, band.q1);
    let ds = jkr_approach_scale(e_star, gamma, radius);
    let a_c = jkr_pull_off_radius(e_star, gamma, radius);
    println!(
        "sphere R = {radius}, E* = {e_star}, gamma = {gamma} (a_c = {a_c:.3}), grid {n}^2 of \
         L = R (a_c/dx = {:.1}), H = {hurst}, q0 = {:.3}, q1 = {:.1}",
        a_c / grid.dx(),
        band.q0,
        band.q1
    );
    println!(
        "alpha* = {target} -> rms height h = {h:.5} = {:.2} (R gamma^2/E*^2)^(1/3) \
         (Eq. 11 forward: alpha* = {:.6})",
        h / ds,
        alpha_star(e_star, gamma, h, hurst, band.q0, band.q1)
    );

    let mut ratios = Vec::new();
    for seed in 1..=5_u64 {
        // The same surface the scene will generate: same grid shape, band, seed.
        let rough = rough_surface(
            grid,
            &RoughSpec {
                rms: h,
                seed,
                ..band
            },
        )?;
        let (top, range) = (rough.max(), rough.max() - rough.min());
        let d_max = top + 3.0 * ds;
        let text = format!(
            r#"version = 1

[material]
e_star = {e_star:?}
gamma = {gamma:?}

[geometry]
shape = "sphere"
radius = {radius:?}

[roughness]
kind = "random"
h = {h:?}
hurst = {hurst:?}
seed = {seed}

[grid]
n = {n}
dx = {dx:?}

[protocol]
max_approach = {d_max:?}
load_step = {load:?}              # one step from the first touch to max_approach
unload_step = {unload:?}          # 0.02 (R gamma^2/E*^2)^(1/3)
coarse_unload_step = {coarse:?}   # 0.2 (R gamma^2/E*^2)^(1/3) while still compressive

[output]
surface = false
"#,
            dx = grid.dx(),
            load = d_max + range,
            unload = 0.02 * ds,
            coarse = 0.2 * ds,
        );
        let scene = Scene::parse(&text, ".", &[])?;
        let outcome = tack::run(&scene, &RunOptions::default(), &mut ())?;
        let step = outcome.path.pull_off_step().expect("the path has steps");
        let at_pull_off = &outcome.path.records[step];
        let ratio = outcome.pull_off_ratio().abs();
        println!(
            "  seed {seed}: |F/F_JKR| = {ratio:.3}, {} contact cluster(s) at pull-off, \
             alpha* recorded {:.4}, {} steps in {:.2?}",
            at_pull_off.n_clusters,
            outcome.result.summary.alpha_star.unwrap_or(f64::NAN),
            outcome.path.records.len(),
            outcome.wall_time,
        );
        ratios.push(ratio);
    }
    let k = ratios.len() as f64;
    let mean = ratios.iter().sum::<f64>() / k;
    let std = (ratios.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / (k - 1.0)).sqrt();
    println!(
        "mean |F/F_JKR| = {mean:.3} ± {std:.3} over {} seeds; Eq. 12: Lambda*({target}) = {:.3}",
        ratios.len(),
        lambda_star(target)
    );
    Ok(())
}
