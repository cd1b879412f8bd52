//! Free (non-periodic) boundaries on an elastic layer: influence coefficients from the layer's
//! axisymmetric kernel, integrated numerically, applied by the zero-padded FFT of
//! [`crate::FreeOperator`] (docs/theory.md §2.5).
//!
//! A unit point load on the layer displaces the surface at distance r by
//! `G(r) = 1/(πE* r) − g(r)`, with the correction
//! `g(r) = (1/(πE* h)) ∫₀^∞ (1 − S(x)) J₀(x r/h) dx` (a Hankel transform; S is
//! [`crate::layer_compliance_factor`]). Since `1 − S(x) ~ x² e^{−2x}`, g is bounded and smooth
//! (analytic for |Im r| < 2h) and the integral may stop at x = 25. Far from the load the layer's
//! displacement dies out, `G(r) ∝ e^{−α r/h}` with α the least imaginary part of a pole of
//! `S(x)/x` (bonded: α ≥ 0.739, the ν = 1/2 value; frictionless: α = 2.106), so beyond
//! [`cutoff`] thicknesses G is zero to round-off and `g = 1/(πE* r)`.
//!
//! The influence coefficient of an element is Love's half-space coefficient minus the element
//! integral of g: `K(X, Y) = love(X, Y)/E* − ∫_element g(|(X, Y) − r'|) dA'`. g is tabulated
//! once in ρ = r/h (step 1/64, each entry a Gauss–Legendre quadrature over panels that resolve
//! both `1 − S` and the Bessel oscillation), read by 8-point Lagrange interpolation, and
//! integrated over the element with 8 × 8 Gauss–Legendre points on each of `m × m` sub-squares
//! no wider than h (m ≤ 64). Elements wholly beyond the cutoff get K = 0.

use ndarray::{Array2, ArrayView2, ArrayViewMut2};
use rayon::prelude::*;
use tack_geometry::Grid;

use crate::FreeOperator;
use crate::layer::{Interface, Layer};
use crate::love::love_rectangle;
use crate::periodic_layer::layer_stiffness_spectrum;
use crate::{ElasticOperator, KernelError, check_modulus};

/// Distance, in thicknesses, beyond which the layer's point-load displacement is taken as zero:
/// `e^{−α ρ}` < 1e-17 there (α from the module documentation).
pub(crate) fn cutoff(interface: Interface) -> f64 {
    match interface {
        Interface::Bonded => 56.0,
        Interface::Frictionless => 20.0,
    }
}

/// Upper limit of the Hankel integral in x = qh: `1 − S(25) < 1e-18`.
const X_MAX: f64 = 25.0;
/// Table step in ρ = r/h.
const STEP: f64 = 1.0 / 64.0;
/// Gauss–Legendre points per panel of the Hankel integral and per side of a sub-square.
const GL_POINTS: usize = 8;
/// Most sub-squares per element side.
const MAX_SUB: usize = 64;

/// The `n`-point Gauss–Legendre rule on [−1, 1] as `(node, weight)` pairs, nodes from the
/// largest down: exact for polynomials of degree up to `2n − 1`. Each node is the root of the
/// Legendre polynomial P_n found by Newton's method from the classical estimate
/// `cos(π(i + 3/4)/(n + 1/2))` (to a step below 1e-16), its weight `2/((1 − x²) P_n′(x)²)`.
/// Used by the layer kernel's quadratures here and by the layer theory of the tests.
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// The correction kernel in units of `1/(πE* h)`: `ĝ(ρ) = ∫₀^25 (1 − S(x)) J₀(xρ) dx`,
/// tabulated on `[0, ρ_max]` and `1/ρ` beyond the cutoff.
pub(crate) struct Correction {
    table: Vec<f64>,
    cutoff: f64,
}

impl Correction {
    /// Tabulates ĝ for `ρ ≤ min(rho_max, cutoff)`.
    pub(crate) fn new(layer: &Layer, rho_max: f64) -> Self {
        let cutoff = cutoff(layer.interface);
        let rho_top = rho_max.min(cutoff);
        let entries = (rho_top / STEP).ceil() as usize + 8;
        // Panels resolve 1 − S (width ≤ 1/4) and half a Bessel period at the largest ρ.
        let width = (0.25f64).min(std::f64::consts::PI / (rho_top + 8.0 * STEP).max(1.0));
        let panels = (X_MAX / width).ceil() as usize;
        let width = X_MAX / panels as f64;
        let rule = gauss_legendre(2 * GL_POINTS);
        let mut nodes = Vec::with_capacity(panels * rule.len());
        for p in 0..panels {
            let mid = (p as f64 + 0.5) * width;
            for &(t, w) in &rule {
                let x = mid + 0.5 * width * t;
                nodes.push((x, 0.5 * width * w * (1.0 - layer.factor_at(x))));
            }
        }
        let table = (0..entries)
            .into_par_iter()
            .map(|i| {
                let rho = i as f64 * STEP;
                nodes.iter().map(|&(x, w)| w * libm::j0(x * rho)).sum()
            })
            .collect();
        Self { table, cutoff }
    }

