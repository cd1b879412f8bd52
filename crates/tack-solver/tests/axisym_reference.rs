//! Checks of the independent axisymmetric ring-element reference (`axisym`) against closed
//! forms: Hertz, the Maugis–Dugdale pull-off, and the DMT and JKR limits of the exponential
//! law, with the mesh refinement observed. Run with `--nocapture` for the tables.

mod axisym;

use axisym::{Law, Reference};
use std::f64::consts::PI;
use std::time::Instant;

const R: f64 = 1.0;
const E_STAR: f64 = 1.0;
const GAMMA: f64 = 1e-3;

/// Maugis' approach scale D = (π²γ²R/K²)^(1/3), K = 4E*/3.
fn d_scale() -> f64 {
    let k = 4.0 / 3.0 * E_STAR;
    (PI * PI * GAMMA * GAMMA * R / (k * k)).cbrt()
}

/// Range ρ of the exponential law for Tabor's μ = (Rγ²/(E*²ρ³))^(1/3).
fn rho_for(mu: f64) -> f64 {
    (R * GAMMA * GAMMA / (E_STAR * E_STAR * mu.powi(3))).cbrt()
}

/// Pull-off F/(πγR) of a load–unload cycle on the given ring edges, the ring count and the
/// run time. The cycle starts at d = 0 (the first step jumps into contact), loads to
/// d = s/10 and retracts by s/30, s = max(D, ρ) the scale of the force–approach curve (ρ = h0
/// for Dugdale); the pull-off is refined by a parabola through the three samples about the
/// minimum. Steps that did not converge are reported (and left out of the pull-off).
fn pull_off_hat(law: Law, edges: Vec<f64>, range: f64) -> (f64, usize, f64) {
    let t = Instant::now();
    let mut m = Reference::with_edges(R, E_STAR, law, edges);
    let s = d_scale().max(range);
    let c = m.cycle(
        0.0,
        0.1 * s,
        0.1 * s,
        s / 30.0,
        -(1.5 * d_scale() + 4.0 * range),
    );
    let failed = c.points.iter().filter(|p| !p.converged).count();
    if failed > 0 {
        eprintln!(
            "warning: {failed} of {} steps did not converge",
            c.points.len()
        );
    }
    (
        c.pull_off / (PI * GAMMA * R),
        m.rings(),
        t.elapsed().as_secs_f64(),
    )
}

/// Ring edges for the exponential law at Tabor's μ: out to where the gap exceeds ~20ρ (the
/// traction beyond is below e^-20 of its peak), rings of width `h` where the contact edge and
/// the process zone move during the retraction (JKR-like, μ ≥ 3) and 4h elsewhere; uniform
/// width h for μ < 3 where nothing is sharp on the scale of ρ.
fn exp_edges(mu: f64, h: f64) -> Vec<f64> {
    let rho = rho_for(mu);
    let outer = (2.0 * R * (0.5 * d_scale().max(rho) + 20.0 * rho)).sqrt();
    if mu >= 3.0 {
        Reference::graded_edges(outer, 0.11, 0.23, h, 4.0)
    } else {
        let n = (outer / h).ceil() as usize;
        (0..=n).map(|i| outer * i as f64 / n as f64).collect()
    }
}

fn row(mu: f64, hat: f64, rings: usize, secs: f64) {
    eprintln!(
        "table | mu {mu:6.2} | pull-off/(pi gamma R) {hat:9.5} | rings {rings:5} | {secs:6.2} s"
    );
}

#[test]
fn hertz() {
    // 400 rings of width h = 1e-3 for contact radii 0.07–0.14: the ring-wise constant
    // pressure resolves the elliptical Hertz pressure to O((h/a)²) ≲ 2e-4 in the force, and the
    // contact radius to one ring (the mid-radius collocation decides contact ring by ring).
    let h = 1e-3;
    let mut m = Reference::new(R, E_STAR, Law::None, 400, 0.4);
    for d in [0.005, 0.01, 0.02] {
        let p = m.step(d);
        let f = 4.0 / 3.0 * E_STAR * R.sqrt() * d.powf(1.5);
        let a = (R * d).sqrt();
        eprintln!(
            "hertz d {d}: F/F_H − 1 = {:.2e}, a − √(Rd) = {:.2e}",
            p.force / f - 1.0,
            p.contact_radius - a
        );
        assert!(p.converged && p.stable);
        assert!((p.force / f - 1.0).abs() < 2e-4);
        assert!((p.contact_radius - a).abs() <= h);
    }
}

