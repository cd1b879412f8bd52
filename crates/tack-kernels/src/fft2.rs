//! A planned 2D real-to-complex FFT pair with its own scratch: the shared engine of both operators.
//!
//! Rows (the contiguous axis) go through real FFTs; the half spectrum is then transposed so
//! that the complex FFTs along the other axis run on contiguous memory, all columns in one
//! batched rustfft call. Kernels are stored in that transposed layout with the inverse
//! normalisation `1/(mx·my)` folded in, so a convolution is: row r2c; then, per block of
//! columns while it is in cache, gather (transpose), column FFT, multiply, column inverse FFT;
//! then gather the rows and row c2r. Zero-padded rows are skipped on the way in, and only the
//! rows wanted are gathered and transformed on the way out.
//!
//! Threads: each of the three regions splits its rows or columns into contiguous bands (4 per
//! thread, so a thread that starts late takes fewer) run on the current rayon pool
//! (`rayon::ThreadPool::install` chooses it). Every row and column is transformed by the same
//! plan with the same arithmetic whatever band it falls in, so the result is bit-identical for
//! any thread count; there are no reductions.
//!
//! Plans: every `Fft2` of the process takes its plans from one table by length ([`planned`]), so
//! operators of the same lengths (a run's free operator and its preconditioner, the sub-grid
//! operators of many sizes, the runs of a sweep) share plans and twiddle tables instead of
//! planning again. Each length is planned by planners of its own, made for it: a RustFFT
//! planner builds a length on the lengths it has cached, so one planner shared by the process
//! gave a length's transform other bits after other lengths had been planned (1152 after 288,
//! 2304 after 288 or 1152), and a run's result depended on what the process had run before, or
//! on which run of a sweep planned first. A plan's algorithm thus depends on its length and the
//! CPU's instruction set only, and a shared plan is only read by `process_with_scratch` (the
//! scratch is each lane's own), so sharing changes no bit.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use ndarray::parallel::prelude::*;
use ndarray::{Array2, ArrayView2, ArrayViewMut2, Axis};
use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

/// Side of the square blocks of the cache-friendly transposes.
const BLOCK: usize = 32;

/// Cyclic convolution with fixed kernels on an `mx × my` real grid. Plans and buffers are made
/// once; `convolve` allocates nothing.
pub struct Fft2 {
    mx: usize,
    my: usize,
    mh: usize,
    /// Half spectra of the rows, row after row (`mx × mh`; rows `..nx` in use).
    rows: Vec<Complex<f64>>,
    /// The same, column after column (`mh × mx`).
    cols: Vec<Complex<f64>>,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    fwd: Arc<dyn Fft<f64>>,
    inv: Arc<dyn Fft<f64>>,
    /// Scratch of each lane (grown to the pool's thread count).
    lanes: Vec<Lane>,
}

/// One lane's scratch: a real row, and the row and column transforms' scratch.
struct Lane {
    real: Vec<f64>,
    row: Vec<Complex<f64>>,
    col: Vec<Complex<f64>>,
}

/// Bands per thread of a parallel region: a thread that starts late (woken from sleep) takes
/// fewer bands instead of holding the region up.
const BANDS_PER_THREAD: usize = 4;

/// Grids with fewer elements than this run on one lane (threads would cost more than they save).
const PARALLEL_MIN: usize = 64 * 64;

/// A row length's real transforms `(r2c, c2r)`.
type RowPlans = (Arc<dyn RealToComplex<f64>>, Arc<dyn ComplexToReal<f64>>);
/// A column length's complex transforms `(forward, inverse)`.
type ColumnPlans = (Arc<dyn Fft<f64>>, Arc<dyn Fft<f64>>);

/// The plans every [`Fft2`] of the process takes: real transforms of the rows and complex ones
/// of the columns, by length, each length planned once per process by planners made for it
/// (module docs; the table holds a few twiddle tables per length, a small fraction of an
/// operator of that length).
#[derive(Default)]
struct Plans {
    rows: HashMap<usize, RowPlans>,
    columns: HashMap<usize, ColumnPlans>,
}

