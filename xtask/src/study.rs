//! `cargo xtask study`: the finite-range studies of `results/study-*.md`: how the loading
//! history moves a rough sphere's pull-off under both adhesion laws, and how much energy a
//! load–retract cycle of a rough sphere dissipates as the roughness grows.

use anyhow::{Result, bail};
use std::fmt::Write as _;
use std::time::Instant;
use tack::problem::Problem;

/// The work of adhesion of [`rough_scene_with`]: a_c ≈ 0.078 R.
const ROUGH_GAMMA: f64 = 1.44868e-4;

/// The rough sphere of the studies: R = 1 on a free L = R grid of `n²`, E* = 1,
/// γ = [`ROUGH_GAMMA`] (a_c ≈ 0.078 R), random roughness of Hurst exponent 0.5 and rms height
/// `h` (0.0052: the speed-bar scene of `cargo xtask bench`), seed `seed` (0: the smooth
/// sphere), the bench's retraction steps (5.5e-4 while compressive, 5.5e-5 once tensile), under
/// the law of the overrides `sets` (none: the zero-range law; [`dugdale_sets`],
/// [`exponential_sets`]).
fn rough_scene_with(n: usize, seed: u64, h: f64, sets: Vec<String>) -> Result<tack::Scene> {
    let gamma = ROUGH_GAMMA;
    // Seed 0: the smooth sphere, the reference of the same law, mesh and path.
    let roughness = if seed == 0 {
        String::new()
    } else {
        format!("[roughness]\nkind = \"random\"\nh = {h}\nhurst = 0.5\nseed = {seed}\n")
    };
    let text = format!(
        "version = 1\n[material]\ne_star = 1.0\ngamma = {gamma}\n[geometry]\nshape = \"sphere\"\n\
         radius = 1.0\n{roughness}[grid]\nn = {n}\ndx = {}\nboundary = \"free\"\n[protocol]\nstart = 0.02255\n\
         max_approach = 0.02255\nload_step = 0.02255\ncoarse_unload_step = 5.5e-4\n\
         unload_step = 5.5e-5\n[output]\nsnapshots = \"none\"\n",
        1.0 / n as f64
    );
    Ok(tack::Scene::parse(&text, ".", &sets)?)
}

/// The `--set` overrides that put a scene of R = E* = 1 and work of adhesion `gamma` under the
/// exponential law at Tabor parameter `mu` (ρ = (Rγ²/(E*²μ³))^(1/3)).
fn exponential_sets(gamma: f64, mu: f64) -> Vec<String> {
    vec![
        format!("{}=\"exponential\"", tack_fields::ADHESION_MODEL),
        format!(
            "{}={}",
            tack_fields::ADHESION_RANGE,
            (gamma * gamma / (mu * mu * mu)).cbrt()
        ),
    ]
}

/// The `--set` overrides that put a scene of R = E* = 1 and work of adhesion `gamma` under the
/// Dugdale law at Maugis parameter `lambda` (σ0 = λ/maugis_lambda(E*, γ, R, 1)); none for
/// `None` (the zero-range law).
pub fn dugdale_sets(gamma: f64, lambda: Option<f64>) -> Vec<String> {
    match lambda {
        None => vec![],
        Some(lambda) => vec![
            format!("{}=\"dugdale\"", tack_fields::ADHESION_MODEL),
            format!(
                "{}={}",
                tack_fields::ADHESION_SIGMA0,
                lambda / tack_analytics::maugis_lambda(1.0, gamma, 1.0, 1.0)
            ),
        ],
    }
}

/// What one run of a study gives.
struct StudyRun {
    /// Pull-off force over F_JKR = −1.5πγR.
    ratio: f64,
    /// Contact area at the deepest approach over πa_c².
    area: f64,
    /// The loop's ∮F dd over πγR·d_s (d_s = (Rγ²/E*²)^(1/3)), when the path is a closed loop.
    dissipated: Option<f64>,
    /// Apparent work of adhesion of the approach and retraction branches (summary extras).
    gamma_approach: Option<f64>,
    gamma_retraction: Option<f64>,
    seconds: f64,
    converged: bool,
}