    /// ĝ(ρ), ρ ≥ 0: 8-point Lagrange interpolation of the table (even in ρ), `1/ρ` beyond the
    /// cutoff.
    pub(crate) fn eval(&self, rho: f64) -> f64 {
        if rho > self.cutoff {
            return 1.0 / rho;
        }
        let s = rho / STEP;
        let first = s.floor() as isize - 3;
        let mut sum = 0.0;
        for j in 0..8 {
            let node = first + j;
            let mut w = 1.0;
            for m in 0..8 {
                if m != j {
                    w *= (s - (first + m) as f64) / (j - m) as f64;
                }
            }
            sum += w * self.table[node.unsigned_abs()];
        }
        sum
    }
}

impl Layer {
    /// The compliance factor at `x = kh`.
    fn factor_at(&self, x: f64) -> f64 {
        crate::layer_compliance_factor(x, self.poisson, self.interface)
    }
}

/// Influence coefficients `K(i·dx, j·dx)` for offsets `0 ≤ i < nx`, `0 ≤ j < ny` (one quadrant;
/// K is even in both offsets).
pub(crate) fn layer_influence(
    nx: usize,
    ny: usize,
    dx: f64,
    e_star: f64,
    layer: &Layer,
) -> Array2<f64> {
    let h = layer.thickness;
    let reach = ((nx as f64).hypot(ny as f64) + 1.0) * dx;
    let correction = Correction::new(layer, reach / h);
    let sub = ((dx / h).ceil() as usize).clamp(1, MAX_SUB);
    let side = dx / sub as f64;
    let rule = gauss_legendre(GL_POINTS);
    // Source points (offsets from the element centre) and weights of the element quadrature.
    let mut points = Vec::with_capacity(sub * sub * GL_POINTS * GL_POINTS);
    for a in 0..sub {
        for b in 0..sub {
            let (cx, cy) = (
                -dx / 2.0 + (a as f64 + 0.5) * side,
                -dx / 2.0 + (b as f64 + 0.5) * side,
            );
            for &(s, ws) in &rule {
                for &(t, wt) in &rule {
                    let w = ws * wt * side * side / 4.0;
                    points.push((cx + s * side / 2.0, cy + t * side / 2.0, w));
                }
            }
        }
    }
    let far = correction.cutoff * h;
    let scale = 1.0 / (std::f64::consts::PI * e_star * h);
    let values: Vec<f64> = (0..nx * ny)
        .into_par_iter()
        .map(|k| {
            let (x, y) = ((k / ny) as f64 * dx, (k % ny) as f64 * dx);
            let gap = (x - dx / 2.0).max(0.0).hypot((y - dx / 2.0).max(0.0));
            if gap > far {
                return 0.0;
            }
            let integral: f64 = points
                .iter()
                .map(|&(px, py, w)| w * correction.eval((x - px).hypot(y - py) / h))
                .sum();
            love_rectangle(x, y, dx / 2.0, dx / 2.0) / e_star - scale * integral
        })
        .collect();
    Array2::from_shape_vec((nx, ny), values).expect("nx·ny values")
}

/// Influence-matrix operator of an elastic layer on a rigid base loaded only on the grid.
///
/// Like [`crate::FreeOperator`]: the coefficients (module documentation) are sampled on a
/// zero-padded `mx × my` grid, so `apply` is the exact direct sum of them; the preconditioner
/// is the layer's periodic spectral stiffness on the unpadded fast size.
pub struct FreeLayerOperator {
    /// The DC-FFT operator of the layer's coefficients.
    inner: FreeOperator,
    layer: Layer,
}

