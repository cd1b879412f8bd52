//! Non-adhesive frictionless contact by constrained conjugate gradients (Polonsky & Keer 1999)
//! in its gap-controlled form: prescribed approach, pressures ≥ 0, zero gap in contact; with a
//! coarse-to-fine start and, on free grids, iterations confined to where contact can occur.

use ndarray::{Array2, Zip, s};
use tack_geometry::{Boundary, Grid, Surface, Window};
use tack_kernels::{ElasticOperator, operator_for};

use crate::{ContactState, SolverError, SolverOptions};

/// Solves `min ½ pᵀKp + pᵀ(f − d)` subject to `p ≥ 0` for a sequence of approaches, reusing
/// the operator, scratch and the previous pressure as a warm start.
pub struct ContactSolver {
    op: Box<dyn ElasticOperator>,
    surface: Surface,
    options: SolverOptions,
    pressure: Array2<f64>,
    disp: Array2<f64>,
    gap: Array2<f64>,
    dir: Array2<f64>,
    kdir: Array2<f64>,
    coarse_start: bool,
    crop: bool,
    /// The cropped sub-problem of the last solve, reused while the window stays the same.
    sub: Option<(Window, Box<ContactSolver>)>,
}

/// Iterations between recomputations of `K p` from scratch (bounds round-off in the update).
const REFRESH: usize = 50;

/// Coarse-to-fine starts stop coarsening below this many elements per side.
const COARSEST: usize = 32;

impl ContactSolver {
    /// A solver for `surface` pressed against the half-space described by `op`.
    pub fn new(
        op: Box<dyn ElasticOperator>,
        surface: &Surface,
        options: SolverOptions,
    ) -> Result<Self, SolverError> {
        options.validate()?;
        let shape = op.grid().shape();
        if surface.grid().shape() != shape {
            return Err(SolverError::GridMismatch {
                surface: surface.grid().shape(),
                operator: shape,
            });
        }
        let z = Array2::zeros(shape);
        Ok(Self {
            op,
            surface: surface.clone(),
            options,
            pressure: z.clone(),
            disp: z.clone(),
            gap: z.clone(),
            dir: z.clone(),
            kdir: z,
            coarse_start: false,
            crop: true,
            sub: None,
        })
    }

    /// Cold starts (no element in contact yet) begin from the solution on a grid coarsened
    /// 2 × 2 (recursively, down to about 32 elements per side; grids with an odd side are not
    /// coarsened), prolonged by injection. The converged answer is the same problem's; only
    /// the iteration count changes. Off by default: the fine-grid iterations are dominated by
    /// settling the contact set, so the saving is small (`cargo xtask bench-contact`: 276 → 234
    /// iterations on a 1024² periodic H = 0.8 surface at 7% contact).
    pub fn set_coarse_start(&mut self, on: bool) {
        self.coarse_start = on;
    }

    /// Free grids: iterate only on the bounding box of the elements with `f ≤ d` (no other
    /// element can touch: compressive pressures only push the surface away), then compute the
    /// full-grid gap with one product. Exact (the same linear problem). On by default.
    pub fn set_crop(&mut self, on: bool) {
        self.crop = on;
    }

    /// Equilibrium at approach `d` (finite), warm-started from the previous solve.
    pub fn solve(&mut self, approach: f64) -> Result<ContactState, SolverError> {
        if !approach.is_finite() {
            return Err(SolverError::OutOfRange {
                field: "approach",
                value: approach,
                allowed: "a finite number",
            });
        }
        let grid = *self.op.grid();
        let fmin = self.surface.min();
        let fmean = self.surface.heights().mean().unwrap_or(0.0);
        if approach <= fmin {
            // Nothing touches: p = 0 is the exact solution.
            self.pressure.fill(0.0);
            self.gap
                .assign(&self.surface.heights().mapv(|f| f - approach));
            return Ok(self.state(approach, 0, 0.0, true, false));
        }
        if grid.boundary() == Boundary::Periodic && approach >= fmean {
            return Ok(self.full_contact(approach));
        }
        let scale = approach - fmin;
        if let Some(w) = self.crop_window(approach) {
            return self.solve_cropped(approach, &w);
        }
        if self.coarse_start && !self.pressure.iter().any(|&p| p > 0.0) {
            self.start_from_coarse(approach)?;
        }
        let (iterations, residual, converged) = self.iterate(approach, scale);
        Ok(self.state(approach, iterations, residual, converged, false))
    }

