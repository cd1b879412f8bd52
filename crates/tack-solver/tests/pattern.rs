//! A work of adhesion that varies over the surface (`AdhesiveSolver::set_gamma_map`) against
//! the exact zero-range answers of `tack_analytics::patterned`: a sphere with a strong core
//! (stick-slip at the ring), a Kendall punch with a weak rim, and the straight fronts of a
//! periodic strip punch crossing stripes.

use ndarray::Array2;
use std::f64::consts::PI;
use tack_analytics::{
    axisymmetric_retraction, jkr_pull_off_radius, kendall_pull_off, strip_punch_release_tension,
};
use tack_geometry::{Boundary, FlatPunch, Grid, Sphere, Surface};
use tack_kernels::operator_for;
use tack_solver::{
    AdhesiveOptions, AdhesiveSolver, ApproachPath, KAPPA, KAPPA_LINE, PathResult, SnapshotRequest,
};

/// Runs `surface` with the work of adhesion `gamma(x, y)` sampled at element centres, loaded in
/// one step to `depth` and retracted by `step` until detached.
fn run_pattern(
    surface: &Surface,
    gamma: impl Fn(f64, f64) -> f64,
    kappa: f64,
    depth: f64,
    step: f64,
) -> PathResult {
    let grid = *surface.grid();
    let (nx, ny) = grid.shape();
    let dx = grid.dx();
    let map = Array2::from_shape_fn((nx, ny), |(i, j)| {
        let x = (i as f64 - (nx / 2) as f64) * dx;
        let y = (j as f64 - (ny / 2) as f64) * dx;
        gamma(x, y)
    });
    let op = operator_for(grid, 1.0).unwrap();
    let mut solver =
        AdhesiveSolver::new(op, surface, 1.0, kappa, AdhesiveOptions::default()).unwrap();
    solver.set_gamma_map(map.view()).unwrap();
    let path = ApproachPath {
        start: depth,
        max_approach: depth,
        load_step: depth.abs().max(step),
        unload_step: step,
        coarse_unload_step: None,
        refine_pull_off: false,
        retract_to: None,
        max_steps: 200_000,
    };
    let r = solver
        .run_path(&path, &SnapshotRequest::None, &mut ())
        .unwrap();
    assert!(r.completed && r.all_converged());
    r
}

/// A sphere (E* = R = 1) with γ0 outside r1 = a_c(γ0) and 4γ0 inside, on a free grid of
/// `ratio` elements per a_c(γ0), loaded to a contact radius 2a_c and retracted. Returns the
/// pull-off over the exact one and the mean force error along the path over F_JKR(γ0).
fn sphere_with_a_strong_core(ratio: f64) -> (f64, f64) {
    let (e, r, g0) = (1.0, 1.0, 0.002);
    let a_c = jkr_pull_off_radius(e, g0, r);
    let r1 = a_c;
    let gamma = |rho: f64| if rho < r1 { 4.0 * g0 } else { g0 };
    let dx = a_c / ratio;
    let n = 2 * (3.0 * ratio).ceil() as usize + 1;
    let grid = Grid::square(n, dx, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Sphere::new(r).unwrap());
    let depth = (2.0 * a_c).powi(2) / r;
    let step = 0.02 * a_c * a_c / r;
    let result = run_pattern(&surface, |x, y| gamma(x.hypot(y)), KAPPA, depth, step);
    assert!(result.records.iter().all(|s| !s.edge_contact));
    // The exact path from the bonded disc the load step left (the elements with f < d: the
    // disc of area n_bonded·Δx²).
    let bonded = (result.records[0].n_bonded as f64 * dx * dx / PI).sqrt();
    let ds: Vec<f64> = result.records.iter().map(|s| s.approach).collect();
    let exact = axisymmetric_retraction(e, r, gamma, bonded, &ds[1..]);
    let f_exact = exact.iter().map(|s| s.force).fold(f64::INFINITY, f64::min);
    let scale = 1.5 * PI * g0 * r;
    let mean_error = result.records[1..]
        .iter()
        .zip(&exact)
        .map(|(s, x)| (s.force - x.force).abs())
        .sum::<f64>()
        / exact.len() as f64
        / scale;
    (result.pull_off_force() / f_exact, mean_error)
}

