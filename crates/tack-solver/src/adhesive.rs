//! JKR-limit adhesive contact: a bonded set with the Pohrt–Popov mesh-dependent detachment
//! criterion, solved at a prescribed approach by an active-set loop around a linear CG.
//!
//! Protocol at approach `d` (docs/theory.md §3.4): solve `K p = d − f` on the bonded set `C`
//! (`p = 0` off it); detach **every** bonded element whose tension exceeds `σ_c` (all at once,
//! as in the reference prototype); attach every free element that penetrates; repeat until `C`
//! no longer changes. Both decisions come from the same solution and are applied together, so
//! the result does not depend on iteration order. Cycles are detected by remembering every
//! bonded set visited in the step; a revisit stops the loop and the step reports
//! `converged = false`. The loop is also capped.

use crate::rounds::{Rounds, Tally};
use std::hash::{DefaultHasher, Hash, Hasher};

use ndarray::{Array2, ArrayView2, Zip};
use tack_geometry::{Boundary, Surface, Window};
use tack_kernels::{ElasticOperator, padded_size};

use crate::base::SolverBase;
use crate::cg::{PcgWork, assign};
use crate::clusters::count_clusters;
use crate::law::Cohesive;
use crate::relax::{Relaxation, Released, take_released};
use crate::smooth::SmoothState;
use crate::state::Convergence;
pub(crate) use crate::subgrid::bounding_box;
use crate::subgrid::{SubProblem, SubgridCache};
use crate::{AdhesionLaw, SolverError, SolverOptions, StepRecord, validate};

/// The Pohrt–Popov constant κ of `σ_c = sqrt(E*γ/(κΔx))`, from the mean displacement of a
/// square element under its own pressure: κ = (2/π)[ln(1+√2) − (√2−1)/3] = 0.473201.
///
/// Measured on the smooth sphere (free boundaries, `tests/adhesion.rs`,
/// `jkr_sphere_pull_off_converges_with_refinement`), the greatest tensile force exceeds F_JKR by
/// +32.6%, +14.1%, +6.9%, +3.5% at a_c/Δx = 5, 10, 20, 40: observed order 1.2, 1.0, 1.0.
/// The centre-displacement variant κ = 0.5611 gives +13.7%, −3.4%, −9.3% at 5, 10, 20: the error
/// changes sign and grows, so it does not converge to JKR. Curved fronts (spheres, rough
/// contacts) cross the elements at every offset; for fronts aligned with the grid see
/// [`KAPPA_LINE`].
pub const KAPPA: f64 = tack_kernels::MEAN_SELF_COMPLIANCE / 2.0;

/// κ for a straight crack front aligned with the grid (1D waviness on a periodic strip): 0.865.
///
/// The criterion compares the edge element's tension with `σ_c`; for a straight front on an
/// element boundary the discrete edge tension is `β·K/√Δx` with a mesh-independent β, and
/// Griffith's `K² = 2E*γ` then requires `κ = 1/(2β²)`. A continuum estimate (edge tension =
/// mean of `K/√(2πr)` over the element, β = 2/√(2π)) gives π/4 = 0.785; the discrete BEM
/// solution of a periodic strip punch (closed form `K = |p̄|√(λ/tan ψ)`) gives β = 0.7603 and
/// κ = 0.8607, 0.8641, 0.8647, 0.8650 at punch widths 127, 511, 2047 (λ/Δx = 4096, 16384)
/// elements — settled by `tests/adhesion.rs::line_front_kappa_from_discrete_punch`.
///
/// Measured on Johnson's 1D waviness (λ/Δx = 1024, α = 0.3): with [`KAPPA`] the mean p̄
/// deviation from Eq. 2 is −0.112 p* and does not shrink with refinement (−0.116 at 256);
/// the sphere's κ makes straight fronts `√(0.865/0.4732) = 1.35×` too adhesive.
pub const KAPPA_LINE: f64 = 0.865;

