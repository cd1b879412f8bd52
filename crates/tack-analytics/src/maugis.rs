//! Maugis (1992) Dugdale model of an adhesive elastic sphere, the JKR–DMT transition: the
//! equilibrium curve in contact and separated from the half-space, its stable parts under
//! approach control, the pull-off, jump-out and jump-in points.
//!
//! Attraction is a constant tension σ0 wherever the gap is below the range h0 = γ/σ0, so that
//! σ0 h0 = γ (Dugdale 1960; Maugis 1992). With K = 4E*/3 the transition is governed by Maugis'
//! parameter λ = 2σ0 (R/(πγK²))^(1/3) ([`maugis_lambda`]); λ → ∞ is JKR, λ → 0 is DMT.
//!
//! # Normalised units (Maugis 1992)
//!
//! A = a / L, C = c / L, P̄ = F / (πγR), Δ̄ = d / D with L = (πγR²/K)^(1/3) and
//! D = (π²γ²R/K²)^(1/3) = L²/R ([`maugis_scales`]); a is the contact radius, c the outer radius
//! of the cohesive zone, m = c/a, F the force (positive when compressive) and d the approach
//! (positive when pressing). Two lengths of the model in these units, from σ0 R/(K L) = λ/2:
//! h0 / D = 2/(πλ) and 4σ0R/(πE*) / L = 8λ/(3π).
//!
//! **Contact branch** (a > 0), parametrised by m > 1 ([`maugis_point`]):
//!
//! ```text
//! (λA²/2)[√(m²−1) + (m²−2) arctan√(m²−1)] + (4λ²A/3)[√(m²−1) arctan√(m²−1) − m + 1] = 1
//! P̄ = A³ − λA²[√(m²−1) + m² arctan√(m²−1)]
//! Δ̄ = A² − (4/3)λA√(m²−1)
//! ```
//!
//! The first line is a quadratic αA² + βA = 1 in A; its positive root is taken as
//! A = 2/(β + √(β² + 4α)), a sum of positive terms. With s = √(m²−1) (computed as
//! √((m−1)(m+1))), the brackets s − arctan s and arctan s − s/(1+m) are summed as series for
//! small s, so A is accurate to rounding for every m, also near m = 1 where both cancel.
//! As m → 1 (λ → ∞) the curve tends to JKR, P̄ = A³ − √(6A³), Δ̄ = A² − (2/3)√(6A); as λ → 0 to
//! DMT, P̄ = A³ − 2, Δ̄ = A². As m → ∞ the contact radius A → 0 while C = mA tends to C0, the
//! positive root of (πλ/4)C0² + (4λ²/3)(π/2 − 1)C0 = 1: there the branch meets the separated one.
//!
//! **Separated branch** (a = 0; [`maugis_separated_point`]): a uniform tension σ0 on the disc
//! r < c gives F = −πσ0c², and the elastic deflection of the disc, (4σ0c/(πE*)) E(r/c) with E the
//! complete elliptic integral (2σ0c/E* at the centre, 4σ0c/(πE*) at the rim), with the gap h0 at
//! r = c, gives d = c²/(2R) − 4σ0c/(πE*) − h0. In the normalised units:
//!
//! ```text
//! P̄ = −(πλ/2)C²,   Δ̄ = C²/2 − (8λ/(3π))C − 2/(πλ),   centre gap / D = −Δ̄ − (4/3)λC ≥ 0.
//! ```
//!
//! The centre gap vanishes at C = C0, where the state is the m → ∞ end of the contact branch
//! (force and approach agree: the two branches join continuously). Under approach control the
//! separated branch is stable where dΔ̄/dC > 0, i.e. C > 8λ/(3π) (c > 4σ0R/(πE*)).
//!
//! # Stability under approach control
//!
//! The contact branch is stable where dΔ̄/dA > 0. From large A it is stable down to a jump-out
//! point ([`maugis_jump_out_hat`]) if λ > λc = (9π/(16(π − 1)))^(1/3) ≈ 0.93795
//! ([`maugis_lambda_critical`]), and all the way to A → 0 otherwise; λc is where C0 = 8λ/(3π),
//! so exactly for λ < λc the stable contact branch continues onto the stable separated branch,
//! which ends at C = 8λ/(3π) ([`maugis_separated_jump_out_hat`]). After either end the sphere is
//! free (F = 0, gap above h0 everywhere). Approaching, the free sphere is caught at d = −h0
//! ([`maugis_jump_in_hat`]).
//!
//! The greatest tensile force under approach control ([`maugis_pull_off_hat`]) is the minimum
//! of P̄ on the stable parts. It lies at dP̄/dA = 0 on the contact branch for every λ checked
//! (1e-4…1e5), so it equals Maugis' adherence force at fixed load, from −1.5 (JKR) to −2 (DMT).
//! (Near A → 0, C = C0 + C2A² with C2 > 0, so P̄ = P̄0 − πλC0C2A² + O(A³) lies below the junction
//! force P̄0 = −(πλ/2)C0²: the minimum is never at the junction, nor on the separated branch.)
//!
//! ```
//! use tack_analytics::{
//!     jkr_pull_off_force, maugis_force_at_hat, maugis_jump_out_hat, maugis_lambda,
//!     maugis_point, maugis_pull_off, maugis_pull_off_hat, MaugisBranch,
//! };
//!
//! // A stiff, weakly adhering sphere (λ ≈ 0.1) pulls off near the DMT −2πγR; a soft one near
//! // the JKR −1.5πγR.
//! assert!((maugis_pull_off_hat(0.1) + 1.95).abs() < 0.01);
//! assert!((maugis_pull_off_hat(1.0e3) + 1.5).abs() < 1e-6);
//! let (e_star, gamma, radius) = (1.0, 1.0e-4, 1.0);
//! let sigma0 = 10.0; // large: λ ≈ 240
//! assert!(maugis_lambda(e_star, gamma, radius, sigma0) > 100.0);
//! let f = maugis_pull_off(e_star, gamma, radius, sigma0);
//! assert!((f / jkr_pull_off_force(gamma, radius) - 1.0).abs() < 1e-5);
//!
//! // The force at a given approach inverts the parametric curve on its stable part.
//! let p = maugis_point(1.0, 1.2);
//! let f = maugis_force_at_hat(1.0, p.approach_hat, MaugisBranch::Contact).unwrap();
//! assert!((f - p.force_hat).abs() < 1e-9);
//! // Below the jump-out approach the contact branch has no stable state.
//! let (d_jump, _) = maugis_jump_out_hat(1.0).unwrap();
//! assert_eq!(maugis_force_at_hat(1.0, d_jump - 0.01, MaugisBranch::Contact), None);
//! ```

