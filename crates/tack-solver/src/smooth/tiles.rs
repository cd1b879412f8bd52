//! Newton's linear solves under a smooth law: restarted GMRES, preconditioned by the exact
//! inverse of the Newton matrix on small tiles of elements.
//!
//! The Newton matrix `K − diag(c)` (module docs of `smooth.rs`) is symmetric but indefinite,
//! and where the front meets the law's steep part its rows couple strongly to their
//! neighbours with both signs. A symmetric positive definite preconditioner, which MINRES
//! needs, cannot carry that sign structure: with the exact inverse of the contact block and
//! the exact Schur complement of the rest (made positive) MINRES still took 55 iterations to
//! 1e-5 of a system it took 61 for with the spectral and diagonal scale (a Newton system of the
//! bench's rough sphere, 54 × 75 elements). The exact inverse of the matrix restricted to each
//! `TILE × TILE` tile that holds a stiff element (contact or the law's steep part), with the
//! plain diagonal elsewhere, is indefinite like the matrix, and GMRES takes it: 17 to 30
//! iterations to 1e-5 on the same systems with 4 × 4 tiles (6 × 6: 15 to 25, 8 × 8: 17 to 28).
//! A tile's inverse costs its side to the sixth, and in the solver 4 × 4 is the fastest
//! (docs/theory.md §3.9, "Newton's solves on tiles").

use nalgebra::DMatrix;
use rayon::prelude::*;
use tack_kernels::ElasticOperator;

use super::Symmetric;

/// The tiles' side in elements.
pub(super) const TILE: usize = 4;
/// GMRES's restart length.
const RESTART: usize = 60;
/// A tile whose inverse reaches beyond this many `1/k` (a tile block near singular, the front
/// at a fold inside it) is preconditioned by its diagonal instead: its exact inverse would
/// amplify the near-null mode the outer iteration has to resolve anyway.
const TILE_AMPLIFICATION: f64 = 1e3;

/// An operator's influence coefficients `K(|Δi|, |Δj|)` for offsets below [`TILE`]: its
/// response to a unit pressure on the first element (every operator of tack depends on the
/// offset only, and is even in it: the half-space, the periodic grid, the layers).
#[derive(Clone)]
pub(super) struct Coefficients([[f64; TILE]; TILE]);

impl Coefficients {
    /// The coefficients of `op` (one product).
    pub(super) fn of(op: &mut dyn ElasticOperator) -> Self {
        let shape = op.grid().shape();
        let mut unit = ndarray::Array2::zeros(shape);
        unit[[0, 0]] = 1.0;
        let mut out = ndarray::Array2::zeros(shape);
        op.apply(unit.view(), out.view_mut());
        let mut c = [[0.0; TILE]; TILE];
        for (a, row) in c.iter_mut().enumerate().take(shape.0) {
            for (b, v) in row.iter_mut().enumerate().take(shape.1) {
                *v = out[[a, b]];
            }
        }
        Self(c)
    }
}

/// One tile: its first element, its shape, the `c` it was inverted at and the inverse of the
/// matrix on it (row-major), or `None` where that is near singular ([`TILE_AMPLIFICATION`]:
/// the tile keeps the diagonal).
struct Block {
    origin: (usize, usize),
    shape: (usize, usize),
    c: Vec<f64>,
    inverse: Option<Vec<f64>>,
}

impl Block {
    /// Whether the block inverted at its `c` still serves `c` (`at`: the tile's values now):
    /// the same contact elements, every other `c` within [`REUSE`] of it.
    fn serves(&self, at: impl Iterator<Item = f64>) -> bool {
        self.c.iter().zip(at).all(|(&old, new)| {
            (old == 0.0) == (new == 0.0) && (new - old).abs() <= REUSE * old.abs()
        })
    }
}

/// A tile's inverse is kept while no element's `c` moved by more than this fraction (nor
/// joined or left the contact): a preconditioner need not be exact, and most tiles (inside
/// the contact, away from the front) do not change between Newton solves.
const REUSE: f64 = 0.1;

