//! A smooth law of the caller's own ([`AdhesionLaw::custom`]): the Morse law, written in the
//! example `custom_law` and nowhere in tack, against the independent ring solution of the same law (`tests/axisym`):
//! the pull-off and both branches at Tabor μ = 1 with the observed order, the DMT limit at
//! μ = 0.1; and a built-in curve run as a custom one gives the built-in's bits.

mod axisym;
#[path = "../examples/custom_law/morse.rs"]
mod morse;
mod sphere_run;

use sphere_run::run;
use std::f64::consts::PI;
use tack_solver::{AdhesionLaw, Curve, Exponential, LennardJones};

use morse::Morse;

/// A built-in law's curve under a name of its own: the same pressure bits through a dynamic
/// call.
#[derive(Debug)]
struct Copied(AdhesionLaw, &'static str);

impl Curve for Copied {
    fn name(&self) -> &'static str {
        self.1
    }
    fn label(&self) -> &'static str {
        "a copy, range l"
    }
    fn length(&self) -> f64 {
        self.0.curve().unwrap().length()
    }
    fn meaning(&self) -> &'static str {
        "a copy of a built-in law"
    }
    fn pressure(&self, gamma: f64, g: f64) -> f64 {
        self.0.curve().unwrap().pressure(gamma, g)
    }
    fn stiffness(&self, gamma: f64, g: f64) -> f64 {
        self.0.curve().unwrap().stiffness(gamma, g)
    }
    fn pressure_and_stiffness(&self, gamma: f64, g: f64) -> (f64, f64) {
        self.0.curve().unwrap().pressure_and_stiffness(gamma, g)
    }
    fn stiffens(&self) -> bool {
        self.0.curve().unwrap().stiffens()
    }
    fn peak(&self, gamma: f64) -> f64 {
        self.0.curve().unwrap().peak(gamma)
    }
    fn reach(&self) -> f64 {
        self.0.curve().unwrap().reach()
    }
    fn falls_past_peak(&self) -> bool {
        self.0.curve().unwrap().falls_past_peak()
    }
}

/// The Morse law at Tabor μ = 1 (ρ = 1): the grid's pull-off against the ring solution traced
/// through its fold (`Reference::trace_retraction`), and its force–approach curve against the
/// ring solution's steps at the same approaches, on 48², 96² and 192² elements of 0.5, 0.25
/// and 0.125 (the process zone (8/3π)E*ρ²/γ = 0.85 spans 1.7, 3.4 and 6.8 of them; the law's
/// tail at the domain's edge r = 12 is e^(−72)).
#[test]
fn a_custom_morse_law_follows_its_ring_solution() {
    let rho = 1.0;
    let law = AdhesionLaw::custom(Morse { range: rho }).unwrap();
    assert_eq!(law.name(), "morse");
    assert_eq!(law.tabor(1.0, 1.0, 1.0), Some(1.0));
    let ring = axisym::Law::Morse { gamma: 1.0, rho };
    let edges = axisym::Reference::graded_edges(12.0, 0.25, 4.0, 0.02, 4.0);
    let traced = axisym::Reference::with_edges(1.0, 1.0, ring, edges.clone())
        .trace_retraction(1.5, 0.02, 4000)
        .expect("the continuation starts and runs");
    // At μ = 1 the Morse law retracts without a jump: the trace runs on past the force's
    // least value (until the tension is half of it), which is the pull-off.
    let f_ref = traced.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    assert!(
        traced.last().is_some_and(|p| p.1 > 0.9 * f_ref),
        "past the least force"
    );
    let path = (-3.0, 1.5, 0.1, -3.0);
    let mut rows = Vec::new();
    let mut refs = Vec::new();
    for (n, dx) in [(48, 0.5), (96, 0.25), (192, 0.125)] {
        let result = run(&law, n, dx, path);
        assert!(result.all_converged(), "n = {n}");
        if refs.is_empty() {
            let mut r = axisym::Reference::with_edges(1.0, 1.0, ring, edges.clone());
            refs = result.records.iter().map(|s| r.step(s.approach)).collect();
        }
        let curve = result
            .records
            .iter()
            .zip(&refs)
            .filter(|(_, p)| p.converged && !p.jumped)
            .map(|(s, p)| (s.force - p.force).abs())
            .fold(0.0f64, f64::max)
            / f_ref.abs();
        let f = result.pull_off_force();
        // The ring solution's least force at the path's own approaches: the same sampling of
        // a minimum that no jump marks.
        let sampled = refs.iter().map(|p| p.force).fold(f64::INFINITY, f64::min);
        eprintln!(
            "n = {n}: F/(πγR) = {:.5} (ring {:.5} at these approaches, {:.5} traced), error \
             {:+.3}%, curve {:.3}%",
            f / -PI,
            sampled / -PI,
            f_ref / -PI,
            100.0 * (f / sampled - 1.0),
            100.0 * curve,
        );
        rows.push((f / sampled - 1.0, curve));
    }
    let order = |a: f64, b: f64| (a.abs() / b.abs()).log2();
    eprintln!(
        "observed order: curve {:.2} then {:.2}, pull-off {:.2} then {:.2}",
        order(rows[0].1, rows[1].1),
        order(rows[1].1, rows[2].1),
        order(rows[0].0, rows[1].0),
        order(rows[1].0, rows[2].0)
    );
    // Measured (296 graded rings; traced 1.76889, sampled 1.76837 πγR): pull-off −0.065%,
    // −0.048%, −0.019% and curve 0.76%, 0.185%, 0.044%, order 2.04 and 2.07 for the curve;
    // the pull-off is within 0.1% on every grid, its order masked by terms of both signs at
    // that level. Bounds at about twice the measured errors.
    assert!(
        order(rows[0].1, rows[1].1) > 1.6 && order(rows[1].1, rows[2].1) > 1.6,
        "{rows:?}"
    );
    assert!(rows.iter().all(|r| r.0.abs() < 1.5e-3), "{rows:?}");
    assert!(rows[2].0.abs() < 5e-4, "{rows:?}");
    assert!(
        rows[0].1 < 1.5e-2 && rows[1].1 < 4e-3 && rows[2].1 < 1e-3,
        "{rows:?}"
    );
}

