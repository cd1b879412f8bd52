//! Conjugate-gradient building blocks: the CG vectors both solvers allocate once ([`Work`]) and
//! the preconditioned CG for the bonded-set problem `K_CC p_C = (d − f)_C` of the adhesive
//! solver ([`pcg`]). The non-adhesive solver's constrained CG (Polonsky–Keer) projects onto
//! `p ≥ 0` inside its iteration and lives in `contact.rs`.

use ndarray::{Array2, ArrayView2, ArrayViewMut2, Zip};
use tack_kernels::ElasticOperator;

use crate::SolverOptions;
use crate::state::Convergence;

/// The CG vectors on one grid, allocated once: `disp = K p` (kept up to date by the iterations
/// that own it), the search direction `dir` and its image `kdir = K dir`.
pub(crate) struct Work {
    pub(crate) disp: Array2<f64>,
    pub(crate) dir: Array2<f64>,
    pub(crate) kdir: Array2<f64>,
}

impl Work {
    pub(crate) fn new(shape: (usize, usize)) -> Self {
        let z = Array2::zeros(shape);
        Self {
            disp: z.clone(),
            dir: z.clone(),
            kdir: z,
        }
    }
}

/// The two further vectors of the preconditioned CG: the residual and its preconditioned image.
pub(crate) struct PcgWork {
    resid: Array2<f64>,
    zres: Array2<f64>,
    /// `r·z` of the last iteration of the last solve on these vectors, while its search
    /// direction (`Work::dir`) and state stand: a `carried` solve continues that iteration.
    rz: Option<f64>,
}

impl PcgWork {
    pub(crate) fn new(shape: (usize, usize)) -> Self {
        let z = Array2::zeros(shape);
        Self {
            resid: z.clone(),
            zres: z,
            rz: None,
        }
    }
}

/// Elements per chunk of the vector loops. Sums are taken per chunk, in element order, and the
/// chunk sums are added in chunk order: the partition depends on the length only, so the bits
/// are the same whether chunks run on one thread or several.
const CHUNK: usize = 8192;

/// Vectors shorter than this run their chunks on the calling thread.
const PARALLEL_MIN: usize = 64 * 64;

/// Whether vectors of `len` elements run their chunks in parallel: long ones, and only inside
/// a rayon pool (a hand-off from an outside thread per loop costs more than it saves).
pub(crate) fn parallel(len: usize) -> bool {
    len >= PARALLEL_MIN && rayon::current_thread_index().is_some()
}

/// `dst = src` element by element, in parallel on long arrays (a copy: the same bits either way).
pub(crate) fn assign<T: Copy + Send + Sync>(dst: ArrayViewMut2<T>, src: ArrayView2<T>) {
    let zip = Zip::from(dst).and(src);
    if parallel(zip.size()) {
        zip.par_for_each(|a, &b| *a = b);
    } else {
        zip.for_each(|a, &b| *a = b);
    }
}

/// Sums `f` over the chunks of `0..len` (see [`CHUNK`]), in parallel on the current rayon pool
/// when the vectors are long, always in the same order.
fn chunk_sum(len: usize, f: impl Fn(std::ops::Range<usize>) -> f64 + Sync) -> f64 {
    chunk_sum_by(len, CHUNK, f)
}

/// [`chunk_sum`] over chunks of `chunk` elements (GMRES's vectors take their own size; the
/// partition, and so the bits, depend on `len` and `chunk` only).
pub(crate) fn chunk_sum_by(
    len: usize,
    chunk: usize,
    f: impl Fn(std::ops::Range<usize>) -> f64 + Sync,
) -> f64 {
    use rayon::prelude::*;
    let chunks = len.div_ceil(chunk);
    let range = |k: usize| k * chunk..((k + 1) * chunk).min(len);
    let sums: Vec<f64> = if parallel(len) {
        (0..chunks).into_par_iter().map(|k| f(range(k))).collect()
    } else {
        (0..chunks).map(|k| f(range(k))).collect()
    };
    sums.iter().sum()
}

