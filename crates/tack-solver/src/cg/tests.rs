//! Tests of the bonded-set CG: a small SPD system against dense elimination, a carried start,
//! the iteration cap and the added diagonal.

use super::*;
use tack_geometry::{Boundary, Grid};
use tack_kernels::FreeOperator;

const N: usize = 10;

/// A paraboloid `f = r²/2` on a free 10 × 10 grid (Δx = 0.1, E* = 1) bonded on a disc of 29
/// elements around its apex, pressed by d = 0.05: a symmetric positive definite `K_CC`.
fn problem() -> (FreeOperator, Array2<f64>, Array2<bool>, f64) {
    let dx = 0.1;
    let op = FreeOperator::new(Grid::square(N, dx, Boundary::Free).unwrap(), 1.0).unwrap();
    let c = (N / 2) as f64;
    let r2 = |i: usize, j: usize| ((i as f64 - c).powi(2) + (j as f64 - c).powi(2)) * dx * dx;
    let heights = Array2::from_shape_fn((N, N), |(i, j)| r2(i, j) / 2.0);
    let bonded = Array2::from_shape_fn((N, N), |(i, j)| r2(i, j) <= 0.09 + 1e-12);
    (op, heights, bonded, 0.05)
}

/// `(K_CC + diag(c)) p_C = (d − f)_C` by dense Gaussian elimination (columns of K from unit
/// loads; `c = 0` without a diagonal).
fn dense_solution(
    op: &mut FreeOperator,
    heights: &Array2<f64>,
    bonded: &Array2<bool>,
    diagonal: Option<&Array2<f64>>,
    d: f64,
) -> Array2<f64> {
    let idx: Vec<(usize, usize)> = bonded
        .indexed_iter()
        .filter(|(_, b)| **b)
        .map(|(k, _)| k)
        .collect();
    let m = idx.len();
    let mut a = vec![vec![0.0; m + 1]; m];
    let (mut unit, mut col) = (Array2::zeros((N, N)), Array2::zeros((N, N)));
    for (c, &e) in idx.iter().enumerate() {
        unit[e] = 1.0;
        op.apply(unit.view(), col.view_mut());
        unit[e] = 0.0;
        for (r, &row) in idx.iter().enumerate() {
            a[r][c] = col[row];
        }
    }
    for (r, &row) in idx.iter().enumerate() {
        a[r][m] = d - heights[row];
        a[r][r] += diagonal.map_or(0.0, |c| c[row]);
    }
    for k in 0..m {
        let pivot = a[k].clone();
        for row in &mut a[k + 1..] {
            let f = row[k] / pivot[k];
            for (x, &y) in row[k..].iter_mut().zip(&pivot[k..]) {
                *x -= f * y;
            }
        }
    }
    let mut x = vec![0.0; m];
    for k in (0..m).rev() {
        let s: f64 = (k + 1..m).map(|c| a[k][c] * x[c]).sum();
        x[k] = (a[k][m] - s) / a[k][k];
    }
    let mut p = Array2::zeros((N, N));
    for (k, &e) in idx.iter().enumerate() {
        p[e] = x[k];
    }
    p
}

/// Counts the products of the operator it wraps.
struct Counting(FreeOperator, usize);

impl ElasticOperator for Counting {
    fn grid(&self) -> &tack_geometry::Grid {
        self.0.grid()
    }
    fn e_star(&self) -> f64 {
        self.0.e_star()
    }
    fn is_half_space(&self) -> bool {
        true
    }
    fn apply(&mut self, p: ArrayView2<f64>, u: ArrayViewMut2<f64>) {
        self.1 += 1;
        self.0.apply(p, u);
    }
    fn self_compliance(&self) -> f64 {
        self.0.self_compliance()
    }
    fn precondition(&mut self, u: ArrayView2<f64>, p: ArrayViewMut2<f64>) {
        self.0.precondition(u, p);
    }
}

