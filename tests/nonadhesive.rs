//! Non-adhesive contact against closed forms: Hertz (free boundaries) and Westergaard (periodic).

use std::f64::consts::PI;
use tack_analytics::{
    hertz_contact_radius, hertz_force, hertz_max_pressure, hertz_pressure, westergaard_p_star,
};
use tack_geometry::{Boundary, Grid, Sphere, Surface};
use tack_kernels::operator_for;
use tack_solver::{ContactMethod, ContactSolver, SolverOptions};

fn solver(grid: Grid, surface: &Surface, e_star: f64) -> ContactSolver {
    ContactSolver::new(
        operator_for(grid, e_star).unwrap(),
        surface,
        SolverOptions::default(),
    )
    .unwrap()
}

/// Hertz sphere at a/Δx = `ratio`: returns (force error, radius error in Δx, max pressure error / p0).
fn hertz_errors(ratio: f64) -> (f64, f64, f64) {
    let (r, e, d) = (1.0, 1.0, 0.01);
    let a = hertz_contact_radius(r, d);
    let dx = a / ratio;
    // Contact stays inside 1.25 a: the free operator needs nothing beyond it.
    let n = 2 * (1.25 * ratio).ceil() as usize + 1;
    let grid = Grid::square(n, dx, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Sphere::new(r).unwrap());
    let s = solver(grid, &surface, e).solve(d).unwrap();
    assert!(
        s.converged,
        "a/dx = {ratio}: not converged after {} iterations",
        s.iterations
    );
    let f_err = (s.force - hertz_force(e, r, d)) / hertz_force(e, r, d);
    let a_num = (s.area / PI).sqrt();
    let p0 = hertz_max_pressure(e, r, d);
    let mut p_err: f64 = 0.0;
    for ((i, j), &p) in s.pressure.indexed_iter() {
        let rr = grid.x(i).hypot(grid.y(j));
        p_err = p_err.max((p - hertz_pressure(e, r, d, rr)).abs() / p0);
    }
    ((f_err), (a_num - a) / dx, p_err)
}

#[test]
fn hertz_sphere_converges_with_refinement() {
    let mut last = f64::INFINITY;
    for ratio in [10.0, 20.0, 40.0] {
        let (f_err, a_err, p_err) = hertz_errors(ratio);
        eprintln!(
            "Hertz a/dx = {ratio}: force error {f_err:+.4e}, radius error {a_err:+.3} dx, max |Δp|/p0 {p_err:.4}"
        );
        assert!(f_err.abs() < last, "force error must fall with refinement");
        last = f_err.abs();
        // The contact edge is resolved to one element; the area-equivalent radius must agree.
        assert!(a_err.abs() < 1.0, "radius error {a_err} dx");
        // The worst pressure error sits at the contact edge where p ~ sqrt(a − r); one element of
        // edge misplacement costs ~ sqrt(2Δx/a)·p0.
        assert!(p_err < 1.5 * (2.0 / ratio).sqrt(), "pressure error {p_err}");
    }
    assert!(last < 0.01, "force error at a/dx = 40 is {last}");
}

/// Periodic 1D waviness f = h[1 − cos 2πx/λ] on an nx × 1 strip (plane strain).
fn wavy_1d(nx: usize, h: f64, lambda: f64) -> (Grid, Surface) {
    let grid = Grid::new(nx, 1, lambda / nx as f64, Boundary::Periodic).unwrap();
    let heights = ndarray::Array2::from_shape_fn((nx, 1), |(i, _)| {
        h * (1.0 - (2.0 * PI * grid.x(i) / lambda).cos())
    });
    (grid, Surface::new(grid, heights).unwrap())
}

/// Max |p̄ − p* sin²ψ|/p* over ψ ∈ [0.2, 1.4] along an approach sweep; also returns the ψ range.
fn westergaard_error(nx: usize) -> (f64, (f64, f64)) {
    let (e, h, lambda) = (1.0, 0.01, 1.0);
    let (grid, surface) = wavy_1d(nx, h, lambda);
    let p_star = westergaard_p_star(e, h, lambda);
    let mut s = solver(grid, &surface, e);
    let mut worst: f64 = 0.0;
    let mut psi_range = (f64::INFINITY, 0.0f64);
    // The mean gap closes at d = h and ψ → π/2 only as d → h: crowd the steps near h.
    for k in 1..60 {
        let d = h * (1.0 - ((60 - k) as f64 / 60.0).powi(4));
        let st = s.solve(d).unwrap();
        assert!(st.converged);
        let a = st.n_contact as f64 * grid.dx() / 2.0;
        let psi = PI * a / lambda;
        if !(0.2..=1.4).contains(&psi) {
            continue;
        }
        psi_range = (psi_range.0.min(psi), psi_range.1.max(psi));
        worst = worst.max((st.mean_pressure - p_star * psi.sin().powi(2)).abs() / p_star);
    }
    (worst, psi_range)
}

