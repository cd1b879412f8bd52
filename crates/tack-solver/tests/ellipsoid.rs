//! The ellipsoid x²/(2Rx) + y²/(2Ry): the non-adhesive contact against the elliptic Hertz
//! solution, and the JKR-limit pull-off against the Johnson–Greenwood approximation
//! (`tack_analytics::elliptic_jkr_pull_off`), whose own error grows with the ellipticity.

use tack_analytics::{elliptic_hertz_from_approach, elliptic_jkr_pull_off};
use tack_geometry::{Boundary, Ellipsoid, Grid, Surface};
use tack_kernels::operator_for;
use tack_solver::{
    AdhesiveOptions, AdhesiveSolver, ApproachPath, ContactSolver, KAPPA, SnapshotRequest,
    SolverOptions,
};

#[test]
fn non_adhesive_ellipsoid_is_elliptic_hertz() {
    // Rx/Ry = 4 (and 1/4, the same contact turned), pressed to d: the contact ellipse's
    // shorter semi-axis spans `k` elements. Measured at b/Δx = 10, 20 (both orientations
    // alike): F/F_H − 1 = +1.1e-4, +4e-5; A/A_H − 1 = +2.7%, +1.1% (the area is counted in
    // whole elements, a first-order rim). Tolerances: force 1e-3, area 4%, both falling.
    let (e, rx, ry) = (1.0, 4.0, 1.0);
    let d = 0.01;
    let hertz = elliptic_hertz_from_approach(e, rx, ry, d);
    let (a, b) = (hertz.semi_axis_x, hertz.semi_axis_y);
    assert!(a > b, "the longer axis lies along the larger radius");
    let mut errors = Vec::new();
    for k in [10.0, 20.0] {
        let dx = b / k;
        let n = 2 * (1.4 * a / dx).ceil() as usize + 1;
        for (rx, ry, grid) in [
            (
                rx,
                ry,
                Grid::new(n, 2 * (1.4 * k) as usize + 1, dx, Boundary::Free),
            ),
            (
                ry,
                rx,
                Grid::new(2 * (1.4 * k) as usize + 1, n, dx, Boundary::Free),
            ),
        ] {
            let grid = grid.unwrap();
            let surface = Surface::from_shape(grid, &Ellipsoid::new(rx, ry).unwrap());
            let op = operator_for(grid, e).unwrap();
            let mut s = ContactSolver::new(op, &surface, SolverOptions::default()).unwrap();
            let st = s.solve(d).unwrap();
            let force = st.force / hertz.force - 1.0;
            let area = st.area / (std::f64::consts::PI * a * b) - 1.0;
            println!("b/Δx = {k}, Rx = {rx}: F/F_H − 1 = {force:+.5}, A/A_H − 1 = {area:+.5}");
            assert!(force.abs() < 1e-3 && area.abs() < 0.04, "{force} {area}");
            errors.push((force.abs(), area.abs()));
        }
    }
    assert!(
        errors[2].0 < errors[0].0 && errors[2].1 < errors[0].1,
        "{errors:?}"
    );
}

/// The pull-off (E* = γ = 1 scale) of the ellipsoid Rx = 4Ry over the Johnson–Greenwood value
/// under approach control, with `k` elements on the shorter semi-axis of that approximation's
/// pull-off contact.
fn elliptic_pull_off_ratio(k: f64) -> f64 {
    let (e, gamma, rx, ry) = (1.0, 0.02, 4.0, 1.0);
    let jg = elliptic_jkr_pull_off(e, gamma, rx, ry).approach_control;
    let dx = jg.semi_axis_x.min(jg.semi_axis_y) / k;
    // One step to the approach of a Hertz ellipse 1.6 times the pull-off one, then retraction.
    let depth = elliptic_hertz_from_approach(e, rx, ry, 1.0)
        .semi_axis_y
        .powi(-2)
        * (1.6 * jg.semi_axis_y).powi(2);
    let hertz = elliptic_hertz_from_approach(e, rx, ry, depth);
    let nx = 2 * (1.3 * (2.0 * rx * depth).sqrt() / dx).ceil() as usize + 1;
    let ny = 2 * (1.3 * (2.0 * ry * depth).sqrt() / dx).ceil() as usize + 1;
    assert!(hertz.semi_axis_x > 1.5 * jg.semi_axis_x);
    let grid = Grid::new(nx, ny, dx, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Ellipsoid::new(rx, ry).unwrap());
    let op = operator_for(grid, e).unwrap();
    let mut s =
        AdhesiveSolver::new(op, &surface, gamma, KAPPA, AdhesiveOptions::default()).unwrap();
    let path = ApproachPath {
        start: depth,
        max_approach: depth,
        load_step: depth,
        unload_step: 0.1 * depth / k,
        coarse_unload_step: None,
        refine_pull_off: false,
        retract_to: None,
        max_steps: 100_000,
    };
    let r = s.run_path(&path, &SnapshotRequest::None, &mut ()).unwrap();
    assert!(r.completed && r.all_converged());
    assert!(
        r.records.iter().all(|s| !s.edge_contact),
        "the grid cuts the contact"
    );
    r.pull_off_force() / jg.force
}

#[test]
fn elliptic_pull_off_beside_the_johnson_greenwood_approximation() {
    // Rx/Ry = 4. Measured F/F_JG at b_JG/Δx = 8, 16, 32: 1.1531, 1.1068, 1.0722; Richardson
    // 1.0604 (8, 16) and 1.0376 (16, 32; 25 s, so CI runs 8 and 16). The zero-range criterion
    // is first order and too adhesive, as on the sphere; the extrapolation lands 6% and 3.8% above
    // F_JG. That is the approximation's own error: it keeps the contact elliptic and imposes
    // Griffith only at the axes' ends, good near the circle and worse with the ellipticity.
    // Tolerance: the meshes ordered and the Richardson value in [1.02, 1.09]: above F_JG by
    // more than the sphere's Richardson error (< 1%), below the coarse pair's +6% plus 3%.
    let (coarse, fine) = (elliptic_pull_off_ratio(8.0), elliptic_pull_off_ratio(16.0));
    let richardson = 2.0 * fine - coarse;
    println!("ellipsoid Rx/Ry = 4: F/F_JG = {coarse:.4}, {fine:.4}; Richardson {richardson:.4}");
    assert!(coarse > fine, "{coarse} {fine}");
    assert!((1.02..1.09).contains(&richardson), "{richardson}");
}
