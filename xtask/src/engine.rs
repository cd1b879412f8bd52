//! Running the scenes of the figures that are not sweeps (Figures 1, 2 and 4): one helper that
//! builds a [`Problem`], solves its load–unload path with `tack::run::solve` (on the crop window,
//! coarse retraction included) keeping only the fields a figure asks for (on the full grid),
//! and runs batches in parallel (rayon) with a progress line per finished run. Figures 5–8 run
//! through `tack_sweep` instead (`crate::sweeps`).
//!
//! Determinism: every run is sequential; a batch is collected in input order, so the results
//! are bit-identical for any thread count.

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use anyhow::{Context, Result};
use ndarray::Array2;
use rayon::prelude::*;
use tack::{Problem, Scene};
use tack_solver::{Observer, PathResult, Phase, StepFields, StepRecord, count_clusters};

/// Which pressure fields and bonded masks a run keeps (fields of all other steps are dropped).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Keep {
    /// The step of the most tensile force (the pull-off).
    pub pull_off: bool,
    /// The last step that still has a bonded element.
    pub last_contact: bool,
    /// Unload steps where the bonded set breaks up: the step before and the step where the
    /// number of clusters first exceeds one.
    pub break_up: bool,
    /// Unload steps spaced by at least this approach interval, starting with the first.
    pub unload_every: Option<f64>,
}

/// One run: a scene plus the fields to keep.
#[derive(Debug, Clone)]
pub struct RunSpec {
    /// File stem of the run's result file, unique within a figure.
    pub name: String,
    /// The tack-cli scene (typed and as TOML text, recorded in the result file).
    pub scene: Scene,
    /// Fields to keep.
    pub keep: Keep,
}

/// What a run produced.
#[derive(Debug)]
pub struct RunOutput {
    /// File stem.
    pub name: String,
    /// The scene as run (full grid).
    pub scene: Scene,
    /// The problem (full grid, and the crop window the path ran on).
    pub problem: Problem,
    /// Steps and kept fields (snapshots on the full grid).
    pub path: PathResult,
    /// A bonded element reached the border of a cropped window (the crop may have cut contact).
    pub touched_edge: bool,
    /// Wall time of the solve in seconds.
    pub seconds: f64,
}

impl RunOutput {
    /// Pull-off force over the JKR force (NaN for bodies other than spheres).
    pub fn pull_off_ratio(&self) -> f64 {
        self.path.pull_off_force() / self.problem.references.f_jkr.unwrap_or(f64::NAN)
    }
    /// Steps that hit a solver cap.
    pub fn non_converged(&self) -> usize {
        self.path.records.iter().filter(|r| !r.converged).count()
    }
    /// The unload records with their step indices.
    pub fn unload(&self) -> impl Iterator<Item = (usize, &StepRecord)> {
        self.path
            .records
            .iter()
            .zip(&self.path.phases)
            .enumerate()
            .filter(|(_, (_, p))| **p == Phase::Unload)
            .map(|(k, (r, _))| (k, r))
    }
    /// Index of the pull-off step (`PathResult::pull_off_step`: full-contact steps left out).
    pub fn pull_off_step(&self) -> usize {
        self.path.pull_off_step().unwrap_or(0)
    }
    /// The kept fields of step `k`, if any.
    pub fn snapshot(&self, k: usize) -> Option<&StepFields> {
        self.path.snapshots.iter().find(|s| s.step == k)
    }
}

