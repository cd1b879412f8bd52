//! The computational grid: element counts, spacing and boundary kind, with element-centre coordinates.

use tack_fields as fields;

use crate::error::{GeometryError, positive};

/// Largest number of elements along one axis (keeps padded FFT sizes and memory sane).
pub const MAX_ELEMENTS_PER_AXIS: usize = 1 << 16;

/// How the elastic half-space behaves at the edge of the grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Boundary {
    /// Non-periodic: the half-space is infinite and unloaded outside the grid.
    Free,
    /// Periodic: the grid is one period of an infinitely repeated pattern.
    Periodic,
}

/// A rectangular grid of `nx × ny` square elements of side `dx`.
///
/// Element `(i, j)` has its centre at `x = (i − ⌊nx/2⌋)·dx`, `y = (j − ⌊ny/2⌋)·dx`, so the
/// origin is always an element centre (the sphere apex, the crest of a waviness).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    nx: usize,
    ny: usize,
    dx: f64,
    boundary: Boundary,
}

impl Grid {
    /// Builds a validated grid: `nx, ny ≥ 1` (at most [`MAX_ELEMENTS_PER_AXIS`]) and a finite `dx > 0`.
    pub fn new(nx: usize, ny: usize, dx: f64, boundary: Boundary) -> Result<Self, GeometryError> {
        for (field, n) in [(fields::GRID_NX, nx), (fields::GRID_NY, ny)] {
            if n == 0 || n > MAX_ELEMENTS_PER_AXIS {
                return Err(GeometryError::BadCount {
                    field,
                    value: n,
                    allowed: "an integer in 1..=65536",
                });
            }
        }
        positive(fields::GRID_DX, dx)?;
        Ok(Self {
            nx,
            ny,
            dx,
            boundary,
        })
    }

    /// A square `n × n` grid.
    pub fn square(n: usize, dx: f64, boundary: Boundary) -> Result<Self, GeometryError> {
        Self::new(n, n, dx, boundary)
    }

    /// Elements along x (first array axis).
    pub fn nx(&self) -> usize {
        self.nx
    }
    /// Elements along y (second array axis).
    pub fn ny(&self) -> usize {
        self.ny
    }
    /// Element side length.
    pub fn dx(&self) -> f64 {
        self.dx
    }
    /// Boundary kind.
    pub fn boundary(&self) -> Boundary {
        self.boundary
    }
    /// `(nx, ny)`, the shape of every field on this grid.
    pub fn shape(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }
    /// Total number of elements.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }
    /// Always false: a valid grid has at least one element.
    pub fn is_empty(&self) -> bool {
        false
    }
    /// Area of one element, `dx²`.
    pub fn element_area(&self) -> f64 {
        self.dx * self.dx
    }
    /// Domain length along x, `nx·dx`.
    pub fn lx(&self) -> f64 {
        self.nx as f64 * self.dx
    }
    /// Domain length along y, `ny·dx`.
    pub fn ly(&self) -> f64 {
        self.ny as f64 * self.dx
    }
    /// x coordinate of the centre of element column `i`.
    pub fn x(&self, i: usize) -> f64 {
        (i as f64 - (self.nx / 2) as f64) * self.dx
    }
    /// y coordinate of the centre of element row `j`.
    pub fn y(&self, j: usize) -> f64 {
        (j as f64 - (self.ny / 2) as f64) * self.dx
    }
    /// The same grid with another boundary kind.
    pub fn with_boundary(&self, boundary: Boundary) -> Self {
        Self { boundary, ..*self }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_sizes_naming_the_field() {
        let e = Grid::new(0, 4, 1.0, Boundary::Free).unwrap_err();
        assert!(e.to_string().contains("grid.nx"), "{e}");
        for dx in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = Grid::new(4, 4, dx, Boundary::Free).unwrap_err();
            assert!(e.to_string().contains("grid.dx"), "{e}");
        }
    }

    #[test]
    fn origin_is_an_element_centre() {
        for n in [1, 4, 5] {
            let g = Grid::square(n, 0.5, Boundary::Periodic).unwrap();
            assert_eq!(g.x(n / 2), 0.0);
            assert_eq!(g.y(n / 2), 0.0);
            assert_eq!(g.lx(), n as f64 * 0.5);
        }
    }
}
