//! The adhesive solver: its state, construction and options, and the round loop shared by the
//! laws with sets (`criterion.rs`, `dugdale.rs`): rounds of one linear solve on the loaded set,
//! then every transition that solution calls for, until an exact round changes nothing. The
//! smooth laws run their own Newton iteration (`smooth.rs`).

use ndarray::{Array2, ArrayView2, Zip};
use tack_geometry::{Boundary, Surface, Window};
use tack_kernels::{ElasticOperator, padded_size};

use crate::base::SolverBase;
use crate::cg::{PcgWork, assign};
use crate::clusters::count_clusters;
use crate::criterion::Criterion;
use crate::dugdale::Dugdale;
use crate::law::{Cohesive, Family, JkrLimit, Traction};
use crate::relax::Relaxation;
use crate::rounds::{Round, Rounds, SetRules, Tally};
use crate::smooth::SmoothState;
use crate::state::Convergence;
use crate::subgrid::{SubProblem, SubgridCache};
use crate::viscoelastic::Viscous;
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
    /// Free grids: run CG on a sub-grid around the bonded set when that is much smaller (and
    /// a smooth law's steps, Newton solves and landings on windows of their own, `smooth.rs`).
    pub bonded_subgrid: bool,
    /// Inexact rounds: the CG tolerance of the detach/attach rounds that only have to find
    /// which elements cross the criterion (`None`: every round is solved to `cg.tolerance`).
    /// Such a round detaches only tensions beyond `σ_c (1 + m)` and attaches only gaps below a
    /// margin ([`crate::LOOSE_DETACH_MARGIN`], [`crate::LOOSE_ATTACH_MARGIN`]): a wrong detachment can set off
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
    /// Zero-range law with local relaxation: after an inexact round's detachments are relaxed,
    /// the bonded elements in the relaxed windows whose relaxed tension exceeds
    /// `σ_c (1 + CASCADE_MARGIN)` are released too, and theirs relaxed in turn, for up to
    /// [`crate::CASCADE_GENERATIONS`] generations before the next solve: a front that recedes
    /// by several elements in one step needs fewer rounds. A predicted release is not undone,
    /// so the state reached may differ from the loop without prediction ([`crate::CASCADE_MARGIN`]
    /// and docs/theory.md §3.4 give how far the measured pull-offs moved). Default on; only
    /// with `local_relaxation`.
    pub cascade: bool,
}

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
            cascade: true,
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
    pub(crate) relaxation: Relaxation,
    /// A viscoelastic solid's arms and clock (`None`: elastic).
    pub(crate) visco: Option<Viscous>,
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
        Self::with_law(
            op,
            surface,
            gamma,
            AdhesionLaw::JkrLimit(JkrLimit { kappa }),
            options,
        )
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
        let kappa = match law.family() {
            Family::Criterion { kappa } => kappa,
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
                options.cascade,
            ) = (false, false, false, false);
        }
        let base = SolverBase::new(op, surface)?;
        let shape = base.grid().shape();
        let (base_dx, e_star) = (base.grid().dx(), base.op.e_star());
        // A law made unbound (the smoothed Dugdale law from its scene name) takes this mesh.
        let law = law.on_mesh(gamma, e_star, base_dx);
        let sigma_c = law.peak_tension(gamma, e_star, base_dx);
        let (cohesive, smooth) = match law.family() {
            Family::Criterion { .. } => (None, None),
            Family::Cohesive { sigma0 } => {
                (Some(Cohesive::new(gamma, sigma0, surface, shape)?), None)
            }
            Family::Smooth(_) => {
                law.check(gamma, surface)?;
                let k = base.op.self_compliance();
                let tolerance = law
                    .smooth_tolerance(gamma, e_star, base_dx, k)?
                    .expect("a smooth law");
                let traction = Traction::new(law.clone(), gamma).expect("a smooth law");
                let peak_gap = law.peak_gap().expect("a smooth law");
                let mut state = SmoothState::new(traction, shape, tolerance, peak_gap);
                state.resolved = law
                    .zone_length(e_star, gamma)
                    .is_some_and(|zone| zone >= crate::smooth::RESOLVED_ZONE_ELEMENTS * base_dx);
                (None, Some(state))
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
            visco: None,
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
        let (gamma_ref, law) = (self.reference.0, &self.reference.1);
        let (e_star, dx) = (self.base.op.e_star(), self.base.grid().dx());
        self.tension = gamma.mapv(|g| law.element_tension(g, gamma_ref, e_star, dx));
        if let Some(s) = self.smooth.as_mut() {
            s.weights = Some(gamma.iter().map(|g| g / gamma_ref).collect());
        }
        self.patterned = true;
        Ok(())
    }

    /// Moves the body: the next step (or [`AdhesiveSolver::hold`]) contacts `surface` instead
    /// of the heights before, on the same grid. The solid stays where it is, so a viscoelastic
    /// solid keeps its history: a body translated a little every time step slides (or rolls,
    /// without friction) over it, the way the steady-crack test drives a front at constant
    /// speed (`tests/steady_crack.rs`). The contact state of the last step is the next one's
    /// start; a γ map ([`AdhesiveSolver::set_gamma_map`]) stays where it is, with the solid.
    ///
    /// Errors name `surface`: a surface of another shape, element size or boundary.
    pub fn move_body(&mut self, surface: Surface) -> Result<(), SolverError> {
        let grid = self.base.grid();
        if surface.grid().shape() != grid.shape() {
            return Err(SolverError::MapShape {
                field: "surface",
                map: surface.grid().shape(),
                grid: grid.shape(),
            });
        }
        if surface.grid() != grid {
            return Err(SolverError::Refused {
                field: "surface",
                reason: "the body must be on the solver's grid: the same element size and boundary",
            });
        }
        if let Some(v) = self.visco.as_mut() {
            v.heights.assign(surface.heights());
        }
        self.base.set_surface(surface);
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
    pub fn law(&self) -> &AdhesionLaw {
        &self.reference.1
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
    ///
    /// A viscoelastic solid ([`AdhesiveSolver::set_viscoelastic`]) takes the step in time:
    /// `|Δd|` over the loading or the retraction speed.
    pub fn step(&mut self, approach: f64) -> Result<StepRecord, SolverError> {
        let d = validate::approach(approach)?;
        match &self.visco {
            Some(v) => {
                let dt = v.step_time(self.last_approach, d);
                self.step_in_time(d, dt)
            }
            None => self.step_elastic(d),
        }
    }

    /// The elastic step at the validated approach `d`: the smooth laws' Newton iteration or
    /// the round loop of the laws with sets.
    pub(crate) fn step_elastic(&mut self, d: f64) -> Result<StepRecord, SolverError> {
        if self.smooth.is_some() {
            return Ok(self.step_smooth(d));
        }
        self.predict(d);
        let tally = match self.cohesive.take() {
            Some(state) => {
                let mut rules = Dugdale { state };
                let tally = self.run_rounds(d, &mut rules);
                self.cohesive = Some(rules.state);
                tally
            }
            None => {
                let mut rules = Criterion::new(self);
                self.run_rounds(d, &mut rules)
            }
        }?;
        Ok(self.record(d, &tally))
    }

    /// One approach step of a law with sets (module docs; `d` is validated): rounds of one
    /// solve on the loaded set, then every transition the `rules` find in that solution, until
    /// an exact round changes nothing. A revisited set stops the step as not converged, as does
    /// the round cap ([`AdhesiveOptions::max_active_set_iterations`]).
    pub(crate) fn run_rounds<R: SetRules>(
        &mut self,
        d: f64,
        rules: &mut R,
    ) -> Result<Tally, SolverError> {
        let periodic = self.base.periodic();
        let mut tally = Tally::new();
        let closed = self.base.closed(d);
        if closed {
            self.bonded.fill(true);
        }
        rules.prepare(self, d, closed, &mut tally)?;
        // Inexact rounds until one finds nothing clear, then an exact round on the same set.
        let tolerance = self.options.cg.tolerance;
        let mut schedule = Rounds::new(rules.start(&self.options), tolerance);
        // `work.disp` and the gap are up to date only inside the last inexact round's window.
        let mut stale = false;
        // A window known to hold every loaded element and every non-zero pressure (`None`: the
        // whole grid): after an inexact sub-grid round only its window can have changed, so
        // the next round's bookkeeping scans that instead of the grid.
        let mut extent: Option<Window> = None;
        // The window of the last round's solve when that round met its tolerance and changed
        // nothing: the pressure, the set, `K p` and the CG's direction (on that window) are as
        // it left them. (A solve stopped by the iteration cap is not continued: each round's
        // CG keeps its own cap.)
        let mut quiet: Option<Option<Window>> = None;
        loop {
            if tally.rounds == self.options.max_active_set_iterations {
                tally.converged = false;
                break;
            }
            tally.rounds += 1;
            if periodic && self.bonded.iter().all(|&b| b) {
                // Full contact, with σ_c (σ0) the greatest tension.
                let map = self.patterned.then_some(self.tension.view());
                match self.base.full_contact_or_weakest(closed, self.sigma_c, map) {
                    None => {
                        tally.full = true;
                        break;
                    }
                    Some(weakest) => {
                        self.bonded[weakest] = false;
                        rules.release(weakest);
                        quiet = None;
                        continue;
                    }
                }
            }
            let loaded = rules.loaded(self, extent);
            let window = self.subgrid_around(loaded.tight);
            let cycle = schedule.visit(loaded.fingerprint);
            rules.before_solve(self, loaded.tight);
            let round = Round {
                d,
                exact: schedule.exact,
                level: schedule.level,
                loaded: loaded.count,
                window,
                extent,
                carried: loaded.count > 0 && quiet == Some(window),
            };
            let (fresh, margins) = rules.solve(self, round, &mut tally);
            stale = fresh.is_some();
            extent = fresh;
            self.update_gap_after_round(d, fresh);
            if cycle {
                tally.converged = false;
                break;
            }
            let changed = rules.judge(self, fresh, &margins);
            quiet = (!changed && loaded.count > 0 && tally.solved).then_some(window);
            if schedule.done(changed) {
                break;
            }
        }
        if stale {
            // The step ended on an inexact sub-grid round: bring `K p` and the gap up to date.
            self.refresh_after_inexact_round(d);
        }
        Ok(tally)
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
    ///
    /// The coarse grids are solved only to the inexact rounds' starting tolerance
    /// ([`AdhesiveOptions::round_tolerance`]): the fine grid's first rounds solve to that
    /// tolerance anyway, so a more accurate coarse answer is mostly discarded by the first fine
    /// round. On the 1024² periodic contact of `cargo xtask bench-contact` this takes the
    /// products on the 512² … 32² grids from 327 to 142 (the solve 1.05 → 0.91 s) while the
    /// 1024² grid's stay at 124 (docs/theory.md §3.4).
    pub(crate) fn start_from_coarse(&mut self, d: f64) -> Result<usize, SolverError> {
        let Some((surface, op)) = self.base.coarsened() else {
            return Ok(0);
        };
        let mut options = self.options;
        if let Some(loose) = options.round_tolerance {
            options.cg.tolerance = options.cg.tolerance.max(loose);
        }
        let mut coarse = AdhesiveSolver::new(op, &surface, 0.0, 1.0, options)?;
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
    /// tension of its `zone` held (`crate::dugdale`). On free grids whose loaded elements fill
    /// little of the grid, the solve runs on the sub-grid `window` around them (the free
    /// operator is exact on any sub-grid, so the linear problem is the same). With `full`,
    /// `work.disp = K p` on the whole grid afterwards (one full-grid product after a sub-grid
    /// solve) and `None` is returned; without it, a sub-grid solve only brings `work.disp` up to
    /// date inside the returned window.
    ///
    /// `window` is the sub-grid ([`Self::subgrid_around`] the loaded set), and `extent` a
    /// window holding every non-zero pressure (`None`: anywhere). With `carried` the last
    /// solve was of the same sets, pressure and window and its `K p`, direction and `r·z` are
    /// still held: the solve continues its CG ([`crate::cg::pcg_from`]).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn solve_set(
        &mut self,
        d: f64,
        tolerance: f64,
        full: bool,
        window: Option<Window>,
        extent: Option<&Window>,
        zone: Option<ArrayView2<bool>>,
        carried: bool,
    ) -> (Convergence, Option<Window>) {
        let cg = SolverOptions {
            tolerance,
            ..self.options.cg
        };
        let pre = self.options.preconditioned;
        let base = &mut self.base;
        // The Dugdale law's zone and tensions (`None`: the criterion).
        let held = zone.map(|z| {
            let tension = self
                .tension
                .broadcast(self.bonded.dim())
                .expect("a 1 × 1 array or the grid's shape");
            (z, tension)
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
                carried,
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
            carried,
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
        let small = crate::subgrid::transform_cost((i1 - i0, j1 - j0))
            < SUBGRID_COST_RATIO * crate::subgrid::transform_cost((nx, ny));
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
            ..
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
            time: None,
        }
    }
}

/// A sub-grid is used when its transform costs less than this fraction of the full grid's.
const SUBGRID_COST_RATIO: f64 = 0.8;

#[cfg(test)]
mod tests;
