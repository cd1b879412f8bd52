//! Cropping a free-boundary problem to where contact can occur changes nothing but the cost.

use std::time::Instant;
use tack_geometry::{Boundary, Grid, RoughSpec, Sphere, Surface, rough_surface};
use tack_kernels::operator_for;
use tack_solver::{
    AdhesiveOptions, AdhesiveSolver, ApproachPath, KAPPA, PathResult, SnapshotRequest,
    SolverOptions, contact_window, touches_edge,
};

fn solve(surface: &Surface, gamma: f64, path: &ApproachPath) -> (PathResult, bool, f64) {
    // Tight CG tolerance: both grids solve the same discrete problem, so their answers may differ
    // only by the solver tolerance (the preconditioner and FFT sizes differ with the grid).
    let options = AdhesiveOptions {
        cg: SolverOptions {
            tolerance: 1e-13,
            max_iterations: 10_000,
        },
        ..AdhesiveOptions::default()
    };
    let op = operator_for(*surface.grid(), 1.0).unwrap();
    let mut s = AdhesiveSolver::new(op, surface, gamma, KAPPA, options).unwrap();
    let t = Instant::now();
    let r = s.run_path(path, &SnapshotRequest::None, &mut ()).unwrap();
    let secs = t.elapsed().as_secs_f64();
    (r, touches_edge(s.bonded()), secs)
}

#[test]
fn cropped_sphere_with_roughness_gives_the_same_curve() {
    // Paper setting: L = R, random roughness H = 0.5 on the sphere, q0 = 2π/L, q1 = π/Δx.
    let (r_s, n) = (1.0, 128);
    let grid = Grid::square(n, r_s / n as f64, Boundary::Free).unwrap();
    let gamma = 2.83e-4; // a_c ≈ 0.1 R with E* = 1
    let rough = rough_surface(grid, &RoughSpec::paper_defaults(grid, 5e-4, 0.5, 7)).unwrap();
    let range = rough.max() - rough.min();
    let mut surface = Surface::from_shape(grid, &Sphere::new(r_s).unwrap());
    surface.add(&rough).unwrap();
    let d_max = 0.02;
    let path = ApproachPath {
        start: surface.min() + 0.002,
        max_approach: d_max,
        load_step: 0.002,
        unload_step: 0.0005,
        coarse_unload_step: None,
        refine_pull_off: false,
        retract_to: None,
        max_steps: 10_000,
    };
    let window = contact_window(&surface, d_max, range, 1.0, gamma).unwrap();
    let cropped = surface.window(&window).unwrap();
    let (full, _, t_full) = solve(&surface, gamma, &path);
    let (crop, edge, t_crop) = solve(&cropped, gamma, &path);
    eprintln!(
        "crop {:?} of {n}²: full {t_full:.2} s, cropped {t_crop:.2} s, speed-up {:.2}×, F_min {:.6e}",
        window.shape(),
        t_full / t_crop,
        full.pull_off_force()
    );
    assert!(
        window.shape().0 < n && window.shape().1 < n,
        "the crop must remove something"
    );
    assert!(!edge, "contact reached the crop edge");
    assert!(full.all_converged() && crop.all_converged());
    assert_eq!(full.records.len(), crop.records.len());
    let scale = full
        .records
        .iter()
        .map(|r| r.force.abs())
        .fold(0.0, f64::max);
    for (a, b) in full.records.iter().zip(&crop.records) {
        assert_eq!(
            a.n_bonded, b.n_bonded,
            "bonded sets differ at d = {}",
            a.approach
        );
        assert!(
            (a.force - b.force).abs() <= 1e-10 * scale,
            "d = {}: {} vs {}",
            a.approach,
            a.force,
            b.force
        );
    }
}