#[test]
fn westergaard_mean_pressure_follows_sin_squared() {
    for nx in [128, 256, 512] {
        let (worst, psi_range) = westergaard_error(nx);
        eprintln!(
            "Westergaard λ/Δx = {nx}: max |p̄ − p* sin²ψ|/p* = {worst:.3e} over ψ ∈ {psi_range:.3?}"
        );
        assert!(
            psi_range.0 < 0.3 && psi_range.1 > 1.3,
            "sweep must cover the range: {psi_range:?}"
        );
        // The half-width is known to ±Δx/2, i.e. ψ to ±π/(2n), which alone moves p̄ by up to
        // ≈ π/(2n)·p*: 1.2% at n = 128, 0.3% at n = 512.
        assert!(
            worst < 2.0 / nx as f64 + 0.002,
            "λ/Δx = {nx}: worst deviation {worst}"
        );
    }
}

#[test]
fn periodic_full_contact_reaches_westergaard_pressure() {
    let (e, h, lambda) = (2.0, 0.01, 1.0);
    let (grid, surface) = wavy_1d(256, h, lambda);
    let st = solver(grid, &surface, e).solve(1.5 * h).unwrap();
    assert!(st.full_contact && st.converged);
    assert_eq!(st.n_contact, 256);
    // The least mean pressure that keeps full contact is p* = πE*h/λ.
    let p_star = westergaard_p_star(e, h, lambda);
    assert!(
        (st.mean_pressure - p_star).abs() < 1e-3 * p_star,
        "{} vs {p_star}",
        st.mean_pressure
    );
}

