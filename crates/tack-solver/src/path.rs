//! Approach paths: load to a maximum approach, then retract until the contact is lost
//! (optionally in coarse steps while the force is still compressive), recording every step and,
//! on request, pressure fields and bonded masks.

use ndarray::Array2;
use tack_fields::{self as fields, field_name};

use crate::{AdhesiveSolver, SolverError, SolverState, StepRecord, validate};

/// How many of the largest tensions released in one fine step (`J`) a coarse step's force may
/// lie above the least force and still have its bracket retraced under
/// [`ApproachPath::refine_pull_off`]: a saw-tooth may hide a tooth deeper than any released
/// before. At 1, one of 90 of Figure 7's full points (H = 0.1, α* = 0.1, seed 8) kept a
/// pull-off 13% short (its deepest tooth lay 1.09 J below the coarse steps around it); at 2 all
/// 90 meet the fine path's pull-off within 5.4e-9, in 21 686 steps against 19 248 at 1 and
/// 33 074 fine (`crates/tack/tests/refine.rs`).
pub const RELEASE_MARGIN: f64 = 2.0;

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
    /// Approach decrement used instead of `unload_step` while the force is still compressive
    /// (> 0); `None`: `unload_step` throughout. The retraction steps back from `max_approach` by
    /// this step; once a step's force is ≤ 0 the path re-anchors at that step's approach `d₀`
    /// and continues at `d₀ − k·unload_step`, k = 1, 2, … (the pull-off lies in the tensile
    /// part). A coarse step that jumps over the whole tensile part misses the pull-off. Under a
    /// smooth law, once a step leaves nothing touching the wall, every gap past the law's
    /// peak ([`crate::AdhesionLaw::peak_gap`]: a Lennard-Jones front peels with nothing on its
    /// wall) and its tension below the step before's (past the pull-off), the path re-anchors
    /// there and steps by the law's length ρ/50, within `unload_step` … `coarse_unload_step`
    /// ([`ApproachPath::tail_step`]): the rest follows the law alone, and fine steps there took
    /// most of a long range's run. Not on a refined retraction, nor on a viscoelastic solid,
    /// whose steps are its time steps.
    pub coarse_unload_step: Option<f64>,
    /// Refined retraction (needs `coarse_unload_step`): coarse steps throughout the retraction,
    /// and every coarse bracket that may hold the pull-off retraced in steps of `unload_step`
    /// from the solver state saved at its start. Every approach is `max_approach −
    /// n·unload_step` for a whole `n` (the coarse step is rounded to a whole number of unload
    /// steps, at least one: below 1.5 unload steps every step is fine and nothing is retraced),
    /// so a retraced stretch solves exactly the fine path's approaches.
    ///
    /// A bracket is the two coarse steps around step `i` when either
    /// - `F_i` is a local minimum of the force (`F_i < F_{i−1}`, `F_i ≤ F_{i+1}`, `F_i < 0`; a
    ///   lost contact counts as `F = 0`) within one coarse change `F_{i−1} − F_i` of the least
    ///   force kept so far, or
    /// - one of the three forces is within [`RELEASE_MARGIN`]`·J` of the least, `J` the largest
    ///   tension released in one fine step of the stretches retraced so far: a saw-tooth curve
    ///   (a front that sticks, then jumps; coarse meshes, rough bodies) may hide a peak that
    ///   deep between coarse steps, and a later tooth may be deeper than any seen before.
    ///
    /// The coarse step in which the contact is lost is retraced when the tension was still
    /// growing before it or is near the least (else the jump-out is located only to the coarse
    /// step). The retraced steps replace the coarse ones: the records stay in path order, and
    /// observers see only kept steps. `false`: as described at `coarse_unload_step`.
    pub refine_pull_off: bool,
    /// Stop retracting below this approach; `None`: retract until no element is bonded.
    pub retract_to: Option<f64>,
    /// Cap on the total number of steps (a path always terminates).
    pub max_steps: usize,
}

impl ApproachPath {
    /// Step cap of the constructors: far more than any sensible path needs, so that only a
    /// path that does not end (a retraction that never loses contact) stops there.
    pub const DEFAULT_MAX_STEPS: usize = 100_000;

