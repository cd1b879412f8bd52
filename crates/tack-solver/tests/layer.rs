//! An elastic layer (film) of thickness h on a rigid base through the solvers: periodic
//! waviness in full contact against the layer's compliance (and its thick and thin limits), and
//! a rigid sphere on a bonded incompressible film — Hertz and JKR pull-off — against an exact
//! axisymmetric layer theory (a Nyström solve of the Fredholm equation, sharing only the
//! compliance factor S and the Gauss–Legendre rule with the library) and Shull's
//! finite-thickness corrections.

use std::f64::consts::PI;
use tack_analytics::westergaard_p_star;
use tack_geometry::{Boundary, Grid, Sphere, Surface, Waviness1d};
use tack_kernels::{
    Interface, Layer, gauss_legendre, layer_compliance_factor, layer_operator_for, operator_for,
};
use tack_solver::{
    AdhesiveOptions, AdhesiveSolver, ApproachPath, ContactSolver, KAPPA, SnapshotRequest,
    SolverOptions,
};

// ---------------------------------------------------------------------------------------------
// 1. Periodic waviness in full contact.
// ---------------------------------------------------------------------------------------------

/// A waviness h_w[1 − cos(2πx/λ)] on one period of `n` elements (an n × 1 periodic grid),
/// pressed into full contact by the layer of thickness kh/k. Returns (p̄, p1, worst residual of
/// the fit p̄ + p1 cos kx over p1), from the solver's pressure field.
fn full_contact_amplitude(n: usize, kh: f64, nu: f64, interface: Interface) -> (f64, f64, f64) {
    let (e_star, lambda, h_w) = (1.0, 1.0, 0.01);
    let k = 2.0 * PI / lambda;
    let grid = Grid::new(n, 1, lambda / n as f64, Boundary::Periodic).unwrap();
    let surface = Surface::from_shape(grid, &Waviness1d::new(h_w, lambda).unwrap());
    let layer = Layer {
        thickness: kh / k,
        poisson: nu,
        interface,
    };
    let op = layer_operator_for(grid, e_star, &layer).unwrap();
    let mut solver = ContactSolver::new(op, &surface, SolverOptions::default()).unwrap();
    // Beyond the mean height h_w: full contact (the approach is from the deformed mean plane).
    let st = solver.solve(1.1 * h_w).unwrap();
    assert!(st.full_contact && st.converged && st.n_contact == n);
    let cos: Vec<f64> = (0..n).map(|i| (k * grid.x(i)).cos()).collect();
    let mean = st.pressure.iter().sum::<f64>() / n as f64;
    let p1 = 2.0 / n as f64
        * st.pressure
            .iter()
            .zip(&cos)
            .map(|(p, c)| p * c)
            .sum::<f64>();
    let resid = st
        .pressure
        .iter()
        .zip(&cos)
        .fold(0.0f64, |m, (p, c)| m.max((p - mean - p1 * c).abs()))
        / p1.abs();
    (mean, p1, resid)
}

/// |p1| = h_w / C(k), C(k) = S(kh)·2/(E*k), E* = λ = 1, h_w = 0.01.
fn compliance_amplitude(kh: f64, nu: f64, interface: Interface) -> f64 {
    let k = 2.0 * PI;
    0.01 / (layer_compliance_factor(kh, nu, interface) * 2.0 / k)
}

