//! The run engine: the one function that turns a validated [`Problem`] into a [`RunOutcome`].
//!
//! [`execute`] owns everything a run does besides building its problem: the rayon pool of
//! [`RunOptions::threads`], the timing, the solve (on the crop window, again on the full grid if
//! contact reaches its edge), the Richardson coarse run, the provenance and the assembly of the
//! result ([`crate::summary::assemble_result`]). Scene runs ([`run`]), runs of height arrays held
//! in memory ([`crate::heights::run`], Python's `tack.pull_off`), sweeps and xtask's figure runs
//! all come through it. Writing the result file is a separate, explicit step
//! ([`RunOutcome::write`]).

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use tack_solver::{Observer, PathResult, Phase, StepFields, StepRecord};

use crate::Error;
use crate::coarse::coarse_problem;
use crate::problem::Problem;
use crate::provenance;
use crate::scene::{Scene, SceneError};
use crate::summary::assemble_result;

/// How [`execute`] runs: threads, the Richardson coarse run, the command line to record.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Command line to record in the provenance; default: this process's.
    pub command_line: Option<String>,
    /// Also run the scene on a grid of twice the element size and record the Richardson
    /// extrapolation of the pull-off force (see [`coarse_problem`]).
    pub richardson: bool,
    /// Threads one solve uses, 1 to [`MAX_THREADS`]: its FFTs are split into lanes across
    /// them, and the result is bit-identical for any count. `None`: the current rayon pool
    /// (all cores unless the caller installed another).
    pub threads: Option<usize>,
}

/// The most threads a run or sweep accepts: far above any machine's cores, below what would
/// exhaust the process's thread limit.
pub const MAX_THREADS: usize = 1024;

/// The one thread-count check (runs, sweeps, the CLI, Python): `n` in `1..=MAX_THREADS`, else
/// an error naming `field`, the value and the range.
pub fn check_threads(field: &str, n: i128) -> Result<usize, Error> {
    match usize::try_from(n) {
        Ok(n) if (1..=MAX_THREADS).contains(&n) => Ok(n),
        _ => Err(Error::Threads(format!(
            "{field} = {n} is invalid: must be an integer from 1 to {MAX_THREADS}"
        ))),
    }
}

/// The rayon pool a solve runs in: `threads` threads; for `None`, the current pool when called
/// from one of its threads (a sweep's worker), else a pool of the global pool's size (all cores,
/// or `RAYON_NUM_THREADS`). A solve runs *inside* its pool so that its parallel FFTs split
/// between pool threads without a hand-off from an outside thread for every transform (that
/// hand-off made two threads slower than one). Refuses counts outside `1..=MAX_THREADS`,
/// naming `field`.
pub fn thread_pool(
    field: &str,
    threads: Option<usize>,
) -> Result<Option<rayon::ThreadPool>, Error> {
    let n = match threads {
        Some(n) => n,
        None if rayon::current_thread_index().is_some() => return Ok(None),
        None => rayon::current_num_threads(),
    };
    check_threads(field, n as i128)?;
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .map(Some)
        .map_err(|e| Error::Threads(format!("{field} = {n}: {e}")))
}

/// What a finished run produced.
#[derive(Debug, Clone)]
pub struct RunOutcome {
    /// The validated problem.
    pub problem: Problem,
    /// The path's steps and snapshots.
    pub path: PathResult,
    /// Wall time of the solve (operator construction included), without the coarse run.
    pub wall_time: Duration,
    /// Wall time of the coarse (2Δx) run of `--richardson`, when there was one.
    pub coarse_wall_time: Option<Duration>,
    /// The result (what [`RunOutcome::write`] writes).
    pub result: tack_io::RunResult,
}

impl RunOutcome {
    /// The pull-off force: the least force over the path (negative when adhesive), NaN when
    /// no step counts (see [`PathResult::pull_off_force`]).
    pub fn pull_off_force(&self) -> f64 {
        self.result.summary.pull_off_force
    }

