//! Power-law bodies z = c·r^m in the JKR limit against the exact method-of-dimensionality-
//! reduction pull-off (`tack_analytics::power_law_pull_off_force`): the cone (m = 1, tip
//! included), the sphere's paraboloid (m = 2) and a flat-tipped body (m = 4), on two meshes.

use tack_analytics::{mdr_shape_factor, power_law_pull_off_force, power_law_pull_off_radius};
use tack_geometry::{Boundary, Grid, PowerLaw, Surface};
use tack_kernels::operator_for;
use tack_solver::{AdhesiveOptions, AdhesiveSolver, ApproachPath, KAPPA, SnapshotRequest};

/// The pull-off of c·r^m (E* = γ = c = 1) over the MDR value, on a free grid of `ratio`
/// elements per pull-off radius a_F: one load step to the approach whose non-adhesive contact
/// radius is 1.6 a_F, then retraction by 0.1/ratio of that approach until detached.
fn pull_off_ratio(m: f64, ratio: f64) -> f64 {
    let (e, gamma, c) = (1.0, 1.0, 1.0);
    let a_f = power_law_pull_off_radius(e, gamma, c, m);
    let dx = a_f / ratio;
    // One step bonds every element with c·r^m < d: a disc of radius κ_m^(1/m)·1.6 a_F (the
    // rigid body's penetration), held with a 20% margin.
    let bonded = mdr_shape_factor(m).powf(1.0 / m) * 1.6;
    let n = 2 * (1.2 * bonded * ratio).ceil() as usize + 3;
    let grid = Grid::square(n, dx, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &PowerLaw::new(c, m).unwrap());
    let op = operator_for(grid, e).unwrap();
    let mut solver =
        AdhesiveSolver::new(op, &surface, gamma, KAPPA, AdhesiveOptions::default()).unwrap();
    let depth = mdr_shape_factor(m) * c * (1.6 * a_f).powf(m);
    let path = ApproachPath {
        start: depth,
        max_approach: depth,
        load_step: depth,
        unload_step: 0.1 * depth / ratio,
        coarse_unload_step: None,
        refine_pull_off: false,
        retract_to: None,
        max_steps: 100_000,
    };
    let r = solver
        .run_path(&path, &SnapshotRequest::None, &mut ())
        .unwrap();
    assert!(
        r.completed && r.all_converged(),
        "m = {m}, a_F/Δx = {ratio}"
    );
    assert!(
        r.records.iter().all(|s| !s.edge_contact),
        "m = {m}: the grid cuts the contact"
    );
    r.pull_off_force() / power_law_pull_off_force(e, gamma, c, m)
}

#[test]
fn power_law_pull_off_converges_to_the_mdr_value() {
    // Measured F/F_MDR at a_F/Δx = 10, 20 (Richardson 2F(20) − F(10)):
    //   m = 1 (cone): 1.2121, 1.1390 (1.066); at 40: 1.0625 (Richardson from 20, 40: 0.986):
    //                 first order once a_F/Δx ≥ 20 (0.61, then 1.15), with a larger constant
    //   m = 2:        1.1285, 1.0638 (0.9991), the sphere's criterion error
    //   m = 4:        1.1004, 1.0487 (0.9970), the exact detach/attach loop's values
    //                 (`round_tolerance: None`) to 1e-9; with the inexact rounds' detach
    //                 margin at 0.3% (before) they pulled off early, 1.0823 and 1.0392
    // Too adhesive and first order, as on the sphere (docs/theory.md §9). Tolerances: each
    // value above 1 and the finer closer; Richardson within 1% for m = 2, 4; the cone's
    // fine value within 15% (its Richardson is not yet asymptotic at 10/20).
    for (m, fine_below) in [(1.0, 1.15), (2.0, 1.07), (4.0, 1.055)] {
        let (coarse, fine) = (pull_off_ratio(m, 10.0), pull_off_ratio(m, 20.0));
        let richardson = 2.0 * fine - coarse;
        println!("m = {m}: F/F_MDR = {coarse:.4}, {fine:.4}; Richardson {richardson:.4}");
        assert!(coarse > fine && fine > 1.0 && fine < fine_below, "m = {m}");
        if m > 1.0 {
            assert!((richardson - 1.0).abs() < 0.01, "m = {m}: {richardson}");
        }
    }
}