    /// Load from `start` to `max_approach` in steps of `load_step`, then retract in steps of
    /// `unload_step` until no element is bonded: the whole force–approach curve.
    ///
    /// **Load deep enough.** Loading bonds only what touches, and a bonded element detaches
    /// only under a tension above σ_c, so the contact reached at `max_approach` pins the
    /// retraction. If that contact is smaller than the JKR pull-off radius a_c, the pull-off
    /// comes out too weak: for a sphere, load to at least d = 6·(Rγ²/E*²)^(1/3) (a contact of
    /// about 1.6 a_c; `docs/theory.md` §3.5). The pull-off is resolved to about `unload_step`.
    ///
    /// ```
    /// use tack_solver::ApproachPath;
    /// let path = ApproachPath::load_retract(0.01, 0.1, 0.01, 0.001)?;
    /// assert_eq!(path.retract_to, None);
    /// assert!(ApproachPath::load_retract(0.01, 0.1, 0.0, 0.001).is_err());
    /// # Ok::<(), tack_solver::SolverError>(())
    /// ```
    pub fn load_retract(
        start: f64,
        max_approach: f64,
        load_step: f64,
        unload_step: f64,
    ) -> Result<Self, SolverError> {
        let path = Self {
            start,
            max_approach,
            load_step,
            unload_step,
            coarse_unload_step: None,
            refine_pull_off: false,
            retract_to: None,
            max_steps: Self::DEFAULT_MAX_STEPS,
        };
        path.validate()?;
        Ok(path)
    }

    /// Only the pull-off: one load step straight to `max_approach`, a retraction in coarse
    /// steps of `coarse_unload_step` while the force is still compressive, then fine steps of
    /// `unload_step` through the tensile part until no element is bonded. Much cheaper than
    /// [`ApproachPath::load_retract`] when only the pull-off force is wanted.
    ///
    /// The load-deep-enough rule of [`ApproachPath::load_retract`] holds here too (one step to
    /// `max_approach` bonds the same contact as a gradual load on a smooth body). A coarse step
    /// larger than the whole tensile part would jump over the pull-off: keep it below the
    /// approach change between zero force and pull-off (for a sphere about |d_JKR|).
    pub fn pull_off_only(
        max_approach: f64,
        coarse_unload_step: f64,
        unload_step: f64,
    ) -> Result<Self, SolverError> {
        let path = Self {
            start: max_approach,
            max_approach,
            load_step: max_approach.abs().max(unload_step),
            unload_step,
            coarse_unload_step: Some(coarse_unload_step),
            refine_pull_off: false,
            retract_to: None,
            max_steps: Self::DEFAULT_MAX_STEPS,
        };
        path.validate()?;
        Ok(path)
    }

    /// [`ApproachPath::pull_off_only`] with the refined retraction
    /// ([`ApproachPath::refine_pull_off`]): coarse steps of `coarse_unload_step` all the way,
    /// the brackets that may hold the pull-off (and the last one before the contact is lost)
    /// retraced in steps of `unload_step`. The pull-off is then resolved to `unload_step` at
    /// the cost of a few coarse steps and one retraced bracket per candidate; the parts of the
    /// curve far from it are sampled only every `coarse_unload_step`.
    ///
    /// ```
    /// use tack_solver::ApproachPath;
    /// let path = ApproachPath::pull_off_refined(1.0, 0.1, 0.02)?;
    /// assert!(path.refine_pull_off && path.coarse_unload_step == Some(0.1));
    /// # Ok::<(), tack_solver::SolverError>(())
    /// ```
    pub fn pull_off_refined(
        max_approach: f64,
        coarse_unload_step: f64,
        unload_step: f64,
    ) -> Result<Self, SolverError> {
        Ok(Self {
            refine_pull_off: true,
            ..Self::pull_off_only(max_approach, coarse_unload_step, unload_step)?
        })
    }

    /// One step pressed in to `approach` and no retraction: an indentation (the force, area
    /// and fields of one state). With adhesion the step bonds what touches, as the first step
    /// of any path does.
    ///
    /// ```
    /// use tack_solver::ApproachPath;
    /// let path = ApproachPath::indentation(0.01)?;
    /// assert!(path.is_indentation());
    /// assert_eq!(path.step_bound(), 1);
    /// # Ok::<(), tack_solver::SolverError>(())
    /// ```
    pub fn indentation(approach: f64) -> Result<Self, SolverError> {
        // The steps are never taken (the one load step is `max_approach`, and retraction stops
        // before its first step); they only need to be valid.
        let path = Self {
            start: approach,
            max_approach: approach,
            load_step: 1.0,
            unload_step: 1.0,
            coarse_unload_step: None,
            refine_pull_off: false,
            retract_to: Some(approach),
            max_steps: Self::DEFAULT_MAX_STEPS,
        };
        path.validate()?;
        Ok(path)
    }