#[test]
fn no_contact_is_exact_and_converged() {
    let grid = Grid::square(16, 0.1, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    let mut s = solver(grid, &surface, 1.0);
    for d in [0.0, -0.5] {
        let st = s.solve(d).unwrap();
        assert!(st.converged);
        assert_eq!((st.force, st.n_contact, st.iterations), (0.0, 0, 0));
    }
    assert!(s.solve(f64::NAN).is_err());
}

#[test]
fn iteration_cap_is_reported_not_hidden() {
    let grid = Grid::square(41, 0.05, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    // One iteration per CG: the active set's rounds continue a quiet round's CG, so with two a
    // chain of rounds reaches 1e-12 here (each within its cap) and the step converges.
    let opts = SolverOptions {
        tolerance: 1e-12,
        max_iterations: 1,
    };
    for method in [ContactMethod::PolonskyKeer, ContactMethod::ActiveSet] {
        let op = operator_for(grid, 1.0).unwrap();
        let mut s = ContactSolver::with_method(op, &surface, opts, method).unwrap();
        let st = s.solve(0.2).unwrap();
        assert!(!st.converged, "{method:?}");
        assert!(st.residual > 1e-12);
        // Polonsky–Keer is one CG; the active set caps each of its rounds' CGs.
        if method == ContactMethod::PolonskyKeer {
            assert_eq!(st.iterations, 1);
        }
    }
}

#[test]
fn periodic_2d_grid_constant_in_y_matches_strip() {
    let (e, h, lambda) = (1.0, 0.01, 1.0);
    let (g1, s1) = wavy_1d(64, h, lambda);
    let g2 = Grid::new(64, 4, lambda / 64.0, Boundary::Periodic).unwrap();
    let heights = ndarray::Array2::from_shape_fn((64, 4), |(i, _)| s1.heights()[[i, 0]]);
    let s2 = Surface::new(g2, heights).unwrap();
    let a = solver(g1, &s1, e).solve(0.5 * h).unwrap();
    let b = solver(g2, &s2, e).solve(0.5 * h).unwrap();
    assert!((a.mean_pressure - b.mean_pressure).abs() < 1e-9 * a.mean_pressure);
    assert_eq!(a.n_contact * 4, b.n_contact);
}

#[test]
fn hertz_check_uses_independent_radius() {
    // Guard the test's own reference: the Hertz radius is sqrt(R d).
    assert!((hertz_contact_radius(2.0, 0.02) - 0.2).abs() < 1e-15);
}

/// Runs one solve with the method, the crop and the coarse-to-fine start set as given.
fn solve_with(
    surface: &Surface,
    d: f64,
    crop: bool,
    coarse: bool,
    method: ContactMethod,
) -> tack_solver::ContactState {
    let op = operator_for(*surface.grid(), 1.0).unwrap();
    let mut s = ContactSolver::with_method(op, surface, SolverOptions::default(), method).unwrap();
    s.set_crop(crop);
    s.set_coarse_start(coarse);
    let st = s.solve(d).unwrap();
    assert!(st.converged);
    st
}

#[test]
fn crop_and_coarse_start_change_nothing_but_the_cost() {
    // Free Hertz sphere on a grid four times wider than the contact: the crop to {f < d} and the
    // coarse-to-fine start solve the same problem; only round-off (tolerance 1e-10) differs.
    let grid = Grid::square(128, 1.0 / 128.0, Boundary::Free).unwrap();
    let sphere = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    // Periodic self-affine roughness, H = 0.8, about 7% contact.
    let pgrid = Grid::square(128, 1.0 / 128.0, Boundary::Periodic).unwrap();
    let rough = tack_geometry::rough_surface(
        pgrid,
        &tack_geometry::RoughSpec::paper_defaults(pgrid, 1e-3, 0.8, 3),
    )
    .unwrap();
    let rough = Surface::new(pgrid, rough.heights().clone()).unwrap();
    let d_rough = rough.min() + 0.6 * (rough.heights().mean().unwrap() - rough.min());
    // Both methods, and the two methods against each other: one convex problem, one answer.
    for (surface, d) in [(&sphere, 0.02), (&rough, d_rough)] {
        let reference = solve_with(surface, d, false, false, ContactMethod::PolonskyKeer);
        for method in [ContactMethod::PolonskyKeer, ContactMethod::ActiveSet] {
            for (crop, coarse) in [(false, false), (true, false), (false, true), (true, true)] {
                let other = solve_with(surface, d, crop, coarse, method);
                let plain = &reference;
                let rel = (other.force - plain.force).abs() / plain.force;
                assert!(rel < 1e-8, "{method:?} crop {crop} coarse {coarse}: {rel}");
                assert_eq!(other.n_contact, plain.n_contact);
                let gap = other
                    .gap
                    .iter()
                    .zip(&plain.gap)
                    .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
                assert!(gap < 1e-8 * d.abs().max(1e-3), "gap differs by {gap}");
            }
        }
    }
}

#[test]
fn adhesive_path_with_gamma_zero_is_the_non_adhesive_curve() {
    // A γ = 0 scene runs the adhesive path engine with σ_c = 0: its load–unload curve must be
    // the non-adhesive equilibrium at every approach, here solved independently by
    // Polonsky–Keer. Sphere + H = 0.8 roughness on a free 96² grid.
    use tack_solver::{AdhesiveOptions, AdhesiveSolver, ApproachPath, KAPPA, SnapshotRequest};
    let grid = Grid::square(96, 1.0 / 96.0, Boundary::Free).unwrap();
    let mut surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    let rough = tack_geometry::rough_surface(
        grid,
        &tack_geometry::RoughSpec::paper_defaults(grid, 2e-4, 0.8, 5),
    )
    .unwrap();
    surface.add(&rough).unwrap();
    let path =
        ApproachPath::load_retract(surface.min() + 5e-4, surface.min() + 0.01, 5e-4, 1e-3).unwrap();
    let op = operator_for(grid, 1.0).unwrap();
    let mut adhesive =
        AdhesiveSolver::new(op, &surface, 0.0, KAPPA, AdhesiveOptions::default()).unwrap();
    let r = adhesive
        .run_path(&path, &SnapshotRequest::None, &mut ())
        .unwrap();
    assert!(r.completed && r.all_converged());
    let op = operator_for(grid, 1.0).unwrap();
    let mut pk = ContactSolver::with_method(
        op,
        &surface,
        SolverOptions::default(),
        ContactMethod::PolonskyKeer,
    )
    .unwrap();
    let f_max = r.records.iter().fold(0.0f64, |m, x| m.max(x.force));
    assert!(r.records.len() > 25 && f_max > 0.0);
    for rec in &r.records {
        let st = pk.solve(rec.approach).unwrap();
        assert!(st.converged);
        assert_eq!(rec.n_bonded, st.n_contact, "d = {}", rec.approach);
        assert!(
            (rec.force - st.force).abs() <= 1e-8 * f_max,
            "d = {}: {} vs {}",
            rec.approach,
            rec.force,
            st.force
        );
    }
}

#[test]
fn cropped_solves_along_a_load_sequence_match_the_plain_ones() {
    // The cropped sub-problem is reused while the window is unchanged and rebuilt when it
    // changes; warm starts carry over either way.
    let grid = Grid::square(96, 1.0 / 96.0, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    let mut cropped = solver(grid, &surface, 1.0);
    let mut plain = solver(grid, &surface, 1.0);
    plain.set_crop(false);
    // d = 0 touches the apex element with a zero load (d − f = 0 there): whether that element
    // counts as in contact, with a pressure of round-off, is a tie, so only the load is
    // compared; d = −0.001 separates the bodies.
    for d in [0.01, 0.01, 0.02, 0.015, 0.015, 0.0, -0.001, 0.02] {
        let (a, b) = (cropped.solve(d).unwrap(), plain.solve(d).unwrap());
        assert!(a.converged && b.converged);
        if d == 0.0 {
            assert!(
                a.force.abs() <= 1e-20 && b.force.abs() <= 1e-20,
                "{a:?} {b:?}"
            );
            continue;
        }
        assert_eq!(a.n_contact, b.n_contact, "d = {d}");
        let scale = b.force.abs().max(1e-12);
        assert!(
            (a.force - b.force).abs() < 1e-8 * scale,
            "d = {d}: {} vs {}",
            a.force,
            b.force
        );
    }
}