/// The block-Jacobi preconditioner on tiles: the exact inverse on tiles that hold a stiff
/// element, `1/(k − c_i)` (the matrix's own diagonal) on the others.
pub(super) struct Tiles {
    shape: (usize, usize),
    /// By tile, row-major over the grid's tiles (`None`: a tile without a stiff element).
    blocks: Vec<Option<Block>>,
    diagonal: Vec<f64>,
    /// Tiles inverted since this preconditioner was made.
    #[cfg(test)]
    rebuilt: usize,
}

impl Tiles {
    pub(super) fn new() -> Self {
        Self {
            shape: (0, 0),
            blocks: Vec::new(),
            diagonal: Vec::new(),
            #[cfg(test)]
            rebuilt: 0,
        }
    }

    /// Builds the preconditioner of `K − diag(c)` on a grid of `shape` with the coefficients
    /// `coef` (self-compliance `k`): a tile is inverted when one of its elements has
    /// `|c| ≤ stiff` (the rest of its rows are diagonal to `k/stiff`), or its last inverse
    /// kept where it still serves ([`REUSE`]).
    pub(super) fn build(
        &mut self,
        shape: (usize, usize),
        c: &[f64],
        k: f64,
        coef: &Coefficients,
        stiff: f64,
    ) {
        let ny = shape.1;
        let tiles = (shape.0.div_ceil(TILE), ny.div_ceil(TILE));
        if self.shape != shape {
            self.shape = shape;
            self.blocks.clear();
            self.blocks.resize_with(tiles.0 * tiles.1, || None);
        }
        // The matrix's own diagonal off the stiff elements (`|k − c| > 99k` there); on a stiff
        // element it serves only where its tile is near singular, and there MINRES's positive
        // scale does (`smooth.rs`, [`super::SCHUR_SHIFT`]).
        self.diagonal.clear();
        self.diagonal.extend(c.iter().map(|&ci| {
            if ci.abs() > stiff {
                1.0 / (k - ci)
            } else if ci > k {
                1.0 / (ci - super::SCHUR_SHIFT * k)
            } else {
                1.0 / (k + ci.abs())
            }
        }));
        let elements = |t: usize| {
            let (i0, j0) = ((t / tiles.1) * TILE, (t % tiles.1) * TILE);
            (i0..(i0 + TILE).min(shape.0))
                .flat_map(move |i| (j0..(j0 + TILE).min(ny)).map(move |j| i * ny + j))
        };
        let mut rebuild = Vec::new();
        for (t, slot) in self.blocks.iter_mut().enumerate() {
            if !elements(t).any(|e| c[e].abs() <= stiff) {
                *slot = None;
            } else if !slot
                .as_ref()
                .is_some_and(|b| b.serves(elements(t).map(|e| c[e])))
            {
                rebuild.push(t);
            }
        }
        #[cfg(test)]
        {
            self.rebuilt += rebuild.len();
        }
        let built: Vec<Block> = rebuild
            .par_iter()
            .map(|&t| {
                let origin = ((t / tiles.1) * TILE, (t % tiles.1) * TILE);
                block(origin, shape, c, k, coef)
            })
            .collect();
        for (t, b) in rebuild.into_iter().zip(built) {
            self.blocks[t] = Some(b);
        }
    }
}

/// A preconditioner `P` for [`Gmres`] (right preconditioning: GMRES solves `A P y = b`).
pub(super) trait Preconditioner {
    /// `out = P r`.
    fn apply(&mut self, r: &[f64], out: &mut [f64]);
}