/// Builds the problem (validation, surface, crop window) and solves its path.
pub fn run(spec: &RunSpec) -> Result<RunOutput> {
    let started = Instant::now();
    let problem = Problem::from_scene(&spec.scene).with_context(|| format!("run {}", spec.name))?;
    let path = walk(&problem, spec.keep)?;
    Ok(RunOutput {
        name: spec.name.clone(),
        scene: spec.scene.clone(),
        touched_edge: path.records.iter().any(|r| r.edge_contact),
        problem,
        path,
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// The load–unload path of `problem` (`tack::run::solve`: on the crop window, again on the
/// full grid should contact reach its edge), keeping the fields `keep` asks for, on the full
/// grid.
fn walk(problem: &Problem, keep: Keep) -> Result<PathResult> {
    let periodic = problem.grid.boundary() == tack_geometry::Boundary::Periodic;
    let mut keeper = Keeper::new(keep, periodic, problem.path.max_approach);
    let mut out = tack::run::solve(problem, &mut keeper)?;
    out.snapshots = keeper.into_snapshots();
    Ok(out)
}

/// Selects the fields of [`Keep`] as the path runs.
struct Keeper {
    keep: Keep,
    periodic: bool,
    kept: BTreeMap<usize, StepFields>,
    /// The least force so far and its fields.
    best: Option<(f64, StepFields)>,
    /// The previous unload step (break-up detection).
    prev: Option<StepFields>,
    /// The latest unload step with a bonded element.
    last: Option<StepFields>,
    /// Approach at or below which the next `unload_every` field is kept.
    next_every: f64,
    /// The path's deepest approach, where `next_every` starts.
    next_every_start: f64,
    broken: bool,
}

impl Keeper {
    fn new(keep: Keep, periodic: bool, max_approach: f64) -> Self {
        Self {
            keep,
            periodic,
            kept: BTreeMap::new(),
            best: None,
            prev: None,
            last: None,
            next_every: max_approach,
            next_every_start: max_approach,
            broken: false,
        }
    }

    /// The kept fields in step order.
    fn into_snapshots(mut self) -> Vec<StepFields> {
        for s in [self.best.map(|b| b.1), self.last].into_iter().flatten() {
            self.kept.insert(s.step, s);
        }
        self.kept.into_values().collect()
    }
}

impl Observer for Keeper {
    fn on_restart(&mut self) {
        *self = Self::new(self.keep, self.periodic, self.next_every_start);
    }

    fn on_fields(
        &mut self,
        step: usize,
        phase: Phase,
        rec: &StepRecord,
        pressure: &Array2<f64>,
        bonded: &Array2<bool>,
    ) {
        let snap = || StepFields {
            step,
            pressure: pressure.clone(),
            bonded: bonded.clone(),
        };
        let keep = self.keep;
        if keep.pull_off && !rec.full_contact && self.best.as_ref().is_none_or(|b| rec.force < b.0)
        {
            self.best = Some((rec.force, snap()));
        }
        if phase != Phase::Unload {
            return;
        }
        if let Some(every) = keep.unload_every
            && rec.approach <= self.next_every
        {
            self.kept.insert(step, snap());
            self.next_every = rec.approach - every;
        }
        if keep.break_up
            && !self.broken
            && rec.n_clusters > 1
            && let Some(pr) = self
                .prev
                .take()
                .filter(|s| count_clusters(&s.bonded, self.periodic) == 1)
        {
            self.kept.insert(pr.step, pr);
            self.kept.insert(step, snap());
            self.broken = true;
        }
        if keep.last_contact && rec.n_bonded > 0 {
            self.last = Some(snap());
        }
        if keep.break_up {
            self.prev = Some(snap());
        }
    }
}

/// Runs a batch in parallel; prints one line per finished run (`[label k/n] name: ...`).
/// Results come back in the order of `specs`.
pub fn run_all(label: &str, specs: &[RunSpec]) -> Result<Vec<Arc<RunOutput>>> {
    let done = AtomicUsize::new(0);
    let n = specs.len();
    specs
        .par_iter()
        .map(|spec| {
            let out = Arc::new(run(spec)?);
            let k = done.fetch_add(1, Ordering::Relaxed) + 1;
            println!("  [{label} {k}/{n}] {}", describe(&out));
            Ok(out)
        })
        .collect()
}

/// One line about a finished run.
fn describe(r: &RunOutput) -> String {
    let (nx, ny) = r.problem.grid.shape();
    let mut s = format!(
        "{}: {} steps on {}, {:.1} s",
        r.name,
        r.path.records.len(),
        match &r.problem.window {
            Some(w) => format!("{}×{} (cropped from {nx}×{ny})", w.shape().0, w.shape().1),
            None => format!("{nx}×{ny}"),
        },
        r.seconds
    );
    let ratio = r.pull_off_ratio();
    if ratio.is_finite() {
        s += &format!(", F_ad/F_JKR = {ratio:.3}");
    }
    if r.non_converged() > 0 {
        s += &format!(", WARNING {} steps did not converge", r.non_converged());
    }
    if r.touched_edge {
        s += ", WARNING contact touched the crop window's edge";
    }
    if !r.path.completed {
        s += ", WARNING path hit its step cap";
    }
    s
}

/// Writes one run's result file (tack-io layout, written atomically) to `dir/<name>.h5`, with
/// the snapshots on the full grid as `tack run` writes them.
/// Of the kept fields, only the pull-off step, the last contact and the steps in `shown` are
/// written (the others served the figure's selection).
pub fn write_run(dir: &Path, r: &RunOutput, shown: &[usize]) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let prov = tack::provenance::provenance(&r.scene, &r.problem, tack::provenance::command_line());
    let last = r.path.records.iter().rposition(|s| s.n_bonded > 0);
    let keep = |k: usize| k == r.pull_off_step() || Some(k) == last || shown.contains(&k);
    let mut path = r.path.clone();
    path.snapshots.retain(|s| keep(s.step));
    // The kept fields are on the full grid already (`tack::run::solve`).
    let mut result = tack::run::result_file(&r.problem, &path, prov);
    result.summary.extra.insert("wall_time_s".into(), r.seconds);
    let file = dir.join(format!("{}.h5", r.name));
    tack_io::write_result(&file, &result).with_context(|| format!("writing {}", file.display()))
}
