//! Linear viscoelastic half-spaces: a generalised Maxwell solid (a Prony series of the
//! plane-strain relaxation modulus) stepped in time by the exact exponential update of each arm
//! (docs/theory.md §3.10).
//!
//! With `E(t) = E0 + Σ E_k e^(−t/τ_k)` the surface pressure is `p(t) = ∫ E(t − s) ẇ(s) ds`, where
//! `w = K₁⁻¹ u` is the pressure that would hold the same displacement on a half-space of unit
//! modulus: the correspondence principle makes the relation local, element by element. Split
//! `p = E0 w + Σ s_k` with `ṡ_k + s_k/τ_k = E_k ẇ`. Over a step of length `Δt` with `w` linear
//! in time the arms update exactly:
//!
//! `s_k ← a_k s_k + E_k b_k (w⁺ − w)`, `a_k = e^(−Δt/τ_k)`, `b_k = (τ_k/Δt)(1 − a_k)`,
//!
//! so `p⁺ = E_Δt w⁺ + H` with the step modulus `E_Δt = E0 + Σ E_k b_k` and the history
//! `H = Σ (a_k s_k − E_k b_k w)`. Hence `u⁺ = C_Δt p⁺ − C_Δt H`: each time step is the elastic
//! adhesive contact of modulus `E_Δt` with the body's heights shifted by the history
//! displacement `−C_Δt H` (one product of the operator per step). The solver keeps the
//! operator of `E0` and runs the step in the pressure `p' = (E0/E_Δt) p`, under which the law's
//! tensions scale by the same factor and its ranges stay: exact for every law whose tension is
//! proportional to γ at a fixed range (the Dugdale and the smooth laws). The zero-range
//! criterion has no rate-consistent form and is refused with adhesion.

use ndarray::{Array2, Zip};
use tack_fields::{self as fields, field_name};

use crate::SolverError;

/// One arm of a [`Prony`] series: a spring of modulus `modulus` in series with a dashpot, its
/// relaxation time `time`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PronyArm {
    /// The arm's plane-strain modulus `E_k > 0`.
    pub modulus: f64,
    /// The arm's relaxation time `τ_k > 0`.
    pub time: f64,
}

/// A generalised Maxwell solid in plane-strain moduli: `E(t) = E0 + Σ E_k e^(−t/τ_k)`, `E0` the
/// relaxed modulus (a scene's `material.e_star`), `E0 + Σ E_k` the instantaneous one. One arm
/// is the standard linear solid.
///
/// ```
/// use tack_solver::Prony;
/// let sls = Prony::new(1.0, &[(9.0, 0.5)])?;
/// assert_eq!(sls.instantaneous(), 10.0);
/// assert!((sls.relaxation(0.5) - (1.0 + 9.0 / std::f64::consts::E)).abs() < 1e-12);
/// assert!(Prony::new(1.0, &[(-1.0, 0.5)]).is_err());
/// # Ok::<(), tack_solver::SolverError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Prony {
    relaxed: f64,
    arms: Vec<PronyArm>,
}