use std::f64::consts::{FRAC_PI_2, PI};

/// Maugis' parameter λ = 2σ0 (R/(πγK²))^(1/3) with K = 4E*/3 (Maugis 1992), for the effective
/// modulus `e_star`, work of adhesion `gamma`, sphere radius `radius` and Dugdale stress `sigma0`
/// (all > 0).
pub fn maugis_lambda(e_star: f64, gamma: f64, radius: f64, sigma0: f64) -> f64 {
    let k = 4.0 / 3.0 * e_star;
    2.0 * sigma0 * (radius / (PI * gamma * k * k)).cbrt()
}

/// λc = (9π/(16(π − 1)))^(1/3) ≈ 0.937947: for λ > λc the stable contact branch ends at a
/// jump-out point with a > 0, for λ ≤ λc it reaches a → 0 and continues onto the stable
/// separated branch (Maugis 1992 model; derived in the module docs: λc is where the junction
/// C0 of the two branches equals 8λ/(3π), the edge of the separated branch's stable part).
pub fn maugis_lambda_critical() -> f64 {
    (9.0 * PI / (16.0 * (PI - 1.0))).cbrt()
}

/// Scales of the normalised Maugis units (Maugis 1992): `radius` L = (πγR²/K)^(1/3) for the
/// contact radius a and the cohesive-zone radius c, `force` πγR, `approach` D = (π²γ²R/K²)^(1/3),
/// with K = 4E*/3. A = a/L, P̄ = F/(πγR), Δ̄ = d/D.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaugisScales {
    /// Length scale of a and c, L = (πγR²/K)^(1/3).
    pub radius: f64,
    /// Force scale πγR (the force itself is positive when compressive).
    pub force: f64,
    /// Approach scale D = (π²γ²R/K²)^(1/3) (the approach is positive when pressing).
    pub approach: f64,
}

