//! Running a scene: solve the approach path, assemble the result file (curve, snapshots,
//! surface, summary, provenance), write it atomically and describe the run on one screen.
//!
//! [`run_scene`] is what `tack run` does; the pieces ([`solve`], [`summary`], [`result_file`],
//! [`report`]) are public so other tools (xtask) can run scenes programmatically.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use tack_solver::{Observer, PathResult, Phase, StepRecord};

use crate::problem::Problem;
use crate::provenance;
use crate::scene::{Geometry, Roughness, Scene, SceneError};

/// How [`run_scene`] reports progress and what it records.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Never draw a progress bar (it is drawn only when stderr is a terminal anyway).
    pub quiet: bool,
    /// Command line to record; default: this process's.
    pub command_line: Option<String>,
    /// Also run the scene on a grid of twice the element size and record the Richardson
    /// extrapolation of the pull-off force (see [`coarsened`]).
    pub richardson: bool,
}

/// What a finished run produced.
#[derive(Debug, Clone)]
pub struct RunOutcome {
    /// The validated problem.
    pub problem: Problem,
    /// The path's steps and snapshots.
    pub path: PathResult,
    /// Wall time of the solve (operator construction included).
    pub wall_time: Duration,
    /// The result file as written.
    pub result: tack_io::RunResult,
}

/// Drives a progress spinner from the solver's step hook.
pub struct Progress {
    bar: ProgressBar,
}

impl Progress {
    /// A spinner on stderr, drawn only when stderr is a terminal and `quiet` is false.
    pub fn new(quiet: bool) -> Self {
        let bar = if quiet || !std::io::stderr().is_terminal() {
            ProgressBar::hidden()
        } else {
            let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
            let style =
                ProgressStyle::with_template("{spinner} [{elapsed_precise}] step {pos} {msg}")
                    .unwrap_or_else(|_| ProgressStyle::default_spinner());
            bar.set_style(style);
            bar.enable_steady_tick(Duration::from_millis(120));
            bar
        };
        Self { bar }
    }

    /// Removes the spinner from the terminal.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl Observer for Progress {
    fn on_step(&mut self, _index: usize, phase: Phase, r: &StepRecord) {
        let phase = match phase {
            Phase::Load => "load",
            Phase::Unload => "unload",
        };
        self.bar.set_message(format!(
            "{phase}: d = {}, F = {}, bonded {}{}",
            num(r.approach),
            num(r.force),
            r.n_bonded,
            if r.converged { "" } else { " (not converged)" }
        ));
        self.bar.inc(1);
    }
}

/// Runs the problem's approach path on a fresh solver.
///
/// With a crop window the path runs on the window; snapshots are embedded back into the full
/// grid. Should contact ever reach the window's edge (the crop rule is conservative, so this
/// means a surprise), the path is solved again on the full grid.
pub fn solve(problem: &Problem, observer: &mut dyn Observer) -> Result<PathResult, SceneError> {
    if let Some(w) = &problem.window {
        let mut solver = problem.solver(Some(w))?;
        let mut result = solver.run_path(&problem.path, &problem.snapshots, observer)?;
        if !result.records.iter().any(|r| r.edge_contact) {
            let block = ndarray::s![w.i0..w.i1, w.j0..w.j1];
            for snap in &mut result.snapshots {
                let mut pressure = ndarray::Array2::zeros(problem.grid.shape());
                let mut bonded = ndarray::Array2::from_elem(problem.grid.shape(), false);
                pressure.slice_mut(block).assign(&snap.pressure);
                bonded.slice_mut(block).assign(&snap.bonded);
                (snap.pressure, snap.bonded) = (pressure, bonded);
            }
            return Ok(result);
        }
    }
    let mut solver = problem.solver(None)?;
    Ok(solver.run_path(&problem.path, &problem.snapshots, observer)?)
}

