//! Independent axisymmetric ring-element reference solution of a rigid sphere on an elastic
//! half-space with an adhesion law, used only by tests (it shares no code with tack's solvers).
//!
//! The surface r < `outer` is cut into rings carrying a uniform pressure each; the displacement
//! is collocated at the ring mid-radii with Love's solution for a uniformly loaded disc (an
//! annulus is the difference of two discs), complete elliptic integrals by the
//! arithmetic–geometric mean. Conventions are tack's: height f(r) = r²/(2R), approach d > 0 when
//! pressing, pressure and force positive when compressive, gap g = f − d + u ≥ 0 with u the
//! displacement into the half-space, E* the plane-strain modulus, F = ∫ p dA.
//!
//! Each ring is in contact (g = 0, p ≥ the law's value at g = 0) or free (p = law(g); for the
//! Dugdale law −σ0 times the fraction of the ring where the interpolated gap is below h0). [`Reference::step`]
//! solves the equilibrium at an approach by an active-set Newton method from the previous state
//! (dense LU on the rings with non-negligible traction); the state is accepted if Newton
//! converges and the sign of the Jacobian's determinant says it is stable (an unstable state of
//! the exponential law has an odd number of negative modes). Otherwise the branch has ended (a
//! jump-in or jump-out): the previous state is relaxed at the new approach by an energy-descent
//! fixed point p ← p + ω(law(g) − p) with the contact pressures solved exactly (ω backtracked
//! so that the total energy decreases, hence it lands on a stable state), then polished by
//! Newton. Every loop has an iteration cap and reports convergence.
#![allow(dead_code, clippy::needless_range_loop)]

use std::f64::consts::PI;

/// Traction–gap law outside contact (pressure positive when compressive).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Law {
    /// No adhesion (Hertz).
    None,
    /// p(g) = −(γ/ρ) e^(−g/ρ), potential V(g) = −γ e^(−g/ρ); hard wall at g = 0.
    Exponential {
        /// Work of adhesion γ.
        gamma: f64,
        /// Range ρ.
        rho: f64,
    },
    /// Lennard-Jones 9–3 with the wall at the equilibrium separation ε: with h = g + ε,
    /// p(g) = −(8γ/3ε)[(ε/h)³ − (ε/h)⁹], zero at the wall; potential
    /// V(g) = −(8γ/3)[(ε/h)²/2 − (ε/h)⁸/8] (V(0) = −γ).
    LennardJones {
        /// Work of adhesion γ.
        gamma: f64,
        /// Equilibrium separation ε.
        eps: f64,
    },
    /// Morse, with the wall at the potential's minimum: with x = g/ρ,
    /// p(g) = −(2γ/ρ)(e^(−x) − e^(−2x)), zero at the wall; potential V(g) = γ(e^(−2x) − 2e^(−x))
    /// (V(0) = −γ), peak tension γ/(2ρ) at x = ln 2.
    Morse {
        /// Work of adhesion γ.
        gamma: f64,
        /// Range ρ.
        rho: f64,
    },
    /// p = −σ0 for 0 < g < h0, 0 beyond (γ = σ0 h0); hard wall at g = 0.
    Dugdale {
        /// Cohesive stress σ0.
        sigma0: f64,
        /// Range h0.
        h0: f64,
    },
}

