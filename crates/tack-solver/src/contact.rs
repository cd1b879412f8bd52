//! Non-adhesive frictionless contact at a prescribed approach (pressures ≥ 0, zero gap in
//! contact). [`ContactSolver`] runs the active-set engine of the adhesive solver with `σ_c = 0`
//! (preconditioned CG, inexact rounds, nested coarse-to-fine cold start) by default, or the
//! constrained conjugate gradients of Polonsky & Keer (1999) in their gap-controlled form, with
//! an optional coarse-to-fine start and, on free grids, iterations confined to where contact
//! can occur.

use ndarray::{Zip, s};
use tack_geometry::{Surface, Window};
use tack_kernels::ElasticOperator;

use crate::base::SolverBase;
use crate::state::Convergence;
use crate::subgrid::{SubgridCache, free_operator};
use crate::{AdhesiveOptions, AdhesiveSolver, ContactState, SolverError, SolverOptions, validate};

/// Solves `min ½ pᵀKp + pᵀ(f − d)` subject to `p ≥ 0` for a sequence of approaches, reusing
/// the operator, scratch and the previous pressure as a warm start.
///
/// Two methods give the same equilibrium (the problem is convex; `tests/nonadhesive.rs`):
/// [`ContactMethod::ActiveSet`] (default) and [`ContactMethod::PolonskyKeer`]. The active set is
/// the [`AdhesiveSolver`] with `γ = 0`: nothing of the adhesive criterion is left but the sign
/// rules (detach `p < 0`, attach `g < 0`), and the same engine serves adhesive scenes with
/// `γ = 0`. On a 512² periodic rough contact at 7% area it takes 54 CG iterations against
/// Polonsky–Keer's 145 (`cargo xtask bench`).
pub struct ContactSolver {
    engine: Engine,
}

/// How [`ContactSolver`] iterates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ContactMethod {
    /// Bonded-set CG with the spectral preconditioner, inexact detach/attach rounds and a nested
    /// coarse-to-fine cold start (docs/theory.md §3.4).
    #[default]
    ActiveSet,
    /// Polonsky & Keer's constrained CG (unpreconditioned; projection inside the iteration).
    PolonskyKeer,
}

enum Engine {
    ActiveSet(Box<AdhesiveSolver>),
    PolonskyKeer(Box<PolonskyKeer>),
}

impl ContactSolver {
    /// A solver for `surface` pressed against the half-space described by `op`, with the
    /// default method ([`ContactMethod::ActiveSet`]).
    pub fn new(
        op: Box<dyn ElasticOperator>,
        surface: &Surface,
        options: SolverOptions,
    ) -> Result<Self, SolverError> {
        Self::with_method(op, surface, options, ContactMethod::default())
    }

    /// A solver using `method`.
    pub fn with_method(
        op: Box<dyn ElasticOperator>,
        surface: &Surface,
        options: SolverOptions,
        method: ContactMethod,
    ) -> Result<Self, SolverError> {
        options.validate()?;
        let engine = match method {
            ContactMethod::ActiveSet => {
                let options = AdhesiveOptions {
                    cg: options,
                    ..AdhesiveOptions::default()
                };
                Engine::ActiveSet(Box::new(AdhesiveSolver::new(
                    op, surface, 0.0, 1.0, options,
                )?))
            }
            ContactMethod::PolonskyKeer => {
                Engine::PolonskyKeer(Box::new(PolonskyKeer::new(op, surface, options)?))
            }
        };
        Ok(Self { engine })
    }

    /// The method in use.
    pub fn method(&self) -> ContactMethod {
        match self.engine {
            Engine::ActiveSet(_) => ContactMethod::ActiveSet,
            Engine::PolonskyKeer(_) => ContactMethod::PolonskyKeer,
        }
    }

