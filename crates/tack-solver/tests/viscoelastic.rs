//! Viscoelastic half-spaces (a standard linear solid, E∞/E0 = 10) against closed forms and
//! limits: a non-adhesive sphere pressed at constant speed against Lee & Radok (1960), both
//! the discrete hereditary integral of the same grid's elastic force (which isolates the time
//! stepping; its observed order) and the continuum one (within the grid's Hertz error); very
//! slow and very fast adhesive paths against the elastic solver at E0 and E∞; a flat punch
//! relaxed under load and retracted fast, between its elastic pull-offs at E0 and E∞; the same
//! bits on one and two threads.
//!
//! Units: R = 1, E0 = 1, τ = 1.

use tack_geometry::{Boundary, FlatPunch, Grid, Shape, Sphere, Surface};
use tack_kernels::operator_for;
use tack_solver::{
    AdhesionLaw, AdhesiveOptions, AdhesiveSolver, ApproachPath, Dugdale, Exponential, JkrLimit,
    KAPPA, PathResult, Prony, Rates, SnapshotRequest,
};

/// The standard linear solid of the tests: E0 = 1, one arm E1 = 9, τ = 1.
fn sls() -> Prony {
    Prony::new(1.0, &[(9.0, 1.0)]).unwrap()
}

/// A solver for `shape` on a free `n × n` grid of side `side` with modulus `e_star`, work of
/// adhesion `gamma` and `law`.
fn solver(
    shape: &dyn Shape,
    n: usize,
    side: f64,
    e_star: f64,
    gamma: f64,
    law: &AdhesionLaw,
) -> AdhesiveSolver {
    let grid = Grid::square(n, side / n as f64, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, shape);
    let op = operator_for(grid, e_star).unwrap();
    AdhesiveSolver::with_law(op, &surface, gamma, law.clone(), AdhesiveOptions::default()).unwrap()
}

fn run(s: &mut AdhesiveSolver, path: &ApproachPath) -> PathResult {
    let r = s.run_path(path, &SnapshotRequest::None, &mut ()).unwrap();
    assert!(r.all_converged(), "every step converges");
    r
}

/// Loading only, from the apex (d = 0) to `depth` in `steps` steps.
fn press(depth: f64, steps: usize) -> ApproachPath {
    ApproachPath {
        start: 0.0,
        max_approach: depth,
        load_step: depth / steps as f64,
        unload_step: depth / steps as f64,
        coarse_unload_step: None,
        refine_pull_off: false,
        retract_to: Some(depth),
        max_steps: 100_000,
    }
}

/// Lee & Radok's force at time `t` of a history `f1(s)` (the force at unit modulus), sampled
/// at `times` with values `forces`, taken piecewise linear in time: `F(t) = ∫ E(t − s) ḟ1 ds`,
/// each interval integrated exactly.
fn hereditary(prony: &Prony, times: &[f64], forces: &[f64], t: f64) -> f64 {
    let mut total = 0.0;
    for k in 1..times.len() {
        let (s0, s1) = (times[k - 1], times[k].min(t));
        if s1 <= s0 {
            break;
        }
        let slope = (forces[k] - forces[k - 1]) / (times[k] - times[k - 1]);
        let mut integral = prony.relaxed() * (s1 - s0);
        for arm in prony.arms() {
            let tau = arm.time;
            integral += arm.modulus * tau * ((-(t - s1) / tau).exp() - (-(t - s0) / tau).exp());
        }
        total += slope * integral;
    }
    total
}