    /// Whether the path is one step at its deepest approach and no retraction
    /// (`start = max_approach = retract_to`), as [`ApproachPath::indentation`] builds it. A
    /// load-only path of several steps (`retract_to = max_approach > start`) is not one.
    pub fn is_indentation(&self) -> bool {
        self.start == self.max_approach && self.retract_to == Some(self.max_approach)
    }

    /// The approaches of the load phase, in order: `start + k·load_step` below `max_approach`,
    /// then `max_approach` itself, at most `max_steps` of them.
    pub fn load_approaches(&self) -> impl Iterator<Item = f64> + '_ {
        let mut k = 0usize;
        let mut done = false;
        std::iter::from_fn(move || {
            if done || k >= self.max_steps {
                return None;
            }
            let d = (self.start + k as f64 * self.load_step).min(self.max_approach);
            done = d >= self.max_approach;
            k += 1;
            Some(d)
        })
    }

    /// The step a plain retraction (not refined) under `law` takes past the pull-off, once
    /// nothing touches, every gap lies past the law's greatest tension and the tension falls
    /// ([`ApproachPath::coarse_unload_step`],
    /// [`crate::AdhesionLaw::tail_step`]): `None` without a coarse step, when it would be no
    /// longer than `unload_step`, and on a `viscoelastic` solid (its steps are its time steps).
    ///
    /// ```
    /// use tack_solver::{AdhesionLaw, ApproachPath, Exponential, JkrLimit, KAPPA};
    /// let law = AdhesionLaw::from(Exponential { range: 0.1 });
    /// let path = ApproachPath::pull_off_only(0.03, 0.01, 1e-4)?;
    /// assert_eq!(path.tail_step(&law, false), Some(0.002));
    /// assert_eq!(path.tail_step(&law, true), None);
    /// let criterion = AdhesionLaw::from(JkrLimit { kappa: KAPPA });
    /// assert_eq!(path.tail_step(&criterion, false), None);
    /// # Ok::<(), tack_solver::SolverError>(())
    /// ```
    pub fn tail_step(&self, law: &crate::AdhesionLaw, viscoelastic: bool) -> Option<f64> {
        if self.refine_pull_off || viscoelastic {
            return None;
        }
        self.coarse_unload_step
            .and_then(|c| law.tail_step(self.unload_step, c))
            .filter(|&t| t > self.unload_step)
    }

    /// How many steps the load phase takes, its first at `start` and its last at
    /// `max_approach` (a float: a path may ask for more than any cap allows).
    ///
    /// ```
    /// use tack_solver::ApproachPath;
    /// assert_eq!(ApproachPath::load_retract(0.0, 1.0, 0.25, 0.1)?.load_steps(), 5.0);
    /// assert_eq!(ApproachPath::load_retract(0.0, 1.0, 0.3, 0.1)?.load_steps(), 5.0);
    /// assert_eq!(ApproachPath::pull_off_only(1.0, 0.1, 0.01)?.load_steps(), 1.0);
    /// # Ok::<(), tack_solver::SolverError>(())
    /// ```
    pub fn load_steps(&self) -> f64 {
        if self.max_approach > self.start {
            ((self.max_approach - self.start) / self.load_step).ceil() + 1.0
        } else {
            1.0
        }
    }

    /// The most steps the path can take: exact for the load phase; for the retraction, the
    /// steps down to `retract_to` when it is set (with a coarse step, as many as fine steps
    /// would take: an upper bound), else `max_steps` (retraction ends when contact is lost,
    /// which only the solve tells). Never above `max_steps`. Memory bounds use it.
    pub fn step_bound(&self) -> usize {
        let load = self.load_steps();
        let total = match self.retract_to {
            Some(r) => {
                let fine = self
                    .unload_step
                    .min(self.coarse_unload_step.unwrap_or(self.unload_step));
                // Refined: every coarse step at most once, and every fine one.
                let coarse = match (self.refine_pull_off, self.coarse_unload_step) {
                    (true, Some(c)) => ((self.max_approach - r) / c).floor() + 1.0,
                    _ => 0.0,
                };
                load + ((self.max_approach - r) / fine).floor() + coarse
            }
            None => return self.max_steps,
        };
        if total.is_finite() && total < self.max_steps as f64 {
            total as usize
        } else {
            self.max_steps
        }
    }

    /// Checks finiteness and ordering; errors name the `protocol.*` field.
    pub fn validate(&self) -> Result<(), SolverError> {
        validate::finite(fields::PROTOCOL_START, self.start)?;
        validate::finite(fields::PROTOCOL_MAX_APPROACH, self.max_approach)?;
        validate::positive(fields::PROTOCOL_LOAD_STEP, self.load_step)?;
        validate::positive(fields::PROTOCOL_UNLOAD_STEP, self.unload_step)?;
        if let Some(c) = self.coarse_unload_step {
            validate::positive(fields::PROTOCOL_COARSE_UNLOAD_STEP, c)?;
        }
        if self.refine_pull_off && self.coarse_unload_step.is_none() {
            return Err(SolverError::Needs {
                field: fields::PROTOCOL_REFINE_PULL_OFF,
                needs: concat!(
                    "a coarse step: set ",
                    field_name!(protocol.coarse_unload_step),
                    " (the refined retraction steps coarsely and retraces the pull-off's brackets in steps of ",
                    field_name!(protocol.unload_step),
                    ")"
                ),
            });
        }
        if self.max_approach < self.start {
            return Err(SolverError::OutOfRange {
                field: fields::PROTOCOL_MAX_APPROACH,
                value: self.max_approach,
                allowed: concat!("≥ ", field_name!(protocol.start)),
            });
        }
        if let Some(r) = self.retract_to {
            validate::at_most(
                fields::PROTOCOL_RETRACT_TO,
                r,
                self.max_approach,
                concat!(
                    "a finite number ≤ ",
                    field_name!(protocol.max_approach),
                    " (equal: no retraction, an indentation)"
                ),
            )?;
        }
        validate::at_least_one(fields::PROTOCOL_MAX_STEPS, self.max_steps)?;
        // Every approach of the path, max_approach − k·step for k ≤ max_steps, must be a
        // finite number: a step of 1e308 passed the checks above and ran into d = −inf.
        let steps = [
            (fields::PROTOCOL_LOAD_STEP, Some(self.load_step)),
            (fields::PROTOCOL_UNLOAD_STEP, Some(self.unload_step)),
            (fields::PROTOCOL_COARSE_UNLOAD_STEP, self.coarse_unload_step),
        ];
        for (field, step) in steps {
            let reach = |v: f64| v * self.max_steps as f64 + self.max_approach.abs();
            if let Some(v) = step
                && (reach(v).is_nan() || reach(v) > 1e300)
            {
                return Err(SolverError::OutOfRange {
                    field,
                    value: v,
                    allowed: concat!(
                        "a finite number > 0 with ",
                        field_name!(protocol.max_steps),
                        " × step + |",
                        field_name!(protocol.max_approach),
                        "| ≤ 1e300 (every approach of the path finite)"
                    ),
                });
            }
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
pub trait Observer: Send {
    /// Called after every step with its index and record.
    fn on_step(&mut self, _index: usize, _phase: Phase, _record: &StepRecord) {}
    /// Called after every step, before [`Observer::on_step`], with the step's pressure field
    /// and bonded mask (on the grid the solver runs on), for observers that select fields by
    /// rules of their own. Clone what you keep.
    fn on_fields(
        &mut self,
        _index: usize,
        _phase: Phase,
        _record: &StepRecord,
        _pressure: &Array2<f64>,
        _bonded: &Array2<bool>,
    ) {
    }
    /// The path starts over from its first step: a driver runs it again (the `tack` facade
    /// re-solves on the full grid when contact reached a crop window's edge). Observers that
    /// keep state per step reset it here.
    fn on_restart(&mut self) {}
    /// Asked after every step: `true` stops the path there with
    /// [`SolverError::Cancelled`] (a long run cancelled from another thread or a signal).
    fn cancelled(&mut self) -> bool {
        false
    }
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
    /// The pull-off step (the least force of the path, the first one on ties; periodic
    /// full-contact steps left out, as in [`PathResult::pull_off_force`]) and the last step
    /// that still has a bonded element (one snapshot when they coincide).
    PullOff,
}

impl SnapshotRequest {
    /// Whether step `step` is kept by a rule that needs no look at the path (`PullOff` decides
    /// as the path goes, see [`SnapshotKeeper`]).
    fn wants(&self, step: usize) -> bool {
        match self {
            Self::None | Self::PullOff => false,
            Self::All => true,
            Self::Every(k) => step % (*k).max(1) == 0,
            Self::Steps(s) => s.contains(&step),
        }
    }
}

/// Snapshot keeping as an [`Observer`]: the fields a [`SnapshotRequest`] asks for. The rules that
/// name steps keep them as they come; [`SnapshotRequest::PullOff`] keeps the least force so far
/// (fields cloned only when a new minimum is found) and the latest step with a bonded element
/// (copied into buffers allocated once).
struct SnapshotKeeper<'r> {
    request: &'r SnapshotRequest,
    steps: Vec<StepFields>,
    pull_off: Option<(f64, StepFields)>,
    last_contact: Option<StepFields>,
}

impl<'r> SnapshotKeeper<'r> {
    fn new(request: &'r SnapshotRequest) -> Self {
        Self {
            request,
            steps: Vec::new(),
            pull_off: None,
            last_contact: None,
        }
    }

    /// The kept snapshots in step order, one per step.
    fn into_snapshots(self) -> Vec<StepFields> {
        if *self.request != SnapshotRequest::PullOff {
            return self.steps;
        }
        let mut out: Vec<StepFields> = self.pull_off.map(|(_, s)| s).into_iter().collect();
        if let Some(last) = self.last_contact
            && out.first().is_none_or(|p| p.step != last.step)
        {
            out.push(last);
        }
        out.sort_by_key(|s| s.step);
        out
    }
}

impl Observer for SnapshotKeeper<'_> {
    fn on_fields(
        &mut self,
        step: usize,
        _phase: Phase,
        record: &StepRecord,
        pressure: &Array2<f64>,
        bonded: &Array2<bool>,
    ) {
        let fields = || StepFields {
            step,
            pressure: pressure.clone(),
            bonded: bonded.clone(),
        };
        if self.request.wants(step) {
            self.steps.push(fields());
        }
        if *self.request != SnapshotRequest::PullOff {
            return;
        }
        if !record.full_contact
            && self
                .pull_off
                .as_ref()
                .is_none_or(|(force, _)| record.force < *force)
        {
            self.pull_off = Some((record.force, fields()));
        }
        if record.n_bonded > 0 {
            match &mut self.last_contact {
                Some(s) => {
                    s.step = step;
                    s.pressure.assign(pressure);
                    s.bonded.assign(bonded);
                }
                None => self.last_contact = Some(fields()),
            }
        }
    }

    fn on_restart(&mut self) {
        self.steps.clear();
        (self.pull_off, self.last_contact) = (None, None);
    }
}

