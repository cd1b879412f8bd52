//! Running the scenes of the figures that are not sweeps (Figures 1, 2 and 4) through the
//! library's run engine (`tack::run`), with a [`Keeper`] observer for the fields a figure asks
//! for beyond the pull-off and last contact (on the full grid), and batches in parallel (rayon)
//! with a progress line per finished run. Figures 5–8 run
//! through `tack_sweep` instead (`crate::sweeps`).
//!
//! Determinism: every run is sequential; a batch is collected in input order, so the results
//! are bit-identical for any thread count.

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

use anyhow::{Context, Result};
use ndarray::Array2;
use rayon::prelude::*;
use tack::scene::Snapshots;
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
pub struct FigureRun {
    /// File stem.
    pub name: String,
    /// The scene as run (full grid).
    pub scene: Scene,
    /// The problem (full grid, and the crop window the path ran on).
    pub problem: Problem,
    /// Steps and kept fields (snapshots on the full grid).
    pub path: PathResult,
    /// The result the run engine assembled (with the kept fields).
    pub result: tack_io::RunResult,
    /// A bonded element reached the border of a cropped window (the crop may have cut contact).
    pub touched_edge: bool,
    /// Wall time of the solve in seconds.
    pub seconds: f64,
}

impl FigureRun {
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

/// Runs the scene through the library's run engine (`tack::run`: validation, the solve on the
/// crop window, the result), keeping the fields of `spec.keep`: the pull-off and last-contact
/// fields by the scene's own `output.snapshots = "pull_off"`, the break-up and periodic unload
/// fields by a [`Keeper`] observer.
pub fn run(spec: &RunSpec) -> Result<FigureRun> {
    let mut scene = spec.scene.clone();
    // The solver's own rule keeps the pull-off step; the Keeper keeps the rest.
    scene.file.output.snapshots = if spec.keep.pull_off {
        Snapshots::PullOff
    } else {
        Snapshots::None
    };
    let periodic = scene.file.grid.boundary == tack::scene::BoundaryKind::Periodic;
    let mut keeper = Keeper::new(spec.keep, periodic);
    // Default options: this process's command line, the batch's pool (`run_all`).
    let mut outcome = tack::run(&scene, &tack::RunOptions::default(), &mut keeper)
        .with_context(|| format!("run {}", spec.name))?;
    let mut kept: BTreeMap<usize, StepFields> = keeper.into_snapshots();
    // Of the solver's "pull_off" snapshots only the pull-off step was asked for (its last
    // contact counts every phase; the Keeper's, as the figures always had it, the unload).
    let pull_off = outcome.path.pull_off_step();
    for s in std::mem::take(&mut outcome.path.snapshots) {
        if Some(s.step) == pull_off {
            kept.insert(s.step, s);
        }
    }
    outcome.replace_snapshots(kept.into_values().collect());
    Ok(FigureRun {
        name: spec.name.clone(),
        scene: spec.scene.clone(),
        touched_edge: outcome.path.records.iter().any(|r| r.edge_contact),
        seconds: outcome.wall_time.as_secs_f64(),
        problem: outcome.problem,
        path: outcome.path,
        result: outcome.result,
    })
}

/// Keeps the fields of [`Keep::last_contact`], [`Keep::break_up`] and [`Keep::unload_every`]
/// as the path runs (the pull-off is the run's own snapshot rule).
struct Keeper {
    keep: Keep,
    periodic: bool,
    kept: BTreeMap<usize, StepFields>,
    /// The previous unload step (break-up detection).
    prev: Option<StepFields>,
    /// The latest unload step with a bonded element.
    last: Option<StepFields>,
    /// Approach at or below which the next `unload_every` field is kept; `None` before the
    /// first unload step.
    next_every: Option<f64>,
    broken: bool,
}

impl Keeper {
    fn new(keep: Keep, periodic: bool) -> Self {
        Self {
            keep,
            periodic,
            kept: BTreeMap::new(),
            prev: None,
            last: None,
            next_every: None,
            broken: false,
        }
    }

    /// The kept fields by step.
    fn into_snapshots(mut self) -> BTreeMap<usize, StepFields> {
        if let Some(last) = self.last.take() {
            self.kept.insert(last.step, last);
        }
        self.kept
    }
}

impl Observer for Keeper {
    fn on_restart(&mut self) {
        *self = Self::new(self.keep, self.periodic);
    }

    fn on_fields(
        &mut self,
        step: usize,
        phase: Phase,
        rec: &StepRecord,
        pressure: &Array2<f64>,
        bonded: &Array2<bool>,
    ) {
        if phase != Phase::Unload {
            return;
        }
        let snap = || StepFields {
            step,
            pressure: pressure.clone(),
            bonded: bonded.clone(),
        };
        let keep = self.keep;
        if let Some(every) = keep.unload_every
            && self.next_every.is_none_or(|next| rec.approach <= next)
        {
            self.kept.insert(step, snap());
            self.next_every = Some(rec.approach - every);
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
pub fn run_all(label: &str, specs: &[RunSpec]) -> Result<Vec<Arc<FigureRun>>> {
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
fn describe(r: &FigureRun) -> String {
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
pub fn write_run(dir: &Path, r: &FigureRun, shown: &[usize]) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let last = r.path.records.iter().rposition(|s| s.n_bonded > 0);
    let keep = |k: usize| k == r.pull_off_step() || Some(k) == last || shown.contains(&k);
    let mut result = r.result.clone();
    result.snapshots.retain(|s| keep(s.step));
    result.summary.extra.insert("wall_time_s".into(), r.seconds);
    let file = dir.join(format!("{}.h5", r.name));
    tack_io::write_result(&file, &result).with_context(|| format!("writing {}", file.display()))
}
