//! Elastic half-space operators: Love's influence coefficients and FFT-accelerated maps from
//! element pressures to surface displacements, for free (non-periodic) and periodic boundaries.
//!
//! Both operators implement [`ElasticOperator`]; build the one a grid needs with [`operator_for`].
//! An elastic [`Layer`] on a rigid base has the same two operators, [`FreeLayerOperator`] and
//! [`PeriodicLayerOperator`] (built by [`layer_operator_for`]), whose spectrum is the
//! half-space's times [`layer_compliance_factor`].
//! FFT plans and scratch buffers are allocated once, at construction, except the scratch of each
//! thread's lane, allocated the first time `apply` runs inside a rayon pool of that size; after
//! that `apply` allocates nothing of its own. Nothing in this crate does IO.
//!
//! Pressure is positive when compressive and pushes the surface in (positive displacement).
//! The free operator samples [`love_rectangle`] on a zero-padded grid, so it equals the direct
//! influence-matrix sum to round-off: a uniformly loaded block of elements displaces its centre
//! exactly as Love's formula for the whole block says.
//!
//! ```
//! use tack_geometry::{Boundary, Grid};
//! use tack_kernels::{
//!     ElasticOperator, FreeOperator, SELF_COMPLIANCE, love_rectangle, operator_for,
//! };
//! use ndarray::{Array2, s};
//!
//! let (e_star, dx, p) = (2.0, 0.1, 3.0);
//! let grid = Grid::square(16, dx, Boundary::Free)?;
//! let mut op = FreeOperator::new(grid, e_star)?;
//!
//! // Uniform pressure p on the 5 × 5 elements centred on the origin (element (8, 8)).
//! let mut pressure = Array2::<f64>::zeros(grid.shape());
//! pressure.slice_mut(s![6..11, 6..11]).fill(p);
//! let mut u = Array2::<f64>::zeros(grid.shape());
//! op.apply(pressure.view(), u.view_mut());
//!
//! // The surface moves in everywhere, most at the centre ...
//! assert!(u.iter().all(|&v| v > 0.0));
//! let centre = u[[8, 8]];
//! assert!(u.iter().all(|&v| v <= centre));
//! // ... by Love's displacement for the 0.5 × 0.5 square: the discrete sum is exact.
//! let love = love_rectangle(0.0, 0.0, 2.5 * dx, 2.5 * dx) * p / e_star;
//! assert!((centre - love).abs() < 1e-12 * love);
//! assert_eq!(op.self_compliance(), SELF_COMPLIANCE * dx / e_star);
//!
//! // `operator_for` picks the operator from the grid's boundary kind.
//! let boxed = operator_for(grid.with_boundary(Boundary::Periodic), e_star)?;
//! assert_eq!(boxed.grid().boundary(), Boundary::Periodic);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod fft2;
pub use fft2::Fft2;
mod free;
mod free_layer;
mod layer;
mod love;
mod periodic;
mod periodic_layer;

pub use free::{FreeOperator, fast_size, padded_size};
pub use free_layer::{FreeLayerOperator, gauss_legendre};
pub use layer::{Interface, Layer, layer_compliance_factor};
pub use love::{MEAN_SELF_COMPLIANCE, SELF_COMPLIANCE, love_rectangle};
pub use periodic::PeriodicOperator;
pub use periodic_layer::PeriodicLayerOperator;

use ndarray::{ArrayView2, ArrayViewMut2};
use tack_geometry::{Boundary, Grid};
use thiserror::Error;

/// Invalid operator input.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum KernelError {
    /// The effective modulus is not a finite positive number.
    #[error(
        "{field} = {0} is invalid: must be a finite number > 0",
        field = tack_fields::MATERIAL_E_STAR
    )]
    Modulus(f64),
    /// The layer thickness is not a finite positive number.
    #[error(
        "{field} = {0} is invalid: must be a finite number > 0",
        field = tack_fields::BODY_THICKNESS
    )]
    Thickness(f64),
    /// The layer's Poisson ratio is outside (−1, 0.5].
    #[error(
        "{field} = {0} is invalid: must be a number in (-1, 0.5]",
        field = tack_fields::BODY_POISSON
    )]
    Poisson(f64),
}

