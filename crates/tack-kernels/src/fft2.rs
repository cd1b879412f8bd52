//! A planned 2D real-to-complex FFT pair with its own scratch: the shared engine of both operators.
//!
//! Rows (the contiguous axis) go through real FFTs; the half spectrum is then transposed so
//! that the complex FFTs along the other axis run on contiguous memory, all columns in one
//! batched rustfft call. Kernels are stored in that transposed layout with the inverse
//! normalisation `1/(mx·my)` folded in, so a convolution is: row r2c, transpose, column FFT,
//! multiply, column inverse FFT, transpose, row c2r. Zero-padded rows are skipped.
//!
//! Threads: rows, columns and transpose blocks are split into contiguous lanes run on the
//! current rayon pool (`rayon::ThreadPool::install` chooses it). Every row and column is
//! transformed by the same plan with the same arithmetic whatever lane it falls in, so the
//! result is bit-identical for any thread count; there are no reductions.

use std::sync::Arc;

use ndarray::{Array2, ArrayView2, ArrayViewMut2};
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
    real: Array2<f64>,
    rows: Vec<Complex<f64>>,
    cols: Vec<Complex<f64>>,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    fwd: Arc<dyn Fft<f64>>,
    inv: Arc<dyn Fft<f64>>,
    /// One row scratch and one column scratch per lane (grown to the pool's thread count).
    scratch: Vec<(Scratch, Scratch)>,
}

/// A transform's scratch buffer.
type Scratch = Vec<Complex<f64>>;

/// Grids with fewer elements than this run on one lane (threads would cost more than they save).
const PARALLEL_MIN: usize = 128 * 128;

impl Fft2 {
    /// Plans the transforms of an `mx × my` real grid.
    pub fn new(mx: usize, my: usize) -> Self {
        let mh = my / 2 + 1;
        let mut real_planner = RealFftPlanner::<f64>::new();
        let r2c = real_planner.plan_fft_forward(my);
        let c2r = real_planner.plan_fft_inverse(my);
        let mut planner = FftPlanner::<f64>::new();
        let fwd = planner.plan_fft_forward(mx);
        let inv = planner.plan_fft_inverse(mx);
        let zero = Complex::new(0.0, 0.0);
        Self {
            mx,
            my,
            mh,
            real: Array2::zeros((mx, my)),
            rows: vec![zero; mx * mh],
            cols: vec![zero; mh * mx],
            r2c,
            c2r,
            fwd,
            inv,
            scratch: Vec::new(),
        }
    }

