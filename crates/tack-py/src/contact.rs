//! `tack.contact`: frictionless non-adhesive contact of a height array (`ContactSolver`).

use numpy::{IntoPyArray, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use tack::geometry::{Boundary, Grid, Surface};
use tack::solver::{ContactSolver, ContactState, SolverOptions};

use crate::errors::value_error;
use crate::guard::released;

/// Equilibrium of non-adhesive contact at one prescribed approach.
#[pyclass(module = "tack", name = "ContactResult", frozen)]
pub struct ContactResult {
    /// Element pressures (positive = compressive), the shape of the heights.
    #[pyo3(get)]
    pressure: Py<PyArray2<f64>>,
    /// Gap `f − d + u` at every element (zero in contact), the shape of the heights.
    #[pyo3(get)]
    gap: Py<PyArray2<f64>>,
    /// The prescribed approach `d` (positive = pressing).
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
    /// Conjugate-gradient iterations used.
    #[pyo3(get)]
    iterations: usize,
    /// Final relative residual.
    #[pyo3(get)]
    residual: f64,
    /// Whether the stopping rule was met within the iteration cap.
    #[pyo3(get)]
    converged: bool,
    /// Periodic grids: every element in contact (the mean pressure is then the least that
    /// keeps full contact admissible).
    #[pyo3(get)]
    full_contact: bool,
}

#[pymethods]
impl ContactResult {
    fn __repr__(&self) -> String {
        format!(
            "<tack.ContactResult: approach = {:.6e}, force = {:.6e}, area = {:.6e}, converged = \
             {}>",
            self.approach,
            self.force,
            self.area,
            if self.converged { "True" } else { "False" }
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
/// are checked between approaches.
#[pyfunction]
#[pyo3(signature = (heights, *, dx, e_star, approaches, periodic=false, tolerance=None, max_iterations=None, threads=None))]
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
    threads: Option<usize>,
) -> PyResult<Vec<ContactResult>> {
    let pool = tack::engine::thread_pool("threads", threads).map_err(value_error)?;
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
        let grid = Grid::new(nx, ny, dx, boundary).map_err(value_error)?;
        let surface = Surface::new(grid, heights).map_err(value_error)?;
        let op = tack::kernels::operator_for(grid, e_star).map_err(value_error)?;
        let mut solver = ContactSolver::new(op, &surface, options).map_err(value_error)?;
        let mut states = Vec::with_capacity(approaches.len());
        for (k, &d) in approaches.iter().enumerate() {
            if k > 0 {
                Python::attach(|py| py.check_signals())?;
            }
            let state = match &pool {
                Some(pool) => pool.install(|| solver.solve(d)),
                None => solver.solve(d),
            };
            states.push(state.map_err(value_error)?);
        }
        Ok::<_, PyErr>(states)
    })?;
    Ok(states
        .into_iter()
        .map(|s| ContactResult::new(py, s))
        .collect())
}