    /// The bounding box of `{f ≤ d}` when cropping pays (free grid, box under half the grid).
    fn crop_window(&self, d: f64) -> Option<Window> {
        let grid = self.op.grid();
        if !self.crop || grid.boundary() != Boundary::Free {
            return None;
        }
        let w = self.surface.window_below(d, 0)?;
        let (nx, ny) = grid.shape();
        (2 * w.shape().0 * w.shape().1 < nx * ny).then_some(w)
    }

    /// Solves on the window `w` (warm-started from the current pressure there), then puts the
    /// pressure back and computes the full-grid gap.
    fn solve_cropped(&mut self, d: f64, w: &Window) -> Result<ContactState, SolverError> {
        let block = s![w.i0..w.i1, w.j0..w.j1];
        let mut sub = match self.sub.take() {
            Some((win, sub)) if win == *w => sub,
            _ => {
                let surface = self
                    .surface
                    .window(w)
                    .expect("a window of the surface's own grid");
                let op =
                    operator_for(*surface.grid(), self.op.e_star()).expect("validated modulus");
                let mut sub = Box::new(ContactSolver::new(op, &surface, self.options)?);
                sub.crop = false;
                sub
            }
        };
        sub.coarse_start = self.coarse_start;
        sub.pressure.assign(&self.pressure.slice(block));
        let st = sub.solve(d)?;
        self.pressure.fill(0.0);
        self.pressure.slice_mut(block).assign(&sub.pressure);
        self.sub = Some((*w, sub));
        self.op.apply(self.pressure.view(), self.disp.view_mut());
        Zip::from(&mut self.gap)
            .and(self.surface.heights())
            .and(&self.disp)
            .for_each(|g, &f, &u| *g = f - d + u);
        Ok(self.state(d, st.iterations, st.residual, st.converged, false))
    }

    /// Fills `pressure` with the prolonged solution of the 2 × 2-coarsened problem, if the grid
    /// can be coarsened.
    fn start_from_coarse(&mut self, d: f64) -> Result<(), SolverError> {
        let grid = *self.op.grid();
        let (nx, ny) = grid.shape();
        if nx % 2 == 1 || ny % 2 == 1 || nx.min(ny) < 2 * COARSEST {
            return Ok(());
        }
        let coarse_grid = Grid::new(nx / 2, ny / 2, 2.0 * grid.dx(), grid.boundary())
            .expect("a coarsened valid grid is valid");
        let f = self.surface.heights();
        let heights = Array2::from_shape_fn((nx / 2, ny / 2), |(i, j)| {
            0.25 * (f[[2 * i, 2 * j]]
                + f[[2 * i + 1, 2 * j]]
                + f[[2 * i, 2 * j + 1]]
                + f[[2 * i + 1, 2 * j + 1]])
        });
        let surface = Surface::new(coarse_grid, heights).expect("finite heights");
        let op = operator_for(coarse_grid, self.op.e_star()).expect("validated modulus");
        // The coarse answer only seeds the fine iterations: a looser tolerance suffices.
        let options = SolverOptions {
            tolerance: self.options.tolerance.max(1e-6),
            ..self.options
        };
        let mut coarse = ContactSolver::new(op, &surface, options)?;
        coarse.crop = false;
        let st = coarse.solve(d)?;
        if st.full_contact {
            return Ok(());
        }
        self.pressure = Array2::from_shape_fn((nx, ny), |(i, j)| coarse.pressure[[i / 2, j / 2]]);
        Ok(())
    }