/// The DMT limit under the custom law: at μ = 0.1 (ρ = 10) the pull-off is close to the rigid
/// value 2πγR, and the grid follows the ring solution of the same law.
#[test]
fn a_custom_morse_law_meets_dmt_at_a_small_tabor_parameter() {
    let rho = 10.0;
    let law = AdhesionLaw::custom(Morse { range: rho }).unwrap();
    let result = run(&law, 40, 1.0, (-30.0, 2.0, 0.5, -30.0));
    assert!(result.all_converged());
    let f = result.pull_off_force() / (-2.0 * PI);
    let ring = axisym::Law::Morse { gamma: 1.0, rho };
    let mut r = axisym::Reference::new(1.0, 1.0, ring, 240, 60.0);
    let f_ref = result
        .records
        .iter()
        .map(|s| r.step(s.approach).force)
        .fold(f64::INFINITY, f64::min)
        / (-2.0 * PI);
    eprintln!("μ = 0.1: F/(2πγR) = {f:.5}, ring {f_ref:.5}");
    // Measured 0.99439 against the ring's 0.99442: DMT within 1% (the ring's own distance from
    // it is 0.56%), the grid within 1e-3 of the ring (3e-5 measured; the domain's edge cuts the
    // law's tail at e^(−14)).
    assert!(
        (f_ref - 1.0).abs() < 0.01 && (f - 1.0).abs() < 0.01,
        "{f} {f_ref}"
    );
    assert!((f / f_ref - 1.0).abs() < 1e-3, "{f} vs {f_ref}");
}

/// The Morse law at μ = 3 on 96², 1.2 elements per process zone (the example's last row):
/// past the pull-off, with nothing on the wall, a landing's stiff set (`s k < −1`, solved with
/// the contact) cycled between 0 and 230 elements, with repeats, to the landing's cap, and a
/// step did not converge (6.5 s). The set is now held once it has changed on 40 iterations of a
/// landing: every step converges (1.2 s), and the pull-off, which comes before, keeps its
/// value (1.5843 πγR, printed to four digits by the example before and after).
#[test]
fn a_cycling_stiff_set_is_held_and_every_step_converges() {
    let rho = 1.0 / 3.0;
    let law = AdhesionLaw::custom(Morse { range: rho }).unwrap();
    // The example's domain: the law's reach around the pull-off contact.
    let half = (2.0 * law.reach(1.0).unwrap()).sqrt().max(3.0);
    let path = (-(3.0 * rho + 1.0), 1.5, rho / 4.0, -(3.0 * rho + 3.0));
    let result = run(&law, 96, 2.0 * half / 96.0, path);
    let stuck: Vec<f64> = result
        .records
        .iter()
        .filter(|r| !r.converged)
        .map(|r| r.approach)
        .collect();
    assert!(stuck.is_empty(), "steps not converged at d = {stuck:?}");
    let f = -result.pull_off_force() / PI;
    assert!((f - 1.5843).abs() < 5e-5, "{f}");
}

/// A built-in law run as a custom one (its curve under another name, through the dynamic
/// call) gives the built-in's bits at every step: the custom path is the same solver.
#[test]
fn a_built_in_curve_run_as_a_custom_law_gives_the_same_bits() {
    let cases = [
        (AdhesionLaw::from(Exponential { range: 0.5 }), "exp_copy"),
        (AdhesionLaw::from(LennardJones { range: 1.0 }), "lj_copy"),
    ];
    for (built_in, name) in cases {
        let custom = AdhesionLaw::custom(Copied(built_in.clone(), name)).unwrap();
        let path = (-3.0, 1.5, 0.1, -3.0);
        let (a, b) = (run(&built_in, 48, 0.25, path), run(&custom, 48, 0.25, path));
        assert!(a.all_converged() && b.all_converged());
        assert_eq!(a.records.len(), b.records.len(), "{name}");
        for (x, y) in a.records.iter().zip(&b.records) {
            assert_eq!(
                x.force.to_bits(),
                y.force.to_bits(),
                "{name} at {}",
                x.approach
            );
            assert_eq!(x.n_bonded, y.n_bonded, "{name}");
            assert_eq!(x.cg_iterations, y.cg_iterations, "{name}");
        }
    }
}
