//! What a load–retract cycle shows beyond its pull-off: the energy the loop dissipates, and the
//! jumps into and out of contact.

use crate::{PathResult, Phase};

/// The cycle quantities of a force–approach path ([`cycle`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Cycle {
    /// The loop integral `∮F dd` (trapezoids over the steps in path order): the work the
    /// loading device puts in over the cycle, dissipated by the jumps (≥ 0 up to the
    /// quadrature). The loop closes at the last step's approach: loading steps below it have no
    /// retraction leg, and are left out (the loading branch is cut there, its force
    /// interpolated). Under a smooth law the path ends where no tension above 1% of the peak is
    /// left, its approach began out of reach, and counting the loading tail there made the loop
    /// open, and negative at small Tabor μ (−2.1e-6 at μ = 0.3 on 64²). `None` unless the path
    /// starts out of contact and ends detached (an open curve has no loop).
    pub dissipated_energy: Option<f64>,
    /// How much [`Cycle::dissipated_energy`] changes when the loading branch keeps only every
    /// other step (its first and last kept): the loop's error from the approach's sampling, to
    /// its order of magnitude. Where the retraction retraces the approach (a reversible cycle)
    /// the loop is the trapezoids' error on the coarser branch alone (docs/theory.md §3.7,
    /// "Cycle quantities"). `None` with the loop.
    pub approach_sampling: Option<f64>,
    /// The first loading step that is joined ([`CycleStep::joined`]) after steps that were not:
    /// its approach and force (a tensile force: the surfaces snapped in). `None` when the path
    /// starts joined.
    pub jump_in: Option<(f64, f64)>,
    /// The last retraction step that is joined before the steps that are not: its approach and
    /// force (the force lost in the jump out). `None` when the path ends joined.
    pub jump_out: Option<(f64, f64)>,
}

/// A step of a curve as [`cycle`] reads it: approach, force, whether anything carries load
/// (elements in contact or in a cohesive zone), whether the surfaces are joined (where the
/// jumps are), and whether it is a loading step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleStep {
    /// Approach `d`.
    pub approach: f64,
    /// Force (compressive positive).
    pub force: f64,
    /// Some element carries load.
    pub loaded: bool,
    /// The surfaces are joined: some element carries load under the zero-range criterion and
    /// the Dugdale law (whose zone carries the law's whole tension σ0: it may jump onto a
    /// separated branch), some element is in contact under a smooth law (every element within
    /// its reach carries a traction, growing smoothly as the surfaces approach, so the jump is
    /// the snap into contact; at small Tabor μ contact forms without a jump, and this is where
    /// it forms).
    pub joined: bool,
    /// The step belongs to the loading branch.
    pub loading: bool,
}

/// The cycle quantities of a curve given step by step (usable on a curve read from a file).
pub fn cycle(steps: &[CycleStep]) -> Cycle {
    let mut out = Cycle::default();
    let (Some(first), Some(last)) = (steps.first(), steps.last()) else {
        return out;
    };
    if !first.loaded && !last.loaded {
        let all = loop_integral(steps, |_| true);
        // The loading branch's steps at odd places dropped, its last kept.
        let loading: Vec<usize> = (0..steps.len()).filter(|&i| steps[i].loading).collect();
        let mut keep = vec![true; steps.len()];
        for (k, &i) in loading.iter().enumerate() {
            keep[i] = k % 2 == 0 || k + 1 == loading.len();
        }
        let coarse = loop_integral(steps, |i| keep[i]);
        out.dissipated_energy = Some(all);
        out.approach_sampling = Some((coarse - all).abs());
    }
    out.jump_in = steps
        .windows(2)
        .find(|w| w[1].loading && !w[0].joined && w[1].joined)
        .map(|w| (w[1].approach, w[1].force));
    out.jump_out = steps
        .windows(2)
        .rev()
        .find(|w| !w[1].loading && w[0].joined && !w[1].joined)
        .map(|w| (w[0].approach, w[0].force));
    out
}