/// The plans of an `mx × my` real grid from the process's [`Plans`]: `(r2c, c2r)` of the
/// rows (length `my`) and `(forward, inverse)` of the columns (length `mx`).
fn planned(mx: usize, my: usize) -> (RowPlans, ColumnPlans) {
    static PLANS: OnceLock<Mutex<Plans>> = OnceLock::new();
    let plans = PLANS.get_or_init(Mutex::default);
    // A panic while planning leaves the table as it was before the failed length: still
    // valid, so a poisoned lock is taken over.
    let mut p = plans
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    let rows = p.rows.entry(my).or_insert_with(|| fresh_rows(my)).clone();
    let columns = p
        .columns
        .entry(mx)
        .or_insert_with(|| fresh_columns(mx))
        .clone();
    (rows, columns)
}

/// The real transforms of rows of length `my`, from a planner made for them.
fn fresh_rows(my: usize) -> RowPlans {
    let mut real = RealFftPlanner::<f64>::new();
    (real.plan_fft_forward(my), real.plan_fft_inverse(my))
}

/// The complex transforms of columns of length `mx`, from a planner made for them.
fn fresh_columns(mx: usize) -> ColumnPlans {
    let mut complex = FftPlanner::<f64>::new();
    (complex.plan_fft_forward(mx), complex.plan_fft_inverse(mx))
}

impl Fft2 {
    /// Plans the transforms of an `mx × my` real grid (plans of lengths planned before in this
    /// process are reused, module docs).
    pub fn new(mx: usize, my: usize) -> Self {
        Self::with_plans(mx, my, planned(mx, my))
    }

    /// An `mx × my` grid's transforms with the given plans (`(r2c, c2r)` of length `my`,
    /// `(forward, inverse)` of length `mx`).
    fn with_plans(mx: usize, my: usize, ((r2c, c2r), (fwd, inv)): (RowPlans, ColumnPlans)) -> Self {
        let mh = my / 2 + 1;
        let zero = Complex::new(0.0, 0.0);
        Self {
            mx,
            my,
            mh,
            rows: vec![zero; mx * mh],
            cols: vec![zero; mh * mx],
            r2c,
            c2r,
            fwd,
            inv,
            lanes: Vec::new(),
        }
    }

    /// Number of lanes for this call: the current pool's threads on large grids when called
    /// from inside a rayon pool (`ThreadPool::install`), else one: handing every transform from
    /// an outside thread to the pool and back costs more than it saves. Allocates the lanes'
    /// scratch the first time a pool of that size is seen.
    fn lanes(&mut self) -> usize {
        let inside = rayon::current_thread_index().is_some();
        let threads = rayon::current_num_threads();
        let lanes = if inside && threads > 1 && self.mx * self.my >= PARALLEL_MIN {
            (BANDS_PER_THREAD * threads).clamp(1, self.mh.min(self.mx))
        } else {
            1
        };
        while self.lanes.len() < lanes {
            let zero = Complex::new(0.0, 0.0);
            let row = self.r2c.get_scratch_len().max(self.c2r.get_scratch_len());
            let col = self
                .fwd
                .get_inplace_scratch_len()
                .max(self.inv.get_inplace_scratch_len());
            self.lanes.push(Lane {
                real: vec![0.0; self.my],
                row: vec![zero; row],
                col: vec![zero; col],
            });
        }
        lanes
    }

    /// Size of the real grid, `(mx, my)`.
    pub fn dim(&self) -> (usize, usize) {
        (self.mx, self.my)
    }