/// The scales of the normalised Maugis units for `e_star`, `gamma` and sphere `radius`
/// (Maugis 1992); see [`MaugisScales`].
pub fn maugis_scales(e_star: f64, gamma: f64, radius: f64) -> MaugisScales {
    let k = 4.0 / 3.0 * e_star;
    MaugisScales {
        radius: (PI * gamma * radius * radius / k).cbrt(),
        force: PI * gamma * radius,
        approach: (PI * PI * gamma * gamma * radius / (k * k)).cbrt(),
    }
}

/// A point of the Maugis equilibrium curve in normalised units (Maugis 1992; module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaugisPoint {
    /// m = c/a ≥ 1; +∞ on the separated branch (a = 0).
    pub m: f64,
    /// Contact radius A = a/L (0 on the separated branch).
    pub a_hat: f64,
    /// Outer radius of the cohesive zone C = c/L = mA.
    pub c_hat: f64,
    /// Force P̄ = F/(πγR), positive when compressive.
    pub force_hat: f64,
    /// Approach Δ̄ = d/D, positive when pressing.
    pub approach_hat: f64,
}

/// Branch of the Maugis equilibrium curve: in contact (a > 0) or separated (a = 0, only the
/// cohesive zone r < c carries the tension σ0).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MaugisBranch {
    /// Contact radius a > 0 (Maugis 1992).
    Contact,
    /// No contact, a uniform tension σ0 on the disc r < c with the gap h0 at r = c.
    Separated,
}

/// The point of the contact branch with m = c/a for Maugis' parameter `lambda` (Maugis 1992;
/// equations in the module docs). m = +∞ gives the a → 0 end, where the contact branch meets the
/// separated one (C = C0); m → 1 gives a → ∞.
///
/// # Panics
///
/// If `lambda` is not a finite number > 0 or `m` is not a number > 1.
pub fn maugis_point(lambda: f64, m: f64) -> MaugisPoint {
    check_lambda(lambda, "maugis_point");
    assert!(m > 1.0, "maugis_point: m must be > 1, got {m}");
    let s = ((m - 1.0) * (m + 1.0)).sqrt();
    let mut p = contact_point(lambda, s);
    if m.is_finite() && p.m.is_finite() {
        p.m = m;
    }
    p
}

/// The point of the separated branch (a = 0) with cohesive-zone radius C = c/L = `c_hat` ≥ 0:
/// P̄ = −(πλ/2)C², Δ̄ = C²/2 − (8λ/(3π))C − 2/(πλ) (module docs). It is a physical state only
/// while the centre gap −Δ̄ − (4/3)λC is ≥ 0, i.e. C ≤ C0, and stable under approach control
/// only for C > 8λ/(3π); neither is checked here.
///
/// # Panics
///
/// If `lambda` is not a finite number > 0.
pub fn maugis_separated_point(lambda: f64, c_hat: f64) -> MaugisPoint {
    check_lambda(lambda, "maugis_separated_point");
    MaugisPoint {
        m: f64::INFINITY,
        a_hat: 0.0,
        c_hat,
        force_hat: -FRAC_PI_2 * lambda * c_hat * c_hat,
        approach_hat: 0.5 * c_hat * c_hat
            - separated_stable_edge(lambda) * c_hat
            - range_hat(lambda),
    }
}

/// Greatest tensile force under approach control, in units of πγR (a negative number; Maugis
/// 1992): the minimum of P̄ over the stable part (dΔ̄/dA > 0) of the contact branch that extends
/// to large A and, for λ ≤ λc where that part reaches A → 0, over the stable separated branch
/// (whose greatest tension, at the junction, is never below the contact branch's minimum).
/// The minimum lies at dP̄/dA = 0 on the contact branch (checked for λ = 1e-4…1e5), so this is
/// also Maugis' adherence force at fixed load. It tends to −1.5 (JKR) as λ → ∞, about −1.5 − 0.164/λ², and to −2 (DMT) as
/// λ → 0, about −2 + 1.72 λ^(3/2).
///
/// The branch is searched on a geometric grid of s = √(m²−1), 50 points per decade from A = 50
/// down to A = 1e-9·min(1, λ), for sign changes of closed-form derivatives of Δ̄ and P̄, each
/// refined by bisection to rounding (some hundreds of evaluations: tens of µs).
///
/// # Panics
///
/// If `lambda` is not a finite number > 0.
pub fn maugis_pull_off_hat(lambda: f64) -> f64 {
    check_lambda(lambda, "maugis_pull_off_hat");
    ContactBranch::new(lambda).pull_off
}

