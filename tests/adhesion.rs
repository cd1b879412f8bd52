//! Adhesive contact against closed forms: JKR sphere, Kendall punch, Johnson's 1D waviness,
//! and the hard cases (single element, huge/tiny Johnson parameter, jumps, large grids).

use ndarray::Array2;
use std::f64::consts::PI;
use tack_analytics::{johnson_1d_mean_pressure_ratio, kendall_pull_off, westergaard_p_star};
use tack_geometry::{Boundary, FlatPunch, Grid, Sphere, Surface, Waviness1d, Waviness2d};
use tack_kernels::operator_for;
use tack_solver::{
    AdhesiveOptions, AdhesiveSolver, ApproachPath, KAPPA, KAPPA_LINE, PathResult, Phase,
    SnapshotRequest, StepRecord,
};
use tack_tests::JkrSphere;

fn solver(surface: &Surface, e: f64, gamma: f64) -> AdhesiveSolver {
    solver_with(surface, e, gamma, KAPPA)
}

fn solver_with(surface: &Surface, e: f64, gamma: f64, kappa: f64) -> AdhesiveSolver {
    let op = operator_for(*surface.grid(), e).unwrap();
    AdhesiveSolver::new(op, surface, gamma, kappa, AdhesiveOptions::default()).unwrap()
}

fn path(start: f64, max: f64, load: f64, unload: f64) -> ApproachPath {
    ApproachPath {
        start,
        max_approach: max,
        load_step: load,
        unload_step: unload,
        coarse_unload_step: None,
        refine_pull_off: false,
        retract_to: None,
        max_steps: 1_000_000,
    }
}

fn run(s: &mut AdhesiveSolver, p: &ApproachPath) -> PathResult {
    let r = s.run_path(p, &SnapshotRequest::None, &mut ()).unwrap();
    assert!(r.completed, "path hit its step cap");
    r
}

/// The state the solver holds is an admissible Pohrt–Popov equilibrium.
fn assert_admissible(s: &AdhesiveSolver, rec: &StepRecord, gap_tol: f64) {
    let (p, b, g) = (s.pressure(), s.bonded(), s.gap());
    let sigma_c = s.critical_stress();
    let force: f64 = p.sum() * s.grid().element_area();
    assert!(
        (force - rec.force).abs() <= 1e-12 * force.abs().max(1e-300),
        "force bookkeeping"
    );
    assert_eq!(rec.n_bonded, b.iter().filter(|&&x| x).count());
    for ((&p, &b), &g) in p.iter().zip(b).zip(g) {
        if b {
            assert!(
                p >= -sigma_c,
                "bonded element beyond the critical tension: {p} < -{sigma_c}"
            );
            assert!(g.abs() <= gap_tol, "bonded element with gap {g}");
        } else {
            assert_eq!(p, 0.0, "free element carries pressure");
            assert!(g >= 0.0, "free element penetrates: {g}");
        }
    }
}