impl Preconditioner for Tiles {
    /// By stripes of [`TILE`] rows in parallel (each tile's rows are its stripe's own).
    fn apply(&mut self, r: &[f64], out: &mut [f64]) {
        let ny = self.shape.1;
        let per_stripe = ny.div_ceil(TILE);
        out.par_chunks_mut(TILE * ny)
            .zip(self.diagonal.par_chunks(TILE * ny))
            .zip(self.blocks.par_chunks(per_stripe))
            .enumerate()
            .for_each(|(stripe, ((out, diagonal), blocks))| {
                let base = stripe * TILE * ny;
                for ((o, &ri), &d) in out.iter_mut().zip(&r[base..]).zip(diagonal) {
                    *o = d * ri;
                }
                let mut gathered = [0.0; TILE * TILE];
                for b in blocks.iter().flatten() {
                    let Some(inverse) = &b.inverse else { continue };
                    let (h, w) = b.shape;
                    let n = h * w;
                    for a in 0..h {
                        let row = (b.origin.0 + a) * ny + b.origin.1;
                        gathered[a * w..(a + 1) * w].copy_from_slice(&r[row..row + w]);
                    }
                    for (l, inv) in inverse.chunks_exact(n).enumerate() {
                        let e = (b.origin.0 + l / w) * ny + b.origin.1 + l % w - base;
                        out[e] = dot(inv, &gathered[..n]);
                    }
                }
            });
    }
}

/// The tile at `origin` inverted at `c`.
fn block(
    origin: (usize, usize),
    shape: (usize, usize),
    c: &[f64],
    k: f64,
    coef: &Coefficients,
) -> Block {
    let h = TILE.min(shape.0 - origin.0);
    let w = TILE.min(shape.1 - origin.1);
    let n = h * w;
    let element = |l: usize| (l / w, l % w);
    let at = |l: usize| {
        let (i, j) = element(l);
        c[(origin.0 + i) * shape.1 + origin.1 + j]
    };
    let a = DMatrix::from_fn(n, n, |p, q| {
        let ((pi, pj), (qi, qj)) = (element(p), element(q));
        let k_pq = coef.0[pi.abs_diff(qi)][pj.abs_diff(qj)];
        if p == q { k_pq - at(p) } else { k_pq }
    });
    let limit = TILE_AMPLIFICATION / k;
    // Row-major: row p of the inverse maps the tile's residual to element p.
    let inverse = a
        .try_inverse()
        .filter(|inv| inv.iter().all(|x| x.is_finite() && x.abs() <= limit))
        .map(|inv| {
            (0..n)
                .flat_map(|p| (0..n).map(move |q| (p, q)))
                .map(|(p, q)| inv[(p, q)])
                .collect()
        });
    Block {
        origin,
        shape: (h, w),
        c: (0..n).map(at).collect(),
        inverse,
    }
}

/// Vectors are summed in chunks of this many elements, in parallel for long vectors and
/// always in the same order (the same bits on any thread count).
const CHUNK: usize = 4096;

/// `a·b` by [`CHUNK`]s, each in four interleaved partial sums.
fn long_dot(a: &[f64], b: &[f64]) -> f64 {
    if a.len() <= CHUNK {
        return dot(a, b);
    }
    let parts: Vec<f64> = a
        .par_chunks(CHUNK)
        .zip(b.par_chunks(CHUNK))
        .map(|(a, b)| dot(a, b))
        .collect();
    parts.iter().sum()
}

/// `y −= h x`, in parallel for long vectors.
fn axpy(y: &mut [f64], h: f64, x: &[f64]) {
    y.par_chunks_mut(CHUNK)
        .zip(x.par_chunks(CHUNK))
        .for_each(|(y, x)| {
            for (y, &x) in y.iter_mut().zip(x) {
                *y -= h * x;
            }
        });
}

/// `a·b` in four interleaved partial sums (vectorised; the same order on every run).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let (a4, b4) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = a4
        .remainder()
        .iter()
        .zip(b4.remainder())
        .map(|(x, y)| x * y)
        .sum();
    let mut s = [0.0f64; 4];
    for (x, y) in a4.zip(b4) {
        for l in 0..4 {
            s[l] += x[l] * y[l];
        }
    }
    (s[0] + s[1]) + (s[2] + s[3]) + tail
}

/// The vectors of restarted GMRES, grown to the system's size on first use.
pub(super) struct Gmres {
    basis: Vec<Vec<f64>>,
    hessenberg: Vec<f64>,
    rotations: Vec<(f64, f64)>,
    rhs: Vec<f64>,
    residual: Vec<f64>,
    work: Vec<f64>,
    combined: Vec<f64>,
}

