//! Generated work-of-adhesion patterns (stripes, checkerboard, seeded log-normal random field): γ per element of a grid.
//!
//! Every element takes the phase of its centre, `((i − ⌊nx/2⌋)Δx, (j − ⌊ny/2⌋)Δx)`. A centre on
//! a phase boundary — within `1e-9` of the period, relative, so whatever the rounding of `x/period`
//! — belongs to phase a.
//!
//! * **Stripes** across x (bands parallel to y): phase b where `|x − round(x/p)·p| < fraction·p/2`, phase a elsewhere.
//! * **Rings** about the origin: the same rule in the radius `r` (phase b on a central disc of
//!   radius `fraction·p/2` and on rings about r = k·p): the axisymmetric patterns whose
//!   zero-range answer is exact (`tack_analytics::axisymmetric_retraction`).
//! * **Checkerboard**: squares of side `s = p/2`; phase b where `round(x/s) + round(y/s)` is odd,
//!   so the square centred at the origin is phase a.
//! * **Random**: `γ = mean·exp(σφ − σ²/2)`, `σ² = ln(1 + contrast²)`: log-normal with mean `mean`
//!   and coefficient of variation `contrast`, positive everywhere. `φ` is a zero-mean,
//!   unit-variance Gaussian random field with correlation `exp(−r²/ℓ²)`, periodic over the grid's
//!   `Lx × Ly`: `φ = Σ_m c_m·exp(i q_m·x)` over the wave vectors `q_m = 2π(mx/Lx, my/Ly)`, `m ≠ 0`,
//!   of the grid's box (`|mx| ≤ ⌊nx/2⌋`, `|my| ≤ ⌊ny/2⌋`, even sides' Nyquist pairs aliased as
//!   the samples see them), `|c_m|² = S(q_m)/V` with `S(q) = exp(−q²ℓ²/4)` and `V = Σ S(q_m)`
//!   over *every* `m ≠ 0` of the infinite lattice. Normalising by the continuous `V` rather than
//!   by the sampled variance makes `φ` one continuous field per seed: grids of `n` and `2n`
//!   elements over one period sample the same field and agree at their shared centres to
//!   rounding once the waves beyond the coarse grid's Nyquist wave carry nothing
//!   (`ℓ ≥ 5Δx` of the coarse grid: a share below 1e-27 of the variance; at `ℓ = 4Δx` it is
//!   about 1e-18, a difference of order 1e-9 in `φ`).
//!
//! Reproducibility: the phases come from the same generator as the roughness of
//! [`rough_surface`](crate::rough_surface) — `ChaCha8Rng::seed_from_u64(seed)`, one stream per
//! wave vector numbered by its zig-zag coded components — but with bit 63 of the stream number
//! set ([`PATTERN_STREAM_DOMAIN`]). The roughness's stream numbers stay below `2^49`, so a pattern
//! and a roughness generated with the same seed draw from disjoint streams and are independent.

use std::f64::consts::PI;

use ndarray::Array2;
use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::SeedableRng;
use tack_fields as fields;

use crate::Grid;
use crate::error::{GeometryError, non_negative, positive};
use crate::rough::{hermitian_half_spectrum, synthesize};

/// Relative width of a phase boundary: a centre within `TIE·period` of it is phase a.
const TIE: f64 = 1e-9;

/// The stream-number bits of the random pattern's phases (see the module text): bit 63, which
/// the roughness never sets.
const PATTERN_STREAM_DOMAIN: u64 = 1 << 63;