#[test]
fn elliptic_integrals() {
    // Closed values: K(0) = E(0) = π/2; K(1/√2) = Γ(1/4)²/(4√π); Legendre's relation
    // E K' + E' K − K K' = π/2 at k = 0.6 (k' = 0.8).
    let (k0, e0) = axisym::elliptic_ke(0.0, 1.0);
    assert!((k0 - PI / 2.0).abs() < 1e-15 && (e0 - PI / 2.0).abs() < 1e-15);
    let s = 0.5_f64.sqrt();
    let (k, _) = axisym::elliptic_ke(s, s);
    assert!((k - 1.854_074_677_301_372).abs() < 1e-14);
    let (k, e) = axisym::elliptic_ke(0.6, 0.8);
    let (kp, ep) = axisym::elliptic_ke(0.8, 0.6);
    assert!((e * kp + ep * k - k * kp - PI / 2.0).abs() < 1e-14);
    // Love: centre displacement of a unit disc 2a/E*, rim 4a/(πE*), continuous across r = a.
    assert!((axisym::disc_displacement(0.0, 1.0) - 2.0).abs() < 1e-14);
    assert!((axisym::disc_displacement(1.0, 1.0) - 4.0 / PI).abs() < 1e-14);
    let (a, b) = (
        axisym::disc_displacement(1.0 - 1e-9, 1.0),
        axisym::disc_displacement(1.0 + 1e-9, 1.0),
    );
    assert!((a - b).abs() < 1e-7);
}

#[test]
fn dugdale_against_maugis() {
    let k = 4.0 / 3.0 * E_STAR;
    let sigma_for = |lambda: f64| lambda / 2.0 * (PI * GAMMA * k * k / R).cbrt();
    for lambda in [0.5, 1.0] {
        let sigma0 = sigma_for(lambda);
        assert!(
            (tack_analytics::maugis_lambda(E_STAR, GAMMA, R, sigma0) / lambda - 1.0).abs() < 1e-12
        );
        let exact = tack_analytics::maugis_pull_off(E_STAR, GAMMA, R, sigma0) / (PI * GAMMA * R);
        let h0 = GAMMA / sigma0;
        let mut errs = Vec::new();
        for n in [200, 400] {
            let edges = (0..=n).map(|i| 0.4 * i as f64 / n as f64).collect();
            let (hat, rings, secs) = pull_off_hat(Law::Dugdale { sigma0, h0 }, edges, h0);
            let err = hat / exact - 1.0;
            eprintln!(
                "maugis | lambda {lambda} | rings {rings} | pull-off/(pi gamma R) {hat:.5} vs {exact:.5} | rel {err:.2e} | {secs:.2} s"
            );
            errs.push(err);
        }
        // Observed: |rel| ≈ 2e-4 → 1e-4 (λ = 0.5) and 1.2e-3 → 4e-4 (λ = 1) from 200 to 400
        // rings (h = 2e-3 → 1e-3, 10–30 rings across the cohesive zone): 0.5% bounds both.
        assert!(errs.iter().all(|e| e.abs() < 5e-3));
        assert!(
            errs[1].abs() <= errs[0].abs() + 1e-4,
            "no convergence with rings: {errs:?}"
        );
    }
    // λ = 3: the cohesive zone is narrow (~0.01 ≈ 10 rings of 1e-3 in the graded band); the
    // zone's outer end, where the gap meets h0 with zero slope, makes ring-wise Dugdale
    // tractions snap as the zone shortens (Newton fails at some steps, the relaxation lands on
    // a neighbouring state), and finer rings do NOT converge there (trials: between −4% and
    // +9% at 1e-3 … 2.5e-4, depending also on the step): a known limit of this reference,
    // checked only at 5% on the 1e-3 mesh. The exponential law has no such problem.
    let lambda = 3.0;
    let sigma0 = sigma_for(lambda);
    let h0 = GAMMA / sigma0;
    let exact = tack_analytics::maugis_pull_off(E_STAR, GAMMA, R, sigma0) / (PI * GAMMA * R);
    let edges = Reference::graded_edges(0.4, 0.09, 0.25, 1e-3, 4.0);
    let (hat, rings, secs) = pull_off_hat(Law::Dugdale { sigma0, h0 }, edges, h0);
    eprintln!(
        "maugis | lambda {lambda} | rings {rings} | pull-off/(pi gamma R) {hat:.5} vs {exact:.5} | rel {:.2e} | {secs:.2} s",
        hat / exact - 1.0
    );
    assert!((hat / exact - 1.0).abs() < 0.05);
}

#[test]
fn exponential_dmt_limit() {
    // μ = 0.2 is still 3–4% above the DMT −2 (the DMT limit is reached only as μ → 0, roughly
    // like Maugis' −2 + 1.72λ^(3/2) with λ ≈ 1.16μ); μ = 1 lies between DMT and JKR.
    let mut hats = Vec::new();
    for mu in [0.2, 1.0] {
        let rho = rho_for(mu);
        let (hat, rings, secs) = pull_off_hat(
            Law::Exponential { gamma: GAMMA, rho },
            exp_edges(mu, rho / 5.0),
            rho,
        );
        row(mu, hat, rings, secs);
        hats.push(hat);
    }
    // Refinement at μ = 0.2 (rings ρ/5 → ρ/10): the pressure varies on the scale √(2Rρ) ≫ ρ,
    // so the coarse mesh should already be within 0.2%.
    let rho = rho_for(0.2);
    let (fine, rings, secs) = pull_off_hat(
        Law::Exponential { gamma: GAMMA, rho },
        exp_edges(0.2, rho / 10.0),
        rho,
    );
    row(0.2, fine, rings, secs);
    assert!((fine / hats[0] - 1.0).abs() < 2e-3, "{fine} vs {}", hats[0]);
    assert!(
        (hats[0] + 2.0).abs() < 0.1,
        "μ = 0.2 should be within 5% of DMT: {}",
        hats[0]
    );
    assert!(
        hats[0] < hats[1] && hats[1] < -1.5,
        "the pull-off should fall from DMT to JKR: {hats:?}"
    );
}