/// The loop integral `∮F dd` over the steps `keep` selects, in path order ([`cycle`]): closed at
/// the last step's approach, the loading branch below it cut there.
fn loop_integral(steps: &[CycleStep], keep: impl Fn(usize) -> bool) -> f64 {
    let end = steps.last().map_or(0.0, |s| s.approach);
    let kept: Vec<&CycleStep> = (0..steps.len())
        .filter(|&i| keep(i))
        .map(|i| &steps[i])
        .collect();
    kept.windows(2)
        .map(|w| {
            let ((a0, f0), (a1, f1)) = ((w[0].approach, w[0].force), (w[1].approach, w[1].force));
            if w[0].loading && w[1].loading && a0 < end {
                // The loading branch below the loop's end: cut at `end`.
                if a1 <= end {
                    return 0.0;
                }
                let at_end = f0 + (f1 - f0) * (end - a0) / (a1 - a0);
                return 0.5 * (at_end + f1) * (a1 - end);
            }
            0.5 * (f0 + f1) * (a1 - a0)
        })
        .sum()
}

impl PathResult {
    /// The cycle quantities of the path ([`cycle`]) under the zero-range criterion or the
    /// Dugdale law: joined where some element carries load ([`CycleStep::joined`]).
    pub fn cycle(&self) -> Cycle {
        self.cycle_joined_by(|r| r.n_bonded + r.n_cohesive > 0)
    }

    /// The cycle quantities of the path ([`cycle`]) under `law`: under a smooth law the jumps
    /// are where contact forms and is lost ([`CycleStep::joined`]).
    pub fn cycle_under(&self, law: &crate::AdhesionLaw) -> Cycle {
        if law.curve().is_some() {
            self.cycle_joined_by(|r| r.n_bonded > 0)
        } else {
            self.cycle()
        }
    }