/// The `/summary` of a run: pull-off force (the minimum force), F_JKR and the ratio (NaN for
/// bodies other than spheres, or γ = 0), Johnson's α or α*, and extras (`d_jkr`, `f_kendall`,
/// `sigma_c`, `kappa`, `first_touch`, `non_converged_steps`).
pub fn summary(problem: &Problem, path: &PathResult) -> tack_io::Summary {
    let pull_off = path.pull_off_force();
    let pull_off = if pull_off.is_finite() {
        pull_off
    } else {
        f64::NAN
    };
    let r = &problem.references;
    let f_jkr = r.f_jkr.unwrap_or(f64::NAN);
    let ratio = if f_jkr != 0.0 {
        pull_off / f_jkr
    } else {
        f64::NAN
    };
    let mut extra = std::collections::BTreeMap::new();
    if let Some(d) = r.d_jkr {
        extra.insert("d_jkr".to_owned(), d);
    }
    if let Some(f) = r.f_kendall {
        extra.insert("f_kendall".to_owned(), f);
    }
    if let Some(p) = r.p_star {
        extra.insert("p_star".to_owned(), p);
    }
    let min_mean_pressure = path
        .records
        .iter()
        .map(|r| r.mean_pressure)
        .fold(f64::INFINITY, f64::min);
    if min_mean_pressure.is_finite() {
        extra.insert("min_mean_pressure".to_owned(), min_mean_pressure);
    }
    let sigma_c = (problem.e_star * problem.gamma / (problem.kappa * problem.grid.dx())).sqrt();
    extra.insert("sigma_c".to_owned(), sigma_c);
    extra.insert("kappa".to_owned(), problem.kappa);
    extra.insert("first_touch".to_owned(), problem.first_touch);
    let bad = path.records.iter().filter(|r| !r.converged).count();
    extra.insert("non_converged_steps".to_owned(), bad as f64);
    let edge = path.records.iter().filter(|r| r.edge_contact).count();
    extra.insert("edge_contact_steps".to_owned(), edge as f64);
    if let Some(w) = &problem.window {
        extra.insert("crop_rows".to_owned(), w.shape().0 as f64);
        extra.insert("crop_cols".to_owned(), w.shape().1 as f64);
    }
    tack_io::Summary {
        pull_off_force: pull_off,
        f_jkr,
        pull_off_ratio: ratio,
        johnson_alpha: r.johnson_alpha,
        alpha_star: r.alpha_star,
        extra,
    }
}

/// Names of every scalar [`summary`] can record: the [`tack_io::Summary`] fields, then its
/// `extra` keys. A run need not have all of them (`d_jkr` only for spheres, `crop_rows` only
/// when cropped, ...). Parameter sweeps collect quantities by these names.
pub const SUMMARY_QUANTITIES: [&str; 19] = [
    "pull_off_force",
    "f_jkr",
    "pull_off_ratio",
    "johnson_alpha",
    "alpha_star",
    "d_jkr",
    "f_kendall",
    "p_star",
    "min_mean_pressure",
    "sigma_c",
    "kappa",
    "first_touch",
    "non_converged_steps",
    "edge_contact_steps",
    "crop_rows",
    "crop_cols",
    "pull_off_force_coarse",
    "pull_off_force_richardson",
    "pull_off_ratio_richardson",
];

/// The summary quantity `name` (a field of [`tack_io::Summary`] or a key of its `extra`), NaN
/// when the summary does not have it.
pub fn summary_quantity(summary: &tack_io::Summary, name: &str) -> f64 {
    match name {
        "pull_off_force" => summary.pull_off_force,
        "f_jkr" => summary.f_jkr,
        "pull_off_ratio" => summary.pull_off_ratio,
        "johnson_alpha" => summary.johnson_alpha.unwrap_or(f64::NAN),
        "alpha_star" => summary.alpha_star.unwrap_or(f64::NAN),
        other => summary.extra.get(other).copied().unwrap_or(f64::NAN),
    }
}