/// Greatest tensile force under approach control, F = πγR·[`maugis_pull_off_hat`] (negative;
/// Maugis 1992), for `e_star`, `gamma`, `radius` and the Dugdale stress `sigma0`.
///
/// # Panics
///
/// If the resulting λ is not a finite number > 0.
pub fn maugis_pull_off(e_star: f64, gamma: f64, radius: f64, sigma0: f64) -> f64 {
    let lambda = maugis_lambda(e_star, gamma, radius, sigma0);
    maugis_pull_off_hat(lambda) * maugis_scales(e_star, gamma, radius).force
}

/// End of the stable contact branch under approach control, the minimum of Δ̄ on it, as
/// (Δ̄, P̄) in normalised units (Maugis 1992); `None` for λ ≤ λc, where the branch stays stable
/// down to A → 0 (module docs). For λ > λc the separated branch has no stable state, and the
/// approach here lies below −h0, so the sphere jumps to the free state F = 0. As λ → ∞ this is
/// the JKR jump-off (Δ̄, P̄) = (−(3/4)^(1/3), −5/6) = (−0.90856, −0.83333).
///
/// # Panics
///
/// If `lambda` is not a finite number > 0.
pub fn maugis_jump_out_hat(lambda: f64) -> Option<(f64, f64)> {
    check_lambda(lambda, "maugis_jump_out_hat");
    ContactBranch::new(lambda).jump.map(|s| {
        let p = contact_point(lambda, s);
        (p.approach_hat, p.force_hat)
    })
}

/// End of the stable separated branch under approach control, at C = 8λ/(3π)
/// (c = 4σ0R/(πE*)), as (Δ̄, P̄) = (−(8λ/(3π))²/2 − 2/(πλ), −32λ³/(9π)); `None` for λ ≥ λc,
/// where the separated branch has no stable state with a non-negative centre gap. After it the
/// sphere is free (F = 0).
///
/// # Panics
///
/// If `lambda` is not a finite number > 0.
pub fn maugis_separated_jump_out_hat(lambda: f64) -> Option<(f64, f64)> {
    check_lambda(lambda, "maugis_separated_jump_out_hat");
    let b = separated_stable_edge(lambda);
    (junction_c_hat(lambda) > b).then(|| {
        let p = maugis_separated_point(lambda, b);
        (p.approach_hat, p.force_hat)
    })
}

/// Jump-in of an approaching free sphere (Maugis 1992 model): the cohesive zone forms when the
/// least gap reaches h0, at Δ̄ = −2/(πλ) (d = −h0), with F = 0 before. Returns that approach,
/// the branch the sphere jumps to and the force P̄ after the jump. It lands on the separated
/// branch at C = 16λ/(3π) (c = 8σ0R/(πE*), the stable root of Δ̄ = −2/(πλ)) when that state
/// has a non-negative centre gap, i.e. for λ ≤ (9/32)^(1/3) ≈ 0.6552, with P̄ = −128λ³/(9π);
/// for larger λ directly on the stable contact branch at the same approach.
///
/// # Panics
///
/// If `lambda` is not a finite number > 0.
pub fn maugis_jump_in_hat(lambda: f64) -> (f64, MaugisBranch, f64) {
    check_lambda(lambda, "maugis_jump_in_hat");
    let d = -range_hat(lambda);
    let c = 2.0 * separated_stable_edge(lambda);
    if c <= junction_c_hat(lambda) {
        (
            d,
            MaugisBranch::Separated,
            maugis_separated_point(lambda, c).force_hat,
        )
    } else {
        let f = maugis_force_at_hat(lambda, d, MaugisBranch::Contact)
            .expect("the stable contact branch reaches below d = -h0 (tested for 0.66..6.6e4)");
        (d, MaugisBranch::Contact, f)
    }
}