#[test]
fn a_sphere_with_a_strong_core_follows_the_exact_stick_slip_path() {
    // Exact (zero-range, approach control): the front recedes with γ0 along JKR down to
    // r1 = a_c (F_JKR(γ0) there), sticks at the ring until G(r1, d) = 4γ0, where the force is
    // the greatest, and then slips off. Measured at a_c/Δx = 10, 20, 40 (steps 0.02 a_c²/R):
    // F/F_exact 1.0243, 1.0114, 1.0032 (Richardson 0.9949); mean |ΔF|/F_JKR(γ0) along the
    // path 0.131, 0.064, 0.039 (first order: the front sits on a stair-stepped ring). The
    // criterion is too adhesive, as on the uniform sphere; tolerances: above 1, each finer
    // closer, Richardson within 2%, the mean path error falling.
    let runs: Vec<(f64, f64)> = [10.0, 20.0, 40.0]
        .iter()
        .map(|&k| sphere_with_a_strong_core(k))
        .collect();
    for ((k, (ratio, err)), _) in [10, 20, 40].iter().zip(&runs).zip(0..) {
        println!("a_c/Δx = {k}: F/F_exact = {ratio:.4}, mean |ΔF|/F_JKR = {err:.4}");
    }
    let richardson = 2.0 * runs[2].0 - runs[1].0;
    println!("Richardson {richardson:.4}");
    assert!(runs[0].0 > runs[1].0 && runs[1].0 > runs[2].0 && runs[2].0 > 1.0);
    assert!((richardson - 1.0).abs() < 0.02, "{richardson}");
    assert!(runs[0].1 > runs[1].1 && runs[1].1 > runs[2].1);
}

/// A circular flat punch of radius a = 1 with γ_rim outside r1 = 0.7 and γ_core = 8 γ_rim
/// inside (E* = 1), `ratio` elements per a. Returns the pull-off over the exact one,
/// √(8π r1³E*γ_core) (the rim lets go at Kendall's √(8πa³E*γ_rim) first, the front jumps to r1
/// and sticks there).
fn punch_with_a_weak_rim(ratio: f64) -> f64 {
    let (e, a, r1, g_rim) = (1.0, 1.0, 0.7, 0.01);
    let g_core = 8.0 * g_rim;
    let dx = a / ratio;
    let n = 2 * (1.6 * ratio).ceil() as usize + 1;
    let grid = Grid::square(n, dx, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &FlatPunch::circular(a).unwrap());
    let gamma = |x: f64, y: f64| if x.hypot(y) < r1 { g_core } else { g_rim };
    let d_core = (2.0 * PI * r1 * g_core / e).sqrt();
    let result = run_pattern(&surface, gamma, KAPPA, 0.01 * d_core, 0.002 * d_core);
    let exact = kendall_pull_off(e, g_core, r1).max(kendall_pull_off(e, g_rim, a));
    assert!(kendall_pull_off(e, g_core, r1) > kendall_pull_off(e, g_rim, a));
    -result.pull_off_force() / exact
}

#[test]
fn a_kendall_punch_with_a_weak_rim_lets_go_at_its_core() {
    // Measured F/F_exact at a/Δx = 10, 20, 40: 0.9522, 0.9877, 0.9995 (Richardson 1.0114):
    // the stair-stepped core holds a little less than its circle at coarse meshes. Tolerances:
    // within 15% at the finest, Richardson within 3% (a punch's edge is the criterion's
    // hardest front: the uniform Kendall punch converges at order ≈ 1 from either side).
    let v: Vec<f64> = [10.0, 20.0, 40.0]
        .iter()
        .map(|&k| punch_with_a_weak_rim(k))
        .collect();
    let richardson = 2.0 * v[2] - v[1];
    println!("punch with a weak rim: F/F_exact = {v:.4?}, Richardson {richardson:.4}");
    assert!((v[2] - 1.0).abs() < 0.15, "{v:?}");
    assert!((richardson - 1.0).abs() < 0.03, "{richardson}");
}

