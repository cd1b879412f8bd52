//! The Dugdale law with its step smoothed over an element's own opening: a smooth law, run by
//! `smooth.rs`, that removes most of the Dugdale law's lattice trapping on coarse meshes.

use tack_fields as fields;

use super::{Curve, REACH_FRACTION};
use crate::SolverError;
use crate::validate::positive;

/// The scene name.
pub(super) const NAME: &str = "smoothed_dugdale";

/// The smoothing's half-width in openings `k σ0` of one element under the tension σ0
/// ([`SmoothedDugdale::on_mesh`]). At the steepest point of the ramp an element's own
/// stiffness then exceeds the law's by `2 / 0.9375`, so no element hops by itself; the
/// collective front still can, as under any smooth law. Measured against Maugis (1992) on the
/// smooth sphere (docs/theory.md §3.7, "A sub-element variant"): half-widths of 0.57, 1.1, 2.3
/// and 4.5 openings at λ = 1 and l/Δx = 10 left +3.6%, +1.6%, +0.47% and +0.15% of the
/// pull-off (the Dugdale law +7.4%); 2 keeps the ramp narrow against the range where the
/// zone is resolved (`s/h0 ≈ 1.76/(l/Δx)`).
pub const SMOOTHING_OPENINGS: f64 = 2.0;

/// The least half-width of the ramp, as a fraction of the range: the custom-curve checks'
/// central differences resolve a ramp down to about this (1e-2 fails near the ramp's ends).
/// Two openings fall below it where the zone spans more than about 90 elements; the ramp then
/// spans more openings, which the measurements above favour.
pub const LEAST_SMOOTHING: f64 = 0.02;

/// The Dugdale law of tension σ0 and range `h0 = γ/σ0` whose tension falls from σ0 to 0 across
/// `h0 − s < g < h0 + s` by the quintic smoothstep `S(t) = t³(10 − 15t + 6t²)` instead of at
/// once: `p(g) = −σ0 S((h0 + s − g)/(2s))`, which keeps the work `σ0 h0 = γ` (the ramp is odd
/// about `h0`), the peak σ0 and a continuous slope. Bound to a mesh ([`SmoothedDugdale::on_mesh`],
/// `s` about an element's own opening) it tends to the Dugdale law as the mesh is refined, with
/// an error 11 to 62 times smaller on the same mesh and no regular order (docs/theory.md §3.7). A
/// scene names it `[adhesion] model = "smoothed_dugdale"` with `sigma0`, and the run binds it to
/// its mesh; [`AdhesionLaw::from_model`](super::AdhesionLaw::from_model) makes it unbound
/// ([`SmoothedDugdale::unbound`]), and [`AdhesionLaw::on_mesh`](super::AdhesionLaw::on_mesh)
/// or the solver binds it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SmoothedDugdale {
    /// The tension σ0 > 0.
    pub sigma0: f64,
    /// The range `h0 = γ/σ0`, where the tension is half of σ0 (0 until bound).
    pub range: f64,
    /// The ramp's half-width `s`, `0 < s < h0` (0 until bound).
    pub width: f64,
}

impl SmoothedDugdale {
    /// The law of tension `sigma0` not yet bound to a work of adhesion and a mesh: its range
    /// and width are 0, and a solver made with it binds it to its own
    /// (`AdhesiveSolver::with_law`).
    pub fn unbound(sigma0: f64) -> Self {
        Self {
            sigma0,
            range: 0.0,
            width: 0.0,
        }
    }

    /// Whether the law has its range and width.
    pub fn is_bound(&self) -> bool {
        self.range > 0.0 && self.width > 0.0
    }

    /// The law of tension `sigma0` and work `gamma` with the ramp's half-width `width` given,
    /// `0 < width < γ/σ0`; errors name the bad value.
    pub fn with_width(sigma0: f64, gamma: f64, width: f64) -> Result<Self, SolverError> {
        positive("sigma0", sigma0)?;
        positive("gamma", gamma)?;
        let range = gamma / sigma0;
        if !(width.is_finite() && width > 0.0 && width < range) {
            return Err(SolverError::OutOfRange {
                field: "SmoothedDugdale::width",
                value: width,
                allowed: "in (0, γ/σ0)",
            });
        }
        Ok(Self {
            sigma0,
            range,
            width,
        })
    }

