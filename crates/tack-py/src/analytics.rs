//! The closed forms of `tack::analytics` as scalar functions (`tack.analytics` vectorises them).

use pyo3::prelude::*;

/// Scalar closed forms: each becomes a Python function of the same name and arguments.
macro_rules! closed_forms {
    ($($name:ident($($arg:ident),*) => $path:path;)*) => {
        $(
            #[pyfunction]
            fn $name($($arg: f64),*) -> f64 {
                $path($($arg),*)
            }
        )*

        /// Registers the closed forms with the module.
        pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
            $(m.add_function(wrap_pyfunction!($name, m)?)?;)*
            Ok(())
        }
    };
}

closed_forms! {
    hertz_force(e_star, radius, d) => tack::analytics::hertz_force;
    hertz_contact_radius(radius, d) => tack::analytics::hertz_contact_radius;
    hertz_max_pressure(e_star, radius, d) => tack::analytics::hertz_max_pressure;
    jkr_pull_off_force(gamma, radius) => tack::analytics::jkr_pull_off_force;
    jkr_pull_off_approach(e_star, gamma, radius) => tack::analytics::jkr_pull_off_approach;
    jkr_pull_off_radius(e_star, gamma, radius) => tack::analytics::jkr_pull_off_radius;
    jkr_approach_scale(e_star, gamma, radius) => tack::analytics::jkr_approach_scale;
    jkr_force_from_radius(e_star, gamma, radius, a) => tack::analytics::jkr_force_from_radius;
    jkr_approach_from_radius(e_star, gamma, radius, a) => tack::analytics::jkr_approach_from_radius;
    jkr_force_from_approach(e_star, gamma, radius, d) => jkr_force_or_nan;
    kendall_pull_off(e_star, gamma, a) => tack::analytics::kendall_pull_off;
    power_law_pull_off_force(e_star, gamma, c, exponent) => tack::analytics::power_law_pull_off_force;
    johnson_alpha(e_star, gamma, h, wavelength) => tack::analytics::johnson_alpha;
    westergaard_p_star(e_star, h, wavelength) => tack::analytics::westergaard_p_star;
    johnson_2d_p_star(e_star, h, wavelength) => tack::analytics::johnson_2d_p_star;
    lambda_fit(alpha) => tack::analytics::lambda_fit;
    alpha_star(e_star, gamma, h, hurst, q0, q1) => tack::analytics::alpha_star;
    rms_height_from_alpha_star(e_star, gamma, alpha_star, hurst, q0, q1) => tack::analytics::rms_height_from_alpha_star;
    lambda_star(alpha_star) => tack::analytics::lambda_star;
    critical_stress(e_star, gamma, dx, kappa) => tack::analytics::critical_stress;
    maugis_lambda(e_star, gamma, radius, sigma0) => tack::analytics::maugis_lambda;
    maugis_pull_off_force(e_star, gamma, radius, sigma0) => tack::analytics::maugis_pull_off;
    maugis_pull_off_hat(lam) => tack::analytics::maugis_pull_off_hat;
    maugis_dissipated_energy(e_star, gamma, radius, sigma0) => maugis_dissipated_or_nan;
    maugis_force_contact(e_star, gamma, radius, sigma0, d) => maugis_force_contact_or_nan;
    maugis_force_separated(e_star, gamma, radius, sigma0, d) => maugis_force_separated_or_nan;
    maugis_jump_out_approach(e_star, gamma, radius, sigma0) => maugis_jump_out_approach_of;
    maugis_jump_out_force(e_star, gamma, radius, sigma0) => maugis_jump_out_force_of;
    maugis_jump_in_approach(e_star, gamma, radius, sigma0) => maugis_jump_in_approach_of;
    maugis_jump_in_force(e_star, gamma, radius, sigma0) => maugis_jump_in_force_of;
}

/// λc of the Maugis model (`tack::analytics::maugis_lambda_critical`), for the Python
/// constant `MAUGIS_LAMBDA_CRITICAL`.
pub fn lambda_critical() -> f64 {
    tack::analytics::maugis_lambda_critical()
}

/// The Maugis loop's dissipated energy; NaN for λ ≤ λc (no contact-branch loop).
fn maugis_dissipated_or_nan(e_star: f64, gamma: f64, radius: f64, sigma0: f64) -> f64 {
    tack::analytics::maugis_dissipated_energy(e_star, gamma, radius, sigma0).unwrap_or(f64::NAN)
}

/// Force on the stable contact branch at approach `d`; NaN where it has no state.
fn maugis_force_contact_or_nan(e_star: f64, gamma: f64, radius: f64, sigma0: f64, d: f64) -> f64 {
    use tack::analytics::{MaugisBranch, maugis_force_at};
    maugis_force_at(e_star, gamma, radius, sigma0, d, MaugisBranch::Contact).unwrap_or(f64::NAN)
}

/// Force on the stable separated branch at approach `d`; NaN where it has no state.
fn maugis_force_separated_or_nan(e_star: f64, gamma: f64, radius: f64, sigma0: f64, d: f64) -> f64 {
    use tack::analytics::{MaugisBranch, maugis_force_at};
    maugis_force_at(e_star, gamma, radius, sigma0, d, MaugisBranch::Separated).unwrap_or(f64::NAN)
}

/// The jump-out under approach control in physical units, `(d, F)`: the end of the stable
/// contact branch (λ > λc) or of the stable separated branch (λ ≤ λc).
fn maugis_jump_out(e_star: f64, gamma: f64, radius: f64, sigma0: f64) -> (f64, f64) {
    use tack::analytics as a;
    let lambda = a::maugis_lambda(e_star, gamma, radius, sigma0);
    let s = a::maugis_scales(e_star, gamma, radius);
    a::maugis_jump_out_hat(lambda)
        .or_else(|| a::maugis_separated_jump_out_hat(lambda))
        .map_or((f64::NAN, f64::NAN), |(d, f)| (d * s.approach, f * s.force))
}

fn maugis_jump_out_approach_of(e_star: f64, gamma: f64, radius: f64, sigma0: f64) -> f64 {
    maugis_jump_out(e_star, gamma, radius, sigma0).0
}

fn maugis_jump_out_force_of(e_star: f64, gamma: f64, radius: f64, sigma0: f64) -> f64 {
    maugis_jump_out(e_star, gamma, radius, sigma0).1
}

/// The jump-in of the approaching free sphere in physical units, `(d, F after the jump)`.
fn maugis_jump_in(e_star: f64, gamma: f64, radius: f64, sigma0: f64) -> (f64, f64) {
    use tack::analytics as a;
    let lambda = a::maugis_lambda(e_star, gamma, radius, sigma0);
    let s = a::maugis_scales(e_star, gamma, radius);
    let (d, _, f) = a::maugis_jump_in_hat(lambda);
    (d * s.approach, f * s.force)
}

fn maugis_jump_in_approach_of(e_star: f64, gamma: f64, radius: f64, sigma0: f64) -> f64 {
    maugis_jump_in(e_star, gamma, radius, sigma0).0
}

fn maugis_jump_in_force_of(e_star: f64, gamma: f64, radius: f64, sigma0: f64) -> f64 {
    maugis_jump_in(e_star, gamma, radius, sigma0).1
}

/// JKR force on the stable branch at approach `d`; NaN below the jump-off approach.
fn jkr_force_or_nan(e_star: f64, gamma: f64, radius: f64, d: f64) -> f64 {
    tack::analytics::jkr_force_from_approach(e_star, gamma, radius, d).unwrap_or(f64::NAN)
}