/// A linear map from element pressures to element-centre surface displacements of an
/// elastic half-space or layer (positive pressure is compressive and pushes the surface in).
pub trait ElasticOperator: Send {
    /// The grid the operator acts on.
    fn grid(&self) -> &Grid;
    /// The effective modulus `E*`.
    fn e_star(&self) -> f64;
    /// Whether this is the homogeneous half-space of [`ElasticOperator::e_star`]: solvers may
    /// then solve on windows and coarsened grids with half-space operators of their own
    /// (sub-grid CG, cropping, nested starts). Other bodies (a layer) return false, and
    /// solvers keep to the operator's own grid. Required, so a new body says which it is.
    fn is_half_space(&self) -> bool;
    /// `displacement = K · pressure`. Both views have the grid's shape.
    fn apply(&mut self, pressure: ArrayView2<f64>, displacement: ArrayViewMut2<f64>);
    /// Displacement of an element's centre per unit pressure on that element alone.
    fn self_compliance(&self) -> f64;
    /// An approximate inverse for preconditioning: `pressure ≈ K⁻¹ · displacement`, applied as
    /// the spectral stiffness `E*|q|/2` (a layer's: `E*|q|/(2S(|q|h))`; positive definite, the
    /// q = 0 mode gets the smallest non-zero wave number of the transform grid).
    fn precondition(&mut self, displacement: ArrayView2<f64>, pressure: ArrayViewMut2<f64>);
    /// For periodic operators: solve `K p = u` for the zero-mean pressure `p` given a
    /// displacement `u` (its mean is ignored) and return true; other operators return false.
    fn solve_zero_mean(
        &mut self,
        _displacement: ArrayView2<f64>,
        _pressure: ArrayViewMut2<f64>,
    ) -> bool {
        false
    }
}

/// Spectral stiffness `E*|q|/2` on an `mx × my` transform grid of spacing `dx`, in natural
/// half-spectrum layout `(mx, my/2 + 1)`; q = 0 is replaced by the smallest non-zero |q|.
pub(crate) fn stiffness_spectrum(
    mx: usize,
    my: usize,
    dx: f64,
    e_star: f64,
) -> ndarray::Array2<f64> {
    let q = wave_numbers(mx, my, dx);
    let q_min = (2.0 * std::f64::consts::PI / (mx.max(my) as f64 * dx)).min(f64::MAX);
    q.mapv(|q| e_star * q.max(q_min) / 2.0)
}

/// |q| of the half spectrum of an `mx × my` real transform with spacing `dx`.
pub(crate) fn wave_numbers(mx: usize, my: usize, dx: f64) -> ndarray::Array2<f64> {
    let wave = |k: usize, n: usize| {
        let k = if k <= n / 2 {
            k as f64
        } else {
            k as f64 - n as f64
        };
        2.0 * std::f64::consts::PI * k / (n as f64 * dx)
    };
    ndarray::Array2::from_shape_fn((mx, my / 2 + 1), |(i, j)| wave(i, mx).hypot(wave(j, my)))
}

/// Validates `E*` (field `material.e_star`).
pub(crate) fn check_modulus(e_star: f64) -> Result<f64, KernelError> {
    if e_star.is_finite() && e_star > 0.0 {
        Ok(e_star)
    } else {
        Err(KernelError::Modulus(e_star))
    }
}

/// The operator a grid needs: zero-padded DC-FFT for [`Boundary::Free`], spectral for
/// [`Boundary::Periodic`].
pub fn operator_for(grid: Grid, e_star: f64) -> Result<Box<dyn ElasticOperator>, KernelError> {
    Ok(match grid.boundary() {
        Boundary::Free => Box::new(FreeOperator::new(grid, e_star)?),
        Boundary::Periodic => Box::new(PeriodicOperator::new(grid, e_star)?),
    })
}

/// [`operator_for`] for an elastic [`Layer`] on a rigid base (`e_star` is the layer's
/// `E/(1 − ν²)`): [`FreeLayerOperator`] or [`PeriodicLayerOperator`].
pub fn layer_operator_for(
    grid: Grid,
    e_star: f64,
    layer: &Layer,
) -> Result<Box<dyn ElasticOperator>, KernelError> {
    Ok(match grid.boundary() {
        Boundary::Free => Box::new(FreeLayerOperator::new(grid, e_star, *layer)?),
        Boundary::Periodic => Box::new(PeriodicLayerOperator::new(grid, e_star, *layer)?),
    })
}

/// The example of README.md, run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctest;
