//! The zero-range (JKR-limit) law's rules for the shared round loop: a bonded set with the
//! Pohrt–Popov mesh-dependent detachment criterion.
//!
//! Protocol at approach `d` (docs/theory.md §3.4): solve `K p = d − f` on the bonded set `C`
//! (`p = 0` off it); detach **every** bonded element whose tension exceeds `σ_c` (all at once,
//! as in the reference prototype); attach every free element that penetrates; repeat until `C`
//! no longer changes. Both decisions come from the same solution and are applied together, so
//! the result does not depend on iteration order. Cycles are detected by remembering every
//! bonded set visited in the step; a revisit stops the loop and the step reports
//! `converged = false`. The loop is also capped (`AdhesiveSolver::run_rounds`).

use ndarray::Zip;
use tack_geometry::Window;

use crate::relax::{Released, take_released};
use crate::rounds::{CASCADE_GENERATIONS, CASCADE_MARGIN};
use crate::rounds::{
    LOOSE_ATTACH_MARGIN, LOOSE_DETACH_MARGIN, LOOSE_REFERENCE_TOLERANCE, Loaded, Round, SetRules,
    Tally, hash_masks_in, round_block,
};
use crate::subgrid::bounding_box;
use crate::{AdhesiveOptions, AdhesiveSolver, SolverError};

/// The criterion's rules for one step: whether detached tension is relaxed before the next
/// solve ([`AdhesiveOptions::local_relaxation`]) and the elements the last round released.
pub(crate) struct Criterion {
    relaxing: bool,
    /// Whether inexact rounds predict further releases from the relaxed tension
    /// ([`AdhesiveOptions::cascade`]).
    cascading: bool,
    released: Vec<Released>,
}

impl Criterion {
    /// The rules for a step of `s`: relaxation only with inexact rounds (`round_tolerance =
    /// None` stays the exact loop, bit for bit), on free grids, with adhesion.
    pub(crate) fn new(s: &AdhesiveSolver) -> Self {
        let o = &s.options;
        let relaxing = o.local_relaxation
            && o.round_tolerance.is_some()
            && !s.base.periodic()
            && (s.sigma_c > 0.0 || s.patterned);
        Self {
            relaxing,
            cascading: relaxing && o.cascade,
            released: Vec::new(),
        }
    }
}

/// What a criterion round's solve leaves its tests: detach where
/// `p < −σ·(1 + detach) − detach_floor`, attach where `g < attach_below`; `predict`: an
/// inexact round with adhesion, whose detachments may set off predicted ones.
pub(crate) struct CriterionMargins {
    attach_below: f64,
    detach: f64,
    detach_floor: f64,
    predict: bool,
}

impl Criterion {
    /// Relaxes the tension of the elements in `released` (tiles anchored at `anchor`) and
    /// empties it; returns the windows solved.
    fn relax_released(&mut self, s: &mut AdhesiveSolver, anchor: (usize, usize)) -> Vec<Window> {
        let windows = s.relaxation.relax(
            &mut s.base.pressure,
            &s.bonded,
            anchor,
            &mut self.released,
            s.options.preconditioned,
        );
        self.released.clear();
        windows
    }

    /// Predicted releases ([`AdhesiveOptions::cascade`]): relaxes the tension of the elements
    /// the round released, releases every bonded element of the relaxed windows whose tension
    /// then exceeds its `σ (1 + CASCADE_MARGIN) + floor`, and goes on with those, for up to
    /// [`CASCADE_GENERATIONS`]. The last generation's elements stay in `released`, relaxed
    /// before the next solve as usual. Tiles are anchored at the set's box as it was after the
    /// round, and windows are scanned in tile order, so the bits depend neither on the crop
    /// nor on the thread count.
    fn cascade(&mut self, s: &mut AdhesiveSolver, fresh: Option<Window>, floor: f64) {
        if self.released.is_empty() {
            // The round only attached: nothing to relax, so no box to scan for.
            return;
        }
        let (tight, _) = bounding_box(&s.bonded, fresh.as_ref());
        let Some(t) = tight else { return };
        for _ in 0..CASCADE_GENERATIONS {
            if self.released.is_empty() {
                return;
            }
            let windows = self.relax_released(s, (t.i0, t.j0));
            let tension = s
                .tension
                .broadcast(s.bonded.dim())
                .expect("a 1 × 1 array or the grid's shape");
            for w in &windows {
                for i in w.i0..w.i1 {
                    for j in w.j0..w.j1 {
                        let p = &mut s.base.pressure[[i, j]];
                        if s.bonded[[i, j]]
                            && *p < -tension[[i, j]] * (1.0 + CASCADE_MARGIN) - floor
                        {
                            s.bonded[[i, j]] = false;
                            self.released.push(Released { i, j, pressure: *p });
                            *p = 0.0;
                        }
                    }
                }
            }
        }
    }
}

impl SetRules for Criterion {
    type Margins = CriterionMargins;

    fn start(&self, options: &AdhesiveOptions) -> Option<f64> {
        options.round_tolerance
    }

    /// Non-adhesive cold starts begin from the coarse grids' solution
    /// ([`AdhesiveOptions::nested_start`]).
    fn prepare(
        &mut self,
        s: &mut AdhesiveSolver,
        d: f64,
        closed: bool,
        tally: &mut Tally,
    ) -> Result<(), SolverError> {
        if !closed
            && s.sigma_c == 0.0
            && !s.patterned
            && s.options.nested_start
            && !s.bonded.iter().any(|&b| b)
        {
            tally.cg += s.start_from_coarse(d)?;
        }
        Ok(())
    }