/// Settings of the adhesive solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdhesiveOptions {
    /// Linear CG stopping rule and cap (per solve on a bonded set).
    pub cg: SolverOptions,
    /// Cap on detach/attach rounds per approach step.
    pub max_active_set_iterations: usize,
    /// Precondition CG with the spectral stiffness `E*|q|/2` restricted to the bonded set.
    pub preconditioned: bool,
    /// Free grids: run CG on a sub-grid around the bonded set when that is much smaller.
    pub bonded_subgrid: bool,
    /// Inexact rounds: the CG tolerance of the detach/attach rounds that only have to find
    /// which elements cross the criterion (`None`: every round is solved to `cg.tolerance`).
    /// Such a round detaches only tensions beyond `σ_c (1 + m)` and attaches only gaps below a
    /// margin ([`LOOSE_DETACH_MARGIN`], [`LOOSE_ATTACH_MARGIN`]): a wrong detachment can set off
    /// a cascade, and adhesion holds a wrongly attached element. On free grids it updates the
    /// gap only inside its sub-grid, so only elements there may attach. When a round changes
    /// nothing, the same set is solved to `cg.tolerance` and judged everywhere without margin,
    /// so every step ends on an exact solve that meets the exact criterion. Default `1e-3`
    /// (docs/theory.md §3.4 has the measurements).
    pub round_tolerance: Option<f64>,
    /// Non-adhesive cold starts (`γ = 0`, nothing in contact yet) begin from the solution on
    /// grids coarsened 2 × 2, recursively (see `docs/theory.md` §3.4). Exact: only the
    /// iteration count changes.
    pub nested_start: bool,
    /// Zero-range law with adhesion: after a round detaches elements, the tension they carried
    /// is redistributed over their neighbourhood by small windowed solves before the next
    /// round's solve (`docs/theory.md` §3.4). Only that solve's start changes; it still runs to
    /// its round's tolerance and takes every decision. Default on; used with inexact rounds
    /// (`round_tolerance`; without them the loop stays the exact one) on free grids of a
    /// half-space, where the windows' operator is exact.
    pub local_relaxation: bool,
}

/// The tolerance [`LOOSE_DETACH_MARGIN`] was measured at; margins scale with a round's
/// tolerance relative to it.
pub(crate) const LOOSE_REFERENCE_TOLERANCE: f64 = 1e-3;

/// Relative tension margin `m` of an inexact round: it detaches `p < −σ_c (1 + m)` only. With
/// `round_tolerance = 1e-3`, `m = 0.001` let a Kendall punch at a/Δx = 20 pull off 0.6% early
/// (a rim element within the inexact solve's error of σ_c started the cascade), and `0.003` let
/// a flat-tipped body z = r⁴ pull off 1.7% and 0.9% early at a_F/Δx = 10 and 20
/// (`tests/power_law.rs`), and the 512² rough sphere of `cargo xtask bench` 1.2·10⁻⁴ early;
/// `0.006` gives the exact algorithm's pull-off on all three (`tests/adhesion.rs`,
/// `tests/power_law.rs`, `crates/tack/tests/relaxation.rs`, docs/theory.md §3.4).
pub const LOOSE_DETACH_MARGIN: f64 = 0.006;

/// Gap margin of an inexact round, in units of its residual bound: it attaches only gaps below
/// `−LOOSE_ATTACH_MARGIN · round_tolerance · scale` (scale: the rms of `d − f` over the set).
pub const LOOSE_ATTACH_MARGIN: f64 = 10.0;

impl Default for AdhesiveOptions {
    fn default() -> Self {
        Self {
            cg: SolverOptions {
                tolerance: 1e-9,
                max_iterations: 5_000,
            },
            max_active_set_iterations: 1_000,
            preconditioned: true,
            bonded_subgrid: true,
            round_tolerance: Some(1e-3),
            nested_start: true,
            local_relaxation: true,
        }
    }
}

/// Quasi-static adhesive contact along an approach path; owns operator, fields and scratch.
pub struct AdhesiveSolver {
    pub(crate) base: SolverBase,
    /// The criterion's σ_c (zero-range law) or the cohesive tension σ0 (Dugdale law) of the
    /// reference work of adhesion.
    pub(crate) sigma_c: f64,
    /// The greatest tension of each element (a patterned work of adhesion,
    /// [`AdhesiveSolver::set_gamma_map`]), or a 1 × 1 array holding `sigma_c`; read through
    /// [`AdhesiveSolver::tension`], which broadcasts it.
    pub(crate) tension: Array2<f64>,
    /// Whether `tension` is a map (per element) rather than the uniform `sigma_c`.
    pub(crate) patterned: bool,
    /// The reference work of adhesion and the law, from which a map's tensions follow.
    reference: (f64, AdhesionLaw),
    pub(crate) options: AdhesiveOptions,
    pub(crate) bonded: Array2<bool>,
    pub(crate) pcg: PcgWork,
    /// Bonded-set CGs on sub-grids of a free grid, by shape.
    pub(crate) boxes: SubgridCache<SubProblem>,
    /// Pressure and approach of the previous step, for the secant predictor.
    pub(crate) history: Option<(Array2<f64>, f64)>,
    pub(crate) last_approach: Option<f64>,
    /// The Dugdale law's cohesive zone and scratch (`None`: the zero-range criterion).
    pub(crate) cohesive: Option<Cohesive>,
    /// A smooth law's curve and Newton vectors (`None`: the criterion or the Dugdale law).
    pub(crate) smooth: Option<SmoothState>,
    /// Windowed solves of [`AdhesiveOptions::local_relaxation`].
    relaxation: Relaxation,
}

