//! Closed-form reference solutions for adhesive and non-adhesive contact (Li, Pohrt & Popov 2019).
//!
//! Plain `f64` functions (dependencies: `libm`, and `ellip` for the elliptic integrals). Units
//! are any consistent system: `e_star` is the effective modulus E*, `gamma` the work of
//! adhesion per unit area, forces are positive when compressive and the approach `d` is
//! positive when pressing. Equation numbers (Eq. N) refer to
//! Li, Pohrt & Popov, "Adhesive Strength of Contacts of Rough Spheres", Front. Mech. Eng. 2019.
//!
//! Besides the closed forms: the inverses of the adhesion parameters (waviness amplitude from
//! Johnson's α, Eq. 3; rms height from α*, Eq. 11) and a least-squares fit of the Gaussian form
//! of Eq. 12 ([`fit_gaussian`]), as used for the paper's Fig. 7. Beyond the paper: the Maugis
//! (1992) Dugdale model of the adhesive sphere, the JKR–DMT transition in one parameter λ, with
//! its stable branches, pull-off and jumps under approach control ([`maugis_pull_off_hat`],
//! [`maugis_force_at_hat`]), for comparisons with a finite interaction range; the toughening
//! `G(v)/G0` of a steady crack in a standard linear solid after Greenwood & Johnson (1981) and
//! Persson & Brener (2005) ([`greenwood_johnson_toughening`], [`persson_brener_toughening`]).
//!
//! ```
//! use std::f64::consts::PI;
//! use tack_analytics::{
//!     alpha_star, jkr_force_from_radius, jkr_pull_off_force, jkr_pull_off_radius,
//!     rms_height_from_alpha_star,
//! };
//!
//! // JKR pull-off under force control: F = −(3/2)πγR (Eq. 7), reached on the equilibrium
//! // curve F(a) at a_c = (9πγR²/(8E*))^(1/3).
//! let (e_star, gamma, radius) = (1.0, 5e-5, 1.0);
//! let f = jkr_pull_off_force(gamma, radius);
//! assert!((f + 1.5 * PI * gamma * radius).abs() < 1e-15);
//! let a_c = jkr_pull_off_radius(e_star, gamma, radius);
//! assert!((jkr_force_from_radius(e_star, gamma, radius, a_c) - f).abs() < 1e-12 * f.abs());
//!
//! // The rms height that gives α* = 0.36 on the band q0 = 2π, q1 = 128π with H = 0.5.
//! let (q0, q1) = (2.0 * PI, 128.0 * PI);
//! let h = rms_height_from_alpha_star(e_star, gamma, 0.36, 0.5, q0, q1);
//! assert!((alpha_star(e_star, gamma, h, 0.5, q0, q1) - 0.36).abs() < 1e-12);
//! ```

mod apparent;
mod const_math;
mod ellipse;
mod fits;
mod gaussian_fit;
mod hertz;
mod jkr;
mod johnson;
mod kendall;
mod maugis;
mod minimize;
mod patterned;
mod pohrt_popov;
mod power_law;
mod quad;
mod viscous_crack;
mod wavy_dugdale;
mod westergaard;

pub use apparent::{CycleBranch, apparent_work_of_adhesion, jkr_branch_force};
pub use ellipse::{
    EllipticHertz, EllipticJkrPoint, EllipticJkrPullOff, elliptic_hertz_eccentricity,
    elliptic_hertz_from_approach, elliptic_hertz_from_force, elliptic_jkr_pull_off,
};
pub use fits::{alpha_star, lambda_fit, lambda_star, rms_height_from_alpha_star};
pub use gaussian_fit::{FitError, GaussianFit, fit_gaussian};
pub use hertz::{hertz_contact_radius, hertz_force, hertz_max_pressure, hertz_pressure};
pub use jkr::{
    JKR_CURVE_MAX_POINTS, JkrPoint, jkr_approach_from_radius, jkr_approach_hat, jkr_approach_scale,
    jkr_curve_normalised, jkr_force_from_approach, jkr_force_from_radius, jkr_force_hat,
    jkr_force_scale, jkr_jump_off, jkr_length_scale_radius, jkr_pull_off_approach,
    jkr_pull_off_force, jkr_pull_off_radius, jkr_radius_from_approach,
    jkr_radius_hat_from_approach_hat,
};
pub use johnson::{
    JOHNSON_1D_CRITICAL_ALPHA, JOHNSON_1D_CRITICAL_PSI, johnson_1d_critical_alpha,
    johnson_1d_mean_pressure_ratio, johnson_2d_near_full_ratio, johnson_2d_p_star, johnson_alpha,
    waviness_amplitude_from_alpha,
};
pub use kendall::kendall_pull_off;
pub use maugis::{
    MaugisBranch, MaugisPoint, MaugisScales, maugis_dissipated_energy,
    maugis_dissipated_energy_hat, maugis_force_at, maugis_force_at_hat, maugis_jump_in_hat,
    maugis_jump_out_hat, maugis_lambda, maugis_lambda_critical, maugis_point, maugis_pull_off,
    maugis_pull_off_hat, maugis_scales, maugis_separated_jump_out_hat, maugis_separated_point,
};
pub use patterned::{
    PatternedState, RECEDE_SCAN, axisymmetric_force, axisymmetric_release_rate,
    axisymmetric_retraction, receding_front, strip_punch_release_tension,
};
pub use pohrt_popov::{KAPPA_CENTRE, KAPPA_MEAN, critical_stress, kappa_centre, kappa_mean};
pub use power_law::{
    mdr_shape_factor, power_law_jkr_approach, power_law_jkr_force, power_law_pull_off_force,
    power_law_pull_off_radius,
};
pub use viscous_crack::{
    dugdale_zone_opening, greenwood_johnson_toughening, persson_brener_toughening,
};
pub use wavy_dugdale::{
    WavyDugdalePoint, wavy_dugdale_lambda, wavy_dugdale_mean_pressure,
    wavy_dugdale_mean_pressure_ratio, wavy_dugdale_point, wavy_dugdale_pull_off_ratio,
    wavy_dugdale_stress_ratio,
};
pub use westergaard::{
    westergaard_half_width, westergaard_mean_pressure, westergaard_p_star, westergaard_pressure,
};

/// The example of README.md, run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctest;
