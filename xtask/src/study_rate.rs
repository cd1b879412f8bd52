//! `cargo xtask study rate`: rate-dependent adhesion of a standard linear solid (E∞/E0 = 10,
//! τ = 1) under the exponential law: a smooth sphere's pull-off against the retraction speed
//! over five decades, the effect of the hold and of the preload, and rough spheres (H = 0.5,
//! α* = 0.3 and 0.7) at three speeds beside the smooth sphere of the same scene: does the
//! roughness enhancement survive at speed? Writes the tables and `results/study-rate.svg`.

use anyhow::Result;
use std::fmt::Write as _;

/// One path of the study: the body, the law's γ and range, the grid, the path in time.
#[derive(Clone, Copy)]
struct RatePath {
    gamma: f64,
    range: f64,
    /// Grid side and elements per side.
    side: f64,
    n: usize,
    /// Random roughness `(h, seed)` (none: the smooth sphere).
    rough: Option<(f64, u64)>,
    depth: f64,
    load_step: f64,
    unload_step: f64,
    /// Loading and retraction speeds and the hold; `None`: the elastic solid of modulus
    /// `e_star`.
    rates: Option<(f64, f64, f64)>,
    e_star: f64,
}

/// The scene of `p`: a sphere R = 1 loaded from out of the law's reach.
fn scene(p: &RatePath) -> Result<tack::Scene> {
    let prony = if p.rates.is_some() {
        "prony = [[9.0, 1.0]]\n"
    } else {
        ""
    };
    let roughness = p.rough.map_or(String::new(), |(h, seed)| {
        format!("[roughness]\nkind = \"random\"\nh = {h}\nhurst = 0.5\nseed = {seed}\n")
    });
    let rates = p.rates.map_or(String::new(), |(load, unload, dwell)| {
        let hold = if dwell > 0.0 {
            format!("dwell = {dwell}\n")
        } else {
            String::new()
        };
        format!("speed = {load}\nunload_speed = {unload}\n{hold}")
    });
    let reach = 18.4 * p.range + p.rough.map_or(0.0, |(h, _)| 5.0 * h);
    let text = format!(
        "version = 1\n[material]\ne_star = {}\ngamma = {}\n{prony}[adhesion]\n\
         model = \"exponential\"\nrange = {}\n[geometry]\nshape = \"sphere\"\nradius = 1.0\n\
         {roughness}[grid]\nn = {}\ndx = {}\nboundary = \"free\"\n[protocol]\nstart = {}\n\
         max_approach = {}\nload_step = {}\nunload_step = {}\n{rates}[output]\n\
         snapshots = \"none\"\n",
        p.e_star,
        p.gamma,
        p.range,
        p.n,
        p.side / p.n as f64,
        -reach,
        p.depth,
        p.load_step,
        p.unload_step,
    );
    Ok(tack::Scene::parse(&text, ".", &[])?)
}

/// One pull-off of the study: over F_JKR = −1.5πγR, whether every step converged, the wall
/// time, and the contact front's speed at the pull-off.
struct Pull {
    ratio: f64,
    ok: bool,
    secs: f64,
    front_speed: f64,
}

/// The pull-off of `p`.
fn pull_off(p: &RatePath) -> Result<Pull> {
    let t = std::time::Instant::now();
    let out = tack::run(&scene(p)?, &tack::RunOptions::default(), &mut ())?;
    let f_jkr = -1.5 * std::f64::consts::PI * p.gamma;
    Ok(Pull {
        ratio: out.path.pull_off_force() / f_jkr,
        ok: out.path.completed && out.path.all_converged(),
        secs: t.elapsed().as_secs_f64(),
        front_speed: front_speed(&out.path),
    })
}

/// The contact front's speed at the pull-off, `−Δa/Δt` over the pull-off step with the contact
/// radius `a = √(A/π)`; NaN on a path without time or without a step before the pull-off.
fn front_speed(path: &tack::solver::PathResult) -> f64 {
    let Some(k) = path.pull_off_step().filter(|&k| k > 0) else {
        return f64::NAN;
    };
    let (r0, r1) = (&path.records[k - 1], &path.records[k]);
    let radius = |area: f64| (area / std::f64::consts::PI).sqrt();
    match (r0.time, r1.time) {
        (Some(t0), Some(t1)) if t1 > t0 => -(radius(r1.area) - radius(r0.area)) / (t1 - t0),
        _ => f64::NAN,
    }
}