    /// Cold starts (no element in contact yet) begin from the solution on grids coarsened
    /// 2 × 2 (recursively, down to about 32 elements per side; grids with an odd side are not
    /// coarsened), prolonged by injection. The converged answer is the same problem's; only
    /// the iteration count changes. On by default for the active set; off by default for
    /// Polonsky–Keer, where the fine-grid iterations are dominated by settling the contact set
    /// (`cargo xtask bench-contact`: 276 → 234 iterations on a 1024² periodic H = 0.8 surface at
    /// 7% contact).
    pub fn set_coarse_start(&mut self, on: bool) {
        match &mut self.engine {
            Engine::ActiveSet(s) => s.set_nested_start(on),
            Engine::PolonskyKeer(s) => s.set_coarse_start(on),
        }
    }

    /// Free grids: iterate only where contact can occur. Exact (the same linear problem); on
    /// by default. Polonsky–Keer crops to the bounding box of the elements with `f ≤ d`; the
    /// active set runs its CG on a sub-grid around the contact set.
    pub fn set_crop(&mut self, on: bool) {
        match &mut self.engine {
            Engine::ActiveSet(s) => s.set_bonded_subgrid(on),
            Engine::PolonskyKeer(s) => s.set_crop(on),
        }
    }

    /// Equilibrium at approach `d` (finite), warm-started from the previous solve.
    pub fn solve(&mut self, approach: f64) -> Result<ContactState, SolverError> {
        match &mut self.engine {
            Engine::PolonskyKeer(s) => s.solve(approach),
            Engine::ActiveSet(s) => {
                let r = s.step(approach)?;
                Ok(ContactState {
                    approach: r.approach,
                    pressure: s.pressure().clone(),
                    gap: s.gap().clone(),
                    force: r.force,
                    mean_pressure: r.mean_pressure,
                    n_contact: r.n_bonded,
                    area: r.area,
                    iterations: r.cg_iterations,
                    residual: r.residual,
                    converged: r.converged,
                    full_contact: r.full_contact,
                })
            }
        }
    }
}

/// The Polonsky–Keer constrained CG: solves `min ½ pᵀKp + pᵀ(f − d)` subject to `p ≥ 0` for a
/// sequence of approaches, reusing the operator, scratch and the previous pressure as a warm
/// start.
pub(crate) struct PolonskyKeer {
    base: SolverBase,
    options: SolverOptions,
    coarse_start: bool,
    crop: bool,
    /// The cropped sub-problem of the last solve with the window it was built for; the windows
    /// `{f ≤ d}` of one surface are nested, so a window of the same shape is the same window.
    subs: SubgridCache<(Window, PolonskyKeer)>,
}

/// Iterations between recomputations of `K p` from scratch (bounds round-off in the update).
const REFRESH: usize = 50;

impl PolonskyKeer {
    /// A solver for `surface` pressed against the half-space described by `op`.
    pub(crate) fn new(
        op: Box<dyn ElasticOperator>,
        surface: &Surface,
        options: SolverOptions,
    ) -> Result<Self, SolverError> {
        options.validate()?;
        // Windows and coarse starts build half-space operators of their own.
        let half_space = op.is_half_space();
        Ok(Self {
            base: SolverBase::new(op, surface)?,
            options,
            coarse_start: false,
            crop: half_space,
            subs: SubgridCache::new(1),
        })
    }

    /// Cold starts (no element in contact yet) begin from the solution on a grid coarsened
    /// 2 × 2 (recursively, down to about 32 elements per side; grids with an odd side are not
    /// coarsened), prolonged by injection. The converged answer is the same problem's; only
    /// the iteration count changes. Off by default: the fine-grid iterations are dominated by
    /// settling the contact set, so the saving is small (`cargo xtask bench-contact`: 276 → 234
    /// iterations on a 1024² periodic H = 0.8 surface at 7% contact).
    pub(crate) fn set_coarse_start(&mut self, on: bool) {
        self.coarse_start = on && self.base.op.is_half_space();
    }

    /// Free grids: iterate only on the bounding box of the elements with `f ≤ d` (no other
    /// element can touch: compressive pressures only push the surface away), then compute the
    /// full-grid gap with one product. Exact (the same linear problem). On by default.
    pub(crate) fn set_crop(&mut self, on: bool) {
        self.crop = on && self.base.op.is_half_space();
    }

