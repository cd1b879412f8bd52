//! Maugis–Dugdale adhesive contact of a 1D sinusoidal waviness f = h[1 − cos(2πx/λ)] with an
//! elastic half-space (plane strain, E*): the mean pressure as a function of the contact
//! half-width, between Westergaard (1939) and Johnson's (1995) JKR law, and its pull-off.
//!
//! Attraction is a constant tension σ0 wherever 0 < gap < h0 = γ/σ0 (Dugdale 1960; Maugis 1992).
//! Per period: contact |x| < a, cohesive zone a < |x| < c, free surface c < |x| < λ/2. This is
//! the problem of Hui, Lin, Baney & Kramer (2001) and of Jin, Guo & Wan (2016), whose papers were
//! not available to us: the equations below were derived here and are checked numerically in
//! the tests, not transcribed.
//!
//! # Derivation in short
//!
//! For an even periodic load the map t = sin(πx/λ) turns the periodic half-plane kernel
//! (π/λ) cot(π(x − s)/λ) into the plain half-plane kernel on the t-line, with the load
//! p(x)·(λ/π)/√(1 − t²) per unit t: the profile becomes the parabola 2ht² (a cylinder of radius
//! 1/(4h)), the mean pressure is the t-line force divided by λ, and the cohesive tension becomes
//! (λσ0/π)/√(1 − t²) on sin ψ < |t| < sin φ, with ψ = πa/λ and φ = πc/λ. On the t-line this is
//! the Maugis problem of a cylinder (Baney & Hui 1997) with that non-uniform tension; with the
//! stress bounded at the contact edge (no singularity at x = a) the substitution
//! sin²(πs/λ) = sin²ψ + cos²ψ sin²β reduces every integral over the zone to one over
//! β ∈ (0, θ). The auxiliary angle θ of the zone end, sin φ = √(sin²ψ + cos²ψ sin²θ), is the
//! natural unknown instead of c.
//!
//! # Normalised units
//!
//! Pressures in p* = πE*h/λ (Westergaard's complete-contact pressure), gaps in h, ψ = πa/λ,
//! S = sin ψ, C = cos ψ. The two parameters are Johnson's α = √(2λγ/(π²h²E*)) and the range
//! parameter λ_w ([`wavy_dugdale_lambda`]), Baney & Hui's Maugis parameter of a cylinder,
//! 4σ0 (R/(π²E*²γ))^(1/3), taken at the crest radius R = λ²/(4π²h). In these units
//! s0 = σ0/p* = π α^(2/3) λ_w / 2^(5/3) ([`wavy_dugdale_stress_ratio`]) and h0/h = πα²/(2s0).
//! λ_w → ∞ is Johnson's JKR law, λ_w → 0 at fixed α (σ0 → 0 with γ fixed) is Westergaard.
//!
//! **Partial zone** (θ < π/2, c < λ/2; [`wavy_dugdale_point`]):
//!
//! ```text
//! p̄/p* = S² − (2s0/π) θ
//! g(c)/h = 2 sinφ C sinθ − 2S² asinh(C sinθ / S) + (2s0/π) C M(ψ, θ) = h0/h = πα²/(2s0)
//! M(ψ, θ) = ∫₀^θ ln[sin(θ + β)/sin(θ − β)] sinβ / √(S² + C² sin²β) dβ
//! ```
//!
//! The first line is the force balance, the second the gap h0 at the end of the zone (the first
//! two terms are the Westergaard gap there, the last the opening by the tension). M has a
//! logarithmic end point at β = θ; it is evaluated by tanh-sinh quadrature (129 nodes, accurate
//! to about 1e-15), the only non-closed part. The contact pressure is closed form,
//! p(x)/p* = 2 cos(πx/λ) √(S² − sin²(πx/λ)) − (2s0/π) arctan[tanθ cos(πx/λ)/√(S² − sin²(πx/λ))],
//! which equals −σ0 at the contact edge (bounded stress; [`WavyDugdalePoint::pressure_ratio`]).
//!
//! **Saturated zone** (θ = π/2, c = λ/2): the tension acts on the whole gap, the trough gap is
//! Westergaard's, 2C − 2S² asinh(C/S) ≤ h0/h, and p̄/p* = S² − s0.
//!
//! For fixed ψ the zone-end gap g(c) is not monotonic in θ (it falls again near θ = π/2), so some
//! (α, λ_w, ψ) have up to three states: two partial zones and the saturated one. This module
//! follows the branch that grows continuously from the JKR limit: the smallest θ solving the gap
//! condition, and the saturated state only where no partial zone exists.
//!
//! # Limits
//!
//! As λ_w → ∞, θ ≈ πα√(tanψ)/(2s0) → 0 and M ≈ θ²/S, so (2s0/π)θ → α√(tanψ): Johnson's
//! p̄/p* = sin²ψ − α√(tanψ), with an error falling like λ_w⁻². For α → 0 at fixed ψ/α^(2/3) (small
//! contacts at the crest) it is Baney & Hui's Maugis cylinder at radius R. As α → 0 at fixed σ0
//! (γ → 0), or λ_w → 0 at fixed α, it is Westergaard's p̄/p* = sin²ψ.
//!
//! ```
//! use std::f64::consts::PI;
//! use tack_analytics::{
//!     johnson_1d_mean_pressure_ratio, johnson_alpha, wavy_dugdale_lambda,
//!     wavy_dugdale_mean_pressure_ratio, wavy_dugdale_point, wavy_dugdale_stress_ratio,
//! };
//!
//! // A short-ranged interaction (λ_w = 1000) is Johnson's JKR law to about 1e-7.
//! let (alpha, psi) = (0.3, 0.4);
//! let p = wavy_dugdale_mean_pressure_ratio(alpha, 1.0e3, psi);
//! assert!((p - johnson_1d_mean_pressure_ratio(alpha, psi)).abs() < 1e-6);
//!
//! // A longer range: the zone reaches further and the adhesive term is smaller.
//! let q = wavy_dugdale_point(alpha, 1.0, psi);
//! assert!(q.psi_c > psi && q.psi_c < PI / 2.0 && !q.saturated);
//! assert!(q.mean_pressure_ratio > p);
//!
//! // Physical inputs: α and λ_w from E*, γ, h, the wavelength and σ0.
//! let (e_star, gamma, h, wavelength, sigma0) = (1.0, 1.0e-4, 0.01, 1.0, 0.02);
//! let alpha = johnson_alpha(e_star, gamma, h, wavelength);
//! let lambda_w = wavy_dugdale_lambda(e_star, gamma, h, wavelength, sigma0);
//! assert!((alpha - 0.4502).abs() < 1e-4 && (lambda_w - 1.0953).abs() < 1e-4);
//! // σ0/p* with p* = πE*h/λ follows from the two parameters.
//! let s0 = wavy_dugdale_stress_ratio(alpha, lambda_w);
//! assert!((s0 - sigma0 / (PI * e_star * h / wavelength)).abs() < 1e-12);
//! ```

