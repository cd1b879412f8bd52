//! `tack.contact`: frictionless non-adhesive contact of a height array (`ContactSolver`).

use numpy::{IntoPyArray, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use tack::fields;
use tack::geometry::{Boundary, Grid, Surface};
use tack::solver::{ContactSolver, ContactState, SolverOptions};

use crate::errors::{Names, value_error, value_error_named};
use crate::guard::released;

/// The fields of the messages of the grid, operator and solver and the arguments of
/// `tack.contact` they stand for.
const CONTACT_NAMES: Names = &[
    (fields::MATERIAL_E_STAR, "e_star"),
    (fields::GRID_NX, "heights.shape[0]"),
    (fields::GRID_NY, "heights.shape[1]"),
    (fields::GRID_DX, "dx"),
    (fields::SOLVER_TOLERANCE, "tolerance"),
    (fields::SOLVER_MAX_ITERATIONS, "max_iterations"),
    (fields::BODY_THICKNESS, "thickness"),
    (fields::BODY_POISSON, "poisson"),
];

/// Equilibrium of non-adhesive contact at one prescribed approach.
#[pyclass(module = "tack", name = "ContactResult", frozen)]
pub struct ContactResult {
    /// Element pressures (positive = compressive), the shape of the heights.
    #[pyo3(get)]
    pressure: Py<PyArray2<f64>>,
    /// Gap `f − d + u` at every element (zero in contact), the shape of the heights.
    #[pyo3(get)]
    gap: Py<PyArray2<f64>>,
    /// The prescribed approach `d` (positive = pressing; periodic grids measure it from the
    /// deformed mean plane, so contact is partial only for `min(heights) < d < mean(heights)`).
    #[pyo3(get)]
    approach: f64,
    /// Total force `Σ p Δx²` (positive = compressive).
    #[pyo3(get)]
    force: f64,
    /// Force over the domain area `Lx·Ly`.
    #[pyo3(get)]
    mean_pressure: f64,
    /// Contact area `n_contact · Δx²`.
    #[pyo3(get)]
    area: f64,
    /// Number of elements in contact.
    #[pyo3(get)]
    n_contact: usize,
    /// Conjugate-gradient iterations used (0 for states known in closed form: nothing touches,
    /// or periodic full contact).
    #[pyo3(get)]
    iterations: usize,
    /// Final relative residual.
    #[pyo3(get)]
    residual: f64,
    /// Whether the stopping rule was met within the iteration cap.
    #[pyo3(get)]
    converged: bool,
    /// Periodic grids only (always False on free grids): `approach >= mean(heights)`, every
    /// gap closed. The approach then no longer sets the load: the state is the one in which
    /// contact has just become full, with the least mean pressure that keeps every element
    /// compressive (its least element pressure is 0), the same for every approach beyond
    /// `mean(heights)`, computed in closed form (`iterations = 0`).
    #[pyo3(get)]
    full_contact: bool,
}

#[pymethods]
impl ContactResult {
    fn __repr__(&self) -> String {
        let flag = |b: bool| if b { "True" } else { "False" };
        format!(
            "<tack.ContactResult: approach = {:.6e}, force = {:.6e}, area = {:.6e}, converged = \
             {}, full_contact = {}>",
            self.approach,
            self.force,
            self.area,
            flag(self.converged),
            flag(self.full_contact)
        )
    }
}

impl ContactResult {
    fn new(py: Python<'_>, s: ContactState) -> Self {
        Self {
            pressure: s.pressure.into_pyarray(py).unbind(),
            gap: s.gap.into_pyarray(py).unbind(),
            approach: s.approach,
            force: s.force,
            mean_pressure: s.mean_pressure,
            area: s.area,
            n_contact: s.n_contact,
            iterations: s.iterations,
            residual: s.residual,
            converged: s.converged,
            full_contact: s.full_contact,
        }
    }
}

/// Solves non-adhesive contact of `heights` at each approach in turn (warm-started) on
/// `threads` threads (default: every core; results are the same bits on any count); signals
/// are checked between approaches. With `thickness` the body is an elastic layer of that
/// thickness and Poisson ratio `poisson` on a rigid base (`interface`: `"bonded"`, the
/// default, or `"frictionless"`), `e_star` its `E/(1 − ν²)`; without, a half-space.
#[pyfunction]
#[pyo3(signature = (heights, *, dx, e_star, approaches, periodic=false, tolerance=None, max_iterations=None, threads=None, thickness=None, poisson=None, interface=None))]
#[allow(clippy::too_many_arguments)]
pub fn contact(
    py: Python<'_>,
    heights: PyReadonlyArray2<'_, f64>,
    dx: f64,
    e_star: f64,
    approaches: Vec<f64>,
    periodic: bool,
    tolerance: Option<f64>,
    max_iterations: Option<usize>,
    threads: Option<i64>,
    thickness: Option<f64>,
    poisson: Option<f64>,
    interface: Option<String>,
) -> PyResult<Vec<ContactResult>> {
    let threads = crate::run::check_threads(threads)?;
    let layer = crate::body::layer_of(thickness, poisson, interface.as_deref())?;
    let pool = tack::engine::thread_pool("threads", threads).map_err(value_error)?;
    let named = |e: &dyn std::fmt::Display| value_error_named(e, CONTACT_NAMES);
    let heights = heights.as_array().to_owned();
    if let Some(((i, j), h)) = heights.indexed_iter().find(|(_, h)| !h.is_finite()) {
        return Err(value_error(format!(
            "heights[{i}, {j}] = {h} is invalid: must be a finite number"
        )));
    }
    let defaults = SolverOptions::default();
    let options = SolverOptions {
        tolerance: tolerance.unwrap_or(defaults.tolerance),
        max_iterations: max_iterations.unwrap_or(defaults.max_iterations),
    };
    let boundary = if periodic {
        Boundary::Periodic
    } else {
        Boundary::Free
    };
    let states = released(py, move || {
        let (nx, ny) = heights.dim();
        let grid = Grid::new(nx, ny, dx, boundary).map_err(|e| named(&e))?;
        let surface = Surface::new(grid, heights).map_err(|e| named(&e))?;
        let op = match &layer {
            Some(layer) => tack::kernels::layer_operator_for(grid, e_star, layer),
            None => tack::kernels::operator_for(grid, e_star),
        }
        .map_err(|e| named(&e))?;
        let mut solver = ContactSolver::new(op, &surface, options).map_err(|e| named(&e))?;
        let mut states = Vec::with_capacity(approaches.len());
        for (k, &d) in approaches.iter().enumerate() {
            if k > 0 {
                Python::attach(|py| py.check_signals())?;
            }
            let state = match &pool {
                Some(pool) => pool.install(|| solver.solve(d)),
                None => solver.solve(d),
            };
            states.push(state.map_err(|e| named(&e))?);
        }
        Ok::<_, PyErr>(states)
    })?;
    Ok(states
        .into_iter()
        .map(|s| ContactResult::new(py, s))
        .collect())
}