    fn release(&mut self, _weakest: (usize, usize)) {}

    fn loaded(&mut self, s: &AdhesiveSolver, extent: Option<Window>) -> Loaded {
        let (tight, count) = bounding_box(&s.bonded, extent.as_ref());
        Loaded {
            tight,
            count,
            fingerprint: hash_masks_in(&[&s.bonded], tight.as_ref()),
        }
    }

    /// The tension the last round's detachments carried is relaxed over their neighbourhood.
    fn before_solve(&mut self, s: &mut AdhesiveSolver, tight: Option<Window>) {
        if let Some(t) = tight {
            self.relax_released(s, (t.i0, t.j0));
        }
        self.released.clear();
    }

    /// None on an empty set, else an inexact solve (returning the margins its decisions carry
    /// and the window where its gap is fresh) or an exact one (counted in the `tally`'s
    /// residual and convergence).
    fn solve(
        &mut self,
        s: &mut AdhesiveSolver,
        round: Round,
        tally: &mut Tally,
    ) -> (Option<Window>, CriterionMargins) {
        let sigma_c = s.sigma_c;
        let mut margins = CriterionMargins {
            attach_below: 0.0,
            detach: 0.0,
            detach_floor: 0.0,
            predict: false,
        };
        let (d, extent) = (round.d, round.extent.as_ref());
        tally.solved = true;
        if round.loaded == 0 {
            s.base.pressure.fill(0.0);
            s.base.work.disp.fill(0.0);
            return (None, margins);
        }
        if round.exact {
            let tolerance = s.options.cg.tolerance;
            let (c, _) = s.solve_set(
                d,
                tolerance,
                true,
                round.window,
                extent,
                None,
                round.carried,
            );
            tally.cg += c.iterations;
            tally.solved = c.converged;
            tally.exact(&c);
            return (None, margins);
        }
        // An inexact round: the gap is only brought up to date inside the sub-grid window, so
        // only elements there may attach; the exact round checks them all. Margins scale with
        // the round's tolerance; without adhesion the equilibrium is unique (a convex
        // problem), so no decision needs one.
        let level = round.level;
        let (c, fresh) = s.solve_set(d, level, false, round.window, extent, None, round.carried);
        tally.cg += c.iterations;
        tally.solved = c.converged;
        if sigma_c > 0.0 || s.patterned {
            let relative = level / LOOSE_REFERENCE_TOLERANCE;
            margins.attach_below = -LOOSE_ATTACH_MARGIN * level * c.scale;
            let margin = LOOSE_DETACH_MARGIN * relative;
            // Detach where `p < −σ·(1 + margin) − floor`: on a map a floor of the reference's
            // margin, so elements of little γ keep one too.
            let floor = if s.patterned { sigma_c * margin } else { 0.0 };
            (margins.detach, margins.detach_floor) = (margin, floor);
            margins.predict = true;
        }
        (fresh, margins)
    }

    /// Detach every bonded element under tension beyond σ_c (with the round's margins), attach
    /// every free element whose gap is below `attach_below`, in the window `fresh` where the
    /// gap is up to date. With relaxation the detached elements' pressure is kept for the next
    /// round's start.
    fn judge(
        &mut self,
        s: &mut AdhesiveSolver,
        fresh: Option<Window>,
        margins: &CriterionMargins,
    ) -> bool {
        // After an inexact sub-grid round only its window can change: every bonded element
        // lies inside it, and only elements there may attach.
        let block = round_block(fresh);
        let relaxing = self.relaxing;
        let (margin, floor, attach_below) =
            (margins.detach, margins.detach_floor, margins.attach_below);
        let tension = s
            .tension
            .broadcast(s.bonded.dim())
            .expect("a 1 × 1 array or the grid's shape");
        let zip = Zip::from(s.bonded.slice_mut(block))
            .and(s.base.pressure.slice_mut(block))
            .and(s.base.gap.slice(block))
            .and(tension.slice(block));
        // Each element's test reads only that element: the split over threads cannot
        // change the outcome. With relaxation a detached element keeps its pressure until
        // `take_released` below collects and clears it.
        let judge = |changed: bool, b: &mut bool, p: &mut f64, &g: &f64, &s: &f64| {
            if *b && *p < -s * (1.0 + margin) - floor {
                *b = false;
                if !relaxing {
                    *p = 0.0;
                }
                true
            } else if !*b && g < attach_below {
                *b = true;
                true
            } else {
                changed
            }
        };
        let changed = if crate::cg::parallel(zip.size()) {
            zip.par_fold(|| false, judge, |a, b| a || b)
        } else {
            zip.fold(false, judge)
        };
        if relaxing && changed {
            let origin = fresh.map_or((0, 0), |w| (w.i0, w.j0));
            self.released = take_released(
                s.base.pressure.slice_mut(block),
                s.bonded.slice(block),
                origin,
            );
            if self.cascading && margins.predict {
                // On a map elements of little γ keep a floor of the reference's margin.
                let floor = if s.patterned {
                    s.sigma_c * CASCADE_MARGIN
                } else {
                    0.0
                };
                self.cascade(s, fresh, floor);
            }
        }
        changed
    }
}