    /// The constrained CG iterations; returns (iterations, relative residual, converged).
    fn iterate(&mut self, d: f64, scale: f64) -> (usize, f64, bool) {
        let n = self.surface.heights().len() as f64;
        let w0 = self.op.self_compliance();
        if !self.pressure.iter().any(|&p| p > 0.0) {
            // Cold start: each penetrating element carries what would close its own gap.
            Zip::from(&mut self.pressure)
                .and(self.surface.heights())
                .for_each(|p, &f| *p = (d - f).max(0.0) / w0);
        }
        let (mut delta, mut g_old) = (0.0, 1.0);
        self.dir.fill(0.0);
        let mut residual = f64::INFINITY;
        // `disp = K p` is recomputed only after a projection (an element clipped to p = 0 or a
        // penetrating one added); otherwise p moved along t and `disp −= τ K t` is exact.
        let mut fresh = false;
        for it in 0..=self.options.max_iterations {
            if !fresh || it % REFRESH == 0 {
                self.op.apply(self.pressure.view(), self.disp.view_mut());
            }
            Zip::from(&mut self.gap)
                .and(self.surface.heights())
                .and(&self.disp)
                .for_each(|g, &f, &u| *g = f - d + u);
            let (mut g_sum, mut res2) = (0.0, 0.0);
            Zip::from(&self.pressure).and(&self.gap).for_each(|&p, &g| {
                if p > 0.0 {
                    g_sum += g * g;
                    res2 += g * g;
                } else if g < 0.0 {
                    res2 += g * g;
                }
            });
            residual = (res2 / n).sqrt() / scale;
            if residual <= self.options.tolerance {
                return (it, residual, true);
            }
            if it == self.options.max_iterations {
                break;
            }
            if g_sum == 0.0 {
                // Contact set emptied by projection: restart from the cold guess.
                Zip::from(&mut self.pressure)
                    .and(self.surface.heights())
                    .for_each(|p, &f| *p = (d - f).max(0.0) / w0);
                (delta, fresh) = (0.0, false);
                continue;
            }
            let ratio = delta * g_sum / g_old;
            Zip::from(&mut self.dir)
                .and(&self.pressure)
                .and(&self.gap)
                .for_each(|t, &p, &g| *t = if p > 0.0 { g + ratio * *t } else { 0.0 });
            g_old = g_sum;
            self.op.apply(self.dir.view(), self.kdir.view_mut());
            let (mut num, mut den) = (0.0, 0.0);
            Zip::from(&self.pressure)
                .and(&self.gap)
                .and(&self.dir)
                .and(&self.kdir)
                .for_each(|&p, &g, &t, &r| {
                    if p > 0.0 {
                        num += g * t;
                        den += r * t;
                    }
                });
            let tau = num / den;
            let (mut overlap, mut clipped) = (false, false);
            Zip::from(&mut self.pressure)
                .and(&self.gap)
                .and(&self.dir)
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
                Zip::from(&mut self.disp)
                    .and(&self.kdir)
                    .for_each(|u, &k| *u -= tau * k);
            }
        }
        (self.options.max_iterations, residual, false)
    }

    /// Periodic full contact (`d ≥ mean f`): the zero-mean pressure that closes every gap, shifted
    /// by the least mean pressure that keeps every element compressive.
    fn full_contact(&mut self, d: f64) -> ContactState {
        let fmean = self.surface.heights().mean().unwrap_or(0.0);
        // Zero-mean displacement needed: u' = (d − f) − mean(d − f) = fmean − f.
        self.gap.assign(&self.surface.heights().mapv(|f| fmean - f));
        let ok = self
            .op
            .solve_zero_mean(self.gap.view(), self.pressure.view_mut());
        debug_assert!(ok, "full contact is only reached on periodic grids");
        let shift = -self.pressure.iter().copied().fold(f64::INFINITY, f64::min);
        self.pressure.mapv_inplace(|p| p + shift.max(0.0));
        self.gap.fill(0.0);
        self.state(d, 0, 0.0, true, true)
    }

    fn state(
        &self,
        approach: f64,
        iterations: usize,
        residual: f64,
        converged: bool,
        full: bool,
    ) -> ContactState {
        let grid = self.op.grid();
        let force = self.pressure.sum() * grid.element_area();
        let n_contact = if full {
            grid.len()
        } else {
            self.pressure.iter().filter(|&&p| p > 0.0).count()
        };
        ContactState {
            approach,
            pressure: self.pressure.clone(),
            gap: self.gap.clone(),
            force,
            mean_pressure: force / (grid.lx() * grid.ly()),
            n_contact,
            area: n_contact as f64 * grid.element_area(),
            iterations,
            residual,
            converged,
            full_contact: full,
        }
    }
}
