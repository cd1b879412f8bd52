//! The Dugdale cohesive-zone law against Maugis (1992): a smooth sphere's force–approach curve
//! on both branches and its pull-off, from the DMT side (λ = 0.3) to the JKR side (λ = 3); the
//! pull-off's observed order of convergence against elements per cohesive zone; the periodic
//! 1D waviness against the Maugis–Dugdale closed form of `tack_analytics::wavy_dugdale` and,
//! as its range parameter grows, Johnson's (1995) JKR-limit law.
//!
//! Units: R = E* = γ = 1 (forces in πγR below). The cohesive zone ahead of a straight crack is
//! `l = πE*γ/(4σ0²)` long; the meshes resolve it by the number of elements given per test.

mod sphere_run;

use std::f64::consts::PI;
use tack_analytics::{MaugisBranch, maugis_force_at, maugis_lambda, maugis_pull_off_hat};
use tack_geometry::{Boundary, Grid, Sphere, Surface};
use tack_kernels::operator_for;
use tack_solver::{
    AdhesionLaw, AdhesiveOptions, AdhesiveSolver, ApproachPath, Dugdale, PathResult, Phase,
    SnapshotRequest,
};

/// σ0 of Maugis parameter `lambda` for R = E* = γ = 1.
fn sigma0_of(lambda: f64) -> f64 {
    lambda / maugis_lambda(1.0, 1.0, 1.0, 1.0)
}

/// A load–retract cycle of the smooth sphere at `lambda` on a free grid of element `dx` whose
/// half-width `half` holds the zone; steps `step` from out of range to `d = 1` and back until
/// the zone lets go.
fn cycle(lambda: f64, dx: f64, half: f64, step: f64) -> PathResult {
    let sigma0 = sigma0_of(lambda);
    let n = 2 * (half / dx).round() as usize + 1;
    let law = AdhesionLaw::Dugdale(Dugdale { sigma0 });
    let r = sphere_run::run_to(&law, n, dx, (-1.0 / sigma0 - step, 1.0, step), None);
    assert!(r.completed && r.all_converged(), "λ = {lambda}, Δx = {dx}");
    assert!(
        r.records.iter().all(|s| !s.edge_contact),
        "zone cut by the grid"
    );
    r
}

/// The mean and greatest deviation `|F − F_MD|/(πγR)` over the steps whose branch the closed form has
/// a stable state for, leaving out the two steps after each change of branch (a jump lands
/// between the steps), and how many steps were compared.
fn curve_deviation(lambda: f64, r: &PathResult) -> (f64, f64, usize) {
    let sigma0 = sigma0_of(lambda);
    let (mut worst, mut sum, mut compared) = (0.0f64, 0.0, 0);
    let branch = |s: &tack_solver::StepRecord| match (s.n_bonded > 0, s.n_cohesive > 0) {
        (true, _) => Some(MaugisBranch::Contact),
        (false, true) => Some(MaugisBranch::Separated),
        _ => None,
    };
    for k in 2..r.records.len() {
        let s = &r.records[k];
        let b = branch(s);
        if b.is_none()
            || b != branch(&r.records[k - 1])
            || b != branch(&r.records[k - 2])
            || r.phases[k] != r.phases[k - 2]
        {
            continue;
        }
        if let Some(f) = maugis_force_at(1.0, 1.0, 1.0, sigma0, s.approach, b.unwrap()) {
            let deviation = (s.force - f).abs() / PI;
            worst = worst.max(deviation);
            sum += deviation;
            compared += 1;
        }
    }
    (sum / compared.max(1) as f64, worst, compared)
}