#[test]
fn periodic_waviness_in_full_contact_follows_the_layer_compliance() {
    // The periodic layer operator multiplies each grid wave vector by the continuum compliance
    // S(|q|h)·2/(E*|q|) itself (periodic_layer.rs: no element-shape or sinc factor), and the
    // sampled waviness is exactly the grid's first cosine mode; so the discrete operator's
    // eigenvalue at k = 2π/λ *is* C(k), for λ/Δx = 64 and 128 alike, and full contact is solved
    // in closed form (solve_zero_mean). Expected: p = p̄ + p1 cos kx with p1 = h_w/C(k) to
    // round-off and p̄ = |p1| (the least mean pressure keeping min p ≥ 0; the sample at x = λ/2
    // has cos = −1). Measured: worst |p1/(h_w/C) − 1| = 1.6e-15 over the 15 cases × 2 meshes,
    // worst fit residual 2.1e-14, worst |p̄/p1 − 1| = 5.3e-15. Tolerance 1e-10 (the solver's
    // own stopping tolerance, which a closed form does not need).
    let mut cases = Vec::new();
    for kh in [0.01, 0.1, 1.0, 10.0, 100.0] {
        for nu in [0.3, 0.5] {
            cases.push((kh, nu, Interface::Bonded));
        }
        cases.push((kh, 0.3, Interface::Frictionless));
    }
    let (mut worst, mut worst_fit, mut worst_mean) = (0.0f64, 0.0f64, 0.0f64);
    for n in [64, 128] {
        for &(kh, nu, interface) in &cases {
            let (mean, p1, fit) = full_contact_amplitude(n, kh, nu, interface);
            let expected = compliance_amplitude(kh, nu, interface);
            let rel = (p1 / expected - 1.0).abs();
            println!(
                "λ/Δx = {n}, kh = {kh}, ν = {nu}, {}: p1 = {p1:.6e}, h_w/C = {expected:.6e}, \
                 rel {rel:.1e}, fit {fit:.1e}, p̄/p1 − 1 = {:.1e}",
                interface.name(),
                mean / p1 - 1.0
            );
            worst = worst.max(rel);
            worst_fit = worst_fit.max(fit);
            worst_mean = worst_mean.max((mean / p1 - 1.0).abs());
            assert!(rel < 1e-10, "n {n} kh {kh} ν {nu} {interface:?}: {rel}");
            assert!(fit < 1e-10, "n {n} kh {kh} ν {nu} {interface:?}: {fit}");
            assert!((mean / p1 - 1.0).abs() < 1e-10);
        }
    }
    println!("worst: p1 {worst:.1e}, fit {worst_fit:.1e}, p̄ {worst_mean:.1e}");
}

#[test]
fn periodic_full_contact_reaches_the_thick_and_thin_limits() {
    let n = 64;
    let (e_star, lambda, h_w) = (1.0, 1.0, 0.01);
    let k = 2.0 * PI / lambda;
    // kh = 100: 1 − S < 1e-80, the half-space. Westergaard's full-contact pressure πE*h_w/λ is
    // the amplitude p1 (and the mean p̄). Measured: p1 2.2e-16, p̄ 1.6e-15 relative;
    // tolerance 1e-12.
    for (nu, interface) in [
        (0.3, Interface::Bonded),
        (0.5, Interface::Bonded),
        (0.3, Interface::Frictionless),
    ] {
        let (mean, p1, _) = full_contact_amplitude(n, 100.0, nu, interface);
        let p_star = westergaard_p_star(e_star, h_w, lambda);
        println!(
            "kh = 100, ν = {nu}, {}: p1/p* − 1 = {:.1e}, p̄/p* − 1 = {:.1e}",
            interface.name(),
            p1 / p_star - 1.0,
            mean / p_star - 1.0
        );
        assert!((p1 / p_star - 1.0).abs() < 1e-12);
        assert!((mean / p_star - 1.0).abs() < 1e-12);
    }
    let x: f64 = 0.01; // kh of the thin cases
    let h = x / k;
    // Thin, compressible, bonded (ν = 0.3): uniaxial strain, C = h(1+ν)(1−2ν)/(E(1−ν)),
    // E = E*(1−ν²). Expanding layer.rs's S to second order, S = S_thin[1 + c x² + O(x⁴)] with
    // c = (3−4ν)/(3(1−2ν)) − 1/(1−ν) = 0.0714 at ν = 0.3: the relative difference 7.1e-6 at
    // kh = 0.01. Tolerance 2|c|x²; measured 7.1e-6 (the expansion's own term).
    {
        let nu: f64 = 0.3;
        let (_, p1, _) = full_contact_amplitude(n, x, nu, Interface::Bonded);
        let e = e_star * (1.0 - nu * nu);
        let c_thin = h * (1.0 + nu) * (1.0 - 2.0 * nu) / (e * (1.0 - nu));
        let c2 = (3.0 - 4.0 * nu) / (3.0 * (1.0 - 2.0 * nu)) - 1.0 / (1.0 - nu);
        let rel = (p1 * c_thin / h_w - 1.0).abs();
        println!(
            "thin bonded ν = 0.3: p1·C_uniaxial/h_w − 1 = {rel:.2e} (c x² = {:.2e})",
            c2 * x * x
        );
        assert!(rel < 2.0 * c2.abs() * x * x, "{rel}");
    }
    // Thin, incompressible, bonded: the cubic law, C = h³k²/(3μ), μ = E/3 = E*(1−ν²)/3; layer.rs:
    // S = (2/3)(kh)³[1 − (9/5)(kh)² + …]: the stiffer law's p1 is larger by 1.8e-4 at kh = 0.01.
    // Tolerance 2·(9/5)x²; measured 1.8e-4.
    {
        let (_, p1, _) = full_contact_amplitude(n, x, 0.5, Interface::Bonded);
        let mu = e_star * 0.75 / 3.0;
        let c_cubic = h * h * h * k * k / (3.0 * mu);
        let rel = (p1 * c_cubic / h_w - 1.0).abs();
        println!(
            "thin bonded ν = 0.5: p1·C_cubic/h_w − 1 = {rel:.2e} ((9/5)x² = {:.2e})",
            1.8 * x * x
        );
        assert!(rel < 3.6 * x * x, "{rel}");
    }
    // Thin, frictionless: the film slides in plane stress along k, C = h/E* for every ν;
    // S = (kh/2)[1 − (kh)⁴/45 + …]: 2.2e-10 at kh = 0.01. Tolerance 1e-9; measured 2.2e-10.
    for nu in [0.3, 0.5] {
        let (_, p1, _) = full_contact_amplitude(n, x, nu, Interface::Frictionless);
        let rel = (p1 * (h / e_star) / h_w - 1.0).abs();
        println!("thin frictionless ν = {nu}: p1·(h/E*)/h_w − 1 = {rel:.2e}");
        assert!(rel < 1e-9, "{rel}");
    }
}