#[test]
fn a_sphere_pressed_at_constant_speed_follows_lee_and_radok() {
    let sphere = Sphere::new(1.0).unwrap();
    let (n, side, depth) = (64, 0.6, 0.02);
    let speed = 0.01; // the load lasts 2τ
    let none = AdhesionLaw::JkrLimit(JkrLimit { kappa: KAPPA });
    // The same grid's elastic force at unit modulus, finely sampled: the discrete problem's own
    // hereditary integral (Lee–Radok holds for it exactly while the contact grows).
    let fine = 800;
    let mut elastic = solver(&sphere, n, side, 1.0, 0.0, &none);
    let e = run(&mut elastic, &press(depth, fine));
    let times: Vec<f64> = e.records.iter().map(|r| r.approach / speed).collect();
    let forces: Vec<f64> = e.records.iter().map(|r| r.force).collect();
    let t_end = depth / speed;
    let discrete = hereditary(&sls(), &times, &forces, t_end);
    // The continuum one: F = (4√R/3)[E0 δ^(3/2) + E1 ∫ e^(−(t−s)/τ) (3/2) v^(3/2) √s ds].
    let continuum = {
        let m = 20_000;
        let h = t_end / m as f64;
        let integrand = |s: f64| (-(t_end - s)).exp() * 1.5 * speed.powf(1.5) * s.sqrt();
        // Simpson's rule on s = u² (smooth in u).
        let mut sum = 0.0;
        let u_end = t_end.sqrt();
        let hu = u_end / m as f64;
        for i in 0..=m {
            let u = i as f64 * hu;
            let w = if i == 0 || i == m {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            sum += w * integrand(u * u) * 2.0 * u;
        }
        let _ = h;
        (4.0 / 3.0) * (depth.powf(1.5) + 9.0 * sum * hu / 3.0)
    };
    let hertz_error = forces.last().unwrap() / ((4.0 / 3.0) * depth.powf(1.5)) - 1.0;
    let mut errors = Vec::new();
    for steps in [10usize, 20, 40, 80] {
        let mut visco = solver(&sphere, n, side, 1.0, 0.0, &none);
        visco.set_viscoelastic(sls(), rates(speed, speed)).unwrap();
        let r = run(&mut visco, &press(depth, steps));
        let last = r.records.last().unwrap();
        assert!((last.time.unwrap() - t_end).abs() < 1e-12 * t_end);
        let err = last.force / discrete - 1.0;
        let cont = last.force / continuum - 1.0;
        println!(
            "{steps} steps: {err:+.3e} against the discrete integral, {cont:+.3e} against the \
             continuum (the grid's Hertz error {hertz_error:+.3e})"
        );
        // Against the continuum: the grid's error (Hertz's at the deepest step, the largest
        // contact of the history) plus the time stepping's, with room for the history's
        // smaller contacts (a third more).
        assert!(
            cont.abs() < 1.35 * hertz_error.abs() + err.abs(),
            "{steps} steps: {cont:+.3e} off Lee–Radok"
        );
        errors.push(err.abs());
    }
    // The arms' exact update with the pressure linear over a step: second order in the time
    // step (measured 2.01, 2.04, 2.06 from 10 to 80 steps of 0.2τ … 0.025τ).
    for w in errors.windows(2) {
        let order = (w[0] / w[1]).log2();
        println!("observed order {order:.2}");
        assert!(order > 1.8, "order {order:.2}");
    }
    assert!(errors[2] < 1e-4, "40 steps over 2τ: {:.2e}", errors[2]);
}

/// Rates of a path: `speed` in, `unload` out, no hold.
fn rates(speed: f64, unload: f64) -> Rates {
    Rates {
        speed,
        unload_speed: unload,
        dwell: 0.0,
        dwell_steps: 1,
    }
}

/// A load–retract path of the adhesive tests: from out of range to `depth` and back until
/// detached, in steps `step`.
fn cycle(depth: f64, step: f64, range: f64) -> ApproachPath {
    ApproachPath::load_retract(-range - step, depth, step, step).unwrap()
}

/// The largest force difference between two curves over the steps both took (the same
/// approaches), over the largest force.
fn curve_gap(a: &PathResult, b: &PathResult) -> f64 {
    println!("steps {} and {}", a.records.len(), b.records.len());
    let scale = a.records.iter().map(|r| r.force.abs()).fold(0.0, f64::max);
    a.records
        .iter()
        .zip(&b.records)
        .map(|(x, y)| (x.force - y.force).abs())
        .fold(0.0, f64::max)
        / scale
}

#[test]
fn very_slow_and_very_fast_paths_are_elastic_at_the_relaxed_and_the_instantaneous_modulus() {
    let sphere = Sphere::new(1.0).unwrap();
    let (n, side, gamma, sigma0) = (48, 1.2, 1e-3, 0.1);
    let law = AdhesionLaw::Dugdale(Dugdale { sigma0 });
    let path = cycle(0.02, 0.001, gamma / sigma0);
    let relaxed = run(&mut solver(&sphere, n, side, 1.0, gamma, &law), &path);
    let glassy = run(&mut solver(&sphere, n, side, 10.0, gamma, &law), &path);
    // Steps of 10⁴τ: each step's modulus is E0 + E1·τ/Δt = 1.0009, the history 9e-4 of w.
    let mut slow = solver(&sphere, n, side, 1.0, gamma, &law);
    slow.set_viscoelastic(sls(), rates(1e-7, 1e-7)).unwrap();
    let slow = run(&mut slow, &path);
    // Steps of 1e-7τ: the modulus is E∞(1 − 4.5e-8), the history as small.
    let mut fast = solver(&sphere, n, side, 1.0, gamma, &law);
    fast.set_viscoelastic(sls(), rates(1e4, 1e4)).unwrap();
    let fast = run(&mut fast, &path);
    let (gs, gf) = (curve_gap(&slow, &relaxed), curve_gap(&fast, &glassy));
    let moduli = curve_gap(&relaxed, &glassy);
    println!("slow against E0: {gs:.2e}; fast against E∞: {gf:.2e}; E0 against E∞: {moduli:.2e}");
    let pull = |r: &PathResult| r.pull_off_force();
    println!(
        "pull-offs: E0 {:.5e}, slow {:.5e}, fast {:.5e}, E∞ {:.5e}",
        pull(&relaxed),
        pull(&slow),
        pull(&fast),
        pull(&glassy)
    );
    // Measured 4.3e-4 and 1.3e-6: the step moduli are 9e-4 and 4.5e-8 off E0 and E∞, the
    // curves apart by 5.4 of their scale.
    assert!(gs < 2e-3, "slow path against E0: {gs:.2e}");
    assert!(gf < 1e-5, "fast path against E∞: {gf:.2e}");
    assert!(moduli > 1.0);
    assert!((pull(&slow) / pull(&relaxed) - 1.0).abs() < 2e-3);
    assert!((pull(&fast) / pull(&glassy) - 1.0).abs() < 1e-5);
}

#[test]
fn a_punch_relaxed_under_load_and_pulled_fast_lies_between_its_elastic_pull_offs() {
    let punch = FlatPunch::circular(0.2).unwrap();
    let (n, side, gamma, sigma0) = (48, 0.6, 1e-3, 0.3);
    let law = AdhesionLaw::Dugdale(Dugdale { sigma0 });
    let range = gamma / sigma0;
    let path = cycle(0.001, 2e-4, range);
    let mut pulls = Vec::new();
    let relaxed = run(&mut solver(&punch, n, side, 1.0, gamma, &law), &path);
    let glassy = run(&mut solver(&punch, n, side, 10.0, gamma, &law), &path);
    for unload in [1e-3, 1e-2, 1e-1, 1e3] {
        let mut s = solver(&punch, n, side, 1.0, gamma, &law);
        let mut r = rates(1e-3, unload);
        (r.dwell, r.dwell_steps) = (50.0, 10);
        s.set_viscoelastic(sls(), r).unwrap();
        let v = run(&mut s, &path);
        println!(
            "unload speed {unload:e}: pull-off {:.5e} (E0 {:.5e}, E∞ {:.5e}), {} steps",
            v.pull_off_force(),
            relaxed.pull_off_force(),
            glassy.pull_off_force(),
            v.records.len()
        );
        pulls.push(-v.pull_off_force());
    }
    // Kendall's pull-off √(8πa³E*γ) at E0 and E∞ bound every speed; the tack's own elastic
    // pull-offs (−0.0173, −0.0359 at a/Δx = 16 and this cohesive law) are the same grid's.
    let kendall = |e: f64| (8.0 * std::f64::consts::PI * 0.2f64.powi(3) * e * gamma).sqrt();
    let (low, high) = (-relaxed.pull_off_force(), -glassy.pull_off_force());
    assert!(pulls.iter().all(|&f| kendall(1.0) < f && f < kendall(10.0)));
    // Faster retraction, stronger pull-off: from above the relaxed one (a retraction of 1.3τ
    // does not relax fully) to the instantaneous one (measured −0.0211 … −0.0361; the fast
    // limit 0.5% beyond the elastic E∞ run: the relaxed compression under the punch).
    assert!(pulls.windows(2).all(|w| w[0] < w[1]), "{pulls:?}");
    assert!(
        pulls[0] > low && (pulls[3] / high - 1.0).abs() < 0.01,
        "{pulls:?}"
    );
}

#[test]
fn a_smooth_law_pull_off_converges_in_the_time_step_and_keeps_its_bits_on_two_threads() {
    let sphere = Sphere::new(1.0).unwrap();
    // Tabor's μ = 1 at E0, 0.22 at E∞; the process zone spans 3.4 elements at E0.
    let (n, side, gamma, range) = (48, 1.2, 1e-3, 0.01);
    let law = AdhesionLaw::Exponential(Exponential { range });
    let mut pulls = Vec::new();
    for k in [1usize, 2, 4] {
        let step = 0.002 / k as f64;
        let path = cycle(0.02, step, 10.0 * range);
        let mut s = solver(&sphere, n, side, 1.0, gamma, &law);
        s.set_viscoelastic(sls(), rates(0.01, 0.01)).unwrap();
        let r = run(&mut s, &path);
        println!(
            "step {step}: pull-off {:.6e}, {} steps",
            r.pull_off_force(),
            r.records.len()
        );
        pulls.push(r.pull_off_force());
    }
    let relaxed = run(
        &mut solver(&sphere, n, side, 1.0, gamma, &law),
        &cycle(0.02, 0.0005, 10.0 * range),
    );
    let glassy = run(
        &mut solver(&sphere, n, side, 10.0, gamma, &law),
        &cycle(0.02, 0.0005, 10.0 * range),
    );
    println!(
        "elastic pull-offs: E0 {:.6e}, E∞ {:.6e}",
        relaxed.pull_off_force(),
        glassy.pull_off_force()
    );
    let order = ((pulls[0] - pulls[1]) / (pulls[1] - pulls[2])).abs().log2();
    println!("observed order {order:.2}");
    // Measured −1.11450e-2, −1.11542e-2, −1.11571e-2 at Δt = 0.2τ, 0.1τ, 0.05τ: order 1.68
    // (the pull-off is the least force over steps, itself sampled at the step), 0.03% apart at
    // the finest pair; the rate doubles the pull-off of both elastic limits.
    assert!(order > 1.4, "order {order:.2}");
    assert!((pulls[2] / pulls[1] - 1.0).abs() < 5e-4);
    assert!(pulls[2] < 1.5 * relaxed.pull_off_force().min(glassy.pull_off_force()));
    // The same bits on one and two threads.
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut s = solver(&sphere, n, side, 1.0, gamma, &law);
            s.set_viscoelastic(sls(), rates(0.01, 0.01)).unwrap();
            let r = run(&mut s, &cycle(0.02, 0.002, 10.0 * range));
            let bits: Vec<u64> = r.records.iter().map(|x| x.force.to_bits()).collect();
            (bits, s.pressure().clone())
        })
    };
    assert!(on(1) == on(2), "the same bits on one and two threads");
}