/// The curve of a path, one entry per step.
pub fn curve(path: &PathResult) -> tack_io::Curve {
    let r = &path.records;
    tack_io::Curve {
        approach: r.iter().map(|s| s.approach).collect(),
        force: r.iter().map(|s| s.force).collect(),
        area: r.iter().map(|s| s.area).collect(),
        n_bonded: r.iter().map(|s| s.n_bonded as u64).collect(),
        n_clusters: r.iter().map(|s| s.n_clusters as u64).collect(),
        iterations: r.iter().map(|s| s.cg_iterations as u64).collect(),
        active_set_iterations: r.iter().map(|s| s.active_set_iterations as u64).collect(),
        converged: r.iter().map(|s| s.converged).collect(),
        mean_pressure: Some(r.iter().map(|s| s.mean_pressure).collect()),
    }
}

/// Everything the result file holds.
pub fn result_file(
    problem: &Problem,
    path: &PathResult,
    provenance: tack_io::Provenance,
) -> tack_io::RunResult {
    tack_io::RunResult {
        provenance,
        curve: curve(path),
        surface: problem
            .store_surface
            .then(|| (problem.surface.heights().clone(), problem.grid.dx())),
        snapshots: path
            .snapshots
            .iter()
            .map(|s| tack_io::Snapshot {
                step: s.step,
                approach: path.records[s.step].approach,
                pressure: s.pressure.clone(),
                bonded: s.bonded.clone(),
            })
            .collect(),
        summary: summary(problem, path),
    }
}

/// A surface-only result file: provenance, the heights and an empty curve (`tack surface`).
pub fn surface_file(problem: &Problem, provenance: tack_io::Provenance) -> tack_io::RunResult {
    tack_io::RunResult {
        provenance,
        curve: tack_io::Curve {
            mean_pressure: None,
            ..tack_io::Curve::default()
        },
        surface: Some((problem.surface.heights().clone(), problem.grid.dx())),
        snapshots: Vec::new(),
        summary: tack_io::Summary {
            pull_off_force: f64::NAN,
            f_jkr: problem.references.f_jkr.unwrap_or(f64::NAN),
            pull_off_ratio: f64::NAN,
            johnson_alpha: problem.references.johnson_alpha,
            alpha_star: problem.references.alpha_star,
            extra: Default::default(),
        },
    }
}

/// Loads `scene_path` with `overrides`, runs it and writes `out` (atomically).
pub fn run_scene(
    scene_path: &Path,
    overrides: &[String],
    out: &Path,
    options: &RunOptions,
) -> anyhow::Result<(Scene, RunOutcome)> {
    let scene = Scene::load(scene_path, overrides)?;
    check_output_path(out)?;
    let outcome = run_loaded(&scene, out, options)?;
    Ok((scene, outcome))
}

/// Runs an already parsed scene and writes `out` (atomically).
pub fn run_loaded(scene: &Scene, out: &Path, options: &RunOptions) -> anyhow::Result<RunOutcome> {
    let problem = Problem::from_scene(scene)?;
    // The coarse scene is validated before the (long) fine solve.
    let coarse = if options.richardson {
        let c = coarsened(scene, &problem)?;
        Some(Problem::from_scene(&c)?)
    } else {
        None
    };
    let started = Instant::now();
    let mut progress = Progress::new(options.quiet);
    let solved = solve(&problem, &mut progress);
    progress.finish();
    let path = solved?;
    let wall_time = started.elapsed();
    let command_line = options
        .command_line
        .clone()
        .unwrap_or_else(provenance::command_line);
    let prov = provenance::provenance(scene, &problem, command_line);
    let mut result = result_file(&problem, &path, prov);
    if let Some(coarse) = coarse {
        let mut progress = Progress::new(options.quiet);
        let solved = solve(&coarse, &mut progress);
        progress.finish();
        let (fine_f, coarse_f) = (path.pull_off_force(), solved?.pull_off_force());
        let extrapolated = tack_solver::richardson_first_order(fine_f, coarse_f);
        let extra = &mut result.summary.extra;
        extra.insert("pull_off_force_coarse".into(), coarse_f);
        extra.insert("pull_off_force_richardson".into(), extrapolated);
        if let Some(f_jkr) = problem.references.f_jkr {
            extra.insert("pull_off_ratio_richardson".into(), extrapolated / f_jkr);
        }
    }
    tack_io::write_result(out, &result)?;
    Ok(RunOutcome {
        problem,
        path,
        wall_time,
        result,
    })
}