impl Law {
    /// Work of adhesion γ.
    pub fn gamma(&self) -> f64 {
        match *self {
            Law::None => 0.0,
            Law::Exponential { gamma, .. }
            | Law::LennardJones { gamma, .. }
            | Law::Morse { gamma, .. } => gamma,
            Law::Dugdale { sigma0, h0 } => sigma0 * h0,
        }
    }
    /// Most tensile pressure the wall can hold: the law at g = 0.
    fn wall(&self) -> f64 {
        match *self {
            Law::None => 0.0,
            Law::Exponential { gamma, rho } => -gamma / rho,
            Law::LennardJones { .. } | Law::Morse { .. } => 0.0,
            Law::Dugdale { sigma0, .. } => -sigma0,
        }
    }
    /// Greatest tension of the law: at the wall, except for Lennard-Jones (zero at the wall,
    /// 16γ/(9√3ε) at h = 3^(1/6)ε).
    fn peak(&self) -> f64 {
        match *self {
            Law::LennardJones { gamma, eps } => 16.0 * gamma / (9.0 * 3f64.sqrt() * eps),
            Law::Morse { gamma, rho } => gamma / (2.0 * rho),
            _ => -self.wall(),
        }
    }
    /// Pressure at gap g > 0 (for Dugdale the single-valued version, 0 at g ≥ h0).
    fn p(&self, g: f64) -> f64 {
        match *self {
            Law::None => 0.0,
            Law::Exponential { gamma, rho } => -gamma / rho * (-g.max(0.0) / rho).exp(),
            Law::LennardJones { gamma, eps } => {
                let t = eps / (g.max(0.0) + eps);
                -(8.0 * gamma / (3.0 * eps)) * (t.powi(3) - t.powi(9))
            }
            Law::Morse { gamma, rho } => {
                let e = (-g.max(0.0) / rho).exp();
                -(2.0 * gamma / rho) * (e - e * e)
            }
            Law::Dugdale { sigma0, h0 } => {
                if g < h0 {
                    -sigma0
                } else {
                    0.0
                }
            }
        }
    }
    /// dp/dg (0 for Dugdale and None).
    fn dp(&self, g: f64) -> f64 {
        match *self {
            Law::Exponential { gamma, rho } => gamma / (rho * rho) * (-g.max(0.0) / rho).exp(),
            Law::LennardJones { gamma, eps } => {
                // p = −A(t³ − t⁹), t = ε/h, dt/dh = −t/h: dp/dh = (3A/h)(t³ − 3t⁹).
                let h = g.max(0.0) + eps;
                let t = eps / h;
                (8.0 * gamma / (eps * h)) * (t.powi(3) - 3.0 * t.powi(9))
            }
            Law::Morse { gamma, rho } => {
                let e = (-g.max(0.0) / rho).exp();
                (2.0 * gamma / (rho * rho)) * (e - 2.0 * e * e)
            }
            _ => 0.0,
        }
    }
    /// Potential V(g), with dV/dg = −p(g).
    fn v(&self, g: f64) -> f64 {
        match *self {
            Law::None => 0.0,
            Law::Exponential { gamma, rho } => -gamma * (-g.max(0.0) / rho).exp(),
            Law::LennardJones { gamma, eps } => {
                let t = eps / (g.max(0.0) + eps);
                -(8.0 * gamma / 3.0) * (0.5 * t.powi(2) - 0.125 * t.powi(8))
            }
            Law::Morse { gamma, rho } => {
                let e = (-g.max(0.0) / rho).exp();
                gamma * (e * e - 2.0 * e)
            }
            Law::Dugdale { sigma0, h0 } => -sigma0 * (h0 - g).max(0.0),
        }
    }
    /// Gap beyond which an exponential traction is below 1e-11 of the wall value (not an
    /// unknown of Newton's method: set explicitly from the gap); the Lennard-Jones tail is
    /// algebraic, so every free ring stays an unknown.
    fn cut(&self) -> f64 {
        match *self {
            Law::Exponential { rho, .. } | Law::Morse { rho, .. } => 25.0 * rho,
            Law::LennardJones { .. } => f64::INFINITY,
            _ => 0.0,
        }
    }
}

/// Complete elliptic integrals (K(k), E(k)) of modulus k, given k and k' = √(1 − k²) (passed
/// separately so that k → 1 keeps its precision), by the arithmetic–geometric mean.
pub fn elliptic_ke(k: f64, kp: f64) -> (f64, f64) {
    if kp <= 0.0 {
        return (f64::INFINITY, 1.0);
    }
    let (mut a, mut b) = (1.0_f64, kp);
    let mut sum = 0.5 * k * k;
    let mut pow = 0.5;
    for _ in 0..80 {
        let c = 0.5 * (a - b);
        let an = 0.5 * (a + b);
        b = (a * b).sqrt();
        a = an;
        pow *= 2.0;
        sum += pow * c * c;
        // (c² is then below rounding; waiting for c = 0 can stall on a 1-ulp gap of a and b
        // while the weight 2^n grows.)
        if c.abs() <= 1e-15 * a {
            break;
        }
    }
    let kk = PI / (2.0 * a);
    (kk, kk * (1.0 - sum))
}

/// Displacement at radius r of a disc of radius a under unit pressure, times E* (Love 1929).
pub fn disc_displacement(r: f64, a: f64) -> f64 {
    if a <= 0.0 {
        return 0.0;
    }
    if r <= a {
        let k = r / a;
        let kp = ((a - r) * (a + r)).sqrt() / a;
        4.0 * a / PI * elliptic_ke(k, kp).1
    } else {
        let k = a / r;
        let kp = ((r - a) * (r + a)).sqrt() / r;
        let (kk, ee) = elliptic_ke(k, kp);
        4.0 * r / PI * (ee - kp * kp * kk)
    }
}

/// Dense LU factorisation with partial pivoting (row-major), with the sign of the determinant.
struct Lu {
    n: usize,
    a: Vec<f64>,
    piv: Vec<usize>,
    det_sign: f64,
}

