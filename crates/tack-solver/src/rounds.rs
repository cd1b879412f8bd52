//! The schedule of one step's detach/attach rounds, shared by both adhesion laws: inexact
//! rounds until one finds nothing clear, tighter ones, then exact rounds until one changes
//! nothing (docs/theory.md §3.4, §3.7).

use std::collections::HashSet;

/// The inexact rounds' tolerance tightens by this factor each time a round finds nothing.
pub(crate) const LOOSE_TIGHTENING: f64 = 100.0;

/// What a step's rounds add up to, for its record: CG iterations, rounds, the worst residual
/// of an exact solve, whether every exact solve converged and no cap or cycle stopped the
/// step, and whether it ended in full contact.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Tally {
    pub(crate) cg: usize,
    pub(crate) rounds: usize,
    pub(crate) worst: f64,
    pub(crate) converged: bool,
    pub(crate) full: bool,
}

impl Tally {
    /// Nothing yet: no iteration, no round, converged.
    pub(crate) fn new() -> Self {
        Self {
            cg: 0,
            rounds: 0,
            worst: 0.0,
            converged: true,
            full: false,
        }
    }

    /// Counts an exact solve's residual and convergence.
    pub(crate) fn exact(&mut self, c: &crate::state::Convergence) {
        self.worst = self.worst.max(c.residual);
        self.converged &= c.converged;
    }
}

/// Where a step's rounds stand: whether the next round is exact, the inexact rounds'
/// tolerance, and the sets already visited.
pub(crate) struct Rounds {
    /// The inexact rounds' starting tolerance (`None`: exact rounds only, from the start or
    /// since inexact rounds came back to a set).
    inexact: Option<f64>,
    /// Whether the next round is solved to the CG tolerance and judged without margins.
    pub(crate) exact: bool,
    /// The next inexact round's tolerance: it tightens [`LOOSE_TIGHTENING`]× whenever a round
    /// finds nothing and returns to the start when a round changes a set.
    pub(crate) level: f64,
    /// The CG tolerance: a level at or below it is an exact round.
    tolerance: f64,
    /// Whether the last round changed a set (a set is revisited only after a change).
    just_changed: bool,
    inexact_visited: HashSet<u64>,
    visited: HashSet<u64>,
}

impl Rounds {
    /// Rounds starting at the inexact tolerance `start` (exact only when `None` or not above
    /// the CG `tolerance`).
    pub(crate) fn new(start: Option<f64>, tolerance: f64) -> Self {
        let inexact = start.filter(|&t| t > tolerance);
        Self {
            inexact,
            exact: inexact.is_none(),
            level: inexact.unwrap_or(0.0),
            tolerance,
            just_changed: true,
            inexact_visited: HashSet::new(),
            visited: HashSet::new(),
        }
    }

    /// Records the set (its `fingerprint`) the next round solves. Inexact rounds that come
    /// back to a set after a change switch the step to exact rounds; returns whether an exact
    /// round revisits a set (a cycle: the step stops as not converged).
    pub(crate) fn visit(&mut self, fingerprint: u64) -> bool {
        if !self.exact && self.just_changed && !self.inexact_visited.insert(fingerprint) {
            (self.inexact, self.exact) = (None, true);
        }
        self.exact && !self.visited.insert(fingerprint)
    }

    /// After a round's tests: whether the step is done (an exact round changed nothing);
    /// otherwise sets the next round's kind and tolerance.
    pub(crate) fn done(&mut self, changed: bool) -> bool {
        self.just_changed = changed;
        if changed {
            self.exact = self.inexact.is_none();
            self.level = self.inexact.unwrap_or(0.0);
            false
        } else if self.exact {
            true
        } else {
            self.level /= LOOSE_TIGHTENING;
            self.exact = self.level <= self.tolerance;
            false
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quiet_rounds_tighten_to_the_exact_round_and_a_change_starts_over() {
        let mut r = Rounds::new(Some(1e-3), 1e-9);
        assert!(!r.exact && r.level == 1e-3);
        assert!(!r.visit(1));
        assert!(!r.done(false));
        assert!(!r.exact && (r.level - 1e-5).abs() < 1e-20);
        assert!(!r.done(false) && !r.done(false));
        assert!(r.exact, "1e-9 is the CG tolerance: the exact round");
        assert!(!r.visit(1), "the first exact round on a set is no cycle");
        assert!(!r.done(true), "a change starts the loose rounds again");
        assert!(!r.exact && r.level == 1e-3);
        assert!(!r.visit(2) && !r.done(false) && !r.done(false) && !r.done(false));
        assert!(
            r.exact && r.done(false),
            "an exact round without change ends the step"
        );
    }

    #[test]
    fn loose_rounds_back_at_a_set_finish_exactly_and_an_exact_revisit_is_a_cycle() {
        let mut r = Rounds::new(Some(1e-3), 1e-9);
        assert!(!r.visit(7) && !r.done(true));
        assert!(!r.visit(8) && !r.done(true));
        assert!(
            !r.visit(7),
            "back at set 7 after a change: exact from here, no cycle yet"
        );
        assert!(r.exact);
        assert!(!r.done(true) && r.exact, "no loose rounds any more");
        assert!(r.visit(7), "an exact round at set 7 again is a cycle");
        let mut exact_only = Rounds::new(None, 1e-9);
        assert!(exact_only.exact);
        let mut too_tight = Rounds::new(Some(1e-10), 1e-9);
        assert!(too_tight.exact && !too_tight.visit(1) && too_tight.done(false));
        assert!(!exact_only.visit(3) && exact_only.visit(3));
    }
}