    /// Equilibrium at approach `d` (finite), warm-started from the previous solve.
    pub(crate) fn solve(&mut self, approach: f64) -> Result<ContactState, SolverError> {
        let d = validate::approach(approach)?;
        if d <= self.base.fmin {
            // Nothing touches: p = 0 is the exact solution.
            self.base.pressure.fill(0.0);
            Zip::from(&mut self.base.gap)
                .and(self.base.surface.heights())
                .for_each(|g, &f| *g = f - d);
            return Ok(self.state(d, Convergence::EXACT, false));
        }
        if self.base.periodic() && d >= self.base.fmean {
            return Ok(self.full_contact(d));
        }
        let scale = d - self.base.fmin;
        if let Some(w) = self.crop_window(d) {
            return self.solve_cropped(d, &w);
        }
        if self.coarse_start && !self.base.pressure.iter().any(|&p| p > 0.0) {
            self.start_from_coarse(d)?;
        }
        let report = self.iterate(d, scale);
        Ok(self.state(d, report, false))
    }

    /// The bounding box of `{f ≤ d}` when cropping pays (free grid, box under half the grid).
    fn crop_window(&self, d: f64) -> Option<Window> {
        if !self.crop || self.base.periodic() {
            return None;
        }
        let w = self.base.surface.window_below(d, 0)?;
        let (nx, ny) = self.base.grid().shape();
        (2 * w.shape().0 * w.shape().1 < nx * ny).then_some(w)
    }

    /// Solves on the window `w` (warm-started from the current pressure there), then puts the
    /// pressure back and computes the full-grid gap.
    fn solve_cropped(&mut self, d: f64, w: &Window) -> Result<ContactState, SolverError> {
        let block = s![w.i0..w.i1, w.j0..w.j1];
        let window_surface = || {
            self.base
                .surface
                .window(w)
                .expect("a window of the surface's own grid")
        };
        let (dx, e_star, options) = (self.base.grid().dx(), self.base.op.e_star(), self.options);
        let (win, sub) = self.subs.get_or_insert_with(w.shape(), || {
            let op = Box::new(free_operator(w.shape(), dx, e_star));
            let mut sub = PolonskyKeer::new(op, &window_surface(), options)
                .expect("validated options on the window's own grid");
            sub.crop = false;
            (*w, sub)
        });
        if win != w {
            sub.base.set_surface(window_surface());
            *win = *w;
        }
        sub.coarse_start = self.coarse_start;
        sub.base.pressure.assign(&self.base.pressure.slice(block));
        let st = sub.solve(d)?;
        self.base.pressure.fill(0.0);
        self.base
            .pressure
            .slice_mut(block)
            .assign(&sub.base.pressure);
        self.base
            .op
            .apply(self.base.pressure.view(), self.base.work.disp.view_mut());
        self.base.update_gap(d);
        let report = Convergence {
            iterations: st.iterations,
            residual: st.residual,
            converged: st.converged,
            scale: d - self.base.fmin,
        };
        Ok(self.state(d, report, false))
    }

    /// Fills `pressure` with the prolonged solution of the 2 × 2-coarsened problem, if the grid
    /// can be coarsened.
    fn start_from_coarse(&mut self, d: f64) -> Result<(), SolverError> {
        let Some((surface, op)) = self.base.coarsened() else {
            return Ok(());
        };
        // The coarse answer only seeds the fine iterations: a looser tolerance suffices.
        let options = SolverOptions {
            tolerance: self.options.tolerance.max(1e-6),
            ..self.options
        };
        let mut coarse = PolonskyKeer::new(op, &surface, options)?;
        coarse.crop = false;
        let st = coarse.solve(d)?;
        if st.full_contact {
            return Ok(());
        }
        let p = &coarse.base.pressure;
        Zip::indexed(&mut self.base.pressure).for_each(|(i, j), q| *q = p[[i / 2, j / 2]]);
        Ok(())
    }

