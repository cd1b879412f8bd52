//! A smooth step on the window of the law's reach, the pressure outside it held.
//!
//! A smooth law loads every element, but on a free half-space grid its pressure falls below
//! any tolerance a few ranges away from the contact (the exponential law's `e^(−g/ρ)`); the
//! crop (`crate::contact_window`) keeps what the deepest approach can reach, and a retraction
//! spends most of its steps far shallower. Each step therefore picks the box of the contact
//! and of every element whose pressure, or whose law's pressure a little closer in, exceeds
//! [`HELD_FRACTION`] of Newton's tolerance; when that box's transform is cheaper than the
//! grid's ([`AdhesiveSolver::subgrid_around`]), the step solves it as a grid of its own:
//! the pressure outside is held, and its displacement enters the window's heights as the last
//! step's `K p` on the grid less one product on the window. One product on the grid then
//! measures every element's residual,
//! and a step that misses Newton's tolerance outside the window (an approach that closes gaps
//! faster than the margin) is finished on the grid, as is a step whose window solve met a cap.
//! So the answer meets the same tolerance on every element; only its round-off differs from a
//! step solved on the grid.

use ndarray::{Array2, Zip, s};
use tack_geometry::{Grid, Surface, Window};

use super::SmoothState;
use crate::AdhesiveSolver;
use crate::base::SolverBase;
use crate::cg::PcgWork;
use crate::rounds::Tally;

/// An element is held outside a step's window when its pressure and its law's pressure at its
/// gap closed by twice the step's approach stay below this fraction of Newton's tolerance (and
/// that gap lies past the law's greatest tension): held, its residual `|p − P(g)|` stays below
/// twice this fraction of the tolerance while its gap opens.
const HELD_FRACTION: f64 = 0.1;

/// A step runs on its window only when the window's transform costs at most this fraction of
/// the grid's: the window adds a product on the grid to the step (the final check; the held
/// pressure's displacement was a second one before 2026-11-29's tiles, when these
/// measurements were taken) and saves only on the step's own products on the grid
/// (its refreshes, Newton's trial states and the product outside Newton's window; the landings,
/// but a step's last, and Newton's solves already run on windows of their own). Measured on bench-laws' peers' case,
/// whose crop the law's reach nearly fills: 2 300 operator products at 64² on the grid, 2 615
/// with windows up to 0.8 of its cost, 2 531 with 0.4 (the early approach steps, cheap either
/// way: the same time within the noise); the bench's rough sphere (windows about 0.2 of the
/// crop's cost) 9.2–9.4 → 7.0–7.4 s.
const STEP_COST_RATIO: f64 = 0.4;

/// Distinct step-window shapes kept (each holds an operator and a smooth state).
const STEP_SHAPES: usize = 4;

/// What a smooth step touches, on a window's shape: the operator, surface (the window's
/// heights plus the held pressure's displacement), fields, bonded set, CG vectors and smooth
/// state (whose Newton and landing windows are the solver's own, lent for the step).
pub(super) struct StepWindow {
    base: SolverBase,
    bonded: Array2<bool>,
    pcg: PcgWork,
    smooth: SmoothState,
}

/// The step windows of one solver, by shape.
pub(super) type StepWindows = crate::subgrid::SubgridCache<StepWindow>;

/// No step window yet.
pub(super) fn step_windows() -> StepWindows {
    crate::subgrid::SubgridCache::new(STEP_SHAPES)
}

impl StepWindow {
    fn new(shape: (usize, usize), dx: f64, e_star: f64, like: &SmoothState) -> Self {
        let grid = Grid::new(shape.0, shape.1, dx, tack_geometry::Boundary::Free)
            .expect("a sub-grid of a valid grid is valid");
        let op = Box::new(crate::subgrid::free_operator(shape, dx, e_star));
        let surface = Surface::flat(grid);
        Self {
            base: SolverBase::new(op, &surface).expect("the operator's own grid"),
            bonded: Array2::from_elem(shape, false),
            pcg: PcgWork::new(shape),
            smooth: SmoothState {
                resolved: like.resolved,
                ..SmoothState::new(like.traction.clone(), shape, like.tolerance, like.peak_gap)
            },
        }
    }
}