/// Runs `scene` loading in `load_steps` equal steps to its deepest approach from just out of
/// reach: from the first touch (zero-range law) or from the first touch less the law's reach
/// (`AdhesionLaw::reach`); `load_steps = 1` jumps there in one step from out of reach.
fn run_loaded(scene: &tack::Scene, load_steps: usize) -> Result<StudyRun> {
    let mut problem = Problem::from_scene(scene)?;
    let range = problem.law.reach(problem.gamma).unwrap_or(0.0);
    let reach = problem.first_touch - range;
    let depth = problem.path.max_approach - reach;
    let step = depth / load_steps as f64;
    // The step before the first lies out of reach, so the path is a closed loop.
    problem.path.start = reach - step.min(problem.path.unload_step);
    problem.path.load_step = step;
    if load_steps == 1 {
        problem.path.start = problem.path.max_approach;
        problem.path.load_step = depth;
    }
    problem.path.validate()?;
    let radius = 1.0;
    let (gamma, e_star) = (problem.gamma, problem.e_star);
    let a_c = tack_analytics::jkr_pull_off_radius(e_star, gamma, radius);
    let d_s = tack_analytics::jkr_approach_scale(e_star, gamma, radius);
    let t = Instant::now();
    let out = tack::engine::execute(scene, problem, &tack::RunOptions::default(), &mut ())?;
    let seconds = t.elapsed().as_secs_f64();
    let deepest = out
        .path
        .records
        .iter()
        .max_by(|a, b| a.approach.total_cmp(&b.approach))
        .map_or(0.0, |r| r.area);
    Ok(StudyRun {
        ratio: out.pull_off_ratio(),
        area: deepest / (std::f64::consts::PI * a_c * a_c),
        dissipated: out
            .path
            .cycle()
            .dissipated_energy
            .map(|w| w / (std::f64::consts::PI * gamma * radius * d_s)),
        gamma_approach: out
            .result
            .summary
            .extra
            .get("apparent_gamma_approach")
            .copied(),
        gamma_retraction: out
            .result
            .summary
            .extra
            .get("apparent_gamma_retraction")
            .copied(),
        seconds,
        converged: out.path.completed && out.path.all_converged(),
    })
}

/// Each law of a study, its name and overrides: zero-range, Dugdale at each `--lambdas` λ,
/// exponential at each `--mus` μ.
fn study_laws(opts: &Opts) -> Vec<(String, Vec<String>)> {
    std::iter::once(("zero-range".to_string(), vec![]))
        .chain(opts.lambdas.iter().map(|&l| {
            (
                format!("Dugdale λ = {l}"),
                dugdale_sets(ROUGH_GAMMA, Some(l)),
            )
        }))
        .chain(opts.mus.iter().map(|&m| {
            (
                format!("exponential μ = {m}"),
                exponential_sets(ROUGH_GAMMA, m),
            )
        }))
        .collect()
}

