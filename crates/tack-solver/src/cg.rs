//! Preconditioned conjugate gradients for the bonded-set problem `K_CC p_C = (d − f)_C`.

use ndarray::{Array2, ArrayView2, ArrayViewMut2, Zip};
use tack_kernels::ElasticOperator;

use crate::SolverOptions;

/// CG vectors on one grid; `disp = K p` is kept up to date.
pub(crate) struct Work {
    pub(crate) disp: Array2<f64>,
    resid: Array2<f64>,
    dir: Array2<f64>,
    kdir: Array2<f64>,
    zres: Array2<f64>,
}

impl Work {
    pub(crate) fn new(shape: (usize, usize)) -> Self {
        let z = Array2::zeros(shape);
        Self {
            disp: z.clone(),
            resid: z.clone(),
            dir: z.clone(),
            kdir: z.clone(),
            zres: z,
        }
    }
}

/// Solves `K_CC p_C = (d − f)_C` (`p = 0` off the bonded set `C`), warm-started from `pressure`,
/// with the masked spectral preconditioner when `preconditioned`. Converged when the rms
/// residual over `C` is below `tolerance` times the rms right-hand side (floored at 1e-3 of
/// the height range over `C`). Returns (iterations, relative residual, converged).
#[allow(clippy::too_many_arguments)]
pub(crate) fn pcg(
    op: &mut dyn ElasticOperator,
    heights: ArrayView2<f64>,
    bonded: ArrayView2<bool>,
    d: f64,
    mut pressure: ArrayViewMut2<f64>,
    w: &mut Work,
    options: &SolverOptions,
    preconditioned: bool,
) -> (usize, f64, bool) {
    Zip::from(&mut pressure).and(&bonded).for_each(|p, &b| {
        if !b {
            *p = 0.0
        }
    });
    let (mut n_c, mut b2, mut fmax, mut fmin) = (0usize, 0.0, f64::NEG_INFINITY, f64::INFINITY);
    Zip::from(&heights).and(&bonded).for_each(|&f, &b| {
        if b {
            n_c += 1;
            b2 += (d - f) * (d - f);
            fmax = fmax.max(f);
            fmin = fmin.min(f);
        }
    });
    let scale = (b2 / n_c as f64)
        .sqrt()
        .max(1e-3 * (fmax - fmin))
        .max(f64::MIN_POSITIVE);
    let target = (options.tolerance * scale).powi(2) * n_c as f64;
    let max_it = options.max_iterations;
    let mut it = 0;
    // The true residual is recomputed from `K p` at every (re)start; inside the loop `disp` is
    // carried along (`disp += α K s`), so a converged solve needs no further product.
    op.apply(pressure.view(), w.disp.view_mut());
    loop {
        let mut rr = 0.0;
        Zip::from(&mut w.resid)
            .and(&heights)
            .and(&w.disp)
            .and(&bonded)
            .for_each(|r, &f, &u, &b| {
                *r = if b { d - f - u } else { 0.0 };
                rr += *r * *r;
            });
        let rel = (rr / n_c as f64).sqrt() / scale;
        if rr <= target {
            return (it, rel, true);
        }
        if it >= max_it {
            return (it, rel, false);
        }
        let mut rz = precondition(op, w, bonded, preconditioned);
        w.dir.assign(&w.zres);
        while it < max_it {
            it += 1;
            op.apply(w.dir.view(), w.kdir.view_mut());
            let mut sq = 0.0;
            Zip::from(&w.dir)
                .and(&w.kdir)
                .and(&bonded)
                .for_each(|&s, &q, &b| {
                    if b {
                        sq += s * q
                    }
                });
            let alpha = rz / sq;
            let mut rr_new = 0.0;
            Zip::from(&mut pressure)
                .and(&mut w.resid)
                .and(&mut w.disp)
                .and(&w.dir)
                .and(&w.kdir)
                .and(&bonded)
                .for_each(|p, r, u, &s, &q, &b| {
                    *u += alpha * q;
                    if b {
                        *p += alpha * s;
                        *r -= alpha * q;
                        rr_new += *r * *r;
                    }
                });
            if rr_new <= target {
                break;
            }
            let rz_new = precondition(op, w, bonded, preconditioned);
            let beta = rz_new / rz;
            rz = rz_new;
            Zip::from(&mut w.dir)
                .and(&w.zres)
                .for_each(|s, &z| *s = z + beta * *s);
            if it % REFRESH == 0 {
                // Long runs: refresh `K p` so round-off in the carried product cannot build up.
                op.apply(pressure.view(), w.disp.view_mut());
            }
        }
        if it >= max_it {
            op.apply(pressure.view(), w.disp.view_mut());
        }
    }
}

/// Iterations between refreshes of the carried product `K p` in long solves.
const REFRESH: usize = 200;

/// `z = P_C M r` (or `z = r` without preconditioning); returns `r·z`.
fn precondition(
    op: &mut dyn ElasticOperator,
    w: &mut Work,
    bonded: ArrayView2<bool>,
    on: bool,
) -> f64 {
    if on {
        op.precondition(w.resid.view(), w.zres.view_mut());
    } else {
        w.zres.assign(&w.resid);
    }
    let mut rz = 0.0;
    Zip::from(&mut w.zres)
        .and(&w.resid)
        .and(&bonded)
        .for_each(|z, &r, &b| {
            if b {
                rz += r * *z;
            } else {
                *z = 0.0;
            }
        });
    rz
}