#[test]
fn jkr_sphere_pull_off_converges_with_refinement() {
    // a_c/Δx = 40 takes ~15 s in release; debug builds stop at 20.
    let ratios: &[f64] = if cfg!(debug_assertions) {
        &[5.0, 10.0, 20.0]
    } else {
        &[5.0, 10.0, 20.0, 40.0]
    };
    let mut prev: Option<(f64, f64, f64)> = None;
    let mut errors = Vec::new();
    for &ratio in ratios {
        let run = JkrSphere::new(ratio, KAPPA).run();
        let err = run.pull_off_error;
        errors.push(err);
        let jump = run.last_contact_approach;
        let order = prev.map_or(f64::NAN, |(e, ..)| (e / err).log2());
        eprintln!(
            "JKR κ=0.473201 a_c/Δx = {ratio}: pull-off error {err:+.4}, order {order:.2}, last contact d̂ = {jump:.3}, \
             curve error {:.4}, steps {}, CG {}",
            run.curve_error,
            run.result.records.len(),
            run.result.cg_iterations()
        );
        assert!(run.result.all_converged());
        assert!(
            run.max_extent < run.grid.nx() / 2,
            "contact reached the grid edge"
        );
        // The criterion overshoots F_JKR (saw-tooth, docs/theory.md §9) and converges about
        // first order.
        assert!(err > 0.0 && err < 0.5);
        if let Some((e, j, c)) = prev {
            assert!(err < e, "pull-off error must fall with refinement");
            assert!(
                (jump + 1.609).abs() < (j + 1.609).abs(),
                "jump-off must approach d̂ = −1.609"
            );
            assert!(run.curve_error < c, "curve error must fall with refinement");
        }
        prev = Some((err, jump, run.curve_error));
    }
    let (err, jump, _) = prev.unwrap();
    if !cfg!(debug_assertions) {
        assert!(err < 0.05, "pull-off error at a_c/Δx = 40 is {err}");
        assert!((jump + 1.609).abs() < 0.1, "jump-off at d̂ = {jump}");
    }
    // First order: Richardson over (N, N/2) cancels the leading term. Measured −0.33% at
    // (20, 10) and +0.16% at (40, 20), against +6.9% and +3.5% without; 1% is the bar.
    for k in 2..errors.len() {
        let r = tack_solver::richardson_first_order(errors[k], errors[k - 1]);
        eprintln!(
            "Richardson a_c/Δx = {} + {}: pull-off error {r:+.4}",
            ratios[k],
            ratios[k - 1]
        );
        assert!(r.abs() < 0.01, "{r}");
    }
}

#[test]
fn centre_displacement_kappa_does_not_converge() {
    // κ = 0.5611 (centre displacement) undershoots more and more with refinement: the error
    // does not fall. This is the evidence for κ = 0.473201 (docs/theory.md §3.2).
    let errs: Vec<f64> = [5.0, 10.0, 20.0]
        .iter()
        .map(|&r| {
            JkrSphere::new(r, tack_analytics::KAPPA_CENTRE)
                .run()
                .pull_off_error
        })
        .collect();
    eprintln!("JKR κ=0.5611 a_c/Δx = 5, 10, 20: pull-off errors {errs:+.4?}");
    assert!(errs[2] < errs[1] && errs[2] < -0.05, "{errs:?}");
}

#[test]
fn kendall_flat_punch_pull_off_converges() {
    let (e, gamma, a) = (1.0, 1.0, 1.0);
    let exact = kendall_pull_off(e, gamma, a);
    let mut errs = Vec::new();
    for ratio in [5.0, 10.0, 20.0, 40.0] {
        let dx = a / ratio;
        let n = 2 * ratio as usize + 3;
        let grid = Grid::square(n, dx, Boundary::Free).unwrap();
        let surface = Surface::from_shape(grid, &FlatPunch::circular(a).unwrap());
        let mut s = solver(&surface, e, gamma);
        // Fully bonded face: F = k d with k ≈ 2E*a, so the pull-off approach is ≈ −F_c/(2E*a).
        let d_c = exact / (2.0 * e * a);
        let r = run(&mut s, &path(1e-3 * d_c, 1e-3 * d_c, 1.0, d_c / 4000.0));
        let err_nominal = -r.pull_off_force() / exact - 1.0;
        // The digitised face is what was modelled: compare with its area-equivalent radius.
        let a_eq = (r.records[0].area / PI).sqrt();
        let err = -r.pull_off_force() / kendall_pull_off(e, gamma, a_eq) - 1.0;
        eprintln!(
            "Kendall a/Δx = {ratio}: pull-off error {err:+.4} (area-equivalent radius), {err_nominal:+.4} (nominal)"
        );
        assert!(r.all_converged());
        errs.push(err);
    }
    // Richardson over (20, 10) must be no worse than the criterion alone at 20 (measured
    // −0.22% against +0.23%): the extrapolation used for spheres does not hurt punches.
    let r = tack_solver::richardson_first_order(errs[2], errs[1]);
    eprintln!("Kendall Richardson a/Δx = 20 + 10: pull-off error {r:+.4}");
    assert!(r.abs() < errs[2].abs() + 1e-3, "{r} vs {}", errs[2]);
    let errs: Vec<f64> = errs.iter().map(|e| e.abs()).collect();
    // Measured: 4.6%, 0.68%, 0.23%, 0.56%. The staircase rim of the digitised disc leaves a
    // ±0.5% scatter once a/Δx ≥ 20, so "falling" is checked as: each of the fine resolutions
    // beats both coarse ones, and both are below 1%.
    assert!(errs[2].max(errs[3]) < errs[0].min(errs[1]), "{errs:?}");
    assert!(errs[2].max(errs[3]) < 0.01, "{errs:?}");
}

