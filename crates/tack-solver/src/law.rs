//! The adhesion laws an [`AdhesiveSolver`](crate::AdhesiveSolver) can run, their facts (name,
//! range, peak tension, Tabor parameter) in one place, the smooth laws' traction–gap curves,
//! and the state the Dugdale law keeps on the solver's grid (its algorithm is in `dugdale.rs`;
//! the smooth laws' in `smooth.rs`).

use ndarray::Array2;
use tack_fields as fields;
use tack_geometry::Surface;

use crate::SolverError;

/// The adhesion law of an [`AdhesiveSolver`](crate::AdhesiveSolver).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AdhesionLaw {
    /// The zero-range (JKR) limit: the Pohrt–Popov detachment criterion
    /// `σ_c = sqrt(E*γ/(κΔx))`; an element bonds when it penetrates (see [`crate::KAPPA`]).
    JkrLimit {
        /// The Pohrt–Popov constant κ.
        kappa: f64,
    },
    /// A Dugdale cohesive zone: tension `σ0` wherever `0 < gap < h0 = γ/σ0` (the module docs of
    /// `dugdale.rs` and docs/theory.md give the three-set algorithm).
    Dugdale {
        /// The cohesive tension σ0 > 0.
        sigma0: f64,
    },
    /// The exponential law of the potential `V(g) = −γ e^(−g/ρ)` with a hard wall at `g = 0`:
    /// out of contact `p(g) = −(γ/ρ) e^(−g/ρ)`, peak tension `γ/ρ` at the wall (the law of
    /// Tamaas, ContactMechanics and the contact-mechanics challenge). Solved by `smooth.rs`.
    Exponential {
        /// The range ρ > 0.
        range: f64,
    },
    /// The Lennard-Jones 9–3 law with a hard wall at its equilibrium separation ε: with
    /// `h = g + ε`, `p(g) = −(8γ/3ε)[(ε/h)³ − (ε/h)⁹]`, zero at the wall, peak tension
    /// `16γ/(9√3 ε) ≈ 1.026 γ/ε` at `h = 3^(1/6) ε`, work `γ` (Derjaguin–Muller–Toporov's and
    /// Greenwood's law of two half-spaces). Solved by `smooth.rs`.
    LennardJones {
        /// The equilibrium separation ε > 0.
        range: f64,
    },
}

/// Which smooth traction–gap curve a [`Traction`] follows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Curve {
    Exponential,
    LennardJones,
}

/// A smooth law's traction–gap curve for work of adhesion `gamma` and `range`, with the hard
/// wall at `g = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Traction {
    pub(crate) curve: Curve,
    pub(crate) gamma: f64,
    pub(crate) range: f64,
}

impl Traction {
    /// The law's pressure at gap `g ≥ 0` (negative: tension).
    #[inline]
    pub(crate) fn pressure(&self, g: f64) -> f64 {
        let (gamma, r) = (self.gamma, self.range);
        match self.curve {
            Curve::Exponential => -(gamma / r) * (-g / r).exp(),
            Curve::LennardJones => {
                let t = r / (g + r);
                let t3 = t * t * t;
                -(8.0 * gamma / (3.0 * r)) * (t3 - t3 * t3 * t3)
            }
        }
    }

    /// `dp/dg` at gap `g ≥ 0`: positive where the law softens (destabilises).
    #[inline]
    pub(crate) fn stiffness(&self, g: f64) -> f64 {
        let (gamma, r) = (self.gamma, self.range);
        match self.curve {
            Curve::Exponential => (gamma / (r * r)) * (-g / r).exp(),
            Curve::LennardJones => {
                let h = g + r;
                let t = r / h;
                let t3 = t * t * t;
                (8.0 * gamma / (r * h)) * (t3 - 3.0 * t3 * t3 * t3)
            }
        }
    }

    /// Whether the law stiffens anywhere (`dp/dg < 0`: the Lennard-Jones law next to its
    /// wall), where the landing's flow must be damped and is slow.
    pub(crate) fn stiffens(&self) -> bool {
        match self.curve {
            Curve::Exponential => false,
            Curve::LennardJones => true,
        }
    }

    /// The greatest tension of the law.
    pub(crate) fn peak(&self) -> f64 {
        match self.curve {
            Curve::Exponential => self.gamma / self.range,
            Curve::LennardJones => 16.0 * self.gamma / (9.0 * 3f64.sqrt() * self.range),
        }
    }
}

/// Least length of a Dugdale cohesive zone, in elements, below which a result is flagged: the
/// zone's tension is then carried by a ring of elements too thin to shape it.
pub const MIN_COHESIVE_ZONE_ELEMENTS: f64 = 2.0;