    /// The pull-off force over the closed-form reference F_JKR of an isolated sphere; NaN
    /// where that reference does not apply.
    pub fn pull_off_ratio(&self) -> f64 {
        self.result.summary.pull_off_ratio
    }

    /// Wall time of the whole run: the solve and the coarse run, if any.
    pub fn total_wall_time(&self) -> Duration {
        self.wall_time + self.coarse_wall_time.unwrap_or_default()
    }

    /// Replaces the kept fields with `snapshots` (on the full grid, in step order), in the path
    /// and in the result: for observers that select fields by rules of their own (xtask's
    /// figures), run with `output.snapshots = "none"`.
    pub fn replace_snapshots(&mut self, snapshots: Vec<StepFields>) {
        self.path.snapshots = snapshots;
        self.result.snapshots = crate::summary::snapshots(&self.path);
    }

    /// Writes the result file atomically (temporary file + rename); refuses an output whose
    /// parent directory is missing or that names a directory.
    pub fn write(&self, out: &Path) -> Result<(), Error> {
        check_output_path(out)?;
        tack_io::write_result(out, &self.result)?;
        Ok(())
    }
}

/// The one run engine: runs `problem` (validated from `scene`, which the provenance records) in
/// the pool of `options.threads`, timed, with progress and cancellation through `observer`;
/// with [`RunOptions::richardson`] also the coarse (2Δx) problem of
/// [`crate::coarse::coarse_problem`], validated before the fine solve. Assembles the result;
/// writes no file.
pub fn execute(
    scene: &Scene,
    problem: Problem,
    options: &RunOptions,
    observer: &mut dyn Observer,
) -> Result<RunOutcome, Error> {
    // The coarse scene and the thread count are checked before the (long) fine solve.
    let coarse = if options.richardson {
        Some(coarse_problem(scene, &problem)?)
    } else {
        None
    };
    let pool = thread_pool("threads", options.threads)?;
    let solve_in_pool = |problem: &Problem, observer: &mut dyn Observer| match &pool {
        Some(pool) => pool.install(|| solve(problem, observer)),
        None => solve(problem, observer),
    };
    let started = Instant::now();
    let path = solve_in_pool(&problem, observer)?;
    let wall_time = started.elapsed();
    let command_line = options
        .command_line
        .clone()
        .unwrap_or_else(provenance::command_line);
    let prov = provenance::provenance(scene, &problem, command_line);
    let mut result = assemble_result(&problem, &path, prov);
    let mut coarse_wall_time = None;
    if let Some(coarse) = coarse {
        let started = Instant::now();
        let coarse_f = solve_in_pool(&coarse, observer)?.pull_off_force();
        coarse_wall_time = Some(started.elapsed());
        let fine_f = path.pull_off_force();
        let extrapolated = tack_solver::richardson_first_order(fine_f, coarse_f);
        let extra = &mut result.summary.extra;
        extra.insert("pull_off_force_coarse".into(), coarse_f);
        extra.insert("pull_off_force_richardson".into(), extrapolated);
        // The sphere's JKR pull-off radius sets the criterion's error floor.
        let dx_over_a_c = match scene.file.geometry {
            crate::scene::Geometry::Sphere { radius } if problem.gamma > 0.0 => Some(
                problem.grid.dx()
                    / tack_analytics::jkr_pull_off_radius(problem.e_star, problem.gamma, radius),
            ),
            _ => None,
        };
        extra.insert(
            "pull_off_error_estimate".into(),
            tack_solver::pull_off_error_estimate(fine_f, coarse_f, dx_over_a_c),
        );
        if let Some(f_jkr) = problem.references.f_jkr {
            extra.insert("pull_off_ratio_richardson".into(), extrapolated / f_jkr);
        }
    }
    Ok(RunOutcome {
        problem,
        path,
        wall_time,
        coarse_wall_time,
        result,
    })
}