    /// Turns a real-valued spectrum given in natural layout `(mx, my/2 + 1)` (index `(kx, ky)`)
    /// into a kernel for [`Self::convolve`]: transposed, with the inverse normalisation folded in.
    pub fn prepare_kernel(&self, spectrum: &Array2<f64>) -> Vec<f64> {
        assert_eq!(spectrum.dim(), (self.mx, self.mh), "kernel spectrum shape");
        let norm = 1.0 / (self.mx * self.my) as f64;
        let mut k = vec![0.0; self.mh * self.mx];
        for ((i, j), &v) in spectrum.indexed_iter() {
            k[j * self.mx + i] = v * norm;
        }
        k
    }

    /// Unnormalised spectrum of a full-size real array, natural layout `(mx, my/2 + 1)`.
    pub fn transform(&mut self, input: ArrayView2<f64>) -> Array2<Complex<f64>> {
        assert_eq!(input.dim(), (self.mx, self.my), "transform input shape");
        let lanes = self.lanes();
        self.rows_forward(input, lanes);
        self.columns(self.mx, lanes, |block, fwd, _, _, scratch| {
            fwd.process_with_scratch(block, scratch)
        });
        Array2::from_shape_fn((self.mx, self.mh), |(i, j)| self.cols[j * self.mx + i])
    }

    /// `out = first nx × ny block of ifft(fft(input zero-padded to mx × my) · kernel)`, with
    /// `kernel` from [`Self::prepare_kernel`]; `out` has the shape of `input`.
    pub fn convolve(&mut self, input: ArrayView2<f64>, kernel: &[f64], out: ArrayViewMut2<f64>) {
        let (nx, ny) = input.dim();
        assert!(nx <= self.mx && ny <= self.my, "input larger than the grid");
        assert_eq!(out.dim(), (nx, ny), "output shape");
        assert_eq!(
            kernel.len(),
            self.mh * self.mx,
            "kernel from prepare_kernel"
        );
        let (mx, lanes) = (self.mx, self.lanes());
        self.rows_forward(input, lanes);
        // Per block of columns while it is in cache: forward FFT, kernel, inverse FFT.
        self.columns(nx, lanes, |block, fwd, inv, j0, scratch| {
            fwd.process_with_scratch(block, scratch);
            let k = &kernel[j0 * mx..j0 * mx + block.len()];
            block.iter_mut().zip(k).for_each(|(c, &k)| *c *= k);
            inv.process_with_scratch(block, scratch);
        });
        self.rows_inverse(nx, Some(out), lanes);
    }

    /// A forward and an inverse transform of the whole grid with nothing in between and no
    /// rows skipped: the floor every FFT operator pays (for benchmarks). The real rows are
    /// zeros, and the inverse's rows are computed and dropped.
    pub fn round_trip(&mut self) {
        let lanes = self.lanes();
        let zeros = Array2::zeros((0, 0));
        self.rows_forward_with(self.mx, zeros.view(), lanes);
        self.columns(self.mx, lanes, |block, fwd, inv, _, scratch| {
            fwd.process_with_scratch(block, scratch);
            inv.process_with_scratch(block, scratch);
        });
        self.rows_inverse(self.mx, None, lanes);
    }

    /// Half spectra of the rows of `input` (zero-padded to `my`) into rows `..nx` of `rows`.
    fn rows_forward(&mut self, input: ArrayView2<f64>, lanes: usize) {
        self.rows_forward_with(input.nrows(), input, lanes);
    }