/// A generated work-of-adhesion pattern (γ per element).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AdhesionPattern {
    /// Stripes across x (bands parallel to y): phase b on the part `fraction` of each period
    /// centred on x = k·period, phase a elsewhere.
    Stripes {
        /// γ of phase a (field `material.gamma`), finite `≥ 0`.
        gamma_a: f64,
        /// γ of phase b (field `adhesion.gamma_b`), finite `≥ 0`.
        gamma_b: f64,
        /// The period (field `adhesion.period`), finite and at least two elements.
        period: f64,
        /// The share of each period that is phase b (field `adhesion.fraction`), in `[0, 1]`.
        fraction: f64,
    },
    /// Rings about the origin: phase b where `|r − round(r/period)·period| < fraction·period/2`
    /// (a central disc of radius `fraction·period/2`, then rings), phase a elsewhere.
    Rings {
        /// γ of phase a (field `material.gamma`), finite `≥ 0`.
        gamma_a: f64,
        /// γ of phase b (field `adhesion.gamma_b`), finite `≥ 0`.
        gamma_b: f64,
        /// The period (field `adhesion.period`), finite and at least two elements.
        period: f64,
        /// The share of each period that is phase b (field `adhesion.fraction`), in `[0, 1]`.
        fraction: f64,
    },
    /// Squares of side period/2, phase a on the square centred at the origin, alternating.
    Checkerboard {
        /// γ of phase a (field `material.gamma`), finite `≥ 0`.
        gamma_a: f64,
        /// γ of phase b (field `adhesion.gamma_b`), finite `≥ 0`.
        gamma_b: f64,
        /// The period, two squares (field `adhesion.period`), finite and at least two elements.
        period: f64,
    },
    /// A log-normal field of mean `mean` and coefficient of variation `contrast`, Gaussian correlation length `correlation_length`, seeded.
    Random {
        /// The mean γ (field `material.gamma`), finite `> 0`.
        mean: f64,
        /// Standard deviation over mean (field `adhesion.contrast`), finite `≥ 0`.
        contrast: f64,
        /// `ℓ` of the correlation `exp(−r²/ℓ²)` (field `adhesion.correlation_length`), finite `> 0`.
        correlation_length: f64,
        /// Seed of the phase generator (field `adhesion.seed`).
        seed: u64,
    },
}

impl AdhesionPattern {
    /// γ of every element of `grid`, shape (nx, ny).
    ///
    /// Errors ([`GeometryError::OutOfRange`]) name the offending field.
    pub fn field(&self, grid: &Grid) -> Result<Array2<f64>, GeometryError> {
        match *self {
            Self::Stripes {
                gamma_a,
                gamma_b,
                period,
                fraction,
            }
            | Self::Rings {
                gamma_a,
                gamma_b,
                period,
                fraction,
            } => {
                check_phases(gamma_a, gamma_b)?;
                check_period(grid, period)?;
                if !(0.0..=1.0).contains(&fraction) {
                    return Err(GeometryError::OutOfRange {
                        field: fields::ADHESION_FRACTION,
                        value: fraction,
                        allowed: "a number from 0 to 1",
                    });
                }
                // The distance that repeats: x for stripes, r for rings.
                let rings = matches!(self, Self::Rings { .. });
                Ok(Array2::from_shape_fn(grid.shape(), |(i, j)| {
                    let s = if rings {
                        grid.x(i).hypot(grid.y(j))
                    } else {
                        grid.x(i)
                    };
                    let t = s / period;
                    if (t - t.round()).abs() < fraction / 2.0 - TIE {
                        gamma_b
                    } else {
                        gamma_a
                    }
                }))
            }
            Self::Checkerboard {
                gamma_a,
                gamma_b,
                period,
            } => {
                check_phases(gamma_a, gamma_b)?;
                check_period(grid, period)?;
                let side = period / 2.0;
                // Distance of t from the nearest square edge (a half-integer), in units of the side.
                let off_edge = |t: f64| ((t - t.round()).abs() - 0.5).abs() > 2.0 * TIE;
                Ok(Array2::from_shape_fn(grid.shape(), |(i, j)| {
                    let (u, v) = (grid.x(i) / side, grid.y(j) / side);
                    if off_edge(u) && off_edge(v) && (u.round() + v.round()).rem_euclid(2.0) == 1.0
                    {
                        gamma_b
                    } else {
                        gamma_a
                    }
                }))
            }
            Self::Random {
                mean,
                contrast,
                correlation_length,
                seed,
            } => random_field(grid, mean, contrast, correlation_length, seed),
        }
    }
}

/// Both phases' γ finite and `≥ 0`.
fn check_phases(gamma_a: f64, gamma_b: f64) -> Result<(), GeometryError> {
    non_negative(fields::MATERIAL_GAMMA, gamma_a)?;
    non_negative(fields::ADHESION_GAMMA_B, gamma_b)?;
    Ok(())
}

