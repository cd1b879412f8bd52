//! The round loop's parts shared by the laws with sets (the zero-range criterion in
//! `criterion.rs`, the Dugdale law in `dugdale.rs`): the [`SetRules`] a law gives the loop, the
//! schedule of one step's rounds (inexact rounds until one finds nothing clear, tighter ones,
//! then exact rounds until one changes nothing; docs/theory.md §3.4, §3.7), the inexact rounds'
//! margins and the sets' fingerprints.

use std::collections::HashSet;
use std::hash::{DefaultHasher, Hash, Hasher};

use ndarray::Array2;
use tack_geometry::Window;

use crate::{AdhesiveOptions, AdhesiveSolver, SolverError};

/// The tolerance [`LOOSE_DETACH_MARGIN`] was measured at; margins scale with a round's
/// tolerance relative to it.
pub(crate) const LOOSE_REFERENCE_TOLERANCE: f64 = 1e-3;

/// Relative tension margin `m` of an inexact round: it detaches `p < −σ_c (1 + m)` only. With
/// `round_tolerance = 1e-3`, `m = 0.001` let a Kendall punch at a/Δx = 20 pull off 0.6% early
/// (a rim element within the inexact solve's error of σ_c started the cascade), and `0.003` let
/// a flat-tipped body z = r⁴ pull off 1.7% and 0.9% early at a_F/Δx = 10 and 20
/// (`tests/power_law.rs`), and the 512² rough sphere of `cargo xtask bench` 1.2·10⁻⁴ early;
/// `0.006` gives the exact algorithm's pull-off on all three (`tests/adhesion.rs`,
/// `tests/power_law.rs`, `crates/tack/tests/relaxation.rs`, docs/theory.md §3.4).
pub const LOOSE_DETACH_MARGIN: f64 = 0.006;

/// Relative tension margin of a predicted release ([`crate::AdhesiveOptions::cascade`]): after
/// an inexact round's detachments are relaxed on windows, a bonded element there is released
/// before the next solve only where its relaxed tension exceeds `σ_c (1 + CASCADE_MARGIN)`.
/// The windowed solves overestimate the tension near a release (only the window's elements
/// take it up): with no margin the 512² rough sphere of `cargo xtask bench` pulled off 0.7%
/// early, and 0.03 gives its pull-off to the last bit but moved the 1024² one by 1.1e-5;
/// 0.06 gives both to 1e-15 and moves the 2048² one by 1.3e-5. A bound measured on these
/// scenes, not an equality: on 90 of Figure 7's full points one pull-off moved by 2.7e-3, onto
/// the exact loop's (docs/theory.md §3.4).
pub const CASCADE_MARGIN: f64 = 0.06;

/// Generations of predicted releases per round ([`crate::AdhesiveOptions::cascade`]).
pub const CASCADE_GENERATIONS: usize = 8;

/// Gap margin of an inexact round, in units of its residual bound: it attaches only gaps below
/// `−LOOSE_ATTACH_MARGIN · round_tolerance · scale` (scale: the rms of `d − f` over the set).
pub const LOOSE_ATTACH_MARGIN: f64 = 10.0;