/// The scene on a grid of twice the element size over (at least) the same domain, for the
/// Richardson extrapolation of `tack run --richardson`: the Pohrt–Popov criterion converges at
/// first order in Δx, so `2·F(Δx) − F(2Δx)` cancels the leading error (smooth sphere: +6.9% at
/// a_c/Δx = 20 becomes −0.3%). The geometry must not depend on the grid: random roughness
/// (realization and q1 = π/Δx follow the grid) and height maps are refused, and periodic grids
/// need even sides (the period is kept).
pub fn coarsened(scene: &Scene, problem: &Problem) -> Result<Scene, SceneError> {
    let refuse = |reason: &str| SceneError::Inconsistent(format!("--richardson {reason}"));
    match &scene.file.roughness {
        Some(Roughness::Random { .. }) => {
            return Err(refuse(
                "needs a geometry that does not depend on the grid; roughness.kind = \"random\" \
                 is generated on the grid (its realization and q1 = π/Δx change with Δx)",
            ));
        }
        Some(Roughness::File { .. }) => {
            return Err(refuse(
                "needs a geometry that does not depend on the grid; a height map \
                 (roughness.kind = \"file\") is given per element",
            ));
        }
        _ => {}
    }
    let grid = problem.grid;
    let (nx, ny) = grid.shape();
    let periodic = grid.boundary() == tack_geometry::Boundary::Periodic;
    if periodic && (nx % 2 == 1 || (ny % 2 == 1 && ny > 1)) {
        return Err(refuse(
            "on a periodic grid needs even grid sides (the coarse grid keeps the period)",
        ));
    }
    let half = |n: usize| if n == 1 { 1 } else { n.div_ceil(2) };
    let mut file = scene.file.clone();
    (file.grid.n, file.grid.length) = (None, None);
    file.grid.nx = Some(half(nx));
    file.grid.ny = Some(half(ny));
    file.grid.dx = Some(2.0 * grid.dx());
    let text = toml::to_string(&file).map_err(|e| refuse(&e.to_string()))?;
    Ok(Scene {
        file,
        text: format!("# tack run --richardson: the coarse (2Δx) scene\n{text}"),
        base_dir: scene.base_dir.clone(),
        origin: scene.origin.clone(),
    })
}

/// Fails early (before a long solve) when the output cannot be written: missing parent
/// directory or a directory in the way.
pub fn check_output_path(out: &Path) -> anyhow::Result<()> {
    let parent = match out.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_owned(),
        _ => PathBuf::from("."),
    };
    if !parent.is_dir() {
        anyhow::bail!(
            "{}: parent directory `{}` does not exist",
            out.display(),
            parent.display()
        );
    }
    if out.is_dir() {
        anyhow::bail!("{}: is a directory", out.display());
    }
    Ok(())
}

