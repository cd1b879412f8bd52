//! Seeded random rough surfaces by Fourier filtering (Pohrt & Li 2014 style, docs/theory.md §4):
//! one continuous surface, sampled at whatever resolution the grid has.
//!
//! The surface is `h(x) = Σ_m c_m·exp(i q_m·x)` over the integer wave vectors `m` of the period
//! `Lx × Ly` (`q_m = 2π(mx/Lx, my/Ly)`) with `q0 ≤ |q_m| ≤ q1`, `|c_m| ∝ |q_m|^−(H+1)` (power
//! `C ∝ q^−2−2H`), `c_−m = conj(c_m)` (a real surface), and a random phase per wave vector. It is
//! scaled so that its rms (the continuous one, `Σ|c_m|²`) is the requested `h`, and sampled at
//! the element centres, `x = ((i − ⌊nx/2⌋)Δx, (j − ⌊ny/2⌋)Δx)`. A grid represents the wave
//! vectors in its box `|mx| ≤ ⌊nx/2⌋`, `|my| ≤ ⌊ny/2⌋`; the two `±n/2` waves of an even side
//! meet in one Nyquist entry, summed as the samples see them (aliased, exactly).
//!
//! Reproducibility: the phase of `c_m` is the first `u64` of ChaCha8 stream `m` (the signed
//! components zig-zag encoded, `my` in the low 32 bits) of `ChaCha8Rng::seed_from_u64(seed)`,
//! for the wave vector of the pair `±m` with `my > 0` (or `my = 0`, `mx > 0`); the other one is
//! its conjugate. The phases therefore depend on the seed and the wave vector only: for a fixed
//! band the `n × n` and `2n × 2n` grids over the same period sample one surface and agree at
//! their coinciding element centres to rounding, and changing `h`, `H`, `q0` or `q1` keeps the
//! phase of every remaining wave. The rms of the *samples* equals `h` exactly when no Nyquist
//! entry is aliased (`q1 < π/Δx`); with the paper's `q1 = π/Δx` the two axis Nyquist pairs make
//! it differ, by 2e-5 relative or less on the test grids. Everything runs on one thread.

use std::f64::consts::{PI, TAU};

use ndarray::Array2;
use ndrustfft::{Complex, FftHandler, R2cFftHandler, ndifft, ndifft_r2c};
use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{RngCore, SeedableRng};
use tack_fields as fields;

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
#[cfg(test)]
fn signed(k: usize, n: usize) -> f64 {
    if k <= n / 2 {
        k as f64
    } else {
        k as f64 - n as f64
    }
}

/// Generates a random rough surface on `grid` (its boundary kind is kept).
///
/// The surface is one period of a pattern of period `Lx × Ly` with zero mean and rms height
/// `spec.rms` (the continuous surface's; see the module text for the samples'). Errors name
/// the offending field.
pub fn rough_surface(grid: Grid, spec: &RoughSpec) -> Result<Surface, GeometryError> {
    let (columns_hat, power) = half_spectrum(&grid, spec)?;
    let mut heights = synthesize(&grid, &columns_hat);
    // The inverse transforms divide by nx·ny; c_m was drawn with amplitude |q|^−(H+1), whose
    // continuous mean square is `power`.
    heights *= if spec.rms == 0.0 {
        0.0
    } else {
        grid.len() as f64 * spec.rms / power.sqrt()
    };
    Surface::new(grid, heights)
}

/// The samples on `grid` of the half spectrum `hat` (shape `(nx, ny/2 + 1)`, as built by
/// [`hermitian_half_spectrum`]): an inverse c2c transform along x, then an inverse c2r
/// transform along y. Like the transforms, the result is divided by `nx·ny`.
pub(crate) fn synthesize(grid: &Grid, hat: &Array2<Complex<f64>>) -> Array2<f64> {
    let (nx, ny) = grid.shape();
    let mut columns = Array2::<Complex<f64>>::zeros(hat.dim());
    ndifft(hat, &mut columns, &FftHandler::new(nx), 0);
    let mut samples = Array2::<f64>::zeros((nx, ny));
    ndifft_r2c(&columns, &mut samples, &R2cFftHandler::new(ny), 1);
    samples
}

