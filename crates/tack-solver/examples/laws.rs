//! Every adhesion law of the registry with its facts on the peers' case (a sphere R = 1 on
//! E* = 1, γ = 1e-3, Tabor μ = 3 for the finite-range laws): parameter, range, reach, peak
//! tension on a 128² grid of the unit domain (the law bound to it), μ, the mesh rule and the
//! warning on a 32² grid.
//!
//! `cargo run --release -p tack-solver --example laws`

use tack_solver::{AdhesionLaw, KAPPA};

fn main() {
    let (radius, e_star, gamma, mu): (f64, f64, f64, f64) = (1.0, 1.0, 1e-3, 3.0);
    // The length ℓ of μ = (Rγ²/(E*²ℓ³))^(1/3), and the Dugdale law's σ0 at Maugis' λ = 1.16 μ.
    let length = (radius * gamma * gamma / (e_star * e_star * mu * mu * mu)).cbrt();
    let sigma0 = 1.16 * mu / tack_analytics::maugis_lambda(e_star, gamma, radius, 1.0);
    for model in AdhesionLaw::models() {
        let probe = AdhesionLaw::from_model(model, 1.0).expect("a listed model");
        let value = match probe.parameter().0 {
            tack_fields::SOLVER_KAPPA => KAPPA,
            tack_fields::ADHESION_SIGMA0 => sigma0,
            _ => length,
        };
        // Bound to the 128² grid (the smoothed Dugdale law's ramp is the element's; the others
        // are as made).
        let law = AdhesionLaw::from_model(model, value)
            .expect("a listed model")
            .on_mesh(gamma, e_star, 1.0 / 128.0);
        let (field, value) = law.parameter();
        println!("{model}: {field} = {value:.5e}: {}", law.meaning());
        println!("    {}", law.describe(gamma, e_star, 1.0 / 128.0));
        let show = |x: Option<f64>| x.map_or("none".to_string(), |x| format!("{x:.4e}"));
        println!(
            "    range {}, reach {}, Tabor mu {}, zone {} (at least {} elements)",
            show(law.range(gamma)),
            show(law.reach(gamma)),
            show(law.tabor(e_star, gamma, radius)),
            show(law.zone_length(e_star, gamma)),
            law.min_zone_elements()
        );
        for (key, v) in law.summary_entries(gamma, e_star, 1.0 / 128.0) {
            println!("    summary {key} = {v:.5e}");
        }
        if let Some(w) = law.mesh_warning(e_star, gamma, 1.0 / 32.0) {
            println!("    on 32²: {w}");
        }
    }
}
