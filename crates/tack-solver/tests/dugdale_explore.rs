use tack_geometry::{Boundary, Grid, Sphere, Surface};
use tack_kernels::operator_for;
use tack_solver::{AdhesionLaw, AdhesiveOptions, AdhesiveSolver, ApproachPath, SnapshotRequest};

#[test]
#[ignore]
fn explore() {
    let lambda: f64 = std::env::var("LAMBDA").map(|s| s.parse().unwrap()).unwrap_or(1.0);
    let per: f64 = std::env::var("PER").map(|s| s.parse().unwrap()).unwrap_or(10.0);
    let sigma0 = lambda / (2.0 * (9.0 / (16.0 * std::f64::consts::PI)).powf(1.0 / 3.0));
    let h0 = 1.0 / sigma0;
    let dx = 1.52 / per;
    let half = (2.0 * (2.0 * h0 + 3.0)).sqrt().max(3.0);
    let n = 2 * (half / dx) as usize + 1;
    let grid = Grid::square(n, dx, Boundary::Free).unwrap();
    let s = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    let op = operator_for(grid, 1.0).unwrap();
    let mut solver =
        AdhesiveSolver::with_law(op, &s, 1.0, AdhesionLaw::Dugdale { sigma0 }, AdhesiveOptions::default()).unwrap();
    let path = ApproachPath {
        start: -h0 - 0.2,
        max_approach: 2.0,
        load_step: 0.05,
        unload_step: 0.02,
        coarse_unload_step: None,
        retract_to: None,
        max_steps: 100_000,
    };
    let t = std::time::Instant::now();
    let r = solver.run_path(&path, &SnapshotRequest::None, &mut ()).unwrap();
    println!("n = {n} lambda {lambda} sigma0 {sigma0} h0 {h0} time {:?}", t.elapsed());
    for (rec, ph) in r.records.iter().zip(&r.phases) {
        println!(
            "{ph:?} d {:+.4} F/pi {:+.5} nb {} nz {} rounds {} cg {} conv {}",
            rec.approach,
            rec.force / std::f64::consts::PI,
            rec.n_bonded,
            rec.n_cohesive,
            rec.active_set_iterations,
            rec.cg_iterations,
            rec.converged
        );
    }
    println!("pull-off F/(pi gamma R) = {}", r.pull_off_force() / std::f64::consts::PI);
}