#[test]
fn smooth_sphere_follows_maugis_on_both_branches() {
    // λ = 1: h0 = 1.13, the zone l = 1.0 long; Δx = 0.1 (10 elements per zone, a_c/Δx = 15).
    let lambda = 1.0;
    let r = cycle(lambda, 0.1, 3.4, 0.04);
    let (mean, worst, compared) = curve_deviation(lambda, &r);
    // Measured |F − F_MD|/(πγR) over 118 steps: mean 0.078, greatest 0.197 (near the jump-out,
    // where the closed form's F(d) turns vertical); at Δx = 0.05: 0.040 and 0.128. The mean
    // is first order in Δx; the discrete approach branch lies above the closed form and the
    // retraction below it (lattice trapping of the zone's elements, which shrinks with Δx).
    // Tolerances: the measured values +30%.
    assert!(compared > 100, "{compared} steps compared");
    assert!(mean < 0.1, "mean |F − F_MD|/(πγR) = {mean}");
    assert!(worst < 0.26, "greatest |F − F_MD|/(πγR) = {worst}");
    // The approach branch is adhesive (the zero-range model's follows Hertz): the jump-in lands
    // at d = −h0 on a tensile force.
    let c = r.cycle();
    let (d_in, f_in) = c.jump_in.unwrap();
    let h0 = 1.0 / sigma0_of(lambda);
    assert!(
        (d_in + h0).abs() <= 0.04 + 1e-12,
        "jump-in at {d_in}, −h0 = {}",
        -h0
    );
    assert!(f_in < -0.5 * PI, "jump-in force {f_in}");
    // The loop dissipates energy (retraction more adhesive than the approach).
    assert!(c.dissipated_energy.unwrap() > 0.0);
    let loading_min = r
        .records
        .iter()
        .zip(&r.phases)
        .filter(|(_, p)| **p == Phase::Load)
        .map(|(s, _)| s.force)
        .fold(f64::INFINITY, f64::min);
    assert!(loading_min > r.pull_off_force());
}

#[test]
fn pull_off_converges_to_maugis_from_dmt_to_jkr_side() {
    // Per λ: the pull-off on two meshes, Δx halved (and the step with it); F_MD from Maugis
    // (1992) under approach control. Measured F/F_MD − 1 (l/Δx elements per cohesive zone):
    //   λ = 0.1 (F_MD = −1.951 πγR): l/Δx = 499, 998 → +0.68%, +0.13% (the zone disc's edge)
    //   λ = 0.3 (F_MD = −1.816 πγR): l/Δx = 56, 113  →  +1.22%, +0.83% (order 0.55)
    //   λ = 1   (−1.601 πγR):        l/Δx = 10, 20   →  +7.49%, +3.52% (order 1.09)
    //   λ = 3   (−1.517 πγR):        l/Δx = 2.8, 5.6 → +18.4%, +9.00% (order 1.03)
    // First order, like the zero-range criterion, and too adhesive from the same cause (the
    // front's elements let go late). Tolerances: the coarse error +35%, the fine one below it,
    // the order within [0.7, 1.5] where the error is well above the path's own (λ ≥ 1).
    for (lambda, dx, half, step, coarse_err) in [
        (0.1, 0.2, 6.5, 0.1, 0.009),
        (0.3, 0.2, 8.0, 0.1, 0.0165),
        (1.0, 0.1, 3.4, 0.02, 0.10),
        (3.0, 0.04, 2.4, 0.01, 0.25),
    ] {
        let f_md = PI * maugis_pull_off_hat(lambda);
        let e_coarse = cycle(lambda, dx, half, step).pull_off_force() / f_md - 1.0;
        let e_fine = cycle(lambda, dx / 2.0, half, step / 2.0).pull_off_force() / f_md - 1.0;
        if lambda == 3.0 {
            // The JKR limit judged by the finite range: the Dugdale pull-off extrapolated
            // (Richardson, first order) beside the zero-range criterion on the finer mesh
            // (a_c/Δx = 76). Measured: 1.0068 F_JKR against 1.0117 (Maugis at λ = 3 is 1.0112;
            // the criterion's own error at this mesh is about +1.2%, README). Tolerance 2%.
            let f_jkr = -1.5 * PI;
            let dugdale = (1.0 + 2.0 * e_fine - e_coarse) * f_md / f_jkr;
            let criterion = criterion_pull_off(dx / 2.0, half, step / 2.0) / f_jkr;
            println!("λ = 3: Dugdale (Richardson) {dugdale:.4}, criterion {criterion:.4} F_JKR");
            assert!(
                (dugdale - criterion).abs() < 0.02,
                "{dugdale} vs {criterion}"
            );
        }
        let order = (e_coarse / e_fine).abs().log2();
        println!("λ = {lambda}: F/F_MD − 1 = {e_coarse:+.4}, {e_fine:+.4}, order {order:.2}");
        assert!(
            e_coarse > 0.0 && e_coarse < coarse_err,
            "λ = {lambda}: {e_coarse}"
        );
        assert!(
            e_fine > 0.0 && e_fine < e_coarse,
            "λ = {lambda}: {e_fine} vs {e_coarse}"
        );
        if lambda >= 1.0 {
            assert!((0.7..1.5).contains(&order), "λ = {lambda}: order {order}");
        }
    }
}