    fn cycle_joined_by(&self, joined: impl Fn(&crate::StepRecord) -> bool) -> Cycle {
        let steps: Vec<CycleStep> = self
            .records
            .iter()
            .zip(&self.phases)
            .map(|(r, &phase)| CycleStep {
                approach: r.approach,
                force: r.force,
                loaded: r.n_bonded + r.n_cohesive > 0,
                joined: joined(r),
                loading: phase == Phase::Load,
            })
            .collect();
        cycle(&steps)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn step(approach: f64, force: f64, loading: bool) -> CycleStep {
        CycleStep {
            approach,
            force,
            loaded: force != 0.0,
            joined: force != 0.0,
            loading,
        }
    }

    #[test]
    fn a_rectangle_loop_dissipates_its_area_and_reports_its_jumps() {
        // Load: nothing until d = 1, then −1 from d = 1 to 3; retract: −2 from 3 down to 0.
        let steps = [
            step(0.0, 0.0, true),
            step(1.0, -1.0, true),
            step(3.0, -1.0, true),
            step(2.0, -2.0, false),
            step(0.0, -2.0, false),
            step(-1.0, 0.0, false),
        ];
        let c = cycle(&steps);
        // ∮F dd: loading −0.5 − 2, the turn 3 → 2 at mean force −1.5 gives +1.5, retraction
        // +4 + 1: 4.
        assert_eq!(c.dissipated_energy, Some(4.0));
        assert_eq!(c.jump_in, Some((1.0, -1.0)));
        assert_eq!(c.jump_out, Some((0.0, -2.0)));
    }

    #[test]
    fn the_loop_closes_at_the_last_approach() {
        // A smooth law's path: the approach starts far out (d = −4) with a little tension
        // everywhere, and the retraction ends at d = −2, where the tension left is below the
        // law's zone cut (not loaded, but not zero). The loading steps below −2 have no
        // retraction leg: the loop is the closed one from −2 on, the loading force at −2
        // interpolated (−0.15). Loading −2 → 0 at −0.15 … −0.5, 0 → 1 at −0.5 … −1; the turn;
        // retraction back to −2.
        let mut steps = vec![
            step(-4.0, -0.05, true),
            step(-3.0, -0.1, true),
            step(-1.0, -0.2, true),
            step(0.0, -0.5, true),
            step(1.0, -1.0, true),
            step(0.0, -2.0, false),
            step(-1.0, -1.0, false),
            step(-2.0, -0.1, false),
        ];
        for s in [0, 1, 7] {
            (steps[s].loaded, steps[s].joined) = (false, false);
        }
        let c = cycle(&steps);
        let loading = 0.5 * (-0.15 - 0.2) * 1.0 + 0.5 * (-0.2 - 0.5) + 0.5 * (-0.5 - 1.0);
        // Each retraction step goes back by 1: −(mean force).
        let retraction = 0.5 * (1.0 + 2.0) + 0.5 * (2.0 + 1.0) + 0.5 * (1.0 + 0.1);
        let want = loading + retraction;
        let got = c.dissipated_energy.unwrap();
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
        // The loading tail from −4 to −2 counted (0.2 of tension work) opened the loop.
        assert!((want - 2.275).abs() < 1e-12);
        // The jumps read `joined`: here the same as loaded.
        assert_eq!(c.jump_in, Some((-1.0, -0.2)));
    }

    #[test]
    fn a_step_loaded_before_the_surfaces_join_is_no_jump() {
        // Under a smooth law tension precedes contact: the jump in is the first joined step.
        let mut steps = vec![
            step(-2.0, 0.0, true),
            step(-1.0, -0.1, true),
            step(0.0, -1.0, true),
            step(-1.0, -0.5, false),
            step(-2.0, 0.0, false),
        ];
        steps[1].joined = false;
        let c = cycle(&steps);
        assert_eq!(c.jump_in, Some((0.0, -1.0)));
        assert_eq!(c.jump_out, Some((-1.0, -0.5)));
    }

    /// A reversible curve `F = d²` on `0 ≤ d ≤ 1`, loaded in steps of 0.25 and retracted in
    /// steps of 0.01: the loop is the approach trapezoids' error, `h²/12·(F'(1) − F'(0))` =
    /// 0.0104 (the retraction's is 1.7e-5), and keeping every other loading step (h = 0.5)
    /// makes it 0.0417: the sampling's estimate, 0.0313, is three times the loop itself.
    #[test]
    fn a_retraced_curve_loops_by_its_approach_sampling_alone() {
        let load = (0..=4)
            .map(|i| f64::from(i) * 0.25)
            .map(|d| step(d, d * d, true));
        let retract = (0..100)
            .rev()
            .map(|i| f64::from(i) * 0.01)
            .map(|d| step(d, d * d, false));
        let steps: Vec<CycleStep> = load.chain(retract).collect();
        let c = cycle(&steps);
        let (w, e) = (c.dissipated_energy.unwrap(), c.approach_sampling.unwrap());
        let err = |h: f64| h * h / 12.0 * 2.0;
        assert!((w - (err(0.25) - err(0.01))).abs() < 1e-12, "{w}");
        assert!((e - (err(0.5) - err(0.25))).abs() < 1e-12, "{e}");
        assert!(e > 2.9 * w);
        // Sampled as finely both ways, the loop vanishes and the estimate is the 0.02-step
        // trapezoids' error less the 0.01-step ones', 5e-5.
        let fine: Vec<CycleStep> = (0..=100)
            .map(|i| f64::from(i) * 0.01)
            .map(|d| step(d, d * d, true))
            .chain(steps[5..].iter().copied())
            .collect();
        let c = cycle(&fine);
        assert!(c.dissipated_energy.unwrap().abs() < 1e-12);
        let e = c.approach_sampling.unwrap();
        assert!((e - (err(0.02) - err(0.01))).abs() < 1e-12, "{e}");
    }

    #[test]
    fn an_open_curve_has_no_loop() {
        let steps = [
            step(1.0, 1.0, true),
            step(0.5, -1.0, false),
            step(0.0, 0.0, false),
        ];
        let c = cycle(&steps);
        assert_eq!(c.dissipated_energy, None);
        assert_eq!(c.jump_in, None);
        assert_eq!(c.jump_out, Some((0.5, -1.0)));
        assert_eq!(cycle(&[]), Cycle::default());
    }
}