// ---------------------------------------------------------------------------------------------
// 2. A rigid sphere on a bonded incompressible film.
// ---------------------------------------------------------------------------------------------
//
// The literature's corrections, as recalled (the papers' text could not be retrieved here, so
// the coefficients below are from memory and are checked against the exact theory further
// down rather than trusted): Shull (2002), Mater. Sci. Eng. R 36, 1–45, §4, fits to the
// finite-element results of Shull, Ahn, Chen, Flanigan & Crosby (1998), Macromol. Chem. Phys.
// 199, 489, for a rigid sphere of radius R on an incompressible (ν = 1/2) layer of thickness h
// bonded to a rigid base, x = a/h, E* = E/(1 − ν²) = 4E/3:
//   flat-punch compliance  C(a)   = [1 + 1.33x + 1.33x³]⁻¹ / (2E*a)
//   Hertz load             P_H(a) = (4E*a³/(3R)) (1 + 0.33x³)
//   Hertz depth            δ_H(a) = (a²/R) (0.4 + 0.6 e^{−1.8x})
//   JKR                    G = (P_H − P)² (−dC/da)/(4πa) = γ,  δ = δ_H − (P_H − P) C.
// They are empirical fits, quoted for a/h up to about 1 with errors of a few per cent (not
// verified here), reducing to Hertz and JKR as x → 0. The three Hertz fits are not consistent
// with one another: a smooth contact has dP_H/dδ_H = 1/C exactly, and the δ_H that P_H and C
// imply (shull_consistent_depth) differs from the exponential fit by 5–10% at a/h = 0.25–1.

fn shull_g(x: f64) -> f64 {
    1.0 + 1.33 * x + 1.33 * x * x * x
}
fn shull_compliance(a: f64, h: f64, e: f64) -> f64 {
    1.0 / (2.0 * e * a * shull_g(a / h))
}
/// −dC/da.
fn shull_compliance_slope(a: f64, h: f64, e: f64) -> f64 {
    let x = a / h;
    let g = shull_g(x);
    (g + x * (1.33 + 3.99 * x * x)) / (2.0 * e * a * a * g * g)
}
fn shull_hertz_load(a: f64, h: f64, e: f64, r: f64) -> f64 {
    let x = a / h;
    4.0 * e * a * a * a / (3.0 * r) * (1.0 + 0.33 * x * x * x)
}
fn shull_hertz_depth(a: f64, h: f64, r: f64) -> f64 {
    a * a / r * (0.4 + 0.6 * (-1.8 * a / h).exp())
}
/// The Hertz depth that Shull's P_H and C imply together: a smooth non-adhesive contact
/// stiffens as dP/dδ = 1/C(a), so δ_H(a) = ∫₀^a C (dP_H/da′) da′ (midpoint rule, 4000 panels;
/// the integrand 2a′(1 + 0.66x′³)/g(x′) is smooth).
fn shull_consistent_depth(a: f64, h: f64, r: f64) -> f64 {
    let m = 4000;
    (0..m)
        .map(|i| {
            let t = (i as f64 + 0.5) / m as f64 * a;
            let x = t / h;
            2.0 * t * (1.0 + 0.66 * x * x * x) / (r * shull_g(x)) * a / m as f64
        })
        .sum()
}