impl Gmres {
    pub(super) fn new() -> Self {
        Self {
            basis: Vec::new(),
            hessenberg: vec![0.0; (RESTART + 1) * RESTART],
            rotations: vec![(0.0, 0.0); RESTART],
            rhs: vec![0.0; RESTART + 1],
            residual: Vec::new(),
            work: Vec::new(),
            combined: Vec::new(),
        }
    }

    /// Solves `A x = b` (`system.apply`) by GMRES right-preconditioned with `tiles`, from
    /// `x = 0`, until the residual's norm falls below `tolerance` of `‖b‖` or `cap`
    /// iterations (restarting every [`RESTART`]); returns the operator products.
    pub(super) fn solve(
        &mut self,
        system: &mut impl Symmetric,
        tiles: &mut impl Preconditioner,
        b: &[f64],
        x: &mut [f64],
        tolerance: f64,
        cap: usize,
    ) -> usize {
        let n = b.len();
        let norm = |v: &[f64]| long_dot(v, v).sqrt();
        x.fill(0.0);
        self.residual.clear();
        self.residual.extend_from_slice(b);
        self.work.resize(n, 0.0);
        self.combined.resize(n, 0.0);
        let b_norm = norm(b);
        if b_norm == 0.0 || !b_norm.is_finite() {
            return 0;
        }
        let target = tolerance * b_norm;
        let mut beta = b_norm;
        let mut products = 0;
        while products < cap {
            let m = self.cycle(system, tiles, beta, target, cap - products);
            products += m;
            self.update(tiles, m, x);
            if self.rhs[m].abs() <= target || products >= cap {
                break;
            }
            // The true residual for the restart: one more product.
            system.apply(x, &mut self.work);
            products += 1;
            for ((r, &bi), &ax) in self.residual.iter_mut().zip(b).zip(&self.work) {
                *r = bi - ax;
            }
            beta = norm(&self.residual);
            if beta <= target || !beta.is_finite() {
                break;
            }
        }
        products
    }

    /// One Arnoldi cycle from the residual (norm `beta`), at most [`RESTART`] and `cap`
    /// steps or until the least-squares residual meets `target`; returns its steps.
    fn cycle(
        &mut self,
        system: &mut impl Symmetric,
        tiles: &mut impl Preconditioner,
        beta: f64,
        target: f64,
        cap: usize,
    ) -> usize {
        let n = self.residual.len();
        if self.basis.len() <= RESTART {
            self.basis.resize_with(RESTART + 1, Vec::new);
        }
        for v in &mut self.basis {
            v.resize(n, 0.0);
        }
        for (v, &r) in self.basis[0].iter_mut().zip(&self.residual) {
            *v = r / beta;
        }
        self.rhs.fill(0.0);
        self.rhs[0] = beta;
        let mut steps = 0;
        for j in 0..RESTART.min(cap) {
            steps = j + 1;
            tiles.apply(&self.basis[j], &mut self.work);
            let (head, tail) = self.basis.split_at_mut(j + 1);
            let next = &mut tail[0];
            system.apply(&self.work, next);
            let col = |i: usize| i * RESTART + j;
            // Modified Gram–Schmidt.
            for (i, v) in head.iter().enumerate() {
                let h = long_dot(next, v);
                self.hessenberg[col(i)] = h;
                axpy(next, h, v);
            }
            let h_next = long_dot(next, next).sqrt();
            self.hessenberg[col(j + 1)] = h_next;
            if h_next > 0.0 {
                for x in next.iter_mut() {
                    *x /= h_next;
                }
            }
            // The earlier rotations on the new column, then its own.
            for i in 0..j {
                let (cs, sn) = self.rotations[i];
                let (a, b) = (self.hessenberg[col(i)], self.hessenberg[col(i + 1)]);
                self.hessenberg[col(i)] = cs * a + sn * b;
                self.hessenberg[col(i + 1)] = -sn * a + cs * b;
            }
            let (a, b) = (self.hessenberg[col(j)], self.hessenberg[col(j + 1)]);
            let r = a.hypot(b);
            let (cs, sn) = if r > 0.0 { (a / r, b / r) } else { (1.0, 0.0) };
            self.rotations[j] = (cs, sn);
            self.hessenberg[col(j)] = r;
            self.hessenberg[col(j + 1)] = 0.0;
            self.rhs[j + 1] = -sn * self.rhs[j];
            self.rhs[j] *= cs;
            if self.rhs[j + 1].abs() <= target || h_next == 0.0 || !r.is_finite() {
                break;
            }
        }
        steps
    }

