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
mod tests;