/// Johnson 1D on a λ/Δx = `nx` strip: (worst and mean signed p̄ deviation from Eq. 2 in units of
/// p*, ψ range compared, path). Compared are unload states just before the front advances (the
/// Griffith equilibria) with ψ ∈ [0.2, 1.4]: beyond 1.4, Eq. 2's √tanψ diverges and one element
/// of front position moves it by more than the tolerance.
fn johnson_1d(alpha: f64, nx: usize, kappa: f64) -> (f64, f64, (f64, f64), PathResult) {
    let (e, h, lambda) = (1.0, 0.01, 1.0);
    let gamma = alpha * alpha * PI * PI * h * h * e / (2.0 * lambda);
    let grid = Grid::new(nx, 1, lambda / nx as f64, Boundary::Periodic).unwrap();
    let surface = Surface::from_shape(grid, &Waviness1d::new(h, lambda).unwrap());
    let mut s = solver_with(&surface, e, gamma, kappa);
    let r = run(&mut s, &path(h / 100.0, 1.02 * h, h / 100.0, h / 1000.0));
    let p_star = westergaard_p_star(e, h, lambda);
    let (mut worst, mut sum, mut count, mut range) = (0.0f64, 0.0, 0, (f64::INFINITY, 0.0f64));
    for (k, (rec, ph)) in r.records.iter().zip(&r.phases).enumerate() {
        let psi = PI * rec.n_bonded as f64 * grid.dx() / (2.0 * lambda);
        // A Griffith state is the tip of a saw tooth: the front is critical and the next step
        // moves it.
        let critical = r
            .records
            .get(k + 1)
            .is_some_and(|next| next.n_bonded < rec.n_bonded);
        if *ph != Phase::Unload || rec.full_contact || !critical || !(0.2..=1.4).contains(&psi) {
            continue;
        }
        let dev = rec.mean_pressure / p_star - johnson_1d_mean_pressure_ratio(alpha, psi);
        worst = worst.max(dev.abs());
        (sum, count) = (sum + dev, count + 1);
        range = (range.0.min(psi), range.1.max(psi));
    }
    (worst, sum / count as f64, range, r)
}

#[test]
fn johnson_1d_waviness_follows_eq2_along_unstable_branch() {
    for alpha in [0.1, 0.3, 0.5] {
        let (worst, mean, range, r) = johnson_1d(alpha, 1024, KAPPA_LINE);
        eprintln!(
            "Johnson 1D α = {alpha}, κ = κ_line: max |Δp̄|/p* = {worst:.4}, mean {mean:+.4}, ψ ∈ {range:.3?}"
        );
        assert!(r.all_converged());
        // Full contact is reached at d = mean f; the unload then traces ψ from near π/2 down
        // past the maximum of Eq. 2 onto its unstable branch before the jump out of contact.
        assert!(r.records.iter().any(|x| x.full_contact));
        assert!(range.0 < 0.3 && range.1 > 1.3, "range {range:?}");
        // Measured worst 0.015, 0.017, 0.031 (exact rounds: 0.015, 0.023, 0.021, ψ ≤ 1.361). The
        // inexact rounds reach a Griffith state at ψ = 1.373, where √tan ψ is steep and one
        // element of front position moves Eq. 2 by about 0.01 p*; the means stay within 0.002.
        assert!(worst < 0.035, "α = {alpha}: deviation {worst}");
        assert!(mean.abs() < 0.005, "α = {alpha}: mean deviation {mean}");
    }
}