impl Lu {
    fn new(mut a: Vec<f64>, n: usize) -> Option<Lu> {
        let mut piv: Vec<usize> = (0..n).collect();
        let mut det_sign = 1.0;
        for k in 0..n {
            let mut best = k;
            let mut bv = a[k * n + k].abs();
            for i in k + 1..n {
                let v = a[i * n + k].abs();
                if v > bv {
                    bv = v;
                    best = i;
                }
            }
            if bv == 0.0 || !bv.is_finite() {
                return None;
            }
            if best != k {
                for j in 0..n {
                    a.swap(k * n + j, best * n + j);
                }
                piv.swap(k, best);
                det_sign = -det_sign;
            }
            let (top, rest) = a.split_at_mut((k + 1) * n);
            let rowk = &top[k * n + k..k * n + n];
            let pk = rowk[0];
            if pk < 0.0 {
                det_sign = -det_sign;
            }
            for i in 0..n - k - 1 {
                let row = &mut rest[i * n + k..i * n + n];
                let l = row[0] / pk;
                row[0] = l;
                if l != 0.0 {
                    for (x, y) in row[1..].iter_mut().zip(&rowk[1..]) {
                        *x -= l * y;
                    }
                }
            }
        }
        Some(Lu {
            n,
            a,
            piv,
            det_sign,
        })
    }
    fn solve(&self, b: &[f64]) -> Vec<f64> {
        let n = self.n;
        let mut x: Vec<f64> = self.piv.iter().map(|&i| b[i]).collect();
        for i in 0..n {
            let s: f64 = (0..i).map(|j| self.a[i * n + j] * x[j]).sum();
            x[i] -= s;
        }
        for i in (0..n).rev() {
            let s: f64 = (i + 1..n).map(|j| self.a[i * n + j] * x[j]).sum();
            x[i] = (x[i] - s) / self.a[i * n + i];
        }
        x
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum St {
    /// g = 0, p ≥ wall.
    Contact,
    /// p = law(g).
    Free,
}

/// One equilibrium point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// Approach d (positive when pressing).
    pub approach: f64,
    /// Force F = ∫ p dA (positive when compressive).
    pub force: f64,
    /// Outer edge of the outermost ring in contact (0 without contact).
    pub contact_radius: f64,
    /// Whether the solution converged.
    pub converged: bool,
    /// Whether the previous branch ended here (Newton failed or found an unstable state) and the
    /// relaxation found a new one: a jump.
    pub jumped: bool,
    /// Stability by the sign of the Jacobian's determinant.
    pub stable: bool,
}

/// A load–unload cycle: its points and the most tensile force.
#[derive(Debug, Clone)]
pub struct Cycle {
    /// All points, loading then unloading.
    pub points: Vec<Point>,
    /// Most tensile force met (negative), refined by a parabola through the minimum sample and
    /// its two neighbours on the same branch when they bracket the minimum.
    pub pull_off: f64,
    /// Most tensile force among the samples, without refinement.
    pub pull_off_sampled: f64,
}

/// The ring-element reference model and its current state.
pub struct Reference {
    radius: f64,
    e_star: f64,
    law: Law,
    /// Ring edges, rings + 1 values from 0 to outer.
    edges: Vec<f64>,
    mid: Vec<f64>,
    area: Vec<f64>,
    /// Influence matrix: u at mid[i] from unit pressure on ring j, row-major.
    infl: Vec<f64>,
    p: Vec<f64>,
    st: Vec<St>,
    /// Iterations of the last step (Newton, relaxation).
    pub last_iterations: (usize, usize),
}

impl Reference {
    /// A model with `rings` uniform rings on r < `outer`, unloaded.
    pub fn new(radius: f64, e_star: f64, law: Law, rings: usize, outer: f64) -> Self {
        let edges: Vec<f64> = (0..=rings)
            .map(|i| outer * i as f64 / rings as f64)
            .collect();
        Self::with_edges(radius, e_star, law, edges)
    }

    /// Ring edges on r < `outer`: width `h_fine` on `fine_from` < r < `fine_to` (where the contact
    /// edge and the process zone move), `ratio` times wider inside and outside that band (each
    /// part uniform, rounded to a whole number of rings).
    pub fn graded_edges(
        outer: f64,
        fine_from: f64,
        fine_to: f64,
        h_fine: f64,
        ratio: f64,
    ) -> Vec<f64> {
        let mut edges = vec![0.0];
        let mut part = |from: f64, to: f64, h: f64| {
            let k = ((to - from) / h).ceil().max(1.0) as usize;
            for i in 1..=k {
                edges.push(from + (to - from) * i as f64 / k as f64);
            }
        };
        part(0.0, fine_from, ratio * h_fine);
        part(fine_from, fine_to, h_fine);
        part(fine_to, outer, ratio * h_fine);
        edges
    }