    /// Rows `..nx` of `rows` from the rows of `input` zero-padded to `my` (rows of `input`
    /// beyond its own taken as zero).
    fn rows_forward_with(&mut self, nx: usize, input: ArrayView2<f64>, lanes: usize) {
        let mh = self.mh;
        let r2c = &self.r2c;
        let band = |first: usize, rows: &mut [Complex<f64>], lane: &mut Lane| {
            for (k, spec) in rows.chunks_exact_mut(mh).enumerate() {
                let i = first + k;
                let real = &mut lane.real;
                let filled = if i < input.nrows() {
                    let row = input.row(i);
                    real.iter_mut().zip(row).for_each(|(r, &v)| *r = v);
                    row.len()
                } else {
                    0
                };
                real[filled..].fill(0.0);
                r2c.process_with_scratch(real, spec, &mut lane.row)
                    .expect("planned lengths");
            }
        };
        let rows = &mut self.rows[..nx * mh];
        if lanes == 1 {
            band(0, rows, &mut self.lanes[0]);
        } else {
            let per = nx.div_ceil(lanes).max(1);
            rows.par_chunks_mut(per * mh)
                .zip(self.lanes.par_iter_mut())
                .enumerate()
                .for_each(|(b, (rows, lane))| band(b * per, rows, lane));
        }
    }

    /// Each lane takes its band of columns and, block by block, gathers them from rows `..nx`
    /// of `rows` (zero below) and runs `f(block, forward plan, inverse plan, first column,
    /// scratch)` on them while they are in cache.
    fn columns(
        &mut self,
        nx: usize,
        lanes: usize,
        f: impl Fn(&mut [Complex<f64>], &dyn Fft<f64>, &dyn Fft<f64>, usize, &mut Vec<Complex<f64>>)
        + Sync,
    ) {
        let (mx, mh) = (self.mx, self.mh);
        let (fwd, inv, rows) = (self.fwd.as_ref(), self.inv.as_ref(), &self.rows);
        let band = |first: usize, cols: &mut [Complex<f64>], scratch: &mut Vec<Complex<f64>>| {
            for (b, block) in cols.chunks_mut(BLOCK * mx).enumerate() {
                let j0 = first + b * BLOCK;
                gather_columns(rows, block, nx, mh, mx, j0);
                f(block, fwd, inv, j0, scratch);
            }
        };
        if lanes == 1 {
            band(0, &mut self.cols, &mut self.lanes[0].col);
        } else {
            let per = mh.div_ceil(lanes);
            self.cols
                .par_chunks_mut(per * mx)
                .zip(self.lanes.par_iter_mut())
                .enumerate()
                .for_each(|(b, (cols, lane))| band(b * per, cols, &mut lane.col));
        }
    }

    /// Rows `..nx` of the inverse: each lane gathers its band of rows from `cols`, runs the
    /// inverse real FFTs and writes each row's first `out.ncols()` values to `out` (dropped
    /// without one).
    fn rows_inverse(&mut self, nx: usize, out: Option<ArrayViewMut2<f64>>, lanes: usize) {
        let (mx, my, mh) = (self.mx, self.my, self.mh);
        let (c2r, cols) = (&self.c2r, &self.cols);
        let band = |first: usize,
                    rows: &mut [Complex<f64>],
                    mut out: Option<ArrayViewMut2<f64>>,
                    lane: &mut Lane| {
            gather_rows(cols, rows, mx, mh, first);
            for (k, spec) in rows.chunks_exact_mut(mh).enumerate() {
                // A real signal's DC (and even-length Nyquist) bins are real; drop round-off.
                spec[0].im = 0.0;
                if my % 2 == 0 {
                    spec[mh - 1].im = 0.0;
                }
                c2r.process_with_scratch(spec, &mut lane.real, &mut lane.row)
                    .expect("planned lengths");
                if let Some(out) = out.as_mut() {
                    out.row_mut(k)
                        .iter_mut()
                        .zip(&lane.real)
                        .for_each(|(o, &v)| *o = v);
                }
            }
        };
        let rows = &mut self.rows[..nx * mh];
        if lanes == 1 {
            band(0, rows, out, &mut self.lanes[0]);
            return;
        }
        let per = nx.div_ceil(lanes).max(1);
        match out {
            Some(mut out) => out
                .axis_chunks_iter_mut(Axis(0), per)
                .into_par_iter()
                .zip(rows.par_chunks_mut(per * mh))
                .zip(self.lanes.par_iter_mut())
                .enumerate()
                .for_each(|(b, ((out, rows), lane))| band(b * per, rows, Some(out), lane)),
            None => rows
                .par_chunks_mut(per * mh)
                .zip(self.lanes.par_iter_mut())
                .enumerate()
                .for_each(|(b, (rows, lane))| band(b * per, rows, None, lane)),
        }
    }
}