/// The period finite and at least two elements long (to rounding).
fn check_period(grid: &Grid, period: f64) -> Result<(), GeometryError> {
    if period.is_finite() && period >= 2.0 * grid.dx() * (1.0 - TIE) {
        Ok(())
    } else {
        Err(GeometryError::OutOfRange {
            field: fields::ADHESION_PERIOD,
            value: period,
            allowed: concat!(
                "a finite length of at least two elements per period (twice ",
                tack_fields::field_name!(grid.dx),
                ")"
            ),
        })
    }
}

/// `e^a·(θ(a) − 1) = 2·Σ_{k ≥ 1} exp(−a(k² − 1))` for `θ(a) = Σ_{k ∈ ℤ} exp(−a·k²)`, `a > 0`:
/// summed directly for `a ≥ π`, else through the Poisson form
/// `θ(a) = √(π/a)·Σ_k exp(−π²k²/a)`, which converges as fast; either sum runs until a term is
/// below 1e-17 of the total.
fn theta_excess(a: f64) -> f64 {
    let series = |rate: f64, first: f64| {
        // first + 2·Σ_{k≥1} exp(−rate·k²)
        let mut sum = first;
        for k in 1u32.. {
            let term = 2.0 * (-rate * f64::from(k * k)).exp();
            sum += term;
            if term < 1e-17 * sum {
                break;
            }
        }
        sum
    };
    if a >= PI {
        // 2·e^a·Σ_{k≥1} e^{−ak²}, written to keep e^a from overflowing: the k = 1 term is 2.
        let mut sum = 2.0;
        for k in 2u32.. {
            let term = 2.0 * (-a * f64::from(k * k - 1)).exp();
            sum += term;
            if term < 1e-17 * sum {
                break;
            }
        }
        sum
    } else {
        a.exp() * ((PI / a).sqrt() * series(PI * PI / a, 1.0) - 1.0)
    }
}

/// The log-normal random pattern (see the module text).
fn random_field(
    grid: &Grid,
    mean: f64,
    contrast: f64,
    correlation_length: f64,
    seed: u64,
) -> Result<Array2<f64>, GeometryError> {
    positive(fields::MATERIAL_GAMMA, mean)?;
    non_negative(fields::ADHESION_CONTRAST, contrast)?;
    let ell = positive(fields::ADHESION_CORRELATION_LENGTH, correlation_length)?;
    if contrast == 0.0 {
        return Ok(Array2::from_elem(grid.shape(), mean));
    }
    // S(q_m) = exp(−a·mx² − b·my²), a = (πℓ/Lx)², b = (πℓ/Ly)². The lattice sum factorises,
    // V = Σ_{m≠0} S = θ(a)·θ(b) − 1 = (θ(a) − 1) + (θ(b) − 1) + (θ(a) − 1)(θ(b) − 1). It is
    // formed as e^{−c}·W with c = min(a, b), and every amplitude is scaled by e^{c/2}, so
    // nothing underflows when ℓ is many periods long.
    let a = (PI * ell / grid.lx()).powi(2);
    let b = (PI * ell / grid.ly()).powi(2);
    let c = a.min(b);
    let (ta, tb) = (theta_excess(a), theta_excess(b));
    let w = (c - a).exp() * ta + (c - b).exp() * tb + (c - a - b).exp() * ta * tb; // e^{c}·V
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (hat, _) = hermitian_half_spectrum(grid, &mut rng, PATTERN_STREAM_DOMAIN, |mx, my| {
        if mx == 0 && my == 0 {
            return None;
        }
        let (mx, my) = (mx as f64, my as f64);
        Some((0.5 * (c - a * mx * mx - b * my * my)).exp() / w.sqrt())
    });
    let mut phi = synthesize(grid, &hat);
    // The inverse transforms divide by nx·ny.
    phi *= grid.len() as f64;
    let sigma2 = contrast.mul_add(contrast, 1.0).ln();
    let sigma = sigma2.sqrt();
    Ok(phi.mapv(|p| mean * sigma.mul_add(p, -0.5 * sigma2).exp()))
}

#[cfg(test)]
mod tests;