/// The smooth sphere of the example scene (γ = 1e-3, ρ = 0.01: Tabor μ = 1 at E0) on `n²`.
fn smooth(n: usize) -> RatePath {
    RatePath {
        gamma: 1e-3,
        range: 0.01,
        side: 1.2,
        n,
        rough: None,
        depth: 0.02,
        load_step: 0.001,
        unload_step: 0.0005,
        rates: Some((1e-4, 1e-2, 0.0)),
        e_star: 1.0,
    }
}

/// Table A and the figure: the pull-off against the retraction speed (loaded slowly, relaxed),
/// beside the elastic runs at E0 and E∞.
fn speeds(n: usize, s: &mut String) -> Result<()> {
    let base = smooth(n);
    let elastic = |e: f64| {
        pull_off(&RatePath {
            rates: None,
            e_star: e,
            ..base
        })
    };
    let (low, high) = (elastic(1.0)?.ratio, elastic(10.0)?.ratio);
    // Persson–Brener's toughening at the front's speed at pull-off, with their fixed cut-off the
    // exponential law's process zone at E0, times the elastic E0 pull-off: the quasi-static
    // reading F ∝ G(v).
    let law = tack::solver::AdhesionLaw::from(tack::solver::Exponential { range: base.range });
    let cutoff = law.zone_length(1.0, base.gamma).unwrap_or(f64::NAN);
    writeln!(
        s,
        "## A. Smooth sphere, pull-off against the retraction speed ({n}²)\n\n\
         R = 1, γ = 1e-3, exponential law ρ = 0.01 (Tabor μ = 1 at E0, 0.22 at E∞); loaded at \
         1e-4 R/τ (relaxed) to d = 0.02, retracted in steps of 5e-4. Elastic pull-offs on the \
         same grid and steps: {low:.3} F_JKR at E0, {high:.3} at E∞. The apparent work of \
         adhesion of JKR's F = 1.5πγ_app R is γ_app/γ = F/F_JKR. Beside it: the contact \
         front's speed at pull-off (−da/dt over the pull-off step), Persson–Brener's G(v)/G0 at \
         that speed (cut-off a = the process zone (8/3π)E0ρ²/γ = {cutoff:.4}), and the pull-off \
         it predicts if F ∝ G: the elastic E0 pull-off times G(v)/G0.\n\n\
         | retraction speed (R/τ) | F/F_JKR = γ_app/γ | front speed at pull-off | PB G/G0 | \
         PB × E0 pull-off | converged | time |\n|---|---|---|---|---|---|---|"
    )?;
    let mut points = Vec::new();
    let mut pb_points = Vec::new();
    for k in 0..=10 {
        let v = 1e-4 * 10f64.powf(k as f64 / 2.0);
        let pull = pull_off(&RatePath {
            rates: Some((1e-4, v, 0.0)),
            ..base
        })?;
        let pb = tack_analytics::persson_brener_toughening(1.0, 9.0, 1.0, cutoff, pull.front_speed);
        eprintln!(
            "speed {v:.1e}: F/F_JKR = {:.4}, front {:.2e}, PB {pb:.3} ({:.1} s)",
            pull.ratio, pull.front_speed, pull.secs
        );
        writeln!(
            s,
            "| {v:.1e} | {:.3} | {:.2e} | {pb:.3} | {:.3} | {} | {:.1} s |",
            pull.ratio,
            pull.front_speed,
            low * pb,
            pull.ok,
            pull.secs
        )?;
        points.push((v.log10(), pull.ratio));
        if pb.is_finite() {
            pb_points.push((v.log10(), low * pb));
        }
    }
    let line = |y: f64| vec![(-4.2, y), (1.2, y)];
    let series = vec![
        crate::plot::Series::new("viscoelastic", points, crate::plot::Style::Line, 0),
        crate::plot::Series::new(
            "Persson–Brener at the front's speed × E0 pull-off",
            pb_points,
            crate::plot::Style::Dashed,
            3,
        ),
        crate::plot::Series::new("elastic, E0", line(low), crate::plot::Style::Dashed, 1),
        crate::plot::Series::new("elastic, E∞", line(high), crate::plot::Style::Dashed, 2),
    ];
    let chart = crate::plot::Chart {
        title: format!("Pull-off of a sphere on a standard linear solid (E∞/E0 = 10), {n}²"),
        x_label: "log10 retraction speed (R/τ)".into(),
        y_label: "F / F_JKR".into(),
        series,
        x_range: Some((-4.2, 1.2)),
        y_range: Some((0.0, 12.0)),
    };
    crate::plot::svg(
        std::path::Path::new("results/study-rate.svg"),
        (800, 520),
        |area| crate::plot::draw_chart(area, &chart),
    )
}