impl Prony {
    /// A solid of relaxed modulus `relaxed` and arms `(E_k, τ_k)`. Errors name
    /// `material.e_star` (not finite or ≤ 0) or `material.prony` (an arm's modulus or time not
    /// finite or ≤ 0, or no arm).
    pub fn new(relaxed: f64, arms: &[(f64, f64)]) -> Result<Self, SolverError> {
        crate::validate::positive(fields::MATERIAL_E_STAR, relaxed)?;
        if arms.is_empty() {
            return Err(SolverError::OutOfRange {
                field: fields::MATERIAL_PRONY,
                value: 0.0,
                allowed: "at least one arm [E_k, tau_k] (the count is given as the value)",
            });
        }
        let mut out = Vec::with_capacity(arms.len());
        for &(modulus, time) in arms {
            for v in [modulus, time] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(SolverError::OutOfRange {
                        field: fields::MATERIAL_PRONY,
                        value: v,
                        allowed: "arms [E_k, tau_k] of finite numbers > 0",
                    });
                }
            }
            out.push(PronyArm { modulus, time });
        }
        Ok(Self { relaxed, arms: out })
    }

    /// The relaxed modulus `E0 = E(∞)`.
    pub fn relaxed(&self) -> f64 {
        self.relaxed
    }

    /// The instantaneous modulus `E(0) = E0 + Σ E_k`.
    pub fn instantaneous(&self) -> f64 {
        self.relaxed + self.arms.iter().map(|a| a.modulus).sum::<f64>()
    }

    /// The arms.
    pub fn arms(&self) -> &[PronyArm] {
        &self.arms
    }

    /// The relaxation modulus `E(t)` at `t ≥ 0`.
    pub fn relaxation(&self, t: f64) -> f64 {
        self.relaxed
            + self
                .arms
                .iter()
                .map(|a| a.modulus * (-t / a.time).exp())
                .sum::<f64>()
    }

    /// The modulus of a time step of length `dt ≥ 0`: `E0 + Σ E_k b_k`, `b_k = (τ_k/Δt)(1 −
    /// e^(−Δt/τ_k))`, from the instantaneous modulus at `dt = 0` to `E0` as `dt → ∞`.
    pub fn step_modulus(&self, dt: f64) -> f64 {
        self.relaxed
            + self
                .arms
                .iter()
                .map(|a| a.modulus * arm_factors(dt, a.time).1)
                .sum::<f64>()
    }
}

/// `(a, b)` of an arm of time `tau` over a step `dt`: `a = e^(−Δt/τ)`, `b = (τ/Δt)(1 − a)`
/// (its limit 1 at `dt = 0`, by `−expm1` for small steps).
fn arm_factors(dt: f64, tau: f64) -> (f64, f64) {
    let x = dt / tau;
    let a = (-x).exp();
    let b = if x < 1e-12 { 1.0 } else { -(-x).exp_m1() / x };
    (a, b)
}

/// The rates of a path in time: the approach speeds of the loading and the retraction, and
/// a hold at the deepest approach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rates {
    /// Approach rate while loading (> 0): a load step `Δd` lasts `Δd/speed`.
    pub speed: f64,
    /// Approach rate while retracting (> 0).
    pub unload_speed: f64,
    /// Time held at the deepest approach before the retraction (≥ 0).
    pub dwell: f64,
    /// Steps the hold is cut into (≥ 1 when `dwell > 0`).
    pub dwell_steps: usize,
}

impl Rates {
    /// Checks every rate: errors name `protocol.speed`, `protocol.unload_speed`,
    /// `protocol.dwell` or `protocol.dwell_steps`.
    pub fn validate(&self) -> Result<(), SolverError> {
        crate::validate::positive(fields::PROTOCOL_SPEED, self.speed)?;
        crate::validate::positive(fields::PROTOCOL_UNLOAD_SPEED, self.unload_speed)?;
        crate::validate::non_negative(fields::PROTOCOL_DWELL, self.dwell)?;
        if self.dwell > 0.0 {
            crate::validate::at_least_one(fields::PROTOCOL_DWELL_STEPS, self.dwell_steps)?;
        }
        Ok(())
    }
}

/// The state of a viscoelastic solver between steps: the material and rates, the body's own
/// heights, the arms' stresses `s_k`, the unit-modulus pressure `w`, the clock and the factor
/// `E0/E_Δt` the law's tensions carry now.
pub(crate) struct Viscous {
    pub(crate) prony: Prony,
    pub(crate) rates: Rates,
    /// The body's heights without the history displacement.
    pub(crate) heights: Array2<f64>,
    arms: Vec<Array2<f64>>,
    w: Array2<f64>,
    /// Scratch: the history `H`, then the displacement it makes.
    pub(crate) history: Array2<f64>,
    pub(crate) shift: Array2<f64>,
    pub(crate) time: f64,
    /// `E0/E_Δt` of the law's tensions in the solver now (1 before the first step).
    pub(crate) scale: f64,
}

impl Viscous {
    pub(crate) fn new(prony: Prony, rates: Rates, heights: Array2<f64>) -> Self {
        let shape = heights.dim();
        let arms = vec![Array2::zeros(shape); prony.arms.len()];
        Self {
            prony,
            rates,
            heights,
            arms,
            w: Array2::zeros(shape),
            history: Array2::zeros(shape),
            shift: Array2::zeros(shape),
            time: 0.0,
            scale: 1.0,
        }
    }