use crate::minimize::golden_min;
use std::f64::consts::{FRAC_PI_2, PI};

/// Range parameter λ_w = 4σ0 (R/(π²E*²γ))^(1/3) with the crest radius R = λ²/(4π²h): the Maugis
/// parameter of a cylinder (Baney & Hui 1997) at the curvature of the crest of
/// f = h[1 − cos(2πx/λ)], for `e_star`, `gamma`, amplitude `h`, wavelength `lambda_wave` and
/// Dugdale stress `sigma0` (all > 0). Large λ_w is the JKR limit (Johnson 1995).
pub fn wavy_dugdale_lambda(e_star: f64, gamma: f64, h: f64, lambda_wave: f64, sigma0: f64) -> f64 {
    let radius = lambda_wave * lambda_wave / (4.0 * PI * PI * h);
    4.0 * sigma0 * (radius / (PI * PI * e_star * e_star * gamma)).cbrt()
}

/// s0 = σ0/p* = π α^(2/3) λ_w / 2^(5/3), the Dugdale stress in units of p* = πE*h/λ, for
/// Johnson's `alpha` and the range parameter `lambda_w` ([`wavy_dugdale_lambda`]). The range
/// is then h0/h = πα²/(2s0).
pub fn wavy_dugdale_stress_ratio(alpha: f64, lambda_w: f64) -> f64 {
    PI * alpha.powf(2.0 / 3.0) * lambda_w / 2f64.powf(5.0 / 3.0)
}

