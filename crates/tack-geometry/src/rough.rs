//! Seeded random rough surfaces by Fourier filtering (Pohrt & Li 2014 style, docs/theory.md §4).
//!
//! The spectrum has amplitude `|q|^−(H+1)` on the band `q0 ≤ |q| ≤ q1` (power `C ∝ q^−2−2H`)
//! and zero elsewhere, with uniform random phases; the inverse transform is real by Hermitian
//! symmetry, its mean is removed and it is scaled to the requested rms height. Only the phases
//! are random: the amplitudes are exactly the power law, except at the few self-conjugate
//! (Nyquist) entries, which must be real and get `a·cos φ` (see `half_spectrum`).
//!
//! Reproducibility: the phases come from `ChaCha8Rng::seed_from_u64(seed)`, one `u64` per entry
//! of the half spectrum `(kx, ky) ∈ [0, nx) × [0, ny/2]` in row-major order (`ky` fastest),
//! drawn for every entry whatever its amplitude. The draws therefore depend on the grid shape
//! only, so changing `h`, `H`, `q0` or `q1` keeps the phase of every remaining wave. Everything
//! runs on one thread.

use std::f64::consts::{PI, TAU};

use ndarray::Array2;
use ndrustfft::{Complex, FftHandler, R2cFftHandler, ndifft, ndifft_r2c};
use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{RngCore, SeedableRng};

use crate::error::{GeometryError, non_negative, positive};
use crate::{Grid, Surface};

/// Relative tolerance on the band edges, so a wave vector computed as `2π·k/L` counts as
/// inside a band edge given as `2π/L` or `π/Δx` whatever the rounding.
const EDGE: f64 = 1e-9;

/// Parameters of a random rough surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoughSpec {
    /// Rms height `h` of the generated surface (field `roughness.h`), finite and `≥ 0`.
    pub rms: f64,
    /// Exponent `H` of the power law (field `roughness.hurst`), `0 < H < 1`.
    pub hurst: f64,
    /// Lower cut-off wave vector `q0` (field `roughness.q0`).
    pub q0: f64,
    /// Upper cut-off wave vector `q1` (field `roughness.q1`), `q0 < q1 ≤ √2·π/Δx`.
    pub q1: f64,
    /// Seed of the phase generator.
    pub seed: u64,
}

impl RoughSpec {
    /// The paper's band on `grid`: `q0 = 2π/L` with `L = max(Lx, Ly)` and `q1 = π/Δx`.
    pub fn paper_defaults(grid: Grid, rms: f64, hurst: f64, seed: u64) -> Self {
        Self {
            rms,
            hurst,
            q0: q_min(&grid),
            q1: PI / grid.dx(),
            seed,
        }
    }
}

/// The smallest non-zero wave vector on the grid, `2π/max(Lx, Ly)`.
fn q_min(grid: &Grid) -> f64 {
    TAU / grid.lx().max(grid.ly())
}

/// Signed wave number of FFT index `k` on an axis of `n` points.
fn signed(k: usize, n: usize) -> f64 {
    if k <= n / 2 {
        k as f64
    } else {
        k as f64 - n as f64
    }
}

/// Generates a random rough surface on `grid` (its boundary kind is kept).
///
/// The surface is one period of a pattern of period `Lx × Ly` and has zero mean and rms
/// height exactly `spec.rms` (to rounding). Errors name the offending field.
pub fn rough_surface(grid: Grid, spec: &RoughSpec) -> Result<Surface, GeometryError> {
    let (nx, ny) = grid.shape();
    let columns_hat = half_spectrum(&grid, spec)?;
    let mut columns = Array2::<Complex<f64>>::zeros(columns_hat.dim());
    ndifft(&columns_hat, &mut columns, &FftHandler::new(nx), 0);
    let mut heights = Array2::<f64>::zeros((nx, ny));
    ndifft_r2c(&columns, &mut heights, &R2cFftHandler::new(ny), 1);
    let n = grid.len() as f64;
    let mean = heights.sum() / n;
    heights -= mean;
    let rms = (heights.iter().map(|h| h * h).sum::<f64>() / n).sqrt();
    heights *= if spec.rms == 0.0 { 0.0 } else { spec.rms / rms };
    Surface::new(grid, heights)
}