/// `cargo xtask study loading [--seeds N] [--n N] [--lambdas L,L] [--mus M,M] [--steps K,K]`:
/// the rough sphere's |F/F_JKR| against the number of load steps, zero-range, Dugdale and
/// exponential.
fn loading(opts: &Opts) -> Result<String> {
    let mut s = format!(
        "## Loading history: rough sphere (H = 0.5, h = 0.0052, R = L, {n}²)\n\n\
         |F/F_JKR| (contact area at the deepest approach / πa_c²) against the number of equal \
         load steps from out of reach to d = 0.02255; `1` jumps there in one step.\n\n\
         | law | seed | {} |\n|---|---|{}\n",
        opts.steps
            .iter()
            .map(|k| k.to_string())
            .collect::<Vec<_>>()
            .join(" | "),
        "---|".repeat(opts.steps.len()),
        n = opts.n
    );
    let laws = study_laws(opts);
    for (name, sets) in &laws {
        for seed in opts.first_seed..=opts.seeds {
            let scene = rough_scene_with(opts.n, seed, 0.0052, sets.clone())?;
            let label = if seed == 0 {
                "smooth".to_string()
            } else {
                seed.to_string()
            };
            let mut row = format!("| {name} | {label} |");
            for &k in &opts.steps {
                let r = run_loaded(&scene, k)?;
                let flag = if r.converged { "" } else { " (not converged)" };
                write!(row, " {:.3} ({:.2}){flag} |", r.ratio.abs(), r.area)?;
                eprintln!(
                    "{name} seed {seed} steps {k}: |F/F_JKR| = {:.4}, area {:.3}, {:.1} s",
                    r.ratio.abs(),
                    r.area,
                    r.seconds
                );
            }
            s += &row;
            s += "\n";
        }
    }
    Ok(s)
}

/// The dissipation study's load steps by default: about ρ/10 a step under the exponential law
/// at μ = 1 (the step is the depth from out of reach over the count). Where the retraction
/// retraces the approach the loop is the trapezoid rule's error on the approach branch: the
/// smooth sphere at μ = 1, a reversible cycle, read 0.169, 0.057 and 0.013 πγR·d_s for 20, 80
/// and 320 steps, and the Dugdale law's at λ = 1 2.22 and 1.84 for 20 and 320 (20 until
/// 2026-11-30); the zero-range loops of 320 steps are those of 20 to 1%.
const LOOP_LOAD_STEPS: usize = 320;