/// Two observers in turn: every hook goes to `first`, then to `second`; either may cancel.
struct Both<'a> {
    first: &'a mut dyn Observer,
    second: &'a mut dyn Observer,
}

impl Observer for Both<'_> {
    fn on_step(&mut self, index: usize, phase: Phase, record: &StepRecord) {
        self.first.on_step(index, phase, record);
        self.second.on_step(index, phase, record);
    }
    fn on_fields(
        &mut self,
        index: usize,
        phase: Phase,
        record: &StepRecord,
        pressure: &Array2<f64>,
        bonded: &Array2<bool>,
    ) {
        self.first.on_fields(index, phase, record, pressure, bonded);
        self.second
            .on_fields(index, phase, record, pressure, bonded);
    }
    fn on_restart(&mut self) {
        self.first.on_restart();
        self.second.on_restart();
    }
    fn cancelled(&mut self) -> bool {
        // Both are asked: neither should miss a poll it counts on.
        let first = self.first.cancelled();
        self.second.cancelled() || first
    }
}

/// The pressure field and bonded mask of one step, kept on request ([`SnapshotRequest`]);
/// the result file stores them, with the step's approach, as `tack_io::Snapshot`.
#[derive(Debug, Clone, PartialEq)]
pub struct StepFields {
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
    pub snapshots: Vec<StepFields>,
    /// The path ended as planned (detached or `retract_to` reached), not by `max_steps`.
    pub completed: bool,
}