    /// The constrained CG iterations.
    fn iterate(&mut self, d: f64, scale: f64) -> Convergence {
        let b = &mut self.base;
        let n = b.heights().len() as f64;
        let w0 = b.op.self_compliance();
        let (tolerance, max_iterations) = (self.options.tolerance, self.options.max_iterations);
        if !b.pressure.iter().any(|&p| p > 0.0) {
            // Cold start: each penetrating element carries what would close its own gap.
            Zip::from(&mut b.pressure)
                .and(b.surface.heights())
                .for_each(|p, &f| *p = (d - f).max(0.0) / w0);
        }
        let (mut delta, mut g_old) = (0.0, 1.0);
        b.work.dir.fill(0.0);
        let mut residual = f64::INFINITY;
        // `disp = K p` is recomputed only after a projection (an element clipped to p = 0 or a
        // penetrating one added); otherwise p moved along t and `disp −= τ K t` is exact.
        let mut fresh = false;
        for it in 0..=max_iterations {
            if !fresh || it % REFRESH == 0 {
                b.op.apply(b.pressure.view(), b.work.disp.view_mut());
            }
            b.update_gap(d);
            let (mut g_sum, mut res2) = (0.0, 0.0);
            Zip::from(&b.pressure).and(&b.gap).for_each(|&p, &g| {
                if p > 0.0 {
                    g_sum += g * g;
                    res2 += g * g;
                } else if g < 0.0 {
                    res2 += g * g;
                }
            });
            residual = (res2 / n).sqrt() / scale;
            if residual <= tolerance {
                return Convergence {
                    iterations: it,
                    residual,
                    converged: true,
                    scale,
                };
            }
            if it == max_iterations {
                break;
            }
            if g_sum == 0.0 {
                // Contact set emptied by projection: restart from the cold guess.
                Zip::from(&mut b.pressure)
                    .and(b.surface.heights())
                    .for_each(|p, &f| *p = (d - f).max(0.0) / w0);
                (delta, fresh) = (0.0, false);
                continue;
            }
            let ratio = delta * g_sum / g_old;
            Zip::from(&mut b.work.dir)
                .and(&b.pressure)
                .and(&b.gap)
                .for_each(|t, &p, &g| *t = if p > 0.0 { g + ratio * *t } else { 0.0 });
            g_old = g_sum;
            b.op.apply(b.work.dir.view(), b.work.kdir.view_mut());
            let (mut num, mut den) = (0.0, 0.0);
            Zip::from(&b.pressure)
                .and(&b.gap)
                .and(&b.work.dir)
                .and(&b.work.kdir)
                .for_each(|&p, &g, &t, &r| {
                    if p > 0.0 {
                        num += g * t;
                        den += r * t;
                    }
                });
            let tau = num / den;
            let (mut overlap, mut clipped) = (false, false);
            Zip::from(&mut b.pressure)
                .and(&b.gap)
                .and(&b.work.dir)
                .for_each(|p, &g, &t| {
                    if *p > 0.0 {
                        let q = *p - tau * t;
                        clipped |= q < 0.0;
                        *p = q.max(0.0);
                    } else if g < 0.0 {
                        // Penetrating element outside the contact set joins it (PK step 7).
                        *p = -tau * g;
                        overlap = true;
                    }
                });
            delta = if overlap { 0.0 } else { 1.0 };
            fresh = !overlap && !clipped;
            if fresh {
                Zip::from(&mut b.work.disp)
                    .and(&b.work.kdir)
                    .for_each(|u, &k| *u -= tau * k);
            }
        }
        Convergence {
            iterations: max_iterations,
            residual,
            converged: false,
            scale,
        }
    }

    /// Periodic full contact (`d ≥ mean f`): the zero-mean pressure that closes every gap, shifted
    /// by the least mean pressure that keeps every element compressive.
    fn full_contact(&mut self, d: f64) -> ContactState {
        let shift = -self.base.full_contact_field();
        self.base.pressure.mapv_inplace(|p| p + shift.max(0.0));
        self.base.gap.fill(0.0);
        self.state(d, Convergence::EXACT, true)
    }