/// Normalised force P̄ at normalised approach Δ̄ = `approach_hat` on the stable part under
/// approach control of `branch` (Maugis 1992; module docs), or `None` where that part has no
/// state at this approach (and for a non-finite approach).
///
/// - [`MaugisBranch::Contact`]: the stable part connected to large A, on which Δ̄ decreases
///   monotonically along the branch from +∞ to the jump-out approach (λ > λc) or to the junction
///   approach Δ̄0 = −(4/3)λC0 (λ ≤ λc, excluded: that state belongs to the separated branch).
///   Inverted by bisection on s = √(m²−1) to rounding, after the scan of
///   [`maugis_pull_off_hat`] that finds the jump-out (tens of µs per call).
/// - [`MaugisBranch::Separated`]: C > 8λ/(3π) and centre gap ≥ 0 (C ≤ C0), i.e. Δ̄ in
///   (−(8λ/(3π))²/2 − 2/(πλ), Δ̄0]; none for λ ≥ λc. Closed form.
///
/// The free state (F = 0, possible for Δ̄ ≤ −2/(πλ), i.e. d ≤ −h0) is not part of either
/// branch.
///
/// # Panics
///
/// If `lambda` is not a finite number > 0.
pub fn maugis_force_at_hat(lambda: f64, approach_hat: f64, branch: MaugisBranch) -> Option<f64> {
    check_lambda(lambda, "maugis_force_at_hat");
    if !approach_hat.is_finite() {
        return None;
    }
    match branch {
        MaugisBranch::Contact => contact_force_at(lambda, approach_hat),
        MaugisBranch::Separated => separated_force_at(lambda, approach_hat),
    }
}

/// Energy W̄ = ∮P̄ dΔ̄ (units of πγR·D) that an approach-controlled load–retract cycle
/// dissipates (Maugis 1992), for λ above [`maugis_lambda_critical`], where the sphere is caught
/// on the contact branch at Δ̄ = −h0/D and leaves it at its jump-out: approach and retraction
/// share that branch above the jump-in, so the loop is W̄ = −∫ P̄ dΔ̄ over the contact branch
/// from the jump-out to the jump-in. `None` below λc (the separated branch takes part).
/// Simpson's rule in s = √(Δ̄ − Δ̄_out), which removes the square-root turn of P̄(Δ̄) at the
/// jump-out, with 4000 intervals (tested against a trapezoid rule on the parametric curve, and
/// at large λ against JKR's own loop).
///
/// ```
/// use tack_analytics::maugis_dissipated_energy_hat;
/// // The loop shrinks as the range grows (λ falls towards λc) and tends to JKR's as λ → ∞.
/// let (w1, w10) = (maugis_dissipated_energy_hat(1.0).unwrap(), maugis_dissipated_energy_hat(10.0).unwrap());
/// assert!(w1 > 0.0 && w10 > w1);
/// assert_eq!(maugis_dissipated_energy_hat(0.5), None);
/// ```
pub fn maugis_dissipated_energy_hat(lambda: f64) -> Option<f64> {
    check_lambda(lambda, "maugis_dissipated_energy_hat");
    if lambda <= maugis_lambda_critical() {
        return None;
    }
    let (d_out, _) = maugis_jump_out_hat(lambda)?;
    let (d_in, branch, _) = maugis_jump_in_hat(lambda);
    if branch != MaugisBranch::Contact || d_in <= d_out {
        return None;
    }
    const N: usize = 4000;
    let s_max = (d_in - d_out).sqrt();
    let h = s_max / N as f64;
    // At s = 0 the integrand 2s·P̄ vanishes; elsewhere the stable branch has a state.
    let f = |k: usize| {
        let s = h * k as f64;
        if k == 0 {
            return 0.0;
        }
        let d = (d_out + s * s).min(d_in);
        2.0 * s * contact_force_at(lambda, d).unwrap_or_else(|| contact_point_at_jump(lambda).1)
    };
    let mut sum = f(0) + f(N);
    for k in 1..N {
        sum += if k % 2 == 1 { 4.0 } else { 2.0 } * f(k);
    }
    Some(-sum * h / 3.0)
}

/// The jump-out point (Δ̄, P̄) of the contact branch, for λ > λc.
fn contact_point_at_jump(lambda: f64) -> (f64, f64) {
    maugis_jump_out_hat(lambda).expect("a jump-out above λc")
}

/// Dissipated energy of a load–retract cycle in physical units:
/// [`maugis_dissipated_energy_hat`] times πγR·D ([`maugis_scales`]).
pub fn maugis_dissipated_energy(e_star: f64, gamma: f64, radius: f64, sigma0: f64) -> Option<f64> {
    let lambda = maugis_lambda(e_star, gamma, radius, sigma0);
    let scales = maugis_scales(e_star, gamma, radius);
    maugis_dissipated_energy_hat(lambda).map(|w| w * scales.force * scales.approach)
}