/// The pull-off step of a force curve given as `(force, full_contact)` per step: the least
/// force over the steps that are not periodic full contact (their force is a bound, not a
/// state's), the first of equal ones; NaN forces are skipped. `None` when no step counts.
/// The one rule behind [`PathResult::pull_off_step`], usable on a curve read from a file.
pub fn pull_off_step(steps: impl IntoIterator<Item = (f64, bool)>) -> Option<usize> {
    let mut best: Option<(usize, f64)> = None;
    for (i, (force, full_contact)) in steps.into_iter().enumerate() {
        if full_contact || force.is_nan() {
            continue;
        }
        if best.is_none_or(|(_, f)| force < f) {
            best = Some((i, force));
        }
    }
    best.map(|(i, _)| i)
}

impl PathResult {
    /// Greatest tensile force: the minimum of the force over the path (negative when adhesive).
    /// Periodic full-contact steps are left out: their force is not fixed by the approach (the
    /// record holds the least admissible one, about −σ_c, a property of the mesh).
    pub fn pull_off_force(&self) -> f64 {
        self.pull_off_step()
            .map_or(f64::INFINITY, |i| self.records[i].force)
    }
    /// Index of the step that carries [`PathResult::pull_off_force`]: the least force over
    /// the steps that are not periodic full contact (the first of equal ones), `None` when
    /// there is no such step.
    pub fn pull_off_step(&self) -> Option<usize> {
        pull_off_step(self.records.iter().map(|r| (r.force, r.full_contact)))
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

/// Which step a plain retraction takes ([`ApproachPath::coarse_unload_step`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stage {
    /// The coarse step, while the force is compressive.
    Coarse,
    /// The unload step, through the tensile part.
    Fine,
    /// A smooth law's tail step ([`crate::AdhesionLaw::tail_step`]), once nothing touches,
    /// every gap is past the law's peak and the tension falls.
    Tail,
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
        if path.refine_pull_off && self.visco.is_some() {
            return Err(SolverError::Refused {
                field: fields::PROTOCOL_REFINE_PULL_OFF,
                reason: "a viscoelastic path is not retraced (its arms carry the time): leave \
                         refine_pull_off out and set unload_step to the retraction's time step",
            });
        }
        let mut keeper = SnapshotKeeper::new(snapshots);
        let mut out = self.drive(
            path,
            &mut Both {
                first: &mut keeper,
                second: observer,
            },
        )?;
        out.snapshots = keeper.into_snapshots();
        Ok(out)
    }