/// A state of the Maugis–Dugdale waviness in normalised units (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WavyDugdalePoint {
    /// ψ_a = πa/λ, a the contact half-width.
    pub psi_a: f64,
    /// ψ_c = πc/λ, c the outer edge of the cohesive zone; π/2 when saturated.
    pub psi_c: f64,
    /// Auxiliary angle θ of the zone end, sin ψ_c = √(sin²ψ_a + cos²ψ_a sin²θ); π/2 when
    /// saturated.
    pub theta_c: f64,
    /// s0 = σ0/p* of the parameters ([`wavy_dugdale_stress_ratio`]).
    pub stress_ratio: f64,
    /// Mean pressure p̄/p* (positive when compressive), p* = πE*h/λ.
    pub mean_pressure_ratio: f64,
    /// Whether the zone fills the whole gap (c = λ/2).
    pub saturated: bool,
}

impl WavyDugdalePoint {
    /// Pressure p(x)/p* at x/λ = `x_over_lambda` (positive when compressive, periodic): in
    /// contact 2 cos(πx/λ) √(sin²ψ_a − sin²(πx/λ)) − (2s0/π) arctan[tanθ cos(πx/λ)/
    /// √(sin²ψ_a − sin²(πx/λ))], −s0 in the cohesive zone, 0 beyond (module docs).
    pub fn pressure_ratio(&self, x_over_lambda: f64) -> f64 {
        let xi = x_over_lambda - x_over_lambda.round();
        let y = PI * xi.abs();
        if y < self.psi_a {
            let q = ((self.psi_a - y).sin() * (self.psi_a + y).sin()).sqrt();
            let cy = y.cos();
            let (st, ct) = self.theta_c.sin_cos();
            2.0 * cy * q - 2.0 * self.stress_ratio / PI * (st * cy).atan2(ct * q)
        } else if y < self.psi_c || self.saturated {
            -self.stress_ratio
        } else {
            0.0
        }
    }
}

/// The state at ψ_a = πa/λ = `psi_a` ∈ [0, π/2) for Johnson's `alpha` > 0 and the range
/// parameter `lambda_w` > 0 (module docs): θ is the smallest root of the zone-end gap condition
/// (bisection to rounding after a scan of 32 steps in θ), or the saturated state if there is
/// none. ψ_a = 0 is the a → 0 end of the contact branch (contact at a point).
///
/// # Panics
///
/// If `alpha` or `lambda_w` is not a finite number > 0, or `psi_a` is not in [0, π/2).
pub fn wavy_dugdale_point(alpha: f64, lambda_w: f64, psi_a: f64) -> WavyDugdalePoint {
    check(alpha, lambda_w, "wavy_dugdale_point");
    assert!(
        (0.0..FRAC_PI_2).contains(&psi_a),
        "wavy_dugdale_point: psi_a must be in [0, pi/2), got {psi_a}"
    );
    Wave::new(alpha, lambda_w).point(psi_a)
}

/// p̄/p* at ψ_a = πa/λ = `psi_a`, the `mean_pressure_ratio` of [`wavy_dugdale_point`].
///
/// # Panics
///
/// As [`wavy_dugdale_point`].
pub fn wavy_dugdale_mean_pressure_ratio(alpha: f64, lambda_w: f64, psi_a: f64) -> f64 {
    wavy_dugdale_point(alpha, lambda_w, psi_a).mean_pressure_ratio
}

/// Mean pressure p̄ at contact half-width `a` in physical units: p* ·
/// [`wavy_dugdale_mean_pressure_ratio`] with α = √(2λγ/(π²h²E*)), λ_w from
/// [`wavy_dugdale_lambda`] and p* = πE*h/λ, for the wavelength `lambda_wave`.
///
/// # Panics
///
/// If γ, σ0 or the lengths give a non-positive or non-finite α or λ_w, or if a is not in
/// [0, λ/2).
pub fn wavy_dugdale_mean_pressure(
    e_star: f64,
    gamma: f64,
    h: f64,
    lambda_wave: f64,
    sigma0: f64,
    a: f64,
) -> f64 {
    let alpha = (2.0 * lambda_wave * gamma / (PI * PI * h * h * e_star)).sqrt();
    let lambda_w = wavy_dugdale_lambda(e_star, gamma, h, lambda_wave, sigma0);
    let p_star = PI * e_star * h / lambda_wave;
    p_star * wavy_dugdale_mean_pressure_ratio(alpha, lambda_w, PI * a / lambda_wave)
}