/// Table B: the hold after a fast load, and the preload.
fn hold_and_preload(n: usize, s: &mut String) -> Result<()> {
    let base = smooth(n);
    writeln!(
        s,
        "\n## B. Hold and preload ({n}²)\n\n\
         Loaded fast (1 R/τ: the load takes 0.02τ), held for the dwell, retracted at 1e-2 R/τ.\n\n\
         | depth | dwell 0 | 0.3τ | 1τ | 3τ | 10τ |\n|---|---|---|---|---|---|"
    )?;
    for depth in [0.01, 0.02, 0.04] {
        let mut row = format!("| {depth} |");
        for dwell in [0.0, 0.3, 1.0, 3.0, 10.0] {
            let Pull {
                ratio, ok, secs, ..
            } = pull_off(&RatePath {
                depth,
                rates: Some((1.0, 1e-2, dwell)),
                ..base
            })?;
            eprintln!("depth {depth}, dwell {dwell}: F/F_JKR = {ratio:.4} ({secs:.1} s)");
            write!(
                row,
                " {ratio:.3}{} |",
                if ok { "" } else { " (not converged)" }
            )?;
        }
        writeln!(s, "{row}")?;
    }
    Ok(())
}

/// Table C: rough spheres (H = 0.5 on an L = R grid of `n²`, γ = 1.44868e-4, ρ = 1.5e-3: Tabor
/// μ = 1.84 at E0) at α* = 0.3 and 0.7, `seeds` seeds, against the smooth sphere of the same
/// scene, at three retraction speeds.
fn rough(n: usize, seeds: u64, s: &mut String) -> Result<()> {
    let gamma = 1.44868e-4;
    let (q0, q1) = (2.0 * std::f64::consts::PI, std::f64::consts::PI * n as f64);
    let base = RatePath {
        gamma,
        range: 1.5e-3,
        side: 1.0,
        n,
        rough: None,
        depth: 0.02255,
        load_step: 0.02255 / 20.0,
        unload_step: 1e-4,
        rates: None,
        e_star: 1.0,
    };
    writeln!(
        s,
        "\n## C. Rough spheres at speed ({n}², H = 0.5, seeds 1–{seeds})\n\n\
         R = L = 1, γ = 1.44868e-4, exponential law ρ = 1.5e-3 (Tabor μ = 1.84 at E0); loaded \
         at 1e-4 R/τ in 20 steps to d = 0.02255, retracted in steps of 1e-4. F/F_JKR of the \
         smooth sphere, and of the rough ones as the mean (range) over seeds, with their ratio \
         to the smooth sphere's.\n\n\
         | retraction speed | smooth | α* = 0.3 | ratio | α* = 0.7 | ratio |\n|---|---|---|---|---|---|"
    )?;
    for v in [1e-4, 1e-2, 1.0] {
        let at = |rough: Option<(f64, u64)>| {
            pull_off(&RatePath {
                rough,
                rates: Some((1e-4, v, 0.0)),
                ..base
            })
        };
        let Pull {
            ratio: smooth,
            secs,
            ..
        } = at(None)?;
        eprintln!("speed {v:.0e}: smooth {smooth:.4} ({secs:.1} s)");
        let mut row = format!("| {v:.0e} | {smooth:.3} |");
        for alpha in [0.3, 0.7] {
            let h = tack_analytics::rms_height_from_alpha_star(1.0, gamma, alpha, 0.5, q0, q1);
            let mut values = Vec::new();
            for seed in 1..=seeds {
                let Pull {
                    ratio, ok, secs, ..
                } = at(Some((h, seed)))?;
                eprintln!("speed {v:.0e} α* {alpha} seed {seed}: {ratio:.4} {ok} ({secs:.1} s)");
                values.push(ratio);
            }
            let mean = values.iter().sum::<f64>() / values.len() as f64;
            let (lo, hi) = values
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                });
            write!(row, " {mean:.3} ({lo:.3}–{hi:.3}) | {:.2} |", mean / smooth)?;
        }
        writeln!(s, "{row}")?;
    }
    Ok(())
}

/// The whole study on `n²` (A, B) and `rough_n²` (C) with `seeds` rough seeds.
pub fn rate(n: usize, rough_n: usize, seeds: u64) -> Result<String> {
    let mut s = String::from(
        "# Rate-dependent adhesion: a standard linear solid (E0 = 1, E∞ = 10, τ = 1)\n\n",
    );
    speeds(n, &mut s)?;
    hold_and_preload(n, &mut s)?;
    rough(rough_n, seeds, &mut s)?;
    Ok(s)
}