impl FreeLayerOperator {
    /// Builds the operator for `grid`, the layer's `e_star = E/(1 − ν²)` (> 0) and `layer`
    /// (checked: [`Layer::check`]). Costs one table of the correction kernel (up to ~3600
    /// Hankel integrals) and `m² · 64` kernel reads per coefficient within the cutoff.
    pub fn new(grid: Grid, e_star: f64, layer: Layer) -> Result<Self, KernelError> {
        let e_star = check_modulus(e_star)?;
        layer.check()?;
        let (nx, ny) = grid.shape();
        let dx = grid.dx();
        let quadrant = layer_influence(nx, ny, dx, e_star, &layer);
        let inner =
            FreeOperator::from_quadrant(grid, e_star, &quadrant, quadrant[[0, 0]], |px, py| {
                layer_stiffness_spectrum(px, py, dx, e_star, &layer)
            });
        Ok(Self { inner, layer })
    }

    /// The layer.
    pub fn layer(&self) -> &Layer {
        &self.layer
    }
}

impl ElasticOperator for FreeLayerOperator {
    fn is_half_space(&self) -> bool {
        false
    }

    fn grid(&self) -> &Grid {
        self.inner.grid()
    }
    fn e_star(&self) -> f64 {
        self.inner.e_star()
    }
    fn apply(&mut self, pressure: ArrayView2<f64>, displacement: ArrayViewMut2<f64>) {
        self.inner.apply(pressure, displacement);
    }
    fn precondition(&mut self, displacement: ArrayView2<f64>, pressure: ArrayViewMut2<f64>) {
        self.inner.precondition(displacement, pressure);
    }
    fn self_compliance(&self) -> f64 {
        self.inner.self_compliance()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::FreeOperator;
    use crate::layer_compliance_factor;
    use tack_geometry::Boundary;

    fn layer(h: f64, nu: f64, interface: Interface) -> Layer {
        Layer {
            thickness: h,
            poisson: nu,
            interface,
        }
    }

    /// The independent reference: the correction of the element coefficient as a 2D Fourier
    /// integral in polar coordinates, `(1/(2π²E*)) ∫₀^{25/h} (1 − S(qh)) ∫₀^{2π} p̂ cos(q_x X)
    /// cos(q_y Y) dθ dq` with the element's transform `p̂ = dx² sinc(q_x dx/2) sinc(q_y dx/2)`;
    /// 16-point Gauss–Legendre panels in q (half the shortest oscillation each), the
    /// trapezoidal rule in θ (exponentially convergent for the periodic integrand) with
    /// `qR + 48` points (R = |X| + |Y| + dx bounds the integrand's bandwidth in θ). Nothing of the production path (table, interpolation, element
    /// quadrature, Love) is shared but S.
    fn reference(x: f64, y: f64, dx: f64, e_star: f64, l: &Layer) -> f64 {
        let h = l.thickness;
        let reach = x.abs() + y.abs() + dx;
        let q_max = X_MAX / h;
        let width = (0.25 / h).min(std::f64::consts::PI / reach);
        let panels = (q_max / width).ceil() as usize;
        let width = q_max / panels as f64;
        let rule = gauss_legendre(16);
        let sinc = |s: f64| if s == 0.0 { 1.0 } else { s.sin() / s };
        let mut total = 0.0;
        for p in 0..panels {
            for &(t, w) in &rule {
                let q = (p as f64 + 0.5 + 0.5 * t) * width;
                let weight = 0.5
                    * width
                    * w
                    * (1.0 - layer_compliance_factor(q * h, l.poisson, l.interface));
                let n = (q * reach) as usize + 48;
                let mut ring = 0.0;
                for k in 0..n {
                    let theta = 2.0 * std::f64::consts::PI * k as f64 / n as f64;
                    let (qx, qy) = (q * theta.cos(), q * theta.sin());
                    ring +=
                        sinc(qx * dx / 2.0) * sinc(qy * dx / 2.0) * (qx * x).cos() * (qy * y).cos();
                }
                total += weight * ring * 2.0 * std::f64::consts::PI / n as f64;
            }
        }
        total * dx * dx / (2.0 * std::f64::consts::PI.powi(2) * e_star)
    }

    #[test]
    fn gauss_legendre_integrates_polynomials() {
        let rule = gauss_legendre(8);
        let sum: f64 = rule.iter().map(|&(x, w)| w * x.powi(14)).sum();
        assert!((sum - 2.0 / 15.0).abs() < 1e-15, "{sum}");
    }

    #[test]
    fn the_kernel_dies_out_at_the_cutoff() {
        // G(ρ)·πE*h = 1/ρ − ĝ(ρ), relative to the half-space's 1/ρ.
        for interface in [Interface::Bonded, Interface::Frictionless] {
            for nu in [0.0, 0.3, 0.5] {
                let l = layer(1.0, nu, interface);
                let c = Correction::new(&l, 100.0);
                let rho = cutoff(interface) - 0.5;
                let g = c.table[(rho / STEP) as usize];
                let rel = ((1.0 / rho - g) * rho).abs();
                assert!(rel < 1e-14, "{interface:?} ν {nu}: {rel}");
            }
        }
    }

    #[test]
    fn coefficients_match_the_fourier_reference() {
        // 16 × 16 grid, dx = 1: the displacement field of a unit pressure on element (0, 0)
        // holds every coefficient K(i, j), i, j < 16; each is compared with Love − reference.
        let (n, dx, e_star) = (16, 1.0, 1.7);
        let grid = Grid::square(n, dx, Boundary::Free).unwrap();
        for l in [
            layer(2.0, 0.3, Interface::Bonded),
            layer(3.0, 0.5, Interface::Bonded),
            layer(1.5, 0.3, Interface::Frictionless),
        ] {
            let mut op = FreeLayerOperator::new(grid, e_star, l).unwrap();
            let mut p = Array2::zeros((n, n));
            p[[0, 0]] = 1.0;
            let mut u = Array2::zeros((n, n));
            op.apply(p.view(), u.view_mut());
            let errors: Vec<f64> = (0..n * n)
                .into_par_iter()
                .map(|k| {
                    let (i, j) = (k / n, k % n);
                    let (x, y) = (i as f64 * dx, j as f64 * dx);
                    let exact = love_rectangle(x, y, dx / 2.0, dx / 2.0) / e_star
                        - reference(x, y, dx, e_star, &l);
                    (u[[i, j]] - exact).abs()
                })
                .collect();
            let worst = errors.iter().fold(0.0f64, |m, &e| m.max(e)) / op.self_compliance();
            eprintln!("{l:?}: worst coefficient error / self-compliance = {worst:e}");
            // Measured ≈ 1e-15; the margin covers the interpolation's 1e-13-level bound.
            assert!(worst < 1e-13, "{l:?}: {worst}");
        }
    }

    #[test]
    fn thin_layers_relative_to_the_element_match_the_reference_near_the_load() {
        // h = dx/2: two sub-squares per side. Offsets near the load only (the reference's cost
        // grows with offset/h).
        let (dx, e_star) = (1.0, 1.0);
        let l = layer(0.5, 0.3, Interface::Bonded);
        let quadrant = layer_influence(4, 4, dx, e_star, &l);
        for (i, j) in [(0, 0), (1, 0), (1, 1), (2, 1), (3, 3)] {
            let (x, y) = (i as f64 * dx, j as f64 * dx);
            let exact =
                love_rectangle(x, y, dx / 2.0, dx / 2.0) / e_star - reference(x, y, dx, e_star, &l);
            let err = (quadrant[[i, j]] - exact).abs() / quadrant[[0, 0]];
            eprintln!("h = dx/2, offset ({i}, {j}): error / self-compliance = {err:e}");
            assert!(err < 1e-12, "({i}, {j}): {err}");
        }
    }

    #[test]
    fn thick_layers_approach_the_half_space() {
        // The difference is about the rigid shift dx²ĝ(0)/(πE*h) of the far base: O(dx/h).
        let (n, dx, e_star) = (16, 0.1, 2.0);
        let grid = Grid::square(n, dx, Boundary::Free).unwrap();
        let mut half = FreeOperator::new(grid, e_star).unwrap();
        let p = Array2::from_shape_fn((n, n), |(i, j)| 1.0 + ((i * 5 + j * 3) % 7) as f64);
        let mut u_half = Array2::zeros((n, n));
        half.apply(p.view(), u_half.view_mut());
        let scale = u_half.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut last = f64::INFINITY;
        for h in [1e2, 1e3, 1e4] {
            let mut op =
                FreeLayerOperator::new(grid, e_star, layer(h, 0.3, Interface::Bonded)).unwrap();
            let mut u = Array2::zeros((n, n));
            op.apply(p.view(), u.view_mut());
            let diff = u_half
                .iter()
                .zip(&u)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
                / scale;
            eprintln!("h = {h}: max |layer − half-space| / max |half-space| = {diff:e}");
            assert!(diff < n as f64 * dx / h, "h = {h}: {diff}");
            assert!(diff < last / 5.0, "h = {h}: {diff} vs {last}");
            last = diff;
        }
    }
}
