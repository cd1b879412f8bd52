//! Free (non-periodic) boundaries: exact discrete convolution by zero-padded FFT (DC-FFT,
//! Liu, Wang & Liu 2000).

use ndarray::{Array2, ArrayView2, ArrayViewMut2};
use tack_geometry::Grid;

use crate::fft2::Fft2;
use crate::love::{SELF_COMPLIANCE, love_rectangle};
use crate::{ElasticOperator, KernelError, check_modulus, stiffness_spectrum};

/// Influence-matrix operator of an infinite half-space loaded only on the grid.
///
/// The Love kernel is sampled at offsets `i·Δx` for `i < n` and `(i − m)·Δx` for `i > m − n` on
/// an `mx × my` grid with `m ≥ 2n − 1` (the next FFT-friendly size); pressure is zero-padded, so
/// the cyclic convolution equals the direct sum `u_i = Σ_j K(x_i − x_j) p_j` exactly (no image
/// interaction).
pub struct FreeOperator {
    grid: Grid,
    e_star: f64,
    /// Kernel spectrum (real: the kernel is even), in the transform's layout.
    kernel_hat: Vec<f64>,
    fft: Fft2,
    /// The preconditioner's spectrum on its own, unpadded transform grid.
    precond_hat: Vec<f64>,
    precond_fft: Fft2,
    /// Displacement of an element's centre per unit pressure on it.
    self_compliance: f64,
}

impl FreeOperator {
    /// Builds the operator for `grid` and effective modulus `e_star` (> 0).
    pub fn new(grid: Grid, e_star: f64) -> Result<Self, KernelError> {
        let e_star = check_modulus(e_star)?;
        let (nx, ny) = grid.shape();
        let dx = grid.dx();
        // Love's coefficient is even in both offsets: evaluate one quadrant, mirror it.
        let quadrant = Array2::from_shape_fn((nx, ny), |(i, j)| {
            love_rectangle(i as f64 * dx, j as f64 * dx, dx / 2.0, dx / 2.0) / e_star
        });
        Ok(Self::from_quadrant(
            grid,
            e_star,
            &quadrant,
            FreeOperator::self_compliance_of(dx, e_star),
            |px, py| stiffness_spectrum(px, py, dx, e_star),
        ))
    }

    /// The displacement of an element's centre per unit pressure on it, for elements of size
    /// `dx` on a half-space of modulus `e_star`: this operator's
    /// [`ElasticOperator::self_compliance`], without building it.
    pub fn self_compliance_of(dx: f64, e_star: f64) -> f64 {
        SELF_COMPLIANCE * dx / e_star
    }

    /// The operator of the even influence coefficients `quadrant[[|i|, |j|]]` (offsets in
    /// elements, the grid's shape) with `self_compliance` and the preconditioner's spectral
    /// stiffness `precond(px, py)` on its own unpadded transform grid: any body whose
    /// coefficients depend on the offset only (the half-space, a layer: `FreeLayerOperator`).
    pub(crate) fn from_quadrant(
        grid: Grid,
        e_star: f64,
        quadrant: &Array2<f64>,
        self_compliance: f64,
        precond: impl FnOnce(usize, usize) -> Array2<f64>,
    ) -> Self {
        let (nx, ny) = grid.shape();
        let (mx, my) = (padded_size(nx), padded_size(ny));
        // |offset| in elements of padded index i, or None in the zero band.
        let offset = |i: usize, n: usize, m: usize| -> Option<usize> {
            if i < n {
                Some(i)
            } else if i > m - n {
                Some(m - i)
            } else {
                None
            }
        };
        let kernel = Array2::from_shape_fn((mx, my), |(i, j)| {
            match (offset(i, nx, mx), offset(j, ny, my)) {
                (Some(ox), Some(oy)) => quadrant[[ox, oy]],
                _ => 0.0,
            }
        });
        let mut fft = Fft2::new(mx, my);
        let spectrum = fft.transform(kernel.view()).mapv(|c| c.re);
        let kernel_hat = fft.prepare_kernel(&spectrum);
        // The preconditioner is only an approximate inverse, so it needs no zero padding: a
        // periodic spectral stiffness on the smallest fast size ≥ n costs about a quarter of
        // the operator's padded transform pair (`cargo xtask bench`, CG iteration table).
        let (px, py) = (fast_size(nx), fast_size(ny));
        let precond_fft = Fft2::new(px, py);
        let precond_hat = precond_fft.prepare_kernel(&precond(px, py));
        Self {
            grid,
            e_star,
            kernel_hat,
            fft,
            precond_hat,
            precond_fft,
            self_compliance,
        }
    }
}

impl ElasticOperator for FreeOperator {
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
    fn precondition(&mut self, displacement: ArrayView2<f64>, pressure: ArrayViewMut2<f64>) {
        self.precond_fft
            .convolve(displacement, &self.precond_hat, pressure);
    }
    fn self_compliance(&self) -> f64 {
        self.self_compliance
    }
}

/// Smallest even `m ≥ 2n − 1` whose prime factors are 2, 3 and 5 (fast FFT sizes).
pub fn padded_size(n: usize) -> usize {
    fast_size((2 * n).max(2) - 1)
}

/// Smallest even `m ≥ n` (and ≥ 2) whose prime factors are 2, 3 and 5.
pub fn fast_size(n: usize) -> usize {
    let smooth = |mut m: usize| {
        for p in [2, 3, 5] {
            while m % p == 0 {
                m /= p;
            }
        }
        m == 1
    };
    let mut m = n.max(2);
    while m % 2 == 1 || !smooth(m) {
        m += 1;
    }
    m
}

#[cfg(test)]
mod tests {
    use super::padded_size;

    #[test]
    fn padded_sizes_are_even_smooth_and_large_enough() {
        assert_eq!(padded_size(1), 2);
        assert_eq!(padded_size(101), 216);
        assert_eq!(padded_size(128), 256);
        for n in 1..300 {
            let m = padded_size(n);
            assert!(
                m >= 2 * n - 1 && m % 2 == 0 && m <= 2 * n + 2 * n / 4 + 2,
                "{n} -> {m}"
            );
        }
    }
}