/// Force F at approach `d` on the stable part of `branch` (Maugis 1992), in physical units:
/// [`maugis_force_at_hat`] with Δ̄ = d/D and F = πγR·P̄ ([`maugis_scales`]); `None` where that
/// branch has no stable state at `d`.
///
/// # Panics
///
/// If the resulting λ is not a finite number > 0.
pub fn maugis_force_at(
    e_star: f64,
    gamma: f64,
    radius: f64,
    sigma0: f64,
    d: f64,
    branch: MaugisBranch,
) -> Option<f64> {
    let lambda = maugis_lambda(e_star, gamma, radius, sigma0);
    let scales = maugis_scales(e_star, gamma, radius);
    maugis_force_at_hat(lambda, d / scales.approach, branch).map(|f| f * scales.force)
}

// ---------------------------------------------------------------------------------------------
// Internals. The contact branch is parametrised by s = √(m²−1) ∈ (0, ∞): A decreases
// monotonically from ∞ to 0 as s grows, since both coefficients of the quadratic increase.

/// Beyond this s the contact point is replaced by its a → 0 limit (A ≈ C0/s < 1e-99).
const S_MAX: f64 = 1.0e100;

/// Grid points per decade of s for the sign-change scans.
const PER_DECADE: f64 = 50.0;

fn check_lambda(lambda: f64, name: &str) {
    assert!(
        lambda.is_finite() && lambda > 0.0,
        "{name}: lambda must be a finite number > 0, got {lambda}"
    );
}

/// h0/D = 2/(πλ).
fn range_hat(lambda: f64) -> f64 {
    2.0 / (PI * lambda)
}

/// 8λ/(3π) = (4σ0R/(πE*))/L, the edge of the separated branch's stable part.
fn separated_stable_edge(lambda: f64) -> f64 {
    8.0 * lambda / (3.0 * PI)
}

/// C0, the positive root of (πλ/4)C² + (4λ²/3)(π/2 − 1)C = 1.
fn junction_c_hat(lambda: f64) -> f64 {
    let a = PI * lambda / 4.0;
    let b = 4.0 * lambda * lambda / 3.0 * (FRAC_PI_2 - 1.0);
    2.0 / (b + (b * b + 4.0 * a).sqrt())
}

/// The a → 0 end of the contact branch (= the separated point at C0).
fn junction_point(lambda: f64) -> MaugisPoint {
    let c0 = junction_c_hat(lambda);
    let b = 4.0 * lambda * lambda / 3.0 * (FRAC_PI_2 - 1.0);
    MaugisPoint {
        m: f64::INFINITY,
        a_hat: 0.0,
        c_hat: c0,
        // −(πλ/2)C0² = −2(1 − (4λ²/3)(π/2 − 1)C0) by the quadratic; → −2 as λ → 0.
        force_hat: -2.0 * (1.0 - b * c0),
        approach_hat: -4.0 / 3.0 * lambda * c0,
    }
}

/// Σ_{k≥1} (−1)^(k+1) w_k s^(2k+1) for |s| < 0.5, to rounding (s² ≤ 1/4, under 30 terms).
fn odd_series(s: f64, weight: impl Fn(f64) -> f64) -> f64 {
    let s2 = s * s;
    let mut power = s * s2;
    let mut sum = 0.0;
    let mut k = 1.0;
    loop {
        let term = weight(k) * power;
        let next = sum + term;
        if next == sum {
            return sum;
        }
        sum = next;
        power *= -s2;
        k += 1.0;
    }
}

/// s − arctan s, without cancellation for small s.
fn s_minus_atan(s: f64) -> f64 {
    if s < 0.5 {
        odd_series(s, |k| 1.0 / (2.0 * k + 1.0))
    } else {
        s - s.atan()
    }
}

/// arctan s − s/(1 + s²), without cancellation for small s.
fn atan_minus_ratio(s: f64) -> f64 {
    if s < 0.5 {
        odd_series(s, |k| 2.0 * k / (2.0 * k + 1.0))
    } else {
        s.atan() - s / (1.0 + s * s)
    }
}

/// Everything the contact branch needs at s = √(m²−1).
struct Contact {
    s: f64,
    m: f64,
    /// m − 1 = s²/(1 + m).
    m1: f64,
    t: f64,
    a: f64,
}