impl AdhesiveSolver {
    /// The window a smooth step at approach `d` runs on (module docs); `None` on the first
    /// step, on periodic grids and films, on a γ map, with sub-grids off, or when the window
    /// would not be cheaper than the grid.
    pub(super) fn step_window(&self, d: f64) -> Option<Window> {
        let s = self.smooth.as_ref()?;
        let d_prev = self.last_approach?;
        if s.weights.is_some() || !self.base.op.is_half_space() {
            return None;
        }
        let cut = HELD_FRACTION * s.tolerance * self.sigma_c;
        // The gap of the last pressure at the last approach on the current heights (a
        // viscoelastic step shifts them), closed by twice this step's approach.
        let closing = d_prev + 2.0 * (d - d_prev).max(0.0);
        let (t, peak_gap) = (&s.traction, s.peak_gap);
        // Beyond `quiet` the law's tension is at most `cut` without evaluating it (the same
        // mask: the law is evaluated on the gaps short of it only).
        let quiet = t.quiet_beyond(cut, peak_gap).unwrap_or(f64::INFINITY);
        let mask = Zip::from(&self.bonded)
            .and(self.base.surface.heights())
            .and(&self.base.work.disp)
            .and(&self.base.pressure)
            .map_collect(|&b, &f, &u, &p| {
                // Short of the law's greatest tension the pressure at the closed gap is no
                // bound on what the step may meet (a Lennard-Jones wall's is 0).
                let g = f - closing + u;
                b || p.abs() > cut || g <= peak_gap || (g < quiet && t.pressure(g).abs() > cut)
            });
        let (tight, _) = crate::subgrid::bounding_box(&mask, None);
        let w = self.subgrid_around(tight)?;
        let cost = crate::subgrid::transform_cost;
        (cost(w.shape()) <= STEP_COST_RATIO * cost(self.base.grid().shape())).then_some(w)
    }

    /// The step at `d` on the window `w` (module docs), into `tally`; returns whether it
    /// landed. Runs right after the predictor, whose secant history then holds the last
    /// pressure (held outside the window).
    pub(super) fn solve_on_window(&mut self, d: f64, w: &Window, tally: &mut Tally) -> bool {
        let k = self.base.op.self_compliance();
        let peak = self.sigma_c;
        let (dx, e_star) = (self.base.grid().dx(), self.base.op.e_star());
        let block = s![w.i0..w.i1, w.j0..w.j1];
        // Outside the window the pressure is held at its last value, which the window was
        // chosen by: the predictor's extrapolation is undone there (after the predictor the
        // secant's history holds the last pressure).
        let s = self.smooth.as_mut().expect("a smooth law");
        if let Some((last, _)) = &self.history {
            s.trial.assign(last);
            s.trial
                .slice_mut(block)
                .assign(&self.base.pressure.slice(block));
            std::mem::swap(&mut self.base.pressure, &mut s.trial);
        }
        let mut steps = std::mem::replace(&mut s.steps, step_windows());
        let sw = steps.get_or_insert_with(w.shape(), || StepWindow::new(w.shape(), dx, e_star, s));
        // The held pressure's displacement on the window, `K p − K_w p_w`: the grid's `K p` of
        // the last pressure is the last step's (its final check), so one product on the
        // window's transform does.
        let last = self
            .history
            .as_ref()
            .map_or(&self.base.pressure, |(p, _)| p);
        sw.base.pressure.assign(&last.slice(block));
        sw.base
            .op
            .apply(sw.base.pressure.view(), sw.base.work.disp.view_mut());
        tally.cg += 1;
        let heights = &self.base.surface.heights().slice(block) + &self.base.work.disp.slice(block)
            - &sw.base.work.disp;
        let grid = *sw.base.grid();
        let Ok(surface) = Surface::new(grid, heights) else {
            s.steps = steps;
            let merit = self.smooth_refresh(d, k);
            return self.solve_smooth(d, merit, tally);
        };
        sw.base.set_surface(surface);
        sw.base.pressure.assign(&self.base.pressure.slice(block));
        sw.bonded.assign(&self.bonded.slice(block));
        sw.smooth.traction = s.traction.clone();
        sw.smooth.tolerance = s.tolerance;
        sw.smooth.landed = s.landed;
        sw.smooth.fallback = s.fallback.take().map(|f| f.slice(block).to_owned());
        self.swap_step_window(sw);
        let wk = self.base.op.self_compliance();
        let merit = self.smooth_refresh(d, wk);
        let landed = self.solve_smooth(d, merit, tally);
        self.swap_step_window(sw);
        self.base
            .pressure
            .slice_mut(block)
            .assign(&sw.base.pressure);
        let s = self.smooth.as_mut().expect("a smooth law");
        s.steps = steps;
        // Every element against Newton's tolerance: one product on the grid.
        let merit = self.smooth_refresh(d, k);
        tally.cg += 1;
        let tolerance = self.smooth.as_ref().expect("a smooth law").tolerance;
        #[cfg(test)]
        {
            let s = self.smooth.as_mut().expect("a smooth law");
            s.window_steps.0 += 1;
            s.window_steps.1 += usize::from(merit.worst > tolerance * peak || !tally.converged);
        }
        if merit.worst <= tolerance * peak && tally.converged {
            tally.worst = tally.worst.max(merit.worst / peak);
            return landed;
        }
        // Finished on the grid: an element outside missed the tolerance, or the window's solve
        // met a cap (the grid's step is judged on its own, and reports its own residual).
        tally.converged = true;
        tally.worst = 0.0;
        self.solve_smooth(d, merit, tally) || landed
    }