/// `cargo xtask study dissipation`: the loop's dissipated energy of the rough sphere against α*
/// (H = 0.5, the rms height set by α*) with the apparent work of adhesion of both branches,
/// zero-range, Dugdale (`--lambdas`) and exponential (`--mus`), each loaded in the last of
/// `--steps` equal steps (default [`LOOP_LOAD_STEPS`]); the smooth sphere (seed 0) as the
/// reference. Writes the table and `results/study-dissipation.svg`.
fn dissipation(opts: &Opts) -> Result<String> {
    let (gamma, n) = (1.44868e-4, opts.n);
    let q0 = 2.0 * std::f64::consts::PI;
    let q1 = std::f64::consts::PI * n as f64;
    // The loading study's default step counts are not this study's: [`LOOP_LOAD_STEPS`]
    // unless given.
    let k = if opts.steps_given {
        opts.steps.last().copied().unwrap_or(LOOP_LOAD_STEPS)
    } else {
        LOOP_LOAD_STEPS
    };
    let laws = study_laws(opts);
    let mut s = format!(
        "## Dissipation of a load–retract cycle: rough sphere (H = 0.5, R = L, {n}²)\n\n\
         Loaded in {k} equal steps from out of reach to d = 0.02255 and retracted until \
         detached. W = ∮F dd / (πγR d_s) (d_s = (Rγ²/E*²)^(1/3)), mean over seeds 1–{} with \
         the range; γ_app/γ of the approach and retraction branches (JKR fits, means).\n\n\
         | α* | h | {} |\n|---|---|{}\n",
        opts.seeds,
        laws.iter()
            .map(|(name, _)| format!("{name}: W (range) · γ_app approach/retraction"))
            .collect::<Vec<_>>()
            .join(" | "),
        "---|".repeat(laws.len())
    );
    let alphas = [0.2, 0.3, 0.4, 0.5, 0.7];
    // Per law: (α*, mean W, lo, hi) and the smooth sphere's W.
    let mut curves: Vec<Vec<(f64, f64, f64, f64)>> = vec![Vec::new(); laws.len()];
    let mut smooth = Vec::new();
    for (name, sets) in &laws {
        let r = run_loaded(&rough_scene_with(n, 0, 0.0, sets.clone())?, k)?;
        let flag = if r.converged { "" } else { " (not converged)" };
        eprintln!("smooth {name}: W = {:?}{flag}", r.dissipated);
        smooth.push((r.dissipated.unwrap_or(f64::NAN), flag));
    }
    writeln!(
        s,
        "| smooth | 0 | {} |",
        smooth
            .iter()
            .map(|(w, flag)| format!("{w:.3}{flag}"))
            .collect::<Vec<_>>()
            .join(" | ")
    )?;
    for alpha in alphas {
        let h = tack_analytics::rms_height_from_alpha_star(1.0, gamma, alpha, 0.5, q0, q1);
        let mut row = format!("| {alpha} | {h:.3e} |");
        for (li, (name, sets)) in laws.iter().enumerate() {
            let (mut w, mut ga, mut gr) = (Vec::new(), Vec::new(), Vec::new());
            let mut unconverged = 0usize;
            for seed in 1..=opts.seeds {
                let r = run_loaded(&rough_scene_with(n, seed, h, sets.clone())?, k)?;
                eprintln!(
                    "α* {alpha} {name} seed {seed}: W = {:?}, |F/F_JKR| = {:.3}, γ_app {:?}/{:?}, {:.1} s{}",
                    r.dissipated,
                    r.ratio.abs(),
                    r.gamma_approach,
                    r.gamma_retraction,
                    r.seconds,
                    if r.converged { "" } else { " (not converged)" }
                );
                unconverged += usize::from(!r.converged);
                w.extend(r.dissipated);
                ga.extend(r.gamma_approach.map(|g| g / gamma));
                gr.extend(r.gamma_retraction.map(|g| g / gamma));
            }
            let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
            let (lo, hi) = w
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                });
            write!(
                row,
                " {:.3} ({lo:.3}–{hi:.3}) · {:.2}/{:.2}{} |",
                mean(&w),
                mean(&ga),
                mean(&gr),
                if unconverged > 0 {
                    format!(" ({unconverged} not converged)")
                } else {
                    String::new()
                }
            )?;
            curves[li].push((alpha, mean(&w), lo, hi));
        }
        s += &row;
        s += "\n";
    }
    // W over the smooth sphere's of the same law and mesh: the discretisation's own loop (the
    // lattice trapping of the fronts) largely cancels.
    let series = laws
        .iter()
        .enumerate()
        .map(|(li, (name, _))| {
            let (c, w0) = (&curves[li], smooth[li].0);
            crate::plot::Series::new(
                name.clone(),
                c.iter().map(|p| (p.0, p.1 / w0)).collect(),
                crate::plot::Style::ErrorBars(c.iter().map(|p| 0.5 * (p.3 - p.2) / w0).collect()),
                li,
            )
        })
        .chain(std::iter::once(crate::plot::Series::new(
            "smooth sphere",
            vec![(0.15, 1.0), (0.75, 1.0)],
            crate::plot::Style::Dashed,
            7,
        )))
        .collect();
    let chart = crate::plot::Chart {
        title: format!("Dissipation of a load–retract cycle, rough sphere H = 0.5, {n}²"),
        x_label: "α*".into(),
        y_label: "W / W(smooth sphere), same law and mesh".into(),
        series,
        x_range: Some((0.15, 0.75)),
        // Below 0 for a loop within its sampling of nothing (μ = 2 at α* = 0.2: −0.008); the
        // headroom above the smooth sphere's 1 holds the legend clear of the error bars.
        y_range: Some((-0.05, 1.9)),
    };
    crate::plot::svg(
        std::path::Path::new("results/study-dissipation.svg"),
        (800, 520),
        |area| crate::plot::draw_chart(area, &chart),
    )?;
    Ok(s)
}

