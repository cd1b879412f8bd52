//! Tests of random roughness: spectra, the continuous surface per seed and band, the checks.

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
                    let map = |i: usize, n: usize| factor * i - factor * (n / 2) + factor * n / 2;
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