impl Contact {
    fn new(lambda: f64, s: f64) -> Self {
        let t = s.atan();
        let m = s.hypot(1.0);
        let m1 = s * s / (1.0 + m);
        // f1 = s + (s² − 1) arctan s = s² arctan s + (s − arctan s);
        // f2 = s arctan s − m + 1 = s (arctan s − s/(1 + m)).
        let f1 = s * s * t + s_minus_atan(s);
        let f2 = s * (t - s / (1.0 + m));
        let alpha = 0.5 * lambda * f1;
        let beta = 4.0 / 3.0 * lambda * lambda * f2;
        let a = 2.0 / (beta + (beta * beta + 4.0 * alpha).sqrt());
        Contact { s, m, m1, t, a }
    }

    fn point(&self, lambda: f64) -> MaugisPoint {
        let (a, s) = (self.a, self.s);
        let u = a * s; // A√(m²−1)
        let c = a * self.m; // C = mA
        MaugisPoint {
            m: self.m,
            a_hat: a,
            c_hat: c,
            force_hat: a * a * a - lambda * (a * u + c * c * self.t),
            approach_hat: a * a - 4.0 / 3.0 * lambda * u,
        }
    }

    /// Q = α'A + β' (primes: d/ds) with α = (λ/2) f1, β = (4λ²/3) f2, so that
    /// dA/ds = −AQ/(2αA + β).
    fn q(&self, lambda: f64) -> f64 {
        let (s, t, m) = (self.s, self.t, self.m);
        let s2p1 = 1.0 + s * s;
        let alpha_p = lambda * (s * t + s * s / s2p1);
        // f2' = arctan s + s/(1 + s²) − s/m.
        let beta_p = 4.0 / 3.0 * lambda * lambda * (t + s / s2p1 - s / m);
        alpha_p * self.a + beta_p
    }

    /// A positive multiple of dΔ̄/ds: dΔ̄/ds = (A/(2αA + β))·G with
    /// G = (4/3)λ[λA(arctan s − s/(1+s²)) + (4λ²/3)(m − 1)/m²] − 2AQ.
    /// The branch is stable (dΔ̄/dA > 0) where G < 0. Every bracket is a sum of positive terms.
    fn approach_slope(&self, lambda: f64) -> f64 {
        let w = atan_minus_ratio(self.s);
        let m2 = self.m * self.m;
        4.0 / 3.0 * lambda * (lambda * self.a * w + 4.0 / 3.0 * lambda * lambda * self.m1 / m2)
            - 2.0 * self.a * self.q(lambda)
    }

    /// A positive multiple of dP̄/ds: dP̄/ds = (A²/(2αA + β))·H with
    /// H = 2λ²A(arctan s − s/(1+s²) + 2s arctan² s) + (8λ³/3)(arctan² s + (m − 1)/m²) − 3AQ.
    fn force_slope(&self, lambda: f64) -> f64 {
        let (s, t, a) = (self.s, self.t, self.a);
        let w = atan_minus_ratio(s);
        let m2 = self.m * self.m;
        2.0 * lambda * lambda * a * (w + 2.0 * s * t * t)
            + 8.0 / 3.0 * lambda.powi(3) * (t * t + self.m1 / m2)
            - 3.0 * a * self.q(lambda)
    }
}

/// Contact point at s; s ≥ S_MAX (or +∞) gives the a → 0 limit.
fn contact_point(lambda: f64, s: f64) -> MaugisPoint {
    if s >= S_MAX {
        junction_point(lambda)
    } else {
        Contact::new(lambda, s).point(lambda)
    }
}

fn approach_at(lambda: f64, s: f64) -> f64 {
    contact_point(lambda, s).approach_hat
}

/// Bisection for a sign change of `f` on [lo, hi] with f(lo) < 0 ≤ f(hi), to adjacent floats;
/// returns the last point with f < 0.
fn bisect_sign(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            return lo;
        }
        if f(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
}

/// The stable contact branch of one λ: where it ends and its least force.
struct ContactBranch {
    /// s at the jump-out (last stable point), `None` if stable down to A → 0.
    jump: Option<f64>,
    /// Least force on the stable parts (contact, and separated for λ ≤ λc).
    pull_off: f64,
}