    /// A model on the given ring edges (increasing, from 0).
    pub fn with_edges(radius: f64, e_star: f64, law: Law, edges: Vec<f64>) -> Self {
        let n = edges.len() - 1;
        let mid: Vec<f64> = (0..n).map(|i| 0.5 * (edges[i] + edges[i + 1])).collect();
        let area: Vec<f64> = (0..n)
            .map(|i| PI * (edges[i + 1] - edges[i]) * (edges[i + 1] + edges[i]))
            .collect();
        let mut infl = vec![0.0; n * n];
        for (i, &r) in mid.iter().enumerate() {
            let mut prev = 0.0;
            for j in 0..n {
                let next = disc_displacement(r, edges[j + 1]);
                infl[i * n + j] = (next - prev) / e_star;
                prev = next;
            }
        }
        Reference {
            radius,
            e_star,
            law,
            edges,
            mid,
            area,
            infl,
            p: vec![0.0; n],
            st: vec![St::Free; n],
            last_iterations: (0, 0),
        }
    }

    /// Number of rings.
    pub fn rings(&self) -> usize {
        self.mid.len()
    }

    fn height(&self, i: usize) -> f64 {
        self.mid[i] * self.mid[i] / (2.0 * self.radius)
    }

    fn gaps(&self, d: f64) -> Vec<f64> {
        let n = self.rings();
        let nz: Vec<usize> = (0..n).filter(|&j| self.p[j] != 0.0).collect();
        (0..n)
            .map(|i| {
                let row = &self.infl[i * n..(i + 1) * n];
                self.height(i) - d + nz.iter().map(|&j| row[j] * self.p[j]).sum::<f64>()
            })
            .collect()
    }

    fn force(&self) -> f64 {
        self.p.iter().zip(&self.area).map(|(p, a)| p * a).sum()
    }

    fn contact_radius(&self) -> f64 {
        (0..self.rings())
            .rev()
            .find(|&i| self.st[i] == St::Contact)
            .map_or(0.0, |i| self.edges[i + 1])
    }

    fn energy(&self, g: &[f64], d: f64) -> f64 {
        let mut e = 0.0;
        for i in 0..self.rings() {
            let u = g[i] - self.height(i) + d;
            e += self.area[i] * (0.5 * self.p[i] * u + self.law.v(g[i]));
        }
        e
    }

    fn p_scale(&self) -> f64 {
        let m = self.p.iter().fold(0.0_f64, |m, p| m.max(p.abs()));
        m.max(self.law.peak()).max(1e-300)
    }

    /// Traction of free ring j given all gaps, and its non-zero derivatives dp_j/dg_k. The
    /// Dugdale traction is −σ0 times the fraction of the ring where the gap, interpolated
    /// linearly between mid-radii, is below h0: a continuous function of the gaps (a ring
    /// switching whole between −σ0 and 0 lets its own attraction trap the zone's edge).
    fn ring_law(&self, j: usize, g: &[f64], der: &mut Vec<(usize, f64)>) -> f64 {
        der.clear();
        match self.law {
            Law::None => 0.0,
            Law::Exponential { .. } | Law::LennardJones { .. } | Law::Morse { .. } => {
                if g[j] < self.law.cut() {
                    der.push((j, self.law.dp(g[j])));
                }
                self.law.p(g[j])
            }
            Law::Dugdale { sigma0, h0 } => {
                let n = self.rings();
                // Left half [e_j, mid_j]: from ga = w g_{j-1} + (1-w) g_j to g_j.
                let (wl, jl) = if j > 0 {
                    let w = (self.mid[j] - self.edges[j]) / (self.mid[j] - self.mid[j - 1]);
                    (w, j - 1)
                } else {
                    (0.0, j)
                };
                let (wr, jr) = if j + 1 < n {
                    let w = (self.edges[j + 1] - self.mid[j]) / (self.mid[j + 1] - self.mid[j]);
                    (w, j + 1)
                } else {
                    (0.0, j)
                };
                let ll = self.mid[j] - self.edges[j];
                let lr = self.edges[j + 1] - self.mid[j];
                let tot = ll + lr;
                // Fraction of a linear segment from ga to gb below h0, and its derivatives.
                let frac = |ga: f64, gb: f64| -> (f64, f64, f64) {
                    match (ga < h0, gb < h0) {
                        (true, true) => (1.0, 0.0, 0.0),
                        (false, false) => (0.0, 0.0, 0.0),
                        (lo, _) => {
                            let dg = gb - ga;
                            let t = (h0 - ga) / dg;
                            let dta = (h0 - gb) / (dg * dg);
                            let dtb = -(h0 - ga) / (dg * dg);
                            if lo {
                                (t, dta, dtb)
                            } else {
                                (1.0 - t, -dta, -dtb)
                            }
                        }
                    }
                };
                let gal = wl * g[jl] + (1.0 - wl) * g[j];
                let (fl, dla, dlb) = frac(gal, g[j]);
                let gbr = (1.0 - wr) * g[j] + wr * g[jr];
                let (fr, dra, drb) = frac(g[j], gbr);
                let phi = (ll * fl + lr * fr) / tot;
                let s = -sigma0 / tot;
                let dj = ll * (dla * (1.0 - wl) + dlb) + lr * (dra + drb * (1.0 - wr));
                let dl = ll * dla * wl;
                let dr = lr * drb * wr;
                for (k, v) in [(j, dj), (jl, dl), (jr, dr)] {
                    if v != 0.0 {
                        der.push((k, s * v));
                    }
                }
                -sigma0 * phi
            }
        }
    }