/// A one-screen account of a run: scene, grid, path, pull-off force against the closed forms,
/// adhesion parameter, convergence and wall time.
pub fn report(scene: &Scene, outcome: &RunOutcome, out: Option<&Path>) -> String {
    let p = &outcome.problem;
    let path = &outcome.path;
    let s = &outcome.result.summary;
    let f = &scene.file;
    let mut lines = Vec::new();
    let origin = scene
        .origin
        .as_ref()
        .map_or_else(|| "(in memory)".to_owned(), |o| o.display().to_string());
    lines.push(format!("scene       {origin}"));
    lines.push(format!(
        "body        {}",
        describe_body(&f.geometry, &f.roughness)
    ));
    lines.push(format!(
        "material    E* = {}, gamma = {}, kappa = {}",
        num(p.e_star),
        num(p.gamma),
        num(p.kappa)
    ));
    let boundary = match p.grid.boundary() {
        tack_geometry::Boundary::Free => "free",
        tack_geometry::Boundary::Periodic => "periodic",
    };
    lines.push(format!(
        "grid        {} x {}, dx = {}, {boundary}{}",
        p.grid.nx(),
        p.grid.ny(),
        p.grid.dx(),
        match (&p.window, p.crop) {
            (Some(w), _) => format!(
                " (cropped to the {} x {} elements that can touch)",
                w.shape().0,
                w.shape().1
            ),
            (None, true) if p.grid.boundary() == tack_geometry::Boundary::Free =>
                " (crop: nothing to remove)".to_owned(),
            _ => String::new(),
        }
    ));
    let loads = path.phases.iter().filter(|&&ph| ph == Phase::Load).count();
    lines.push(format!(
        "path        {} steps ({} load, {} unload), d from {} to {} and back{}",
        path.records.len(),
        loads,
        path.records.len() - loads,
        num(p.path.start),
        num(p.path.max_approach),
        if path.completed {
            ""
        } else {
            "; STOPPED at protocol.max_steps before detachment"
        }
    ));
    let at = path
        .records
        .iter()
        .min_by(|a, b| a.force.total_cmp(&b.force))
        .map_or(f64::NAN, |r| r.approach);
    lines.push(format!(
        "pull-off    F = {} at d = {} (the minimum force)",
        num(s.pull_off_force),
        num(at)
    ));
    if s.f_jkr.is_finite() {
        lines.push(format!(
            "            F_JKR = {}, F/F_JKR = {:.4} (Eq. 7)",
            num(s.f_jkr),
            s.pull_off_ratio
        ));
    }
    if let Some(&fk) = s.extra.get("f_kendall") {
        lines.push(format!(
            "            F_Kendall = {}, F/F_Kendall = {:.4}",
            num(fk),
            s.pull_off_force / fk
        ));
    }
    if let (Some(&fr), Some(&fc)) = (
        s.extra.get("pull_off_force_richardson"),
        s.extra.get("pull_off_force_coarse"),
    ) {
        let ratio = s
            .extra
            .get("pull_off_ratio_richardson")
            .map_or(String::new(), |r| format!(", F/F_JKR = {r:.4}"));
        lines.push(format!(
            "Richardson  F = {} = 2·F(Δx) − F(2Δx), F(2Δx) = {}{ratio}",
            num(fr),
            num(fc)
        ));
    }
    let sphere = matches!(f.geometry, Geometry::Sphere { .. });
    if let (Some(&p_star), Some(&p_min)) = (s.extra.get("p_star"), s.extra.get("min_mean_pressure"))
        && p.grid.boundary() == tack_geometry::Boundary::Periodic
    {
        lines.push(format!(
            "            min mean pressure = {} = {:.4} p* (p* = {}, complete-contact pressure)",
            num(p_min),
            p_min / p_star,
            num(p_star)
        ));
    }
    if let Some(a) = s.johnson_alpha {
        let tail = match (&f.roughness, sphere) {
            (Some(Roughness::Waviness2d { .. }), true) => format!(
                "; Eq. 9 predicts F/F_JKR = {:.3} (fit for lambda/R = 0.05)",
                tack_analytics::lambda_fit(a)
            ),
            (Some(Roughness::Waviness1d { .. }), false) => format!(
                "; 1D critical value {:.4}: {}",
                tack_analytics::JOHNSON_1D_CRITICAL_ALPHA,
                if a > tack_analytics::JOHNSON_1D_CRITICAL_ALPHA {
                    "jumps into full contact at first touch"
                } else {
                    "partial contact is stable"
                }
            ),
            _ => String::new(),
        };
        lines.push(format!("alpha       Johnson alpha = {a:.4} (Eq. 3){tail}"));
    }
    if let Some(a) = s.alpha_star {
        let tail = if sphere {
            format!(
                "; Eq. 12 predicts |F/F_JKR| = {:.3}",
                tack_analytics::lambda_star(a)
            )
        } else {
            String::new()
        };
        lines.push(format!("alpha*      {a:.4} (Eq. 11){tail}"));
    }
    let bad = path.records.iter().filter(|r| !r.converged).count();
    lines.push(format!(
        "converged   {}/{} steps{}",
        path.records.len() - bad,
        path.records.len(),
        if bad > 0 {
            format!(" ({bad} NOT converged)")
        } else {
            String::new()
        }
    ));
    let edge = path.records.iter().filter(|r| r.edge_contact).count();
    if edge > 0 {
        lines.push(format!(
            "WARNING     contact reached the edge of the free grid in {edge} steps: the domain \
             cuts it off; enlarge grid.n or grid.length"
        ));
    }
    lines.push(format!(
        "wall time   {:.2} s ({} CG iterations)",
        outcome.wall_time.as_secs_f64(),
        path.cg_iterations()
    ));
    if let Some(out) = out {
        lines.push(format!("wrote       {}", out.display()));
    }
    lines.join("\n") + "\n"
}

