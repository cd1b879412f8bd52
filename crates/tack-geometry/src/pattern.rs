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
mod tests {
    use super::*;
    use crate::Boundary;

    fn stripes(period: f64, fraction: f64) -> AdhesionPattern {
        AdhesionPattern::Stripes {
            gamma_a: 1.0,
            gamma_b: 3.0,
            period,
            fraction,
        }
    }

    fn board(period: f64) -> AdhesionPattern {
        AdhesionPattern::Checkerboard {
            gamma_a: 1.0,
            gamma_b: 3.0,
            period,
        }
    }

    fn random(contrast: f64, correlation_length: f64, seed: u64) -> AdhesionPattern {
        AdhesionPattern::Random {
            mean: 0.05,
            contrast,
            correlation_length,
            seed,
        }
    }

    fn share_b(f: &Array2<f64>) -> f64 {
        f.iter().filter(|&&g| g == 3.0).count() as f64 / f.len() as f64
    }

    #[test]
    fn stripes_phase_b_share_is_the_fraction_to_one_element_per_period() {
        // Grids spanning whole periods (13 and 16 elements per period, odd and even nx).
        for (nx, period) in [(65, 1.3), (64, 1.6)] {
            let g = Grid::new(nx, 3, 0.1, Boundary::Periodic).unwrap();
            let per_period = period / 0.1;
            for fraction in [0.0, 0.2, 0.37, 0.5, 0.9, 1.0] {
                let f = stripes(period, fraction).field(&g).unwrap();
                assert_eq!(f.dim(), (nx, 3));
                let share = share_b(&f);
                assert!(
                    (share - fraction).abs() <= 1.0 / per_period + 1e-12,
                    "nx {nx}, fraction {fraction}: share {share}"
                );
                // Stripes run along y: every column is one phase.
                for row in f.rows() {
                    assert!(row.iter().all(|&g| g == row[0]));
                }
            }
        }
    }

    #[test]
    fn rings_are_a_disc_and_rings_about_the_origin() {
        let g = Grid::new(41, 41, 0.1, Boundary::Free).unwrap();
        let rings = AdhesionPattern::Rings {
            gamma_a: 1.0,
            gamma_b: 2.0,
            period: 2.0,
            fraction: 0.7,
        };
        let f = rings.field(&g).unwrap();
        for ((i, j), &v) in f.indexed_iter() {
            let r = g.x(i).hypot(g.y(j));
            // The disc r < 0.7 and the ring |r − 2| < 0.7 are phase b.
            let b = r < 0.7 - 1e-9 || (r - 2.0).abs() < 0.7 - 1e-9;
            assert_eq!(v, if b { 2.0 } else { 1.0 }, "({i}, {j}) r = {r}");
        }
        let bad = AdhesionPattern::Rings {
            gamma_a: 1.0,
            gamma_b: 2.0,
            period: 2.0,
            fraction: 1.5,
        };
        assert!(
            bad.field(&g)
                .unwrap_err()
                .to_string()
                .contains("adhesion.fraction")
        );
    }

    #[test]
    fn patterns_are_symmetric_about_the_origin_on_odd_grids() {
        let g = Grid::new(41, 37, 0.1, Boundary::Free).unwrap();
        let (nx, ny) = g.shape();
        for pattern in [
            stripes(0.37, 0.3),
            stripes(0.9, 0.61),
            board(0.37),
            board(1.1),
        ] {
            let f = pattern.field(&g).unwrap();
            for ((i, j), &v) in f.indexed_iter() {
                assert_eq!(v, f[[nx - 1 - i, j]], "{pattern:?} ({i}, {j})");
                assert_eq!(v, f[[i, ny - 1 - j]], "{pattern:?} ({i}, {j})");
            }
            assert_eq!(
                f[[nx / 2, ny / 2]],
                if matches!(pattern, AdhesionPattern::Stripes { .. }) {
                    3.0
                } else {
                    1.0
                }
            );
        }
    }

