//! Cropping a free-boundary problem to the elements that can ever touch.
//!
//! On free boundaries the operator is exact for any sub-grid, and elements that never bond
//! carry no pressure, so solving on a window that holds every element that can touch gives the
//! same discrete problem at a fraction of the cost. Periodic problems are never cropped.

use ndarray::Array2;
use tack_geometry::{Boundary, Surface, Window};

/// The window of a free-boundary `surface` where contact can occur up to `max_approach`.
///
/// An element can touch only where its rigid gap at the deepest approach, `f − d_max`, is
/// smaller than what can close it: the roughness range `roughness_range` (heights of the
/// roughness alone, max − min) plus the adhesive reach `sqrt(2πγℓ/E*)`. For a JKR contact of
/// radius a the edge sits at `f − d = (s − d)/2 < s/2` with `s = sqrt(2πγa/E*)`; the reach uses
/// ℓ = the half-diagonal of the region `f ≤ d_max + roughness_range` (an upper bound on the
/// contact radius) and no factor ½, so it over-covers by at least 2×. The window is padded by
/// two elements. Returns `None` for periodic grids (no cropping) or when nothing can touch.
pub fn contact_window(
    surface: &Surface,
    max_approach: f64,
    roughness_range: f64,
    e_star: f64,
    gamma: f64,
) -> Option<Window> {
    let grid = surface.grid();
    if grid.boundary() == Boundary::Periodic {
        return None;
    }
    let geometric = max_approach + roughness_range.max(0.0);
    let core = surface.window_below(geometric, 0)?;
    let (rows, cols) = core.shape();
    let ell = 0.5 * grid.dx() * ((rows * rows + cols * cols) as f64).sqrt();
    surface.window_below(geometric + adhesive_reach(e_star, gamma, ell), 2)
}

/// How far above the approach adhesion can pull the surface into contact around a contact of
/// radius at most `ell`: `sqrt(2πγℓ/E*)` (the JKR edge gap scale without its factor ½, so an
/// over-estimate); the margin [`contact_window`] adds, and what a grid sized in advance for
/// a contact must leave room for.
pub fn adhesive_reach(e_star: f64, gamma: f64, ell: f64) -> f64 {
    (2.0 * std::f64::consts::PI * gamma * ell / e_star).sqrt()
}

/// True when a bonded element lies on the outer ring of the grid: on a cropped problem this
/// means the window may have cut off contact, and the result must not be trusted.
pub fn touches_edge(bonded: &Array2<bool>) -> bool {
    let (nx, ny) = bonded.dim();
    let rows = bonded.row(0).iter().chain(bonded.row(nx - 1)).any(|&b| b);
    rows || bonded
        .column(0)
        .iter()
        .chain(bonded.column(ny - 1))
        .any(|&b| b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use tack_geometry::{Grid, Sphere};

    #[test]
    fn window_of_a_sphere_grows_with_approach_and_adhesion() {
        let grid = Grid::square(101, 0.01, Boundary::Free).unwrap();
        let s = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
        let dry = contact_window(&s, 0.01, 0.0, 1.0, 0.0).unwrap();
        let sticky = contact_window(&s, 0.01, 0.0, 1.0, 1e-3).unwrap();
        assert!(dry.shape().0 < sticky.shape().0 && sticky.shape().0 <= 101);
        // f ≤ d ⇔ r ≤ sqrt(2Rd) = 0.1414 = 14 elements, plus the 2-element pad.
        assert_eq!(dry.shape(), (2 * 14 + 1 + 4, 2 * 14 + 1 + 4));
        let periodic = Surface::flat(grid.with_boundary(Boundary::Periodic));
        assert!(contact_window(&periodic, 1.0, 0.0, 1.0, 0.0).is_none());
    }

    #[test]
    fn edge_detection() {
        let mut m = Array2::from_elem((4, 5), false);
        m[[1, 2]] = true;
        assert!(!touches_edge(&m));
        m[[3, 2]] = true;
        assert!(touches_edge(&m));
    }
}