/// A round that changed nothing hands its solve to the next, tighter one: started `carried`,
/// the tighter solve continues the last one's iteration (its `K p`, direction and `r·z`), so
/// the two together take the iterations and products of one solve run straight to the tight
/// tolerance; a fresh start from the same pressure pays a product and a restarted iteration.
#[test]
fn a_carried_solve_continues_the_last_one() {
    let (op, heights, bonded, d) = problem();
    let mut op = Counting(op, 0);
    let exact = dense_solution(&mut op.0, &heights, &bonded, None, d);
    let p_max = exact.iter().fold(0.0f64, |m, p| m.max(p.abs()));
    let loose = SolverOptions {
        tolerance: 1e-3,
        max_iterations: 200,
    };
    let tight = SolverOptions {
        tolerance: 1e-12,
        ..loose
    };
    let system = || System {
        heights: heights.view(),
        bonded: bonded.view(),
        held: None,
        diagonal: None,
        d,
    };
    // (iterations, products) of a sequence of solves from zero, each at its tolerance and
    // carried or not.
    let mut run = |plan: &[(&SolverOptions, bool)]| {
        let mut p = Array2::zeros((N, N));
        let (mut w, mut pw) = (Work::new((N, N)), PcgWork::new((N, N)));
        let before = op.1;
        let mut iterations = 0;
        for &(options, carried) in plan {
            let c = pcg_from(
                &mut op,
                system(),
                p.view_mut(),
                &mut w,
                &mut pw,
                options,
                true,
                carried,
            );
            assert!(c.converged && c.iterations >= 1, "{plan:?}: {c:?}");
            iterations += c.iterations;
        }
        let err = (&p - &exact).iter().fold(0.0f64, |m, e| m.max(e.abs()));
        assert!(err <= 1e-9 * p_max, "{plan:?}: error {err} of {p_max}");
        (iterations, op.1 - before)
    };
    let straight = run(&[(&tight, false)]);
    let carried = run(&[(&loose, false), (&tight, true)]);
    let fresh = run(&[(&loose, false), (&tight, false)]);
    assert!(
        carried.0.abs_diff(straight.0) <= 1 && carried.1.abs_diff(straight.1) <= 1,
        "carried {carried:?} against straight {straight:?}"
    );
    assert!(
        fresh.1 > carried.1 && fresh.0 >= carried.0,
        "fresh {fresh:?} against carried {carried:?}"
    );
}

#[test]
fn solves_a_small_spd_system_to_the_tolerance() {
    let (mut op, heights, bonded, d) = problem();
    assert_eq!(bonded.iter().filter(|&&b| b).count(), 29);
    let exact = dense_solution(&mut op, &heights, &bonded, None, d);
    let p_max = exact.iter().fold(0.0f64, |m, p| m.max(p.abs()));
    let options = SolverOptions {
        tolerance: 1e-12,
        max_iterations: 200,
    };
    for preconditioned in [true, false] {
        // Start from a pressure that is wrong everywhere, also off the bonded set.
        let mut p = Array2::from_elem((N, N), 1.0);
        let (mut w, mut pw) = (Work::new((N, N)), PcgWork::new((N, N)));
        let c = pcg(
            &mut op,
            heights.view(),
            bonded.view(),
            d,
            p.view_mut(),
            &mut w,
            &mut pw,
            &options,
            preconditioned,
        );
        assert!(
            c.converged && c.residual <= 1e-12,
            "{preconditioned}: {c:?}"
        );
        assert!(c.iterations >= 3 && c.iterations <= 29, "{c:?}");
        // Off the bonded set p = 0 exactly; on it, the dense solution.
        assert!(p.iter().zip(&bonded).all(|(&p, &b)| b || p == 0.0));
        let err = (&p - &exact).iter().fold(0.0f64, |m, e| m.max(e.abs()));
        assert!(
            err <= 1e-9 * p_max,
            "{preconditioned}: error {err} of {p_max}"
        );
        // `disp` is the product K p, and closes the gap on C to the tolerance.
        let mut u = Array2::zeros((N, N));
        op.apply(p.view(), u.view_mut());
        let du = (&u - &w.disp).iter().fold(0.0f64, |m, e| m.max(e.abs()));
        assert!(du <= 1e-12 * d, "carried K p off by {du}");
        let (mut rr, mut bb, mut n) = (0.0, 0.0, 0.0);
        for ((&f, &u), &b) in heights.iter().zip(&u).zip(&bonded) {
            if b {
                rr += (d - f - u).powi(2);
                bb += (d - f).powi(2);
                n += 1.0;
            }
        }
        let rel = (rr / n).sqrt() / (bb / n).sqrt();
        assert!(rel <= 1e-12, "true residual {rel}");
        // A warm start from the solution needs no iteration.
        let again = pcg(
            &mut op,
            heights.view(),
            bonded.view(),
            d,
            p.view_mut(),
            &mut w,
            &mut pw,
            &options,
            preconditioned,
        );
        assert_eq!(again.iterations, 0);
        assert!(again.converged);
    }
}