/// A contiguous slice of an array in standard layout (every CG vector is one).
fn flat<'a>(a: &'a ArrayView2<'a, f64>) -> &'a [f64] {
    a.as_slice().expect("CG vectors are contiguous")
}

/// Solves `K_CC p_C = (d − f)_C` (`p = 0` off the bonded set `C`), warm-started from `pressure`,
/// with the masked spectral preconditioner when `preconditioned`. Converged when the rms
/// residual over `C` is below `tolerance` times the rms right-hand side (floored at 1e-3 of
/// the height range over `C`). Leaves `work.disp = K p`. The vector loops run in fixed chunks
/// (bit-identical on any thread count).
#[allow(clippy::too_many_arguments)]
pub(crate) fn pcg(
    op: &mut dyn ElasticOperator,
    heights: ArrayView2<f64>,
    bonded: ArrayView2<bool>,
    d: f64,
    pressure: ArrayViewMut2<f64>,
    w: &mut Work,
    pw: &mut PcgWork,
    options: &SolverOptions,
    preconditioned: bool,
) -> Convergence {
    let system = System {
        heights,
        bonded,
        held: None,
        diagonal: None,
        d,
    };
    pcg_from(op, system, pressure, w, pw, options, preconditioned, false)
}

/// The linear system of one CG solve: [`pcg`]'s `K_CC p_C = (d − f)_C`, with the pressure of
/// the `held` elements off the bonded set kept as it is (the Dugdale law's cohesive zone: the
/// solve is then `K_CC p_C = (d − f − K_CH p_H)_C` and `work.disp = K p` includes the held
/// pressure) and with a `diagonal` (`c ≥ 0` per element) the matrix on the set
/// `K_CC + diag(c)` (still symmetric positive definite: a smooth law's landing solves its
/// stiff elements' linearised law `u_i + c_i p_i = d − f_i` with the set).
pub(crate) struct System<'a> {
    pub(crate) heights: ArrayView2<'a, f64>,
    pub(crate) bonded: ArrayView2<'a, bool>,
    pub(crate) held: Option<ArrayView2<'a, bool>>,
    pub(crate) diagonal: Option<ArrayView2<'a, f64>>,
    pub(crate) d: f64,
}