#[test]
fn sphere_kappa_overestimates_adhesion_of_straight_fronts() {
    // The evidence for KAPPA_LINE: with the sphere's κ the adhesive term of Eq. 2 is too strong
    // by √(0.865/0.4732) = 1.35, and refining does not help.
    let (_, coarse, ..) = johnson_1d(0.3, 256, KAPPA);
    let (_, fine, ..) = johnson_1d(0.3, 1024, KAPPA);
    eprintln!(
        "Johnson 1D α = 0.3, κ = 0.4732: mean Δp̄/p* = {coarse:+.4} (λ/Δx = 256), {fine:+.4} (1024)"
    );
    assert!(fine < -0.07 && coarse < -0.07, "{coarse} {fine}");
    assert!(
        (fine - coarse).abs() < 0.02,
        "refinement must not remove the bias: {coarse} {fine}"
    );
}

#[test]
fn single_element_contact_is_exact() {
    // One asperity tip: one element at height 0, all others at 1 (never touched).
    let grid = Grid::square(9, 0.1, Boundary::Free).unwrap();
    let mut h = Array2::from_elem((9, 9), 1.0);
    h[[4, 4]] = 0.0;
    let surface = Surface::new(grid, h).unwrap();
    let mut s = solver(&surface, 2.0, 0.3);
    let w0 = tack_kernels::SELF_COMPLIANCE * 0.1 / 2.0;
    let rec = s.step(1e-3).unwrap();
    assert_eq!((rec.n_bonded, rec.n_clusters), (1, 1));
    let p = 1e-3 / w0;
    assert!(
        (rec.force - p * 0.01).abs() < 1e-12 * p * 0.01,
        "{} vs {}",
        rec.force,
        p * 0.01
    );
    assert_admissible(&s, &rec, 1e-12);
    // Pulled back, it holds until its tension exceeds σ_c: d = −σ_c·w0.
    let d_c = -s.critical_stress() * w0;
    let held = s.step(0.99 * d_c).unwrap();
    assert!(held.converged && held.n_bonded == 1 && held.force < 0.0);
    let gone = s.step(1.01 * d_c).unwrap();
    assert!(gone.converged && gone.n_bonded == 0 && gone.force == 0.0);
}

#[test]
fn huge_johnson_parameter_jumps_into_full_contact() {
    // α = 5 ≫ 0.57: Eq. 2 is negative for every ψ. The contact snaps into full contact once the
    // mean gap closes, holds it under tension, and on retraction every Griffith state pulls.
    let (worst, _, _, r) = johnson_1d(5.0, 256, KAPPA_LINE);
    assert!(r.all_converged() && r.completed);
    let first_full = r
        .records
        .iter()
        .position(|x| x.full_contact)
        .expect("full contact");
    assert_eq!(r.phases[first_full], Phase::Load);
    assert!(
        r.records[first_full].mean_pressure < 0.0,
        "full contact holds under tension"
    );
    assert!(worst.is_finite());
    let (e, h, lambda, alpha) = (1.0, 0.01, 1.0, 5.0f64);
    let p_star = westergaard_p_star(e, h, lambda);
    for (k, rec) in r.records.iter().enumerate().skip(first_full) {
        let critical = r
            .records
            .get(k + 1)
            .is_some_and(|n| n.n_bonded < rec.n_bonded);
        if critical && !rec.full_contact && rec.n_bonded > 0 {
            let psi = PI * rec.n_bonded as f64 / 256.0 / 2.0;
            assert!(
                rec.mean_pressure < 0.0,
                "Griffith state at ψ = {psi}: p̄ = {}",
                rec.mean_pressure
            );
            assert!(johnson_1d_mean_pressure_ratio(alpha, psi) * p_star < 0.0);
        }
    }
    let _ = lambda;
}