/// What a law with sets gives the shared round loop ([`AdhesiveSolver::run_rounds`]): its
/// rounds' starting tolerance, what it does before the rounds and when full periodic contact
/// releases an element, its loaded set, its solve and its transitions. The loop owns the
/// schedule, the cap, the cycle test, the sub-grid and the gap; a law owns its sets' state for
/// the step.
pub(crate) trait SetRules {
    /// What a round's solve leaves its tests (margins, the window where the gap is fresh).
    type Margins;
    /// The inexact rounds' starting tolerance (`None`: exact rounds only).
    fn start(&self, options: &AdhesiveOptions) -> Option<f64>;
    /// Before the first round at approach `d`; `closed` when every element was bonded (full
    /// periodic contact is possible).
    fn prepare(
        &mut self,
        s: &mut AdhesiveSolver,
        d: f64,
        closed: bool,
        tally: &mut Tally,
    ) -> Result<(), SolverError>;
    /// Full periodic contact released the `weakest` element (already taken off the bonded set).
    fn release(&mut self, weakest: (usize, usize));
    /// The loaded set, searched only in `extent` (`None`: the grid).
    fn loaded(&mut self, s: &AdhesiveSolver, extent: Option<Window>) -> Loaded;
    /// Before the round's solve, with the loaded set's box `tight`.
    fn before_solve(&mut self, _s: &mut AdhesiveSolver, _tight: Option<Window>) {}
    /// The round's solve; returns the window where the gap is fresh (`None`: everywhere, once
    /// the loop has updated it) and the margins of the round's tests.
    fn solve(
        &mut self,
        s: &mut AdhesiveSolver,
        round: Round,
        tally: &mut Tally,
    ) -> (Option<Window>, Self::Margins);
    /// The round's transitions in the window `fresh`; returns whether any set changed.
    fn judge(
        &mut self,
        s: &mut AdhesiveSolver,
        fresh: Option<Window>,
        margins: &Self::Margins,
    ) -> bool;
}

/// A law's loaded set for one round: its bounding box, how many elements and its fingerprint.
pub(crate) struct Loaded {
    pub(crate) tight: Option<Window>,
    pub(crate) count: usize,
    pub(crate) fingerprint: u64,
}

/// What one round solves: the approach, exact or at the inexact `level`, the loaded set's
/// size, the sub-grid `window` (`None`: the grid), a window `extent` holding every non-zero
/// pressure (`None`: anywhere) and whether the last round's CG is continued.
#[derive(Clone, Copy)]
pub(crate) struct Round {
    pub(crate) d: f64,
    pub(crate) exact: bool,
    pub(crate) level: f64,
    pub(crate) loaded: usize,
    pub(crate) window: Option<Window>,
    pub(crate) extent: Option<Window>,
    /// A round right after one that solved the same `window` and changed nothing: its solve
    /// left `K p` of the unchanged pressure and its iteration, which this one continues.
    pub(crate) carried: bool,
}

/// The block of a round's tests: the window `fresh` where its gap is up to date (an inexact
/// sub-grid round), or the whole grid.
pub(crate) fn round_block(
    fresh: Option<Window>,
) -> ndarray::SliceInfo<[ndarray::SliceInfoElem; 2], ndarray::Ix2, ndarray::Ix2> {
    match fresh {
        Some(w) => ndarray::s![w.i0..w.i1, w.j0..w.j1],
        None => ndarray::s![.., ..],
    }
}

/// Deterministic fingerprint of one or more masks of one grid (the criterion's bonded set, the
/// Dugdale law's contact and zone) whose `true` elements all lie in the box `tight` (the box of
/// their union, [`crate::subgrid::bounding_box`]): the box and each mask inside it, packed into
/// 64-bit words row by row, hashed.
pub(crate) fn hash_masks_in(masks: &[&Array2<bool>], tight: Option<&Window>) -> u64 {
    let mut h = DefaultHasher::new();
    if let Some(w) = tight {
        (w.i0, w.i1, w.j0, w.j1).hash(&mut h);
        for mask in masks {
            for i in w.i0..w.i1 {
                let row = &mask.row(i).to_slice().expect("standard layout")[w.j0..w.j1];
                pack_into(row, &mut h);
            }
        }
    }
    h.finish()
}

/// Hashes `bits` packed into 64-bit words.
fn pack_into(bits: &[bool], h: &mut DefaultHasher) {
    for chunk in bits.chunks(64) {
        let word = chunk
            .iter()
            .enumerate()
            .fold(0u64, |w, (k, &b)| w | (u64::from(b) << k));
        word.hash(h);
    }
}

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
    /// Whether the last round's solve met its tolerance (a capped one is not continued).
    pub(crate) solved: bool,
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
            solved: true,
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
