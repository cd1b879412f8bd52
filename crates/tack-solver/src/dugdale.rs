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
//! previous step's state). Every round is solved to the CG tolerance.

use ndarray::{Array2, ArrayView2, ArrayViewMut2, Zip};
use std::collections::HashSet;
use tack_kernels::ElasticOperator;

use crate::adhesive::{SubProblem, hash_masks};
use crate::cg::{PcgWork, Work, pcg_holding};
use crate::state::Convergence;
use crate::{AdhesiveSolver, SolverOptions, StepRecord};

impl AdhesiveSolver {
    /// One approach step under the Dugdale law (module docs); `d` is validated.
    pub(crate) fn step_dugdale(&mut self, d: f64) -> StepRecord {
        let periodic = self.base.periodic();
        let n = self.base.heights().len();
        let (sigma0, range) = {
            let c = self.cohesive.as_ref().expect("the Dugdale law");
            (c.sigma0, c.range)
        };
        let tolerance = self.options.cg.tolerance;
        let (mut cg_total, mut worst, mut converged, mut full) = (0, 0.0f64, true, false);
        let mut visited = HashSet::new();
        let mut rounds = 0;
        let closed = self.base.closed(d);
        if closed {
            self.bonded.fill(true);
            self.zone_mut().fill(false);
        }
        loop {
            if rounds == self.options.max_active_set_iterations {
                converged = false;
                break;
            }
            rounds += 1;
            let n_bonded = self.bonded.iter().filter(|&&b| b).count();
            if periodic && n_bonded == n {
                // Full contact: as under the criterion, with σ0 the greatest tension; the
                // released element joins the zone.
                let map = self.patterned.then_some(self.tension.view());
                match self.base.full_contact_or_weakest(closed, sigma0, map) {
                    None => {
                        full = true;
                        break;
                    }
                    Some(weakest) => {
                        self.bonded[weakest] = false;
                        self.zone_mut()[weakest] = true;
                        continue;
                    }
                }
            }
            let zone = &self.cohesive.as_ref().expect("the Dugdale law").zone;
            let cycle = !visited.insert(hash_masks(&[&self.bonded, zone]));
            let c = self.solve_cohesive(d);
            cg_total += c.iterations;
            worst = worst.max(c.residual);
            converged &= c.converged;
            self.base.update_gap(d);
            if cycle {
                converged = false;
                break;
            }
            let p_margin = tolerance * sigma0;
            let g_margin = tolerance * c.scale.max(range);
            let mut changed = false;
            let coh = self.cohesive.as_mut().expect("the Dugdale law");
            let tension = self
                .tension
                .broadcast(self.bonded.dim())
                .expect("a 1 × 1 array or the grid's shape");
            Zip::from(&mut self.bonded)
                .and(&mut coh.zone)
                .and(&mut self.base.pressure)
                .and(&self.base.gap)
                .and(&tension)
                .for_each(|b, z, p, &g, &s| {
                    if *b {
                        if *p < -s - p_margin {
                            (*b, *z, *p) = (false, true, -s);
                            changed = true;
                        }
                    } else if *z {
                        if g < -g_margin {
                            (*b, *z) = (true, false);
                            changed = true;
                        } else if g > range {
                            (*z, *p) = (false, 0.0);
                            changed = true;
                        }
                    } else if g < -g_margin {
                        *b = true;
                        changed = true;
                    } else if g < range {
                        (*z, *p) = (true, -s);
                        changed = true;
                    }
                });
            if !changed {
                break;
            }
        }
        self.record(d, cg_total, rounds, worst, converged, full)
    }

    fn zone_mut(&mut self) -> &mut Array2<bool> {
        &mut self.cohesive.as_mut().expect("the Dugdale law").zone
    }

    /// Solves the contact set with the zone's tension held: `pressure` holds `p_C` on the
    /// contact, `−σ0` on the zone and 0 elsewhere, `work.disp = K p` on the whole grid. On free
    /// grids whose loaded elements fill little of the grid, the solve runs on a sub-grid around
    /// them (exact, as for the criterion) and one full-grid product follows.
    fn solve_cohesive(&mut self, d: f64) -> Convergence {
        let cg = self.options.cg;
        let pre = self.options.preconditioned;
        let window = {
            let coh = self.cohesive.as_mut().expect("the Dugdale law");
            Zip::from(&mut coh.loaded)
                .and(&self.bonded)
                .and(&coh.zone)
                .for_each(|l, &b, &z| *l = b || z);
            let coh = self.cohesive.as_ref().expect("the Dugdale law");
            self.subgrid_of(&coh.loaded)
        };
        let coh = self.cohesive.as_ref().expect("the Dugdale law");
        let base = &mut self.base;
        let tension = self
            .tension
            .broadcast(self.bonded.dim())
            .expect("a 1 × 1 array or the grid's shape");
        let Some(window) = window else {
            return solve_with_zone(
                base.op.as_mut(),
                base.surface.heights().view(),
                self.bonded.view(),
                coh.zone.view(),
                tension,
                d,
                base.pressure.view_mut(),
                &mut base.work,
                &mut self.pcg,
                &cg,
                pre,
            );
        };
        let shape = window.shape();
        let (dx, e_star) = (base.grid().dx(), base.op.e_star());
        let sub = self
            .boxes
            .get_or_insert_with(shape, || SubProblem::new(shape, dx, e_star));
        let block = ndarray::s![window.i0..window.i1, window.j0..window.j1];
        let zone = sub
            .zone
            .get_or_insert_with(|| Array2::from_elem(shape, false));
        zone.assign(&coh.zone.slice(block));
        sub.pressure.assign(&base.pressure.slice(block));
        sub.heights.assign(&base.surface.heights().slice(block));
        sub.bonded.assign(&self.bonded.slice(block));
        let out = solve_with_zone(
            &mut sub.op,
            sub.heights.view(),
            sub.bonded.view(),
            zone.view(),
            tension.slice(block),
            d,
            sub.pressure.view_mut(),
            &mut sub.work,
            &mut sub.pcg,
            &cg,
            pre,
        );
        base.pressure.fill(0.0);
        base.pressure.slice_mut(block).assign(&sub.pressure);
        base.op
            .apply(base.pressure.view(), base.work.disp.view_mut());
        out
    }
}

/// `K_CC p_C = (d − f − K p_Z)_C` on one grid with `p_Z = −σ0` on `zone` (σ0 per element:
/// `tension`); leaves the whole pressure in `pressure` and `work.disp = K p`.
#[allow(clippy::too_many_arguments)]
fn solve_with_zone(
    op: &mut dyn ElasticOperator,
    heights: ArrayView2<f64>,
    bonded: ArrayView2<bool>,
    zone: ArrayView2<bool>,
    tension: ArrayView2<f64>,
    d: f64,
    mut pressure: ArrayViewMut2<f64>,
    work: &mut Work,
    pcg_work: &mut PcgWork,
    cg: &SolverOptions,
    preconditioned: bool,
) -> Convergence {
    Zip::from(&mut pressure)
        .and(&bonded)
        .and(&zone)
        .and(&tension)
        .for_each(|p, &b, &z, &s| {
            if z {
                *p = -s;
            } else if !b {
                *p = 0.0;
            }
        });
    if bonded.iter().any(|&b| b) {
        pcg_holding(
            op,
            heights,
            bonded,
            Some(zone),
            d,
            pressure.view_mut(),
            work,
            pcg_work,
            cg,
            preconditioned,
        )
    } else {
        op.apply(pressure.view(), work.disp.view_mut());
        Convergence::EXACT
    }
}