/// Distinct sub-grid shapes kept by one solver (the least recently used is replaced). Each holds
/// an operator with its buffers; on the 1024² rough-sphere pull-off 16 shapes held twice the
/// memory of 4 (544 against 272 MB peak) for the same time, as a path passes through its
/// shapes in order and rarely returns to an old one.
const SUBGRID_SHAPES: usize = 4;

impl AdhesiveSolver {
    /// A solver for `surface` against the half-space `op` with work of adhesion `gamma ≥ 0`
    /// (`γ = 0` is non-adhesive contact) and Pohrt–Popov constant `kappa > 0` (see [`KAPPA`]).
    pub fn new(
        op: Box<dyn ElasticOperator>,
        surface: &Surface,
        gamma: f64,
        kappa: f64,
        options: AdhesiveOptions,
    ) -> Result<Self, SolverError> {
        Self::with_law(op, surface, gamma, AdhesionLaw::JkrLimit { kappa }, options)
    }

    /// A solver for `surface` against `op` with work of adhesion `gamma` under `law`: the
    /// zero-range criterion ([`AdhesiveSolver::new`]) or a Dugdale cohesive zone of tension σ0
    /// and range `h0 = γ/σ0` ([`AdhesionLaw::Dugdale`], `γ > 0`).
    pub fn with_law(
        op: Box<dyn ElasticOperator>,
        surface: &Surface,
        gamma: f64,
        law: AdhesionLaw,
        options: AdhesiveOptions,
    ) -> Result<Self, SolverError> {
        let kappa = match law {
            AdhesionLaw::JkrLimit { kappa } => kappa,
            _ => KAPPA,
        };
        validate::adhesion(gamma, kappa, &options)?;
        let mut options = options;
        if !op.is_half_space() {
            // Sub-grids, coarse starts and relaxation windows build half-space operators of
            // their own.
            (
                options.bonded_subgrid,
                options.nested_start,
                options.local_relaxation,
            ) = (false, false, false);
        }
        let base = SolverBase::new(op, surface)?;
        let shape = base.grid().shape();
        let (base_dx, e_star) = (base.grid().dx(), base.op.e_star());
        let sigma_c = law.peak_tension(gamma, e_star, base_dx);
        let (cohesive, smooth) = match law {
            AdhesionLaw::JkrLimit { .. } => (None, None),
            AdhesionLaw::Dugdale { sigma0 } => {
                (Some(Cohesive::new(gamma, sigma0, surface, shape)?), None)
            }
            AdhesionLaw::Exponential { .. } | AdhesionLaw::LennardJones { .. } => {
                law.check(gamma, surface)?;
                let traction = law.traction(gamma).expect("a smooth law");
                (None, Some(SmoothState::new(traction, shape)))
            }
        };
        Ok(Self {
            base,
            sigma_c,
            tension: Array2::from_elem((1, 1), sigma_c),
            patterned: false,
            reference: (gamma, law),
            options,
            bonded: Array2::from_elem(shape, false),
            pcg: PcgWork::new(shape),
            boxes: SubgridCache::new(SUBGRID_SHAPES),
            history: None,
            last_approach: None,
            cohesive,
            smooth,
            relaxation: Relaxation::new(base_dx, e_star),
        })
    }

    /// Switches the nested coarse-to-fine cold start of non-adhesive solves on or off
    /// ([`AdhesiveOptions::nested_start`]).
    pub fn set_nested_start(&mut self, on: bool) {
        self.options.nested_start = on && self.base.op.is_half_space();
    }

    /// Switches sub-grid CG on free grids on or off ([`AdhesiveOptions::bonded_subgrid`]).
    pub fn set_bonded_subgrid(&mut self, on: bool) {
        self.options.bonded_subgrid = on && self.base.op.is_half_space();
    }