    fn state(&self, approach: f64, report: Convergence, full: bool) -> ContactState {
        let n_contact = if full {
            self.base.grid().len()
        } else {
            self.base.pressure.iter().filter(|&&p| p > 0.0).count()
        };
        let totals = self.base.totals(n_contact);
        ContactState {
            approach,
            pressure: self.base.pressure.clone(),
            gap: self.base.gap.clone(),
            force: totals.force,
            mean_pressure: totals.mean_pressure,
            n_contact: totals.n_contact,
            area: totals.area,
            iterations: report.iterations,
            residual: report.residual,
            converged: report.converged,
            full_contact: full,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;
    use tack_geometry::{Boundary, FlatPunch, Grid, Sphere, Waviness2d};
    use tack_kernels::operator_for;

    /// The Polonsky–Keer engine (its iteration and cropping details are tested here; the
    /// methods' agreement in `tests/nonadhesive.rs`).
    fn solver(surface: &Surface, options: SolverOptions) -> PolonskyKeer {
        let op = operator_for(*surface.grid(), 1.0).unwrap();
        PolonskyKeer::new(op, surface, options).unwrap()
    }

    /// Hertz with a = √(Rd) = 10 Δx on a free 41² grid (E* = R = 1, d = 0.01).
    fn hertz_surface() -> Surface {
        let grid = Grid::square(41, 0.01, Boundary::Free).unwrap();
        Surface::from_shape(grid, &Sphere::new(1.0).unwrap())
    }

    #[test]
    fn flat_punch_force_matches_boussinesq_at_first_order() {
        // F = 2E*·a·d for a rigid circular punch, with a the radius of the disc of the discrete
        // face's area. Uniform element pressures cannot follow the 1/√(a − r) edge singularity:
        // an error of order Δx/a (measured −0.93% at a/Δx = 10, −0.52% at 20). The bound is
        // 15%·Δx/a: 1.5% and 0.75%.
        let mut errors = Vec::new();
        for (n, a_elements) in [(41, 10.0), (81, 20.0)] {
            let dx = 0.01;
            let grid = Grid::square(n, dx, Boundary::Free).unwrap();
            let surface = Surface::from_shape(grid, &FlatPunch::circular(a_elements * dx).unwrap());
            let d = 1e-3;
            let st = solver(&surface, SolverOptions::default()).solve(d).unwrap();
            assert!(st.converged);
            let face = surface.heights().iter().filter(|&&f| f == 0.0).count();
            assert_eq!(st.n_contact, face);
            assert!(st.pressure.iter().all(|&p| p >= 0.0));
            let a = (face as f64 / PI).sqrt() * dx;
            let error = st.force / (2.0 * a * d) - 1.0;
            assert!(
                error.abs() < 0.15 / a_elements,
                "a/Δx = {a_elements}: {error}"
            );
            errors.push(error);
        }
        // First order: doubling the resolution about halves the error.
        assert!(errors[1].abs() < 0.7 * errors[0].abs(), "{errors:?}");
    }

    #[test]
    fn hertz_force_with_nonnegative_gap_and_pressure() {
        let surface = hertz_surface();
        let d = 0.01;
        let options = SolverOptions::default();
        let st = solver(&surface, options).solve(d).unwrap();
        assert!(st.converged && st.residual <= options.tolerance);
        // F = (4/3)E*√R d^{3/2}; at a/Δx = 10 the staircase contact edge costs 3.4·10⁻⁴
        // (tests/nonadhesive.rs follows it under refinement); the bound leaves a 3× margin.
        let hertz = 4.0 / 3.0 * d.powf(1.5);
        assert!(
            (st.force / hertz - 1.0).abs() < 1e-3,
            "{}",
            st.force / hertz
        );
        let a = (st.area / PI).sqrt();
        assert!((a - d.sqrt()).abs() < 0.01, "contact radius {a}");
        // p ≥ 0 exactly (projection); the gap is ≥ 0 up to the stopping rule: its rms over the
        // grid is ≤ tolerance·(d − min f), so no single gap is below −√N times that.
        assert!(st.pressure.iter().all(|&p| p >= 0.0));
        let bound = (surface.heights().len() as f64).sqrt() * options.tolerance * d;
        let g_min = st.gap.iter().fold(f64::INFINITY, |m, &g| m.min(g));
        assert!(g_min >= -bound, "gap {g_min} below {bound}");
        // Complementarity: in contact the gap is closed, out of contact the pressure is zero.
        for (&p, &g) in st.pressure.iter().zip(&st.gap) {
            assert!(p == 0.0 || g.abs() <= bound, "p = {p} with gap {g}");
        }
        assert!(
            st.gap.iter().any(|&g| g > 0.0 && g < 1e-4),
            "no element just off the edge"
        );
    }

    #[test]
    fn one_iteration_is_reported_as_not_converged() {
        let options = SolverOptions {
            max_iterations: 1,
            ..SolverOptions::default()
        };
        let mut s = solver(&hertz_surface(), options);
        let st = s.solve(0.01).unwrap();
        assert!(!st.converged);
        assert_eq!(st.iterations, 1);
        assert!(st.residual > options.tolerance && st.residual.is_finite());
        assert!(st.pressure.iter().all(|&p| p >= 0.0));
        // Each further solve goes on from there and still reports the cap.
        let again = s.solve(0.01).unwrap();
        assert!(!again.converged && again.residual < st.residual);
    }

    #[test]
    fn cropped_solves_match_the_full_grid() {
        let surface = hertz_surface();
        let mut cropped = solver(&surface, SolverOptions::default());
        let mut full = solver(&surface, SolverOptions::default());
        full.set_crop(false);
        // 0.004 twice: the second solve reuses the cached window and starts converged.
        for (k, d) in [0.004, 0.009, 0.004, 0.004].into_iter().enumerate() {
            let (a, b) = (cropped.solve(d).unwrap(), full.solve(d).unwrap());
            assert!(a.converged && b.converged);
            assert_eq!(a.n_contact, b.n_contact);
            assert!((a.force / b.force - 1.0).abs() < 1e-9, "d = {d}");
            // Each gap is within √N·tolerance·d of the exact one (see the Hertz test).
            let dg = (&a.gap - &b.gap).iter().fold(0.0f64, |m, g| m.max(g.abs()));
            assert!(dg < 2.0 * 41.0 * 1e-10 * d, "gap differs by {dg}");
            if k == 3 {
                assert_eq!(a.iterations, 0);
            }
        }
        assert_eq!(cropped.subs.len(), 1);
    }

    #[test]
    fn periodic_full_contact_is_the_closed_form() {
        // The periodic operator is the continuum's spectral stiffness, exact for the single
        // Fourier mode of the sampled waviness: full contact needs p*₂D = √2πE*h/λ (Eq. 5), to
        // round-off, and the least admissible field has min p = 0 exactly.
        let grid = Grid::square(32, 1.0 / 32.0, Boundary::Periodic).unwrap();
        let h = 0.01;
        let surface = Surface::from_shape(grid, &Waviness2d::new(h, 1.0).unwrap());
        let mean = surface.heights().mean().unwrap();
        let mut s = solver(&surface, SolverOptions::default());
        for d in [mean, mean + 0.003] {
            let st = s.solve(d).unwrap();
            assert!(st.full_contact && st.converged);
            assert_eq!(st.n_contact, 32 * 32);
            assert!(st.gap.iter().all(|&g| g == 0.0));
            assert_eq!(
                st.pressure.iter().fold(f64::INFINITY, |m, &p| m.min(p)),
                0.0
            );
            let p_star = 2f64.sqrt() * PI * h;
            assert!((st.mean_pressure / p_star - 1.0).abs() < 1e-12);
        }
        let partial = s.solve(mean - 0.002).unwrap();
        assert!(!partial.full_contact && partial.converged);
        assert!(partial.n_contact < 32 * 32 && partial.mean_pressure < 2f64.sqrt() * PI * h);
    }

    #[test]
    fn inputs_are_checked() {
        let surface = hertz_surface();
        let other = Grid::square(40, 0.01, Boundary::Free).unwrap();
        let op = operator_for(other, 1.0).unwrap();
        let e = ContactSolver::new(op, &surface, SolverOptions::default()).err();
        assert_eq!(
            e,
            Some(SolverError::GridMismatch {
                surface: (41, 41),
                operator: (40, 40)
            })
        );
        let e = solver(&surface, SolverOptions::default())
            .solve(f64::INFINITY)
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "approach = inf is invalid: must be a finite number"
        );
    }
}
