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
//! The law's rules run in the round loop it shares with the criterion
//! (`AdhesiveSolver::run_rounds`). As under the criterion, rounds start inexact (`AdhesiveOptions::round_tolerance`, here
//! divided by [`DUGDALE_ROUND_FACTOR`]): such a round solves loosely, on a sub-grid brings the
//! gap up to date only there, and makes only the transitions its error cannot reverse: tension
//! beyond `σ0 (1 + m)`, gaps below `−ε` or beyond `h0 ± ε` with `ε` ten times its error. When
//! one finds nothing, the tolerance tightens until the exact round, which judges the whole
//! grid without those margins; so every step ends on an exact solve and an exact test.

use ndarray::Zip;
use tack_geometry::Window;

use crate::law::Cohesive;
use crate::rounds::{
    LOOSE_ATTACH_MARGIN, LOOSE_DETACH_MARGIN, LOOSE_REFERENCE_TOLERANCE, Loaded, Round, SetRules,
    Tally, hash_masks_in, round_block,
};
use crate::subgrid::bounding_box;
use crate::{AdhesiveOptions, AdhesiveSolver, SolverError};

/// The Dugdale law's inexact rounds start `round_tolerance / DUGDALE_ROUND_FACTOR` (`1e-5` by
/// default): each of their zone-edge tests (`g` against `h0`) needs a gap margin of ten times
/// the inexact solve's error, and at `1e-3` that margin holds back most of the zone edge's
/// moves until the exact round. Measured on `cargo xtask bench-dugdale` (smooth sphere,
/// Tabor μ = 3, 256²): starting at 1e-3, 1e-4, 1e-5 and 1e-6 took 6 258, 4 296, 2 907 and
/// 2 755 rounds and 9.6, 7.9, 7.1 and 7.7 s (exact rounds only: 1 871 rounds, 9.4 s), every
/// one with the same pull-off.
const DUGDALE_ROUND_FACTOR: f64 = 100.0;

/// The Dugdale law's rules for one step: the law's state (σ0, range, the cohesive zone), held
/// by the rules while the step runs.
pub(crate) struct Dugdale {
    pub(crate) state: Cohesive,
}

/// The margins of a Dugdale round's tests: tension (`C → Z`), gap below zero (`Z → C`,
/// `F → C`) and gap against the range (`Z ↔ F`).
pub(crate) struct DugdaleMargins {
    p: f64,
    g: f64,
    r: f64,
}

impl SetRules for Dugdale {
    type Margins = DugdaleMargins;

    fn start(&self, options: &AdhesiveOptions) -> Option<f64> {
        options.round_tolerance.map(|t| t / DUGDALE_ROUND_FACTOR)
    }

    /// A closed periodic grid starts in full contact: no zone.
    fn prepare(
        &mut self,
        _s: &mut AdhesiveSolver,
        _d: f64,
        closed: bool,
        _tally: &mut Tally,
    ) -> Result<(), SolverError> {
        if closed {
            self.state.zone.fill(false);
        }
        Ok(())
    }

    /// The element full contact released joins the zone.
    fn release(&mut self, weakest: (usize, usize)) {
        self.state.zone[weakest] = true;
    }

    /// The loaded set (contact or zone, into the law's `loaded` mask), its bounding box and
    /// fingerprint, searched only in `extent`: after an inexact sub-grid round every loaded
    /// element lies in its window.
    fn loaded(&mut self, s: &AdhesiveSolver, extent: Option<Window>) -> Loaded {
        let coh = &mut self.state;
        let block = round_block(extent);
        Zip::from(coh.loaded.slice_mut(block))
            .and(s.bonded.slice(block))
            .and(coh.zone.slice(block))
            .for_each(|l, &b, &z| *l = b || z);
        let (tight, count) = bounding_box(&coh.loaded, extent.as_ref());
        let fingerprint = hash_masks_in(&[&s.bonded, &coh.zone], tight.as_ref());
        Loaded {
            tight,
            count,
            fingerprint,
        }
    }

    /// The contact set's solve with the zone's tension held. Exact rounds: the `C ↔ Z` tests
    /// carry the CG tolerance (module docs), `Z ↔ F` none. Inexact rounds: every test carries
    /// the inexact solve's error, so each transition they make is one the exact solve would
    /// make too; the gap is fresh only in the round's sub-grid, so only elements there may
    /// change.
    fn solve(
        &mut self,
        s: &mut AdhesiveSolver,
        round: Round,
        tally: &mut Tally,
    ) -> (Option<Window>, DugdaleMargins) {
        let (sigma0, range) = (self.state.sigma0, self.state.range);
        let tolerance = s.options.cg.tolerance;
        let zone = Some(self.state.zone.view());
        let (d, extent) = (round.d, round.extent.as_ref());
        let (c, fresh) = if round.exact {
            s.solve_set(
                d,
                tolerance,
                true,
                round.window,
                extent,
                zone,
                round.carried,
            )
        } else {
            s.solve_set(
                d,
                round.level,
                false,
                round.window,
                extent,
                zone,
                round.carried,
            )
        };
        tally.cg += c.iterations;
        tally.solved = c.converged;
        if round.exact {
            tally.exact(&c);
        }
        let margins = if round.exact {
            DugdaleMargins {
                p: tolerance * sigma0,
                g: tolerance * c.scale.max(range),
                r: 0.0,
            }
        } else {
            let relative = round.level / LOOSE_REFERENCE_TOLERANCE;
            let g = LOOSE_ATTACH_MARGIN * round.level * c.scale.max(range);
            DugdaleMargins {
                p: LOOSE_DETACH_MARGIN * relative * sigma0,
                g,
                r: g,
            }
        };
        (fresh, margins)
    }

    /// A Dugdale round's transitions (module docs) in the window `fresh` where the gap is up
    /// to date (`None`: the grid).
    fn judge(
        &mut self,
        s: &mut AdhesiveSolver,
        fresh: Option<Window>,
        margins: &DugdaleMargins,
    ) -> bool {
        let block = round_block(fresh);
        let range = self.state.range;
        let (p_margin, g_margin, r_margin) = (margins.p, margins.g, margins.r);
        let tension = s
            .tension
            .broadcast(s.bonded.dim())
            .expect("a 1 × 1 array or the grid's shape");
        let zip = Zip::from(s.bonded.slice_mut(block))
            .and(self.state.zone.slice_mut(block))
            .and(s.base.pressure.slice_mut(block))
            .and(s.base.gap.slice(block))
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
}