/// Greatest tension under load control from partial contact, as p̄/p* (negative): the least
/// p̄ on the branch of [`wavy_dugdale_point`] from ψ_a = 0 up to its first rise, i.e. at the
/// first local minimum of p̄(ψ_a), or at ψ_a = 0 if p̄ rises from there. `None` if p̄ falls
/// over the whole scan (no stable partial contact). As λ_w → ∞ it is the minimum of Johnson's
/// sin²ψ − α√tanψ.
///
/// The scan samples ψ_a = (π/2)(j/64)², j = 0…63, and refines the minimum by golden-section
/// search to 1e-10 in ψ_a (some thousands of gap solves: tens of ms).
///
/// # Panics
///
/// If `alpha` or `lambda_w` is not a finite number > 0.
pub fn wavy_dugdale_pull_off_ratio(alpha: f64, lambda_w: f64) -> Option<f64> {
    check(alpha, lambda_w, "wavy_dugdale_pull_off_ratio");
    let wave = Wave::new(alpha, lambda_w);
    let p = |psi: f64| wave.point(psi).mean_pressure_ratio;
    const N: usize = 64;
    let psi: Vec<f64> = (0..N)
        .map(|j| FRAC_PI_2 * (j as f64 / N as f64).powi(2))
        .collect();
    let values: Vec<f64> = psi.iter().map(|&x| p(x)).collect();
    let j = (0..N - 1).find(|&j| values[j + 1] > values[j])?;
    let lo = psi[j.saturating_sub(1)];
    let hi = psi[j + 1];
    let (_, fx) = golden_min(p, lo, hi, 1e-10);
    Some(fx.min(values[j]))
}

// ---------------------------------------------------------------------------------------------
// Internals.

fn check(alpha: f64, lambda_w: f64, name: &str) {
    assert!(
        alpha.is_finite() && alpha > 0.0,
        "{name}: alpha must be a finite number > 0, got {alpha}"
    );
    assert!(
        lambda_w.is_finite() && lambda_w > 0.0,
        "{name}: lambda_w must be a finite number > 0, got {lambda_w}"
    );
}

/// Tanh-sinh (double-exponential) rule on [0, 1]: nodes v_k, their complements 1 − v_k (exact,
/// not by subtraction) and weights, for t = kh, |t| ≤ 4. End-point singularities of log and
/// square-root type cost nothing; the error falls like exp(−c/h).
pub(crate) struct TanhSinh {
    nodes: Vec<(f64, f64, f64)>,
}

impl TanhSinh {
    /// The rule with step `h` in t (1/16 gives 129 nodes).
    pub(crate) fn new(h: f64) -> Self {
        let k_max = (4.0 / h).round() as i64;
        let nodes = (-k_max..=k_max)
            .map(|k| {
                let t = k as f64 * h;
                let u = FRAC_PI_2 * t.sinh();
                // v = 1/(1 + e^(−2u)), 1 − v = 1/(1 + e^(2u)), dv/dt = π cosh t · v(1 − v).
                let v = 1.0 / (1.0 + (-2.0 * u).exp());
                let w = 1.0 / (1.0 + (2.0 * u).exp());
                (v, w, h * PI * t.cosh() * v * w)
            })
            .collect();
        TanhSinh { nodes }
    }

    /// ∫_a^b f, with the nodes near b placed as b − (b − a)(1 − v) so that both ends are
    /// resolved to rounding.
    #[cfg(test)]
    pub(crate) fn integrate(&self, f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
        let len = b - a;
        let sum: f64 = self
            .nodes
            .iter()
            .map(|&(v, w, wt)| {
                let x = if v < 0.5 { a + len * v } else { b - len * w };
                wt * f(x)
            })
            .sum();
        sum * len
    }
}

/// Σ_{n≥1} c_n r^(2n+1) = r√(1 + r²) − asinh r for r < 0.5, c_n = C(1/2, n) − C(−1/2, n)/(2n+1),
/// summed to rounding (r² ≤ 1/4: under 30 terms); the direct form cancels like r².
fn root_minus_asinh_series(r: f64) -> f64 {
    let r2 = r * r;
    let (mut b_half, mut b_mhalf) = (1.0, 1.0);
    let mut power = r;
    let mut sum = 0.0;
    let mut n = 1.0;
    loop {
        b_half *= (1.5 - n) / n;
        b_mhalf *= (0.5 - n) / n;
        power *= r2;
        let next = sum + (b_half - b_mhalf / (2.0 * n + 1.0)) * power;
        if next == sum {
            return sum;
        }
        sum = next;
        n += 1.0;
    }
}