/// A periodic strip punch (period λ = 1, half-width c0 = λ/4, E* = 1) with γ_low on
/// c1 < |x| ≤ c0 and 4γ_low inside (c1 = 0.15 λ), `n` elements per period. The straight fronts
/// leave the punch's edge at |p̄| = √(2E*γ_low tan ψ0/λ), cross the weak stripe, stick at c1
/// and leave it at √(2E*·4γ_low·tan ψ1/λ), the pull-off. Returns the pull-off over that.
fn strip_punch_crossing_stripes(n: usize) -> f64 {
    let (e, l, g_low) = (1.0, 1.0, 0.01);
    let dx = l / n as f64;
    let grid = Grid::new(n, 1, dx, Boundary::Periodic).unwrap();
    let (half, inner) = (n / 4, (3 * n) / 20);
    let c = n / 2;
    let heights = Array2::from_shape_fn(
        (n, 1),
        |(i, _)| {
            if i.abs_diff(c) < half { 0.0 } else { 1.0 }
        },
    );
    let surface = Surface::new(grid, heights).unwrap();
    // Element i covers |x| ≤ (|i − c| + 1/2)Δx: the strong stripe is the elements within c1.
    let gamma = |x: f64, _| {
        if x.abs() < inner as f64 * dx {
            4.0 * g_low
        } else {
            g_low
        }
    };
    let c0 = (2 * half - 1) as f64 * dx / 2.0;
    let c1 = (2 * inner - 1) as f64 * dx / 2.0;
    let exact = strip_punch_release_tension(e, 4.0 * g_low, l, c1 + dx / 2.0);
    assert!(exact > strip_punch_release_tension(e, g_low, l, c0 + dx / 2.0));
    let depth = 1e-4;
    let result = run_pattern(&surface, gamma, KAPPA_LINE, depth, 2e-4 * exact);
    let p_min = result
        .records
        .iter()
        .filter(|s| !s.full_contact)
        .map(|s| s.mean_pressure)
        .fold(f64::INFINITY, f64::min);
    -p_min / exact
}

#[test]
fn straight_fronts_crossing_stripes_are_held_by_the_strong_one() {
    // The half-widths on element boundaries, c = (2k − 1)Δx/2 + Δx/2 (the front between the
    // last bonded element and the first free one). Measured at λ/Δx = 1000, 4000: 0.9966,
    // 0.9990 (steps of 2e-4 of the answer in approach). KAPPA_LINE was settled on the uniform
    // strip punch to 1e-3, so the tolerance is 1% at the finer mesh and the coarser no closer.
    let v: Vec<f64> = [1000, 4000]
        .iter()
        .map(|&n| strip_punch_crossing_stripes(n))
        .collect();
    println!("strip punch crossing stripes: |p̄|/exact = {v:.4?}");
    assert!((v[1] - 1.0).abs() < 0.01, "{v:?}");
    assert!((v[0] - 1.0).abs() >= (v[1] - 1.0).abs() - 1e-3, "{v:?}");
}