/// A smooth sphere R = E* = γ = 1 resolved by `ratio` elements per JKR pull-off radius a_c, on
/// the default pull-off path of its law: zero-range when `lambda` is `None`, else Dugdale at
/// Maugis parameter `lambda`. Returns F/F_JKR and the elements per cohesive zone.
fn smooth_pull_off(ratio: f64, lambda: Option<f64>) -> Result<(f64, Option<f64>, bool)> {
    let a_c = tack_analytics::jkr_pull_off_radius(1.0, 1.0, 1.0);
    let dx = a_c / ratio;
    // Zero-range: one step to d = 3 d_s, the default pull-off path's depth (it bonds a disc of
    // √6 = 1.6 a_c: a contact pinned below a_c would pull off early). Dugdale: in steps from out
    // of range to d = 0.05, where the equilibrium (JKR-like) disc is about 1.25 a_c. A
    // half-width of 3.2 a_c holds either with its zone; retraction in the default rule's steps.
    let n = 2 * (3.2 * ratio).ceil() as usize + 1;
    let unload = 0.2 / ratio;
    let protocol = match lambda {
        None => "start = 3.0\nmax_approach = 3.0\nload_step = 3.0\n".to_string(),
        Some(lambda) => {
            let h0 = tack_analytics::maugis_lambda(1.0, 1.0, 1.0, 1.0) / lambda;
            format!(
                "start = {}\nmax_approach = 0.05\nload_step = {unload}\n",
                -h0 - unload
            )
        }
    };
    let text = format!(
        "version = 1\n[material]\ne_star = 1.0\ngamma = 1.0\n[geometry]\nshape = \"sphere\"\n\
         radius = 1.0\n[grid]\nn = {n}\ndx = {dx}\nboundary = \"free\"\n[protocol]\n{protocol}\
         coarse_unload_step = 0.1\nunload_step = {unload}\n[output]\nsnapshots = \"none\"\n"
    );
    let sets = dugdale_sets(1.0, lambda);
    let scene = tack::Scene::parse(&text, ".", &sets)?;
    let out = tack::run(&scene, &tack::RunOptions::default(), &mut ())?;
    let zone = out
        .result
        .summary
        .extra
        .get("cohesive_zone_elements")
        .copied();
    Ok((
        out.pull_off_ratio(),
        zone,
        out.path.completed && out.path.all_converged(),
    ))
}

/// `cargo xtask study jkr-limit [--lambdas L,..] [--ratios N,..]`: the Dugdale pull-off of a
/// smooth sphere at growing λ beside the zero-range criterion at the same a_c/Δx, each with
/// its first-order Richardson value from the two finest meshes, and Maugis' closed form.
fn jkr_limit(opts: &Opts) -> Result<String> {
    let ratios = &opts.ratios;
    let head: Vec<String> = ratios.iter().map(|r| format!("a_c/Δx = {r}")).collect();
    let mut s = format!(
        "## The JKR limit: smooth sphere, F/F_JKR\n\n\
         Dugdale at Maugis λ (l/Δx: elements per cohesive zone) and the zero-range criterion \
         (κ = 0.4732) at the same meshes; Richardson: 2F(finest) − F(next), first order. \
         F_JKR = −1.5πγR.\n\n| law | {} | Richardson | closed form |\n|---|{}---|---|\n",
        head.join(" | "),
        "---|".repeat(ratios.len())
    );
    // Successive `--ratios` are expected to double (first-order Richardson of the last two).
    let richardson = |f: &[f64]| match f {
        [.., a, b] => tack_solver::richardson_first_order(*b, *a),
        _ => f64::NAN,
    };
    let mut criterion = Vec::new();
    let mut row = String::from("| zero-range criterion |");
    for &r in ratios {
        let (f, _, ok) = smooth_pull_off(r, None)?;
        eprintln!("criterion a_c/Δx = {r}: {f:.5}");
        criterion.push(f);
        write!(row, " {f:.4}{} |", if ok { "" } else { " (not converged)" })?;
    }
    writeln!(row, " {:.4} | 1 (JKR) |", richardson(&criterion))?;
    for &lambda in &opts.lambdas {
        let mut fs = Vec::new();
        write!(s, "| Dugdale λ = {lambda} |")?;
        for &r in ratios {
            let (f, zone, ok) = smooth_pull_off(r, Some(lambda))?;
            eprintln!("λ = {lambda} a_c/Δx = {r}: {f:.5} (l/Δx = {zone:?})");
            fs.push(f);
            write!(
                s,
                " {f:.4} (l/Δx {:.1}){} |",
                zone.unwrap_or(f64::NAN),
                if ok { "" } else { " (not converged)" }
            )?;
        }
        writeln!(
            s,
            " {:.4} | {:.4} (Maugis) |",
            richardson(&fs),
            tack_analytics::maugis_pull_off_hat(lambda) / -1.5
        )?;
    }
    s += &row;
    Ok(s)
}

