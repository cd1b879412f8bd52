//! A planned 2D real-to-complex FFT pair with its own scratch: the shared engine of both operators.

use ndarray::{Array2, ArrayView2, ArrayViewMut2, Zip};
use ndrustfft::{Complex, FftHandler, R2cFftHandler, ndfft, ndfft_r2c, ndifft, ndifft_r2c};

/// Cyclic convolution with a fixed kernel on an `mx × my` real grid via r2c FFTs.
///
/// The real transform runs along the contiguous second axis (`my → my/2 + 1`), the complex one
/// along the first. Plans and buffers are made once.
pub(crate) struct Fft2 {
    /// Real-space work array, `mx × my`.
    pub(crate) real: Array2<f64>,
    spec: Array2<Complex<f64>>,
    spec2: Array2<Complex<f64>>,
    r2c: R2cFftHandler<f64>,
    c2c: FftHandler<f64>,
}

impl Fft2 {
    pub(crate) fn new(mx: usize, my: usize) -> Self {
        Self {
            real: Array2::zeros((mx, my)),
            spec: Array2::zeros((mx, my / 2 + 1)),
            spec2: Array2::zeros((mx, my / 2 + 1)),
            r2c: R2cFftHandler::new(my),
            c2c: FftHandler::new(mx),
        }
    }

    /// Forward transform of `self.real` (unnormalised); the spectrum is returned by reference.
    pub(crate) fn forward(&mut self) -> &mut Array2<Complex<f64>> {
        ndfft_r2c(&self.real, &mut self.spec, &self.r2c, 1);
        ndfft(&self.spec, &mut self.spec2, &self.c2c, 0);
        &mut self.spec2
    }

    /// Inverse transform (normalised by `1/(mx·my)`) of the spectrum left by [`Self::forward`]
    /// into `self.real`.
    pub(crate) fn inverse(&mut self) {
        ndifft(&self.spec2, &mut self.spec, &self.c2c, 0);
        ndifft_r2c(&self.spec, &mut self.real, &self.r2c, 1);
    }

    /// Spectrum of a real array of this size (used once, to transform a kernel).
    pub(crate) fn transform(&mut self, input: ArrayView2<f64>) -> Array2<Complex<f64>> {
        self.real.assign(&input);
        self.forward().clone()
    }

    /// `out = first block of ifft(fft(input zero-padded) · kernel)`, the core of `apply`.
    /// `kernel` must have [`Self::spectrum_dim`].
    pub(crate) fn convolve(
        &mut self,
        input: ArrayView2<f64>,
        kernel: &Array2<f64>,
        mut out: ArrayViewMut2<f64>,
    ) {
        let (nx, ny) = input.dim();
        self.real.fill(0.0);
        self.real.slice_mut(ndarray::s![..nx, ..ny]).assign(&input);
        let spec = self.forward();
        Zip::from(spec).and(kernel).for_each(|s, &k| *s *= k);
        self.inverse();
        out.assign(&self.real.slice(ndarray::s![..nx, ..ny]));
    }
}