    /// The critical tensile stress `σ_c = sqrt(E*γ/(κΔx))` of the detachment criterion, or the
    /// cohesive tension σ0 of the Dugdale law (the greatest tension any element carries).
    pub fn critical_stress(&self) -> f64 {
        self.sigma_c
    }
    /// Makes the work of adhesion a field: `gamma[[i, j]] ≥ 0` on element `(i, j)` (the grid's
    /// shape). The criterion detaches an element beyond its own `σ_c = sqrt(E*γ_ij/(κΔx))`;
    /// the Dugdale law keeps one range `h0 = γ/σ0` of the reference `γ` given at construction
    /// and gives each element the tension `σ0·γ_ij/γ` (docs/theory.md §3.8). The reference `γ`
    /// stays what [`AdhesiveSolver::critical_stress`] and [`AdhesiveSolver::range`] report.
    ///
    /// Errors name `adhesion.gamma_map`: a map of another shape, or an entry that is negative
    /// or not finite.
    pub fn set_gamma_map(&mut self, gamma: ArrayView2<f64>) -> Result<(), SolverError> {
        let shape = self.bonded.dim();
        if gamma.dim() != shape {
            return Err(SolverError::MapShape {
                field: tack_fields::ADHESION_GAMMA_MAP,
                map: gamma.dim(),
                grid: shape,
            });
        }
        if let Some(&bad) = gamma.iter().find(|g| !(g.is_finite() && **g >= 0.0)) {
            return Err(SolverError::OutOfRange {
                field: tack_fields::ADHESION_GAMMA_MAP,
                value: bad,
                allowed: "a finite number ≥ 0 in every element",
            });
        }
        let (gamma_ref, law) = self.reference;
        self.tension = match law {
            AdhesionLaw::JkrLimit { kappa } => {
                let scale = self.base.op.e_star() / (kappa * self.base.grid().dx());
                gamma.mapv(|g| (scale * g).sqrt())
            }
            AdhesionLaw::Dugdale { sigma0 } => gamma.mapv(|g| sigma0 * (g / gamma_ref)),
            AdhesionLaw::Exponential { .. } | AdhesionLaw::LennardJones { .. } => {
                let share: std::sync::Arc<[f64]> = gamma.iter().map(|g| g / gamma_ref).collect();
                if let Some(s) = self.smooth.as_mut() {
                    s.weights = Some(share);
                }
                gamma.mapv(|g| self.sigma_c * (g / gamma_ref))
            }
        };
        self.patterned = true;
        Ok(())
    }

