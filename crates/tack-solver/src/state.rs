//! The records of solves: the non-adhesive [`ContactState`], the adhesive [`StepRecord`], and the
//! integrals and convergence report both are built from.

use ndarray::Array2;
use tack_geometry::Grid;

/// Equilibrium at one prescribed approach.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactState {
    /// Prescribed approach `d` (positive = pressing).
    pub approach: f64,
    /// Element pressures (positive = compressive).
    pub pressure: Array2<f64>,
    /// Gap `f − d + u` at every element (zero in contact up to the tolerance).
    pub gap: Array2<f64>,
    /// Total normal force `Σ p Δx²` (positive = compressive).
    pub force: f64,
    /// Mean pressure over the whole grid, `force / (Lx·Ly)`.
    pub mean_pressure: f64,
    /// Number of elements in contact.
    pub n_contact: usize,
    /// Contact area, `n_contact · Δx²`.
    pub area: f64,
    /// Conjugate-gradient iterations used.
    pub iterations: usize,
    /// Final rms residual relative to the displacement scale.
    pub residual: f64,
    /// Whether the stopping rule was met within the caps.
    pub converged: bool,
    /// Periodic grids only: every element is in contact. The mean pressure is then not fixed by
    /// the approach; the state reports the least mean pressure that keeps full contact admissible.
    pub full_contact: bool,
}

/// What one approach step of the [`AdhesiveSolver`](crate::AdhesiveSolver) produced.
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
    /// Linear CG iterations summed over the step; under a smooth law, the operator products of
    /// Newton's Krylov solves, its line search and the landings' CG iterations.
    pub cg_iterations: usize,
    /// Detach/attach rounds in the step.
    pub active_set_iterations: usize,
    /// Worst relative CG residual of the step's solves; under a smooth law, the worst
    /// complementarity residual as a fraction of the peak tension, where the step ended
    /// (converged or not).
    pub residual: f64,
    /// Every solve met its tolerance and the bonded set settled without a cycle.
    pub converged: bool,
    /// Periodic grids: every element bonded (the mean pressure is then the least one that keeps
    /// full contact admissible, see [`AdhesiveSolver::step`](crate::AdhesiveSolver::step)).
    pub full_contact: bool,
    /// Free grids: a bonded element lies on the outer ring of the grid, so the contact may be
    /// cut off by the domain (enlarge the grid or the crop). Under the Dugdale law a cohesive
    /// element there counts too.
    pub edge_contact: bool,
    /// Elements of the law's zone ahead of the contact, the values of its
    /// [`Law::step_column`](crate::Law::step_column): the Dugdale law's cohesive zone (out of
    /// contact, carrying σ0), a smooth law's process zone (out of contact, tension beyond 1% of
    /// the peak); always 0 under the zero-range criterion.
    pub n_cohesive: usize,
    /// The time at the end of the step on a viscoelastic solid
    /// ([`AdhesiveSolver::set_viscoelastic`](crate::AdhesiveSolver::set_viscoelastic)), `None`
    /// on an elastic one.
    pub time: Option<f64>,
}

/// The integrals of a pressure field that both records carry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Totals {
    /// `Σ p Δx²`.
    pub(crate) force: f64,
    /// `force / (Lx·Ly)`.
    pub(crate) mean_pressure: f64,
    /// Elements in contact (bonded), as counted by the caller.
    pub(crate) n_contact: usize,
    /// `n_contact · Δx²`.
    pub(crate) area: f64,
}

impl Totals {
    pub(crate) fn new(grid: &Grid, pressure: &Array2<f64>, n_contact: usize) -> Self {
        let force = pressure.sum() * grid.element_area();
        Self {
            force,
            mean_pressure: force / (grid.lx() * grid.ly()),
            n_contact,
            area: n_contact as f64 * grid.element_area(),
        }
    }
}

/// How an iterative solve ended: iterations used, final relative residual, whether the stopping
/// rule was met within the cap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Convergence {
    pub(crate) iterations: usize,
    pub(crate) residual: f64,
    pub(crate) converged: bool,
    /// The displacement scale the residual is relative to (0 when nothing was solved).
    pub(crate) scale: f64,
}

impl Convergence {
    /// A state known exactly, without iterating (nothing touches, periodic full contact).
    pub(crate) const EXACT: Self = Self {
        iterations: 0,
        residual: 0.0,
        converged: true,
        scale: 0.0,
    };
}