    /// Squared norm of the NCP residual min(g_i/A_ii, p_i − law_i(g)) over all rings.
    fn merit(&self, g: &[f64]) -> f64 {
        let n = self.rings();
        let mut der = Vec::new();
        (0..n)
            .map(|i| {
                let lp = self.ring_law(i, g, &mut der);
                let f = (g[i] / self.infl[i * n + i]).min(self.p[i] - lp);
                f * f
            })
            .sum()
    }

    /// Active-set Newton from the current state; Some(stable) when converged.
    fn newton(&mut self, d: f64, max_it: usize) -> (Option<bool>, usize) {
        let n = self.rings();
        let wall = self.law.wall();
        let mut der = Vec::new();
        for it in 0..max_it {
            let g = self.gaps(d);
            // Semismooth active set: ring i is in contact iff g_i/A_ii < p_i − law_i(g).
            // (Not at the first iteration: the previous state's set predicts the new one.)
            let mut changed = false;
            for i in (0..n).filter(|_| it > 0) {
                let lp = self.ring_law(i, &g, &mut der);
                let c = g[i] / self.infl[i * n + i] < self.p[i] - lp;
                let was = self.st[i] == St::Contact;
                if c != was {
                    changed = true;
                    if c {
                        self.st[i] = St::Contact;
                    } else {
                        self.st[i] = St::Free;
                        self.p[i] = lp.max(wall);
                    }
                }
            }
            // Released rings changed their pressure: gaps afresh.
            let g = if changed { self.gaps(d) } else { g };
            // Free rings: unknown where the traction depends on the gaps, explicit elsewhere.
            let mut unk = Vec::new();
            let mut rows: Vec<Vec<(usize, f64)>> = Vec::new();
            let mut res = Vec::new();
            let mut big = 0.0_f64;
            for i in 0..n {
                if self.st[i] == St::Contact {
                    unk.push(i);
                    rows.push(Vec::new());
                    res.push(g[i]);
                    continue;
                }
                let p = self.ring_law(i, &g, &mut der);
                if der.is_empty() {
                    big = big.max((p - self.p[i]).abs());
                    self.p[i] = p;
                } else {
                    unk.push(i);
                    rows.push(der.clone());
                    res.push(self.p[i] - p);
                }
            }
            let m = unk.len();
            let ps = self.p_scale();
            if m == 0 {
                if it > 0 && !changed && big <= 1e-10 * ps {
                    return (Some(true), it + 1);
                }
                continue;
            }
            let mut jac = vec![0.0; m * m];
            for (a, &i) in unk.iter().enumerate() {
                let jr = &mut jac[a * m..(a + 1) * m];
                if self.st[i] == St::Contact {
                    let row = &self.infl[i * n..(i + 1) * n];
                    for (b, &j) in unk.iter().enumerate() {
                        jr[b] = row[j];
                    }
                } else {
                    for &(k, s) in &rows[a] {
                        let row = &self.infl[k * n..(k + 1) * n];
                        for (b, &j) in unk.iter().enumerate() {
                            jr[b] -= s * row[j];
                        }
                    }
                    jr[a] += 1.0;
                }
            }
            let Some(lu) = Lu::new(jac, m) else {
                return (None, it + 1);
            };
            let rhs: Vec<f64> = res.iter().map(|r| -r).collect();
            let delta = lu.solve(&rhs);
            let p0 = self.p.clone();
            let m0 = self.merit(&g);
            let mut alpha = 1.0;
            loop {
                for (a, &i) in unk.iter().enumerate() {
                    self.p[i] = p0[i] + alpha * delta[a];
                }
                let m1 = self.merit(&self.gaps(d));
                if m1 <= (1.0 - 1e-4 * alpha) * m0
                    || m0 <= n as f64 * (1e-12 * ps).powi(2)
                    || alpha < 1.0 / 64.0
                {
                    break;
                }
                alpha *= 0.5;
            }
            for x in &delta {
                big = big.max(x.abs());
            }
            if !big.is_finite() {
                return (None, it + 1);
            }
            if it > 0 && !changed && big <= 1e-10 * ps {
                // Converged if the updated state is still admissible.
                let g = self.gaps(d);
                let ok = (0..n).all(|i| match self.st[i] {
                    St::Contact => self.p[i] >= wall,
                    _ => g[i] >= 0.0,
                });
                if ok {
                    return (Some(lu.det_sign > 0.0), it + 1);
                }
            }
        }
        (None, max_it)
    }

