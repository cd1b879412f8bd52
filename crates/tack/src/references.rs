//! The closed-form reference values of a problem (F_JKR, Kendall, Maugis, α*, …) that the
//! summary compares a run against; each shape and law sets its own (`crate::shape`).

/// Closed-form reference values for the summary; `None` where they do not apply.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct References {
    /// JKR pull-off force −(3/2)πγR of the smooth sphere (Eq. 7), spheres only.
    pub f_jkr: Option<f64>,
    /// Approach at the JKR pull-off (Eq. 8), spheres only.
    pub d_jkr: Option<f64>,
    /// Johnson's parameter α (Eq. 3) of a waviness.
    pub johnson_alpha: Option<f64>,
    /// The adhesion parameter α* (Eq. 11) of random roughness.
    pub alpha_star: Option<f64>,
    /// Dugdale law on a sphere: the Maugis parameter λ = 2σ0 (R/(πγK²))^(1/3), K = 4E*/3.
    pub maugis_lambda: Option<f64>,
    /// Dugdale law on a sphere: the Maugis–Dugdale pull-off force under approach control.
    pub f_maugis: Option<f64>,
    /// Smooth law on a sphere: Tabor's parameter μ = (Rγ²/(E*²ℓ³))^(1/3) with the law's range ℓ
    /// (ρ or ε).
    pub tabor_mu: Option<f64>,
    /// Kendall's pull-off force −sqrt(8πa³E*γ) (signed: tensile) of a circular punch.
    pub f_kendall: Option<f64>,
    /// The exact JKR-limit pull-off force of a power-law body c·r^m on a free grid (method of
    /// dimensionality reduction; `tack_analytics::power_law_pull_off_force`).
    pub f_mdr: Option<f64>,
    /// The approximate (Johnson–Greenwood) JKR pull-off force of an ellipsoid under approach
    /// control, signed (tensile negative): `tack_analytics::elliptic_jkr_pull_off`.
    pub f_elliptic: Option<f64>,
    /// Mean pressure of complete non-adhesive contact of a waviness: p*_1D = πE*h/λ (Eq. 2)
    /// or p*_2D = √2πE*h/λ (Eq. 5).
    pub p_star: Option<f64>,
    /// The contact radius at the pull-off that sets the detachment criterion's mesh error
    /// (a_c of a sphere, a punch's radius, a power law's a_F, an ellipse's shorter semi-axis):
    /// the error floor of a Richardson extrapolation.
    pub pull_off_radius: Option<f64>,
    /// The length the zero-range criterion's mesh rule judges and what it is (the pull-off
    /// contact radius a_c of a sphere, a punch's radius, …): a problem under the criterion
    /// warns when it spans too few elements (`crate::shape::under_resolved`); a finite-range
    /// law's own warning judges its zone instead.
    pub criterion_mesh: Option<(f64, &'static str)>,
}

impl References {
    /// The JKR references of a sphere of radius `radius`: F_JKR and d_JKR.
    pub fn set_jkr(&mut self, e_star: f64, gamma: f64, radius: f64) {
        self.f_jkr = Some(tack_analytics::jkr_pull_off_force(gamma, radius));
        self.d_jkr = Some(tack_analytics::jkr_pull_off_approach(e_star, gamma, radius));
    }
}
