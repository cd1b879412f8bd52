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
}

/// JKR force on the stable branch at approach `d`; NaN below the jump-off approach.
fn jkr_force_or_nan(e_star: f64, gamma: f64, radius: f64, d: f64) -> f64 {
    tack::analytics::jkr_force_from_approach(e_star, gamma, radius, d).unwrap_or(f64::NAN)
}
