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

use std::collections::{HashMap, HashSet};
use std::hash::{DefaultHasher, Hash, Hasher};

use ndarray::{Array2, Zip};
use tack_geometry::{Boundary, Surface, Window};
use tack_kernels::{ElasticOperator, FreeOperator, padded_size};

use crate::cg::{Work, pcg};
use crate::clusters::count_clusters;
use crate::{SolverError, SolverOptions};

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
        }
    }
}

/// What one approach step produced.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepRecord {
    /// Prescribed approach `d` (positive = pressing; periodic: from the deformed mean plane).
    pub approach: f64,
    /// Total normal force `Σ p Δx²` (positive = compressive, negative = adhesive pull).
    pub force: f64,
    /// Force per domain area `Lx·Ly` (the mean pressure of periodic problems).
    pub mean_pressure: f64,
    /// Bonded (in-contact) area, `n_bonded · Δx²`.
    pub area: f64,
    /// Number of bonded elements.
    pub n_bonded: usize,
    /// Number of separate contact clusters (edge-connected).
    pub n_clusters: usize,
    /// Linear CG iterations summed over the step.
    pub cg_iterations: usize,
    /// Detach/attach rounds in the step.
    pub active_set_iterations: usize,
    /// Worst relative CG residual of the step's solves.
    pub residual: f64,
    /// Every solve met its tolerance and the bonded set settled without a cycle.
    pub converged: bool,
    /// Periodic grids: every element bonded (the mean pressure is then the least one that keeps
    /// full contact admissible, see [`AdhesiveSolver::step`]).
    pub full_contact: bool,
    /// Free grids: a bonded element lies on the outer ring of the grid, so the contact may be
    /// cut off by the domain (enlarge the grid or the crop).
    pub edge_contact: bool,
}