#[test]
fn tiny_johnson_parameter_gives_a_point_cloud() {
    // Sphere + 2D waviness (Eq. 6) with α ≈ 0.05: contact only at the wave crests.
    let (e, r_s, lambda, h) = (1.0, 1.0, 0.05, 0.01);
    let alpha: f64 = 0.05;
    let gamma = alpha * alpha * PI * PI * h * h * e / (2.0 * lambda);
    let n = 96;
    let grid = Grid::square(n, lambda / 12.0, Boundary::Free).unwrap();
    let mut surface = Surface::from_shape(grid, &Sphere::new(r_s).unwrap());
    surface.add_shape(&Waviness2d::new(h, lambda).unwrap());
    let mut s = solver(&surface, e, gamma);
    let rec = s.step(0.03).unwrap();
    eprintln!(
        "point cloud: {} bonded in {} clusters",
        rec.n_bonded, rec.n_clusters
    );
    assert!(rec.converged);
    assert!(
        rec.n_clusters >= 9,
        "expected many spots, got {}",
        rec.n_clusters
    );
    assert_admissible(&s, &rec, 1e-6 * h);
    let back = s.step(-0.001).unwrap();
    assert!(back.converged);
    assert_admissible(&s, &back, 1e-6 * h);
}

#[test]
fn a_step_across_the_jump_off_terminates_detached() {
    let mut jkr = JkrSphere::new(5.0, KAPPA);
    jkr.unload_step = 1.3; // 6 → 4.7 → … → −1.8 jumps straight past d̂ = −1.609
    let run = jkr.run();
    assert!(run.result.all_converged() && run.result.completed);
    let last = run.result.records.last().unwrap();
    assert_eq!((last.n_bonded, last.force), (0, 0.0));
}

#[test]
fn same_inputs_give_the_same_bits_on_any_thread_count() {
    // The run inside rayon pools of 1, 2 and 3 threads, one of them while two other runs
    // compete for the cores: every parallel part of a solve must reduce in a fixed order, so
    // every record matches to the bit (StepRecord's derived PartialEq would let −0.0 == 0.0
    // and NaN != NaN pass or fail wrongly: the f64 fields are compared as bits).
    // a_c/Δx = 20: the grid's transforms (256² and more) are split into lanes, one per thread.
    let go = || {
        JkrSphere {
            coarse_unload_step: Some(0.1),
            ..JkrSphere::new(20.0, KAPPA)
        }
        .run()
        .result
    };
    let in_pool = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(go)
    };
    let reference = in_pool(1);
    let busy: Vec<_> = (0..2).map(|_| std::thread::spawn(go)).collect();
    let others = [in_pool(2), in_pool(3)];
    let others = others
        .into_iter()
        .chain(busy.into_iter().map(|h| h.join().unwrap()));
    let bits = |r: &StepRecord| {
        [r.approach, r.force, r.mean_pressure, r.area, r.residual].map(f64::to_bits)
    };
    for run in others {
        assert_eq!(reference.records.len(), run.records.len());
        for (x, y) in reference.records.iter().zip(&run.records) {
            assert_eq!(bits(x), bits(y));
            assert_eq!(
                (
                    x.n_bonded,
                    x.n_clusters,
                    x.cg_iterations,
                    x.active_set_iterations
                ),
                (
                    y.n_bonded,
                    y.n_clusters,
                    y.cg_iterations,
                    y.active_set_iterations
                )
            );
            assert_eq!((x.converged, x.full_contact), (y.converged, y.full_contact));
        }
    }
}

