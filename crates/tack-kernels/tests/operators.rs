//! Operator tests: the FFT operators against brute-force sums, closed forms and symmetry.

use ndarray::{Array2, ArrayView2};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;
use tack_geometry::{Boundary, Grid};
use tack_kernels::{
    ElasticOperator, FreeOperator, PeriodicOperator, SELF_COMPLIANCE, love_rectangle,
};

fn random_field(nx: usize, ny: usize, seed: u64) -> Array2<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    Array2::from_shape_fn((nx, ny), |_| rng.random_range(-1.0..1.0))
}

fn apply(op: &mut dyn ElasticOperator, p: ArrayView2<f64>) -> Array2<f64> {
    let mut u = Array2::zeros(p.dim());
    op.apply(p, u.view_mut());
    u
}

fn max_abs(a: &Array2<f64>) -> f64 {
    a.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// Direct O(N²) summation of the influence matrix.
fn brute_force(p: &Array2<f64>, dx: f64, e_star: f64) -> Array2<f64> {
    let (nx, ny) = p.dim();
    Array2::from_shape_fn((nx, ny), |(i, j)| {
        let mut s = 0.0;
        for ((k, l), &pk) in p.indexed_iter() {
            let ox = (i as f64 - k as f64) * dx;
            let oy = (j as f64 - l as f64) * dx;
            s += love_rectangle(ox, oy, dx / 2.0, dx / 2.0) / e_star * pk;
        }
        s
    })
}

#[test]
fn free_operator_equals_direct_summation() {
    // Round-off of an FFT of size M grows like ε·log M; 1e-12 relative leaves a wide margin.
    for (nx, ny, dx, e) in [
        (7, 5, 0.3, 2.0),
        (16, 16, 1.0, 1.0),
        (1, 9, 0.5, 3.0),
        (12, 1, 2.0, 1.5),
    ] {
        let grid = Grid::new(nx, ny, dx, Boundary::Free).unwrap();
        let mut op = FreeOperator::new(grid, e).unwrap();
        let p = random_field(nx, ny, 7 + nx as u64);
        let fast = apply(&mut op, p.view());
        let slow = brute_force(&p, dx, e);
        let rel = max_abs(&(&fast - &slow)) / max_abs(&slow);
        assert!(rel < 1e-12, "{nx}x{ny}: rel = {rel:e}");
    }
}

#[test]
fn self_influence_and_far_field_of_one_element() {
    let (n, dx, e) = (257, 0.01, 2.5);
    let grid = Grid::square(n, dx, Boundary::Free).unwrap();
    let mut op = FreeOperator::new(grid, e).unwrap();
    let mut p = Array2::zeros((n, n));
    let c = n / 2;
    p[[c, c]] = 3.0;
    let u = apply(&mut op, p.view());
    let w0 = u[[c, c]] * e / (3.0 * dx);
    assert!((w0 - 1.1222).abs() < 1e-4, "self influence {w0}");
    assert!((op.self_compliance() * e / dx - SELF_COMPLIANCE).abs() < 1e-15);
    // Far field: u → F/(π E* r); the finite element size adds a relative O((Δx/r)²) correction.
    let force = 3.0 * dx * dx;
    for k in [20usize, 60, 128] {
        let r = k as f64 * dx;
        let point = force / (PI * e * r);
        let rel = (u[[c + k, c]] - point).abs() / point;
        assert!(rel < 0.05 / (k * k) as f64, "r = {k} dx: rel {rel:e}");
    }
}

#[test]
fn periodic_operator_reproduces_cosine_solution() {
    // u = 2 p̂/(E* q) cos(q·x) is exact for the spectral kernel: only round-off remains.
    let (nx, ny, dx, e) = (32, 24, 0.25, 1.7);
    let grid = Grid::new(nx, ny, dx, Boundary::Periodic).unwrap();
    let mut op = PeriodicOperator::new(grid, e).unwrap();
    for (mx, my) in [(1, 0), (3, 2), (16, 0), (5, 12)] {
        let qx = 2.0 * PI * mx as f64 / grid.lx();
        let qy = 2.0 * PI * my as f64 / grid.ly();
        let q = qx.hypot(qy);
        let phase = |i: usize, j: usize| qx * grid.x(i) + qy * grid.y(j);
        let p = Array2::from_shape_fn((nx, ny), |(i, j)| 0.7 * phase(i, j).cos());
        let exact =
            Array2::from_shape_fn((nx, ny), |(i, j)| 2.0 * 0.7 / (e * q) * phase(i, j).cos());
        let u = apply(&mut op, p.view());
        let err = max_abs(&(&u - &exact)) / max_abs(&exact);
        assert!(err < 1e-12, "mode ({mx},{my}): {err:e}");
    }
}

#[test]
fn periodic_operator_drops_the_mean_and_inverts() {
    let grid = Grid::new(16, 8, 1.0, Boundary::Periodic).unwrap();
    let mut op = PeriodicOperator::new(grid, 1.0).unwrap();
    let p0 = random_field(16, 8, 3);
    let u = apply(&mut op, p0.view());
    assert!(u.mean().unwrap().abs() < 1e-14);
    let mut p = Array2::zeros((16, 8));
    assert!(op.solve_zero_mean(u.view(), p.view_mut()));
    let expected = &p0 - p0.mean().unwrap();
    assert!(max_abs(&(&p - &expected)) < 1e-12);
}

#[test]
fn periodic_self_compliance_approaches_love_value() {
    // The spectral kernel over the square Brillouin zone integrates to 4 ln(1+√2)/π·Δx/E*;
    // dropping the q = 0 cell costs O(1/N).
    let n = 512;
    let grid = Grid::square(n, 1.0, Boundary::Periodic).unwrap();
    let op = PeriodicOperator::new(grid, 1.0).unwrap();
    let rel = (op.self_compliance() - SELF_COMPLIANCE).abs() / SELF_COMPLIANCE;
    assert!(rel < 2.0 / n as f64, "rel {rel:e}");
}

#[test]
fn influence_matrices_are_symmetric() {
    let cases = [
        (Grid::new(9, 6, 0.5, Boundary::Free).unwrap(), 1.0),
        (Grid::new(9, 6, 0.5, Boundary::Periodic).unwrap(), 2.0),
    ];
    for (grid, e) in cases {
        let mut op = tack_kernels::operator_for(grid, e).unwrap();
        let a = random_field(9, 6, 11);
        let b = random_field(9, 6, 12);
        let kb = apply(op.as_mut(), b.view());
        let ka = apply(op.as_mut(), a.view());
        let (ab, ba) = ((&a * &kb).sum(), (&b * &ka).sum());
        assert!((ab - ba).abs() < 1e-13 * ab.abs().max(1.0), "{ab} vs {ba}");
        // Positive definiteness on a random field (free) / semi-definiteness (periodic).
        assert!((&a * &ka).sum() > 0.0);
    }
}

#[test]
fn rejects_bad_modulus() {
    let grid = Grid::square(4, 1.0, Boundary::Free).unwrap();
    for e in [0.0, -1.0, f64::NAN] {
        let err = tack_kernels::operator_for(grid, e).err().unwrap();
        assert!(err.to_string().contains("material.e_star"));
    }
}
