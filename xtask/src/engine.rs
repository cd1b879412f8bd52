//! Running the figures' scenes: one helper that builds a tack-cli [`Problem`], crops a free grid
//! to where contact can occur, walks the load–unload path keeping only the fields a figure asks
//! for, and runs batches in parallel (rayon) with a per-process cache and a progress line per
//! finished run.
//!
//! Determinism: every run is sequential; a batch is collected in input order, so the results
//! are bit-identical for any thread count.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;

use anyhow::{Context, Result};
use rayon::prelude::*;
use tack_cli::{Problem, Scene};
use tack_solver::{PathResult, Phase, Snapshot, StepRecord, count_clusters};

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

/// One run: a scene plus what the engine needs beyond it.
#[derive(Debug, Clone)]
pub struct RunSpec {
    /// File stem of the run's result file, unique within a figure.
    pub name: String,
    /// The tack-cli scene (typed and as TOML text, recorded in the result file).
    pub scene: Scene,
    /// Fields to keep.
    pub keep: Keep,
    /// Retraction step used instead of the scene's while the force is still compressive (the
    /// pull-off lies in the tensile part, which always uses the scene's `unload_step`).
    pub coarse_unload: Option<f64>,
}

impl RunSpec {
    /// Identity of the run for the cache: the scene text and the fields kept.
    fn key(&self) -> String {
        format!(
            "{}\n#keep {:?} coarse {:?}",
            self.scene.text, self.keep, self.coarse_unload
        )
    }
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
    /// Steps and kept fields (snapshots are on the crop window).
    pub path: PathResult,
    /// A bonded element reached the border of a cropped window (the crop may have cut contact).
    pub touched_edge: bool,
    /// Wall time of the solve in seconds.
    pub seconds: f64,
    /// The retraction step used while the force was compressive, if not the scene's.
    pub coarse_unload: Option<f64>,
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
    /// Index of the most tensile step.
    pub fn pull_off_step(&self) -> usize {
        let r = &self.path.records;
        (0..r.len())
            .min_by(|&a, &b| r[a].force.total_cmp(&r[b].force))
            .unwrap_or(0)
    }
    /// A kept bonded mask placed on the full grid (snapshots are on the crop window).
    pub fn full_mask(&self, s: &Snapshot) -> ndarray::Array2<bool> {
        match &self.problem.window {
            Some(w) => {
                let mut m = ndarray::Array2::from_elem(self.problem.grid.shape(), false);
                m.slice_mut(ndarray::s![w.i0..w.i1, w.j0..w.j1])
                    .assign(&s.bonded);
                m
            }
            None => s.bonded.clone(),
        }
    }
    /// The kept fields of step `k`, if any.
    pub fn snapshot(&self, k: usize) -> Option<&Snapshot> {
        self.path.snapshots.iter().find(|s| s.step == k)
    }
}

/// Builds the problem (tack-cli: validation, surface, crop window) and walks its path on the
/// crop window.
pub fn run(spec: &RunSpec) -> Result<RunOutput> {
    let started = Instant::now();
    let problem = Problem::from_scene(&spec.scene).with_context(|| format!("run {}", spec.name))?;
    let path = walk(&problem, spec.keep, spec.coarse_unload)?;
    Ok(RunOutput {
        name: spec.name.clone(),
        scene: spec.scene.clone(),
        touched_edge: path.records.iter().any(|r| r.edge_contact),
        problem,
        path,
        seconds: started.elapsed().as_secs_f64(),
        coarse_unload: spec.coarse_unload,
    })
}