    /// The history `H = Σ (a_k s_k − E_k b_k w)` of a step `dt` into `self.history`; returns
    /// the step modulus `E_Δt`.
    pub(crate) fn history_for(&mut self, dt: f64) -> f64 {
        self.history.fill(0.0);
        for (arm, s) in self.prony.arms.iter().zip(&self.arms) {
            let (a, b) = arm_factors(dt, arm.time);
            let eb = arm.modulus * b;
            Zip::from(&mut self.history)
                .and(s)
                .and(&self.w)
                .for_each(|h, &s, &w| *h += a * s - eb * w);
        }
        self.prony.step_modulus(dt)
    }

    /// After a step `dt` that reached the (physical) pressure `p` with step modulus `e_step`
    /// and the history of [`Viscous::history_for`]: `w⁺ = (p − H)/E_Δt`, each arm's exact
    /// update, the clock.
    pub(crate) fn advance(&mut self, dt: f64, e_step: f64, p: &Array2<f64>) {
        // `history` becomes `w⁺ − w` here, then `w⁺` is stored.
        Zip::from(&mut self.history)
            .and(p)
            .and(&self.w)
            .for_each(|h, &p, &w| *h = (p - *h) / e_step - w);
        for (arm, s) in self.prony.arms.iter().zip(self.arms.iter_mut()) {
            let (a, b) = arm_factors(dt, arm.time);
            let eb = arm.modulus * b;
            Zip::from(s)
                .and(&self.history)
                .for_each(|s, &dw| *s = a * *s + eb * dw);
        }
        self.w += &self.history;
        self.time += dt;
    }

    /// The length of a step from approach `from` to `to`: `|Δd|` over the loading or the
    /// retraction speed; the first step of a path (`from = None`) is instantaneous.
    pub(crate) fn step_time(&self, from: Option<f64>, to: f64) -> f64 {
        match from {
            None => 0.0,
            Some(f) if to >= f => (to - f) / self.rates.speed,
            Some(f) => (f - to) / self.rates.unload_speed,
        }
    }
}

impl crate::AdhesiveSolver {
    /// Makes the half-space a viscoelastic solid of relaxation modulus `prony` stepped along
    /// paths in time at `rates` ([`Prony`], module docs): each approach step lasts `|Δd|` over
    /// the loading or the retraction speed, the first step of a path is reached instantly, and
    /// [`crate::ApproachPath`]s hold `rates.dwell` at their deepest approach. Records carry the
    /// time ([`crate::StepRecord::time`]).
    ///
    /// Refused (errors name the field): a solver that has taken a step already (the solid
    /// starts at rest), an operator that is not a half-space or whose modulus is not the
    /// relaxed `E0`, the zero-range criterion with adhesion (it has no rate-consistent form:
    /// use a finite-range law), invalid rates.
    pub fn set_viscoelastic(&mut self, prony: Prony, rates: Rates) -> Result<(), SolverError> {
        rates.validate()?;
        if self.last_approach.is_some() {
            return Err(SolverError::Refused {
                field: fields::MATERIAL_PRONY,
                reason: "a viscoelastic solid starts at rest: set it before the first step",
            });
        }
        if !self.base.op.is_half_space() {
            return Err(SolverError::Refused {
                field: fields::MATERIAL_PRONY,
                reason: concat!(
                    "viscoelastic solids are half-spaces (",
                    field_name!(body.kind),
                    " = \"half_space\"); a film is elastic only"
                ),
            });
        }
        let e_star = self.base.op.e_star();
        if (e_star - prony.relaxed()).abs() > 1e-12 * e_star {
            return Err(SolverError::OutOfRange {
                field: fields::MATERIAL_E_STAR,
                value: prony.relaxed(),
                allowed: "the operator's modulus: the relaxed modulus E0 of the Prony series",
            });
        }
        if matches!(self.law(), crate::AdhesionLaw::JkrLimit(_)) && self.sigma_c > 0.0 {
            return Err(SolverError::Refused {
                field: fields::ADHESION_MODEL,
                reason: concat!(
                    "the zero-range criterion has no rate-consistent form: a viscoelastic solid (",
                    field_name!(material.prony),
                    ") with adhesion needs a finite-range law: any ",
                    field_name!(adhesion.model),
                    " but \"jkr_limit\""
                ),
            });
        }
        let heights = self.base.heights().clone();
        self.visco = Some(Viscous::new(prony, rates, heights));
        Ok(())
    }