#[test]
#[cfg_attr(debug_assertions, ignore = "512² grid: release mode only")]
fn large_512_grid_converges() {
    // Periodic 512² with 2D waviness (8 wavelengths per side, α = 0.3): load and pull back.
    let (e, lambda, h) = (1.0, 1.0 / 8.0, 1e-3);
    let alpha: f64 = 0.3;
    let gamma = alpha * alpha * PI * PI * h * h * e / (2.0 * lambda);
    let grid = Grid::square(512, 1.0 / 512.0, Boundary::Periodic).unwrap();
    let surface = Surface::from_shape(grid, &Waviness2d::new(h, lambda).unwrap());
    let mut s = solver(&surface, e, gamma);
    for d in [0.3 * h, 0.6 * h, 0.2 * h] {
        let rec = s.step(d).unwrap();
        assert!(rec.converged, "d = {d}: {rec:?}");
        assert_admissible(&s, &rec, 1e-6 * h);
        assert_eq!(
            rec.n_clusters % 64,
            0,
            "symmetric spots: {}",
            rec.n_clusters
        );
    }
}

#[test]
fn line_front_kappa_from_discrete_punch() {
    // A periodic strip punch (width 2a, period λ) has the closed-form edge field
    // K = |p̄|·√(λ/tan ψ), ψ = πa/λ. The discrete solution's edge tension p_e defines
    // β = p_e√Δx/K and the criterion constant κ = 1/(2β²); it must converge to KAPPA_LINE.
    let mut last = f64::INFINITY;
    for (nx, width) in [(1024usize, 127usize), (4096, 511), (16384, 2047)] {
        let dx = 1.0 / nx as f64;
        let grid = Grid::new(nx, 1, dx, Boundary::Periodic).unwrap();
        let c = nx / 2;
        let h = Array2::from_shape_fn(
            (nx, 1),
            |(i, _)| if i.abs_diff(c) <= width / 2 { 0.0 } else { 1.0 },
        );
        let surface = Surface::new(grid, h).unwrap();
        // Huge γ: nothing detaches, so this is the bonded linear problem.
        let mut s = solver_with(&surface, 1.0, 1e6, KAPPA);
        let rec = s.step(1e-4).unwrap();
        assert!(rec.converged && rec.n_bonded == width);
        let psi = PI * rec.n_bonded as f64 * dx / 2.0;
        let k = rec.mean_pressure.abs() * (1.0 / psi.tan()).sqrt();
        let edge = s.pressure()[[c + width / 2, 0]];
        let beta = edge * dx.sqrt() / k;
        let kappa = 1.0 / (2.0 * beta * beta);
        eprintln!("strip punch {width}/{nx}: β = {beta:.5}, κ_line = {kappa:.5}");
        let err = (kappa - KAPPA_LINE).abs();
        assert!(err < last || err < 2e-4, "κ_line must converge: {kappa}");
        last = err;
    }
    assert!(
        last < 1e-3,
        "κ_line = {KAPPA_LINE} not settled: off by {last}"
    );
}