    /// `x += P V y` with `y` the least-squares solution of the cycle's `m` steps.
    fn update(&mut self, tiles: &mut impl Preconditioner, m: usize, x: &mut [f64]) {
        let mut y = self.rhs[..m].to_vec();
        for i in (0..m).rev() {
            let mut s = y[i];
            for (l, &yl) in y.iter().enumerate().take(m).skip(i + 1) {
                s -= self.hessenberg[i * RESTART + l] * yl;
            }
            let d = self.hessenberg[i * RESTART + i];
            y[i] = if d != 0.0 { s / d } else { 0.0 };
        }
        self.combined.fill(0.0);
        for (v, &yi) in self.basis.iter().zip(&y) {
            for (c, &vi) in self.combined.iter_mut().zip(v) {
                *c += yi * vi;
            }
        }
        tiles.apply(&self.combined, &mut self.work);
        for (xi, &w) in x.iter_mut().zip(&self.work) {
            *xi += w;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::smooth::Symmetric;
    use tack_geometry::{Boundary, Grid};

    /// `K − diag(c)` of a free half-space grid, for the tests.
    struct Newton {
        op: tack_kernels::FreeOperator,
        c: Vec<f64>,
    }

    impl Symmetric for Newton {
        fn apply(&mut self, v: &[f64], out: &mut [f64]) {
            let shape = self.op.grid().shape();
            let vv = ndarray::ArrayView2::from_shape(shape, v).unwrap();
            let o = ndarray::ArrayViewMut2::from_shape(shape, out).unwrap();
            self.op.apply(vv, o);
            for ((o, &vi), &ci) in out.iter_mut().zip(v).zip(&self.c) {
                *o -= ci * vi;
            }
        }
        fn precondition(&mut self, r: &[f64], out: &mut [f64]) {
            out.copy_from_slice(r);
        }
    }

    /// A free grid of `shape` with `c` by element: contact (0), the law's steep part (1.3k to
    /// 3k, softening like the exponential law's at 1.3 elements per process zone) and its
    /// tail (100k and beyond), in a fixed pattern.
    fn newton(shape: (usize, usize)) -> (Newton, f64) {
        let grid = Grid::new(shape.0, shape.1, 0.01, Boundary::Free).unwrap();
        let op = tack_kernels::FreeOperator::new(grid, 1.0).unwrap();
        let k = op.self_compliance();
        let c = (0..shape.0 * shape.1)
            .map(|e| match e % 5 {
                0 | 1 => 0.0,
                2 => 1.3 * k,
                3 => 3.0 * k,
                _ => 1e3 * k,
            })
            .collect();
        (Newton { op, c }, k)
    }

    fn vector(n: usize) -> Vec<f64> {
        (0..n)
            .map(|i| ((i * 7919) % 97) as f64 / 97.0 - 0.4)
            .collect()
    }

    /// On a grid of one tile the preconditioner is the matrix's exact inverse: `P A x = x`.
    #[test]
    fn one_tile_is_the_exact_inverse() {
        let (mut a, k) = newton((TILE, TILE));
        let coef = Coefficients::of(&mut a.op);
        let mut tiles = Tiles::new();
        tiles.build((TILE, TILE), &a.c, k, &coef, 100.0 * k);
        let x = vector(TILE * TILE);
        let (mut ax, mut pax) = (vec![0.0; x.len()], vec![0.0; x.len()]);
        a.apply(&x, &mut ax);
        tiles.apply(&ax, &mut pax);
        for (p, x) in pax.iter().zip(&x) {
            assert!((p - x).abs() <= 1e-10, "{p} against {x}");
        }
    }

    /// GMRES with the tiles solves the Newton matrix of a 23 × 17 grid (partial tiles at two
    /// edges) to its tolerance, against the residual computed afresh, in far fewer
    /// iterations than the grid's elements; with a tolerance it cannot meet in one cycle it
    /// restarts and still converges.
    #[test]
    fn gmres_meets_its_tolerance_with_and_without_restarts() {
        let shape = (23, 17);
        let (mut a, k) = newton(shape);
        let coef = Coefficients::of(&mut a.op);
        let mut tiles = Tiles::new();
        tiles.build(shape, &a.c, k, &coef, 100.0 * k);
        let b = vector(shape.0 * shape.1);
        let b_norm = b.iter().map(|x| x * x).sum::<f64>().sqrt();
        let residual = |a: &mut Newton, x: &[f64]| {
            let mut ax = vec![0.0; x.len()];
            a.apply(x, &mut ax);
            ax.iter()
                .zip(&b)
                .map(|(p, q)| (p - q) * (p - q))
                .sum::<f64>()
                .sqrt()
        };
        let mut gmres = Gmres::new();
        let mut x = vec![0.0; b.len()];
        let products = gmres.solve(&mut a, &mut tiles, &b, &mut x, 1e-8, 2_000);
        assert!(products < 60, "{products} products");
        assert!(residual(&mut a, &x) <= 1.01e-8 * b_norm);
        // An identity preconditioner needs more than one cycle here.
        struct Identity;
        impl Preconditioner for Identity {
            fn apply(&mut self, r: &[f64], out: &mut [f64]) {
                out.copy_from_slice(r);
            }
        }
        let products = gmres.solve(&mut a, &mut Identity, &b, &mut x, 1e-8, 2_000);
        assert!(products > RESTART, "{products} products");
        assert!(residual(&mut a, &x) <= 1.01e-8 * b_norm);
        // A cap stops it.
        assert_eq!(
            gmres.solve(&mut a, &mut Identity, &b, &mut x, 1e-14, 10),
            10
        );
    }

    /// A tile kept while its `c` moves less than [`REUSE`], rebuilt beyond or when an
    /// element joins the contact; a near-singular tile keeps a finite positive scale.
    #[test]
    fn tiles_are_kept_while_they_serve() {
        let shape = (2 * TILE, 2 * TILE);
        let (mut a, k) = newton(shape);
        let coef = Coefficients::of(&mut a.op);
        let mut tiles = Tiles::new();
        let stiff = 100.0 * k;
        tiles.build(shape, &a.c, k, &coef, stiff);
        assert_eq!(tiles.rebuilt, 4);
        let e = 2; // c = 1.3k, in the first tile
        a.c[e] *= 1.05;
        tiles.build(shape, &a.c, k, &coef, stiff);
        assert_eq!(tiles.rebuilt, 4);
        a.c[e] *= 1.2;
        tiles.build(shape, &a.c, k, &coef, stiff);
        assert_eq!(tiles.rebuilt, 5);
        a.c[e] = 0.0;
        tiles.build(shape, &a.c, k, &coef, stiff);
        assert_eq!(tiles.rebuilt, 6);
        // One element at `c = k`: its 1 × 1 matrix `k − c` is singular.
        let single = Grid::new(1, 1, 0.01, Boundary::Free).unwrap();
        let mut op = tack_kernels::FreeOperator::new(single, 1.0).unwrap();
        let coef = Coefficients::of(&mut op);
        let k = op.self_compliance();
        let mut one = Tiles::new();
        one.build((1, 1), &[k], k, &coef, stiff);
        let mut out = [0.0];
        one.apply(&[1.0], &mut out);
        assert!(out[0].is_finite() && out[0] > 0.0, "{}", out[0]);
    }
}
