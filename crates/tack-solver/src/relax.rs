//! Local relaxation of released tension: the tension each element detached by a round carried is
//! redistributed over its neighbourhood by a small windowed solve, as the warm start of the next
//! round's solve on the whole set (docs/theory.md §3.4).
//!
//! A round that detaches `U` leaves the pressure `p` with `p_U = 0`, and the residual of the
//! bonded set grows by `v = K p_U` (the displacement the released tension no longer holds). Its
//! short-range part is taken up near `U`: per tile of [`TILE`]² elements holding released
//! elements, the window of [`WINDOW`]² elements around it solves `K_WW δ = v_W` on the bonded
//! elements of the window (free operator, exact on any window of a free grid) to a loose
//! tolerance, and `p += δ`. Only the start of the next solve changes: that solve still runs to
//! its round's tolerance on the whole set, and every decision is taken from it.

use ndarray::{Array2, ArrayView2, ArrayViewMut2, Axis, Zip, s};
use rayon::prelude::*;
use tack_geometry::Window;
use tack_kernels::ElasticOperator;

use crate::cg::{assign, pcg};
use crate::options::SolverOptions;
use crate::subgrid::SubProblem;

/// Side, in elements, of the window a tile's released tension is relaxed on.
pub(crate) const WINDOW: usize = 16;

/// Side of the tiles released elements are grouped by; each tile's window adds
/// `(WINDOW − TILE)/2` elements on every side (the part of a window past the grid's edge counts
/// as free).
pub(crate) const TILE: usize = 8;

/// Relative tolerance and iteration cap of a windowed solve: a warm start needs no more (on the
/// 512² rough-sphere pull-off, 1e-2 or 1e-3 with 100 iterations, or a cap of 2, gave the same
/// time).
const WINDOW_OPTIONS: SolverOptions = SolverOptions {
    tolerance: 0.05,
    max_iterations: 20,
};

/// An element a round detached, and the pressure (a tension, negative) it carried.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Released {
    pub(crate) i: usize,
    pub(crate) j: usize,
    pub(crate) pressure: f64,
}

/// The elements of a block that are free but still carry pressure (those a round has just
/// detached: every other free element has none), with their pressure, which is cleared.
/// `origin` is the block's first element in the grid.
pub(crate) fn take_released(
    mut pressure: ArrayViewMut2<f64>,
    bonded: ArrayView2<bool>,
    origin: (usize, usize),
) -> Vec<Released> {
    let row = |(r, (mut p, b)): (
        usize,
        (ndarray::ArrayViewMut1<f64>, ndarray::ArrayView1<bool>),
    )| {
        let mut out = Vec::new();
        for (c, (p, &b)) in p.iter_mut().zip(b).enumerate() {
            if !b && *p != 0.0 {
                out.push(Released {
                    i: origin.0 + r,
                    j: origin.1 + c,
                    pressure: *p,
                });
                *p = 0.0;
            }
        }
        out
    };
    let rows = pressure
        .axis_iter_mut(Axis(0))
        .zip(bonded.axis_iter(Axis(0)));
    if crate::cg::parallel(bonded.len()) {
        let rows: Vec<_> = rows.collect();
        rows.into_par_iter()
            .enumerate()
            .map(row)
            .collect::<Vec<_>>()
            .concat()
    } else {
        rows.enumerate().flat_map(row).collect()
    }
}

/// Windowed solves of one worker: a [`WINDOW`]² problem and its source buffer.
struct Worker {
    sub: SubProblem,
    source: Array2<f64>,
}

/// The relaxation's windowed problems, one per worker, built on first use.
pub(crate) struct Relaxation {
    workers: Vec<Worker>,
    dx: f64,
    e_star: f64,
}

impl Relaxation {
    pub(crate) fn new(dx: f64, e_star: f64) -> Self {
        Self {
            workers: Vec::new(),
            dx,
            e_star,
        }
    }