/// Runs an already parsed scene in memory: [`Problem::from_scene`], then [`execute`].
pub fn run(
    scene: &Scene,
    options: &RunOptions,
    observer: &mut dyn Observer,
) -> Result<RunOutcome, Error> {
    execute(scene, Problem::from_scene(scene)?, options, observer)
}

/// Loads the scene file `scene_path` with `overrides` (`--set` assignments) and runs it in
/// memory; see [`run`].
pub fn run_file(
    scene_path: &Path,
    overrides: &[String],
    options: &RunOptions,
    observer: &mut dyn Observer,
) -> Result<(Scene, RunOutcome), Error> {
    let scene = Scene::load(scene_path, overrides)?;
    let outcome = run(&scene, options, observer)?;
    Ok((scene, outcome))
}

/// Runs a scene and writes `out` atomically; the output path is checked before the solve.
pub fn run_to_file(
    scene: &Scene,
    out: &Path,
    options: &RunOptions,
    observer: &mut dyn Observer,
) -> Result<RunOutcome, Error> {
    check_output_path(out)?;
    let outcome = run(scene, options, observer)?;
    outcome.write(out)?;
    Ok(outcome)
}

/// Runs the problem's approach path on a fresh solver.
///
/// With a crop window the path runs on the window; snapshots, and the fields the observer
/// sees in [`Observer::on_fields`], are on the full grid either way. Should contact ever reach
/// the window's edge (the crop rule is conservative, so this means a surprise), the observer
/// is told ([`Observer::on_restart`]) and the path is solved again on the full grid.
pub fn solve(problem: &Problem, observer: &mut dyn Observer) -> Result<PathResult, SceneError> {
    if let Some(w) = &problem.window {
        let mut solver = problem.solver(Some(w))?;
        let mut embed = OnFullGrid {
            inner: &mut *observer,
            window: *w,
            shape: problem.grid.shape(),
        };
        let mut result = solver.run_path(&problem.path, &problem.snapshots, &mut embed)?;
        if !result.records.iter().any(|r| r.edge_contact) {
            for snap in &mut result.snapshots {
                (snap.pressure, snap.bonded) = embed.fields(&snap.pressure, &snap.bonded);
            }
            return Ok(result);
        }
        observer.on_restart();
    }
    let mut solver = problem.solver(None)?;
    Ok(solver.run_path(&problem.path, &problem.snapshots, observer)?)
}

/// Passes a cropped run's steps on with their fields placed on the full grid (zero pressure,
/// unbonded outside the window).
struct OnFullGrid<'a> {
    inner: &'a mut dyn Observer,
    window: tack_geometry::Window,
    shape: (usize, usize),
}

impl OnFullGrid<'_> {
    fn fields(
        &self,
        pressure: &ndarray::Array2<f64>,
        bonded: &ndarray::Array2<bool>,
    ) -> (ndarray::Array2<f64>, ndarray::Array2<bool>) {
        let w = &self.window;
        let block = ndarray::s![w.i0..w.i1, w.j0..w.j1];
        let mut full_pressure = ndarray::Array2::zeros(self.shape);
        let mut full_bonded = ndarray::Array2::from_elem(self.shape, false);
        full_pressure.slice_mut(block).assign(pressure);
        full_bonded.slice_mut(block).assign(bonded);
        (full_pressure, full_bonded)
    }
}