    /// The viscoelastic solid and its rates (`None`: elastic).
    pub fn viscoelastic(&self) -> Option<(&Prony, &Rates)> {
        self.visco.as_ref().map(|v| (&v.prony, &v.rates))
    }

    /// Holds the last approach for `duration` (a viscoelastic solid relaxes; an elastic one
    /// gives the same state again). Before any step there is nothing to hold.
    pub fn hold(&mut self, duration: f64) -> Result<crate::StepRecord, SolverError> {
        crate::validate::non_negative(fields::PROTOCOL_DWELL, duration)?;
        let Some(d) = self.last_approach else {
            return Err(SolverError::Refused {
                field: fields::PROTOCOL_DWELL,
                reason: "a hold needs an approach to hold: take a step first",
            });
        };
        self.step_in_time(d, duration)
    }

    /// One time step of length `dt` to approach `d` (validated): the elastic step of modulus
    /// `E_Δt` on the heights shifted by the history displacement, run in the scaled pressure
    /// `p' = (E0/E_Δt) p` (module docs), then the arms' update.
    pub(crate) fn step_in_time(
        &mut self,
        d: f64,
        dt: f64,
    ) -> Result<crate::StepRecord, SolverError> {
        let Some(mut v) = self.visco.take() else {
            return self.step_elastic(d);
        };
        let e_step = v.history_for(dt);
        let c = v.prony.relaxed() / e_step;
        // The history displacement −C_Δt H = −c·C_E0 H, added to the body's heights.
        self.base.op.apply(v.history.view(), v.shift.view_mut());
        let mut heights = v.heights.clone();
        Zip::from(&mut heights)
            .and(&v.shift)
            .for_each(|f, &u| *f -= c * u);
        let grid = *self.base.grid();
        match tack_geometry::Surface::new(grid, heights) {
            Ok(surface) => self.base.set_surface(surface),
            Err(_) => {
                self.visco = Some(v);
                return Err(SolverError::OutOfRange {
                    field: fields::MATERIAL_PRONY,
                    value: f64::NAN,
                    allowed: "arms whose history stays finite (the shifted heights were not)",
                });
            }
        }
        if c != v.scale {
            self.scale_law(c / v.scale);
            v.scale = c;
        }
        self.scale_pressure(c);
        let step = self.step_elastic(d);
        self.scale_pressure(1.0 / c);
        let mut rec = match step {
            Ok(rec) => rec,
            Err(e) => {
                self.visco = Some(v);
                return Err(e);
            }
        };
        v.advance(dt, e_step, &self.base.pressure);
        rec.force /= c;
        rec.mean_pressure /= c;
        rec.time = Some(v.time);
        self.visco = Some(v);
        Ok(rec)
    }

    /// Multiplies the law's tensions (σ_c, σ0, a smooth law's γ at its range; a γ map's) by
    /// `ratio`: the law of the scaled pressure `p'`.
    fn scale_law(&mut self, ratio: f64) {
        self.sigma_c *= ratio;
        self.tension.mapv_inplace(|t| t * ratio);
        if let Some(c) = self.cohesive.as_mut() {
            c.sigma0 *= ratio;
        }
        if let Some(s) = self.smooth.as_mut() {
            s.traction.gamma *= ratio;
        }
    }

    /// Multiplies the pressure, its `K p` and the secant predictor's previous pressure by
    /// `factor` (physical ↔ scaled pressure).
    fn scale_pressure(&mut self, factor: f64) {
        self.base.pressure.mapv_inplace(|p| p * factor);
        self.base.work.disp.mapv_inplace(|u| u * factor);
        if let Some((p0, _)) = self.history.as_mut() {
            p0.mapv_inplace(|p| p * factor);
        }
    }
}
