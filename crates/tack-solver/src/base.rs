//! What both solvers own and do alike: the operator and surface (checked to share a grid), the
//! pressure and gap fields and the CG vectors, all allocated once; the gap update
//! `g = f − d + K p`; the periodic full-contact field; the integrals of a record.

use ndarray::{Array2, ArrayView2, Zip};
use tack_geometry::{Boundary, Grid, Surface, Window};
use tack_kernels::ElasticOperator;

use crate::SolverError;
use crate::cg::{Work, assign};
use crate::state::Totals;

/// Operator, surface, fields and CG vectors of one solver.
pub(crate) struct SolverBase {
    pub(crate) op: Box<dyn ElasticOperator>,
    pub(crate) surface: Surface,
    /// Lowest height: the approach of the first touch.
    pub(crate) fmin: f64,
    /// Mean height: periodic grids are in full contact from `d = fmean` on.
    pub(crate) fmean: f64,
    pub(crate) pressure: Array2<f64>,
    pub(crate) gap: Array2<f64>,
    /// `work.disp = K p` whenever a solve has finished.
    pub(crate) work: Work,
}

impl SolverBase {
    /// Checks that `surface` lives on the operator's grid.
    pub(crate) fn new(
        op: Box<dyn ElasticOperator>,
        surface: &Surface,
    ) -> Result<Self, SolverError> {
        let shape = crate::validate::same_grid(op.as_ref(), surface)?;
        let z = Array2::zeros(shape);
        Ok(Self {
            fmin: surface.min(),
            fmean: mean_height(surface),
            op,
            surface: surface.clone(),
            pressure: z.clone(),
            gap: z,
            work: Work::new(shape),
        })
    }

    /// Replaces the surface by another on the same grid (a cached sub-problem moved to a new
    /// window of the same shape); fields and vectors are kept.
    pub(crate) fn set_surface(&mut self, surface: Surface) {
        debug_assert_eq!(surface.grid(), self.op.grid());
        self.fmin = surface.min();
        self.fmean = mean_height(&surface);
        self.surface = surface;
    }

    pub(crate) fn heights(&self) -> &Array2<f64> {
        self.surface.heights()
    }

    pub(crate) fn grid(&self) -> &Grid {
        self.op.grid()
    }

    pub(crate) fn periodic(&self) -> bool {
        self.grid().boundary() == Boundary::Periodic
    }

    /// `gap = f − d + disp` at every element (`disp = K p` from the last product).
    pub(crate) fn update_gap(&mut self, d: f64) {
        gap_of(
            self.gap.view_mut(),
            self.surface.heights().view(),
            self.work.disp.view(),
            d,
        );
    }

    /// Takes a sub-grid solve on `window` back into the grid: the pressure is cleared over
    /// `extent` (a window holding every non-zero pressure before; `None`: the grid) and the
    /// sub-grid's `pressure` copied in. With `full`, `work.disp = K p` on the whole grid and
    /// `None` is returned; otherwise the sub-grid's `disp` (its `K p`, exact there: every
    /// non-zero pressure lies in the window) is copied in and `window` returned, the one
    /// region where `work.disp` is up to date.
    pub(crate) fn adopt_subgrid(
        &mut self,
        window: &Window,
        extent: Option<&Window>,
        pressure: ArrayView2<f64>,
        disp: ArrayView2<f64>,
        full: bool,
    ) -> Option<Window> {
        match extent {
            Some(e) => self
                .pressure
                .slice_mut(ndarray::s![e.i0..e.i1, e.j0..e.j1])
                .fill(0.0),
            None => self.pressure.fill(0.0),
        }
        let block = ndarray::s![window.i0..window.i1, window.j0..window.j1];
        assign(self.pressure.slice_mut(block), pressure);
        if full {
            self.op
                .apply(self.pressure.view(), self.work.disp.view_mut());
            None
        } else {
            assign(self.work.disp.slice_mut(block), disp);
            Some(*window)
        }
    }

    /// `gap = f − d + disp` inside the window `w` only.
    pub(crate) fn update_gap_in(&mut self, d: f64, w: &Window) {
        let block = ndarray::s![w.i0..w.i1, w.j0..w.j1];
        gap_of(
            self.gap.slice_mut(block),
            self.surface.heights().slice(block),
            self.work.disp.slice(block),
            d,
        );
    }