    #[test]
    fn centres_on_a_phase_boundary_belong_to_phase_a() {
        // Δx = 0.1 (not exact in binary): x/period lands on the boundary only up to rounding.
        let g = Grid::new(81, 81, 0.1, Boundary::Free).unwrap();
        let c = 40i64;
        let k = |i: usize| i as i64 - c;
        // Stripes of period 4Δx, half b: the edges ±Δx (+ 4kΔx) are centres, so b is the
        // centre line of each period only.
        let f = stripes(0.4, 0.5).field(&g).unwrap();
        for ((i, _), &v) in f.indexed_iter() {
            let want = if k(i).rem_euclid(4) == 0 { 3.0 } else { 1.0 };
            assert_eq!(v, want, "stripes, k = {}", k(i));
        }
        // Period 0.6, fraction 1/3: edges at ±0.1 + 0.6k, again centres.
        let f = stripes(0.6, 1.0 / 3.0).field(&g).unwrap();
        for ((i, _), &v) in f.indexed_iter() {
            let want = if k(i).rem_euclid(6) == 0 { 3.0 } else { 1.0 };
            assert_eq!(v, want, "stripes 0.6, k = {}", k(i));
        }
        // Fraction 1: only the edges (x = (k + ½)·period on centres) stay phase a.
        let f = stripes(0.2, 1.0).field(&g).unwrap();
        for ((i, _), &v) in f.indexed_iter() {
            let want = if k(i).rem_euclid(2) == 0 { 3.0 } else { 1.0 };
            assert_eq!(v, want, "stripes fraction 1, k = {}", k(i));
        }
        // Checkerboard of period 4Δx: squares of side 2Δx, edges on the odd centres.
        let f = board(0.4).field(&g).unwrap();
        for ((i, j), &v) in f.indexed_iter() {
            let (ki, kj) = (k(i), k(j));
            let want = if ki % 2 == 0 && kj % 2 == 0 && (ki / 2 + kj / 2).rem_euclid(2) == 1 {
                3.0
            } else {
                1.0
            };
            assert_eq!(v, want, "checkerboard ({ki}, {kj})");
        }
    }