/// Fills `block` (whole columns of length `mx`, the first being column `j0`) from the first
/// `nx` rows of the row-major `rows` (row length `mh`), zero below row `nx`.
fn gather_columns(
    rows: &[Complex<f64>],
    block: &mut [Complex<f64>],
    nx: usize,
    mh: usize,
    mx: usize,
    j0: usize,
) {
    gather(rows, mh, j0, block, mx, nx);
    for col in block.chunks_exact_mut(mx) {
        col[nx..].fill(Complex::new(0.0, 0.0));
    }
}

/// Fills `rows` (whole rows of length `mh`, the first being row `first`) from the columns
/// stored one after another in `cols` (column length `mx`).
fn gather_rows(
    cols: &[Complex<f64>],
    rows: &mut [Complex<f64>],
    mx: usize,
    mh: usize,
    first: usize,
) {
    gather(cols, mx, first, rows, mh, mh);
}

/// A blocked transpose: line `k` of `dst` (lines `dst_stride` apart) gets, at `i < len`, entry
/// `first + k` of line `i` of `src` (lines `src_stride` apart), for every line of `dst`.
fn gather(
    src: &[Complex<f64>],
    src_stride: usize,
    first: usize,
    dst: &mut [Complex<f64>],
    dst_stride: usize,
    len: usize,
) {
    let lines = dst.len() / dst_stride;
    for i0 in (0..len).step_by(BLOCK) {
        for k in 0..lines {
            let line = &mut dst[k * dst_stride..];
            for i in i0..(i0 + BLOCK).min(len) {
                line[i] = src[i * src_stride + first + k];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identity_kernel_round_trips_with_padding() {
        for (mx, my, nx, ny) in [(8, 6, 3, 2), (5, 1, 5, 1), (12, 10, 12, 10), (2, 2, 1, 1)] {
            let mut f = Fft2::new(mx, my);
            let ones = Array2::from_elem((mx, my / 2 + 1), 1.0);
            let k = f.prepare_kernel(&ones);
            let input = Array2::from_shape_fn((nx, ny), |(i, j)| (i * 3 + j) as f64 - 2.5);
            let mut out = Array2::zeros((nx, ny));
            f.convolve(input.view(), &k, out.view_mut());
            let err = (&out - &input).iter().fold(0.0f64, |m, v| m.max(v.abs()));
            assert!(err < 1e-13, "{mx}x{my}: {err}");
        }
    }

    /// The convolution of a fixed input and kernel on `f` (an `mx × my` grid, input `nx × ny`).
    fn convolved(f: &mut Fft2, nx: usize, ny: usize) -> Array2<f64> {
        let (mx, my) = f.dim();
        let input = Array2::from_shape_fn((nx, ny), |(i, j)| ((i * 7 + j * 13) % 17) as f64 - 8.3);
        let spectrum =
            Array2::from_shape_fn((mx, my / 2 + 1), |(i, j)| 1.0 / (1.0 + (i + 2 * j) as f64));
        let k = f.prepare_kernel(&spectrum);
        let mut out = Array2::zeros((nx, ny));
        f.convolve(input.view(), &k, out.view_mut());
        out
    }

    #[test]
    fn shared_plans_are_reused_and_give_the_bits_of_fresh_planners() {
        // Other lengths planned first, from several threads at once, in no set order; among
        // them 288 and 576, on which one shared RustFFT planner built 1152 and 2304 otherwise
        // (other bits).
        std::thread::scope(|scope| {
            for t in 0..3 {
                scope.spawn(move || {
                    for m in [48, 90, 100, 126, 150, 180, 250, 288] {
                        Fft2::new(m + t, 2 * m);
                    }
                });
            }
        });
        for (mx, my) in [(180, 250), (1152, 2304)] {
            let (a, b) = (Fft2::new(mx, my), Fft2::new(mx, my));
            assert!(Arc::ptr_eq(&a.fwd, &b.fwd) && Arc::ptr_eq(&a.inv, &b.inv));
            assert!(Arc::ptr_eq(&a.r2c, &b.r2c) && Arc::ptr_eq(&a.c2r, &b.c2r));
            let mut real = RealFftPlanner::<f64>::new();
            let mut complex = FftPlanner::<f64>::new();
            let fresh_plans = (
                (real.plan_fft_forward(my), real.plan_fft_inverse(my)),
                (complex.plan_fft_forward(mx), complex.plan_fft_inverse(mx)),
            );
            let mut fresh = Fft2::with_plans(mx, my, fresh_plans);
            let mut shared = a;
            let (x, y) = (
                convolved(&mut fresh, mx / 2, my / 2),
                convolved(&mut shared, mx / 2, my / 2),
            );
            assert!(x.iter().any(|v| *v != 0.0));
            assert!(
                x.iter().zip(&y).all(|(p, q)| p.to_bits() == q.to_bits()),
                "{mx} x {my}"
            );
        }
    }

    /// RustFFT's own planner builds a length on the lengths it has cached: the reason
    /// [`planned`] plans every length with planners of its own. If a RustFFT release stops
    /// doing so this test fails, and the table could go back to one shared planner.
    #[test]
    fn a_shared_rustfft_planner_changes_a_lengths_bits() {
        let signal = |n: usize| -> Vec<Complex<f64>> {
            (0..n)
                .map(|i| Complex::new(((i * 7919) % 1000) as f64 / 997.0, (i % 101) as f64))
                .collect()
        };
        let mut fresh = signal(1152);
        FftPlanner::<f64>::new()
            .plan_fft_forward(1152)
            .process(&mut fresh);
        let mut shared = FftPlanner::<f64>::new();
        shared.plan_fft_forward(288);
        let mut after = signal(1152);
        shared.plan_fft_forward(1152).process(&mut after);
        let same = fresh
            .iter()
            .zip(&after)
            .all(|(a, b)| a.re.to_bits() == b.re.to_bits() && a.im.to_bits() == b.im.to_bits());
        let close = fresh
            .iter()
            .zip(&after)
            .all(|(a, b)| (a - b).norm() <= 1e-9 * (1.0 + a.norm()));
        assert!(close && !same);
    }

    #[test]
    fn any_thread_count_gives_the_same_bits() {
        // Odd and even sizes above the parallel threshold; 1, 2 and 3 lanes split the rows
        // and columns differently, and every bit must agree.
        for (mx, my, nx, ny) in [(256, 256, 200, 256), (270, 135, 270, 135)] {
            let input =
                Array2::from_shape_fn((nx, ny), |(i, j)| ((i * 7 + j * 13) % 17) as f64 - 8.3);
            let spectrum =
                Array2::from_shape_fn((mx, my / 2 + 1), |(i, j)| 1.0 / (1.0 + (i + 2 * j) as f64));
            let run = |threads: usize| {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                pool.install(|| {
                    let mut f = Fft2::new(mx, my);
                    let k = f.prepare_kernel(&spectrum);
                    let mut out = Array2::zeros((nx, ny));
                    f.convolve(input.view(), &k, out.view_mut());
                    out
                })
            };
            let one = run(1);
            assert!(one.iter().any(|v| *v != 0.0));
            for threads in [2, 3] {
                let other = run(threads);
                assert!(
                    one.iter()
                        .zip(&other)
                        .all(|(a, b)| a.to_bits() == b.to_bits()),
                    "{mx}x{my}: {threads} threads differ"
                );
            }
        }
    }
}