impl ContactBranch {
    fn new(lambda: f64) -> Self {
        let a_at = |s: f64| Contact::new(lambda, s).a;
        let slope_d = |s: f64| Contact::new(lambda, s).approach_slope(lambda);
        let slope_f = |s: f64| Contact::new(lambda, s).force_slope(lambda);

        // The grid spans A from 50 (Hertz-like, stable, force increasing with A) down to
        // 1e-9·min(1, λ), well below the force minimum (A ≈ 2.09λ as λ → 0).
        let mut s_lo = 1.0;
        while a_at(s_lo) < 50.0 && s_lo > 1e-300 {
            s_lo *= 0.5;
        }
        let a_floor = 1e-9 * lambda.min(1.0);
        let mut s_hi = 1.0;
        while a_at(s_hi) > a_floor && s_hi < S_MAX {
            s_hi *= 2.0;
        }
        let n = ((s_hi / s_lo).log10() * PER_DECADE).ceil().max(1.0) as usize;
        let ratio = (s_hi / s_lo).powf(1.0 / n as f64);
        let grid: Vec<f64> = (0..=n).map(|i| s_lo * ratio.powi(i as i32)).collect();

        // Jump-out: the first s with dΔ̄/ds ≥ 0.
        let mut jump = grid
            .windows(2)
            .find(|w| slope_d(w[1]) >= 0.0)
            .map(|w| bisect_sign(slope_d, w[0], w[1]));
        if jump.is_none() && lambda > maugis_lambda_critical() {
            // Close above λc the jump-out lies at A below the grid: there dΔ̄/ds/A tends to a
            // constant ∝ (λ − λc) > 0, which the closed form resolves without cancellation.
            let mut lo = s_hi;
            let mut hi = 2.0 * s_hi;
            while slope_d(hi) < 0.0 && hi < S_MAX {
                lo = hi;
                hi *= 2.0;
            }
            if hi < S_MAX {
                jump = Some(bisect_sign(slope_d, lo, hi));
            }
        }

        // Least force on the stable part: local minima (dP̄/ds from < 0 to ≥ 0) and the end.
        let s_end = jump.unwrap_or(f64::INFINITY);
        let end = contact_point(lambda, s_end);
        let mut pull_off = end.force_hat;
        for w in grid.windows(2) {
            if w[0] >= s_end {
                break;
            }
            let hi = w[1].min(s_end);
            if slope_f(w[0]) < 0.0 && slope_f(hi) >= 0.0 {
                let s = bisect_sign(slope_f, w[0], hi);
                // Both neighbours of the crossing: the force is flat there to rounding.
                for x in [s, next_up(s).min(hi)] {
                    pull_off = pull_off.min(contact_point(lambda, x).force_hat);
                }
            }
        }
        ContactBranch { jump, pull_off }
    }
}

/// The next float above a positive finite x.
fn next_up(x: f64) -> f64 {
    f64::from_bits(x.to_bits() + 1)
}

fn contact_force_at(lambda: f64, d: f64) -> Option<f64> {
    let branch = ContactBranch::new(lambda);
    // hi: a point of the stable part with Δ̄ ≤ d (Δ̄ decreases with s there).
    let hi = match branch.jump {
        Some(s_jump) => {
            if d < approach_at(lambda, s_jump) {
                return None;
            }
            s_jump
        }
        None => {
            if d <= junction_point(lambda).approach_hat {
                return None;
            }
            let mut hi = 1.0;
            while approach_at(lambda, hi) > d && hi < S_MAX {
                hi *= 2.0;
            }
            hi
        }
    };
    // lo: Δ̄(lo) ≥ d; Δ̄ → +∞ as s → 0 (A → ∞).
    let mut lo = hi.min(1.0);
    while approach_at(lambda, lo) < d && lo > 1e-300 {
        lo *= 0.5;
    }
    let s = bisect_sign(|s| d - approach_at(lambda, s), lo, hi);
    Some(contact_point(lambda, s).force_hat)
}

fn separated_force_at(lambda: f64, d: f64) -> Option<f64> {
    let b = separated_stable_edge(lambda);
    let junction = junction_point(lambda);
    if junction.c_hat <= b || d > junction.approach_hat {
        return None;
    }
    // Stable root of C²/2 − bC − 2/(πλ) = Δ̄.
    let disc = b * b + 2.0 * (d + range_hat(lambda));
    (disc > 0.0).then(|| maugis_separated_point(lambda, b + disc.sqrt()).force_hat)
}

#[cfg(test)]
mod tests;
