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
        // The pull-off contact radius (a sphere's a_c, a punch's a, …) sets the zero-range
        // criterion's error floor; a finite-range law has none of its own.
        let dx_over_a_c = problem
            .references
            .pull_off_radius
            .filter(|_| matches!(problem.law, tack_solver::AdhesionLaw::JkrLimit(_)))
            .map(|a| problem.grid.dx() / a);
        let forces = (path.pull_off_force(), coarse_f);
        insert_richardson(&mut result.summary, &problem, forces, dx_over_a_c);
    }
    Ok(RunOutcome {
        problem,
        path,
        wall_time,
        coarse_wall_time,
        result,
    })
}

/// The summary entries of a Richardson extrapolation of `problem`'s pull-off from the
/// `(fine, coarse)` forces at Δx and 2Δx: `richardson_order` (the law's: first for the
/// criterion and the Dugdale law, second for the smooth laws, where a first-order rule would
/// overshoot by twice the fine error), `pull_off_force_coarse`, `pull_off_force_richardson`,
/// `pull_off_error_estimate` (with the criterion's floor when `dx_over_a_c` is given) and,
/// where F_JKR applies, `pull_off_ratio_richardson`; and [`richardson_warning`] where the
/// law has one. Shared by `--richardson` and [`crate::heights_richardson`].
pub(crate) fn insert_richardson(
    summary: &mut tack_io::Summary,
    problem: &Problem,
    (fine, coarse): (f64, f64),
    dx_over_a_c: Option<f64>,
) {
    summary.warnings.extend(richardson_warning(&problem.law));
    let extra = &mut summary.extra;
    let order = problem.law.convergence_order();
    let extrapolated = tack_solver::richardson(fine, coarse, order);
    extra.insert("richardson_order".into(), order);
    extra.insert("pull_off_force_coarse".into(), coarse);
    extra.insert("pull_off_force_richardson".into(), extrapolated);
    extra.insert(
        "pull_off_error_estimate".into(),
        tack_solver::pull_off_error_estimate(fine, coarse, dx_over_a_c),
    );
    if let Some(f_jkr) = problem.references.f_jkr {
        extra.insert("pull_off_ratio_richardson".into(), extrapolated / f_jkr);
    }
}

/// The warning of a Richardson pair under a law bound to the mesh (the smoothed Dugdale law):
/// its two runs solve two laws, so the first-order rule is no error estimate (its measured
/// orders are irregular, 0.04 to 2.2: docs/theory.md §3.7).
pub(crate) fn richardson_warning(law: &tack_solver::AdhesionLaw) -> Option<String> {
    matches!(law, tack_solver::AdhesionLaw::SmoothedDugdale(_)).then(|| {
        "richardson: the smoothed Dugdale law's ramp is bound to the grid, so the fine and \
         coarse runs solve two laws and its error has no regular order (measured 0.04 to 2.2, \
         docs/theory.md §3.7): the extrapolated pull-off and its error estimate do not hold; \
         compare the run with f_maugis or refine the grid instead"
            .to_owned()
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
/// sees in [`Observer::on_fields`], are on the full grid either way, and so is every record's
/// mean pressure (the force over the full grid's area, as without the crop). Should contact ever reach
/// the window's edge (the crop rule is conservative, so this means a surprise), the observer
/// is told ([`Observer::on_restart`]) and the path is solved again on the full grid.
pub fn solve(problem: &Problem, observer: &mut dyn Observer) -> Result<PathResult, SceneError> {
    if let Some(w) = &problem.window {
        let mut solver = problem.solver(Some(w))?;
        let mut embed = OnFullGrid {
            inner: &mut *observer,
            window: *w,
            shape: problem.grid.shape(),
            area: problem.grid.lx() * problem.grid.ly(),
        };
        let mut result = solver.run_path(&problem.path, &problem.snapshots, &mut embed)?;
        if !result.records.iter().any(|r| r.edge_contact) {
            for r in &mut result.records {
                *r = embed.record(r);
            }
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
    /// The full grid's area `Lx·Ly`.
    area: f64,
}

impl OnFullGrid<'_> {
    /// A cropped run's record with the mean pressure of the full grid (the solver divides the
    /// force by the window's area).
    fn record(&self, r: &StepRecord) -> StepRecord {
        StepRecord {
            mean_pressure: r.force / self.area,
            ..*r
        }
    }

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
        let record = self.record(record);
        self.inner.on_step(index, phase, &record);
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
        let record = self.record(record);
        self.inner
            .on_fields(index, phase, &record, &pressure, &bonded);
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
mod tests;
