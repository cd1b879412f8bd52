//! The outcome of one contact solve: fields, integral quantities and convergence report.

use ndarray::Array2;

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