    /// Solve the contact rings exactly with the free pressures held (active set on contact).
    fn solve_contact(&mut self, d: f64, cache: &mut Option<(Vec<usize>, Lu)>) -> bool {
        let n = self.rings();
        let wall = self.law.wall();
        for _ in 0..200 {
            let cset: Vec<usize> = (0..n).filter(|&i| self.st[i] == St::Contact).collect();
            if !cset.is_empty() {
                let fresh = !matches!(cache, Some((c, _)) if *c == cset);
                if fresh {
                    let m = cset.len();
                    let mut a = vec![0.0; m * m];
                    for (x, &i) in cset.iter().enumerate() {
                        for (y, &j) in cset.iter().enumerate() {
                            a[x * m + y] = self.infl[i * n + j];
                        }
                    }
                    let Some(lu) = Lu::new(a, m) else {
                        return false;
                    };
                    *cache = Some((cset.clone(), lu));
                }
                let lu = &cache.as_ref().expect("factorised").1;
                for &i in &cset {
                    self.p[i] = 0.0;
                }
                let g = self.gaps(d);
                let rhs: Vec<f64> = cset.iter().map(|&i| -g[i]).collect();
                let x = lu.solve(&rhs);
                for (a, &i) in cset.iter().enumerate() {
                    self.p[i] = x[a];
                }
            }
            let g = self.gaps(d);
            let mut changed = false;
            for i in 0..n {
                if self.st[i] == St::Contact && self.p[i] < wall {
                    self.st[i] = St::Free;
                    self.p[i] = wall;
                    changed = true;
                } else if self.st[i] != St::Contact && g[i] < 0.0 {
                    self.st[i] = St::Contact;
                    changed = true;
                }
            }
            if !changed {
                return true;
            }
        }
        false
    }

    /// Energy-descent relaxation towards a stable state; returns iterations and success.
    fn relax(&mut self, d: f64, max_it: usize) -> (bool, usize) {
        let n = self.rings();
        let mut cache = None;
        if !self.solve_contact(d, &mut cache) {
            return (false, 0);
        }
        let mut g = self.gaps(d);
        let mut e0 = self.energy(&g, d);
        let mut omega = 0.5;
        let tol = 1e-5 * self.p_scale();
        let mut der = Vec::new();
        for it in 0..max_it {
            let target: Vec<f64> = (0..n)
                .map(|i| {
                    if self.st[i] == St::Contact {
                        self.p[i]
                    } else {
                        self.ring_law(i, &g, &mut der)
                    }
                })
                .collect();
            let res = (0..n).fold(0.0_f64, |m, i| m.max((target[i] - self.p[i]).abs()));
            if res <= tol || omega < 1e-8 {
                return (true, it);
            }
            let saved = (self.p.clone(), self.st.clone());
            for i in 0..n {
                if self.st[i] != St::Contact {
                    self.p[i] += omega * (target[i] - self.p[i]);
                }
            }
            let ok = self.solve_contact(d, &mut cache);
            let g1 = self.gaps(d);
            let e1 = self.energy(&g1, d);
            if ok && e1 <= e0 {
                g = g1;
                e0 = e1;
                omega = (omega * 1.5).min(1.0);
            } else {
                (self.p, self.st) = saved;
                omega *= 0.5;
            }
        }
        (false, max_it)
    }

    fn point(&self, d: f64, converged: bool, jumped: bool, stable: bool) -> Point {
        Point {
            approach: d,
            force: self.force(),
            contact_radius: self.contact_radius(),
            converged,
            jumped,
            stable,
        }
    }

    /// Equilibrium at approach `d`, continuing the current state on its stable branch, or
    /// jumping to a new stable state where that branch has ended.
    pub fn step(&mut self, d: f64) -> Point {
        let saved = (self.p.clone(), self.st.clone());
        let (r, it) = self.newton(d, 40);
        if r == Some(true) {
            self.last_iterations = (it, 0);
            return self.point(d, true, false, true);
        }
        (self.p, self.st) = saved;
        let (_, rit) = self.relax(d, 4000);
        let (r, it2) = self.newton(d, 60);
        self.last_iterations = (it + it2, rit);
        self.point(d, r.is_some(), true, r == Some(true))
    }