fn describe_body(geometry: &Geometry, roughness: &Option<Roughness>) -> String {
    let shape = match geometry {
        Geometry::Sphere { radius } => format!("sphere R = {radius}"),
        Geometry::FlatPunch {
            radius: Some(r), ..
        } => format!("circular flat punch a = {r}"),
        Geometry::FlatPunch {
            half_side: Some(s), ..
        } => format!("square flat punch half side {s}"),
        Geometry::FlatPunch { .. } => "flat punch".to_owned(),
        Geometry::None => "flat".to_owned(),
    };
    let rough = match roughness {
        None => String::new(),
        Some(Roughness::Waviness1d { h, lambda }) => {
            format!(" + 1D waviness h = {h}, lambda = {lambda}")
        }
        Some(Roughness::Waviness2d { h, lambda }) => {
            format!(" + 2D waviness h = {h}, lambda = {lambda}")
        }
        Some(Roughness::Random { h, hurst, seed, .. }) => {
            format!(" + random roughness rms {h}, H = {hurst}, seed {seed}")
        }
        Some(Roughness::File { path, .. }) => format!(" + height map {}", path.display()),
    };
    shape + &rough
}

/// A number with 6 significant digits, in plain notation for magnitudes in [1e-3, 1e6).
pub fn num(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let mag = x.abs().log10().floor();
    if (-3.0..6.0).contains(&mag) {
        let decimals = (5.0 - mag).max(0.0) as usize;
        let s = format!("{x:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_owned()
        } else {
            s
        }
    } else {
        let s = format!("{x:.5e}");
        match s.split_once('e') {
            Some((mantissa, exp)) if mantissa.contains('.') => format!(
                "{}e{exp}",
                mantissa.trim_end_matches('0').trim_end_matches('.')
            ),
            _ => s,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene(text: &str) -> Scene {
        Scene::parse(text, Path::new("."), &[]).unwrap()
    }

    const SPHERE: &str = r#"
version = 1
[material]
e_star = 1.0
gamma = 0.05
[geometry]
shape = "sphere"
radius = 1.0
[grid]
n = 41
dx = 0.02
[protocol]
max_approach = 0.05
load_step = 0.01
unload_step = 0.002
"#;

    #[test]
    fn richardson_runs_the_scene_at_twice_the_element_size() {
        let fine = scene(SPHERE);
        let problem = Problem::from_scene(&fine).unwrap();
        let coarse = coarsened(&fine, &problem).unwrap();
        let cp = Problem::from_scene(&coarse).unwrap();
        assert_eq!(cp.grid.shape(), (21, 21));
        assert_eq!(cp.grid.dx(), 0.04);
        // Same domain or more: 21 · 0.04 ≥ 41 · 0.02.
        assert!(cp.grid.lx() >= problem.grid.lx());
        // The result file records 2·F(Δx) − F(2Δx).
        let dir = std::env::temp_dir().join(format!("tack-richardson-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("r.h5");
        let options = RunOptions {
            quiet: true,
            command_line: None,
            richardson: true,
        };
        let outcome = run_loaded(&fine, &out, &options).unwrap();
        let e = &outcome.result.summary.extra;
        let (f, c) = (outcome.path.pull_off_force(), e["pull_off_force_coarse"]);
        assert!(f < 0.0 && c < 0.0 && f != c);
        assert_eq!(e["pull_off_force_richardson"], 2.0 * f - c);
        assert!(report(&fine, &outcome, Some(&out)).contains("Richardson"));
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn richardson_refuses_grid_dependent_geometry() {
        let rough = scene(&format!(
            "{SPHERE}[roughness]\nkind = \"random\"\nh = 0.001\nhurst = 0.5\n"
        ));
        let p = Problem::from_scene(&rough).unwrap();
        let err = coarsened(&rough, &p).unwrap_err().to_string();
        assert!(
            err.contains("--richardson") && err.contains("random"),
            "{err}"
        );
        let periodic = scene(&SPHERE.replace("dx = 0.02", "dx = 0.02\nboundary = \"periodic\""));
        let p = Problem::from_scene(&periodic).unwrap();
        let err = coarsened(&periodic, &p).unwrap_err().to_string();
        assert!(err.contains("even"), "{err}");
    }

    #[test]
    fn every_summary_quantity_is_listed() {
        let text = r#"
version = 1
[material]
e_star = 1.0
gamma = 0.125
[geometry]
shape = "sphere"
radius = 8.0
[roughness]
kind = "waviness2d"
h = 0.01
lambda = 3.0
[grid]
n = 48
dx = 0.6
[protocol]
max_approach = 1.0
load_step = 0.25
unload_step = 0.1
"#;
        let scene = Scene::parse(text, ".", &[]).unwrap();
        let problem = Problem::from_scene(&scene).unwrap();
        assert!(problem.window.is_some(), "the test wants a cropped run");
        let path = solve(&problem, &mut ()).unwrap();
        let s = summary(&problem, &path);
        let mut present = vec![
            ("pull_off_force", s.pull_off_force),
            ("f_jkr", s.f_jkr),
            ("pull_off_ratio", s.pull_off_ratio),
            ("johnson_alpha", s.johnson_alpha.unwrap()),
        ];
        present.extend(s.extra.iter().map(|(k, &v)| (k.as_str(), v)));
        assert!(present.len() >= 14, "{present:?}");
        for (name, value) in present {
            assert!(SUMMARY_QUANTITIES.contains(&name), "{name} is not listed");
            assert_eq!(
                summary_quantity(&s, name).to_bits(),
                value.to_bits(),
                "{name}"
            );
        }
        assert!(summary_quantity(&s, "alpha_star").is_nan());
        assert!(summary_quantity(&s, "f_kendall").is_nan());
    }

    #[test]
    fn numbers_have_six_significant_digits() {
        assert_eq!(num(-5.3454057683), "-5.34541");
        assert_eq!(num(0.005), "0.005");
        assert_eq!(num(3.0), "3");
        assert_eq!(num(123456.7), "123457");
        assert_eq!(num(1.5e-7), "1.5e-7");
        assert_eq!(num(5e-4), "5e-4");
        assert_eq!(num(f64::NAN), "NaN");
        assert_eq!(num(0.0), "0");
    }
}