/// Validates `spec` against `grid` and builds the half spectrum `(nx, ny/2 + 1)` that an
/// inverse c2c transform along x followed by an inverse c2r transform along y turns into
/// the (unscaled) surface.
///
/// In the self-paired columns `ky = 0` and `ky = ny/2` (even `ny`) the entry at `nx − kx`
/// is the conjugate of the one at `kx`; the self-conjugate entries (`kx = 0` or `nx/2`) are
/// `a·cos φ`, the value of a wave of random phase sampled at the Nyquist rate.
pub(crate) fn half_spectrum(
    grid: &Grid,
    spec: &RoughSpec,
) -> Result<Array2<Complex<f64>>, GeometryError> {
    let hurst = spec.hurst;
    if !(hurst > 0.0 && hurst < 1.0) {
        return Err(GeometryError::OutOfRange {
            field: "roughness.hurst",
            value: hurst,
            allowed: "a number in the open interval (0, 1)",
        });
    }
    non_negative("roughness.h", spec.rms)?;
    let (q0, q1) = (spec.q0, spec.q1);
    for (field, value) in [("roughness.q0", q0), ("roughness.q1", q1)] {
        positive(field, value)?;
    }
    let band_error = GeometryError::RoughnessBand {
        q0,
        q1,
        q_min: q_min(grid),
        q_nyquist: PI / grid.dx(),
    };
    if q0 >= q1
        || q0 < q_min(grid) * (1.0 - EDGE)
        || q1 > 2f64.sqrt() * PI / grid.dx() * (1.0 + EDGE)
    {
        return Err(band_error);
    }

    let (nx, ny) = grid.shape();
    let mut rng = ChaCha8Rng::seed_from_u64(spec.seed);
    let mut hat = Array2::<Complex<f64>>::zeros((nx, ny / 2 + 1));
    let mut any = false;
    for ((kx, ky), entry) in hat.indexed_iter_mut() {
        let phase = (rng.next_u64() >> 11) as f64 * (TAU / (1u64 << 53) as f64);
        let qx = TAU * signed(kx, nx) / grid.lx();
        let qy = TAU * signed(ky, ny) / grid.ly();
        let q = qx.hypot(qy);
        if q < q0 * (1.0 - EDGE) || q > q1 * (1.0 + EDGE) {
            continue;
        }
        any = true;
        let amplitude = q.powf(-(hurst + 1.0));
        let self_paired = ky == 0 || 2 * ky == ny;
        let self_conjugate = kx == 0 || 2 * kx == nx;
        *entry = if self_paired && self_conjugate {
            Complex::new(amplitude * phase.cos(), 0.0)
        } else {
            Complex::from_polar(amplitude, phase)
        };
    }
    if !any {
        return Err(band_error);
    }
    for ky in [0, ny / 2]
        .into_iter()
        .filter(|&ky| ky == 0 || 2 * ky == ny)
    {
        for kx in nx / 2 + 1..nx {
            hat[[kx, ky]] = hat[[nx - kx, ky]].conj();
        }
    }
    Ok(hat)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Boundary;
    use ndrustfft::{FftHandler, ndfft, ndfft_r2c};

    fn grid(nx: usize, ny: usize) -> Grid {
        Grid::new(nx, ny, 0.5, Boundary::Free).unwrap()
    }

    /// |ĥ|² and |q| of every half-spectrum entry of the surface.
    fn power(s: &Surface) -> Vec<(f64, f64)> {
        let g = s.grid();
        let (nx, ny) = g.shape();
        let mut rows = Array2::<Complex<f64>>::zeros((nx, ny / 2 + 1));
        ndfft_r2c(s.heights(), &mut rows, &R2cFftHandler::new(ny), 1);
        let mut hat = rows.clone();
        ndfft(&rows, &mut hat, &FftHandler::new(nx), 0);
        hat.indexed_iter()
            .map(|((kx, ky), c)| {
                let q = (TAU * signed(kx, nx) / g.lx()).hypot(TAU * signed(ky, ny) / g.ly());
                (q, c.norm_sqr())
            })
            .collect()
    }

    #[test]
    fn rms_and_mean_are_exact_on_odd_even_and_strip_grids() {
        for (nx, ny) in [(64, 64), (33, 20), (17, 31), (64, 1), (1, 40)] {
            let g = grid(nx, ny);
            let s = rough_surface(g, &RoughSpec::paper_defaults(g, 2.5e-3, 0.7, 7)).unwrap();
            let n = g.len() as f64;
            let rms = (s.heights().iter().map(|h| h * h).sum::<f64>() / n).sqrt();
            assert!((rms / 2.5e-3 - 1.0).abs() < 1e-12, "{nx}×{ny}: rms {rms}");
            assert!(
                s.mean().abs() < 1e-12 * 2.5e-3,
                "{nx}×{ny}: mean {}",
                s.mean()
            );
        }
        let g = grid(16, 16);
        let flat = rough_surface(g, &RoughSpec::paper_defaults(g, 0.0, 0.5, 1)).unwrap();
        assert_eq!(flat, Surface::flat(g));
    }

    #[test]
    fn power_spectrum_has_slope_minus_2_minus_2h_inside_the_band_and_nothing_outside() {
        let g = grid(128, 96);
        let (q0, q1) = (4.0 * q_min(&g), 0.5 * PI / g.dx());
        for hurst in [0.1, 0.5, 0.9] {
            let spec = RoughSpec {
                rms: 1e-3,
                hurst,
                q0,
                q1,
                seed: 3,
            };
            let p = power(&rough_surface(g, &spec).unwrap());
            let inside: f64 = p
                .iter()
                .filter(|(q, _)| *q >= q0 && *q <= q1)
                .map(|x| x.1)
                .sum();
            let outside = p.iter().filter(|(q, _)| *q < q0 * 0.999 || *q > q1 * 1.001);
            assert!(outside.clone().count() > 1000);
            for &(q, c) in outside {
                assert!(
                    c < 1e-20 * inside,
                    "H = {hurst}: power {c} at q = {q} outside the band"
                );
            }
            // Radial average over 12 logarithmic bins spanning the band; fit the inner 10.
            let bins = 12;
            let width = (q1 / q0).ln() / bins as f64;
            let mut sums = vec![(0.0, 0.0, 0usize); bins];
            for &(q, c) in &p {
                let b = ((q / q0).ln() / width).floor();
                if b >= 0.0 && (b as usize) < bins {
                    let s = &mut sums[b as usize];
                    *s = (s.0 + q, s.1 + c, s.2 + 1);
                }
            }
            let pts: Vec<(f64, f64)> = sums[1..bins - 1]
                .iter()
                .map(|&(q, c, n)| ((q / n as f64).ln(), (c / n as f64).ln()))
                .collect();
            let m = pts.len() as f64;
            let (sx, sy) = pts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
            let (mx, my) = (sx / m, sy / m);
            let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
            let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
            let slope = sxy / sxx;
            eprintln!(
                "H = {hurst}: measured slope {slope:.4}, expected {}",
                -2.0 - 2.0 * hurst
            );
            assert!(
                (slope + 2.0 + 2.0 * hurst).abs() < 0.1,
                "H = {hurst}: slope {slope}"
            );
        }
    }

    #[test]
    fn half_spectrum_is_hermitian_so_the_inverse_is_real() {
        for (nx, ny) in [(8, 6), (7, 6), (8, 5), (5, 5)] {
            let g = grid(nx, ny);
            let spec = RoughSpec::paper_defaults(g, 1.0, 0.5, 11);
            let hat = half_spectrum(&g, &spec).unwrap();
            assert_eq!(hat[[0, 0]], Complex::new(0.0, 0.0), "no mean");
            let mut cols = hat.clone();
            ndifft(&hat, &mut cols, &FftHandler::new(nx), 0);
            let scale = cols.iter().map(|c| c.norm()).fold(0.0, f64::max);
            // c2r drops the imaginary part of the self-paired columns: it must be zero already.
            for ky in [0, ny / 2]
                .into_iter()
                .filter(|&ky| ky == 0 || 2 * ky == ny)
            {
                for kx in 0..nx {
                    assert!(
                        cols[[kx, ky]].im.abs() < 1e-14 * scale,
                        "{nx}×{ny} ({kx}, {ky})"
                    );
                }
            }
        }
    }

    #[test]
    fn same_seed_gives_same_bits_on_any_thread_and_other_seeds_differ() {
        let g = grid(24, 20);
        let spec = RoughSpec::paper_defaults(g, 1.0, 0.3, 99);
        let a = rough_surface(g, &spec).unwrap();
        let b = std::thread::spawn(move || rough_surface(g, &spec).unwrap())
            .join()
            .unwrap();
        assert!(
            a.heights()
                .iter()
                .zip(b.heights())
                .all(|(x, y)| x.to_bits() == y.to_bits())
        );
        let c = rough_surface(g, &RoughSpec { seed: 100, ..spec }).unwrap();
        assert_ne!(a, c);
    }

    #[test]
    fn snapshot_of_a_fixed_seed_guards_portability() {
        let g = Grid::square(32, 1.0, Boundary::Periodic).unwrap();
        let s = rough_surface(g, &RoughSpec::paper_defaults(g, 1.0, 0.5, 42)).unwrap();
        let h = s.heights();
        for (got, want) in [
            (h[[0, 0]], 2.01224511035386e-1),
            (h[[3, 5]], 1.57405779250175),
            (h[[10, 2]], -1.41179916004006),
        ] {
            assert!(
                (got / want - 1.0).abs() < 1e-12,
                "got {got:.15e}, want {want:.15e}"
            );
        }
    }

    #[test]
    fn rejects_bad_specs_naming_the_field() {
        let g = grid(32, 32);
        let good = RoughSpec::paper_defaults(g, 1.0, 0.5, 0);
        let qn = PI / g.dx();
        for (spec, field) in [
            (RoughSpec { hurst: 0.0, ..good }, "roughness.hurst"),
            (RoughSpec { hurst: 1.0, ..good }, "roughness.hurst"),
            (
                RoughSpec {
                    hurst: f64::NAN,
                    ..good
                },
                "roughness.hurst",
            ),
            (RoughSpec { rms: -1.0, ..good }, "roughness.h"),
            (
                RoughSpec {
                    rms: f64::INFINITY,
                    ..good
                },
                "roughness.h",
            ),
            (RoughSpec { q0: 0.0, ..good }, "roughness.q0"),
            (
                RoughSpec {
                    q1: f64::NAN,
                    ..good
                },
                "roughness.q1",
            ),
            (
                RoughSpec {
                    q0: qn,
                    q1: qn / 2.0,
                    ..good
                },
                "roughness.q0/q1",
            ),
            (
                RoughSpec {
                    q0: good.q0 / 2.0,
                    ..good
                },
                "roughness.q0/q1",
            ),
            (
                RoughSpec {
                    q1: 1.5 * qn,
                    ..good
                },
                "roughness.q0/q1",
            ),
            (
                RoughSpec {
                    q0: 1.1 * good.q0,
                    q1: 1.2 * good.q0,
                    ..good
                },
                "roughness.q0/q1",
            ),
        ] {
            let e = rough_surface(g, &spec).unwrap_err();
            assert!(e.to_string().contains(field), "{e}");
        }
        let e = rough_surface(
            g,
            &RoughSpec {
                q1: 1.5 * qn,
                ..good
            },
        )
        .unwrap_err();
        assert!(e.to_string().contains("from 2π/L = 0.39"), "{e}");
    }
}