    #[test]
    fn checkerboard_alternates_and_has_phase_a_at_the_origin() {
        // Period 6Δx: squares of 3 × 3 elements, edges between centres.
        let g = Grid::new(36, 30, 0.1, Boundary::Periodic).unwrap();
        let f = board(0.6).field(&g).unwrap();
        let (cx, cy) = (18i64, 15i64);
        for ((i, j), &v) in f.indexed_iter() {
            let sq = |k: i64| (k as f64 / 3.0).round() as i64;
            let want = if (sq(i as i64 - cx) + sq(j as i64 - cy)).rem_euclid(2) == 1 {
                3.0
            } else {
                1.0
            };
            assert_eq!(v, want, "({i}, {j})");
            if i + 3 < 36 {
                assert_ne!(v, f[[i + 3, j]]);
            }
            if j + 3 < 30 {
                assert_ne!(v, f[[i, j + 3]]);
            }
        }
        for i in 17..=19 {
            for j in 14..=16 {
                assert_eq!(f[[i, j]], 1.0);
            }
        }
        assert!((share_b(&f) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn random_is_deterministic_per_seed_positive_and_differs_between_seeds() {
        let g = Grid::new(48, 40, 0.1, Boundary::Periodic).unwrap();
        let p = random(0.8, 0.5, 17);
        let a = p.field(&g).unwrap();
        let b = std::thread::spawn(move || p.field(&g).unwrap())
            .join()
            .unwrap();
        assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()));
        assert!(a.iter().all(|&v| v > 0.0 && v.is_finite()));
        let c = random(0.8, 0.5, 18).field(&g).unwrap();
        let d = a
            .iter()
            .zip(&c)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        assert!(d > 0.01, "seeds 17 and 18 differ by at most {d}");
        // Strong contrast, long and short correlation: still finite and positive.
        for (contrast, ell) in [(5.0, 0.3), (1.0, 100.0), (1.0, 0.01)] {
            let f = random(contrast, ell, 3).field(&g).unwrap();
            assert!(
                f.iter().all(|&v| v > 0.0 && v.is_finite()),
                "{contrast}, {ell}"
            );
        }
    }

    #[test]
    fn random_pattern_is_independent_of_the_roughness_of_the_same_seed() {
        // Same seed, same generator key, disjoint streams: the phases of one wave vector differ.
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for (mx, my) in [(1, 0), (0, 1), (3, -2), (-5, 4)] {
            let rough = crate::rough::phase(&mut rng, 0, mx, my);
            let pattern = crate::rough::phase(&mut rng, PATTERN_STREAM_DOMAIN, mx, my);
            assert_ne!(rough, pattern);
        }
    }

    #[test]
    fn random_contrast_zero_is_exactly_the_mean() {
        let g = Grid::new(16, 9, 0.1, Boundary::Free).unwrap();
        let f = random(0.0, 0.4, 1).field(&g).unwrap();
        assert!(f.iter().all(|&v| v == 0.05));
    }

    #[test]
    fn random_is_one_continuous_field_at_every_resolution() {
        // Period 3.2 × 2.4. Coarse element i is fine element 2i − 2⌊n/2⌋ + n (2i for even n).
        for (nx, ny, dx) in [(32, 24, 0.1), (15, 21, 0.2)] {
            for ell_elements in [5.0, 8.0] {
                let ell = ell_elements * dx;
                for seed in [0, 99] {
                    let p = random(0.7, ell, seed);
                    let coarse = p
                        .field(&Grid::new(nx, ny, dx, Boundary::Periodic).unwrap())
                        .unwrap();
                    let fine = p
                        .field(&Grid::new(2 * nx, 2 * ny, dx / 2.0, Boundary::Free).unwrap())
                        .unwrap();
                    let map = |i: usize, n: usize| 2 * i - 2 * (n / 2) + n;
                    let worst = coarse
                        .indexed_iter()
                        .map(|((i, j), v)| (fine[[map(i, nx), map(j, ny)]] / v - 1.0).abs())
                        .fold(0.0, f64::max);
                    eprintln!(
                        "{nx}×{ny}, ℓ = {ell_elements}Δx, seed {seed}: n vs 2n worst {worst:.2e}"
                    );
                    assert!(worst < 1e-10, "{nx}×{ny}, ℓ = {ell_elements}Δx: {worst:e}");
                }
            }
        }
        // At ℓ = 4Δx the waves beyond the coarse Nyquist wave carry ~1.3e-18 of the variance
        // (2·erfc(2π)): a difference of order 1e-9 in φ, σ ≈ 0.63 times that in γ/mean.
        let p = random(0.7, 0.4, 5);
        let coarse = p
            .field(&Grid::new(32, 32, 0.1, Boundary::Free).unwrap())
            .unwrap();
        let fine = p
            .field(&Grid::new(64, 64, 0.05, Boundary::Free).unwrap())
            .unwrap();
        let worst = coarse
            .indexed_iter()
            .map(|((i, j), v)| (fine[[2 * i, 2 * j]] / v - 1.0).abs())
            .fold(0.0, f64::max);
        eprintln!("ℓ = 4Δx: n vs 2n worst {worst:.2e}");
        assert!(worst < 5e-9, "{worst:e}");
    }

    #[test]
    fn random_sample_mean_and_contrast_match_the_parameters() {
        // L/ℓ = 64 (256² elements, ℓ = 4Δx, area A = (64ℓ)²), three seeds. Every sampled wave
        // has zero spatial mean and the amplitudes are fixed (only phases are random), so the
        // sample mean and variance of φ are deterministic (0 and 1 − 1e-18). Expanding
        // exp(σφ) in Hermite polynomials, the seed-to-seed variance of the sample mean of
        // γ/mean is then (1/A)∫Σ_{k≥3} σ^{2k}C^k/k! = (πℓ²/A)·Σ_{k≥3} σ^{2k}/(k!·k) (the k = 1, 2
        // terms vanish): std 6.9e-4 at contrast 0.5, 4.0e-3 at contrast 1. The sample
        // coefficient of variation moves with E[γ²], a log-normal of parameter 2σ: the same sum
        // with 4σ² gives relative std 1.5e-2 and 4.1e-2 of cv. Tolerances: five standard
        // deviations.
        let g = Grid::square(256, 0.25, Boundary::Periodic).unwrap();
        for (contrast, tol_mean, tol_cv) in [(0.5, 3.5e-3, 0.075), (1.0, 0.02, 0.2)] {
            for seed in [1, 2, 3] {
                let f = random(contrast, 1.0, seed).field(&g).unwrap();
                let n = f.len() as f64;
                let m = f.sum() / n;
                let var = f.iter().map(|v| (v - m).powi(2)).sum::<f64>() / n;
                let cv = var.sqrt() / m;
                eprintln!(
                    "contrast {contrast}, seed {seed}: mean/γ − 1 = {:+.2e}, cv/contrast − 1 = {:+.2e}",
                    m / 0.05 - 1.0,
                    cv / contrast - 1.0
                );
                assert!((m / 0.05 - 1.0).abs() < tol_mean, "mean {m}");
                assert!((cv / contrast - 1.0).abs() < tol_cv, "cv {cv}");
                assert!(f.iter().all(|&v| v > 0.0));
            }
        }
    }

    #[test]
    fn continuous_variance_matches_a_brute_force_lattice_sum() {
        for (a, b) in [(0.01, 0.02), (0.5, 3.0), (3.2, 3.2), (20.0, 0.3)] {
            let mut v = 0.0;
            for mx in -400i32..=400 {
                for my in -400i32..=400 {
                    if (mx, my) != (0, 0) {
                        v += (-a * f64::from(mx * mx) - b * f64::from(my * my)).exp();
                    }
                }
            }
            let c = f64::min(a, b);
            let (ta, tb) = (theta_excess(a), theta_excess(b));
            let w = (c - a).exp() * ta + (c - b).exp() * tb + (c - a - b).exp() * ta * tb;
            let got = (-c).exp() * w;
            assert!((got / v - 1.0).abs() < 1e-13, "a {a}, b {b}: {got} vs {v}");
        }
    }

    #[test]
    fn rejects_bad_inputs_naming_the_field() {
        let g = Grid::new(20, 20, 0.1, Boundary::Free).unwrap();
        let cases = [
            (
                AdhesionPattern::Stripes {
                    gamma_a: -1.0,
                    gamma_b: 1.0,
                    period: 1.0,
                    fraction: 0.5,
                },
                "material.gamma",
            ),
            (
                AdhesionPattern::Stripes {
                    gamma_a: f64::NAN,
                    gamma_b: 1.0,
                    period: 1.0,
                    fraction: 0.5,
                },
                "material.gamma",
            ),
            (
                AdhesionPattern::Stripes {
                    gamma_a: 1.0,
                    gamma_b: f64::INFINITY,
                    period: 1.0,
                    fraction: 0.5,
                },
                "adhesion.gamma_b",
            ),
            (
                AdhesionPattern::Stripes {
                    gamma_a: 1.0,
                    gamma_b: -0.1,
                    period: 1.0,
                    fraction: 0.5,
                },
                "adhesion.gamma_b",
            ),
            (stripes(0.19, 0.5), "adhesion.period"),
            (stripes(f64::INFINITY, 0.5), "adhesion.period"),
            (stripes(f64::NAN, 0.5), "adhesion.period"),
            (stripes(1.0, -0.1), "adhesion.fraction"),
            (stripes(1.0, 1.1), "adhesion.fraction"),
            (stripes(1.0, f64::NAN), "adhesion.fraction"),
            (
                AdhesionPattern::Checkerboard {
                    gamma_a: -1.0,
                    gamma_b: 1.0,
                    period: 1.0,
                },
                "material.gamma",
            ),
            (
                AdhesionPattern::Checkerboard {
                    gamma_a: 1.0,
                    gamma_b: f64::NAN,
                    period: 1.0,
                },
                "adhesion.gamma_b",
            ),
            (board(0.1), "adhesion.period"),
            (board(-1.0), "adhesion.period"),
            (
                AdhesionPattern::Random {
                    mean: 0.0,
                    contrast: 0.5,
                    correlation_length: 1.0,
                    seed: 0,
                },
                "material.gamma",
            ),
            (
                AdhesionPattern::Random {
                    mean: f64::INFINITY,
                    contrast: 0.5,
                    correlation_length: 1.0,
                    seed: 0,
                },
                "material.gamma",
            ),
            (random(-0.5, 1.0, 0), "adhesion.contrast"),
            (random(f64::NAN, 1.0, 0), "adhesion.contrast"),
            (random(0.5, 0.0, 0), "adhesion.correlation_length"),
            (random(0.5, f64::INFINITY, 0), "adhesion.correlation_length"),
            (random(0.0, -1.0, 0), "adhesion.correlation_length"),
        ];
        for (pattern, field) in cases {
            let e = pattern.field(&g).unwrap_err();
            assert!(matches!(e, GeometryError::OutOfRange { .. }), "{e}");
            assert!(e.to_string().contains(field), "{pattern:?}: {e}");
        }
        // Exactly two elements per period is allowed, also as a rounded product.
        assert!(stripes(0.2, 0.5).field(&g).is_ok());
        assert!(board(2.0 * 0.1).field(&g).is_ok());
        assert!(stripes(0.1 * 3.0 - 0.1, 0.5).field(&g).is_ok());
    }
}