/// Least width of a smooth law's process zone, in elements, below which a result is flagged:
/// an element's own stiffness `E*/(κ₀Δx)` then no longer holds the law's steepest softening,
/// the front advances element by element and the forces depend on the mesh.
pub const MIN_PROCESS_ZONE_ELEMENTS: f64 = 1.0;

/// A smooth law's reach ([`AdhesionLaw::reach`]) is where its tension falls to this fraction
/// of the peak: what a crop leaves out is a tension below it.
pub const REACH_FRACTION: f64 = 1e-8;

/// The smallest range allowed, relative to the largest height: below it the gap test
/// `g < h0` is decided by the round-off of `f − d + u`.
pub const RANGE_ROUND_OFF: f64 = 1e-12;

impl AdhesionLaw {
    /// The name in scene files and results: `"jkr_limit"`, `"dugdale"`, `"exponential"` or
    /// `"lennard_jones"`.
    pub fn name(&self) -> &'static str {
        match self {
            AdhesionLaw::JkrLimit { .. } => "jkr_limit",
            AdhesionLaw::Dugdale { .. } => "dugdale",
            AdhesionLaw::Exponential { .. } => "exponential",
            AdhesionLaw::LennardJones { .. } => "lennard_jones",
        }
    }

    /// Whether every element carries the traction of its own gap (a smooth law).
    pub fn is_smooth(&self) -> bool {
        matches!(
            self,
            AdhesionLaw::Exponential { .. } | AdhesionLaw::LennardJones { .. }
        )
    }

    /// The law's length for work of adhesion `gamma`: the Dugdale range `γ/σ0`, ρ, ε; `None`
    /// for the zero-range criterion.
    pub fn range(&self, gamma: f64) -> Option<f64> {
        match *self {
            AdhesionLaw::JkrLimit { .. } => None,
            AdhesionLaw::Dugdale { sigma0 } => Some(gamma / sigma0),
            AdhesionLaw::Exponential { range } | AdhesionLaw::LennardJones { range } => Some(range),
        }
    }

    /// The gap beyond which the law's tension is negligible, for cropping and for where a path
    /// starts: the Dugdale range `γ/σ0`; for a smooth law the gap where its tension falls to
    /// [`REACH_FRACTION`] of the peak (`ρ ln 10⁸ ≈ 18.4ρ`, about `640ε`); `None` for the
    /// zero-range criterion.
    pub fn reach(&self, gamma: f64) -> Option<f64> {
        match *self {
            AdhesionLaw::JkrLimit { .. } => None,
            AdhesionLaw::Dugdale { sigma0 } => Some(gamma / sigma0),
            AdhesionLaw::Exponential { range } => Some(range * (1.0 / REACH_FRACTION).ln()),
            AdhesionLaw::LennardJones { range } => {
                // (8/3)(t³ − t⁹)/(16/(9√3)) = fraction with t = ε/h: t³ ≈ fraction·2/(3√3).
                let t = (REACH_FRACTION * 2.0 / (3.0 * 3f64.sqrt())).cbrt();
                Some(range / t - range)
            }
        }
    }

    /// The greatest tension an element carries: the criterion's `σ_c = sqrt(E*γ/(κΔx))`, σ0,
    /// `γ/ρ`, or `16γ/(9√3 ε)`.
    pub fn peak_tension(&self, gamma: f64, e_star: f64, dx: f64) -> f64 {
        match *self {
            AdhesionLaw::JkrLimit { kappa } => (e_star * gamma / (kappa * dx)).sqrt(),
            AdhesionLaw::Dugdale { sigma0 } => sigma0,
            AdhesionLaw::Exponential { .. } | AdhesionLaw::LennardJones { .. } => {
                self.traction(gamma).map_or(0.0, |t| t.peak())
            }
        }
    }

    /// Tabor's parameter `μ = (Rγ²/(E*²ℓ³))^(1/3)` of a sphere of `radius` with the law's
    /// length ℓ ([`AdhesionLaw::range`]); `None` for the zero-range criterion (μ = ∞).
    pub fn tabor(&self, e_star: f64, gamma: f64, radius: f64) -> Option<f64> {
        let l = self.range(gamma)?;
        Some((radius * gamma * gamma / (e_star * e_star * l * l * l)).cbrt())
    }

    /// The greatest tension of an element of work of adhesion `gamma` when the law was set for
    /// the `reference` work (a γ map, [`crate::AdhesiveSolver::set_gamma_map`]): the criterion's
    /// own `σ_c(γ)`; the Dugdale law keeps its range `h0 = γ_ref/σ0` and scales σ0 by
    /// `γ/γ_ref`; a smooth law keeps its range and scales its peak by `γ/γ_ref`.
    pub fn element_tension(&self, gamma: f64, reference: f64, e_star: f64, dx: f64) -> f64 {
        match *self {
            AdhesionLaw::JkrLimit { kappa } => (e_star / (kappa * dx) * gamma).sqrt(),
            AdhesionLaw::Dugdale { sigma0 } => sigma0 * (gamma / reference),
            AdhesionLaw::Exponential { .. } | AdhesionLaw::LennardJones { .. } => {
                self.peak_tension(reference, e_star, dx) * (gamma / reference)
            }
        }
    }

    /// The length the mesh must resolve: the Dugdale law's cohesive zone `πE*γ/(4σ0²)` ahead of
    /// a straight crack (Griffith's `K² = 2E*γ` in `l = (π/8)(K/σ0)²`), a smooth law's process
    /// zone `(8/3π)E*ℓ²/γ` (ℓ its range ρ or ε: the length over which the exponential law's
    /// tension acts ahead of a crack; the Lennard-Jones law's is of the same order); `None`
    /// for the zero-range criterion, whose mesh rule is the contact's own size.
    pub fn zone_length(&self, e_star: f64, gamma: f64) -> Option<f64> {
        match *self {
            AdhesionLaw::JkrLimit { .. } => None,
            AdhesionLaw::Dugdale { sigma0 } => {
                Some(std::f64::consts::PI * e_star * gamma / (4.0 * sigma0 * sigma0))
            }
            AdhesionLaw::Exponential { range } | AdhesionLaw::LennardJones { range } => {
                Some(8.0 / (3.0 * std::f64::consts::PI) * e_star * range * range / gamma)
            }
        }
    }

    /// The least number of elements across [`AdhesionLaw::zone_length`] below which a result
    /// is flagged: [`MIN_COHESIVE_ZONE_ELEMENTS`] or [`MIN_PROCESS_ZONE_ELEMENTS`].
    pub fn min_zone_elements(&self) -> f64 {
        match self {
            AdhesionLaw::JkrLimit { .. } => 0.0,
            AdhesionLaw::Dugdale { .. } => MIN_COHESIVE_ZONE_ELEMENTS,
            _ => MIN_PROCESS_ZONE_ELEMENTS,
        }
    }

    /// The warning of a mesh of element `dx` that does not resolve the law's zone
    /// ([`AdhesionLaw::zone_length`], [`AdhesionLaw::min_zone_elements`]), naming the fields
    /// that mend it; `None` when it does (and for the criterion, whose mesh rules are the
    /// contact's and are checked with the body).
    pub fn mesh_warning(&self, e_star: f64, gamma: f64, dx: f64) -> Option<String> {
        let zone = self.zone_length(e_star, gamma)?;
        let (elements, least) = (zone / dx, self.min_zone_elements());
        if elements >= least {
            return None;
        }
        let shown = fields::num((elements * 100.0).round() / 100.0);
        let dx_field = fields::GRID_DX;
        Some(match self {
            AdhesionLaw::Dugdale { .. } => format!(
                "under-resolved cohesive zone: its length πE*γ/(4σ0²) = {} spans {shown} \
                 elements (at least {least} needed); the Dugdale law then acts element by \
                 element and the forces depend on the mesh (refine {dx_field} or lower {})",
                fields::num(zone),
                fields::ADHESION_SIGMA0,
            ),
            _ => format!(
                "under-resolved process zone: its width (8/3π)E*ρ²/γ = {} spans {shown} \
                 elements (at least {least} needed); the front then moves element by element \
                 and the forces depend on the mesh (refine {dx_field} or raise {})",
                fields::rounded(zone),
                fields::ADHESION_RANGE,
            ),
        })
    }

    /// The law's own entries of a result's summary for work of adhesion `gamma`, modulus
    /// `e_star` and element `dx`: `sigma_c` and `kappa` (zero-range); `sigma0`, `range` and
    /// `cohesive_zone_elements` (Dugdale); `range`, `peak_tension` and `process_zone_elements`
    /// (smooth laws).
    pub fn summary_entries(&self, gamma: f64, e_star: f64, dx: f64) -> Vec<(&'static str, f64)> {
        let peak = self.peak_tension(gamma, e_star, dx);
        let elements = self.zone_length(e_star, gamma).map(|z| z / dx);
        match *self {
            AdhesionLaw::JkrLimit { kappa } => vec![("sigma_c", peak), ("kappa", kappa)],
            AdhesionLaw::Dugdale { sigma0 } => vec![
                ("sigma0", sigma0),
                ("range", gamma / sigma0),
                ("cohesive_zone_elements", elements.unwrap_or(0.0)),
            ],
            AdhesionLaw::Exponential { range } | AdhesionLaw::LennardJones { range } => vec![
                ("range", range),
                ("peak_tension", peak),
                ("process_zone_elements", elements.unwrap_or(0.0)),
            ],
        }
    }

    /// One line naming the law and its parameters for a run's report, e.g. `Dugdale, sigma0 =
    /// 2, range = 0.0005`.
    pub fn describe(&self, gamma: f64, e_star: f64, dx: f64) -> String {
        let r = fields::rounded;
        let peak = r(self.peak_tension(gamma, e_star, dx));
        match *self {
            AdhesionLaw::JkrLimit { kappa } => format!("zero-range limit, kappa = {}", r(kappa)),
            AdhesionLaw::Dugdale { sigma0 } => {
                format!(
                    "Dugdale, sigma0 = {}, range = {}",
                    r(sigma0),
                    r(gamma / sigma0)
                )
            }
            AdhesionLaw::Exponential { range } => {
                format!(
                    "exponential, range rho = {}, peak tension = {peak}",
                    r(range)
                )
            }
            AdhesionLaw::LennardJones { range } => format!(
                "Lennard-Jones 9-3, range epsilon = {}, peak tension = {peak}",
                r(range)
            ),
        }
    }

    /// The smooth law's curve (`None` for the criterion and the Dugdale law).
    pub(crate) fn traction(&self, gamma: f64) -> Option<Traction> {
        let (curve, range) = match *self {
            AdhesionLaw::Exponential { range } => (Curve::Exponential, range),
            AdhesionLaw::LennardJones { range } => (Curve::LennardJones, range),
            _ => return None,
        };
        Some(Traction {
            curve,
            gamma,
            range,
        })
    }

    /// Checks the law's own inputs for work of adhesion `gamma` on `surface`: κ > 0 for the
    /// criterion; for the Dugdale law σ0 > 0, γ > 0 and a range γ/σ0 above the round-off of
    /// the heights ([`RANGE_ROUND_OFF`]). Errors name the field.
    pub fn check(&self, gamma: f64, surface: &Surface) -> Result<(), SolverError> {
        let sigma0 = match *self {
            AdhesionLaw::JkrLimit { kappa } => {
                return crate::validate::positive(fields::SOLVER_KAPPA, kappa).map(|_| ());
            }
            AdhesionLaw::Dugdale { sigma0 } => sigma0,
            AdhesionLaw::Exponential { range } | AdhesionLaw::LennardJones { range } => {
                return check_smooth(range, gamma, surface);
            }
        };
        crate::validate::positive(fields::ADHESION_SIGMA0, sigma0)?;
        if gamma <= 0.0 {
            return Err(SolverError::OutOfRange {
                field: fields::MATERIAL_GAMMA,
                value: gamma,
                allowed: "a finite number > 0 under the Dugdale law (the range is γ/σ0)",
            });
        }
        let range = gamma / sigma0;
        let top = surface
            .heights()
            .iter()
            .fold(0.0f64, |m, &f| m.max(f.abs()));
        if range.is_nan() || range <= RANGE_ROUND_OFF * top {
            return Err(SolverError::OutOfRange {
                field: fields::ADHESION_SIGMA0,
                value: sigma0,
                allowed: "small enough that the range γ/σ0 exceeds 1e-12 of the largest height \
                          (below it the gap test is round-off)",
            });
        }
        Ok(())
    }
}

