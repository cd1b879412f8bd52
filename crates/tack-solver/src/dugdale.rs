//! The Dugdale cohesive-zone law (Maugis 1992): a constant tension σ0 wherever the gap lies in
//! `0 < g < h0`, with `γ = σ0·h0`; solved by the adhesive solver's active-set loop on three sets.
//!
//! At approach `d` every element is in one of three sets: **contact** `C` (`g = 0`, `p ≥ −σ0`),
//! the **cohesive zone** `Z` (`p = −σ0`, `0 < g < h0`) or **free** `F` (`p = 0`, `g ≥ h0`).
//! A round solves `K_CC p_C = (d − f − K p_Z)_C` with `p_Z = −σ0` (the bonded-set CG with the
//! zone's pressure held, so `K p` of both comes from the products CG makes anyway), brings the gap up
//! to date everywhere and applies every transition the one solution calls for, together:
//! `C → Z` where `p < −σ0`, `Z → C` where `g < 0`, `Z → F` where `g > h0`, `F → C` where
//! `g < 0`, `F → Z` where `g < h0`. It repeats until no set changes; a revisited pair of sets
//! stops the step as not converged, as does the round cap. The `C ↔ Z` tests carry a margin of
//! the CG tolerance (for an element at the contact edge `p < −σ0` in `C` is equivalent to
//! `g > 0` in `Z`, so without one round-off could flip it forever); the `Z ↔ F` test has none
//! (near `g = h0` both states can be admissible: the law's own bistability, settled by the
//! previous step's state).
//!
//! As under the criterion, rounds start inexact (`AdhesiveOptions::round_tolerance`, here
//! divided by [`DUGDALE_ROUND_FACTOR`]): such a round solves loosely, on a sub-grid brings the
//! gap up to date only there, and makes only the transitions its error cannot reverse: tension
//! beyond `σ0 (1 + m)`, gaps below `−ε` or beyond `h0 ± ε` with `ε` ten times its error. When
//! one finds nothing, the tolerance tightens until the exact round, which judges the whole
//! grid without those margins; so every step ends on an exact solve and an exact test.

use crate::rounds::{Rounds, Tally};
use ndarray::{Array2, Zip};
use tack_geometry::Window;

use crate::adhesive::{
    LOOSE_ATTACH_MARGIN, LOOSE_DETACH_MARGIN, LOOSE_REFERENCE_TOLERANCE, bounding_box,
    hash_masks_in, round_block,
};
use crate::{AdhesiveSolver, StepRecord};

/// The Dugdale law's inexact rounds start `round_tolerance / DUGDALE_ROUND_FACTOR` (`1e-5` by
/// default): each of their zone-edge tests (`g` against `h0`) needs a gap margin of ten times
/// the inexact solve's error, and at `1e-3` that margin holds back most of the zone edge's
/// moves until the exact round. Measured on `cargo xtask bench-dugdale` (smooth sphere,
/// Tabor μ = 3, 256²): starting at 1e-3, 1e-4, 1e-5 and 1e-6 took 6 258, 4 296, 2 907 and
/// 2 755 rounds and 9.6, 7.9, 7.1 and 7.7 s (exact rounds only: 1 871 rounds, 9.4 s), every
/// one with the same pull-off.
const DUGDALE_ROUND_FACTOR: f64 = 100.0;

