//! Closed-form reference solutions for adhesive and non-adhesive contact (Li, Pohrt & Popov 2019).
//!
//! Plain `f64` functions, no dependencies. Units are any consistent system: `e_star` is the
//! effective modulus E*, `gamma` the work of adhesion per unit area, forces are positive when
//! compressive and the approach `d` is positive when pressing. Equation numbers (Eq. N) refer to
//! Li, Pohrt & Popov, "Adhesive Strength of Contacts of Rough Spheres", Front. Mech. Eng. 2019.

mod const_math;
mod fits;
mod hertz;
mod jkr;
mod johnson;
mod kendall;
mod pohrt_popov;
#[cfg(test)]
mod quad;
mod westergaard;

pub use fits::{alpha_star, lambda_fit, lambda_star};
pub use hertz::{hertz_contact_radius, hertz_force, hertz_max_pressure, hertz_pressure};
pub use jkr::{
    JkrPoint, jkr_approach_from_radius, jkr_approach_hat, jkr_approach_scale,
    jkr_force_from_approach, jkr_force_from_radius, jkr_force_hat, jkr_force_scale, jkr_jump_off,
    jkr_length_scale_radius, jkr_pull_off_approach, jkr_pull_off_force, jkr_pull_off_radius,
    jkr_radius_from_approach, jkr_radius_hat_from_approach_hat,
};
pub use johnson::{
    JOHNSON_1D_CRITICAL_ALPHA, JOHNSON_1D_CRITICAL_PSI, johnson_1d_critical_alpha,
    johnson_1d_mean_pressure_ratio, johnson_2d_near_full_ratio, johnson_2d_p_star, johnson_alpha,
};
pub use kendall::kendall_pull_off;
pub use pohrt_popov::{KAPPA_CENTRE, KAPPA_MEAN, critical_stress, kappa_centre, kappa_mean};
pub use westergaard::{
    westergaard_half_width, westergaard_mean_pressure, westergaard_p_star, westergaard_pressure,
};