#[test]
fn reports_non_convergence_at_the_iteration_cap() {
    let (mut op, heights, bonded, d) = problem();
    let mut p = Array2::zeros((N, N));
    let (mut w, mut pw) = (Work::new((N, N)), PcgWork::new((N, N)));
    let capped = SolverOptions {
        tolerance: 1e-12,
        max_iterations: 2,
    };
    let c = pcg(
        &mut op,
        heights.view(),
        bonded.view(),
        d,
        p.view_mut(),
        &mut w,
        &mut pw,
        &capped,
        true,
    );
    assert!(!c.converged);
    assert_eq!(c.iterations, 2);
    assert!(c.residual > 1e-6 && c.residual < 1.0, "{c:?}");
    // The capped solve still leaves `disp = K p` for the pressure it stopped at.
    let mut u = Array2::zeros((N, N));
    op.apply(p.view(), u.view_mut());
    assert!((&u - &w.disp).iter().all(|e| e.abs() <= 1e-12 * d));
}

/// With a diagonal (the smooth laws' stiff elements: `c` from 0.1 to 0.9 self-compliances on
/// the disc's outer ring, 0 inside), `pcg_from` solves `(K_CC + diag(c)) p_C = (d − f)_C`:
/// the dense solution to 1e-9 of the largest pressure, with and without preconditioning.
#[test]
fn solves_the_set_with_a_diagonal() {
    let (mut op, heights, bonded, d) = problem();
    let k = tack_kernels::ElasticOperator::self_compliance(&op);
    let c = (N / 2) as f64;
    let diag = Array2::from_shape_fn((N, N), |(i, j)| {
        let r2 = ((i as f64 - c).powi(2) + (j as f64 - c).powi(2)) * 0.01;
        if bonded[(i, j)] && r2 > 0.04 + 1e-12 {
            k * (0.1 + 0.8 * ((i + 2 * j) % 5) as f64 / 4.0)
        } else {
            0.0
        }
    });
    assert!(diag.iter().filter(|&&c| c > 0.0).count() >= 8);
    let exact = dense_solution(&mut op, &heights, &bonded, Some(&diag), d);
    let without = dense_solution(&mut op, &heights, &bonded, None, d);
    let p_max = exact.iter().fold(0.0f64, |m, p| m.max(p.abs()));
    // The diagonal matters: the two systems' solutions differ well beyond the tolerance.
    let apart = (&exact - &without)
        .iter()
        .fold(0.0f64, |m, e| m.max(e.abs()));
    assert!(apart > 1e-3 * p_max, "{apart}");
    let options = SolverOptions {
        tolerance: 1e-12,
        max_iterations: 200,
    };
    for preconditioned in [true, false] {
        let mut p = Array2::from_elem((N, N), 1.0);
        let (mut w, mut pw) = (Work::new((N, N)), PcgWork::new((N, N)));
        let system = System {
            heights: heights.view(),
            bonded: bonded.view(),
            held: None,
            diagonal: Some(diag.view()),
            d,
        };
        let conv = pcg_from(
            &mut op,
            system,
            p.view_mut(),
            &mut w,
            &mut pw,
            &options,
            preconditioned,
            false,
        );
        assert!(conv.converged, "{preconditioned}: {conv:?}");
        let err = (&p - &exact).iter().fold(0.0f64, |m, e| m.max(e.abs()));
        assert!(
            err <= 1e-9 * p_max,
            "{preconditioned}: error {err} of {p_max}"
        );
    }
}