/// The force minimum of Shull's JKR branch, P(a) = P_H(a) − √(4πaγ/(−dC/da)) (golden section
/// on [lo, hi]): (a, P).
fn shull_pull_off(gamma: f64, h: f64, mut lo: f64, mut hi: f64) -> (f64, f64) {
    let force = |a: f64| {
        shull_hertz_load(a, h, 1.0, 1.0)
            - (4.0 * PI * a * gamma / shull_compliance_slope(a, h, 1.0)).sqrt()
    };
    let phi = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..60 {
        let (m1, m2) = (hi - phi * (hi - lo), lo + phi * (hi - lo));
        if force(m1) < force(m2) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    let a = 0.5 * (lo + hi);
    (a, force(a))
}

// ---------------------------------------------------------------------------------------------
// The exact axisymmetric layer theory (an independent reference for the BEM, sharing only S).
// ---------------------------------------------------------------------------------------------
//
// With the pressure's Hankel transform written p̂(k) = ∫₀^a φ(t) cos(kt) dt, the surface
// displacement u(r) = (2/E*)∫₀^∞ S(kh) p̂(k) J₀(kr) dk equals a prescribed g(r) on r < a iff
// (Abel transform) φ(s) − (2/π)∫₀^a K(s,t) φ(t) dt = (E*/2)Ψ(s), with
// K(s,t) = ½[F(s−t) + F(s+t)], F(u) = ∫₀^∞ (1 − S(kh)) cos(ku) dk, and
// Ψ(s) = (2/π) d/ds ∫₀^s r g(r)/√(s² − r²) dr: 2δ/π for a flat punch (g = δ), −2s²/(πR) for
// g = −r²/(2R). The load is P = 2π∫₀^a φ dt; the pressure is bounded at r = a iff φ(a) = 0.
// (The half-space, K = 0: φ = E*δ/π gives P = 2E*aδ; Hertz gives δ = a²/R, P = 4E*a³/(3R).)
// This is a Fredholm equation of the second kind with a smooth kernel (F is analytic within
// |Im u| < 2αh), solved by Nyström on Gauss–Legendre nodes: exponentially convergent.
// For a contact of radius a: the flat-punch stiffness k(a) = 1/C(a) = 2π∫φ₁ (unit δ), the Hertz
// depth δ_H = −φ₂(a)/φ₁(a) and load P_H = δ_H k + 2π∫φ₂, and the JKR branch (exact for the
// zero-range limit by superposing a punch on the Hertz field: G = (P_H − P)² k′/(4πa k²) = γ).

/// The bonded ν = 1/2 layer of thickness `h` (E* = R = 1) in the exact axisymmetric theory.
struct LayerTheory {
    h: f64,
    /// Quadrature of F: nodes x = kh and weights (1 − S(x)) dx on [0, 25] (1 − S(25) < 1e-18).
    f_nodes: Vec<(f64, f64)>,
    /// Nyström nodes per contact.
    m: usize,
}

/// One contact radius: (punch stiffness k = 1/C, Hertz depth δ_H, Hertz load P_H).
struct Contact {
    k: f64,
    depth: f64,
    load: f64,
}

impl LayerTheory {
    /// Resolves F(u) for u ≤ `u_max` (panels ≤ 1/4 in x and ≤ half a cosine period).
    fn new(h: f64, u_max: f64, m: usize) -> Self {
        let width = 0.25f64.min(PI / (u_max / h).max(1.0) / 2.0);
        let panels = (25.0 / width).ceil() as usize;
        let width = 25.0 / panels as f64;
        let rule = gauss_legendre(16);
        let mut f_nodes = Vec::with_capacity(panels * 16);
        for p in 0..panels {
            for &(t, w) in &rule {
                let x = (p as f64 + 0.5 + 0.5 * t) * width;
                let s = layer_compliance_factor(x, 0.5, Interface::Bonded);
                f_nodes.push((x, 0.5 * width * w * (1.0 - s)));
            }
        }
        Self { h, f_nodes, m }
    }

    fn f(&self, u: f64) -> f64 {
        let scale = u / self.h;
        self.f_nodes
            .iter()
            .map(|&(x, w)| w * (x * scale).cos())
            .sum::<f64>()
            / self.h
    }

    fn contact(&self, a: f64) -> Contact {
        let m = self.m;
        let rule: Vec<(f64, f64)> = gauss_legendre(m)
            .into_iter()
            .map(|(t, w)| (0.5 * a * (t + 1.0), 0.5 * a * w))
            .collect();
        let kernel = |s: f64, t: f64| 0.5 * (self.f(s - t) + self.f(s + t));
        // A = I − (2/π) K W; right-hand sides (E*/2)Ψ: 1/π (punch) and −s²/π (paraboloid).
        let mut mat = vec![vec![0.0; m + 2]; m];
        for (i, row) in mat.iter_mut().enumerate() {
            let s = rule[i].0;
            for (j, &(t, w)) in rule.iter().enumerate() {
                row[j] = -2.0 / PI * kernel(s, t) * w + if i == j { 1.0 } else { 0.0 };
            }
            row[m] = 1.0 / PI;
            row[m + 1] = -s * s / PI;
        }
        // Gaussian elimination with partial pivoting, two right-hand sides.
        for col in 0..m {
            let piv = (col..m)
                .max_by(|&i, &j| mat[i][col].abs().total_cmp(&mat[j][col].abs()))
                .unwrap();
            mat.swap(col, piv);
            let prow = mat[col].clone();
            for row in mat.iter_mut().skip(col + 1) {
                let f = row[col] / prow[col];
                for (r, p) in row.iter_mut().zip(&prow).skip(col) {
                    *r -= f * p;
                }
            }
        }
        let mut phi = vec![[0.0; 2]; m];
        for i in (0..m).rev() {
            for c in 0..2 {
                let s: f64 = (i + 1..m).map(|j| mat[i][j] * phi[j][c]).sum();
                phi[i][c] = (mat[i][m + c] - s) / mat[i][i];
            }
        }
        // Nyström interpolation to s = a, and the loads.
        let mut at_a = [1.0 / PI, -a * a / PI];
        let mut total = [0.0; 2];
        for (j, &(t, w)) in rule.iter().enumerate() {
            let kw = 2.0 / PI * kernel(a, t) * w;
            for c in 0..2 {
                at_a[c] += kw * phi[j][c];
                total[c] += 2.0 * PI * w * phi[j][c];
            }
        }
        let depth = -at_a[1] / at_a[0];
        Contact {
            k: total[0],
            depth,
            load: depth * total[0] + total[1],
        }
    }

    /// The JKR branch at radius a: (P, δ).
    fn jkr(&self, a: f64, gamma: f64) -> (f64, f64) {
        let c = self.contact(a);
        let da = 1e-4 * a;
        let slope = (self.contact(a + da).k - self.contact(a - da).k) / (2.0 * da);
        let p1 = (4.0 * PI * a * gamma * c.k * c.k / slope).sqrt();
        (c.load - p1, c.depth - p1 / c.k)
    }

    /// The force minimum on the JKR branch (golden section on [lo, hi]): (a, P, δ).
    fn pull_off(&self, gamma: f64, mut lo: f64, mut hi: f64) -> (f64, f64, f64) {
        let phi = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..40 {
            let (m1, m2) = (hi - phi * (hi - lo), lo + phi * (hi - lo));
            if self.jkr(m1, gamma).0 < self.jkr(m2, gamma).0 {
                hi = m2;
            } else {
                lo = m1;
            }
        }
        let a = 0.5 * (lo + hi);
        let (p, d) = self.jkr(a, gamma);
        (a, p, d)
    }
}

/// The elastic body under the sphere on a free grid: the bonded ν = 1/2 film of thickness `h`
/// (E* = 1), or the half-space when `h` is None.
fn body(grid: Grid, h: Option<f64>) -> Box<dyn tack_kernels::ElasticOperator> {
    match h {
        Some(h) => {
            let layer = Layer {
                thickness: h,
                poisson: 0.5,
                interface: Interface::Bonded,
            };
            layer_operator_for(grid, 1.0, &layer).unwrap()
        }
        None => operator_for(grid, 1.0).unwrap(),
    }
}

/// Non-adhesive indentation of a sphere (R = E* = 1) to approach `d` on a free grid of
/// spacing `dx` and half-width `half`. Returns (force, contact radius √(area/π), contact
/// stiffness dP/dδ at a fixed contact set).
fn indent(d: f64, h: Option<f64>, dx: f64, half: f64) -> (f64, f64, f64) {
    let n = 2 * (half / dx).ceil() as usize + 1;
    let grid = Grid::square(n, dx, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    let mut solver = ContactSolver::new(body(grid, h), &surface, SolverOptions::default()).unwrap();
    let st = solver.solve(d).unwrap();
    assert!(st.converged);
    // A tiny extra approach keeps the contact set: the force increment is that set's stiffness
    // as a flat punch.
    let eps = 1e-7 * d;
    let up = solver.solve(d + eps).unwrap();
    assert!(up.converged && up.n_contact == st.n_contact);
    (st.force, (st.area / PI).sqrt(), (up.force - st.force) / eps)
}

#[test]
fn sphere_on_a_bonded_film_hertz_part() {
    // (a) The exact theory itself: Nyström with 16 nodes agrees with 24 and 48 to 1e-10 (run
    // once: k/(2E*a) = 1.3694701584, 1.9329343708, 3.6187358490 at a/h = 0.25, 0.5, 1 for every
    // m); a layer of h = 1e7·a is the half-space to ~1e-7 (the O(a/h) correction).
    let (a, r) = (0.1, 1.0);
    let thick = LayerTheory::new(1e7 * a, 2.0 * a, 16).contact(a);
    assert!((thick.k / (2.0 * a) - 1.0).abs() < 1e-6);
    assert!((thick.depth * r / (a * a) - 1.0).abs() < 1e-6);
    assert!((thick.load * 3.0 * r / (4.0 * a * a * a) - 1.0).abs() < 1e-6);
    // (b) BEM mesh error on the half-space at a/Δx = 24 (Hertz: δ = a²/R, P = 4E*a³/(3R),
    // punch stiffness 2E*a). Measured: P 5.5e-5 at the exact depth; the stair-stepped area
    // overstates a by 0.54% (√(area/π)); the contact set's stiffness is 2E*a to 7.5e-4.
    let dx = a / 24.0;
    let (p0, a0, k0) = indent(a * a / r, None, dx, 1.4 * a);
    let mesh_p = (p0 * 3.0 * r / (4.0 * a * a * a) - 1.0).abs();
    let mesh_a = a0 / a - 1.0;
    let mesh_k = (k0 / (2.0 * a) - 1.0).abs();
    println!(
        "half-space, a/Δx = 24: |P/P_Hertz − 1| = {mesh_p:.1e}, a/a_Hertz − 1 = {mesh_a:.1e}, \
         |k/(2E*a) − 1| = {mesh_k:.1e}"
    );
    // Measured (Shull/exact − 1 | BEM/exact − 1 at a/Δx = 24):
    //   a/h    1/C     P_H     δ_H exp  δ_H cons |  P        a        k
    //   0.25  −0.0118 −0.0065 −0.0507  −0.0050   | +7e-5    +0.00536 +0.0008
    //   0.5   −0.0526 −0.0349 −0.0751  −0.0009   | +1.0e-4  +0.00536 +0.0015
    //   1     +0.0114 −0.0571 −0.1077  −0.0192   | +1.3e-4  +0.00536 +0.0019
    // Shull's compliance and load fits are within 6% of the exact theory up to a/h = 1 (the
    // load's error grows with a/h: 5.7% at a/h = 1, where the fits are at the end of their
    // range); the exponential depth fit, as recalled, is off by 5–11% and is only printed;
    // the depth that P_H and C imply is within 2%. Tolerances: the fits within 6% (1/C, P_H)
    // and 2.5% (consistent δ_H) — the "few per cent" of an empirical fit, no mesh error (the
    // exact theory is converged to 1e-10); the BEM within its half-space mesh error: P at the
    // exact depth within 1e-3 (measured ≤ 1.3e-4; the half-space's 5.5e-5), √(area/π) within
    // ±1e-3 of the half-space's own stair-step excess, the contact set's stiffness within 5e-3
    // of the exact k(a) (measured ≤ 1.9e-3; the half-space's 7.5e-4).
    for x in [0.25, 0.5, 1.0] {
        let h = a / x;
        let exact = LayerTheory::new(h, 2.0 * a, 16);
        let c = exact.contact(a);
        // (c) Shull's fits against the exact theory.
        let fit_k = 1.0 / (shull_compliance(a, h, 1.0) * c.k) - 1.0;
        let fit_p = shull_hertz_load(a, h, 1.0, r) / c.load - 1.0;
        let fit_d_exp = shull_hertz_depth(a, h, r) / c.depth - 1.0;
        let fit_d_cons = shull_consistent_depth(a, h, r) / c.depth - 1.0;
        println!(
            "a/h = {x}: exact k/(2E*a) = {:.5}, δ_H R/a² = {:.5}, P_H 3R/(4E*a³) = {:.5}; \
             Shull/exact − 1: 1/C {fit_k:+.4}, P_H {fit_p:+.4}, δ_H (exp fit) {fit_d_exp:+.4}, \
             δ_H (consistent) {fit_d_cons:+.4}",
            c.k / (2.0 * a),
            c.depth * r / (a * a),
            c.load * 3.0 * r / (4.0 * a * a * a)
        );
        assert!(fit_k.abs() < 0.06 && fit_p.abs() < 0.06, "a/h = {x}");
        assert!(fit_d_cons.abs() < 0.025, "a/h = {x}");
        // (d) The BEM at the exact Hertz depth of radius a.
        let (p, a_m, k) = indent(c.depth, Some(h), dx, 1.4 * a);
        let (err_p, err_a, err_k) = (p / c.load - 1.0, a_m / a - 1.0, k / c.k - 1.0);
        println!("         BEM (a/Δx = 24)/exact − 1: P {err_p:+.5}, a {err_a:+.5}, k {err_k:+.5}");
        assert!(err_p.abs() < 1e-3, "a/h = {x}: {err_p}");
        assert!((err_a - mesh_a).abs() < 1e-3, "a/h = {x}: {err_a}");
        assert!(err_k.abs() < 5e-3, "a/h = {x}: {err_k}");
    }
}

/// The BEM pull-off of a sphere (E* = R = 1, γ) on the film of thickness `h` (None: the
/// half-space), `ratio` elements per `a_f` (the expected pull-off radius): one load step to
/// the approach whose rigid penetration disc has radius 1.6 a_f, retraction by 0.1/ratio of that
/// approach until detached. Returns the least force on the path.
fn bem_pull_off(gamma: f64, h: Option<f64>, a_f: f64, ratio: f64) -> f64 {
    let dx = a_f / ratio;
    let n = 2 * (1.2 * 1.6 * ratio).ceil() as usize + 3;
    let grid = Grid::square(n, dx, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    let mut solver = AdhesiveSolver::new(
        body(grid, h),
        &surface,
        gamma,
        KAPPA,
        AdhesiveOptions::default(),
    )
    .unwrap();
    let depth = (1.6 * a_f).powi(2) / 2.0;
    let path = ApproachPath {
        start: depth,
        max_approach: depth,
        load_step: depth,
        unload_step: 0.1 * depth / ratio,
        coarse_unload_step: None,
        refine_pull_off: false,
        retract_to: None,
        max_steps: 100_000,
    };
    let res = solver
        .run_path(&path, &SnapshotRequest::None, &mut ())
        .unwrap();
    assert!(res.completed && res.all_converged());
    assert!(res.records.iter().all(|s| !s.edge_contact));
    res.pull_off_force()
}

#[test]
fn sphere_pull_off_from_a_bonded_film() {
    // γ = 1e-3, E* = R = 1, films with a_F∞/h = 0.5 and 1 (a_F∞ = (9πγR²/8E*)^{1/3}, the
    // half-space's pull-off radius). Measured:
    //   half-space: F/F_JKR = 1.1285 (a_F/Δx = 10), 1.0638 (20), Richardson 0.9991
    //   a_F∞/h = 0.5: exact a_F/h = 0.5113, F/F_JKR∞ = 1.0645; Shull a_F/h = 0.5097,
    //                 F_Shull/F_exact = 1.0108; BEM F/F_exact = 1.1334, 1.0716, Richardson 1.0099
    //   a_F∞/h = 1:   exact a_F/h = 0.9876, F/F_JKR∞ = 1.2010; Shull a_F/h = 0.9665,
    //                 F_Shull/F_exact = 0.9305; BEM F/F_exact = 1.0994, 1.0480, Richardson 0.9966
    // The film raises the pull-off (the exact theory: +6% and +20%); Shull's corrected JKR, built on
    // the derivative of the compliance fit, is 1% high at a_F/h = 0.5 and 7% low at a_F/h ≈ 1
    // — the literature's correction is itself approximate there. The BEM (JKR-limit criterion)
    // is too adhesive and first order, as on the half-space, and its Richardson value lies
    // within 1% of the exact theory. The Richardson value depends on where the front falls on
    // the grid: the same runs with Δx taken from Shull's a_F instead (0.3% and 2% coarser) gave
    // 1.0037 and 1.0269 (and 1.0142 from a_F/Δx = 20, 40 at a_F∞/h = 1, 10 s a run: not
    // affordable here). Tolerances: BEM above the exact value and the finer closer (as on the
    // half-space), Richardson within 3% (that grid-phase scatter); Shull within 8% of the exact
    // theory (its measured 7% at the edge of the fits' range a/h ≲ 1).
    let gamma = 1e-3;
    let a_hs = (9.0 * PI * gamma / 8.0).powf(1.0 / 3.0);
    let f_hs = -1.5 * PI * gamma;
    // Half-space, same procedure: the criterion's mesh error.
    let (c0, f0) = (
        bem_pull_off(gamma, None, a_hs, 10.0),
        bem_pull_off(gamma, None, a_hs, 20.0),
    );
    println!(
        "half-space: F/F_JKR = {:.4} (a_F/Δx = 10), {:.4} (20), Richardson {:.4}",
        c0 / f_hs,
        f0 / f_hs,
        (2.0 * f0 - c0) / f_hs
    );
    for x in [0.5, 1.0] {
        let h = a_hs / x;
        let exact = LayerTheory::new(h, 4.0 * a_hs, 16);
        let (a_f, f_exact, d_f) = exact.pull_off(gamma, 0.3 * a_hs, 1.5 * a_hs);
        // Retraction under approach control passes the force minimum if δ still rises with a
        // there (the approach-control jump comes later, at a smaller radius).
        let stable = exact.jkr(1.01 * a_f, gamma).1 > d_f;
        let (a_s, f_s) = shull_pull_off(gamma, h, 0.3 * a_hs, 1.5 * a_hs);
        let (coarse, fine) = (
            bem_pull_off(gamma, Some(h), a_f, 10.0),
            bem_pull_off(gamma, Some(h), a_f, 20.0),
        );
        let (coarse, fine) = (coarse / f_exact, fine / f_exact);
        let rich = 2.0 * fine - coarse;
        println!(
            "a_F∞/h = {x}: exact a_F/h = {:.4}, F/F_JKR∞ = {:.4} (passed on retraction: \
             {stable}); Shull a_F/h = {:.4}, F_Shull/F_exact = {:.4}; BEM F/F_exact = \
             {coarse:.4} (10), {fine:.4} (20), Richardson {rich:.4}",
            a_f / h,
            f_exact / f_hs,
            a_s / h,
            f_s / f_exact,
        );
        assert!(stable, "a_F∞/h = {x}");
        assert!(f_exact < f_hs, "the film raises the pull-off");
        assert!(coarse > fine && fine > 1.0, "a_F∞/h = {x}");
        assert!((rich - 1.0).abs() < 0.03, "a_F∞/h = {x}: {rich}");
        assert!((f_s / f_exact - 1.0).abs() < 0.08, "a_F∞/h = {x}");
    }
}