impl Observer for OnFullGrid<'_> {
    fn on_step(&mut self, index: usize, phase: Phase, record: &StepRecord) {
        self.inner.on_step(index, phase, record);
    }
    fn on_fields(
        &mut self,
        index: usize,
        phase: Phase,
        record: &StepRecord,
        pressure: &ndarray::Array2<f64>,
        bonded: &ndarray::Array2<bool>,
    ) {
        let (pressure, bonded) = self.fields(pressure, bonded);
        self.inner
            .on_fields(index, phase, record, &pressure, &bonded);
    }
    fn on_restart(&mut self) {
        self.inner.on_restart();
    }
    fn cancelled(&mut self) -> bool {
        self.inner.cancelled()
    }
}
/// Fails early (before a long solve) when the output cannot be written: missing parent
/// directory, or an existing path that is not a regular file (a directory, a FIFO, a device).
pub fn check_output_path(out: &Path) -> Result<(), Error> {
    let parent = match out.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_owned(),
        _ => PathBuf::from("."),
    };
    let refuse = |reason: String| Error::Output {
        path: out.to_owned(),
        reason,
    };
    if !parent.is_dir() {
        return Err(refuse(format!(
            "parent directory `{}` does not exist",
            parent.display()
        )));
    }
    // A FIFO or a device (`/dev/null`) would be replaced by the rename of the result.
    match tack_io::not_a_regular_file(out) {
        Some(kind) => Err(refuse(format!(
            "{kind}: refusing to replace it (name a regular file or a new path)"
        ))),
        None => Ok(()),
    }
}
#[cfg(test)]
mod tests {
    use super::*;
    use crate::summary::{SUMMARY_QUANTITIES, summary, summary_quantity};

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
    fn apparent_work_of_adhesion_per_branch() {
        // Smooth sphere R = E* = γ = 1, a_c/Δx = 21, on the default path of each law.
        let text = "version = 1\n[material]\ne_star = 1.0\ngamma = 1.0\n[geometry]\n\
                    shape = \"sphere\"\nradius = 1.0\n[grid]\nn = 81\ndx = 0.0732\n";
        let zero_range = run(&scene(text), &RunOptions::default(), &mut ()).unwrap();
        let dugdale = run(
            &Scene::parse(
                text,
                Path::new("."),
                &[
                    "adhesion.model=\"dugdale\"".into(),
                    "adhesion.sigma0=0.887".into(),
                ],
            )
            .unwrap(),
            &RunOptions::default(),
            &mut (),
        )
        .unwrap();
        let stepped = run(
            &Scene::parse(
                text,
                Path::new("."),
                &[
                    "protocol.start=-0.05".into(),
                    "protocol.max_approach=3.0".into(),
                    "protocol.load_step=0.05".into(),
                    "protocol.unload_step=0.01".into(),
                ],
            )
            .unwrap(),
            &RunOptions::default(),
            &mut (),
        )
        .unwrap();
        let g = |o: &RunOutcome, key: &str| o.result.summary.extra.get(key).copied();
        // One load step: no approach branch to fit. The retraction fits a γ above the scene's
        // (measured 1.103: the criterion's mesh error, and a curve that is JKR's only near its
        // minimum). Tolerance: [1, 1.2].
        assert_eq!(g(&zero_range, "apparent_gamma_approach"), None);
        let r = g(&zero_range, "apparent_gamma_retraction").unwrap();
        assert!((1.0..1.2).contains(&r), "{r}");
        // Loaded in steps, the zero-range approach is Hertz's (measured γ_app = 0: the fit sits
        // at the bottom of its range), and the retraction from the Hertz contact is not JKR's
        // curve (0.726), though its pull-off is.
        assert_eq!(g(&stepped, "apparent_gamma_approach"), Some(0.0));
        let r = g(&stepped, "apparent_gamma_retraction").unwrap();
        assert!((0.6..0.85).contains(&r), "{r}");
        // Dugdale at λ = 1 (13.7 elements per zone): both branches adhesive (1.004 and 1.170;
        // Maugis' pull-off is 1.067 F_JKR, and +7% the mesh's), the retraction more so.
        let (a, r) = (
            g(&dugdale, "apparent_gamma_approach").unwrap(),
            g(&dugdale, "apparent_gamma_retraction").unwrap(),
        );
        assert!(
            (0.85..1.15).contains(&a) && (1.05..1.3).contains(&r) && r > a,
            "{a} {r}"
        );
    }

