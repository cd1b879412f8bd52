//! Periodic boundaries on an elastic layer: the spectral kernel `ũ(q) = S(qh)·2p̃(q)/(E*|q|)`
//! with the mean (q = 0) mode dropped, as for the half-space (docs/theory.md §2.5).

use ndarray::{Array2, ArrayView2, ArrayViewMut2};
use tack_geometry::Grid;

use crate::layer::Layer;
use crate::{ElasticOperator, KernelError, PeriodicOperator, check_modulus, wave_numbers};

/// Layer operator for a grid that is one period of a repeated pattern: the half-space's
/// [`crate::PeriodicOperator`] with its spectrum `2/(E*|q|)` multiplied by the layer's
/// [`crate::layer_compliance_factor`]`(|q|h)` at every wave vector of the grid.
///
/// The mean mode: a uniform pressure `p̄` on a layer displaces it by the finite
/// `p̄ ·` [`Self::mean_compliance`] (uniaxial strain), unlike the half-space. The operator still
/// drops it, so displacements are zero-mean and the solvers' convention (the approach measured
/// from the mean plane of the deformed surface, [`ElasticOperator::solve_zero_mean`]) holds
/// unchanged; a caller that wants the approach from the rigid base adds
/// `p̄ · mean_compliance()`. Keeping the mode would make the operator the physical one, but then
/// `solve_zero_mean` would no longer be the inverse on zero-mean fields for a frictionless
/// base, whose mean compliance is not the k → 0 limit of its spectrum.
pub struct PeriodicLayerOperator {
    /// The spectral operator of the layer's compliance.
    inner: PeriodicOperator,
    e_star: f64,
    layer: Layer,
}

/// The layer's spectral stiffness `E*|q|/(2S(|q|h))` on an `mx × my` transform grid of spacing
/// `dx`, natural half-spectrum layout; q = 0 gets the smallest non-zero |q| (positive definite).
pub(crate) fn layer_stiffness_spectrum(
    mx: usize,
    my: usize,
    dx: f64,
    e_star: f64,
    layer: &Layer,
) -> Array2<f64> {
    let q_min = 2.0 * std::f64::consts::PI / (mx.max(my) as f64 * dx);
    wave_numbers(mx, my, dx).mapv(|q| 1.0 / layer.compliance(q.max(q_min), e_star))
}

impl PeriodicLayerOperator {
    /// Builds the operator for `grid` (one period), the layer's `e_star = E/(1 − ν²)` (> 0)
    /// and `layer` (checked: [`Layer::check`]).
    pub fn new(grid: Grid, e_star: f64, layer: Layer) -> Result<Self, KernelError> {
        let e_star = check_modulus(e_star)?;
        layer.check()?;
        let (nx, ny) = grid.shape();
        let q = wave_numbers(nx, ny, grid.dx());
        let kernel_hat = q.mapv(|q| {
            if q > 0.0 {
                layer.compliance(q, e_star)
            } else {
                0.0
            }
        });
        let inverse_hat = kernel_hat.mapv(|k| if k > 0.0 { 1.0 / k } else { 0.0 });
        let precond_hat = layer_stiffness_spectrum(nx, ny, grid.dx(), e_star, &layer);
        let inner =
            PeriodicOperator::from_spectra(grid, e_star, &kernel_hat, &inverse_hat, &precond_hat);
        Ok(Self {
            inner,
            e_star,
            layer,
        })
    }

    /// The layer.
    pub fn layer(&self) -> &Layer {
        &self.layer
    }

    /// Displacement of the dropped mean mode per unit mean pressure:
    /// [`Layer::uniform_compliance`] (0 for an incompressible layer).
    pub fn mean_compliance(&self) -> f64 {
        self.layer.uniform_compliance(self.e_star)
    }
}

impl ElasticOperator for PeriodicLayerOperator {
    fn is_half_space(&self) -> bool {
        false
    }