#[test]
fn a_uniform_map_gives_the_equilibria_of_the_uniform_solver() {
    let grid = Grid::square(41, 0.05, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    let path = ApproachPath::load_retract(0.0, 0.2, 0.02, 0.01).unwrap();
    let mut results = Vec::new();
    for with_map in [false, true] {
        let op = operator_for(grid, 1.0).unwrap();
        let mut s =
            AdhesiveSolver::new(op, &surface, 0.05, KAPPA, AdhesiveOptions::default()).unwrap();
        if with_map {
            s.set_gamma_map(Array2::from_elem((41, 41), 0.05).view())
                .unwrap();
        }
        let r = s.run_path(&path, &SnapshotRequest::None, &mut ()).unwrap();
        results.push(r.records.iter().map(|s| s.force).collect::<Vec<_>>());
    }
    // The map path adds a floor to the inexact rounds' margin, so the rounds may differ; the
    // equilibria may not.
    for (a, b) in results[0].iter().zip(&results[1]) {
        assert!((a - b).abs() < 1e-9, "{a} vs {b}");
    }
}

#[test]
fn a_uniform_map_keeps_the_bits_of_the_dugdale_law() {
    use tack_solver::{AdhesionLaw, Dugdale};
    let grid = Grid::square(41, 0.05, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    let path = ApproachPath::load_retract(-0.05, 0.2, 0.02, 0.01).unwrap();
    let law = AdhesionLaw::Dugdale(Dugdale { sigma0: 0.5 });
    let mut results = Vec::new();
    for with_map in [false, true] {
        let op = operator_for(grid, 1.0).unwrap();
        let mut s =
            AdhesiveSolver::with_law(op, &surface, 0.05, law.clone(), AdhesiveOptions::default())
                .unwrap();
        if with_map {
            s.set_gamma_map(Array2::from_elem((41, 41), 0.05).view())
                .unwrap();
        }
        let r = s.run_path(&path, &SnapshotRequest::None, &mut ()).unwrap();
        results.push(r.records.iter().map(|s| s.force).collect::<Vec<_>>());
    }
    assert_eq!(results[0], results[1]);
}

#[test]
fn a_dugdale_map_scales_the_tension_at_one_range() {
    // γ_ij = 2γ everywhere at reference γ and σ0 is the uniform law of 2γ and 2σ0 (the same
    // range γ/σ0): the map's tensions σ0·γ_ij/γ must carry the whole physics.
    use tack_solver::{AdhesionLaw, Dugdale};
    let grid = Grid::square(41, 0.05, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    let path = ApproachPath::load_retract(-0.05, 0.2, 0.02, 0.01).unwrap();
    let run = |gamma: f64, sigma0: f64, map: Option<f64>| {
        let op = operator_for(grid, 1.0).unwrap();
        let law = AdhesionLaw::Dugdale(Dugdale { sigma0 });
        let mut s =
            AdhesiveSolver::with_law(op, &surface, gamma, law, AdhesiveOptions::default()).unwrap();
        if let Some(g) = map {
            s.set_gamma_map(Array2::from_elem((41, 41), g).view())
                .unwrap();
        }
        let r = s.run_path(&path, &SnapshotRequest::None, &mut ()).unwrap();
        assert!(r.completed && r.all_converged());
        r.records.iter().map(|s| s.force).collect::<Vec<_>>()
    };
    let (mapped, uniform) = (run(0.05, 0.5, Some(0.1)), run(0.1, 1.0, None));
    let scale = uniform.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    for (a, b) in mapped.iter().zip(&uniform) {
        assert!((a - b).abs() < 1e-9 * scale, "{a} vs {b}");
    }
    // And it is not the reference's own law.
    let reference = run(0.05, 0.5, None);
    assert!(
        reference
            .iter()
            .zip(&uniform)
            .any(|(a, b)| (a - b).abs() > 1e-3 * scale)
    );
}

#[test]
fn bad_maps_are_refused_naming_the_field() {
    let grid = Grid::square(8, 0.1, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    let op = operator_for(grid, 1.0).unwrap();
    let mut s = AdhesiveSolver::new(op, &surface, 0.05, KAPPA, AdhesiveOptions::default()).unwrap();
    let e = s
        .set_gamma_map(Array2::from_elem((8, 7), 0.05).view())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("adhesion.gamma_map") && e.contains("8 × 7"),
        "{e}"
    );
    let mut bad = Array2::from_elem((8, 8), 0.05);
    bad[[3, 4]] = -0.1;
    let e = s.set_gamma_map(bad.view()).unwrap_err().to_string();
    assert!(e.contains("adhesion.gamma_map = -0.1"), "{e}");
}