/// The load–unload path of `problem` (as `AdhesiveSolver::run_path`, retracting until nothing
/// is bonded), keeping the fields `keep` asks for. Runs on the problem's crop window, if any; the kept fields
/// are on the window.
fn walk(problem: &Problem, keep: Keep, coarse: Option<f64>) -> Result<PathResult> {
    let mut solver = problem.solver(problem.window.as_ref())?;
    let p = problem.path;
    let periodic = problem.grid.boundary() == tack_geometry::Boundary::Periodic;
    let mut out = PathResult::default();
    let mut kept: BTreeMap<usize, Snapshot> = BTreeMap::new();
    let (mut best, mut prev, mut last): (Option<Snapshot>, Option<Snapshot>, Option<Snapshot>) =
        (None, None, None);
    let mut next_every = f64::INFINITY;
    let mut broken = false;
    let mut k = 0usize;
    let mut unloading = false;
    let (mut anchor, mut stride) = (p.max_approach, coarse.unwrap_or(p.unload_step));
    loop {
        if out.records.len() >= p.max_steps {
            break;
        }
        let d = if unloading {
            // Retract from `anchor` in steps of `stride`; switch to the scene's step
            // (re-anchored at the last approach) once the force is no longer compressive.
            if stride != p.unload_step && out.records.last().is_some_and(|r| r.force <= 0.0) {
                (anchor, stride, k) = (
                    out.records.last().map_or(anchor, |r| r.approach),
                    p.unload_step,
                    1,
                );
            }
            anchor - k as f64 * stride
        } else {
            (p.start + k as f64 * p.load_step).min(p.max_approach)
        };
        let rec = solver.step(d)?;
        let step = out.records.len();
        let phase = if unloading {
            Phase::Unload
        } else {
            Phase::Load
        };
        let snap = || Snapshot {
            step,
            pressure: solver.pressure().clone(),
            bonded: solver.bonded().clone(),
        };
        if keep.pull_off
            && best
                .as_ref()
                .is_none_or(|b| rec.force < out.records[b.step].force)
        {
            best = Some(snap());
        }
        if unloading {
            if keep.unload_every.is_some() && d <= next_every {
                kept.insert(step, snap());
                next_every = d - keep.unload_every.unwrap_or(0.0);
            }
            if keep.break_up
                && !broken
                && rec.n_clusters > 1
                && let Some(pr) = prev
                    .take()
                    .filter(|s| count_clusters(&s.bonded, periodic) == 1)
            {
                kept.insert(pr.step, pr);
                kept.insert(step, snap());
                broken = true;
            }
            if keep.last_contact && rec.n_bonded > 0 {
                last = Some(snap());
            }
            if keep.break_up {
                prev = Some(snap());
            }
        }
        out.records.push(rec);
        out.phases.push(phase);
        if unloading && rec.n_bonded == 0 {
            out.completed = true;
            break;
        }
        if !unloading && d >= p.max_approach {
            unloading = true;
            next_every = p.max_approach;
            k = 0;
        }
        k += 1;
    }
    for s in [best, last].into_iter().flatten() {
        kept.insert(s.step, s);
    }
    out.snapshots = kept.into_values().collect();
    Ok(out)
}

/// Runs a batch in parallel, reusing runs already made by this process; prints one line per
/// finished run (`[label k/n] name: ...`). Results come back in the order of `specs`.
pub fn run_all(label: &str, specs: &[RunSpec], cache: &Cache) -> Result<Vec<Arc<RunOutput>>> {
    let done = AtomicUsize::new(0);
    let n = specs.len();
    specs
        .par_iter()
        .map(|spec| {
            let key = spec.key();
            if let Some(hit) = cache.get(&key) {
                let k = done.fetch_add(1, Ordering::Relaxed) + 1;
                println!("  [{label} {k}/{n}] {}: reused", spec.name);
                return Ok(hit);
            }
            let out = Arc::new(run(spec)?);
            let k = done.fetch_add(1, Ordering::Relaxed) + 1;
            println!("  [{label} {k}/{n}] {}", describe(&out));
            cache.put(key, out.clone());
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

/// Runs already made by this process, keyed by scene text and kept fields.
#[derive(Default)]
pub struct Cache(Mutex<HashMap<String, Arc<RunOutput>>>);

impl Cache {
    fn get(&self, key: &str) -> Option<Arc<RunOutput>> {
        self.0.lock().ok()?.get(key).cloned()
    }
    fn put(&self, key: String, value: Arc<RunOutput>) {
        if let Ok(mut m) = self.0.lock() {
            m.insert(key, value);
        }
    }
}

/// Writes one run's result file (tack-io layout, written atomically) to `dir/<name>.h5`, with
/// the snapshots placed on the full grid as `tack run` writes them.
/// Of the kept fields, only the pull-off step, the last contact and the steps in `shown` are
/// written (the others served the figure's selection).
pub fn write_run(dir: &Path, r: &RunOutput, shown: &[usize]) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let mut prov = tack_cli::provenance::provenance(
        &r.scene,
        &r.problem,
        tack_cli::provenance::command_line(),
    );
    if let Some(c) = r.coarse_unload {
        prov.scene += &format!(
            "\n# cargo xtask reproduce: retraction in steps of {c:e} while the force was \
             compressive, then protocol.unload_step\n"
        );
    }
    let last = r.path.records.iter().rposition(|s| s.n_bonded > 0);
    let keep = |k: usize| k == r.pull_off_step() || Some(k) == last || shown.contains(&k);
    let mut path = r.path.clone();
    path.snapshots.retain(|s| keep(s.step));
    let mut result = tack_cli::run::result_file(&r.problem, &path, prov);
    // Snapshots back into the full grid, as `tack run` writes them.
    if let Some(w) = &r.problem.window {
        let block = ndarray::s![w.i0..w.i1, w.j0..w.j1];
        let shape = r.problem.grid.shape();
        for snap in &mut result.snapshots {
            let mut pressure = ndarray::Array2::zeros(shape);
            let mut bonded = ndarray::Array2::from_elem(shape, false);
            pressure.slice_mut(block).assign(&snap.pressure);
            bonded.slice_mut(block).assign(&snap.bonded);
            (snap.pressure, snap.bonded) = (pressure, bonded);
        }
    }
    result.summary.extra.insert("wall_time_s".into(), r.seconds);
    let file = dir.join(format!("{}.h5", r.name));
    tack_io::write_result(&file, &result).with_context(|| format!("writing {}", file.display()))
}
