//! A height field on a grid: the gap at zero approach, built from shapes and composed by addition.

use ndarray::Array2;

use crate::error::{GeometryError, finite};
use crate::{Grid, Shape};

/// A rectangular block of elements `[i0, i1) × [j0, j1)` of a grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Window {
    /// First row (x index).
    pub i0: usize,
    /// One past the last row.
    pub i1: usize,
    /// First column (y index).
    pub j0: usize,
    /// One past the last column.
    pub j1: usize,
}

impl Window {
    /// Number of elements `(rows, columns)`.
    pub fn shape(&self) -> (usize, usize) {
        (self.i1 - self.i0, self.j1 - self.j0)
    }
}

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

    /// The part of the surface inside `window` (a sub-grid with the same `dx` and boundary).
    pub fn window(&self, window: &Window) -> Result<Surface, GeometryError> {
        let (nx, ny) = self.grid.shape();
        if window.i1 > nx || window.j1 > ny || window.i0 >= window.i1 || window.j0 >= window.j1 {
            return Err(GeometryError::Mismatch(format!(
                "window {window:?} does not lie inside the {nx}×{ny} grid"
            )));
        }
        let grid = Grid::new(
            window.i1 - window.i0,
            window.j1 - window.j0,
            self.grid.dx(),
            self.grid.boundary(),
        )?;
        let heights = self
            .heights
            .slice(ndarray::s![window.i0..window.i1, window.j0..window.j1])
            .to_owned();
        Ok(Surface { grid, heights })
    }

    /// The smallest window holding every element with `height ≤ level`, grown by `pad` elements
    /// on each side (clipped to the grid); `None` if no element qualifies.
    pub fn window_below(&self, level: f64, pad: usize) -> Option<Window> {
        let (nx, ny) = self.grid.shape();
        let (mut i0, mut i1, mut j0, mut j1) = (usize::MAX, 0, usize::MAX, 0);
        for ((i, j), &h) in self.heights.indexed_iter() {
            if h <= level {
                (i0, i1, j0, j1) = (i0.min(i), i1.max(i + 1), j0.min(j), j1.max(j + 1));
            }
        }
        (i1 > 0).then(|| Window {
            i0: i0.saturating_sub(pad),
            i1: (i1 + pad).min(nx),
            j0: j0.saturating_sub(pad),
            j1: (j1 + pad).min(ny),
        })
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
    fn window_below_finds_the_lowest_region() {
        let g = Grid::square(11, 1.0, Boundary::Free).unwrap();
        let s = Surface::from_shape(g, &Sphere::new(1.0).unwrap());
        // Heights (x² + y²)/2 ≤ 2 ⇔ |x|, |y| ≤ 2: rows 3..8 with the centre at 5.
        let w = s.window_below(2.0, 0).unwrap();
        assert_eq!(
            w,
            Window {
                i0: 3,
                i1: 8,
                j0: 3,
                j1: 8
            }
        );
        let w2 = s.window_below(2.0, 10).unwrap();
        assert_eq!(w2.shape(), (11, 11));
        let sub = s.window(&w).unwrap();
        assert_eq!(sub.heights()[[2, 2]], 0.0);
        assert!(s.window_below(-1.0, 0).is_none());
        assert!(
            s.window(&Window {
                i0: 5,
                i1: 12,
                j0: 0,
                j1: 1
            })
            .is_err()
        );
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
