//! Non-adhesive frictionless contact by constrained conjugate gradients (Polonsky & Keer 1999)
//! in its gap-controlled form: prescribed approach, pressures ≥ 0, zero gap in contact.

use ndarray::{Array2, Zip};
use tack_geometry::{Boundary, Surface};
use tack_kernels::ElasticOperator;

use crate::{ContactState, SolverError, SolverOptions};

/// Solves `min ½ pᵀKp + pᵀ(f − d)` subject to `p ≥ 0` for a sequence of approaches, reusing
/// the operator, scratch and the previous pressure as a warm start.
pub struct ContactSolver {
    op: Box<dyn ElasticOperator>,
    heights: Array2<f64>,
    options: SolverOptions,
    pressure: Array2<f64>,
    disp: Array2<f64>,
    gap: Array2<f64>,
    dir: Array2<f64>,
    kdir: Array2<f64>,
}

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
            heights: surface.heights().clone(),
            options,
            pressure: z.clone(),
            disp: z.clone(),
            gap: z.clone(),
            dir: z.clone(),
            kdir: z,
        })
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
        let fmin = self.heights.iter().copied().fold(f64::INFINITY, f64::min);
        let fmean = self.heights.mean().unwrap_or(0.0);
        if approach <= fmin {
            // Nothing touches: p = 0 is the exact solution.
            self.pressure.fill(0.0);
            self.gap.assign(&self.heights.mapv(|f| f - approach));
            return Ok(self.state(approach, 0, 0.0, true, false));
        }
        if grid.boundary() == Boundary::Periodic && approach >= fmean {
            return Ok(self.full_contact(approach));
        }
        let scale = approach - fmin;
        let (iterations, residual, converged) = self.iterate(approach, scale);
        Ok(self.state(approach, iterations, residual, converged, false))
    }

    /// The constrained CG iterations; returns (iterations, relative residual, converged).
    fn iterate(&mut self, d: f64, scale: f64) -> (usize, f64, bool) {
        let n = self.heights.len() as f64;
        let w0 = self.op.self_compliance();
        if !self.pressure.iter().any(|&p| p > 0.0) {
            // Cold start: each penetrating element carries what would close its own gap.
            Zip::from(&mut self.pressure)
                .and(&self.heights)
                .for_each(|p, &f| *p = (d - f).max(0.0) / w0);
        }
        let (mut delta, mut g_old) = (0.0, 1.0);
        self.dir.fill(0.0);
        let mut residual = f64::INFINITY;
        for it in 0..=self.options.max_iterations {
            self.op.apply(self.pressure.view(), self.disp.view_mut());
            Zip::from(&mut self.gap)
                .and(&self.heights)
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
                    .and(&self.heights)
                    .for_each(|p, &f| *p = (d - f).max(0.0) / w0);
                delta = 0.0;
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
            let mut overlap = false;
            Zip::from(&mut self.pressure)
                .and(&self.gap)
                .and(&self.dir)
                .for_each(|p, &g, &t| {
                    if *p > 0.0 {
                        *p = (*p - tau * t).max(0.0);
                    } else if g < 0.0 {
                        // Penetrating element outside the contact set joins it (PK step 7).
                        *p = -tau * g;
                        overlap = true;
                    }
                });
            delta = if overlap { 0.0 } else { 1.0 };
        }
        (self.options.max_iterations, residual, false)
    }

    /// Periodic full contact (`d ≥ mean f`): the zero-mean pressure that closes every gap, shifted
    /// by the least mean pressure that keeps every element compressive.
    fn full_contact(&mut self, d: f64) -> ContactState {
        let fmean = self.heights.mean().unwrap_or(0.0);
        // Zero-mean displacement needed: u' = (d − f) − mean(d − f) = fmean − f.
        self.gap.assign(&self.heights.mapv(|f| fmean - f));
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