    /// The law of tension `sigma0` and work `gamma` on a mesh of elements `dx` over a modulus
    /// `e_star`: the ramp's half-width is [`SMOOTHING_OPENINGS`] openings `k σ0` of a
    /// half-space's element (`k = 1.1222 Δx/E*`, `FreeOperator::self_compliance_of`; a film's or
    /// a periodic grid's element is a little stiffer, and the ramp is the same law there), at
    /// least [`LEAST_SMOOTHING`] of the range and at most half of it (`s/h0 ≈ 1.76/(l/Δx)`,
    /// capped on zones under about 3.5 elements). Errors name the value that is not finite and
    /// positive.
    pub fn on_mesh(sigma0: f64, gamma: f64, e_star: f64, dx: f64) -> Result<Self, SolverError> {
        for (field, value) in [
            ("sigma0", sigma0),
            ("gamma", gamma),
            ("e_star", e_star),
            ("dx", dx),
        ] {
            positive(field, value)?;
        }
        let k = tack_kernels::FreeOperator::self_compliance_of(dx, e_star);
        let range = gamma / sigma0;
        let width = (SMOOTHING_OPENINGS * k * sigma0).clamp(LEAST_SMOOTHING * range, 0.5 * range);
        Self::with_width(sigma0, gamma, width)
    }

    /// The ramp's argument `t` at gap `g`: 1 short of the ramp, 0 past it.
    #[inline]
    fn t(&self, g: f64) -> f64 {
        ((self.range + self.width - g) / (2.0 * self.width)).clamp(0.0, 1.0)
    }
}

impl Curve for SmoothedDugdale {
    fn name(&self) -> &'static str {
        NAME
    }

    fn label(&self) -> &'static str {
        "smoothed Dugdale, range h0"
    }

    /// The range `h0`: the process zone `(8/3π)E*h0²/γ` is then within 8% of the Dugdale
    /// zone `(π/4)E*h0²/γ`, and the mesh rule and Tabor's μ read as the Dugdale law's.
    fn length(&self) -> f64 {
        self.range
    }

    fn meaning(&self) -> &'static str {
        "the tension σ0 > 0 of the smoothed Dugdale law (the range is γ/σ0)"
    }

    /// The scene's `adhesion.sigma0`, as the Dugdale law's.
    fn parameter(&self) -> (&'static str, f64) {
        (fields::ADHESION_SIGMA0, self.sigma0)
    }

    /// σ0 finite and > 0, and the law bound to a mesh.
    fn check_parameter(&self) -> Result<(), SolverError> {
        positive(fields::ADHESION_SIGMA0, self.sigma0)?;
        if !self.is_bound() {
            return Err(SolverError::Refused {
                field: fields::ADHESION_MODEL,
                reason: "the smoothed Dugdale law is not bound to a mesh: make it with \
                         SmoothedDugdale::on_mesh or bind it with AdhesionLaw::on_mesh",
            });
        }
        Ok(())
    }

    fn symbol(&self) -> &'static str {
        "h0"
    }

    #[inline]
    fn pressure(&self, gamma: f64, g: f64) -> f64 {
        let t = self.t(g);
        -(gamma / self.range) * t * t * t * (10.0 - 15.0 * t + 6.0 * t * t)
    }

    #[inline]
    fn stiffness(&self, gamma: f64, g: f64) -> f64 {
        let t = self.t(g);
        let u = t * (1.0 - t);
        (gamma / self.range) * 30.0 * u * u / (2.0 * self.width)
    }

    fn stiffens(&self) -> bool {
        false
    }

    /// σ0 = γ/h0, on `0 ≤ g ≤ h0 − s`.
    fn peak(&self, gamma: f64) -> f64 {
        gamma / self.range
    }

    /// Where the tension falls to [`REACH_FRACTION`] of the peak, just short of `h0 + s` (where
    /// it is 0): `S(t) = REACH_FRACTION` at `t ≈ 1e-3`, solved by Newton's method.
    fn reach(&self) -> f64 {
        let mut t = (REACH_FRACTION / 10.0).cbrt();
        for _ in 0..4 {
            let s = t * t * t * (10.0 - 15.0 * t + 6.0 * t * t);
            let ds = 30.0 * t * t * (1.0 - t) * (1.0 - t);
            t -= (s - REACH_FRACTION) / ds;
        }
        self.range + self.width - 2.0 * self.width * t
    }

    /// Its tension is σ0 up to the ramp and falls across it.
    fn falls_past_peak(&self) -> bool {
        true
    }

    /// First order: the ramp is bound to the mesh, so the law itself moves with Δx
    /// (observed 0.9–1.2 on the smooth sphere, docs/theory.md §3.7).
    fn convergence_order(&self) -> f64 {
        1.0
    }
}
