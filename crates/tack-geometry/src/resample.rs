//! Coarsening a band-limited height map to twice its element size (the coarse run of a
//! Richardson extrapolation), refusing maps the coarse grid cannot hold.
//!
//! A map of `(nx, ny)` elements of size `Δx` covers the period `nx·Δx × ny·Δx`; the grid of
//! element size `2Δx` over the same period holds the wave vectors `|mx| ≤ ⌊nx/4⌋`,
//! `|my| ≤ ⌊ny/4⌋` (integer wave numbers of the period). A map whose Fourier content lies in
//! that box is one band-limited surface, and its spectral resampling to `2Δx` (the inverse
//! transform of the spectrum cut to the box, the `±` Nyquist waves aliased as samples see them)
//! is exactly its value at the coarse element centres, which are fine element centres too
//! (element `(i, j)` is centred at `((i − ⌊nx/2⌋)Δx, (j − ⌊ny/2⌋)Δx)`). So the coarse map is
//! read off the fine one; the spectrum decides only whether that is allowed.

use ndarray::Array2;
use ndrustfft::{Complex, FftHandler, R2cFftHandler, ndfft, ndfft_r2c};

use crate::error::GeometryError;

/// Default largest share of a map's rms (its mean removed) allowed above the coarse grid's
/// Nyquist wave by [`coarsen_band_limited`]: a map sampled from a band-limited surface has
/// rounding there (1e-15); dropping a 1e-6 share changes heights by 1e-6 of their rms.
pub const BAND_LIMIT_TOLERANCE: f64 = 1e-6;

/// The rms of the Fourier content of `heights` above the Nyquist wave of the grid of twice its
/// element size (any wave number `|mx| > ⌊nx/4⌋` or `|my| > ⌊ny/4⌋`, counted on the map's
/// period), relative to the rms of the map with its mean removed; `0` for a constant map. A
/// side of one element has no wave along it.
pub fn share_above_coarse_nyquist(heights: &Array2<f64>) -> f64 {
    let (nx, ny) = heights.dim();
    if nx == 0 || ny == 0 {
        return 0.0;
    }
    let mut rows = Array2::<Complex<f64>>::zeros((nx, ny / 2 + 1));
    ndfft_r2c(heights, &mut rows, &R2cFftHandler::new(ny), 1);
    let mut hat = rows.clone();
    ndfft(&rows, &mut hat, &FftHandler::new(nx), 0);
    let signed = |k: usize, n: usize| if 2 * k <= n { k } else { n - k };
    let (mut above, mut total) = (0.0, 0.0);
    for ((kx, ky), c) in hat.indexed_iter() {
        if kx == 0 && ky == 0 {
            continue; // the mean
        }
        // The r2c half spectrum holds ky and its mirror ny − ky once, except ky = 0 and ny/2.
        let weight = if ky == 0 || 2 * ky == ny { 1.0 } else { 2.0 };
        let power = weight * c.norm_sqr();
        total += power;
        if signed(kx, nx) > nx / 4 || signed(ky, ny) > ny / 4 {
            above += power;
        }
    }
    if total == 0.0 {
        0.0
    } else {
        (above / total).sqrt()
    }
}

/// The map at the element centres of the grid of twice its element size over the same period:
/// shape `(nx/2, ny/2)`, a side of one element staying one. Exact (to rounding) for a map whose
/// content lies at or below that grid's Nyquist wave; a map with a larger share than
/// `tolerance` of its rms above it ([`share_above_coarse_nyquist`]) is refused, as is an odd
/// side (the period could not be kept).
pub fn coarsen_band_limited(
    heights: &Array2<f64>,
    tolerance: f64,
) -> Result<Array2<f64>, GeometryError> {
    let (nx, ny) = heights.dim();
    for (field, n) in [("height map nx", nx), ("height map ny", ny)] {
        if n != 1 && n % 2 == 1 {
            return Err(GeometryError::BadCount {
                field,
                value: n,
                allowed: "an even number of elements (or 1), so the grid of twice the element \
                          size keeps the period",
            });
        }
    }
    let share = share_above_coarse_nyquist(heights);
    if share > tolerance || share.is_nan() {
        return Err(GeometryError::AboveNyquist {
            share,
            allowed: tolerance,
        });
    }
    Ok(coarse_centres(heights))
}