impl AdhesiveSolver {
    /// One approach step under the Dugdale law (module docs); `d` is validated.
    pub(crate) fn step_dugdale(&mut self, d: f64) -> StepRecord {
        let periodic = self.base.periodic();
        let (sigma0, range) = {
            let c = self.cohesive.as_ref().expect("the Dugdale law");
            (c.sigma0, c.range)
        };
        let tolerance = self.options.cg.tolerance;
        let mut tally = Tally::new();
        let closed = self.base.closed(d);
        if closed {
            self.bonded.fill(true);
            self.zone_mut().fill(false);
        }
        // Inexact rounds until one finds nothing clear, then exact rounds (as under the
        // criterion): the tolerance starts at `round_tolerance / DUGDALE_ROUND_FACTOR`,
        // tightens 100× whenever an inexact round finds nothing and returns to its start when
        // a round changes a set.
        let start = self
            .options
            .round_tolerance
            .map(|t| t / DUGDALE_ROUND_FACTOR);
        let mut schedule = Rounds::new(start, tolerance);
        // `work.disp` and the gap are up to date only inside the last inexact round's window.
        let mut stale = false;
        // A window known to hold every loaded element (`None`: the whole grid).
        let mut extent: Option<Window> = None;
        loop {
            if tally.rounds == self.options.max_active_set_iterations {
                tally.converged = false;
                break;
            }
            tally.rounds += 1;
            if periodic && self.bonded.iter().all(|&b| b) {
                // Full contact: as under the criterion, with σ0 the greatest tension; the
                // released element joins the zone.
                let map = self.patterned.then_some(self.tension.view());
                match self.base.full_contact_or_weakest(closed, sigma0, map) {
                    None => {
                        tally.full = true;
                        break;
                    }
                    Some(weakest) => {
                        self.bonded[weakest] = false;
                        self.zone_mut()[weakest] = true;
                        continue;
                    }
                }
            }
            let (tight, fingerprint) = self.loaded_set(extent);
            let window = self.subgrid_around(tight);
            let cycle = schedule.visit(fingerprint);
            let (exact, level) = (schedule.exact, schedule.level);
            let (c, fresh) = if exact {
                self.solve_set(d, tolerance, true, window, extent.as_ref())
            } else {
                self.solve_set(d, level, false, window, extent.as_ref())
            };
            extent = fresh;
            tally.cg += c.iterations;
            if exact {
                tally.exact(&c);
            }
            stale = fresh.is_some();
            self.update_gap_after_round(d, fresh);
            if cycle {
                tally.converged = false;
                break;
            }
            // Exact rounds: the `C ↔ Z` tests carry the CG tolerance (module docs), `Z ↔ F`
            // none. Inexact rounds: every test carries the inexact solve's error, so each
            // transition they make is one the exact solve would make too; the gap is fresh only
            // in the round's sub-grid, so only elements there may change.
            let margins = if exact {
                (tolerance * sigma0, tolerance * c.scale.max(range), 0.0)
            } else {
                let relative = level / LOOSE_REFERENCE_TOLERANCE;
                let g = LOOSE_ATTACH_MARGIN * level * c.scale.max(range);
                (LOOSE_DETACH_MARGIN * relative * sigma0, g, g)
            };
            if schedule.done(self.judge_dugdale(fresh, margins, range)) {
                break;
            }
        }
        if stale {
            // The step ended on an inexact sub-grid round (the round cap): `K p` and the gap.
            self.refresh_after_inexact_round(d);
        }
        self.record(d, &tally)
    }

    /// The loaded set (contact or zone, into the law's `loaded` mask), its bounding box and
    /// fingerprint, searched only in `extent`: after an inexact sub-grid round every loaded
    /// element lies in its window.
    fn loaded_set(&mut self, extent: Option<Window>) -> (Option<Window>, u64) {
        let coh = self.cohesive.as_mut().expect("the Dugdale law");
        let block = round_block(extent);
        Zip::from(coh.loaded.slice_mut(block))
            .and(self.bonded.slice(block))
            .and(coh.zone.slice(block))
            .for_each(|l, &b, &z| *l = b || z);
        let (tight, _) = bounding_box(&coh.loaded, extent.as_ref());
        let fingerprint = hash_masks_in(&[&self.bonded, &coh.zone], tight.as_ref());
        (tight, fingerprint)
    }

    /// A Dugdale round's transitions (module docs) in the window `fresh` where the gap is up
    /// to date (`None`: the grid), with the `(p_margin, g_margin, r_margin)` of the round's
    /// tests and the law's `range`; returns whether any set changed.
    fn judge_dugdale(
        &mut self,
        fresh: Option<Window>,
        (p_margin, g_margin, r_margin): (f64, f64, f64),
        range: f64,
    ) -> bool {
        let block = round_block(fresh);
        let coh = self.cohesive.as_mut().expect("the Dugdale law");
        let tension = self
            .tension
            .broadcast(self.bonded.dim())
            .expect("a 1 × 1 array or the grid's shape");
        let zip = Zip::from(self.bonded.slice_mut(block))
            .and(coh.zone.slice_mut(block))
            .and(self.base.pressure.slice_mut(block))
            .and(self.base.gap.slice(block))
            .and(tension.slice(block));
        // Each element's tests read only that element: the split over threads cannot
        // change the outcome.
        let judge = |changed: bool, b: &mut bool, z: &mut bool, p: &mut f64, &g: &f64, &s: &f64| {
            if *b {
                if *p < -s - p_margin {
                    (*b, *z, *p) = (false, true, -s);
                    return true;
                }
            } else if *z {
                if g < -g_margin {
                    (*b, *z) = (true, false);
                    return true;
                } else if g > range + r_margin {
                    (*z, *p) = (false, 0.0);
                    return true;
                }
            } else if g < -g_margin {
                *b = true;
                return true;
            } else if g < range - r_margin {
                (*z, *p) = (true, -s);
                return true;
            }
            changed
        };
        if crate::cg::parallel(zip.size()) {
            zip.par_fold(|| false, judge, |a, b| a || b)
        } else {
            zip.fold(false, judge)
        }
    }

    fn zone_mut(&mut self) -> &mut Array2<bool> {
        &mut self.cohesive.as_mut().expect("the Dugdale law").zone
    }
}