/// [`pcg`] of `system` (held elements, a diagonal). With `carried`, the last solve on these
/// vectors was of the same system and left the pressure as it is (a round that changed
/// nothing), so `work.disp` holds its `K p` and the solve continues that one's iteration
/// (direction and `r·z`): no first product, no restart, the iterates of one solve run to the
/// tighter tolerance.
#[allow(clippy::too_many_arguments)]
pub(crate) fn pcg_from(
    op: &mut dyn ElasticOperator,
    system: System<'_>,
    mut pressure: ArrayViewMut2<f64>,
    w: &mut Work,
    pw: &mut PcgWork,
    options: &SolverOptions,
    preconditioned: bool,
    carried: bool,
) -> Convergence {
    let System {
        heights,
        bonded,
        held,
        diagonal,
        d,
    } = system;
    let f = flat(&heights);
    let c = bonded.as_slice().expect("contiguous mask");
    let stats = clear_off_set(
        f,
        c,
        held.as_ref()
            .map(|h| h.as_slice().expect("contiguous mask")),
        d,
        pressure.as_slice_mut().expect("contiguous pressure"),
    );
    let n_c = stats.count;
    let scale = (stats.rhs_squared / n_c as f64)
        .sqrt()
        .max(1e-3 * (stats.highest - stats.lowest))
        .max(f64::MIN_POSITIVE);
    let target = (options.tolerance * scale).powi(2) * n_c as f64;
    let max_it = options.max_iterations;
    let diag = diagonal
        .as_ref()
        .map(|c| c.as_slice().expect("contiguous diagonal"));
    let mut it = 0;
    // The true residual is recomputed from `K p` at every (re)start (but a `carried` one);
    // inside the loop `disp` is carried along (`disp += α K s`), so a converged solve needs
    // no further product.
    // A `carried` solve also continues the last one's iteration (its direction and `r·z`):
    // the same iterates as one solve run to the tighter tolerance.
    let mut continued = if carried { pw.rz.take() } else { None };
    if !carried {
        op.apply(pressure.view(), w.disp.view_mut());
    }
    loop {
        let rr = bonded_residual(f, c, diag, d, &pressure, &w.disp, &mut pw.resid);
        let residual = (rr / n_c as f64).sqrt() / scale;
        if rr <= target || it >= max_it {
            if it == 0 {
                // Nothing moved: what could be continued still can.
                pw.rz = continued;
            }
            return Convergence {
                iterations: it,
                residual,
                converged: rr <= target,
                scale,
            };
        }
        let mut rz = precondition(op, pw, bonded, preconditioned);
        match continued.take() {
            Some(last) => next_direction(&pw.zres, rz / last, &mut w.dir),
            None => w.dir.assign(&pw.zres),
        }
        pw.rz = None;
        while it < max_it {
            it += 1;
            op.apply(w.dir.view(), w.kdir.view_mut());
            let alpha = rz / curvature(c, diag, w);
            let rr_new = advance(alpha, c, diag, pressure.view_mut(), &mut pw.resid, w);
            if rr_new <= target {
                pw.rz = Some(rz);
                break;
            }
            let rz_new = precondition(op, pw, bonded, preconditioned);
            let beta = rz_new / rz;
            rz = rz_new;
            next_direction(&pw.zres, beta, &mut w.dir);
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

/// What [`clear_off_set`] gathers over the bonded set: its element count, its height range and
/// Σ(d − f)², the squared norm of the right-hand side.
struct SetStats {
    count: usize,
    highest: f64,
    lowest: f64,
    rhs_squared: f64,
}

/// One pass over the elements: zero the pressure `p` off the bonded set `c` (and off the
/// `held` elements) and gather the bonded set's [`SetStats`] per chunk (the sum in chunk order,
/// as [`chunk_sum`]).
fn clear_off_set(f: &[f64], c: &[bool], h: Option<&[bool]>, d: f64, p: &mut [f64]) -> SetStats {
    use rayon::prelude::*;
    let body = |k: usize, p: &mut [f64]| {
        let base = k * CHUNK;
        let (mut n, mut hi, mut lo, mut s) = (0usize, f64::NEG_INFINITY, f64::INFINITY, 0.0);
        for (i, p) in p.iter_mut().enumerate() {
            let e = base + i;
            if c[e] {
                let fe = f[e];
                n += 1;
                hi = hi.max(fe);
                lo = lo.min(fe);
                s += (d - fe) * (d - fe);
            } else if h.is_none_or(|h| !h[e]) {
                *p = 0.0;
            }
        }
        (n, hi, lo, s)
    };
    let stats: Vec<(usize, f64, f64, f64)> = if parallel(p.len()) {
        p.par_chunks_mut(CHUNK)
            .enumerate()
            .map(|(k, p)| body(k, p))
            .collect()
    } else {
        p.chunks_mut(CHUNK)
            .enumerate()
            .map(|(k, p)| body(k, p))
            .collect()
    };
    let mut total = SetStats {
        count: 0,
        highest: f64::NEG_INFINITY,
        lowest: f64::INFINITY,
        rhs_squared: 0.0,
    };
    for &(n, hi, lo, s) in &stats {
        total.count += n;
        total.highest = total.highest.max(hi);
        total.lowest = total.lowest.min(lo);
        total.rhs_squared += s;
    }
    total
}

/// The residual `r = d − f − u` (`− c p` with a diagonal) on the bonded set `c` (0 off it) into
/// `resid`, from the displacement `disp`; returns Σ r².
fn bonded_residual(
    f: &[f64],
    c: &[bool],
    diag: Option<&[f64]>,
    d: f64,
    pressure: &ArrayViewMut2<f64>,
    disp: &Array2<f64>,
    resid: &mut Array2<f64>,
) -> f64 {
    let u = disp.as_slice().expect("contiguous");
    let p = pressure.as_slice().expect("contiguous pressure");
    let resid = resid.as_slice_mut().expect("contiguous");
    chunked_mut(resid, |k, r| {
        let base = k * CHUNK;
        let mut s = 0.0;
        for (i, r) in r.iter_mut().enumerate() {
            let e = base + i;
            *r = match (c[e], diag) {
                (false, _) => 0.0,
                (true, None) => d - f[e] - u[e],
                (true, Some(cd)) => d - f[e] - u[e] - cd[e] * p[e],
            };
            s += *r * *r;
        }
        s
    })
}

/// The curvature `sᵀ K s` (`+ sᵀ diag(c) s` with a diagonal) of the search direction `w.dir`
/// over the bonded set `c`, from its image `w.kdir`.
fn curvature(c: &[bool], diag: Option<&[f64]>, w: &Work) -> f64 {
    let (s, q) = (
        w.dir.as_slice().expect("contiguous"),
        w.kdir.as_slice().expect("contiguous"),
    );
    chunk_sum(s.len(), |r| {
        let mut acc = 0.0;
        for e in r {
            if c[e] {
                acc += match diag {
                    None => s[e] * q[e],
                    Some(cd) => s[e] * (q[e] + cd[e] * s[e]),
                };
            }
        }
        acc
    })
}

/// One CG step of length `alpha` along `w.dir`: the pressure and the residual on the bonded set
/// `c`, and the carried displacement `w.disp += α K s` everywhere; returns the new Σ r².
fn advance(
    alpha: f64,
    c: &[bool],
    diag: Option<&[f64]>,
    mut pressure: ArrayViewMut2<f64>,
    resid: &mut Array2<f64>,
    w: &mut Work,
) -> f64 {
    use rayon::prelude::*;
    let p = pressure.as_slice_mut().expect("contiguous pressure");
    let r = resid.as_slice_mut().expect("contiguous");
    let u = w.disp.as_slice_mut().expect("contiguous");
    let (s, q) = (
        w.dir.as_slice().expect("contiguous"),
        w.kdir.as_slice().expect("contiguous"),
    );
    let step = |k: usize, p: &mut [f64], r: &mut [f64], u: &mut [f64]| {
        let base = k * CHUNK;
        let mut acc = 0.0;
        for i in 0..p.len() {
            let e = base + i;
            u[i] += alpha * q[e];
            if c[e] {
                p[i] += alpha * s[e];
                r[i] -= match diag {
                    None => alpha * q[e],
                    Some(cd) => alpha * (q[e] + cd[e] * s[e]),
                };
                acc += r[i] * r[i];
            }
        }
        acc
    };
    let sums: Vec<f64> = if parallel(p.len()) {
        p.par_chunks_mut(CHUNK)
            .zip(r.par_chunks_mut(CHUNK))
            .zip(u.par_chunks_mut(CHUNK))
            .enumerate()
            .map(|(k, ((p, r), u))| step(k, p, r, u))
            .collect()
    } else {
        p.chunks_mut(CHUNK)
            .zip(r.chunks_mut(CHUNK))
            .zip(u.chunks_mut(CHUNK))
            .enumerate()
            .map(|(k, ((p, r), u))| step(k, p, r, u))
            .collect()
    };
    sums.iter().sum::<f64>()
}

/// The next search direction `s = z + β s` from the preconditioned residual `zres`.
fn next_direction(zres: &Array2<f64>, beta: f64, dir: &mut Array2<f64>) {
    let z = zres.as_slice().expect("contiguous");
    let s = dir.as_slice_mut().expect("contiguous");
    chunked_mut(s, |k, s| {
        let base = k * CHUNK;
        for (i, s) in s.iter_mut().enumerate() {
            *s = z[base + i] + beta * *s;
        }
        0.0
    });
}

/// Runs `f(chunk index, chunk)` over the [`CHUNK`]s of `v` (in parallel when long) and returns
/// the sum of its results in chunk order.
fn chunked_mut(v: &mut [f64], f: impl Fn(usize, &mut [f64]) -> f64 + Sync) -> f64 {
    chunked_mut_by(v, CHUNK, f)
}

/// [`chunked_mut`] over chunks of `chunk` elements.
pub(crate) fn chunked_mut_by(
    v: &mut [f64],
    chunk: usize,
    f: impl Fn(usize, &mut [f64]) -> f64 + Sync,
) -> f64 {
    use rayon::prelude::*;
    let sums: Vec<f64> = if parallel(v.len()) {
        v.par_chunks_mut(chunk)
            .enumerate()
            .map(|(k, c)| f(k, c))
            .collect()
    } else {
        v.chunks_mut(chunk)
            .enumerate()
            .map(|(k, c)| f(k, c))
            .collect()
    };
    sums.iter().sum()
}

/// Iterations between refreshes of the carried product `K p` in long solves.
const REFRESH: usize = 200;

/// `z = P_C M r` (or `z = r` without preconditioning); returns `r·z`.
fn precondition(
    op: &mut dyn ElasticOperator,
    w: &mut PcgWork,
    bonded: ArrayView2<bool>,
    on: bool,
) -> f64 {
    if on {
        op.precondition(w.resid.view(), w.zres.view_mut());
    } else {
        w.zres.assign(&w.resid);
    }
    let c = bonded.as_slice().expect("contiguous mask");
    let r = w.resid.as_slice().expect("contiguous");
    chunked_mut(w.zres.as_slice_mut().expect("contiguous"), |k, z| {
        let base = k * CHUNK;
        let mut acc = 0.0;
        for (i, z) in z.iter_mut().enumerate() {
            let e = base + i;
            if c[e] {
                acc += r[e] * *z;
            } else {
                *z = 0.0;
            }
        }
        acc
    })
}

/// One solve of the contact set on one grid (the whole grid or a sub-grid): the bonded-set CG,
/// or with `held` (the Dugdale law's zone and per-element tension) the CG with the zone's
/// tension held. With `carried` the solve continues the last one's ([`pcg_from`]).
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve_grid(
    op: &mut dyn ElasticOperator,
    heights: ArrayView2<f64>,
    bonded: ArrayView2<bool>,
    held: Option<(ArrayView2<bool>, ArrayView2<f64>)>,
    d: f64,
    pressure: ArrayViewMut2<f64>,
    work: &mut Work,
    pcg_work: &mut PcgWork,
    cg: &SolverOptions,
    preconditioned: bool,
    carried: bool,
) -> Convergence {
    match held {
        None => {
            let system = System {
                heights,
                bonded,
                held: None,
                diagonal: None,
                d,
            };
            pcg_from(
                op,
                system,
                pressure,
                work,
                pcg_work,
                cg,
                preconditioned,
                carried,
            )
        }
        Some((zone, tension)) => solve_with_zone(
            op,
            heights,
            bonded,
            zone,
            tension,
            d,
            pressure,
            work,
            pcg_work,
            cg,
            preconditioned,
            carried,
        ),
    }
}

/// `K_CC p_C = (d − f − K p_Z)_C` on one grid with `p_Z = −σ0` on `zone` (σ0 per element:
/// `tension`); leaves the whole pressure in `pressure` and `work.disp = K p`. With `carried`
/// the last solve was of the same sets and pressure, whose CG this one continues.
#[allow(clippy::too_many_arguments)]
fn solve_with_zone(
    op: &mut dyn ElasticOperator,
    heights: ArrayView2<f64>,
    bonded: ArrayView2<bool>,
    zone: ArrayView2<bool>,
    tension: ArrayView2<f64>,
    d: f64,
    mut pressure: ArrayViewMut2<f64>,
    work: &mut Work,
    pcg_work: &mut PcgWork,
    cg: &SolverOptions,
    preconditioned: bool,
    carried: bool,
) -> Convergence {
    Zip::from(&mut pressure)
        .and(&bonded)
        .and(&zone)
        .and(&tension)
        .for_each(|p, &b, &z, &s| {
            if z {
                *p = -s;
            } else if !b {
                *p = 0.0;
            }
        });
    if bonded.iter().any(|&b| b) {
        let system = System {
            heights,
            bonded,
            held: Some(zone),
            diagonal: None,
            d,
        };
        pcg_from(
            op,
            system,
            pressure.view_mut(),
            work,
            pcg_work,
            cg,
            preconditioned,
            carried,
        )
    } else {
        op.apply(pressure.view(), work.disp.view_mut());
        Convergence::EXACT
    }
}

#[cfg(test)]
mod tests;