/// The zero-range criterion's pull-off of the smooth sphere (R = E* = γ = 1) on the same free
/// grid as [`cycle`]: one step to d = 2.5 (a bonded disc of √5 = 1.47 a_c: a contact pinned
/// below a_c would pull off early, docs/theory.md §3.5), then retraction by `step` until
/// detached.
fn criterion_pull_off(dx: f64, half: f64, step: f64) -> f64 {
    let n = 2 * (half / dx).round() as usize + 1;
    let grid = Grid::square(n, dx, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    let op = operator_for(grid, 1.0).unwrap();
    let mut solver = AdhesiveSolver::new(
        op,
        &surface,
        1.0,
        tack_solver::KAPPA,
        AdhesiveOptions::default(),
    )
    .unwrap();
    let path = ApproachPath {
        start: 2.5,
        max_approach: 2.5,
        load_step: 2.5,
        unload_step: step,
        coarse_unload_step: None,
        refine_pull_off: false,
        retract_to: None,
        max_steps: 100_000,
    };
    let r = solver
        .run_path(&path, &SnapshotRequest::None, &mut ())
        .unwrap();
    assert!(r.completed && r.all_converged());
    r.pull_off_force()
}

#[test]
fn same_bits_on_one_and_two_threads() {
    // 141² elements: the CG's vectors exceed 128² and split into chunks run in parallel.
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| cycle(1.0, 0.05, 3.5, 0.1))
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one.records.len(), two.records.len());
    for (a, b) in one.records.iter().zip(&two.records) {
        assert_eq!(a.force.to_bits(), b.force.to_bits());
        assert_eq!((a.n_bonded, a.n_cohesive), (b.n_bonded, b.n_cohesive));
    }
}

/// Mean |p̄ − p̄_cf|/p* of a load–retract cycle of the 1D waviness h[1 − cos(2πx/λ)] (λ = 1,
/// h = 0.01, E* = 1) on `nx` periodic elements, under the Dugdale law at Johnson's `alpha` and
/// range parameter `lambda_w`, against the closed form `cf(ψ)` at the measured ψ = πa/λ (a half
/// the contact's width); the steps with contact but not full contact and `keep(ψ)` are compared.
/// Also the mean deviation from Johnson's (1995) JKR-limit law, and the number compared.
fn wavy_cycle(alpha: f64, lambda_w: f64, nx: usize) -> (f64, f64, usize) {
    use tack_analytics::{
        johnson_1d_mean_pressure_ratio, wavy_dugdale_point, wavy_dugdale_stress_ratio,
    };
    let (h, e_star) = (0.01, 1.0);
    let p_star = PI * e_star * h;
    let gamma = alpha * alpha * PI * PI * h * h * e_star / 2.0;
    let sigma0 = wavy_dugdale_stress_ratio(alpha, lambda_w) * p_star;
    let grid = Grid::new(nx, 1, 1.0 / nx as f64, Boundary::Periodic).unwrap();
    let heights =
        ndarray::Array2::from_shape_fn((nx, 1), |(i, _)| h * (1.0 - (2.0 * PI * grid.x(i)).cos()));
    let surface = Surface::new(grid, heights).unwrap();
    let op = operator_for(grid, e_star).unwrap();
    let law = AdhesionLaw::Dugdale(Dugdale { sigma0 });
    let mut solver =
        AdhesiveSolver::with_law(op, &surface, gamma, law, AdhesiveOptions::default()).unwrap();
    let step = h / 200.0;
    let path = ApproachPath {
        start: -gamma / sigma0 - step,
        max_approach: 0.9 * h,
        load_step: step,
        unload_step: step,
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
        "α = {alpha}, λ_w = {lambda_w}"
    );
    let (mut dev, mut dev_johnson, mut k) = (0.0, 0.0, 0);
    for s in &r.records {
        if s.n_bonded == 0 || s.full_contact {
            continue;
        }
        let psi = PI * s.n_bonded as f64 / (2.0 * nx as f64);
        let cf = wavy_dugdale_point(alpha, lambda_w, psi);
        if cf.saturated || !(0.2..1.3).contains(&psi) {
            continue;
        }
        dev += (s.mean_pressure / p_star - cf.mean_pressure_ratio).abs();
        dev_johnson +=
            (s.mean_pressure / p_star - johnson_1d_mean_pressure_ratio(alpha, psi)).abs();
        k += 1;
    }
    (dev / k.max(1) as f64, dev_johnson / k.max(1) as f64, k)
}