#[test]
fn what_a_viscoelastic_solver_refuses_is_named() {
    let sphere = Sphere::new(1.0).unwrap();
    let law = AdhesionLaw::Exponential(Exponential { range: 0.01 });
    let message = |e: tack_solver::SolverError| e.to_string();
    // Another modulus than the operator's, the criterion with adhesion, bad rates.
    let mut s = solver(&sphere, 16, 1.2, 2.0, 1e-3, &law);
    let e = message(s.set_viscoelastic(sls(), rates(1.0, 1.0)).unwrap_err());
    assert!(e.starts_with("material.e_star = 1 is invalid"), "{e}");
    let criterion = AdhesionLaw::JkrLimit(JkrLimit { kappa: KAPPA });
    let mut s = solver(&sphere, 16, 1.2, 1.0, 1e-3, &criterion);
    let e = message(s.set_viscoelastic(sls(), rates(1.0, 1.0)).unwrap_err());
    assert!(
        e.starts_with("adhesion.model: the zero-range criterion"),
        "{e}"
    );
    let mut s = solver(&sphere, 16, 1.2, 1.0, 1e-3, &law);
    let e = message(s.set_viscoelastic(sls(), rates(-1.0, 1.0)).unwrap_err());
    assert!(e.starts_with("protocol.speed = -1 is invalid"), "{e}");
    // A hold before any step; a solid set after one; a saved state restored.
    s.set_viscoelastic(sls(), rates(1.0, 1.0)).unwrap();
    assert!(message(s.hold(1.0).unwrap_err()).contains("take a step first"));
    s.step(0.001).unwrap();
    let saved = s.save_state();
    assert!(message(s.restore_state(&saved).unwrap_err()).contains("holds no viscoelastic arms"));
    let first = s.hold(1.0).unwrap();
    assert_eq!(
        first.time,
        Some(1.0),
        "the first step is instant, the hold lasts 1"
    );
    let mut late = solver(&sphere, 16, 1.2, 1.0, 1e-3, &law);
    late.step(0.001).unwrap();
    let e = message(late.set_viscoelastic(sls(), rates(1.0, 1.0)).unwrap_err());
    assert!(e.contains("starts at rest"), "{e}");
    // An arm that is not a spring and a dashpot.
    for arms in [[(0.0, 1.0)], [(1.0, f64::INFINITY)]] {
        let e = message(Prony::new(1.0, &arms).unwrap_err());
        assert!(e.starts_with("material.prony = "), "{e}");
    }
}