    /// Periodic grids: fills `pressure` with the zero-mean pressure that closes every gap
    /// (`K p = mean f − f`; `disp` and `gap` hold that displacement) and returns its minimum.
    /// The mean pressure is then free: each solver shifts it by its own admissibility rule.
    pub(crate) fn full_contact_field(&mut self) -> f64 {
        let fmean = self.fmean;
        Zip::from(&mut self.gap)
            .and(self.surface.heights())
            .for_each(|g, &f| *g = fmean - f);
        let periodic = self
            .op
            .solve_zero_mean(self.gap.view(), self.pressure.view_mut());
        debug_assert!(periodic, "full contact is only reached on periodic grids");
        self.work.disp.assign(&self.gap);
        self.pressure.iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// Periodic grids: whether the mean gap `f̄ − d` is closed at approach `d` (every gap zero,
    /// full contact the only admissible state; testing it element by element would cycle on
    /// round-off).
    pub(crate) fn closed(&self, d: f64) -> bool {
        self.periodic() && d >= self.fmean - 1e-12 * (self.fmean.abs() + d.abs())
    }

    /// Periodic grids with every element bonded. With the mean gap `closed`, sets the
    /// full-contact state at the least mean pressure whose greatest tension is `tension` (σ_c
    /// of the criterion, σ0 of the Dugdale law, 0 without adhesion) and returns `None`;
    /// otherwise full contact cannot hold and the element to release is returned: the most
    /// tensile of the full-contact field (first in row-major order on ties). With a `map` of
    /// per-element tensions (patterned adhesion) the same holds element by element: the weakest
    /// element is the least `p + σ_ij`.
    pub(crate) fn full_contact_or_weakest(
        &mut self,
        closed: bool,
        tension: f64,
        map: Option<ArrayView2<f64>>,
    ) -> Option<(usize, usize)> {
        let p_min = self.full_contact_field();
        let ncols = self.pressure.ncols();
        if let Some(map) = map {
            // Per-element tensions: the mean pressure that keeps every `p + m ≥ −σ_ij` is
            // `m = −min(p + σ)`, reached at the weakest element.
            let (mut least, mut weakest) = (f64::INFINITY, 0);
            for (k, (&p, &s)) in self.pressure.iter().zip(map.iter()).enumerate() {
                if p + s < least {
                    (least, weakest) = (p + s, k);
                }
            }
            if closed {
                self.pressure.mapv_inplace(|p| p - least);
                self.gap.fill(0.0);
                return None;
            }
            return Some((weakest / ncols, weakest % ncols));
        }
        if closed {
            self.pressure.mapv_inplace(|p| p - p_min - tension);
            self.gap.fill(0.0);
            return None;
        }
        let weakest = self.pressure.iter().position(|&p| p == p_min).unwrap_or(0);
        Some((weakest / ncols, weakest % ncols))
    }

    /// The problem on the grid coarsened 2 × 2 (heights averaged) with its operator, or `None`
    /// when a side is odd or below `2 × COARSEST`: the coarse-to-fine starts of both solvers.
    pub(crate) fn coarsened(&self) -> Option<(Surface, Box<dyn ElasticOperator>)> {
        let grid = *self.grid();
        let (nx, ny) = grid.shape();
        if nx % 2 == 1 || ny % 2 == 1 || nx.min(ny) < 2 * COARSEST {
            return None;
        }
        let coarse_grid = Grid::new(nx / 2, ny / 2, 2.0 * grid.dx(), grid.boundary())
            .expect("a coarsened valid grid is valid");
        let f = self.heights();
        let heights = Array2::from_shape_fn((nx / 2, ny / 2), |(i, j)| {
            0.25 * (f[[2 * i, 2 * j]]
                + f[[2 * i + 1, 2 * j]]
                + f[[2 * i, 2 * j + 1]]
                + f[[2 * i + 1, 2 * j + 1]])
        });
        let surface = Surface::new(coarse_grid, heights).expect("averages of finite heights");
        let op =
            tack_kernels::operator_for(coarse_grid, self.op.e_star()).expect("validated modulus");
        Some((surface, op))
    }

    /// Force, mean pressure and area of the current pressure with `n_contact` elements in contact.
    pub(crate) fn totals(&self, n_contact: usize) -> Totals {
        Totals::new(self.grid(), &self.pressure, n_contact)
    }
}

/// Coarse-to-fine starts stop coarsening below this many elements per side.
const COARSEST: usize = 32;

fn mean_height(surface: &Surface) -> f64 {
    surface.heights().mean().unwrap_or(0.0)
}

/// `g = f − d + u` element by element, in parallel on long grids (the same bits either way).
pub(crate) fn gap_of(
    gap: ndarray::ArrayViewMut2<f64>,
    f: ArrayView2<f64>,
    u: ArrayView2<f64>,
    d: f64,
) {
    let zip = Zip::from(gap).and(f).and(u);
    let set = |g: &mut f64, &f: &f64, &u: &f64| *g = f - d + u;
    if crate::cg::parallel(zip.size()) {
        zip.par_for_each(set);
    } else {
        zip.for_each(set);
    }
}