/// Westergaard gap at the zone end, 2 w √(S² + w²) − 2S² asinh(w/S) with w = C sin θ
/// (= 2S²[r√(1 + r²) − asinh r], r = w/S), in units of h.
fn westergaard_zone_gap(s: f64, w: f64) -> f64 {
    if s == 0.0 {
        return 2.0 * w * w;
    }
    let r = w / s;
    if r < 0.5 {
        2.0 * s * s * root_minus_asinh_series(r)
    } else {
        2.0 * w * s.hypot(w) - 2.0 * s * s * r.asinh()
    }
}

/// The parameters of one (α, λ_w) and the quadrature rule.
struct Wave {
    /// s0 = σ0/p*.
    s0: f64,
    /// h0/h = πα²/(2s0).
    range: f64,
    rule: TanhSinh,
}

impl Wave {
    fn new(alpha: f64, lambda_w: f64) -> Self {
        let s0 = wavy_dugdale_stress_ratio(alpha, lambda_w);
        Wave {
            s0,
            range: PI * alpha * alpha / (2.0 * s0),
            rule: TanhSinh::new(1.0 / 16.0),
        }
    }

    /// M(ψ, θ) = θ ∫₀¹ ln[sin(θ(1+v))/sin(θ(1−v))] sin(θv)/√(S² + C² sin²(θv)) dv, the log
    /// written as ln(1 + 2 cosθ sin(θv)/sin(θ(1−v))) (sin(θ(1+v)) − sin(θ(1−v)) = 2 cosθ sin θv).
    fn m(&self, s: f64, c: f64, theta: f64) -> f64 {
        let ct = theta.cos();
        let sum: f64 = self
            .rule
            .nodes
            .iter()
            .map(|&(v, w, wt)| {
                let sv = (theta * v).sin();
                let log = (2.0 * ct * sv / (theta * w).sin()).ln_1p();
                wt * log * sv / s.hypot(c * sv)
            })
            .sum();
        theta * sum
    }

    /// Gap at the zone end in units of h for zone angle θ (module docs).
    fn zone_end_gap(&self, s: f64, c: f64, theta: f64) -> f64 {
        westergaard_zone_gap(s, c * theta.sin()) + 2.0 * self.s0 / PI * c * self.m(s, c, theta)
    }

    /// Smallest θ in (0, π/2] with zone-end gap = h0, or `None`.
    fn theta(&self, s: f64, c: f64) -> Option<f64> {
        let e = |t: f64| self.zone_end_gap(s, c, t) - self.range;
        const N: usize = 32;
        let mut prev = 0.0;
        for k in 1..=N {
            let t = FRAC_PI_2 * k as f64 / N as f64;
            if e(t) >= 0.0 {
                let (mut lo, mut hi) = (prev, t);
                if lo == 0.0 {
                    // The gap vanishes as θ → 0 (below h0): halve down to a negative point.
                    lo = 0.5 * hi;
                    while e(lo) >= 0.0 {
                        hi = lo;
                        lo *= 0.5;
                    }
                }
                loop {
                    let mid = 0.5 * (lo + hi);
                    if mid <= lo || mid >= hi {
                        return Some(0.5 * (lo + hi));
                    }
                    if e(mid) < 0.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
            }
            prev = t;
        }
        None
    }

    fn point(&self, psi_a: f64) -> WavyDugdalePoint {
        let (s, c) = psi_a.sin_cos();
        match self.theta(s, c) {
            Some(theta) => WavyDugdalePoint {
                psi_a,
                psi_c: s.hypot(c * theta.sin()).min(1.0).asin(),
                theta_c: theta,
                stress_ratio: self.s0,
                mean_pressure_ratio: s * s - 2.0 * self.s0 / PI * theta,
                saturated: false,
            },
            None => WavyDugdalePoint {
                psi_a,
                psi_c: FRAC_PI_2,
                theta_c: FRAC_PI_2,
                stress_ratio: self.s0,
                mean_pressure_ratio: s * s - self.s0,
                saturated: true,
            },
        }
    }
}

#[cfg(test)]
mod tests;
