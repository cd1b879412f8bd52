//! A height field on a grid: the gap at zero approach, built from shapes and composed by addition.

use ndarray::Array2;

use crate::error::{GeometryError, finite};
use crate::{Grid, Shape};

/// Heights `f` of the rigid body, one per element of a [`Grid`].
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    grid: Grid,
    heights: Array2<f64>,
}

impl Surface {
    /// Wraps a height array; its shape must be `(nx, ny)` and every height finite.
    pub fn new(grid: Grid, heights: Array2<f64>) -> Result<Self, GeometryError> {
        if heights.dim() != grid.shape() {
            return Err(GeometryError::Mismatch(format!(
                "heights have shape {:?} but the grid is {:?}",
                heights.dim(),
                grid.shape()
            )));
        }
        for &h in &heights {
            finite("surface.heights", h)?;
        }
        Ok(Self { grid, heights })
    }

    /// A flat surface (all heights zero).
    pub fn flat(grid: Grid) -> Self {
        Self {
            grid,
            heights: Array2::zeros(grid.shape()),
        }
    }

    /// Samples a shape at every element centre.
    pub fn from_shape(grid: Grid, shape: &dyn Shape) -> Self {
        let heights =
            Array2::from_shape_fn(grid.shape(), |(i, j)| shape.height(grid.x(i), grid.y(j)));
        Self { grid, heights }
    }

    /// The grid the heights live on.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }
    /// The heights, shape `(nx, ny)`.
    pub fn heights(&self) -> &Array2<f64> {
        &self.heights
    }
    /// Consumes the surface, returning the height array.
    pub fn into_heights(self) -> Array2<f64> {
        self.heights
    }

    /// Adds another surface on the same grid (macro shape + roughness).
    pub fn add(&mut self, other: &Surface) -> Result<(), GeometryError> {
        if other.grid.shape() != self.grid.shape() || other.grid.dx() != self.grid.dx() {
            return Err(GeometryError::Mismatch(format!(
                "cannot add a {:?} surface with dx = {} to a {:?} surface with dx = {}",
                other.grid.shape(),
                other.grid.dx(),
                self.grid.shape(),
                self.grid.dx()
            )));
        }
        self.heights += &other.heights;
        Ok(())
    }

    /// Adds a shape sampled on this surface's grid.
    pub fn add_shape(&mut self, shape: &dyn Shape) {
        let g = self.grid;
        for ((i, j), h) in self.heights.indexed_iter_mut() {
            *h += shape.height(g.x(i), g.y(j));
        }
    }

    /// Lowest height.
    pub fn min(&self) -> f64 {
        self.heights.iter().copied().fold(f64::INFINITY, f64::min)
    }
    /// Highest height.
    pub fn max(&self) -> f64 {
        self.heights
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max)
    }
    /// Mean height.
    pub fn mean(&self) -> f64 {
        self.heights.iter().sum::<f64>() / self.grid.len() as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Boundary, Sphere};

    #[test]
    fn sphere_surface_has_apex_at_origin_and_composes() {
        let g = Grid::new(5, 4, 0.1, Boundary::Free).unwrap();
        let mut s = Surface::from_shape(g, &Sphere::new(1.0).unwrap());
        assert_eq!(s.heights()[[2, 2]], 0.0);
        assert_eq!(s.min(), 0.0);
        let before = s.max();
        s.add_shape(&Sphere::new(1.0).unwrap());
        assert!((s.max() - 2.0 * before).abs() < 1e-15);
        let other = Surface::flat(Grid::new(4, 4, 0.1, Boundary::Free).unwrap());
        assert!(s.add(&other).is_err());
    }

    #[test]
    fn sphere_plus_2d_waviness_is_eq_6_by_composition() {
        let g = Grid::square(9, 0.05, Boundary::Free).unwrap();
        let (r, h, lambda) = (2.0, 0.01, 0.1);
        let mut s = Surface::from_shape(g, &Sphere::new(r).unwrap());
        s.add_shape(&crate::Waviness2d::new(h, lambda).unwrap());
        for ((i, j), &f) in s.heights().indexed_iter() {
            let (x, y) = (g.x(i), g.y(j));
            let k = std::f64::consts::TAU / lambda;
            let eq6 = (x * x + y * y) / (2.0 * r) + h * (1.0 - (k * x).cos() * (k * y).cos());
            assert!((f - eq6).abs() < 1e-15, "({i}, {j})");
        }
    }

    #[test]
    fn rejects_nan_heights_and_wrong_shape() {
        let g = Grid::square(2, 1.0, Boundary::Free).unwrap();
        let mut h = Array2::zeros((2, 2));
        h[[0, 1]] = f64::NAN;
        assert!(
            Surface::new(g, h)
                .unwrap_err()
                .to_string()
                .contains("surface.heights")
        );
        assert!(Surface::new(g, Array2::zeros((3, 2))).is_err());
    }
}