/// A smooth law's inputs: γ > 0 and a range ρ (ε) > 0 above the round-off of the heights.
fn check_smooth(range: f64, gamma: f64, surface: &Surface) -> Result<(), SolverError> {
    crate::validate::positive(fields::ADHESION_RANGE, range)?;
    if gamma <= 0.0 || !gamma.is_finite() {
        return Err(SolverError::OutOfRange {
            field: fields::MATERIAL_GAMMA,
            value: gamma,
            allowed: "a finite number > 0 under a smooth law (exponential, lennard_jones)",
        });
    }
    let top = surface
        .heights()
        .iter()
        .fold(0.0f64, |m, &f| m.max(f.abs()));
    if range <= RANGE_ROUND_OFF * top {
        return Err(SolverError::OutOfRange {
            field: fields::ADHESION_RANGE,
            value: range,
            allowed: "above 1e-12 of the largest height (below it the law acts on round-off)",
        });
    }
    Ok(())
}

/// The Dugdale law's state on the solver's grid: σ0, the range and the cohesive zone.
pub(crate) struct Cohesive {
    pub(crate) sigma0: f64,
    pub(crate) range: f64,
    pub(crate) zone: Array2<bool>,
    /// Contact or zone: the loaded elements that fix the sub-grid.
    pub(crate) loaded: Array2<bool>,
}

impl Cohesive {
    /// Checks the law ([`AdhesionLaw::check`]) and makes the empty zone.
    pub(crate) fn new(
        gamma: f64,
        sigma0: f64,
        surface: &Surface,
        shape: (usize, usize),
    ) -> Result<Self, SolverError> {
        AdhesionLaw::Dugdale { sigma0 }.check(gamma, surface)?;
        Ok(Self {
            sigma0,
            range: gamma / sigma0,
            zone: Array2::from_elem(shape, false),
            loaded: Array2::from_elem(shape, false),
        })
    }
}