    /// Adds to `pressure` the windowed response of the `bonded` elements to the release of
    /// `released` (sorted here, so their order does not matter). Tiles start at `anchor` (the
    /// bonded set's bounding box), and a window reaching past the grid's edge is taken as free
    /// there, so the result does not move with the grid (a cropped grid gives the same). Each
    /// tile's correction is computed on its own and they are added in tile order, so the bits
    /// depend neither on the order of `released` nor on the thread count. Returns the part on
    /// the grid of each window solved, in tile order.
    pub(crate) fn relax(
        &mut self,
        pressure: &mut Array2<f64>,
        bonded: &Array2<bool>,
        anchor: (usize, usize),
        released: &mut [Released],
        preconditioned: bool,
    ) -> Vec<Window> {
        if released.is_empty() {
            return Vec::new();
        }
        let (nx, ny) = bonded.dim();
        let (ai, aj) = (anchor.0 as isize, anchor.1 as isize);
        let t = TILE as isize;
        let tile = |e: &Released| {
            (
                (e.i as isize - ai).div_euclid(t),
                (e.j as isize - aj).div_euclid(t),
            )
        };
        released.sort_unstable_by_key(|e| (tile(e), e.i, e.j));
        let groups: Vec<&[Released]> = released.chunk_by(|a, b| tile(a) == tile(b)).collect();
        let margin = ((WINDOW - TILE) / 2) as isize;
        // The window's first element (may lie before the grid) and the part of it on the grid:
        // grid rows `r0..r1` are window rows `r0 − i0 ..`, and the same for columns.
        let place = |g: &[Released]| {
            let (ti, tj) = tile(&g[0]);
            let (i0, j0) = (ai + ti * t - margin, aj + tj * t - margin);
            let clip = |lo: isize, n: usize| {
                let a = lo.clamp(0, n as isize) as usize;
                let b = (lo + WINDOW as isize).clamp(0, n as isize) as usize;
                (a, b, (a as isize - lo) as usize)
            };
            (clip(i0, nx), clip(j0, ny))
        };
        // Outside a rayon pool everything runs on the calling thread (as `cg::parallel`).
        let threads = match rayon::current_thread_index() {
            Some(_) => rayon::current_num_threads(),
            None => 1,
        };
        let lanes = threads.clamp(1, groups.len());
        while self.workers.len() < lanes {
            self.workers.push(Worker {
                sub: SubProblem::new((WINDOW, WINDOW), self.dx, self.e_star),
                source: Array2::zeros((WINDOW, WINDOW)),
            });
        }
        let per_lane = groups.len().div_ceil(lanes);
        let solve = |w: &mut Worker, g: &[Released]| -> Option<Array2<f64>> {
            let ((r0, r1, wr), (c0, c1, wc)) = place(g);
            let (grid, win) = (
                s![r0..r1, c0..c1],
                s![wr..wr + (r1 - r0), wc..wc + (c1 - c0)],
            );
            w.sub.bonded.fill(false);
            assign(w.sub.bonded.slice_mut(win), bonded.slice(grid));
            if !w.sub.bonded.iter().any(|&b| b) {
                return None;
            }
            w.source.fill(0.0);
            for e in g {
                w.source[[e.i - r0 + wr, e.j - c0 + wc]] = e.pressure;
            }
            // `v = K p_U` into the displacement buffer, then `K_CC δ = v_C` as the CG's
            // `K_CC p = (d − f)_C` with `d = 0`, `f = −v`.
            w.sub.op.apply(w.source.view(), w.sub.work.disp.view_mut());
            Zip::from(&mut w.sub.heights)
                .and(&w.sub.work.disp)
                .for_each(|f, &v| *f = -v);
            w.sub.pressure.fill(0.0);
            pcg(
                &mut w.sub.op,
                w.sub.heights.view(),
                w.sub.bonded.view(),
                0.0,
                w.sub.pressure.view_mut(),
                &mut w.sub.work,
                &mut w.sub.pcg,
                &WINDOW_OPTIONS,
                preconditioned,
            );
            Some(w.sub.pressure.clone())
        };
        let corrections: Vec<Option<Array2<f64>>> = if lanes == 1 {
            let w = &mut self.workers[0];
            groups.iter().map(|g| solve(w, g)).collect()
        } else {
            self.workers[..lanes]
                .par_iter_mut()
                .zip(groups.par_chunks(per_lane))
                .map(|(w, chunk)| chunk.iter().map(|g| solve(w, g)).collect::<Vec<_>>())
                .collect::<Vec<_>>()
                .into_iter()
                .flatten()
                .collect()
        };
        let mut solved = Vec::new();
        for (g, delta) in groups.iter().zip(corrections) {
            let Some(delta) = delta else { continue };
            let ((r0, r1, wr), (c0, c1, wc)) = place(g);
            Zip::from(pressure.slice_mut(s![r0..r1, c0..c1]))
                .and(delta.slice(s![wr..wr + (r1 - r0), wc..wc + (c1 - c0)]))
                .for_each(|p, &q| *p += q);
            solved.push(Window {
                i0: r0,
                i1: r1,
                j0: c0,
                j1: c1,
            });
        }
        solved
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cg::{PcgWork, Work};
    use tack_geometry::{Boundary, Grid};
    use tack_kernels::FreeOperator;

    /// A free `n × n` grid (Δx = 1, E* = 1) with a bonded disc of radius `r` around `centre`,
    /// pressed flat by d = 1 (f = 0): the pressure of the exact bonded-set solve.
    fn disc(n: usize, centre: (f64, f64), r: f64) -> (FreeOperator, Array2<bool>, Array2<f64>) {
        let mut op = FreeOperator::new(Grid::square(n, 1.0, Boundary::Free).unwrap(), 1.0).unwrap();
        let bonded = Array2::from_shape_fn((n, n), |(i, j)| {
            (i as f64 - centre.0).hypot(j as f64 - centre.1) <= r
        });
        let mut p = Array2::zeros((n, n));
        let opts = SolverOptions {
            tolerance: 1e-12,
            max_iterations: 500,
        };
        let c = pcg(
            &mut op,
            Array2::zeros((n, n)).view(),
            bonded.view(),
            1.0,
            p.view_mut(),
            &mut Work::new((n, n)),
            &mut PcgWork::new((n, n)),
            &opts,
            true,
        );
        assert!(c.converged);
        (op, bonded, p)
    }

    /// rms over the bonded set of `d − f − K p` (f = 0, d = 1).
    fn residual(op: &mut FreeOperator, bonded: &Array2<bool>, p: &Array2<f64>) -> f64 {
        let mut u = Array2::zeros(p.dim());
        op.apply(p.view(), u.view_mut());
        let (mut s, mut n) = (0.0, 0);
        Zip::from(bonded).and(&u).for_each(|&b, &u| {
            if b {
                s += (1.0 - u) * (1.0 - u);
                n += 1;
            }
        });
        (s / n as f64).sqrt()
    }

    /// Releases the rim elements of the disc's quarter towards the grid's far corner (`far`) or
    /// towards its origin (the edge of a punch carries the greatest tension when pulled, here
    /// the greatest pressure: the sign does not matter to a linear solve).
    fn release_rim(bonded: &mut Array2<bool>, p: &mut Array2<f64>, far: bool) -> Vec<Released> {
        let (n, _) = bonded.dim();
        let mut out = Vec::new();
        for i in 1..n - 1 {
            for j in 1..n - 1 {
                let rim = bonded[[i, j]]
                    && [(0, 1), (2, 1), (1, 0), (1, 2)]
                        .iter()
                        .any(|&(a, b)| !bonded[[i + a - 1, j + b - 1]]);
                let quarter = if far {
                    i > n / 2 && j > n / 2
                } else {
                    i < n / 2 && j < n / 2
                };
                if rim && quarter {
                    out.push(Released {
                        i,
                        j,
                        pressure: p[[i, j]],
                    });
                }
            }
        }
        for e in &out {
            bonded[[e.i, e.j]] = false;
            p[[e.i, e.j]] = 0.0;
        }
        out
    }

    /// The first row and column of the bonded set (its bounding box's corner).
    fn corner(bonded: &Array2<bool>) -> (usize, usize) {
        let (tight, _) = crate::subgrid::bounding_box(bonded, None);
        let w = tight.expect("a bonded element");
        (w.i0, w.j0)
    }

    #[test]
    fn relaxation_takes_up_most_of_the_released_load() {
        // A punch of radius 14 loses a quarter of its rim: the exact response is long-range,
        // but the released load is taken up where it was released. The residual of the start
        // must fall by far more than half (measured: 11.6× here), and only bonded elements within
        // the windows of the released ones may change.
        let (mut op, mut bonded, mut p) = disc(48, (23.5, 23.5), 14.0);
        let mut released = release_rim(&mut bonded, &mut p, true);
        assert!(released.len() > 5);
        let before = residual(&mut op, &bonded, &p);
        let old = p.clone();
        let mut relax = Relaxation::new(1.0, 1.0);
        let windows = relax.relax(&mut p, &bonded, corner(&bonded), &mut released, true);
        let after = residual(&mut op, &bonded, &p);
        assert!(!windows.is_empty());
        assert!(after < 0.3 * before, "residual {before} -> {after}");
        // A released element's window reaches at most TILE − 1 + (WINDOW − TILE)/2 away.
        let reach = TILE - 1 + (WINDOW - TILE) / 2;
        Zip::indexed(&p)
            .and(&old)
            .and(&bonded)
            .for_each(|(i, j), &a, &b, &c| {
                let near = released
                    .iter()
                    .any(|e| e.i.abs_diff(i) <= reach && e.j.abs_diff(j) <= reach);
                if a != b {
                    assert!(c && near, "({i}, {j}) changed: bonded {c}, near {near}");
                }
            });
    }

    #[test]
    fn relaxation_does_not_move_with_the_grid_the_order_or_the_threads() {
        // The same disc on a 40² grid whose far (then near) edge cuts the windows of the
        // released elements, and shifted by (5, 3) inside a 60² grid that holds them whole,
        // with the released elements listed in opposite orders, and solved on the calling
        // thread against a pool of 3: the same corrections, bit for bit.
        for (centre, far) in [(23.5, true), (16.5, false)] {
            let (_, mut b1, mut p1) = disc(40, (centre, centre), 14.0);
            let mut r1 = release_rim(&mut b1, &mut p1, far);
            let (mut b2, mut p2) = (Array2::from_elem((60, 60), false), Array2::zeros((60, 60)));
            b2.slice_mut(s![5..45, 3..43]).assign(&b1);
            p2.slice_mut(s![5..45, 3..43]).assign(&p1);
            let mut r2: Vec<Released> = r1
                .iter()
                .rev()
                .map(|e| Released {
                    i: e.i + 5,
                    j: e.j + 3,
                    ..*e
                })
                .collect();
            let (o1, o2) = (p1.clone(), p2.clone());
            let (a1, a2) = (corner(&b1), corner(&b2));
            // A window reaches (WINDOW − TILE)/2 = 4 past its tile, so past its elements.
            let cut = r1.iter().any(|e| {
                let m = (WINDOW - TILE) / 2;
                if far {
                    e.i + m >= 40 || e.j + m >= 40
                } else {
                    e.i < m || e.j < m
                }
            });
            assert!(cut, "the 40² grid's edge must cut a window");
            Relaxation::new(1.0, 1.0).relax(&mut p1, &b1, a1, &mut r1, true);
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(3)
                .build()
                .unwrap();
            let lanes = pool.install(|| {
                let mut r = Relaxation::new(1.0, 1.0);
                r.relax(&mut p2, &b2, a2, &mut r2, true);
                r.workers.len()
            });
            assert_eq!(lanes, 3, "the pool's threads must share the windows");
            assert!(o2.iter().zip(&p2).any(|(a, b)| a != b), "nothing relaxed");
            for i in 0..40 {
                for j in 0..40 {
                    let d1 = p1[[i, j]] - o1[[i, j]];
                    let d2 = p2[[i + 5, j + 3]] - o2[[i + 5, j + 3]];
                    assert_eq!(d1.to_bits(), d2.to_bits(), "far {far}: ({i}, {j})");
                }
            }
        }
    }

    #[test]
    fn released_elements_are_the_free_ones_with_pressure() {
        let mut p = Array2::from_shape_fn((4, 5), |(i, j)| (i * 5 + j) as f64 - 3.0);
        let bonded = Array2::from_shape_fn((4, 5), |(i, j)| (i + j) % 3 != 0);
        let expect: Vec<Released> = (0..4)
            .flat_map(|i| (0..5).map(move |j| (i, j)))
            .filter(|&(i, j)| (i + j) % 3 == 0 && i * 5 + j != 3)
            .map(|(i, j)| Released {
                i: i + 10,
                j: j + 20,
                pressure: (i * 5 + j) as f64 - 3.0,
            })
            .collect();
        let got = take_released(p.view_mut(), bonded.view(), (10, 20));
        assert_eq!(got, expect);
        Zip::from(&p).and(&bonded).for_each(|&p, &b| {
            if !b {
                assert_eq!(p, 0.0);
            }
        });
    }
}
