//! Sub-grid problems on free grids, cached by shape: the free operator is exact on any
//! sub-grid, so a solver can iterate on a window (the non-adhesive crop of `{f ≤ d}`, the
//! adhesive solver's box around the bonded set) with an operator built once per window shape.

use std::collections::HashMap;

use ndarray::Array2;
use tack_geometry::{Boundary, Grid, Window};
use tack_kernels::FreeOperator;

use crate::base::SolverBase;
use crate::cg::{PcgWork, Work, assign};

/// The free operator of an `nx × ny` sub-grid with spacing `dx` of a grid whose operator was
/// built with `e_star` (so both are valid).
pub(crate) fn free_operator(shape: (usize, usize), dx: f64, e_star: f64) -> FreeOperator {
    let grid = Grid::new(shape.0, shape.1, dx, Boundary::Free)
        .expect("a sub-grid of a valid grid is valid");
    FreeOperator::new(grid, e_star).expect("the modulus was validated with the operator")
}

/// The cost of a product on a free grid of `shape`, in units of its padded transform's
/// `m ln m` (`m` its number of points): what a sub-grid is weighed by against the grid.
pub(crate) fn transform_cost((a, b): (usize, usize)) -> f64 {
    let m = (tack_kernels::padded_size(a) * tack_kernels::padded_size(b)) as f64;
    m * m.ln()
}

/// A bonded-set CG on a sub-grid: its own free operator and buffers.
pub(crate) struct SubProblem {
    pub(crate) op: FreeOperator,
    pub(crate) work: Work,
    pub(crate) pcg: PcgWork,
    pub(crate) pressure: Array2<f64>,
    pub(crate) heights: Array2<f64>,
    pub(crate) bonded: Array2<bool>,
    /// The Dugdale law's zone on this sub-grid, made on first use.
    pub(crate) zone: Option<Array2<bool>>,
}

impl SubProblem {
    pub(crate) fn new(shape: (usize, usize), dx: f64, e_star: f64) -> Self {
        Self {
            op: free_operator(shape, dx, e_star),
            work: Work::new(shape),
            pcg: PcgWork::new(shape),
            pressure: Array2::zeros(shape),
            heights: Array2::zeros(shape),
            bonded: Array2::from_elem(shape, false),
            zone: None,
        }
    }

    /// Copies the pressure, heights and bonded set of `window` in from the whole grid.
    pub(crate) fn load(&mut self, base: &SolverBase, bonded: &Array2<bool>, window: &Window) {
        let block = ndarray::s![window.i0..window.i1, window.j0..window.j1];
        assign(self.pressure.view_mut(), base.pressure.slice(block));
        assign(self.heights.view_mut(), base.surface.heights().slice(block));
        assign(self.bonded.view_mut(), bonded.slice(block));
    }
}

/// Sub-problems keyed by their shape (an operator with its FFT plans, spectra and buffers is
/// costly to build); at most `capacity` are kept: a new shape beyond that replaces the one
/// used least recently.
pub(crate) struct SubgridCache<T> {
    /// Each shape's sub-problem and the use count when it was last asked for.
    entries: HashMap<(usize, usize), (T, u64)>,
    capacity: usize,
    uses: u64,
}

impl<T> SubgridCache<T> {
    pub(crate) fn new(capacity: usize) -> Self {
        Self {
            entries: HashMap::new(),
            capacity: capacity.max(1),
            uses: 0,
        }
    }

    /// The sub-problem of `shape`, built by `build` when it is not cached.
    pub(crate) fn get_or_insert_with(
        &mut self,
        shape: (usize, usize),
        build: impl FnOnce() -> T,
    ) -> &mut T {
        self.uses += 1;
        if !self.entries.contains_key(&shape) && self.entries.len() >= self.capacity {
            let oldest = self
                .entries
                .iter()
                .min_by_key(|(_, (_, used))| *used)
                .map(|(k, _)| *k);
            if let Some(k) = oldest {
                self.entries.remove(&k);
            }
        }
        let entry = self.entries.entry(shape).or_insert_with(|| (build(), 0));
        entry.1 = self.uses;
        &mut entry.0
    }

    /// Number of cached sub-problems.
    #[cfg(test)]
    pub(crate) fn len(&self) -> usize {
        self.entries.len()
    }
}

/// The bounding box of the `true` elements of `mask` that lie in `within` (the whole grid when
/// `None`), and their number; `None` when there are none.
pub(crate) fn bounding_box(
    mask: &Array2<bool>,
    within: Option<&Window>,
) -> (Option<Window>, usize) {
    let (nx, ny) = mask.dim();
    let w = within.copied().unwrap_or(Window {
        i0: 0,
        i1: nx,
        j0: 0,
        j1: ny,
    });
    let (mut i0, mut i1, mut j0, mut j1) = (usize::MAX, 0, usize::MAX, 0);
    let mut count = 0;
    for i in w.i0..w.i1 {
        let row = &mask.row(i).to_slice().expect("standard layout")[w.j0..w.j1];
        if let Some(first) = row.iter().position(|&b| b) {
            let last = row.iter().rposition(|&b| b).unwrap_or(first);
            count += row[first..=last].iter().filter(|&&b| b).count();
            (i0, i1) = (i0.min(i), i + 1);
            (j0, j1) = (j0.min(w.j0 + first), j1.max(w.j0 + last + 1));
        }
    }
    let tight = (count > 0).then_some(Window { i0, i1, j0, j1 });
    (tight, count)
}

#[cfg(test)]
mod tests {
    use super::*;
    use tack_kernels::ElasticOperator;

    #[test]
    fn builds_once_per_shape_and_replaces_the_least_recently_used() {
        let mut cache = SubgridCache::new(2);
        let mut built = 0;
        for shape in [
            (3, 4),
            (3, 4),
            (5, 5),
            (3, 4),
            (6, 2),
            (6, 2),
            (3, 4),
            (5, 5),
        ] {
            let v = cache.get_or_insert_with(shape, || {
                built += 1;
                shape.0 * shape.1
            });
            assert_eq!(*v, shape.0 * shape.1);
        }
        // (3,4) and (5,5) built once; (6,2) replaces (5,5), the least recently used, so (3,4)
        // is still there and (5,5) is built again (replacing (6,2)).
        assert_eq!(built, 4);
        assert_eq!(cache.len(), 2);
        let op = free_operator((4, 7), 0.5, 2.0);
        assert_eq!(op.grid().shape(), (4, 7));
        assert_eq!((op.grid().dx(), op.e_star()), (0.5, 2.0));
        assert_eq!(op.grid().boundary(), Boundary::Free);
    }
}