    /// Load from `d_start` to `d_max` by `load_step`, then retract by `unload_step` until the
    /// force has passed its minimum and returned to ~0 (within 2% of the minimum), or below
    /// `d_min`.
    pub fn cycle(
        &mut self,
        d_start: f64,
        d_max: f64,
        load_step: f64,
        unload_step: f64,
        d_min: f64,
    ) -> Cycle {
        let mut points = Vec::new();
        let nl = ((d_max - d_start) / load_step).ceil().max(0.0) as usize;
        for k in 0..=nl {
            let d = (d_start + k as f64 * load_step).min(d_max);
            points.push(self.step(d));
        }
        let first_unload = points.len();
        let mut fmin = f64::INFINITY;
        let mut k = 1;
        loop {
            let d = d_max - k as f64 * unload_step;
            if d < d_min {
                break;
            }
            let pt = self.step(d);
            points.push(pt);
            fmin = fmin.min(pt.force);
            if fmin < 0.0 && pt.force > fmin && pt.force >= 0.02 * fmin {
                break;
            }
            k += 1;
        }
        let (imin, pmin) = points
            .iter()
            .enumerate()
            .filter(|(_, p)| p.converged)
            .min_by(|a, b| a.1.force.total_cmp(&b.1.force))
            .map(|(i, p)| (i, p.force))
            .unwrap_or((0, f64::NAN));
        let mut pull_off = pmin;
        if imin > first_unload && imin + 1 < points.len() {
            let (a, b, c) = (points[imin - 1], points[imin], points[imin + 1]);
            if !b.jumped && !c.jumped && a.converged && c.converged {
                // Parabola through three equally spaced points (spacing h, in d).
                let h = a.approach - b.approach;
                let (fa, fb, fc) = (a.force, b.force, c.force);
                let curv = fa - 2.0 * fb + fc;
                if curv > 0.0 && h > 0.0 {
                    let t = 0.5 * (fc - fa) / curv; // vertex offset in steps towards a
                    if t.abs() <= 1.0 {
                        pull_off = fb - 0.125 * (fc - fa) * (fc - fa) / curv;
                    }
                }
            }
        }
        Cycle {
            points,
            pull_off,
            pull_off_sampled: pmin,
        }
    }