    #[test]
    fn richardson_runs_the_scene_at_twice_the_element_size() {
        let fine = scene(SPHERE);
        let problem = Problem::from_scene(&fine).unwrap();
        let cp = coarse_problem(&fine, &problem).unwrap();
        assert_eq!(cp.grid.shape(), (21, 21));
        assert_eq!(cp.grid.dx(), 0.04);
        // Same domain or more: 21 · 0.04 ≥ 41 · 0.02.
        assert!(cp.grid.lx() >= problem.grid.lx());
        // The result file records 2·F(Δx) − F(2Δx).
        let dir = std::env::temp_dir().join(format!("tack-richardson-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let options = RunOptions {
            command_line: None,
            richardson: true,
            threads: None,
        };
        let outcome = run(&fine, &options, &mut ()).unwrap();
        let e = &outcome.result.summary.extra;
        let (f, c) = (outcome.path.pull_off_force(), e["pull_off_force_coarse"]);
        assert!(f < 0.0 && c < 0.0 && f != c);
        assert_eq!(e["pull_off_force_richardson"], 2.0 * f - c);
        assert!(outcome.coarse_wall_time.is_some());
        // Written only on request, and it reads back.
        let out = dir.join("r.h5");
        assert!(!out.exists());
        outcome.write(&out).unwrap();
        let back = tack_io::read_result(&out).unwrap();
        assert_eq!(back.summary.extra["pull_off_force_richardson"], 2.0 * f - c);
        std::fs::remove_dir_all(&dir).ok();
    }

    fn run_with(sets: &[&str]) -> RunOutcome {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let scene = Scene::parse(JKR_EXAMPLE, ".", &sets).unwrap();
        run(&scene, &RunOptions::default(), &mut ()).unwrap()
    }

    const JKR_EXAMPLE: &str = include_str!("../../../data/examples/smooth_jkr_sphere.toml");

    #[test]
    fn a_patterned_sphere_crops_to_the_same_answer() {
        // The γ map is sliced with the crop window: stripes (not symmetric about the window's
        // own centre when the window is off-centre) give the uncropped forces.
        let text = "version = 1\n[material]\ne_star = 1.0\ngamma = 0.02\n[adhesion]\n\
                    pattern = \"stripes\"\ngamma_b = 0.06\nperiod = 0.17\nfraction = 0.3\n\
                    [geometry]\nshape = \"sphere\"\nradius = 1.0\n[grid]\nnx = 140\nny = 131\n\
                    dx = 0.025\n";
        let run_crop = |crop: bool| {
            let sets = vec![format!("grid.crop={crop}")];
            let scene = Scene::parse(text, ".", &sets).unwrap();
            let out = run(&scene, &RunOptions::default(), &mut ()).unwrap();
            (
                out.result.curve.force.clone(),
                out.result.summary.extra.clone(),
            )
        };
        let ((cropped, extra), (full, _)) = (run_crop(true), run_crop(false));
        assert!(
            extra.contains_key("crop_rows"),
            "the window must crop: {extra:?}"
        );
        assert_eq!(cropped.len(), full.len());
        let scale = full.iter().fold(0.0f64, |m, f| m.max(f.abs()));
        for (a, b) in cropped.iter().zip(&full) {
            assert!((a - b).abs() < 1e-8 * scale, "{a} vs {b}");
        }
    }

    #[test]
    fn a_run_says_whether_it_is_complete() {
        let done = run_with(&[]);
        let s = &done.result.summary;
        assert_eq!(s.status.as_deref(), Some(tack_io::Summary::COMPLETE));
        assert!(s.warnings.is_empty(), "{:?}", s.warnings);
        // Stopped before detachment: not complete, and said so.
        let stopped = run_with(&["protocol.max_steps=30"]);
        let s = &stopped.result.summary;
        assert_eq!(
            s.status.as_deref(),
            Some(tack_io::Summary::STOPPED_AT_MAX_STEPS)
        );
        assert!(!s.is_complete());
        assert!(
            s.warnings
                .iter()
                .any(|w| w.contains("protocol.max_steps = 30")),
            "{s:?}"
        );
    }

    #[test]
    fn an_indentation_without_adhesion_says_nothing_of_a_pull_off() {
        // The smooth sphere pressed in once, γ = 0: one step, complete, no warnings.
        let no_path = JKR_EXAMPLE.split("[protocol]").next().unwrap();
        let text = format!("{no_path}[protocol]\nindent = 0.2\n");
        let scene = Scene::parse(&text, ".", &["material.gamma=0".to_owned()]).unwrap();
        let outcome = run(&scene, &RunOptions::default(), &mut ()).unwrap();
        let s = &outcome.result.summary;
        assert_eq!(outcome.path.records.len(), 1);
        assert!(outcome.path.completed);
        assert!(s.is_complete(), "{s:?}");
        assert!(s.warnings.is_empty(), "{:?}", s.warnings);
        assert!(s.pull_off_force.is_nan() && s.pull_off_ratio.is_nan());
        // Hertz: F = (4/3) E* R^(1/2) d^(3/2) = 1.1 for R = 8, d = 0.2, within the mesh error.
        let force = outcome.result.curve.force[0];
        let hertz = 4.0 / 3.0 * 8.0_f64.sqrt() * 0.2_f64.powf(1.5);
        assert!((force / hertz - 1.0).abs() < 0.05, "{force} vs {hertz}");
        // A path stopped by max_steps without adhesion: incomplete, and no pull-off talk.
        let stopped = Scene::parse(
            JKR_EXAMPLE,
            ".",
            &[
                "material.gamma=0".to_owned(),
                "protocol.max_steps=3".to_owned(),
            ],
        )
        .unwrap();
        let outcome = run(&stopped, &RunOptions::default(), &mut ()).unwrap();
        let w = &outcome.result.summary.warnings;
        assert!(
            w.iter().any(|w| w.contains("protocol.max_steps = 3")),
            "{w:?}"
        );
        assert!(w.iter().all(|w| !w.contains("pull-off")), "{w:?}");
    }

    #[test]
    fn periodic_full_contact_is_flagged_in_the_summary() {
        // A 2D waviness pressed beyond its full-contact approach, without adhesion.
        let text = r#"
version = 1
[material]
e_star = 1.0
gamma = 0.0
[geometry]
shape = "none"
[roughness]
kind = "waviness2d"
h = 0.01
lambda = 1.0
[grid]
n = 16
length = 1.0
boundary = "periodic"
[protocol]
max_approach = 0.03
load_step = 0.015
retract_to = 0.0
"#;
        let scene = Scene::parse(text, ".", &[]).unwrap();
        let outcome = run(&scene, &RunOptions::default(), &mut ()).unwrap();
        let s = &outcome.result.summary;
        let full = outcome
            .path
            .records
            .iter()
            .filter(|r| r.full_contact)
            .count();
        assert!(full > 0, "the test wants full contact");
        assert_eq!(s.extra["full_contact_steps"], full as f64);
        assert!(
            s.warnings
                .iter()
                .any(|w| w.starts_with(&format!("full contact in {full} of"))),
            "{:?}",
            s.warnings
        );
        // Partial contact: no such warning.
        let partial = Scene::parse(text, ".", &["protocol.max_approach=0.005".to_owned()]).unwrap();
        let outcome = run(&partial, &RunOptions::default(), &mut ()).unwrap();
        let s = &outcome.result.summary;
        assert_eq!(s.extra["full_contact_steps"], 0.0);
        assert!(s.warnings.iter().all(|w| !w.contains("full contact")));
    }

    #[test]
    fn a_pull_off_the_path_steps_over_is_flagged() {
        // Retracting by 3 (|d_JKR| = 0.39) leaves one tensile step: F/F_JKR came out 0.90.
        let coarse = run_with(&["protocol.unload_step=3"]);
        let w = &coarse.result.summary.warnings;
        assert!(
            w.iter().any(|w| w.contains("pull-off not resolved")),
            "{w:?}"
        );
        let fine = run_with(&["protocol.unload_step=0.1"]);
        assert!(fine.result.summary.warnings.is_empty());
    }

    #[test]
    fn an_under_resolved_pull_off_is_flagged() {
        // a_c = 3.05, Δx = 2: 1.5 elements across the pull-off contact radius.
        let coarse = run_with(&["grid.dx=2", "grid.n=16"]);
        let w = &coarse.result.summary.warnings;
        assert!(
            w.iter().any(|w| w.contains("under-resolved pull-off")),
            "{w:?}"
        );
        // The bound is documented as 5 elements: 3.05/0.6 = 5.1 passes.
        let ok = run_with(&["grid.dx=0.6", "grid.n=24"]);
        assert!(
            ok.result.summary.warnings.is_empty(),
            "{:?}",
            ok.result.summary.warnings
        );
    }

    #[test]
    fn a_sphere_whose_reference_does_not_apply_has_no_ratio() {
        // A periodic cell of 2.4 against 2a_c = 6.1, and a periodic 64 × 1 strip of spheres.
        let small_cell = JKR_EXAMPLE.replace("n = 48", "n = 8\nboundary = \"periodic\"");
        let strip = JKR_EXAMPLE.replace("n = 48", "nx = 64\nny = 1\nboundary = \"periodic\"");
        for text in [small_cell, strip] {
            let text = text.replace("boundary = \"free\"", "");
            let scene = Scene::parse(&text, ".", &[]).unwrap();
            let outcome = run(&scene, &RunOptions::default(), &mut ()).unwrap();
            let s = &outcome.result.summary;
            assert!(
                s.f_jkr.is_nan() && s.pull_off_ratio.is_nan(),
                "{text}: {s:?}"
            );
            let w = &s.warnings;
            assert!(w.iter().any(|w| w.contains("no F_JKR reference")), "{w:?}");
        }
    }

    #[test]
    fn scales_that_overflow_or_underflow_are_refused_naming_the_fields() {
        let refused = |sets: &[&str], field: &str| {
            let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
            let scene = Scene::parse(JKR_EXAMPLE, ".", &sets).unwrap();
            let e = Problem::from_scene(&scene).unwrap_err().to_string();
            assert!(e.contains(field), "{sets:?}: {e}");
        };
        refused(
            &["material.e_star=1.797e308"],
            "material.e_star = 1.797e308",
        );
        refused(&["material.e_star=5e-324"], "material.e_star = 5e-324");
        refused(&["grid.dx=1e300"], "grid.dx = 1e300");
        // Every length 1e-160 of its value: Δx² = 9e-322 is subnormal.
        refused(
            &[
                "grid.dx=3e-161",
                "geometry.radius=8e-160",
                "protocol.max_approach=3e-160",
                "protocol.load_step=1.5e-161",
                "protocol.unload_step=5e-163",
            ],
            "grid.dx = 3e-161",
        );
    }

    #[test]
    fn richardson_takes_band_limited_roughness_and_maps_as_the_same_body() {
        // 40 × 40 elements of 0.02: the coarse grid's Nyquist wave is π/(2Δx) = 25π ≈ 78.54,
        // and coarse centre (i, j) is fine centre (2i, 2j).
        let sphere = SPHERE.replace("n = 41", "n = 40");
        let same_body = |fine: &Problem, coarse: &Problem| {
            assert_eq!(coarse.grid.shape(), (20, 20));
            let (f, c) = (fine.surface.heights(), coarse.surface.heights());
            let worst = c
                .indexed_iter()
                .map(|((i, j), h)| (h - f[[2 * i, 2 * j]]).abs())
                .fold(0.0, f64::max);
            assert!(worst < 1e-15, "largest difference {worst:e}");
        };
        let random = |q1: &str| {
            scene(&format!(
                "{sphere}[roughness]\nkind = \"random\"\nh = 0.001\nhurst = 0.5\n{q1}seed = 3\n"
            ))
        };
        let rough = random("q1 = 78.5\n");
        let fine = Problem::from_scene(&rough).unwrap();
        same_body(&fine, &coarse_problem(&rough, &fine).unwrap());
        let above = random("q1 = 80.0\n");
        let err = coarse_problem(&above, &Problem::from_scene(&above).unwrap())
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("roughness.q1 = 80 is above π/(2Δx) = 78.53"),
            "{err}"
        );

        // The same roughness as a text map, on the same sphere.
        let dir = std::env::temp_dir().join(format!("tack-richardson-map-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let smooth = Problem::from_scene(&scene(&sphere)).unwrap();
        let rough_only = fine.surface.heights() - smooth.surface.heights();
        let write_map = |name: &str, heights: &ndarray::Array2<f64>| {
            let mut text = String::from("# dx = 0.02\n");
            for row in heights.rows() {
                let cells: Vec<String> = row.iter().map(|h| format!("{h:e}")).collect();
                text.push_str(&cells.join(","));
                text.push('\n');
            }
            std::fs::write(dir.join(name), text).unwrap();
        };
        write_map("band.txt", &rough_only);
        let mapped = |name: &str| {
            Scene::parse(
                &format!("{sphere}[roughness]\nkind = \"file\"\npath = \"{name}\"\n"),
                &dir,
                &[],
            )
            .unwrap()
        };
        let map_scene = mapped("band.txt");
        let fine = Problem::from_scene(&map_scene).unwrap();
        same_body(&fine, &coarse_problem(&map_scene, &fine).unwrap());
        let outcome = run(
            &map_scene,
            &RunOptions {
                command_line: None,
                richardson: true,
                threads: None,
            },
            &mut (),
        )
        .unwrap();
        let e = &outcome.result.summary.extra;
        let (f, c) = (outcome.path.pull_off_force(), e["pull_off_force_coarse"]);
        // The larger of the change between the levels and the criterion's floor 1.4·Δx/a_c.
        let a_c = tack_analytics::jkr_pull_off_radius(1.0, 0.05, 1.0);
        let floor = 1.4 * (0.02 / a_c) * f.abs();
        assert_eq!(e["pull_off_error_estimate"], (f - c).abs().max(floor));
        assert!(f < 0.0 && c < 0.0 && f != c);

        // Content above the coarse Nyquist wave: a wave at the fine grid's Nyquist.
        let mut spiky = rough_only.clone();
        for ((i, _), h) in spiky.indexed_iter_mut() {
            *h += if i % 2 == 0 { 1e-4 } else { -1e-4 };
        }
        write_map("spiky.txt", &spiky);
        let spiky_scene = mapped("spiky.txt");
        let err = coarse_problem(&spiky_scene, &Problem::from_scene(&spiky_scene).unwrap())
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("roughness.path = `spiky.txt`")
                && err.contains("not band-limited")
                && err.contains("π/(2Δx)"),
            "{err}"
        );
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn richardson_refuses_grid_dependent_geometry() {
        let rough = scene(&format!(
            "{SPHERE}[roughness]\nkind = \"random\"\nh = 0.001\nhurst = 0.5\n"
        ));
        let p = Problem::from_scene(&rough).unwrap();
        let err = coarse_problem(&rough, &p).unwrap_err().to_string();
        assert!(
            err.contains("--richardson") && err.contains("random") && err.contains("roughness.q1"),
            "{err}"
        );
        let periodic = scene(&SPHERE.replace("dx = 0.02", "dx = 0.02\nboundary = \"periodic\""));
        let p = Problem::from_scene(&periodic).unwrap();
        let err = coarse_problem(&periodic, &p).unwrap_err().to_string();
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
}