/// Quasi-static adhesive contact along an approach path; owns operator, fields and scratch.
pub struct AdhesiveSolver {
    op: Box<dyn ElasticOperator>,
    heights: Array2<f64>,
    sigma_c: f64,
    options: AdhesiveOptions,
    bonded: Array2<bool>,
    pressure: Array2<f64>,
    gap: Array2<f64>,
    work: Work,
    boxes: HashMap<(usize, usize), SubProblem>,
    /// Pressure and approach of the previous step, for the secant predictor.
    history: Option<(Array2<f64>, f64)>,
    last_approach: Option<f64>,
}

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
        options.cg.validate()?;
        if !(gamma.is_finite() && gamma >= 0.0) {
            return Err(SolverError::OutOfRange {
                field: "material.gamma",
                value: gamma,
                allowed: "a finite number ≥ 0",
            });
        }
        if !(kappa.is_finite() && kappa > 0.0) {
            return Err(SolverError::OutOfRange {
                field: "solver.kappa",
                value: kappa,
                allowed: "a finite number > 0",
            });
        }
        if options.max_active_set_iterations == 0 {
            return Err(SolverError::OutOfRange {
                field: "solver.max_active_set_iterations",
                value: 0.0,
                allowed: "an integer ≥ 1",
            });
        }
        let shape = op.grid().shape();
        if surface.grid().shape() != shape {
            return Err(SolverError::GridMismatch {
                surface: surface.grid().shape(),
                operator: shape,
            });
        }
        let sigma_c = (op.e_star() * gamma / (kappa * op.grid().dx())).sqrt();
        let z = Array2::zeros(shape);
        Ok(Self {
            op,
            heights: surface.heights().clone(),
            sigma_c,
            options,
            bonded: Array2::from_elem(shape, false),
            pressure: z.clone(),
            gap: z,
            work: Work::new(shape),
            boxes: HashMap::new(),
            history: None,
            last_approach: None,
        })
    }

    /// The critical tensile stress `σ_c = sqrt(E*γ/(κΔx))` of the detachment criterion.
    pub fn critical_stress(&self) -> f64 {
        self.sigma_c
    }
    /// Current element pressures.
    pub fn pressure(&self) -> &Array2<f64> {
        &self.pressure
    }
    /// Current bonded mask.
    pub fn bonded(&self) -> &Array2<bool> {
        &self.bonded
    }
    /// Current gap `f − d + u` (zero on the bonded set up to the tolerance).
    pub fn gap(&self) -> &Array2<f64> {
        &self.gap
    }
    /// The grid of the problem.
    pub fn grid(&self) -> &tack_geometry::Grid {
        self.op.grid()
    }

    /// Equilibrium at approach `d`, starting from the current bonded set and pressures.
    ///
    /// Periodic grids with every element bonded are handled in closed form: for `d ≥ mean f`
    /// the state is full contact and reports the least mean pressure at which no element's
    /// tension exceeds `σ_c`; for `d < mean f` full contact is impossible (the mean gap is
    /// positive), so the most tensile element of the full-contact field is detached.
    pub fn step(&mut self, approach: f64) -> Result<StepRecord, SolverError> {
        if !approach.is_finite() {
            return Err(SolverError::OutOfRange {
                field: "approach",
                value: approach,
                allowed: "a finite number",
            });
        }
        let d = approach;
        self.predict(d);
        let periodic = self.op.grid().boundary() == Boundary::Periodic;
        let n = self.heights.len();
        let fmean = self.heights.mean().unwrap_or(0.0);
        let (mut cg_total, mut worst, mut converged, mut full) = (0, 0.0f64, true, false);
        let mut visited = HashSet::new();
        let mut rounds = 0;
        // The mean gap f̄ − d is closed: every gap is zero and the only admissible state is full
        // contact (testing it element by element would cycle on round-off).
        let closed = periodic && d >= fmean - 1e-12 * (fmean.abs() + d.abs());
        if closed {
            self.bonded.fill(true);
        }
        loop {
            if rounds == self.options.max_active_set_iterations {
                converged = false;
                break;
            }
            rounds += 1;
            let n_bonded = self.bonded.iter().filter(|&&b| b).count();
            if periodic && n_bonded == n {
                let p_min = self.full_contact_field();
                if closed {
                    self.pressure.mapv_inplace(|p| p - p_min - self.sigma_c);
                    self.gap.fill(0.0);
                    full = true;
                    break;
                }
                let weakest = self.pressure.iter().position(|&p| p == p_min).unwrap_or(0);
                let idx = (
                    weakest / self.heights.ncols(),
                    weakest % self.heights.ncols(),
                );
                self.bonded[idx] = false;
                continue;
            }
            let cycle = !visited.insert(hash_mask(&self.bonded));
            if n_bonded == 0 {
                self.pressure.fill(0.0);
                self.work.disp.fill(0.0);
            } else {
                let (it, res, ok) = self.solve_bonded(d);
                cg_total += it;
                worst = worst.max(res);
                converged &= ok;
            }
            Zip::from(&mut self.gap)
                .and(&self.heights)
                .and(&self.work.disp)
                .for_each(|g, &f, &u| *g = f - d + u);
            if cycle {
                converged = false;
                break;
            }
            let sigma_c = self.sigma_c;
            let mut changed = false;
            Zip::from(&mut self.bonded)
                .and(&mut self.pressure)
                .and(&self.gap)
                .for_each(|b, p, &g| {
                    if *b && *p < -sigma_c {
                        *b = false;
                        *p = 0.0;
                        changed = true;
                    } else if !*b && g < 0.0 {
                        *b = true;
                        changed = true;
                    }
                });
            if !changed {
                break;
            }
        }
        Ok(self.record(d, cg_total, rounds, worst, converged, full))
    }

    /// Secant predictor: with an unchanged bonded set the pressure is affine in `d`, so
    /// `p(d) = p₁ + (p₁ − p₀)(d − d₁)/(d₁ − d₀)` is exact and CG only corrects for set changes.
    /// Remembers the current state as the new `(p₀, d₀)`.
    fn predict(&mut self, d: f64) {
        if let Some(d1) = self.last_approach {
            match &mut self.history {
                Some((p0, d0)) if *d0 != d1 => {
                    let t = (d - d1) / (d1 - *d0);
                    Zip::from(&mut self.pressure)
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
                _ => self.history = Some((self.pressure.clone(), d1)),
            }
        }
        self.last_approach = Some(d);
    }

    /// Fills `pressure` with the zero-mean periodic full-contact field and returns its minimum.
    fn full_contact_field(&mut self) -> f64 {
        let fmean = self.heights.mean().unwrap_or(0.0);
        self.gap.assign(&self.heights.mapv(|f| fmean - f));
        let periodic = self
            .op
            .solve_zero_mean(self.gap.view(), self.pressure.view_mut());
        debug_assert!(periodic);
        self.work.disp.assign(&self.gap);
        self.pressure.iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// Conjugate gradients for `K_CC p_C = (d − f)_C`, warm-started from the current pressure;
    /// leaves `work.disp = K p` on the full grid. On free grids whose bonded set fills little of
    /// the grid, the CG runs on a sub-grid around the bonded set (the free operator is exact on
    /// any sub-grid, so the linear problem is the same) and one full-grid product follows.
    /// Returns (iterations, relative residual, converged).
    fn solve_bonded(&mut self, d: f64) -> (usize, f64, bool) {
        let (cg, pre) = (self.options.cg, self.options.preconditioned);
        let Some(window) = self.bonded_window() else {
            return pcg(
                self.op.as_mut(),
                self.heights.view(),
                self.bonded.view(),
                d,
                self.pressure.view_mut(),
                &mut self.work,
                &cg,
                pre,
            );
        };
        if self.boxes.len() > 16 {
            self.boxes.clear();
        }
        let shape = window.shape();
        let (dx, e_star) = (self.op.grid().dx(), self.op.e_star());
        let sub = self
            .boxes
            .entry(shape)
            .or_insert_with(|| SubProblem::new(shape, dx, e_star));
        let block = ndarray::s![window.i0..window.i1, window.j0..window.j1];
        sub.pressure.assign(&self.pressure.slice(block));
        sub.heights.assign(&self.heights.slice(block));
        sub.bonded.assign(&self.bonded.slice(block));
        let out = pcg(
            &mut sub.op,
            sub.heights.view(),
            sub.bonded.view(),
            d,
            sub.pressure.view_mut(),
            &mut sub.work,
            &cg,
            pre,
        );
        self.pressure.fill(0.0);
        self.pressure.slice_mut(block).assign(&sub.pressure);
        self.op
            .apply(self.pressure.view(), self.work.disp.view_mut());
        out
    }

    /// The sub-grid to solve on: the bonded set's bounding box, grown to the largest size with
    /// the same FFT length (so few distinct sub-operators are built), or `None` when the grid is
    /// periodic, sub-grids are switched off, or the box's transform would not be clearly
    /// cheaper than the grid's.
    fn bonded_window(&self) -> Option<Window> {
        let grid = self.op.grid();
        if grid.boundary() != Boundary::Free || !self.options.bonded_subgrid {
            return None;
        }
        let (nx, ny) = grid.shape();
        let (mut i0, mut i1, mut j0, mut j1) = (usize::MAX, 0, usize::MAX, 0);
        for ((i, j), &b) in self.bonded.indexed_iter() {
            if b {
                (i0, i1, j0, j1) = (i0.min(i), i1.max(i + 1), j0.min(j), j1.max(j + 1));
            }
        }
        if i1 == 0 {
            return None;
        }
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

    fn record(
        &self,
        d: f64,
        cg: usize,
        rounds: usize,
        residual: f64,
        converged: bool,
        full: bool,
    ) -> StepRecord {
        let grid = self.op.grid();
        let force = self.pressure.sum() * grid.element_area();
        let n_bonded = self.bonded.iter().filter(|&&b| b).count();
        StepRecord {
            approach: d,
            force,
            mean_pressure: force / (grid.lx() * grid.ly()),
            area: n_bonded as f64 * grid.element_area(),
            n_bonded,
            n_clusters: count_clusters(&self.bonded, grid.boundary() == Boundary::Periodic),
            cg_iterations: cg,
            active_set_iterations: rounds,
            residual,
            converged,
            full_contact: full,
            edge_contact: grid.boundary() == Boundary::Free && crate::touches_edge(&self.bonded),
        }
    }
}

/// A sub-grid is used when its transform costs less than this fraction of the full grid's.
const SUBGRID_COST_RATIO: f64 = 0.8;

/// Deterministic fingerprint of a bonded set (for cycle detection within one step).
fn hash_mask(mask: &Array2<bool>) -> u64 {
    let mut h = DefaultHasher::new();
    for (k, &b) in mask.iter().enumerate() {
        if b {
            k.hash(&mut h);
        }
    }
    h.finish()
}

/// A bonded-set CG on a sub-grid: its own free operator and buffers.
struct SubProblem {
    op: FreeOperator,
    work: Work,
    pressure: Array2<f64>,
    heights: Array2<f64>,
    bonded: Array2<bool>,
}

impl SubProblem {
    fn new(shape: (usize, usize), dx: f64, e_star: f64) -> Self {
        let grid = tack_geometry::Grid::new(shape.0, shape.1, dx, Boundary::Free)
            .expect("a sub-grid of a valid grid is valid");
        Self {
            op: FreeOperator::new(grid, e_star)
                .expect("the modulus was validated with the operator"),
            work: Work::new(shape),
            pressure: Array2::zeros(shape),
            heights: Array2::zeros(shape),
            bonded: Array2::from_elem(shape, false),
        }
    }
}