    /// The greatest tension of every element: the criterion's `σ_c` or the Dugdale law's σ0,
    /// per element when the work of adhesion is a map ([`AdhesiveSolver::set_gamma_map`]).
    pub fn tension(&self) -> ArrayView2<'_, f64> {
        self.tension
            .broadcast(self.bonded.dim())
            .expect("a 1 × 1 array or the grid's shape")
    }

    /// The adhesion law's range (`h0 = γ/σ0` of the Dugdale law, ρ, ε), `None` for the
    /// zero-range criterion.
    pub fn range(&self) -> Option<f64> {
        self.reference.1.range(self.reference.0)
    }

    /// The adhesion law the solver runs.
    pub fn law(&self) -> AdhesionLaw {
        self.reference.1
    }
    /// Dugdale law: the cohesive zone (elements not in contact that carry the tension σ0, their
    /// gap below the range); smooth laws: the elements out of contact whose tension exceeds 1%
    /// of the peak. `None` for the zero-range criterion.
    pub fn cohesive_zone(&self) -> Option<&Array2<bool>> {
        match (&self.cohesive, &self.smooth) {
            (Some(c), _) => Some(&c.zone),
            (None, Some(s)) => Some(&s.zone),
            (None, None) => None,
        }
    }
    /// Current element pressures (the cohesive zone's tension −σ0 included).
    pub fn pressure(&self) -> &Array2<f64> {
        &self.base.pressure
    }
    /// Current bonded mask.
    pub fn bonded(&self) -> &Array2<bool> {
        &self.bonded
    }
    /// Current gap `f − d + u` (zero on the bonded set up to the tolerance).
    pub fn gap(&self) -> &Array2<f64> {
        &self.base.gap
    }
    /// The grid of the problem.
    pub fn grid(&self) -> &tack_geometry::Grid {
        self.base.grid()
    }

    /// Equilibrium at approach `d`, starting from the current bonded set and pressures.
    ///
    /// Periodic grids with every element bonded are handled in closed form: for `d ≥ mean f`
    /// the state is full contact and reports the least mean pressure at which no element's
    /// tension exceeds `σ_c`; for `d < mean f` full contact is impossible (the mean gap is
    /// positive), so the most tensile element of the full-contact field is detached.
    ///
    /// Under the Dugdale law the same loop runs on three sets (contact, cohesive zone, free);
    /// see [`AdhesionLaw::Dugdale`].
    pub fn step(&mut self, approach: f64) -> Result<StepRecord, SolverError> {
        let d = validate::approach(approach)?;
        if self.smooth.is_some() {
            return Ok(self.step_smooth(d));
        }
        self.predict(d);
        if self.cohesive.is_some() {
            return Ok(self.step_dugdale(d));
        }
        self.step_criterion(d)
    }

    /// One approach step under the zero-range criterion: rounds of one solve on the bonded
    /// set, then every detachment and attachment that solution calls for, until an exact round
    /// changes nothing (module docs); `d` is validated.
    fn step_criterion(&mut self, d: f64) -> Result<StepRecord, SolverError> {
        let periodic = self.base.periodic();
        let n = self.base.heights().len();
        let mut tally = Tally::new();
        let closed = self.base.closed(d);
        if closed {
            self.bonded.fill(true);
        } else if self.sigma_c == 0.0
            && !self.patterned
            && self.options.nested_start
            && !self.bonded.iter().any(|&b| b)
        {
            tally.cg += self.start_from_coarse(d)?;
        }
        let sigma_c = self.sigma_c;
        // Inexact rounds until one finds nothing clear, then an exact round on the same set.
        let mut schedule = Rounds::new(self.options.round_tolerance, self.options.cg.tolerance);
        // `work.disp` and the gap are up to date only inside the last inexact round's window.
        let mut stale = false;
        // A window known to hold every bonded element and every non-zero pressure (`None`: the
        // whole grid): after an inexact sub-grid round only its window can have changed, so
        // the next round's bookkeeping scans that instead of the grid.
        let mut extent: Option<Window> = None;
        // The elements the last round detached, whose tension the next round's start relaxes.
        // Inexact rounds only: `round_tolerance = None` stays the exact loop, bit for bit.
        let relaxing = self.options.local_relaxation
            && self.options.round_tolerance.is_some()
            && !periodic
            && (sigma_c > 0.0 || self.patterned);
        let mut released: Vec<Released> = Vec::new();
        loop {
            if tally.rounds == self.options.max_active_set_iterations {
                tally.converged = false;
                break;
            }
            tally.rounds += 1;
            let (tight, n_bonded) = bounding_box(&self.bonded, extent.as_ref());
            if periodic && n_bonded == n {
                let map = self.patterned.then_some(self.tension.view());
                match self.base.full_contact_or_weakest(closed, sigma_c, map) {
                    None => {
                        tally.full = true;
                        break;
                    }
                    Some(weakest) => {
                        self.bonded[weakest] = false;
                        continue;
                    }
                }
            }
            let fingerprint = hash_box(&self.bonded, tight.as_ref());
            let window = self.subgrid_around(tight);
            let cycle = schedule.visit(fingerprint);
            if let Some(t) = tight.filter(|_| !released.is_empty()) {
                self.relaxation.relax(
                    &mut self.base.pressure,
                    &self.bonded,
                    (t.i0, t.j0),
                    &mut released,
                    self.options.preconditioned,
                );
            }
            released.clear();
            let round = CriterionRound {
                exact: schedule.exact,
                level: schedule.level,
                n_bonded,
                window,
            };
            let margins = self.solve_criterion_round(d, round, extent.as_ref(), &mut tally);
            stale = margins.fresh.is_some();
            extent = margins.fresh;
            self.update_gap_after_round(d, margins.fresh);
            if cycle {
                tally.converged = false;
                break;
            }
            let changed = self.judge_criterion(&margins, relaxing, &mut released);
            if schedule.done(changed) {
                break;
            }
        }
        if stale {
            // The step ended on an inexact sub-grid round: bring `K p` and the gap up to date.
            self.refresh_after_inexact_round(d);
        }
        Ok(self.record(d, &tally))
    }

    /// A criterion round's solve: none on an empty set, else an inexact one (returning the
    /// margins its decisions carry and the window where its gap is fresh) or an exact one
    /// (counted in the `tally`'s residual and convergence).
    fn solve_criterion_round(
        &mut self,
        d: f64,
        round: CriterionRound,
        extent: Option<&Window>,
        tally: &mut Tally,
    ) -> CriterionMargins {
        let sigma_c = self.sigma_c;
        let mut margins = CriterionMargins {
            attach_below: 0.0,
            detach: 0.0,
            detach_floor: 0.0,
            fresh: None,
        };
        if round.n_bonded == 0 {
            self.base.pressure.fill(0.0);
            self.base.work.disp.fill(0.0);
        } else if !round.exact {
            // An inexact round: the gap is only brought up to date inside the sub-grid
            // window, so only elements there may attach; the exact round checks them all.
            // Margins scale with the round's tolerance; without adhesion the equilibrium is
            // unique (a convex problem), so no decision needs one.
            let level = round.level;
            let (c, w) = self.solve_set(d, level, false, round.window, extent);
            tally.cg += c.iterations;
            if sigma_c > 0.0 || self.patterned {
                let relative = level / LOOSE_REFERENCE_TOLERANCE;
                margins.attach_below = -LOOSE_ATTACH_MARGIN * level * c.scale;
                let margin = LOOSE_DETACH_MARGIN * relative;
                // Detach where `p < −σ·(1 + margin) − floor`: on a map a floor of the
                // reference's margin, so elements of little γ keep one too.
                let floor = if self.patterned {
                    sigma_c * margin
                } else {
                    0.0
                };
                (margins.detach, margins.detach_floor) = (margin, floor);
            }
            margins.fresh = w;
        } else {
            let tolerance = self.options.cg.tolerance;
            let (c, _) = self.solve_set(d, tolerance, true, round.window, extent);
            tally.cg += c.iterations;
            tally.exact(&c);
        }
        margins
    }

    /// A criterion round's tests: detach every bonded element under tension beyond σ_c (with
    /// the round's margins), attach every free element whose gap is below `attach_below`, in
    /// the window where the gap is fresh; returns whether any changed. With `relaxing` the
    /// detached elements' pressure goes to `released` (cleared there) for the next round.
    fn judge_criterion(
        &mut self,
        margins: &CriterionMargins,
        relaxing: bool,
        released: &mut Vec<Released>,
    ) -> bool {
        // After an inexact sub-grid round only its window can change: every bonded element
        // lies inside it, and only elements there may attach.
        let block = round_block(margins.fresh);
        let (margin, floor, attach_below) =
            (margins.detach, margins.detach_floor, margins.attach_below);
        let tension = self
            .tension
            .broadcast(self.bonded.dim())
            .expect("a 1 × 1 array or the grid's shape");
        let zip = Zip::from(self.bonded.slice_mut(block))
            .and(self.base.pressure.slice_mut(block))
            .and(self.base.gap.slice(block))
            .and(tension.slice(block));
        // Each element's test reads only that element: the split over threads cannot
        // change the outcome. With relaxation a detached element keeps its pressure until
        // `take_released` below collects and clears it.
        let judge = |changed: bool, b: &mut bool, p: &mut f64, &g: &f64, &s: &f64| {
            if *b && *p < -s * (1.0 + margin) - floor {
                *b = false;
                if !relaxing {
                    *p = 0.0;
                }
                true
            } else if !*b && g < attach_below {
                *b = true;
                true
            } else {
                changed
            }
        };
        let changed = if crate::cg::parallel(zip.size()) {
            zip.par_fold(|| false, judge, |a, b| a || b)
        } else {
            zip.fold(false, judge)
        };
        if relaxing && changed {
            let origin = margins.fresh.map_or((0, 0), |w| (w.i0, w.j0));
            *released = take_released(
                self.base.pressure.slice_mut(block),
                self.bonded.slice(block),
                origin,
            );
        }
        changed
    }

    /// After a round's solve: the gap everywhere, or only in the window `fresh` of an inexact
    /// sub-grid round.
    pub(crate) fn update_gap_after_round(&mut self, d: f64, fresh: Option<Window>) {
        match fresh {
            None => self.base.update_gap(d),
            Some(w) => self.base.update_gap_in(d, &w),
        }
    }

    /// A step that ended on an inexact sub-grid round: `K p` and the gap brought up to date on
    /// the whole grid.
    pub(crate) fn refresh_after_inexact_round(&mut self, d: f64) {
        let b = &mut self.base;
        b.op.apply(b.pressure.view(), b.work.disp.view_mut());
        b.update_gap(d);
    }

    /// Non-adhesive cold start (`γ = 0`, nothing bonded): solves the problem on the grid
    /// coarsened 2 × 2 (heights averaged; recursively, while both sides are even and at least
    /// `2 × COARSEST`), then takes its pressure and contact set, injected, as the start of the
    /// fine rounds. The fine rounds end on the fine grid's own exact state; only the work
    /// changes. Returns the CG iterations spent on the coarse grids (in fine-grid units: each
    /// coarse iteration counted as a quarter of the level above).
    fn start_from_coarse(&mut self, d: f64) -> Result<usize, SolverError> {
        let Some((surface, op)) = self.base.coarsened() else {
            return Ok(0);
        };
        let mut coarse = AdhesiveSolver::new(op, &surface, 0.0, 1.0, self.options)?;
        let r = coarse.step(d)?;
        if r.full_contact || r.n_bonded == 0 {
            return Ok(r.cg_iterations.div_ceil(4));
        }
        let (p, b) = (&coarse.base.pressure, &coarse.bonded);
        Zip::indexed(&mut self.base.pressure)
            .and(&mut self.bonded)
            .for_each(|(i, j), q, c| {
                *q = p[[i / 2, j / 2]];
                *c = b[[i / 2, j / 2]];
            });
        Ok(r.cg_iterations.div_ceil(4))
    }

    /// Secant predictor: with an unchanged bonded set the pressure is affine in `d`, so
    /// `p(d) = p₁ + (p₁ − p₀)(d − d₁)/(d₁ − d₀)` is exact and CG only corrects for set changes.
    /// Remembers the current state as the new `(p₀, d₀)`.
    pub(crate) fn predict(&mut self, d: f64) {
        if let Some(d1) = self.last_approach {
            match &mut self.history {
                Some((p0, d0)) if *d0 != d1 => {
                    let t = (d - d1) / (d1 - *d0);
                    Zip::from(&mut self.base.pressure)
                        .and(p0)
                        .and(&self.bonded)
                        .for_each(|p, q, &b| {
                            let p1 = *p;
                            if b {
                                *p += (p1 - *q) * t;
                            }
                            *q = p1;
                        });
                    *d0 = d1;
                }
                _ => self.history = Some((self.base.pressure.clone(), d1)),
            }
        }
        self.last_approach = Some(d);
    }

    /// Solves the bonded (contact) set to `tolerance`, warm-started from the current pressure:
    /// `K_CC p_C = (d − f)_C` under the criterion, and under the Dugdale law the same with the
    /// zone's tension `−σ0` held (`crate::dugdale`). On free grids whose loaded elements fill
    /// little of the grid, the solve runs on the sub-grid `window` around them (the free
    /// operator is exact on any sub-grid, so the linear problem is the same). With `full`,
    /// `work.disp = K p` on the whole grid afterwards (one full-grid product after a sub-grid
    /// solve) and `None` is returned; without it, a sub-grid solve only brings `work.disp` up to
    /// date inside the returned window.
    ///
    /// `window` is the sub-grid ([`Self::subgrid_around`] the loaded set), and `extent` a
    /// window holding every non-zero pressure (`None`: anywhere).
    pub(crate) fn solve_set(
        &mut self,
        d: f64,
        tolerance: f64,
        full: bool,
        window: Option<Window>,
        extent: Option<&Window>,
    ) -> (Convergence, Option<Window>) {
        let cg = SolverOptions {
            tolerance,
            ..self.options.cg
        };
        let pre = self.options.preconditioned;
        let base = &mut self.base;
        // The Dugdale law's zone and tensions (`None`: the criterion).
        let held = self.cohesive.as_ref().map(|c| {
            let tension = self
                .tension
                .broadcast(self.bonded.dim())
                .expect("a 1 × 1 array or the grid's shape");
            (c.zone.view(), tension)
        });
        let Some(window) = window else {
            let c = crate::cg::solve_grid(
                base.op.as_mut(),
                base.surface.heights().view(),
                self.bonded.view(),
                held,
                d,
                base.pressure.view_mut(),
                &mut base.work,
                &mut self.pcg,
                &cg,
                pre,
            );
            return (c, None);
        };
        let shape = window.shape();
        let (dx, e_star) = (base.grid().dx(), base.op.e_star());
        let sub = self
            .boxes
            .get_or_insert_with(shape, || SubProblem::new(shape, dx, e_star));
        sub.load(base, &self.bonded, &window);
        let block = ndarray::s![window.i0..window.i1, window.j0..window.j1];
        let sub_held = match held {
            None => None,
            Some((zone, tension)) => {
                let z = sub
                    .zone
                    .get_or_insert_with(|| Array2::from_elem(shape, false));
                assign(z.view_mut(), zone.slice(block));
                Some((z.view(), tension.slice_move(block)))
            }
        };
        let out = crate::cg::solve_grid(
            &mut sub.op,
            sub.heights.view(),
            sub.bonded.view(),
            sub_held,
            d,
            sub.pressure.view_mut(),
            &mut sub.work,
            &mut sub.pcg,
            &cg,
            pre,
        );
        let fresh = base.adopt_subgrid(
            &window,
            extent,
            sub.pressure.view(),
            sub.work.disp.view(),
            full,
        );
        (out, fresh)
    }

    /// The sub-grid to solve on around the bounding box `tight` of a set: the box grown to the
    /// largest size with the same FFT length (so few distinct sub-operators are built), or
    /// `None` when the set is empty, the grid is periodic, sub-grids are switched off, or the
    /// box's transform would not be clearly cheaper than the grid's.
    pub(crate) fn subgrid_around(&self, tight: Option<Window>) -> Option<Window> {
        let grid = self.base.grid();
        if grid.boundary() != Boundary::Free || !self.options.bonded_subgrid {
            return None;
        }
        let (nx, ny) = grid.shape();
        let Window { i0, i1, j0, j1 } = tight?;
        let grow = |lo: usize, hi: usize, n: usize| {
            let size = (padded_size(hi - lo) / 2).clamp(hi - lo, n);
            let start = lo.min(n - size);
            (start, start + size)
        };
        let (i0, i1) = grow(i0, i1, nx);
        let (j0, j1) = grow(j0, j1, ny);
        // A sub-grid solve adds one full-grid product per round; with several CG iterations per
        // round it pays once its transform is clearly cheaper than the full grid's.
        let cost = |a: usize, b: usize| {
            let m = (padded_size(a) * padded_size(b)) as f64;
            m * m.ln()
        };
        let small = cost(i1 - i0, j1 - j0) < SUBGRID_COST_RATIO * cost(nx, ny);
        small.then_some(Window { i0, i1, j0, j1 })
    }

    /// The step's record at approach `d` from the state and the `tally` of its rounds.
    pub(crate) fn record(&self, d: f64, tally: &Tally) -> StepRecord {
        let Tally {
            cg,
            rounds,
            worst: residual,
            converged,
            full,
        } = *tally;
        let grid = self.base.grid();
        let n_bonded = self.bonded.iter().filter(|&&b| b).count();
        let totals = self.base.totals(n_bonded);
        let zone = self.cohesive_zone();
        let n_cohesive = zone.map_or(0, |z| z.iter().filter(|&&b| b).count());
        let free = grid.boundary() == Boundary::Free;
        StepRecord {
            approach: d,
            force: totals.force,
            mean_pressure: totals.mean_pressure,
            area: totals.area,
            n_bonded,
            n_clusters: count_clusters(&self.bonded, grid.boundary() == Boundary::Periodic),
            cg_iterations: cg,
            active_set_iterations: rounds,
            residual,
            converged,
            full_contact: full,
            edge_contact: free
                && (crate::touches_edge(&self.bonded) || zone.is_some_and(crate::touches_edge)),
            n_cohesive,
        }
    }
}