    /// The steps of `path`: load, then retract; every step goes to `observer`.
    fn drive(
        &mut self,
        path: &ApproachPath,
        observer: &mut dyn Observer,
    ) -> Result<PathResult, SolverError> {
        let mut out = PathResult::default();
        for d in path.load_approaches() {
            self.record_step(d, Phase::Load, observer, &mut out)?;
        }
        // A load cut short by `max_steps` never retracts (and is not complete).
        if out
            .records
            .last()
            .is_none_or(|r| r.approach < path.max_approach)
        {
            return Ok(out);
        }
        // A viscoelastic solid holds the deepest approach for its dwell, in steps of the load.
        let dwell = self
            .visco
            .as_ref()
            .map(|v| (v.rates.dwell, v.rates.dwell_steps));
        if let Some((dwell, steps)) = dwell.filter(|&(t, _)| t > 0.0) {
            for _ in 0..steps {
                let rec = self.hold(dwell / steps as f64)?;
                self.tell(rec, Phase::Load, observer, &mut out)?;
            }
        }
        if let (true, Some(coarse)) = (path.refine_pull_off, path.coarse_unload_step) {
            self.retract_refined(path, coarse, observer, &mut out)?;
            return Ok(out);
        }
        // Retract from `anchor` in steps of `stride`: the coarse step while the force is
        // compressive, then the unload step from the approach where it stopped being so, and
        // under a smooth law, past its pull-off, the law's tail step ([`Stage::Tail`]).
        let (mut anchor, mut stride) = (
            path.max_approach,
            path.coarse_unload_step.unwrap_or(path.unload_step),
        );
        // A coarse step equal to the fine one is no coarse step (no re-anchoring: the same bits).
        let mut stage = if path
            .coarse_unload_step
            .is_some_and(|c| c != path.unload_step)
        {
            Stage::Coarse
        } else {
            Stage::Fine
        };
        let tail = path.tail_step(self.law(), self.visco.is_some());
        let mut k = 1usize;
        loop {
            if stage == Stage::Coarse
                && let Some(last) = out.records.last()
                && last.force <= 0.0
            {
                (anchor, stride, k, stage) = (last.approach, path.unload_step, 1, Stage::Fine);
            }
            if stage == Stage::Fine
                && let Some(t) = tail
                && let [.., before, last] = out.records.as_slice()
                && last.n_bonded == 0
                && last.force > before.force
                && self.past_peak()
            {
                (anchor, stride, k, stage) = (last.approach, t, 1, Stage::Tail);
            }
            let d = anchor - k as f64 * stride;
            // The path's own end first: a path that ends at `retract_to` on its last allowed
            // step (an indentation with `max_steps = 1`) is complete, not stopped by the cap.
            if path.retract_to.is_some_and(|r| d < r) {
                out.completed = true;
                break;
            }
            if out.records.len() >= path.max_steps {
                break;
            }
            let rec = self.record_step(d, Phase::Unload, observer, &mut out)?;
            if rec.n_bonded + rec.n_cohesive == 0 && path.retract_to.is_none() {
                out.completed = true;
                break;
            }
            k += 1;
        }
        Ok(out)
    }