#[derive(Debug, Clone, PartialEq)]
struct Opts {
    /// Seed 0 is the smooth sphere.
    first_seed: u64,
    /// Whether `--steps`, `--n`, `--seeds` were given.
    steps_given: bool,
    n_given: bool,
    seeds_given: bool,
    ratios: Vec<f64>,
    n: usize,
    seeds: u64,
    lambdas: Vec<f64>,
    /// Tabor parameters of the exponential law (`--mus`; loading and dissipation studies).
    mus: Vec<f64>,
    steps: Vec<usize>,
}

fn list<T: std::str::FromStr>(v: &str) -> Result<Vec<T>>
where
    T::Err: std::error::Error + Send + Sync + 'static,
{
    Ok(v.split(',').map(str::parse).collect::<Result<_, _>>()?)
}

impl Default for Opts {
    fn default() -> Self {
        Self {
            n: 256,
            seeds: 4,
            lambdas: vec![1.0, 2.0, 3.0],
            mus: Vec::new(),
            steps: vec![1, 5, 20, 80],
            ratios: vec![20.0, 40.0, 80.0],
            first_seed: 0,
            steps_given: false,
            n_given: false,
            seeds_given: false,
        }
    }
}

/// `cargo xtask study <loading|dissipation|jkr-limit> [--n N] [--seeds S] [--lambdas L,..] [--steps K,..]`.
pub fn run(args: &[String]) -> Result<()> {
    let mut opts = Opts::default();
    let Some(what) = args.first() else {
        bail!(
            "usage: cargo xtask study <loading|dissipation|jkr-limit|rate> [--n N] [--seeds S] [--lambdas L,..] [--steps K,..]"
        );
    };
    let mut it = args[1..].iter();
    while let Some(flag) = it.next() {
        let Some(value) = it.next() else {
            bail!("{flag} needs a value");
        };
        match flag.as_str() {
            "--n" => (opts.n, opts.n_given) = (value.parse()?, true),
            "--seeds" => (opts.seeds, opts.seeds_given) = (value.parse()?, true),
            "--first-seed" => opts.first_seed = value.parse()?,
            "--lambdas" if value == "none" => opts.lambdas = Vec::new(),
            "--lambdas" => opts.lambdas = list(value)?,
            "--mus" => opts.mus = list(value)?,
            "--steps" => (opts.steps, opts.steps_given) = (list(value)?, true),
            "--ratios" => opts.ratios = list(value)?,
            _ => bail!("unknown option {flag}"),
        }
    }
    std::fs::create_dir_all("results")?;
    let report = match what.as_str() {
        "loading" => loading(&opts)?,
        "dissipation" => dissipation(&opts)?,
        "jkr-limit" => jkr_limit(&opts)?,
        // Its own sizes: the smooth sphere's tables at 96², the rough spheres at 128² (or
        // `--n`), three seeds (or `--seeds`).
        "rate" => crate::study_rate::rate(
            96,
            if opts.n_given { opts.n } else { 128 },
            if opts.seeds_given { opts.seeds } else { 3 },
        )?,
        other => bail!("unknown study `{other}` (loading, dissipation, jkr-limit, rate)"),
    };
    let out = format!("results/study-{what}.md");
    std::fs::write(&out, &report)?;
    println!("{report}\nwritten to {out}");
    Ok(())
}
