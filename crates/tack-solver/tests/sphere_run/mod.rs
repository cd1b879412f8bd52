//! The smooth sphere's path of the law tests (`smooth.rs`, `custom_law.rs`,
//! `smoothed_dugdale.rs`, `dugdale.rs`): a sphere R = 1 on E* = 1 with γ = 1, free grid, loaded
//! and retracted in equal steps.

// Each test file uses the entry point it needs.
#![allow(dead_code)]

use tack_geometry::{Boundary, Grid, Sphere, Surface};
use tack_kernels::operator_for;
use tack_solver::{
    AdhesionLaw, AdhesiveOptions, AdhesiveSolver, ApproachPath, PathResult, SnapshotRequest,
};

/// A sphere R = 1 on E* = 1 with γ = 1 under `law`, on a free grid of `n` elements of `dx`,
/// loaded from `start` to `depth` and retracted in steps of `step` to `end`.
pub fn run(law: &AdhesionLaw, n: usize, dx: f64, path: (f64, f64, f64, f64)) -> PathResult {
    let (start, depth, step, end) = path;
    run_to(law, n, dx, (start, depth, step), Some(end))
}

/// [`run`], retracted to `end` or, without one, until nothing is in contact or under the law.
pub fn run_to(
    law: &AdhesionLaw,
    n: usize,
    dx: f64,
    path: (f64, f64, f64),
    end: Option<f64>,
) -> PathResult {
    let grid = Grid::square(n, dx, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    let op = operator_for(grid, 1.0).unwrap();
    let mut solver =
        AdhesiveSolver::with_law(op, &surface, 1.0, law.clone(), AdhesiveOptions::default())
            .unwrap();
    let (start, depth, step) = path;
    let path = ApproachPath {
        start,
        max_approach: depth,
        load_step: step,
        unload_step: step,
        coarse_unload_step: None,
        refine_pull_off: false,
        retract_to: end,
        max_steps: 100_000,
    };
    solver
        .run_path(&path, &SnapshotRequest::None, &mut ())
        .unwrap()
}