/// Zig-zag code of a signed wave number: 0, −1, 1, −2, 2, … ↦ 0, 1, 2, 3, 4, …
pub(crate) fn zigzag(m: i64) -> u64 {
    ((m << 1) ^ (m >> 63)) as u64
}

/// The phase (radians in `[0, 2π)`) of the wave vector `(mx, my)`: the first `u64` of the
/// ChaCha8 stream numbered `domain | zigzag(mx) << 32 | zigzag(my)`. The roughness uses
/// `domain = 0`; since `|mx|, |my| ≤ 2^15` the codes stay below `2^17`, so a `domain` made of
/// higher bits (e.g. bit 63) gives streams the roughness never draws from.
pub(crate) fn phase(rng: &mut ChaCha8Rng, domain: u64, mx: i64, my: i64) -> f64 {
    rng.set_stream(domain | (zigzag(mx) << 32) | zigzag(my));
    rng.set_word_pos(0);
    (rng.next_u64() >> 11) as f64 * (TAU / (1u64 << 53) as f64)
}

/// Validates `spec` against `grid` and builds the half spectrum `(nx, ny/2 + 1)` that an
/// inverse c2c transform along x followed by an inverse c2r transform along y turns into the
/// surface (times `nx·ny`, with amplitudes `|q|^−(H+1)`), and the continuous mean square of
/// that unscaled surface, `Σ_m |q_m|^−2(H+1)` over every represented wave vector.
pub(crate) fn half_spectrum(
    grid: &Grid,
    spec: &RoughSpec,
) -> Result<(Array2<Complex<f64>>, f64), GeometryError> {
    let hurst = spec.hurst;
    if !(hurst > 0.0 && hurst < 1.0) {
        return Err(GeometryError::OutOfRange {
            field: fields::ROUGHNESS_HURST,
            value: hurst,
            allowed: "a number in the open interval (0, 1)",
        });
    }
    non_negative(fields::ROUGHNESS_H, spec.rms)?;
    let (q0, q1) = (spec.q0, spec.q1);
    for (field, value) in [(fields::ROUGHNESS_Q0, q0), (fields::ROUGHNESS_Q1, q1)] {
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
    let (lx, ly) = (grid.lx(), grid.ly());
    let mut rng = ChaCha8Rng::seed_from_u64(spec.seed);
    let (hat, power) = hermitian_half_spectrum(grid, &mut rng, 0, |mx, my| {
        let q = (TAU * mx as f64 / lx).hypot(TAU * my as f64 / ly);
        if q < q0 * (1.0 - EDGE) || q > q1 * (1.0 + EDGE) {
            None
        } else {
            Some(q.powf(-(hurst + 1.0)))
        }
    });
    if power == 0.0 {
        return Err(band_error);
    }
    Ok((hat, power))
}

/// The half spectrum `(nx, ny/2 + 1)` of the real field `Σ_m c_m·exp(i q_m·x)` over the wave
/// vectors `m` of the grid's box (`|mx| ≤ ⌊nx/2⌋`, `|my| ≤ ⌊ny/2⌋`) for which `amplitude(mx,
/// my)` is `Some(|c_m|)` (it must be even in `m`), with the phase of `c_m` from
/// [`phase`]`(rng, domain, m)` for the member of the pair `±m` with `my > 0` (or `my = 0`,
/// `mx > 0`) and `c_−m = conj(c_m)`; and `Σ_m |c_m|²` over the same wave vectors.
///
/// Entry `(kx, ky)` holds every wave vector `m ≡ (kx, ky)` (mod the grid) of the box, each
/// times `exp(i q_m·x₀)` for the centre `x₀` of element `(0, 0)`; the entries are Hermitian
/// in the self-paired columns `ky = 0` and `ky = ny/2` because `c_−m = conj(c_m)`.
pub(crate) fn hermitian_half_spectrum(
    grid: &Grid,
    rng: &mut ChaCha8Rng,
    domain: u64,
    amplitude: impl Fn(i64, i64) -> Option<f64>,
) -> (Array2<Complex<f64>>, f64) {
    let (nx, ny) = grid.shape();
    let (nx_i, ny_i) = (nx as i64, ny as i64);
    // Element (0, 0) sits at x₀ = −(⌊nx/2⌋, ⌊ny/2⌋)·Δx.
    let (cx, cy) = (nx_i / 2, ny_i / 2);
    let mut hat = Array2::<Complex<f64>>::zeros((nx, ny / 2 + 1));
    let mut power = 0.0;
    for my in -(ny_i / 2)..=ny_i / 2 {
        let ky = my.rem_euclid(ny_i) as usize;
        for mx in -(nx_i / 2)..=nx_i / 2 {
            let Some(amplitude) = amplitude(mx, my) else {
                continue;
            };
            power += amplitude * amplitude;
            if ky > ny / 2 {
                continue; // held by the conjugate entry of the c2r half spectrum
            }
            let c = if my > 0 || (my == 0 && mx > 0) {
                Complex::from_polar(amplitude, phase(rng, domain, mx, my))
            } else {
                Complex::from_polar(amplitude, phase(rng, domain, -mx, -my)).conj()
            };
            // exp(i q_m·x₀) = exp(−2πi (mx·cx/nx + my·cy/ny)), reduced exactly in integers.
            let turns = (mx * cx).rem_euclid(nx_i) as f64 / nx as f64
                + (my * cy).rem_euclid(ny_i) as f64 / ny as f64;
            hat[[mx.rem_euclid(nx_i) as usize, ky]] += c * Complex::from_polar(1.0, -TAU * turns);
        }
    }
    (hat, power)
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

    fn sample_rms(s: &Surface) -> f64 {
        let n = s.grid().len() as f64;
        (s.heights().iter().map(|h| h * h).sum::<f64>() / n).sqrt()
    }

    #[test]
    fn rms_and_mean_are_exact_on_odd_even_and_strip_grids() {
        for (nx, ny) in [(64, 64), (33, 20), (17, 31), (64, 1), (1, 40)] {
            let g = grid(nx, ny);
            // Below the Nyquist wave nothing aliases: the samples' rms is the surface's.
            let spec = RoughSpec {
                q1: 0.9 * PI / g.dx(),
                ..RoughSpec::paper_defaults(g, 2.5e-3, 0.7, 7)
            };
            let s = rough_surface(g, &spec).unwrap();
            let rms = sample_rms(&s);
            assert!((rms / 2.5e-3 - 1.0).abs() < 1e-12, "{nx}×{ny}: rms {rms}");
            assert!(
                s.mean().abs() < 1e-12 * 2.5e-3,
                "{nx}×{ny}: mean {}",
                s.mean()
            );
            // The paper's band ends on the Nyquist waves, whose ± pair the samples alias:
            // the samples' rms then differs from the surface's by their share only.
            let paper = rough_surface(g, &RoughSpec::paper_defaults(g, 2.5e-3, 0.7, 7)).unwrap();
            let rms = sample_rms(&paper);
            eprintln!(
                "{nx}×{ny}: paper band, sample rms / h − 1 = {:.2e}",
                rms / 2.5e-3 - 1.0
            );
            assert!((rms / 2.5e-3 - 1.0).abs() < 5e-5, "{nx}×{ny}: rms {rms}");
            assert!(paper.mean().abs() < 1e-12 * 2.5e-3);
        }
        let g = grid(16, 16);
        let flat = rough_surface(g, &RoughSpec::paper_defaults(g, 0.0, 0.5, 1)).unwrap();
        assert_eq!(flat, Surface::flat(g));
    }

    /// The surface sampled on a grid of `(nx, ny)` elements of size `dx`.
    fn sampled(nx: usize, ny: usize, dx: f64, boundary: Boundary, spec: &RoughSpec) -> Surface {
        rough_surface(Grid::new(nx, ny, dx, boundary).unwrap(), spec).unwrap()
    }

    #[test]
    fn one_band_gives_one_continuous_surface_at_every_resolution() {
        // Period 1.2 × 0.8; the band ends at or below the coarsest grid's Nyquist wave (the
        // 15 × 10 grid, π/Δx = 12.5π), so every grid samples the same waves. Element (i, j) of a
        // grid is centred at ((i − ⌊nx/2⌋)Δx, (j − ⌊ny/2⌋)Δx): the coarse centre i is the
        // fine centre 2i − 2⌊nx/2⌋ + ⌊2nx/2⌋.
        let lx = 1.2;
        for (q1, hurst, seed) in [(12.5 * PI, 0.3, 1), (10.0 * PI, 0.8, 2024)] {
            let spec = RoughSpec {
                rms: 1e-3,
                hurst,
                q0: TAU / lx,
                q1,
                seed,
            };
            for (nx, ny) in [(30, 20), (15, 10)] {
                for boundary in [Boundary::Free, Boundary::Periodic] {
                    let dx = lx / nx as f64;
                    let coarse = sampled(nx, ny, dx, boundary, &spec);
                    for factor in [2, 4] {
                        let fine = sampled(
                            factor * nx,
                            factor * ny,
                            dx / factor as f64,
                            boundary,
                            &spec,
                        );
                        let map =
                            |i: usize, n: usize| factor * i - factor * (n / 2) + factor * n / 2;
                        let mut worst: f64 = 0.0;
                        for ((i, j), h) in coarse.heights().indexed_iter() {
                            let f = fine.heights()[[map(i, nx), map(j, ny)]];
                            worst = worst.max((h - f).abs());
                        }
                        assert!(
                            worst < 1e-12 * spec.rms,
                            "{nx}×{ny} vs ×{factor}: largest difference {worst:e}"
                        );
                    }
                }
            }
        }
        // The paper's band follows the grid (q1 = π/Δx): refining adds waves, so the
        // surfaces differ, though every wave they share keeps its phase.
        let g = grid(32, 32);
        let g2 = Grid::new(64, 64, 0.25, Boundary::Free).unwrap();
        let a = rough_surface(g, &RoughSpec::paper_defaults(g, 1.0, 0.5, 5)).unwrap();
        let b = rough_surface(g2, &RoughSpec::paper_defaults(g2, 1.0, 0.5, 5)).unwrap();
        assert!((a.heights()[[16, 16]] - b.heights()[[32, 32]]).abs() > 1e-6);
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
            let (hat, _) = half_spectrum(&g, &spec).unwrap();
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
    fn phases_are_uniform_and_independent_across_wave_vectors_and_seeds() {
        // 4 seeds × 1 088 wave vectors: a mean of exp(iφ) beyond 4/√N, or two equal phases,
        // would mean the streams repeat.
        let mut all = Vec::new();
        for seed in 0..4 {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            for my in 0..=16 {
                for mx in -32..32 {
                    all.push(phase(&mut rng, 0, mx, my));
                }
            }
        }
        let n = all.len() as f64;
        let (c, s) = all
            .iter()
            .fold((0.0, 0.0), |(c, s), p| (c + p.cos(), s + p.sin()));
        assert!(c.hypot(s) / n < 4.0 / n.sqrt(), "mean {:e}", c.hypot(s) / n);
        let mut sorted = all.clone();
        sorted.sort_by(f64::total_cmp);
        assert!(sorted.windows(2).all(|w| w[0] < w[1]), "a phase repeats");
        assert!(all.iter().all(|p| (0.0..TAU).contains(p)));
        // Lag-one correlation along mx, as a check on stream independence.
        let cos: Vec<f64> = all.iter().map(|p| p.cos()).collect();
        let lag: f64 = cos.windows(2).map(|w| w[0] * w[1]).sum::<f64>() / n;
        assert!(
            lag.abs() < 4.0 * 0.5 / n.sqrt(),
            "lag-one correlation {lag}"
        );
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
            (h[[0, 0]], 9.31579811952505e-1),
            (h[[3, 5]], -2.39401374822905e-1),
            (h[[10, 2]], 1.04169102531819),
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