/// The map sampled at the element centres of the grid of twice its element size (shape
/// `(nx/2, ny/2)` for even sides, a side of one element staying one): coarse centre `i` sits at
/// `(i − ⌊n/4⌋)·2Δx`, which is the fine centre `2i − 2⌊n/4⌋ + n/2`. No band check: see
/// [`coarsen_band_limited`] for the checked form.
pub fn coarse_centres(heights: &Array2<f64>) -> Array2<f64> {
    let (nx, ny) = heights.dim();
    let fine = |i: usize, n: usize| {
        if n == 1 {
            0
        } else {
            2 * i + n / 2 - 2 * (n / 4)
        }
    };
    let half = |n: usize| if n == 1 { 1 } else { n / 2 };
    Array2::from_shape_fn((half(nx), half(ny)), |(i, j)| {
        heights[[fine(i, nx), fine(j, ny)]]
    })
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{PI, TAU};

    use super::*;
    use crate::{Boundary, Grid, RoughSpec, rough_surface};

    #[test]
    fn a_band_limited_surface_coarsens_to_its_own_coarse_sampling() {
        // The rough surface on the band q1 = π/(2Δx) at n = 2m is, at m, the same surface.
        for (nx, ny, seed) in [(64, 48, 3), (60, 20, 4), (32, 1, 5)] {
            let dx = 0.02;
            let fine = Grid::new(nx, ny, dx, Boundary::Periodic).unwrap();
            let coarse = Grid::new(nx / 2, (ny / 2).max(1), 2.0 * dx, Boundary::Periodic).unwrap();
            let spec = RoughSpec {
                q1: PI / (2.0 * dx),
                ..RoughSpec::paper_defaults(fine, 1e-3, 0.6, seed)
            };
            let f = rough_surface(fine, &spec).unwrap();
            let share = share_above_coarse_nyquist(f.heights());
            assert!(share < 1e-13, "{nx}×{ny}: share {share:e}");
            let c = coarsen_band_limited(f.heights(), BAND_LIMIT_TOLERANCE).unwrap();
            let want = rough_surface(coarse, &spec).unwrap();
            let worst = c
                .iter()
                .zip(want.heights())
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(worst < 1e-12 * spec.rms, "{nx}×{ny}: {worst:e}");
        }
    }

    #[test]
    fn content_above_the_coarse_nyquist_is_measured_and_refused() {
        let (nx, ny) = (32, 32);
        // One wave at the coarse Nyquist (allowed), one just above it (refused), in x.
        let wave = |m: f64, amp: f64| {
            Array2::from_shape_fn((nx, ny), |(i, _)| {
                amp * (TAU * m * i as f64 / nx as f64).cos()
            })
        };
        let at = wave(8.0, 1.0);
        assert!(share_above_coarse_nyquist(&at) < 1e-14);
        assert!(coarsen_band_limited(&at, BAND_LIMIT_TOLERANCE).is_ok());
        // Equal amplitudes: half the power lies above, a share of √½.
        let mixed = &at + &wave(9.0, 1.0);
        let share = share_above_coarse_nyquist(&mixed);
        assert!((share - 0.5f64.sqrt()).abs() < 1e-12, "{share}");
        let e = coarsen_band_limited(&mixed, BAND_LIMIT_TOLERANCE).unwrap_err();
        assert!(e.to_string().contains("0.707"), "{e}");
        // A 1e-4 share passes a 1e-3 tolerance and fails the default.
        let slight = &at + &wave(12.0, 1e-4);
        assert!(coarsen_band_limited(&slight, 1e-3).is_ok());
        assert!(coarsen_band_limited(&slight, BAND_LIMIT_TOLERANCE).is_err());
        // Odd sides cannot keep the period.
        let odd = Array2::<f64>::zeros((31, 32));
        let e = coarsen_band_limited(&odd, BAND_LIMIT_TOLERANCE).unwrap_err();
        assert!(e.to_string().contains("height map nx = 31"), "{e}");
        // A constant map has no content anywhere.
        assert_eq!(
            share_above_coarse_nyquist(&Array2::from_elem((8, 8), 2.0)),
            0.0
        );
    }
}