    /// The retraction branch traced by pseudo-arclength continuation, a method independent of
    /// [`Reference::step`] (no active set, no relaxation) for laws with `P(0) = 0` at the wall
    /// (Lennard-Jones), where the active-set Newton method meets a wall far stiffer than a ring.
    /// Each ring has one unknown `z` on the complementarity graph: `g = z`, `p = P(z)` for
    /// `z ≥ 0` (off the wall), `g = 0`, `p = P′(0) z ≥ 0` for `z < 0` (on it; `P′(0) < 0`), so
    /// `p(z)` is C¹ and the graph is one curve. The equations `g(z_i) − f_i + d − Σ C_ij p(z_j) = 0`
    /// and the approach `d` are continued along the arclength from the equilibrium at `d0`
    /// (found by damped Newton from the rigid gaps), towards smaller `d`, until the tension has
    /// fallen back to half its greatest value (past the fold where displacement control jumps
    /// out, on the unstable branch; the rings' lattice makes small folds of its own, which a fine
    /// `ds` resolves) or `max_points`. Returns the points (approach, force); the pull-off under
    /// displacement control is their least force, which lies before the fold.
    pub fn trace_retraction(&self, d0: f64, ds: f64, max_points: usize) -> Option<Vec<(f64, f64)>> {
        assert!(
            self.law.wall() == 0.0,
            "continuation needs P(0) = 0 at the wall"
        );
        let n = self.rings();
        let s0 = self.law.dp(0.0);
        assert!(s0 < 0.0, "the law must turn tensile off the wall");
        let g_of = |z: f64| z.max(0.0);
        let dg = |z: f64| if z >= 0.0 { 1.0 } else { 0.0 };
        let p_of = |z: f64| if z >= 0.0 { self.law.p(z) } else { s0 * z };
        let dp = |z: f64| if z >= 0.0 { self.law.dp(z) } else { s0 };
        let heights: Vec<f64> = (0..n).map(|i| self.height(i)).collect();
        let residual = |z: &[f64], d: f64| -> Vec<f64> {
            let p: Vec<f64> = z.iter().map(|&z| p_of(z)).collect();
            (0..n)
                .map(|i| {
                    let row = &self.infl[i * n..(i + 1) * n];
                    let u: f64 = row.iter().zip(&p).map(|(c, p)| c * p).sum();
                    g_of(z[i]) - heights[i] + d - u
                })
                .collect()
        };
        // The (n + 1)-column Jacobian [∂F/∂z, ∂F/∂d], row-major, n rows.
        let jacobian = |z: &[f64]| -> Vec<f64> {
            let m = n + 1;
            let mut j = vec![0.0; n * m];
            let slopes: Vec<f64> = z.iter().map(|&z| dp(z)).collect();
            for i in 0..n {
                let row = &self.infl[i * n..(i + 1) * n];
                let out = &mut j[i * m..(i + 1) * m];
                for k in 0..n {
                    out[k] = -row[k] * slopes[k];
                }
                out[i] += dg(z[i]);
                out[n] = 1.0;
            }
            j
        };
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        // The arclength's metric: the rings' mean square and the approach, `Σz²/n + d²`.
        let w = 1.0 / n as f64;
        let weighted = |t: &[f64]| -> Vec<f64> {
            t.iter()
                .enumerate()
                .map(|(i, v)| if i < n { v * w } else { *v })
                .collect()
        };
        let length = |t: &[f64]| {
            weighted(t)
                .iter()
                .zip(t)
                .map(|(a, b)| a * b)
                .sum::<f64>()
                .sqrt()
        };
        let scale = self.law.peak() * self.infl[0];
        // The equilibrium at d0: damped Newton in z from the rigid gaps.
        let mut z: Vec<f64> = heights.iter().map(|&f| f - d0).collect();
        let mut ok = false;
        for _ in 0..200 {
            let r = residual(&z, d0);
            let r0 = norm(&r);
            if r0 <= 1e-12 * scale * (n as f64).sqrt() {
                ok = true;
                break;
            }
            let j = jacobian(&z);
            let a: Vec<f64> = (0..n)
                .flat_map(|i| j[i * (n + 1)..i * (n + 1) + n].to_vec())
                .collect();
            let lu = Lu::new(a, n)?;
            let step = lu.solve(&r.iter().map(|x| -x).collect::<Vec<_>>());
            let mut alpha = 1.0;
            loop {
                let trial: Vec<f64> = z.iter().zip(&step).map(|(z, s)| z + alpha * s).collect();
                if norm(&residual(&trial, d0)) < (1.0 - 1e-4 * alpha) * r0 || alpha < 1e-6 {
                    z = trial;
                    break;
                }
                alpha *= 0.5;
            }
        }
        if !ok {
            return None;
        }
        let force =
            |z: &[f64]| -> f64 { z.iter().zip(&self.area).map(|(&z, a)| p_of(z) * a).sum() };
        let mut x: Vec<f64> = z.clone();
        x.push(d0);
        let mut points = vec![(d0, force(&z))];
        // The first tangent points to smaller d.
        let mut tangent: Vec<f64> = vec![0.0; n + 1];
        tangent[n] = -1.0;
        let mut h = ds;
        let mut least = f64::INFINITY;
        while points.len() < max_points && h > 1e-6 * ds {
            // Tangent: [J; tᵀ] t' = [0; 1], normalised, in the direction of the last one.
            let mut a = jacobian(&x[..n]);
            a.extend_from_slice(&weighted(&tangent));
            let lu = Lu::new(a, n + 1)?;
            let mut rhs = vec![0.0; n + 1];
            rhs[n] = 1.0;
            let mut t = lu.solve(&rhs);
            let tn = length(&t);
            t.iter_mut().for_each(|v| *v /= tn);
            let tw = weighted(&t);
            // Predictor, then Newton on [F(x) = 0, tᵀ(x − x_pred) = 0].
            let pred: Vec<f64> = x.iter().zip(&t).map(|(x, t)| x + h * t).collect();
            let mut y = pred.clone();
            let mut converged = false;
            for _ in 0..12 {
                let r = residual(&y[..n], y[n]);
                if norm(&r) <= 1e-11 * scale * (n as f64).sqrt() {
                    converged = true;
                    break;
                }
                let mut a = jacobian(&y[..n]);
                a.extend_from_slice(&tw);
                let Some(lu) = Lu::new(a, n + 1) else { break };
                let mut b: Vec<f64> = r.iter().map(|v| -v).collect();
                let along: f64 = y
                    .iter()
                    .zip(&pred)
                    .zip(&tw)
                    .map(|((y, p), t)| (y - p) * t)
                    .sum();
                b.push(-along);
                let step = lu.solve(&b);
                y.iter_mut().zip(&step).for_each(|(y, s)| *y += s);
            }
            if !converged {
                h *= 0.5;
                continue;
            }
            tangent = t;
            x = y;
            let f = force(&x[..n]);
            points.push((x[n], f));
            least = least.min(f);
            if least < 0.0 && f >= 0.5 * least {
                break;
            }
            h = (h * 1.2).min(ds);
        }
        Some(points)
    }
}
