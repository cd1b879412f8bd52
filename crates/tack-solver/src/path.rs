//! Approach paths: load to a maximum approach, then retract until the contact is lost,
//! recording every step and, on request, pressure fields and bonded masks.

use ndarray::Array2;

use crate::{AdhesiveSolver, SolverError, StepRecord};

/// A load–unload path under approach control.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ApproachPath {
    /// First approach of the load phase.
    pub start: f64,
    /// Deepest approach; the load phase ends exactly there.
    pub max_approach: f64,
    /// Approach increment while loading (> 0).
    pub load_step: f64,
    /// Approach decrement while retracting (> 0).
    pub unload_step: f64,
    /// Stop retracting below this approach; `None`: retract until no element is bonded.
    pub retract_to: Option<f64>,
    /// Cap on the total number of steps (a path always terminates).
    pub max_steps: usize,
}

impl ApproachPath {
    /// Checks finiteness and ordering; errors name the `protocol.*` field.
    pub fn validate(&self) -> Result<(), SolverError> {
        let bad = |field, value, allowed| {
            Err(SolverError::OutOfRange {
                field,
                value,
                allowed,
            })
        };
        for (field, v) in [
            ("protocol.start", self.start),
            ("protocol.max_approach", self.max_approach),
        ] {
            if !v.is_finite() {
                return bad(field, v, "a finite number");
            }
        }
        for (field, v) in [
            ("protocol.load_step", self.load_step),
            ("protocol.unload_step", self.unload_step),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return bad(field, v, "a finite number > 0");
            }
        }
        if self.max_approach < self.start {
            return bad(
                "protocol.max_approach",
                self.max_approach,
                "≥ protocol.start",
            );
        }
        if let Some(r) = self.retract_to
            && !(r.is_finite() && r < self.max_approach)
        {
            return bad(
                "protocol.retract_to",
                r,
                "a finite number < protocol.max_approach",
            );
        }
        if self.max_steps == 0 {
            return bad("protocol.max_steps", 0.0, "an integer ≥ 1");
        }
        Ok(())
    }
}

/// Which part of the path a step belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Approach increasing.
    Load,
    /// Approach decreasing (pull-off).
    Unload,
}

/// Progress hooks; the CLI maps them to a progress bar.
pub trait Observer {
    /// Called after every step with its index and record.
    fn on_step(&mut self, _index: usize, _phase: Phase, _record: &StepRecord) {}
}

impl Observer for () {}

/// Which steps keep their pressure field and bonded mask.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub enum SnapshotRequest {
    /// No fields.
    #[default]
    None,
    /// Every step.
    All,
    /// Every k-th step (k ≥ 1), starting with step 0.
    Every(usize),
    /// The listed step indices.
    Steps(Vec<usize>),
}

impl SnapshotRequest {
    fn wants(&self, step: usize) -> bool {
        match self {
            Self::None => false,
            Self::All => true,
            Self::Every(k) => step % (*k).max(1) == 0,
            Self::Steps(s) => s.contains(&step),
        }
    }
}

/// Fields stored at one step.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    /// Step index into [`PathResult::records`].
    pub step: usize,
    /// Element pressures.
    pub pressure: Array2<f64>,
    /// Bonded mask.
    pub bonded: Array2<bool>,
}

/// Everything a path produced.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PathResult {
    /// One record per step, in path order.
    pub records: Vec<StepRecord>,
    /// Phase of each step.
    pub phases: Vec<Phase>,
    /// Requested fields.
    pub snapshots: Vec<Snapshot>,
    /// The path ended as planned (detached or `retract_to` reached), not by `max_steps`.
    pub completed: bool,
}

impl PathResult {
    /// Greatest tensile force: the minimum of the force over the path (negative when adhesive).
    /// Periodic full-contact steps are left out: their force is not fixed by the approach (the
    /// record holds the least admissible one, about −σ_c, a property of the mesh).
    pub fn pull_off_force(&self) -> f64 {
        self.records
            .iter()
            .filter(|r| !r.full_contact)
            .map(|r| r.force)
            .fold(f64::INFINITY, f64::min)
    }
    /// Every step converged.
    pub fn all_converged(&self) -> bool {
        self.records.iter().all(|r| r.converged)
    }
    /// Total CG iterations over the path.
    pub fn cg_iterations(&self) -> usize {
        self.records.iter().map(|r| r.cg_iterations).sum()
    }
}

impl AdhesiveSolver {
    /// Runs `path` from the solver's current state.
    pub fn run_path(
        &mut self,
        path: &ApproachPath,
        snapshots: &SnapshotRequest,
        observer: &mut dyn Observer,
    ) -> Result<PathResult, SolverError> {
        path.validate()?;
        let mut out = PathResult::default();
        let mut k = 0usize;
        loop {
            let d = (path.start + k as f64 * path.load_step).min(path.max_approach);
            self.record_step(d, Phase::Load, snapshots, observer, &mut out)?;
            if d >= path.max_approach || out.records.len() >= path.max_steps {
                break;
            }
            k += 1;
        }
        let mut k = 1usize;
        while out.records.len() < path.max_steps {
            let d = path.max_approach - k as f64 * path.unload_step;
            if path.retract_to.is_some_and(|r| d < r) {
                out.completed = true;
                break;
            }
            let rec = self.record_step(d, Phase::Unload, snapshots, observer, &mut out)?;
            if rec.n_bonded == 0 && path.retract_to.is_none() {
                out.completed = true;
                break;
            }
            k += 1;
        }
        Ok(out)
    }

    fn record_step(
        &mut self,
        d: f64,
        phase: Phase,
        snapshots: &SnapshotRequest,
        observer: &mut dyn Observer,
        out: &mut PathResult,
    ) -> Result<StepRecord, SolverError> {
        let rec = self.step(d)?;
        let index = out.records.len();
        if snapshots.wants(index) {
            out.snapshots.push(Snapshot {
                step: index,
                pressure: self.pressure().clone(),
                bonded: self.bonded().clone(),
            });
        }
        observer.on_step(index, phase, &rec);
        out.records.push(rec);
        out.phases.push(phase);
        Ok(rec)
    }
}