    fn grid(&self) -> &Grid {
        self.inner.grid()
    }
    fn e_star(&self) -> f64 {
        self.e_star
    }
    fn apply(&mut self, pressure: ArrayView2<f64>, displacement: ArrayViewMut2<f64>) {
        self.inner.apply(pressure, displacement);
    }
    fn self_compliance(&self) -> f64 {
        self.inner.self_compliance()
    }
    fn precondition(&mut self, displacement: ArrayView2<f64>, pressure: ArrayViewMut2<f64>) {
        self.inner.precondition(displacement, pressure);
    }
    fn solve_zero_mean(
        &mut self,
        displacement: ArrayView2<f64>,
        pressure: ArrayViewMut2<f64>,
    ) -> bool {
        self.inner.solve_zero_mean(displacement, pressure)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layer::Interface;
    use crate::{PeriodicOperator, layer_compliance_factor};
    use tack_geometry::Boundary;

    fn layer(h: f64, nu: f64, interface: Interface) -> Layer {
        Layer {
            thickness: h,
            poisson: nu,
            interface,
        }
    }

    #[test]
    fn a_cosine_mode_is_scaled_by_the_factor() {
        // p = cos(2π m x/L) on a 64 × 8 period: u = S(kh)·2/(E*k)·cos to round-off.
        let (n, dx, e_star) = (64, 0.1, 2.5);
        let grid = Grid::new(n, 8, dx, Boundary::Periodic).unwrap();
        let mut worst: f64 = 0.0;
        for interface in [Interface::Bonded, Interface::Frictionless] {
            for nu in [-0.9, 0.0, 0.3, 0.49, 0.5] {
                for m in [1usize, 3, 10] {
                    let k = 2.0 * std::f64::consts::PI * m as f64 / (n as f64 * dx);
                    for kh in [0.01, 0.1, 1.0, 10.0, 100.0] {
                        let l = layer(kh / k, nu, interface);
                        let mut op = PeriodicLayerOperator::new(grid, e_star, l).unwrap();
                        let p = Array2::from_shape_fn((n, 8), |(i, _)| (k * i as f64 * dx).cos());
                        let mut u = Array2::zeros((n, 8));
                        op.apply(p.view(), u.view_mut());
                        let c = layer_compliance_factor(kh, nu, interface) * 2.0 / (e_star * k);
                        let err = u
                            .iter()
                            .zip(&p)
                            .fold(0.0f64, |e, (u, p)| e.max((u - c * p).abs()))
                            / c;
                        worst = worst.max(err);
                        assert!(err < 1e-12, "{interface:?} ν {nu} kh {kh} m {m}: {err}");
                        // solve_zero_mean inverts it.
                        let mut back = Array2::zeros((n, 8));
                        assert!(op.solve_zero_mean(u.view(), back.view_mut()));
                        let inv = back
                            .iter()
                            .zip(&p)
                            .fold(0.0f64, |e, (b, p)| e.max((b - p).abs()));
                        assert!(inv < 1e-11, "{interface:?} ν {nu} kh {kh} m {m}: {inv}");
                    }
                }
            }
        }
        eprintln!("periodic layer, cosine modes: worst relative error {worst:e}");
    }

    #[test]
    fn the_mean_is_dropped_and_reported() {
        let grid = Grid::square(16, 0.5, Boundary::Periodic).unwrap();
        let l = layer(0.7, 0.3, Interface::Bonded);
        let mut op = PeriodicLayerOperator::new(grid, 2.0, l).unwrap();
        let p = Array2::from_elem((16, 16), 1.0);
        let mut u = Array2::from_elem((16, 16), 9.0);
        op.apply(p.view(), u.view_mut());
        assert!(u.iter().all(|v| v.abs() < 1e-15));
        let expected = 0.7 * (1.0 - 0.6) / (2.0 * 0.49);
        assert!((op.mean_compliance() - expected).abs() < 1e-15);
    }

    #[test]
    fn thick_layers_are_the_half_space() {
        let grid = Grid::square(32, 0.1, Boundary::Periodic).unwrap();
        let mut half = PeriodicOperator::new(grid, 1.5).unwrap();
        // Smallest |q| = 2π/3.2 ≈ 1.96; h = 20 puts every mode at qh > 39: 1 − S < 1e-30.
        let mut thick =
            PeriodicLayerOperator::new(grid, 1.5, layer(20.0, 0.3, Interface::Bonded)).unwrap();
        let p = Array2::from_shape_fn((32, 32), |(i, j)| ((i * 7 + j * 3) % 11) as f64 - 5.0);
        let (mut a, mut b) = (Array2::zeros((32, 32)), Array2::zeros((32, 32)));
        half.apply(p.view(), a.view_mut());
        thick.apply(p.view(), b.view_mut());
        let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(a.iter().zip(&b).all(|(a, b)| (a - b).abs() < 1e-14 * scale));
        assert!((half.self_compliance() - thick.self_compliance()).abs() < 1e-14);
    }

    #[test]
    fn rejects_bad_layers() {
        let grid = Grid::square(4, 1.0, Boundary::Periodic).unwrap();
        assert!(PeriodicLayerOperator::new(grid, 1.0, layer(0.0, 0.3, Interface::Bonded)).is_err());
        assert!(PeriodicLayerOperator::new(grid, 1.0, layer(1.0, 0.6, Interface::Bonded)).is_err());
    }
}