    /// Exchanges the solver's grid state with a step window's.
    fn swap_step_window(&mut self, sw: &mut StepWindow) {
        std::mem::swap(&mut self.base, &mut sw.base);
        std::mem::swap(&mut self.bonded, &mut sw.bonded);
        std::mem::swap(&mut self.pcg, &mut sw.pcg);
        let s = self.smooth.as_mut().expect("a smooth law");
        std::mem::swap(s, &mut sw.smooth);
        // The Newton and landing windows stay with the solver: their operators depend only on
        // their shape, and a step window's shape changes often on a moving contact.
        std::mem::swap(&mut s.windows, &mut sw.smooth.windows);
        std::mem::swap(&mut s.landings, &mut sw.smooth.landings);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{AdhesionLaw, AdhesiveOptions, Exponential};
    use tack_geometry::{Boundary, Sphere};

    /// The sphere R = 1 on E* = 1, γ = 1e-3, under the exponential law of range 0.01 (Tabor
    /// μ = 1, process zone 0.085, 2.8 elements) on a free 96² grid of elements 0.03: the law's
    /// reach (18.4ρ) ends about 0.65 from the axis at the deepest approach, so the steps run on
    /// windows of under half the grid's side. Sub-grids on or off.
    fn sphere(subgrids: bool) -> AdhesiveSolver {
        let grid = Grid::square(96, 0.03, Boundary::Free).unwrap();
        let surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
        let op = tack_kernels::operator_for(grid, 1.0).unwrap();
        let options = AdhesiveOptions {
            bonded_subgrid: subgrids,
            ..AdhesiveOptions::default()
        };
        let law = AdhesionLaw::Exponential(Exponential { range: 0.01 });
        AdhesiveSolver::with_law(op, &surface, 1e-3, law, options).unwrap()
    }

    /// A load from d = −0.03 to 0.02 in steps of 0.005 (the jump-in near −d_c/2 ≈ −0.008) and
    /// a retraction to −0.03 in steps of 0.0025, past the pull-off.
    fn path() -> Vec<f64> {
        let load = (0..=10).map(|i| -0.03 + 0.005 * f64::from(i));
        let retract = (1..=20).map(|i| 0.02 - 0.0025 * f64::from(i));
        load.chain(retract).collect()
    }

    /// The 20² window around the grid's centre (±0.3 of the axis): it holds the contact at
    /// d ≤ 0.015, not the law's tension beyond it.
    fn centre_window() -> Window {
        Window {
            i0: 38,
            i1: 58,
            j0: 38,
            j1: 58,
        }
    }

    /// Each step on its window meets the same tolerance as the grid's step: forces within 1e-6
    /// of the greatest. Two states that each leave every element within 1e-7 of the peak
    /// tension (γ/ρ = 0.1) of its equilibrium differ by about that over the few hundred
    /// elements that carry the law's tension: 3e-6·Δx² ≈ 3e-9 against forces of order
    /// πγR = 3e-3.
    #[test]
    fn steps_on_windows_meet_the_grid_solution() {
        let (mut windowed, mut grid) = (sphere(true), sphere(false));
        let mut worst = 0.0f64;
        let mut greatest = 0.0f64;
        for d in path() {
            let (a, b) = (windowed.step(d).unwrap(), grid.step(d).unwrap());
            assert!(a.converged && b.converged, "d = {d}");
            worst = worst.max((a.force - b.force).abs());
            greatest = greatest.max(b.force.abs());
        }
        assert!(worst <= 1e-6 * greatest, "{worst:e} of {greatest:e}");
        let (on_window, finished) = windowed.smooth.as_ref().unwrap().window_steps;
        assert!(on_window >= 20, "{on_window} of 31 steps on a window");
        assert_eq!(finished, 0, "no step should need the grid on this path");
        assert_eq!(grid.smooth.as_ref().unwrap().window_steps.0, 0);
    }

    /// Same inputs, same bits, on one thread and on two, with the steps on windows.
    #[test]
    fn steps_on_windows_give_the_same_bits_on_one_and_two_threads() {
        let run_on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let mut solver = sphere(true);
                let forces: Vec<u64> = path()
                    .into_iter()
                    .map(|d| solver.step(d).unwrap().force.to_bits())
                    .collect();
                (forces, solver.smooth.as_ref().unwrap().window_steps.0)
            })
        };
        let (one, two) = (run_on(1), run_on(2));
        assert!(one.1 >= 20, "{} steps on a window", one.1);
        assert_eq!(one, two);
    }

    /// The held pressure's displacement: a converged state stays converged on a window that
    /// cuts through the law's tension (the pressure outside reaches 1e-3 of the peak and
    /// more), with no step finished on the grid and the pressure moved by less than the
    /// tolerance; without the held displacement the window's gaps would be off by it.
    #[test]
    fn a_converged_state_stays_converged_on_a_window_that_cuts_the_law() {
        let mut solver = sphere(true);
        let d = 0.01;
        for d in [-0.03, -0.02, -0.01, 0.0, d] {
            assert!(solver.step(d).unwrap().converged);
        }
        let w = centre_window();
        let before = solver.base.pressure.clone();
        let peak = solver.sigma_c;
        let mut outside = before.clone();
        outside.slice_mut(s![w.i0..w.i1, w.j0..w.j1]).fill(0.0);
        let held = outside.iter().fold(0.0f64, |m, p| m.max(p.abs()));
        assert!(held > 1e-3 * peak, "the window holds the law: {held:e}");
        let counts = solver.smooth.as_ref().unwrap().window_steps;
        solver.predict_smooth(d);
        let mut tally = Tally::new();
        solver.solve_on_window(d, &w, &mut tally);
        assert!(tally.converged);
        let s = solver.smooth.as_ref().unwrap();
        assert_eq!(
            s.window_steps,
            (counts.0 + 1, counts.1),
            "finished on the grid"
        );
        let moved = Zip::from(&solver.base.pressure)
            .and(&before)
            .fold(0.0f64, |m, a, b| m.max((a - b).abs()));
        assert!(
            moved <= s.tolerance * peak,
            "moved by {:e} of the peak",
            moved / peak
        );
    }

    /// A window that cuts through the law's zone leaves the elements outside it off their
    /// equilibrium: the step is finished on the grid, to the grid's answer.
    #[test]
    fn a_window_that_cuts_the_law_is_finished_on_the_grid() {
        let (mut windowed, mut grid) = (sphere(true), sphere(false));
        for d in [-0.03, -0.02, -0.01, 0.0, 0.01] {
            windowed.step(d).unwrap();
            grid.step(d).unwrap();
        }
        // The contact's radius at d = 0.015 is about 0.2 (7 elements): a 20² window around
        // the centre holds the contact but not the law's tension beyond it.
        let d = 0.015;
        let w = centre_window();
        let (on_window, finished) = windowed.smooth.as_ref().unwrap().window_steps;
        windowed.predict_smooth(d);
        let mut tally = Tally::new();
        windowed.solve_on_window(d, &w, &mut tally);
        let record = windowed.record(d, &tally);
        let expected = grid.step(d).unwrap();
        assert!(record.converged && expected.converged);
        assert_eq!(
            windowed.smooth.as_ref().unwrap().window_steps,
            (on_window + 1, finished + 1)
        );
        let k = windowed.base.op.self_compliance();
        let merit = windowed.smooth_refresh(d, k);
        let tolerance = windowed.smooth.as_ref().unwrap().tolerance;
        assert!(merit.worst <= tolerance * windowed.sigma_c);
        let gap = (record.force - expected.force).abs();
        assert!(
            gap <= 1e-6 * expected.force.abs(),
            "{} vs {}",
            record.force,
            expected.force
        );
    }
}