    /// The refined retraction ([`ApproachPath::refine_pull_off`]) after the load phase: coarse
    /// steps from `max_approach`, each kept back (with a copy of the solver's state) until the
    /// next one tells whether it is the middle of a bracket to retrace. Every approach is
    /// `max_approach − n·unload_step` for a whole `n` (the coarse step is a whole number `m` of
    /// unload steps), so a retraced stretch samples the fine path's own approaches.
    fn retract_refined(
        &mut self,
        path: &ApproachPath,
        coarse: f64,
        observer: &mut dyn Observer,
        out: &mut PathResult,
    ) -> Result<(), SolverError> {
        let fine = path.unload_step;
        let m = ((coarse / fine).round() as usize).max(1);
        let at = |n: usize| path.max_approach - n as f64 * fine;
        // The state after the last kept step (where a retraced bracket starts) and its index,
        // and the coarse steps not kept yet, oldest first, with their indices and the states
        // after them (at most two).
        let mut start = (0usize, self.save_state());
        let mut pending: Vec<(usize, StepRecord, SolverState)> = Vec::new();
        let mut spare: Vec<SolverState> = Vec::new();
        // The largest tension released in one fine step of a retraced stretch: how far a peak
        // of a saw-tooth curve (a front that sticks, then jumps) may hide between coarse steps.
        let mut release = 0.0f64;
        let mut n = 0usize;
        loop {
            n += m;
            let d = at(n);
            if path.retract_to.is_some_and(|r| d < r) {
                self.keep_pending(&mut pending, &mut start, &mut spare, observer, out)?;
                out.completed = true;
                return Ok(());
            }
            if out.records.len() + pending.len() >= path.max_steps {
                self.keep_pending(&mut pending, &mut start, &mut spare, observer, out)?;
                return Ok(());
            }
            let rec = self.step(d)?;
            let mut state = spare.pop().unwrap_or_else(|| self.save_state());
            self.save_state_into(&mut state);
            pending.push((n, rec, state));
            let lost = rec.n_bonded + rec.n_cohesive == 0 && path.retract_to.is_none();
            if pending.len() < 2 && !lost {
                continue;
            }
            let least = out
                .records
                .iter()
                .filter(|r| !r.full_contact)
                .map(|r| r.force)
                .fold(f64::INFINITY, f64::min);
            let before = out.records.last().map_or(f64::INFINITY, |r| r.force);
            // Within one released saw-tooth of the least force: a peak may hide next to it.
            let near = |f: f64| release > 0.0 && f < 0.0 && f - RELEASE_MARGIN * release <= least;
            // `pending` is [F_i, F_{i+1}] (or [F_{i+1}] alone when contact was lost): is step
            // i the middle of a bracket that may hold the pull-off? (A lost contact has F = 0.)
            let candidate = pending.len() == 2 && {
                let (f, after) = (pending[0].1.force, pending[1].1.force);
                let minimum = f < before && f <= after && f < 0.0 && f - (before - f) <= least;
                minimum || near(before) || near(f) || near(after)
            };
            if !candidate && pending.len() == 2 {
                // Step i is kept; step i + 1 waits for its own neighbour.
                let (i, rec, state) = pending.remove(0);
                self.keep(rec, &state, observer, out)?;
                spare.push(std::mem::replace(&mut start, (i, state)).1);
            }
            // Contact lost within the coarse step after the last kept one: retrace it only if
            // the tension was still growing there or is near the least (the pull-off may lie
            // just before the jump-out); otherwise the jump-out stays located to the coarse step.
            let growing = match out.records.as_slice() {
                [.., a, b] => (b.force < 0.0 && b.force < a.force) || near(b.force),
                _ => true,
            };
            if lost && !candidate && !growing {
                self.keep_pending(&mut pending, &mut start, &mut spare, observer, out)?;
                out.completed = true;
                return Ok(());
            }
            if m == 1 {
                // The coarse step is the fine one: every step is already fine.
                self.keep_pending(&mut pending, &mut start, &mut spare, observer, out)?;
                if lost {
                    out.completed = true;
                    return Ok(());
                }
                continue;
            }
            if candidate || lost {
                // Retrace from the kept state to the last coarse step's approach.
                let end = pending.last().expect("a pending step").0;
                spare.extend(pending.drain(..).map(|(_, _, s)| s));
                self.restore_state(&start.1)?;
                for j in start.0 + 1..=end {
                    if out.records.len() >= path.max_steps {
                        return Ok(());
                    }
                    let previous = out.records.last().map(|r| r.force);
                    let rec = self.record_step(at(j), Phase::Unload, observer, out)?;
                    if let Some(p) = previous {
                        release = release.max(rec.force - p);
                    }
                    if rec.n_bonded + rec.n_cohesive == 0 && path.retract_to.is_none() {
                        out.completed = true;
                        return Ok(());
                    }
                }
                start.0 = end;
                self.save_state_into(&mut start.1);
            }
        }
    }

