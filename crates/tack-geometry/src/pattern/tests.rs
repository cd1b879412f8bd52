//! Tests of the adhesion patterns: their fields on grids, checks and the seeded random map.

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