/// A sub-grid is used when its transform costs less than this fraction of the full grid's.
const SUBGRID_COST_RATIO: f64 = 0.8;

/// The block of a round's tests: the window `fresh` where its gap is up to date (an inexact
/// sub-grid round), or the whole grid.
pub(crate) fn round_block(
    fresh: Option<Window>,
) -> ndarray::SliceInfo<[ndarray::SliceInfoElem; 2], ndarray::Ix2, ndarray::Ix2> {
    match fresh {
        Some(w) => ndarray::s![w.i0..w.i1, w.j0..w.j1],
        None => ndarray::s![.., ..],
    }
}

/// What a criterion round solves: exact or at the inexact `level`, on a set of `n_bonded`
/// elements, on the sub-grid `window` (`None`: the grid).
#[derive(Clone, Copy)]
struct CriterionRound {
    exact: bool,
    level: f64,
    n_bonded: usize,
    window: Option<Window>,
}

/// What a criterion round's solve leaves its tests: detach where
/// `p < −σ·(1 + detach) − detach_floor`, attach where `g < attach_below`, and the window
/// where the gap is fresh (`None`: everywhere).
struct CriterionMargins {
    attach_below: f64,
    detach: f64,
    detach_floor: f64,
    fresh: Option<Window>,
}

/// Deterministic fingerprint of a set from its bounding box `tight` ([`bounding_box`]): the
/// box and the mask inside it, packed into 64-bit words row by row, hashed.
fn hash_box(mask: &Array2<bool>, tight: Option<&Window>) -> u64 {
    let mut h = DefaultHasher::new();
    if let Some(w) = tight {
        (w.i0, w.i1, w.j0, w.j1).hash(&mut h);
        for i in w.i0..w.i1 {
            let row = &mask.row(i).to_slice().expect("standard layout")[w.j0..w.j1];
            pack_into(row, &mut h);
        }
    }
    h.finish()
}

/// Deterministic fingerprint of several masks of one grid (the Dugdale law's two sets) whose
/// `true` elements all lie in the box `tight` (the box of their union, [`bounding_box`]): the
/// box and each mask inside it, packed into 64-bit words row by row, hashed.
pub(crate) fn hash_masks_in(masks: &[&Array2<bool>], tight: Option<&Window>) -> u64 {
    let mut h = DefaultHasher::new();
    if let Some(w) = tight {
        (w.i0, w.i1, w.j0, w.j1).hash(&mut h);
        for mask in masks {
            for i in w.i0..w.i1 {
                let row = &mask.row(i).to_slice().expect("standard layout")[w.j0..w.j1];
                pack_into(row, &mut h);
            }
        }
    }
    h.finish()
}

/// Hashes `bits` packed into 64-bit words.
fn pack_into(bits: &[bool], h: &mut DefaultHasher) {
    for chunk in bits.chunks(64) {
        let word = chunk
            .iter()
            .enumerate()
            .fold(0u64, |w, (k, &b)| w | (u64::from(b) << k));
        word.hash(h);
    }
}

#[cfg(test)]
mod tests;