    /// Keeps the pending coarse steps, in order (the path ends).
    fn keep_pending(
        &mut self,
        pending: &mut Vec<(usize, StepRecord, SolverState)>,
        start: &mut (usize, SolverState),
        spare: &mut Vec<SolverState>,
        observer: &mut dyn Observer,
        out: &mut PathResult,
    ) -> Result<(), SolverError> {
        for (i, rec, state) in pending.drain(..) {
            self.keep(rec, &state, observer, out)?;
            spare.push(std::mem::replace(start, (i, state)).1);
        }
        Ok(())
    }

    /// Keeps a step solved earlier: tells the observer (with the fields saved after it) and
    /// appends the record, as [`Self::record_step`] does for the step just solved.
    fn keep(
        &mut self,
        rec: StepRecord,
        state: &SolverState,
        observer: &mut dyn Observer,
        out: &mut PathResult,
    ) -> Result<(), SolverError> {
        let index = out.records.len();
        observer.on_fields(index, Phase::Unload, &rec, state.pressure(), state.bonded());
        observer.on_step(index, Phase::Unload, &rec);
        out.records.push(rec);
        out.phases.push(Phase::Unload);
        if observer.cancelled() {
            return Err(SolverError::Cancelled {
                steps: out.records.len(),
            });
        }
        Ok(())
    }

    /// One step at `d`: solve, tell the observer (fields, then record), append the record.
    fn record_step(
        &mut self,
        d: f64,
        phase: Phase,
        observer: &mut dyn Observer,
        out: &mut PathResult,
    ) -> Result<StepRecord, SolverError> {
        let rec = self.step(d)?;
        self.tell(rec, phase, observer, out)
    }

    /// The step just solved, `rec`: tell the observer (fields, then record), append the record.
    fn tell(
        &mut self,
        rec: StepRecord,
        phase: Phase,
        observer: &mut dyn Observer,
        out: &mut PathResult,
    ) -> Result<StepRecord, SolverError> {
        let index = out.records.len();
        observer.on_fields(index, phase, &rec, self.pressure(), self.bonded());
        observer.on_step(index, phase, &rec);
        out.records.push(rec);
        out.phases.push(phase);
        if observer.cancelled() {
            return Err(SolverError::Cancelled {
                steps: out.records.len(),
            });
        }
        Ok(rec)
    }
}

#[cfg(test)]
mod tests;