#[test]
fn wavy_surface_follows_the_dugdale_closed_form_and_tends_to_johnson() {
    // α = 0.3; the zone of a line crack, l = πE*γ/(4σ0²) = 0.18λ/λ_w², holds 92 … 0.9
    // elements below. Measured mean |p̄ − p̄_cf|/p* (and from Johnson's JKR-limit law):
    //   λ_w = 1:  nx = 512, 1024, 2048 → 0.00153, 0.00082, 0.00045 (Johnson 0.063)
    //   λ_w = 3:                        → 0.0129, 0.0075, 0.0042   (Johnson 0.017)
    //   λ_w = 10:                       → 0.090, 0.058, 0.036      (the closed form is
    //   Johnson's to 1e-5 there; the zone is 0.9 … 3.7 elements, so the mesh error dominates)
    // First order or nearly (0.9, 0.8, 0.65), the contact width's own ±Δx/2 included. Tolerances:
    // the measured value +30%, each refinement better, and the closed form nearer Johnson's law
    // as λ_w grows.
    let (d1, j1, k1) = wavy_cycle(0.3, 1.0, 512);
    let (d1f, _, _) = wavy_cycle(0.3, 1.0, 1024);
    let (d3, j3, _) = wavy_cycle(0.3, 3.0, 1024);
    let (d10, j10, _) = wavy_cycle(0.3, 10.0, 1024);
    let (d10f, j10f, _) = wavy_cycle(0.3, 10.0, 2048);
    println!(
        "λ_w = 1: {d1:.5} {d1f:.5} (Johnson {j1:.4}); 3: {d3:.5} ({j3:.4}); 10: {d10:.4} {d10f:.4} ({j10:.4} {j10f:.4})"
    );
    assert!(k1 > 300, "{k1} steps compared");
    assert!(d1 < 0.002 && d1f < 0.6 * d1, "λ_w = 1: {d1}, {d1f}");
    let order = (d1 / d1f).log2();
    assert!((0.6..1.3).contains(&order), "order {order}");
    assert!(d3 < 0.01, "λ_w = 3: {d3}");
    assert!(d10 < 0.075 && d10f < 0.75 * d10, "λ_w = 10: {d10}, {d10f}");
    // Towards Johnson as λ_w grows: the deviation from the JKR-limit law falls from 0.063
    // (λ_w = 1, a property of the closed form: 40× the mesh error there) to the mesh's own.
    assert!(j1 > 0.05 && j3 < 0.4 * j1 && j10f < j1, "{j1} {j3} {j10f}");
    assert!(
        (j10f - d10f).abs() < 1e-3,
        "at λ_w = 10 the closed form is Johnson's"
    );
}

#[test]
fn hysteresis_loop_converges_to_maugis() {
    // The loop ∮F dd of a cycle to d = 1 at λ = 1 against Maugis' (the contact branch between
    // its jump-out and the jump-in at −h0: 2.761 γR·d_s here, R = E* = γ = 1, d_s = 1).
    // Measured: 4.280, 3.527 at l/Δx = 10, 20 (3.148 at 40): +55%, +28% (+14%), first order
    // (0.98); Richardson 2·W(Δx/2) − W(Δx) = 2.774, 0.5% from the closed form. The excess is lattice trapping:
    // the discrete approach lies above the closed form and the retraction below, over the
    // whole loaded range. The jump-out lands within a step of Maugis' approach (−1.757).
    // Tolerances: the order within [0.8, 1.2], Richardson within 2%, the jump-out within 2
    // steps.
    use tack_analytics::{maugis_dissipated_energy, maugis_jump_out_hat, maugis_scales};
    let w_md = maugis_dissipated_energy(1.0, 1.0, 1.0, sigma0_of(1.0)).unwrap();
    let d_out_md = maugis_jump_out_hat(1.0).unwrap().0 * maugis_scales(1.0, 1.0, 1.0).approach;
    let mut w = Vec::new();
    for (dx, step) in [(0.1, 0.04), (0.05, 0.02)] {
        let c = cycle(1.0, dx, 3.4, step).cycle();
        let (d_out, _) = c.jump_out.unwrap();
        assert!(
            (d_out - d_out_md).abs() < 2.0 * step,
            "jump-out at {d_out} vs {d_out_md}"
        );
        w.push(c.dissipated_energy.unwrap());
    }
    let order = ((w[0] - w_md) / (w[1] - w_md)).log2();
    let richardson = 2.0 * w[1] - w[0];
    println!("W = {w:?}, W_MD = {w_md}, order {order:.2}, Richardson {richardson}");
    assert!(w[0] > w[1] && w[1] > w_md, "{w:?} vs {w_md}");
    assert!((0.8..1.2).contains(&order), "order {order}");
    assert!(
        (richardson / w_md - 1.0).abs() < 0.02,
        "{richardson} vs {w_md}"
    );
}
