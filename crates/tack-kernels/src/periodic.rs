//! Periodic boundaries: the spectral half-space kernel `ũ(q) = 2 p̃(q)/(E*|q|)` with the
//! mean (q = 0) mode dropped, so displacements are zero-mean (docs/theory.md §2.3).

use ndarray::{Array2, ArrayView2, ArrayViewMut2};
use tack_geometry::Grid;

use crate::fft2::Fft2;
use crate::{ElasticOperator, KernelError, check_modulus, stiffness_spectrum, wave_numbers};

/// Half-space operator for a grid that is one period of a repeated pattern.
///
/// The mean pressure produces a rigid shift of infinite compliance; it is dropped here and
/// handled by the solver, which measures the approach from the mean plane of the deformed
/// surface.
pub struct PeriodicOperator {
    grid: Grid,
    e_star: f64,
    kernel_hat: Vec<f64>,
    inverse_hat: Vec<f64>,
    precond_hat: Vec<f64>,
    self_compliance: f64,
    fft: Fft2,
}

impl PeriodicOperator {
    /// Builds the operator for `grid` (one period) and effective modulus `e_star` (> 0).
    pub fn new(grid: Grid, e_star: f64) -> Result<Self, KernelError> {
        let e_star = check_modulus(e_star)?;
        let (nx, ny) = grid.shape();
        let q = wave_numbers(nx, ny, grid.dx());
        let kernel_hat = q.mapv(|q| if q > 0.0 { 2.0 / (e_star * q) } else { 0.0 });
        let inverse_hat = q.mapv(|q| e_star * q / 2.0);
        let precond_hat = stiffness_spectrum(nx, ny, grid.dx(), e_star);
        Ok(Self::from_spectra(
            grid,
            e_star,
            &kernel_hat,
            &inverse_hat,
            &precond_hat,
        ))
    }

    /// The operator of the compliance spectrum `kernel_hat` (natural half-spectrum layout, 0 at
    /// q = 0: the mean mode dropped), its inverse on zero-mean fields and the preconditioner's
    /// stiffness: any body whose response is a function of the wave vector (the half-space, a
    /// layer: `PeriodicLayerOperator`).
    pub(crate) fn from_spectra(
        grid: Grid,
        e_star: f64,
        kernel_hat: &Array2<f64>,
        inverse_hat: &Array2<f64>,
        precond_hat: &Array2<f64>,
    ) -> Self {
        let (nx, ny) = grid.shape();
        let fft = Fft2::new(nx, ny);
        // Centre displacement under a unit pressure on one element, minus the dropped mean:
        // the inverse DFT at the origin of the kernel times the element's share 1/N of the load.
        let (mut total, n) = (0.0, (nx * ny) as f64);
        for ((_, j), &k) in kernel_hat.indexed_iter() {
            // Columns 1..ny/2 (excluding a real Nyquist column) stand for two conjugate modes.
            let weight = if j == 0 || (ny % 2 == 0 && j == ny / 2) {
                1.0
            } else {
                2.0
            };
            total += weight * k;
        }
        Self {
            grid,
            e_star,
            kernel_hat: fft.prepare_kernel(kernel_hat),
            inverse_hat: fft.prepare_kernel(inverse_hat),
            precond_hat: fft.prepare_kernel(precond_hat),
            self_compliance: total / n,
            fft,
        }
    }
}

impl ElasticOperator for PeriodicOperator {
    fn is_half_space(&self) -> bool {
        true
    }

    fn grid(&self) -> &Grid {
        &self.grid
    }
    fn e_star(&self) -> f64 {
        self.e_star
    }
    fn apply(&mut self, pressure: ArrayView2<f64>, displacement: ArrayViewMut2<f64>) {
        self.fft.convolve(pressure, &self.kernel_hat, displacement);
    }
    fn self_compliance(&self) -> f64 {
        self.self_compliance
    }
    fn precondition(&mut self, displacement: ArrayView2<f64>, pressure: ArrayViewMut2<f64>) {
        self.fft.convolve(displacement, &self.precond_hat, pressure);
    }
    fn solve_zero_mean(
        &mut self,
        displacement: ArrayView2<f64>,
        pressure: ArrayViewMut2<f64>,
    ) -> bool {
        self.fft.convolve(displacement, &self.inverse_hat, pressure);
        true
    }
}