    /// Number of lanes for this call: the current pool's threads on large grids when called
    /// from inside a rayon pool (`ThreadPool::install`), else one: handing every transform from
    /// an outside thread to the pool and back costs more than it saves. Allocates the lanes'
    /// scratch the first time a pool of that size is seen.
    fn lanes(&mut self) -> usize {
        let inside = rayon::current_thread_index().is_some();
        let lanes = if inside && self.mx * self.my >= PARALLEL_MIN {
            rayon::current_num_threads().clamp(1, self.mh.min(self.mx))
        } else {
            1
        };
        while self.scratch.len() < lanes {
            let zero = Complex::new(0.0, 0.0);
            let rows = self.r2c.get_scratch_len().max(self.c2r.get_scratch_len());
            let cols = self
                .fwd
                .get_inplace_scratch_len()
                .max(self.inv.get_inplace_scratch_len());
            self.scratch.push((vec![zero; rows], vec![zero; cols]));
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
        self.real.assign(&input);
        self.forward(self.mx);
        Array2::from_shape_fn((self.mx, self.mh), |(i, j)| self.cols[j * self.mx + i])
    }

    /// `out = first nx × ny block of ifft(fft(input zero-padded to mx × my) · kernel)`, with
    /// `kernel` from [`Self::prepare_kernel`].
    pub fn convolve(
        &mut self,
        input: ArrayView2<f64>,
        kernel: &[f64],
        mut out: ArrayViewMut2<f64>,
    ) {
        let (nx, ny) = input.dim();
        self.real.slice_mut(ndarray::s![..nx, ..]).fill(0.0);
        self.real.slice_mut(ndarray::s![..nx, ..ny]).assign(&input);
        self.forward(nx);
        let multiply = |c: &mut [Complex<f64>], k: &[f64]| {
            c.iter_mut().zip(k).for_each(|(c, &k)| *c *= k);
        };
        if self.lanes() == 1 {
            multiply(&mut self.cols, kernel);
        } else {
            self.cols
                .par_chunks_mut(self.mx * 64)
                .zip(kernel.par_chunks(self.mx * 64))
                .for_each(|(c, k)| multiply(c, k));
        }
        self.inverse(nx);
        out.assign(&self.real.slice(ndarray::s![..nx, ..ny]));
    }

    /// A forward and an inverse transform of the whole grid with nothing in between and no
    /// rows skipped: the floor every FFT operator pays (for benchmarks).
    pub fn round_trip(&mut self) {
        self.forward(self.mx);
        self.inverse(self.mx);
    }

    /// Spectrum of `self.real` (rows `nx..` taken as zero) into `self.cols`.
    fn forward(&mut self, nx: usize) {
        let (mx, my, mh) = (self.mx, self.my, self.mh);
        let lanes = self.lanes();
        let r2c = &self.r2c;
        let rows_fft = |real: &mut [f64], rows: &mut [Complex<f64>], scratch: &mut Scratch| {
            for (row, out) in real.chunks_exact_mut(my).zip(rows.chunks_exact_mut(mh)) {
                r2c.process_with_scratch(row, out, scratch)
                    .expect("planned lengths");
            }
        };
        let real = &mut self.real.as_slice_mut().expect("standard layout")[..nx * my];
        let rows = &mut self.rows[..nx * mh];
        in_row_bands(real, rows, (my, mh), &mut self.scratch, lanes, rows_fft);
        transpose(&self.rows, &mut self.cols, nx, mh, mx, lanes);
        let fwd = &self.fwd;
        in_column_bands(
            &mut self.cols,
            mx,
            &mut self.scratch,
            lanes,
            |cols, scratch| fwd.process_with_scratch(cols, scratch),
        );
    }

    /// Inverse of `self.cols` into rows `..nx` of `self.real`.
    fn inverse(&mut self, nx: usize) {
        let (mx, mh, my) = (self.mx, self.mh, self.my);
        let lanes = self.lanes();
        let inv = &self.inv;
        in_column_bands(
            &mut self.cols,
            mx,
            &mut self.scratch,
            lanes,
            |cols, scratch| inv.process_with_scratch(cols, scratch),
        );
        transpose(&self.cols, &mut self.rows, mh, mx, mh, lanes);
        let c2r = &self.c2r;
        let rows_ifft = |real: &mut [f64], rows: &mut [Complex<f64>], scratch: &mut Scratch| {
            for (row, spec) in real.chunks_exact_mut(my).zip(rows.chunks_exact_mut(mh)) {
                // A real signal's DC (and even-length Nyquist) bins are real; drop round-off.
                spec[0].im = 0.0;
                if my % 2 == 0 {
                    spec[mh - 1].im = 0.0;
                }
                c2r.process_with_scratch(spec, row, scratch)
                    .expect("planned lengths");
            }
        };
        let real = &mut self.real.as_slice_mut().expect("standard layout")[..nx * my];
        let rows = &mut self.rows[..nx * mh];
        in_row_bands(real, rows, (my, mh), &mut self.scratch, lanes, rows_ifft);
    }
}

/// Runs `f` on the real rows (length `my`) and their half spectra (length `mh`), `(my, mh)`
/// = `row_lengths`, split into `lanes` contiguous bands of whole rows, each with its lane's
/// row scratch; one lane runs on the calling thread.
fn in_row_bands(
    real: &mut [f64],
    rows: &mut [Complex<f64>],
    (my, mh): (usize, usize),
    scratch: &mut [(Scratch, Scratch)],
    lanes: usize,
    f: impl Fn(&mut [f64], &mut [Complex<f64>], &mut Scratch) + Sync,
) {
    if lanes == 1 {
        f(real, rows, &mut scratch[0].0);
    } else {
        let per = (real.len() / my).div_ceil(lanes).max(1);
        real.par_chunks_mut(per * my)
            .zip(rows.par_chunks_mut(per * mh))
            .zip(scratch.par_iter_mut())
            .for_each(|((real, rows), (scratch, _))| f(real, rows, scratch));
    }
}

/// Runs `f` on the columns (each `mx` entries, stored one after another in `cols`) split into
/// `lanes` contiguous bands of whole columns, each with its lane's column scratch; one lane
/// runs on the calling thread.
fn in_column_bands(
    cols: &mut [Complex<f64>],
    mx: usize,
    scratch: &mut [(Scratch, Scratch)],
    lanes: usize,
    f: impl Fn(&mut [Complex<f64>], &mut Scratch) + Sync,
) {
    if lanes == 1 {
        f(cols, &mut scratch[0].1);
    } else {
        let per = (cols.len() / mx).div_ceil(lanes);
        cols.par_chunks_mut(per * mx)
            .zip(scratch.par_iter_mut())
            .for_each(|(cols, (_, scratch))| f(cols, scratch));
    }
}

/// Writes the transpose of the first `rows` rows of the row-major `src` (row length `cols`)
/// into `dst` (row length `dst_stride`), zero-filling `dst` columns `rows..dst_stride`. The
/// destination rows are split into `lanes` contiguous bands written in parallel (pure copies).
fn transpose(
    src: &[Complex<f64>],
    dst: &mut [Complex<f64>],
    rows: usize,
    cols: usize,
    dst_stride: usize,
    lanes: usize,
) {
    let per = cols.div_ceil(lanes).div_ceil(BLOCK).max(1) * BLOCK;
    let band_copy = |band: usize, dst: &mut [Complex<f64>]| {
        let first = band * per;
        let last = (first + per).min(cols);
        for j0 in (first..last).step_by(BLOCK) {
            for i0 in (0..rows).step_by(BLOCK) {
                for j in j0..(j0 + BLOCK).min(last) {
                    let d = &mut dst[(j - first) * dst_stride..];
                    for i in i0..(i0 + BLOCK).min(rows) {
                        d[i] = src[i * cols + j];
                    }
                }
            }
            for j in j0..(j0 + BLOCK).min(last) {
                let k = j - first;
                dst[k * dst_stride + rows..(k + 1) * dst_stride].fill(Complex::new(0.0, 0.0));
            }
        }
    };
    let dst = &mut dst[..cols * dst_stride];
    if lanes == 1 {
        band_copy(0, dst);
    } else {
        dst.par_chunks_mut(per * dst_stride)
            .enumerate()
            .for_each(|(band, dst)| band_copy(band, dst));
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