#[test]
fn exponential_jkr_limit() {
    // Rings must be fine enough that a ring's own attraction cannot snap it: roughly
    // h·(2/π)(1 + ln(8a/h))·max|dp/dg|/E* < 1 with max|dp/dg| = γ/ρ², i.e. h ≲ ρ/3 at μ = 3,
    // ρ/4 at μ = 5, ρ/7 at μ = 10 (at μ = 10 with h = ρ/3 the pull-off came out 7% off, with
    // a failed step). μ = 10 needs ~1000 rings: see `exponential_mu10_fine` (ignored: minutes).
    // The fine band must also hold the process zone at the deepest approach of the cycle,
    // else coarse rings there snap and trap extra attached area (seen with a band ending at
    // 0.195 < a + zone).
    // μ = 5 approaches JKR's −1.5 from below (the process zone adds attraction outside the
    // contact), within 3%, and closer than μ = 3.
    let mut hats = Vec::new();
    for (mu, per) in [(3.0, 3.0), (5.0, 4.0)] {
        let rho = rho_for(mu);
        let (hat, rings, secs) = pull_off_hat(
            Law::Exponential { gamma: GAMMA, rho },
            exp_edges(mu, rho / per),
            rho,
        );
        row(mu, hat, rings, secs);
        hats.push(hat);
    }
    assert!((hats[1] + 1.5).abs() < 0.045, "{hats:?}");
    assert!((hats[1] + 1.5).abs() < (hats[0] + 1.5).abs(), "{hats:?}");
}

#[test]
#[ignore = "minutes: ~1000 rings"]
fn exponential_mu10_fine() {
    // Observed: −1.50598 with 998 rings (h = ρ/7 on 0.12 < r < 0.23), 240 s; not refined
    // further (an earlier run with the band ending at 0.195, inside the process zone at the
    // deepest approach, gave −1.548, and h = ρ/3 gave −1.605 with a failed step).
    let mu = 10.0;
    let rho = rho_for(mu);
    let outer = (2.0 * R * (0.5 * d_scale() + 20.0 * rho)).sqrt();
    let edges = Reference::graded_edges(outer, 0.12, 0.23, rho / 7.0, 4.0);
    let (hat, rings, secs) = pull_off_hat(Law::Exponential { gamma: GAMMA, rho }, edges, rho);
    row(mu, hat, rings, secs);
    assert!((hat + 1.5).abs() < 0.03, "{hat}");
}

#[test]
fn exponential_refinement_mu3() {
    // The peers' case: R = 1, E* = 1, γ = 1e-3, ρ = (Rγ²/(27E*²))^(1/3) ≈ 3.33e-3 (μ = 3).
    let mu = 3.0;
    let rho = rho_for(mu);
    let mut hats = Vec::new();
    let q: f64 = 1.5;
    for h in [rho / 3.0, rho / (3.0 * q), rho / (3.0 * q * q)] {
        let (hat, rings, secs) = pull_off_hat(
            Law::Exponential { gamma: GAMMA, rho },
            exp_edges(mu, h),
            rho,
        );
        row(mu, hat, rings, secs);
        hats.push(hat);
    }
    let (d1, d2) = (hats[0] - hats[1], hats[1] - hats[2]);
    let order = (d1 / d2).abs().ln() / q.ln();
    let extrapolated = hats[2] - d2 / ((d1 / d2).abs() - 1.0).max(1e-3);
    eprintln!(
        "mu 3 refinement: differences {d1:.2e}, {d2:.2e}, observed order {order:.2}, extrapolated {extrapolated:.5}"
    );
    // The last two meshes agree to 0.1%, and the pull-off lies between JKR (−1.5) and the
    // Maugis–Dugdale value at λ ≈ 1.16μ... bounded loosely by −1.6.
    assert!(d2.abs() < 1e-3 * hats[2].abs(), "{hats:?}");
    // The graded mesh against uniform rings of the band's width ρ/3 everywhere.
    let edges = exp_edges(mu, rho / 3.0);
    let outer = *edges.last().expect("edges");
    let n = (3.0 * outer / rho).ceil() as usize;
    let uniform = (0..=n).map(|i| outer * i as f64 / n as f64).collect();
    let (hat_u, rings, secs) = pull_off_hat(Law::Exponential { gamma: GAMMA, rho }, uniform, rho);
    row(mu, hat_u, rings, secs);
    assert!(
        (hat_u / hats[0] - 1.0).abs() < 1e-3,
        "uniform {hat_u} vs graded {}",
        hats[0]
    );
    assert!(hats.iter().all(|h| *h < -1.5 && *h > -1.6), "{hats:?}");
}