#[test]
fn bonded_subgrid_cg_changes_nothing_but_the_cost() {
    // The free operator is exact on any sub-grid: CG on a window around the bonded set solves the
    // same linear problem as on the whole grid. Tight tolerance, so only round-off differs.
    let grid = Grid::square(61, 0.05, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    let run_with = |bonded_subgrid: bool| {
        let options = AdhesiveOptions {
            cg: tack_solver::SolverOptions {
                tolerance: 1e-13,
                max_iterations: 10_000,
            },
            bonded_subgrid,
            // Inexact rounds attach only inside their sub-grid, so the rounds (not the
            // equilibria) would differ: compare the exact algorithm's paths.
            round_tolerance: None,
            ..AdhesiveOptions::default()
        };
        let op = operator_for(grid, 1.0).unwrap();
        let mut s = AdhesiveSolver::new(op, &surface, 0.05, KAPPA, options).unwrap();
        run(&mut s, &path(0.02, 0.4, 0.02, 0.01))
    };
    let (full, sub) = (run_with(false), run_with(true));
    assert_eq!(full.records.len(), sub.records.len());
    let scale = full
        .records
        .iter()
        .map(|r| r.force.abs())
        .fold(0.0, f64::max);
    for (a, b) in full.records.iter().zip(&sub.records) {
        assert_eq!(a.n_bonded, b.n_bonded, "d = {}", a.approach);
        assert!(
            (a.force - b.force).abs() <= 1e-10 * scale,
            "d = {}: {} vs {}",
            a.approach,
            a.force,
            b.force
        );
    }
    assert!(full.pull_off_force() < 0.0);
}

/// Virtual crack closure on a discrete straight front: with `t_e` the tension of the front
/// element and `g_f` the gap of the free element behind it, `t_e·g_f/2` is the energy release
/// rate `G = K²/(2E*)` of the closed-form field, for fronts along the grid (a periodic strip,
/// closed form `K = |p̄|·√(λ/tan ψ)`) and at 45° (a diagonal band of the same closed form): the
/// ratio converges to 1 (second order). Kept as the record of why the crack-closure criterion
/// was tried and why it was dropped: on the staircase fronts of a disc the same estimate is
/// biased by configuration (see ARCHITECTURE.md, "Detachment criterion").
#[test]
fn crack_closure_product_is_the_energy_release_rate_on_straight_fronts() {
    // (grid side, bonded width, 45°?)
    let cases = [
        (1024usize, 127usize, false),
        (4096, 511, false),
        (16384, 2047, false),
        (256, 64, true),
        (512, 128, true),
    ];
    let mut last = [f64::INFINITY; 2];
    for (n, w, diagonal) in cases {
        let dx = 1.0 / n as f64;
        let eps = 1e-12;
        let (grid, h, lambda) = if diagonal {
            let grid = Grid::new(n, n, dx, Boundary::Periodic).unwrap();
            let h =
                Array2::from_shape_fn((n, n), |(i, j)| if (i + n - j) % n < w { 0.0 } else { eps });
            (grid, h, dx * n as f64 / 2f64.sqrt())
        } else {
            let grid = Grid::new(n, 1, dx, Boundary::Periodic).unwrap();
            let c = n / 2;
            let h = Array2::from_shape_fn(
                (n, 1),
                |(i, _)| if i.abs_diff(c) <= w / 2 { 0.0 } else { eps },
            );
            (grid, h, 1.0)
        };
        let surface = Surface::new(grid, h).unwrap();
        // Bond the band (it alone penetrates), then pull with a γ so large nothing detaches.
        let mut s = solver_with(&surface, 1.0, 1e9, KAPPA);
        let bonded = s.step(eps / 2.0).unwrap().n_bonded;
        let rec = s.step(-1.0).unwrap();
        assert!(rec.converged && rec.n_bonded == bonded);
        let psi = PI * rec.n_bonded as f64 / (2.0 * grid.len() as f64);
        let k = rec.mean_pressure.abs() * (lambda / psi.tan()).sqrt();
        // Front element and the free element behind it.
        let (front, behind) = if diagonal {
            ([5, 5], [5, 6])
        } else {
            ([n / 2 + w / 2, 0], [n / 2 + w / 2 + 1, 0])
        };
        let (t, g) = (-s.pressure()[front], s.gap()[behind]);
        let ratio = (t * g / 2.0) / (k * k / 2.0);
        eprintln!(
            "front {} width {w}/{n}: t·g/2 / G = {ratio:.5}",
            if diagonal { "45°" } else { "0°" }
        );
        let err = (ratio - 1.0).abs();
        let l = &mut last[diagonal as usize];
        assert!(err < *l, "must converge to 1: {ratio}");
        *l = err;
    }
    assert!(last[0] < 5e-4 && last[1] < 5e-3, "{last:?}");
}
