//! The adhesion laws an [`AdhesiveSolver`](crate::AdhesiveSolver) can run: one type per law
//! (its own file here) behind one interface, [`Law`], and the smooth laws' traction–gap
//! curves behind [`Curve`]; [`AdhesionLaw`] is the set a scene, the solver and the results
//! name: the built-in laws and smooth laws of the caller's own.
//!
//! A law states its parameter and checks, its range, reach and peak tension, the mesh rule it
//! needs and the warning when a mesh breaks it, its summary entries, the per-step column it
//! adds to a result's curve ([`StepColumn`]), its one-line description, and which of the
//! solver's three algorithms runs it ([`Family`]): the zero-range criterion (`criterion.rs`),
//! the Dugdale cohesive zone (`dugdale.rs`, with the [`Cohesive`] state kept here) or a smooth
//! curve (`smooth.rs`). A smooth law of the caller's own is one type implementing [`Curve`]
//! (every [`Law`] fact follows from it), given to [`AdhesionLaw::custom`] (checked in
//! `custom.rs`). A new built-in law is that type in its own module and one line of
//! `built_in_laws!` (its variant, `From`, and registry entry follow), its name among the scene
//! field's choices (`tack-fields`, which the docs are made from; a test checks that the two
//! agree), its Python class, its docs and its tests; the solver's loops, the scene's reading
//! and the messages that list laws need no edit (a smooth built-in may also join `on_curve!`,
//! which inlines its curve in the hot loops).

mod custom;
mod dugdale;
mod exponential;
mod jkr_limit;
mod lennard_jones;
mod smoothed_dugdale;

use ndarray::Array2;
use tack_fields as fields;
use tack_geometry::Surface;

use crate::SolverError;

pub use custom::CustomCurve;
pub use dugdale::Dugdale;
pub use exponential::Exponential;
pub use jkr_limit::JkrLimit;
pub use lennard_jones::LennardJones;
pub use smoothed_dugdale::{LEAST_SMOOTHING, SMOOTHING_OPENINGS, SmoothedDugdale};

/// Least length of a Dugdale cohesive zone, in elements, below which a result is flagged: the
/// zone's tension is then carried by a ring of elements too thin to shape it.
pub const MIN_COHESIVE_ZONE_ELEMENTS: f64 = 2.0;

/// Least width of a smooth law's process zone, in elements, below which a result is flagged:
/// an element's own stiffness `E*/(κ₀Δx)` then no longer holds the law's steepest softening,
/// the front advances element by element and the forces depend on the mesh.
pub const MIN_PROCESS_ZONE_ELEMENTS: f64 = 1.0;

/// A smooth law's reach ([`Law::reach`]) is where its tension falls to this fraction of the
/// peak: what a crop leaves out is a tension below it.
pub const REACH_FRACTION: f64 = 1e-8;

/// A path approaching under a smooth law starts where the law's tension falls to this fraction
/// of the peak ([`AdhesionLaw::approach_reach`]), not at its reach: beyond, the body barely
/// moves (a tension of 1e-4 of the peak on the nearest element) and the steps out there took
/// most of a run under the Lennard-Jones law, whose g⁻³ tail reaches 637 ε (at 1e-4: 29 ε; the
/// exponential law's 18.4 ρ, at 1e-4: 9.2 ρ).
pub const APPROACH_FRACTION: f64 = 1e-4;

/// A smooth law changes its forces over its length ρ: where the solution follows the law
/// alone (nothing touches the wall) a path need not step finer than ρ over this. The default
/// path loads from out of reach in such steps (`tack::pull_off_path::load_plan`), and a
/// plain retraction with a coarse step takes them once every gap is past the law's peak and
/// the tension falls ([`AdhesionLaw::tail_step`]).
pub const STEPS_PER_LENGTH: f64 = 50.0;

/// The smallest range allowed, relative to the largest height: below it the gap test
/// `g < h0` is decided by the round-off of `f − d + u`.
pub const RANGE_ROUND_OFF: f64 = 1e-12;

/// The name of the per-step column of the laws with a zone ahead of the contact (the Dugdale
/// law's cohesive zone, a smooth law's process zone): `/curve/n_cohesive` in results.
pub const ZONE_COLUMN: &str = "n_cohesive";

/// Under a smooth law, elements out of contact count as the process zone (the law's
/// [`ZONE_COLUMN`]) when their tension exceeds this fraction of their peak tension.
pub(crate) const ZONE_FRACTION: f64 = 0.01;

/// A per-step column a law adds to a path's curve: its name in results (`/curve/<name>`) and
/// what it counts, stored beside it; its values are each step's
/// [`StepRecord::n_cohesive`](crate::StepRecord::n_cohesive).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StepColumn {
    /// The column's name.
    pub name: &'static str,
    /// What it counts, in a sentence.
    pub meaning: String,
}

/// Which of the solver's algorithms runs a law.
#[derive(Debug, Clone, Copy)]
pub enum Family<'a> {
    /// The zero-range detachment criterion of constant κ (`criterion.rs`).
    Criterion {
        /// The Pohrt–Popov constant κ.
        kappa: f64,
    },
    /// A Dugdale cohesive zone of tension σ0 (`dugdale.rs`).
    Cohesive {
        /// The cohesive tension σ0.
        sigma0: f64,
    },
    /// A smooth traction–gap curve with a hard wall (`smooth.rs`).
    Smooth(&'a dyn Curve),
}

/// What an adhesion law states about itself; every method takes the work of adhesion `gamma`
/// (and the modulus `e_star` and element `dx` where they enter) because a law is set by its
/// own parameter and scaled by γ.
pub trait Law: std::fmt::Debug + Send + Sync {
    /// The name in scene files and results (`adhesion.model`).
    fn name(&self) -> &'static str;
    /// The scene field of the law's parameter and its value (`solver.kappa`,
    /// `adhesion.sigma0` or `adhesion.range`).
    fn parameter(&self) -> (&'static str, f64);
    /// What the parameter is and its allowed range, for a message that asks for it.
    fn meaning(&self) -> &'static str;
    /// The algorithm that runs the law.
    fn family(&self) -> Family<'_>;
    /// The law's length: the Dugdale range `γ/σ0`, ρ, ε; `None` for the zero-range criterion.
    fn range(&self, gamma: f64) -> Option<f64>;
    /// The gap beyond which the law's tension is negligible, for cropping and for where a
    /// path starts (a smooth law's is where its tension falls to [`REACH_FRACTION`] of the
    /// peak); `None` for the zero-range criterion.
    fn reach(&self, gamma: f64) -> Option<f64>;
    /// The greatest tension an element of size `dx` carries.
    fn peak_tension(&self, gamma: f64, e_star: f64, dx: f64) -> f64;
    /// The greatest tension of an element of work of adhesion `gamma` when the law was set for
    /// the `reference` work (a γ map, [`crate::AdhesiveSolver::set_gamma_map`]).
    fn element_tension(&self, gamma: f64, reference: f64, e_star: f64, dx: f64) -> f64;
    /// The length the mesh must resolve (`None`: the contact's own size, checked with the
    /// body).
    fn zone_length(&self, e_star: f64, gamma: f64) -> Option<f64>;
    /// The least number of elements across [`Law::zone_length`] below which a result is
    /// flagged.
    fn min_zone_elements(&self) -> f64;
    /// The order in Δx of the pull-off's mesh error on a smooth body, which Richardson
    /// extrapolation assumes ([`crate::richardson`]): 1 where the front moves by whole elements
    /// (the criterion, the Dugdale law), 2 where every element carries its own gap's traction
    /// (the smooth laws).
    fn convergence_order(&self) -> f64;
    /// The warning of a mesh of element `dx` that does not resolve the law's zone, naming the
    /// fields that mend it; `None` when it does.
    fn mesh_warning(&self, e_star: f64, gamma: f64, dx: f64) -> Option<String>;
    /// The law's own entries of a result's summary.
    fn summary_entries(&self, gamma: f64, e_star: f64, dx: f64) -> Vec<(&'static str, f64)>;
    /// The per-step column the law adds to a result's curve (`None`: none, the zero-range
    /// criterion).
    fn step_column(&self) -> Option<StepColumn>;
    /// One line naming the law and its parameters for a run's report.
    fn describe(&self, gamma: f64, e_star: f64, dx: f64) -> String;
    /// Checks the law's own inputs for work of adhesion `gamma` on `surface`; errors name the
    /// field.
    fn check(&self, gamma: f64, surface: &Surface) -> Result<(), SolverError>;
}

/// A smooth law: every element carries the pressure of its own gap, `p(g)` for `g > 0`, with a
/// hard wall at `g = 0`. Implementing it makes the type a [`Law`]: its range, reach, peak
/// tension, process zone, mesh rule, summary and checks follow from the curve.
///
/// What the solver assumes of a curve (and [`AdhesionLaw::custom`] checks): it is asked only at
/// gaps `g ≥ 0`, however far beyond the reach, and must be finite at each; the pressure is
/// continuous, the stiffness its derivative; the pressure, stiffness and peak scale as `γ` at
/// one length (`p(γ, g) = γ·p(1, g)`); the work `−∫₀^∞ p dg` is `γ`; [`Curve::length`] is the
/// curve's smallest length scale. Richardson extrapolation takes every curve as second order
/// in Δx ([`Law::convergence_order`]).
pub trait Curve: std::fmt::Debug + Send + Sync {
    /// The name in results (`adhesion_model`) and, for the built-in laws, in scene files.
    fn name(&self) -> &'static str;
    /// The name in reports, with the symbol of its range, e.g. `exponential, range rho`.
    fn label(&self) -> &'static str;
    /// The law's length ρ (ε): the scene's `adhesion.range` for the built-in laws; the length
    /// of Tabor's μ and of the process zone.
    fn length(&self) -> f64;
    /// What the length is, for a message that asks for it (e.g. `the range ρ > 0 of …`).
    fn meaning(&self) -> &'static str;
    /// The length's symbol in messages: `ρ` unless the curve says otherwise (`ε` of the
    /// Lennard-Jones law).
    fn symbol(&self) -> &'static str {
        "ρ"
    }
    /// The pressure at gap `g ≥ 0` for work of adhesion `gamma` (negative: tension).
    fn pressure(&self, gamma: f64, g: f64) -> f64;
    /// `dp/dg` at gap `g ≥ 0`: positive where the law softens (destabilises).
    fn stiffness(&self, gamma: f64, g: f64) -> f64;
    /// [`Curve::pressure`] and [`Curve::stiffness`] at one gap, for a curve that shares work
    /// between them (the same bits as the two calls).
    #[inline]
    fn pressure_and_stiffness(&self, gamma: f64, g: f64) -> (f64, f64) {
        (self.pressure(gamma, g), self.stiffness(gamma, g))
    }
    /// Whether the law stiffens anywhere (`dp/dg < 0`: the Lennard-Jones law next to its
    /// wall), where the landing solves the stiff elements with the contact set.
    fn stiffens(&self) -> bool;
    /// The greatest tension of the law.
    fn peak(&self, gamma: f64) -> f64;
    /// The gap where the tension falls to [`REACH_FRACTION`] of the peak (a custom law's may
    /// leave up to 1e-6 of it): the solver crops the law beyond it.
    fn reach(&self) -> f64;
    /// Whether the tension only falls as the gap opens past the law's greatest tension
    /// ([`AdhesionLaw::peak_gap`]), to every gap: then a step's window is chosen by evaluating
    /// the law only short of the gap where its tension falls below the choice's cut, not on
    /// every element (docs/theory.md §3.9, "Steps on the law's window"). Nothing is promised
    /// unless a curve says so; a custom curve that does is checked on its samples past the
    /// peak and beyond its reach. The built-in laws do.
    fn falls_past_peak(&self) -> bool {
        false
    }
    /// The order in Δx of the pull-off's mesh error that Richardson extrapolation assumes
    /// ([`Law::convergence_order`]): 2 for a curve of its own lengths, 1 for a curve bound to
    /// the mesh ([`SmoothedDugdale`]).
    fn convergence_order(&self) -> f64 {
        2.0
    }
    /// The scene field of the law's parameter and its value ([`Law::parameter`]):
    /// `adhesion.range` and the length unless the curve says otherwise (the smoothed Dugdale
    /// law's `adhesion.sigma0`).
    fn parameter(&self) -> (&'static str, f64) {
        (fields::ADHESION_RANGE, self.length())
    }
    /// Checks of the curve's own parameter that [`Law::check`] makes first (none unless the
    /// curve has them).
    fn check_parameter(&self) -> Result<(), SolverError> {
        Ok(())
    }
}

impl<C: Curve> Law for C {
    fn name(&self) -> &'static str {
        Curve::name(self)
    }

    fn parameter(&self) -> (&'static str, f64) {
        Curve::parameter(self)
    }

    fn meaning(&self) -> &'static str {
        Curve::meaning(self)
    }

    fn family(&self) -> Family<'_> {
        Family::Smooth(self)
    }

    fn range(&self, _gamma: f64) -> Option<f64> {
        Some(self.length())
    }

    fn reach(&self, _gamma: f64) -> Option<f64> {
        Some(Curve::reach(self))
    }

    fn peak_tension(&self, gamma: f64, _e_star: f64, _dx: f64) -> f64 {
        self.peak(gamma)
    }

    /// A smooth law keeps its range and scales its peak by `γ/γ_ref`.
    fn element_tension(&self, gamma: f64, reference: f64, _e_star: f64, _dx: f64) -> f64 {
        self.peak(reference) * (gamma / reference)
    }

    /// The process zone `(8/3π)E*ℓ²/γ` (ℓ the range: the length over which the exponential
    /// law's tension acts ahead of a crack; other smooth laws' is of the same order).
    fn zone_length(&self, e_star: f64, gamma: f64) -> Option<f64> {
        let l = self.length();
        Some(8.0 / (3.0 * std::f64::consts::PI) * e_star * l * l / gamma)
    }

    fn min_zone_elements(&self) -> f64 {
        MIN_PROCESS_ZONE_ELEMENTS
    }

    /// Second order: the force–approach curves of the exponential, Lennard-Jones and Morse laws
    /// converge at 2.0–3.3 against their ring solutions (`tests/smooth.rs`,
    /// `tests/custom_law.rs`); their pull-offs less regularly (the exponential law's 1.6 then a
    /// sign change, Lennard-Jones 2.4, the peers' case 3.8 then 3.3), since a pull-off is one point of
    /// the curve. Every smooth curve, a custom one too, is taken as second order unless it
    /// says otherwise ([`Curve::convergence_order`]).
    fn convergence_order(&self) -> f64 {
        Curve::convergence_order(self)
    }

    fn mesh_warning(&self, e_star: f64, gamma: f64, dx: f64) -> Option<String> {
        let zone = self.zone_length(e_star, gamma)?;
        let shown = under_resolved(zone / dx, self.min_zone_elements())?;
        let strength = format!("the peak tension {}", fields::rounded(self.peak(gamma)));
        let symbol = Curve::symbol(self);
        // The law's own field: raise a length, lower a tension (σ0 sets the range γ/σ0).
        let mend = match Curve::parameter(self).0 {
            fields::ADHESION_SIGMA0 => format!("lower {}", fields::ADHESION_SIGMA0),
            field => format!("raise {field}"),
        };
        Some(format!(
            "under-resolved process zone: its width (8/3π)E*{symbol}²/γ = {} spans {shown} \
             elements (at least {} needed); the front then moves element by element and the \
             forces depend on the mesh (refine {} or {mend}){}",
            fields::rounded(zone),
            self.min_zone_elements(),
            fields::GRID_DX,
            glued(zone / dx, &strength),
        ))
    }

    fn summary_entries(&self, gamma: f64, e_star: f64, dx: f64) -> Vec<(&'static str, f64)> {
        vec![
            ("range", self.length()),
            ("peak_tension", self.peak(gamma)),
            (
                "process_zone_elements",
                self.zone_length(e_star, gamma).unwrap_or(0.0) / dx,
            ),
        ]
    }

    /// The process zone's elements: out of contact with tension beyond
    /// 1% of their peak (`ZONE_FRACTION`).
    fn step_column(&self) -> Option<StepColumn> {
        Some(StepColumn {
            name: ZONE_COLUMN,
            meaning: format!(
                "elements of the process zone: out of contact, with a tension beyond {}% of the \
                 law's peak",
                ZONE_FRACTION * 100.0
            ),
        })
    }

    fn describe(&self, gamma: f64, _e_star: f64, _dx: f64) -> String {
        format!(
            "{} = {}, peak tension = {}",
            self.label(),
            fields::rounded(self.length()),
            fields::rounded(self.peak(gamma))
        )
    }

    /// The curve's own checks ([`Curve::check_parameter`]), γ > 0 and a range ρ (ε) > 0
    /// above the round-off of the heights.
    fn check(&self, gamma: f64, surface: &Surface) -> Result<(), SolverError> {
        self.check_parameter()?;
        let range = self.length();
        crate::validate::positive(fields::ADHESION_RANGE, range)?;
        if gamma <= 0.0 || !gamma.is_finite() {
            return Err(SolverError::OutOfRange {
                field: fields::MATERIAL_GAMMA,
                value: gamma,
                allowed: "a finite number > 0 under a smooth law",
            });
        }
        if range <= RANGE_ROUND_OFF * largest_height(surface) {
            return Err(SolverError::OutOfRange {
                field: fields::ADHESION_RANGE,
                value: range,
                allowed: "above 1e-12 of the largest height (below it the law acts on round-off)",
            });
        }
        Ok(())
    }
}

/// The elements across a zone for a warning, when fewer than `least`, as
/// [`fields::elements`] writes them (the run's report too).
fn under_resolved(elements: f64, least: f64) -> Option<String> {
    (elements < least).then(|| fields::elements(elements))
}

/// Below this many elements across a finite-range law's zone an element holds the law's whole
/// strength whatever its neighbours do: the body glues, and the pull-off grows without bound as
/// the zone shrinks on a fixed mesh (docs/theory.md §3.9). The warning then says so and names
/// the zero-range criterion, whose strength is set by the mesh.
pub(crate) const GLUED_ELEMENTS: f64 = 0.3;

/// The zero-range criterion as a message names it: `the zero-range criterion (adhesion.model
/// = "jkr_limit")`.
pub(crate) fn zero_range_hint() -> String {
    format!(
        "the zero-range criterion ({} = \"{}\")",
        fields::ADHESION_MODEL,
        jkr_limit::NAME
    )
}

/// The clause a mesh warning adds below [`GLUED_ELEMENTS`] (empty above); `strength` names the
/// law's greatest tension.
fn glued(elements: f64, strength: &str) -> String {
    if elements < GLUED_ELEMENTS {
        format!(
            "; below {GLUED_ELEMENTS} elements across it each one holds up to {strength} \
             whatever its neighbours do, so the body glues and the pull-off grows without bound \
             as the zone shrinks on this mesh: for the JKR limit use {}",
            zero_range_hint(),
        )
    } else {
        String::new()
    }
}

/// The largest `|f|` of the heights: the scale of their round-off.
fn largest_height(surface: &Surface) -> f64 {
    surface
        .heights()
        .iter()
        .fold(0.0f64, |m, &f| m.max(f.abs()))
}

/// Declares the built-in laws, one line each (`Variant(Type) = module, |parameter| value;`):
/// the variants of [`AdhesionLaw`] beside `Custom`, their `From`, [`AdhesionLaw::law`] and the
/// registry `MODELS` of scene names (`module::NAME`) and how each law is made from its
/// parameter. A new built-in law is its type (its own module) and its line here.
macro_rules! built_in_laws {
    (
        $(#[$meta:meta])*
        pub enum $name:ident {
            $( $(#[$doc:meta])* $variant:ident($ty:ident) = $module:ident, |$v:ident| $make:expr; )*
        }
    ) => {
        $(#[$meta])*
        pub enum $name {
            $( $(#[$doc])* $variant($ty), )*
            /// A smooth law of the caller's own ([`AdhesionLaw::custom`]).
            Custom(CustomCurve),
        }

        $(
            impl From<$ty> for $name {
                fn from(l: $ty) -> Self {
                    $name::$variant(l)
                }
            }
        )*

        /// Each built-in law: its scene name and how it is made from its parameter (the order
        /// of the docs).
        const MODELS: &[(&str, Make)] = &[ $( ($module::NAME, |$v| $make.into()), )* ];

        impl $name {
            /// The law's interface.
            pub fn law(&self) -> &(dyn Law + 'static) {
                match self {
                    $( $name::$variant(l) => l, )*
                    $name::Custom(c) => c.0.as_ref(),
                }
            }
        }
    };
}

/// How a law is made from its parameter.
type Make = fn(f64) -> AdhesionLaw;

built_in_laws! {
    /// The adhesion law of an [`AdhesiveSolver`](crate::AdhesiveSolver): one of the law types.
    /// It dereferences to its law's [`Law`] interface (`law.name()`, `law.reach(γ)`, …); build
    /// one from a law type with `From` (`AdhesionLaw::from(Exponential { range })`), by its
    /// scene name with [`AdhesionLaw::from_model`], or from a curve of your own with
    /// [`AdhesionLaw::custom`]. Clones are cheap (a custom curve is shared).
    #[derive(Debug, Clone, PartialEq)]
    pub enum AdhesionLaw {
        /// The zero-range (JKR) limit, the paper's model.
        JkrLimit(JkrLimit) = jkr_limit, |kappa| JkrLimit { kappa };
        /// A Dugdale cohesive zone.
        Dugdale(Dugdale) = dugdale, |sigma0| Dugdale { sigma0 };
        /// The exponential law `p = −(γ/ρ) e^(−g/ρ)`.
        Exponential(Exponential) = exponential, |range| Exponential { range };
        /// The Lennard-Jones 9–3 law.
        LennardJones(LennardJones) = lennard_jones, |range| LennardJones { range };
        /// The Dugdale law's step smoothed over about an element's opening (bound to a mesh
        /// by [`AdhesionLaw::on_mesh`]).
        SmoothedDugdale(SmoothedDugdale) = smoothed_dugdale, |sigma0| SmoothedDugdale::unbound(sigma0);
    }
}

impl AdhesionLaw {
    /// A smooth law of the caller's own: any type implementing [`Curve`], run by the same
    /// solver as the built-in smooth laws (through a dynamic call, where the built-ins are
    /// inlined). The curve is checked once, at γ = 1 on a few thousand graded gaps up to its
    /// reach: a name of its own (lowercase, digits, `_`; not a built-in's), a finite positive
    /// length, peak and reach, a stiffness that is the pressure's derivative (1e-4), negative
    /// only where [`Curve::stiffens`] says so, the work `−∫p dg = γ` and the greatest tension
    /// [`Curve::peak`] (both within 1e-3), and a tension at the reach below 1e-6 of the peak;
    /// the error ([`SolverError::Curve`]) names the method that fails. The law is shared:
    /// clones are one curve.
    pub fn custom<C: Curve + 'static>(curve: C) -> Result<AdhesionLaw, SolverError> {
        Ok(AdhesionLaw::Custom(CustomCurve::new(curve)?))
    }

    /// The law bound to a run of work of adhesion `gamma` on elements `dx` over a modulus
    /// `e_star`: an unbound smoothed Dugdale law ([`SmoothedDugdale::unbound`], as
    /// [`AdhesionLaw::from_model`] makes it) gets its range and ramp
    /// ([`SmoothedDugdale::on_mesh`]); every other law, and a bound one, is returned as it is.
    /// Invalid values leave the law unbound, for [`Law::check`] to name.
    pub fn on_mesh(self, gamma: f64, e_star: f64, dx: f64) -> AdhesionLaw {
        match self {
            AdhesionLaw::SmoothedDugdale(l) if !l.is_bound() => {
                SmoothedDugdale::on_mesh(l.sigma0, gamma, e_star, dx)
                    .map_or(self, AdhesionLaw::SmoothedDugdale)
            }
            other => other,
        }
    }

    /// The scene names of every law, in the order of the docs.
    pub fn models() -> impl Iterator<Item = &'static str> {
        MODELS.iter().map(|m| m.0)
    }

    /// The law a scene names by `model` with its parameter `value` (κ, σ0 or the range;
    /// [`Law::parameter`] says which); `None` for a name no law has. The value is checked by
    /// [`Law::check`], not here.
    pub fn from_model(model: &str, value: f64) -> Option<AdhesionLaw> {
        MODELS
            .iter()
            .find(|m| m.0 == model)
            .map(|(_, make)| make(value))
    }

    /// How far ahead of the first touch an approach starts: the Dugdale law's range γ/σ0 (its
    /// tension is σ0 up to it); a smooth law's gap where its tension falls to
    /// [`APPROACH_FRACTION`] of the peak for work `gamma` (scanned down from its reach in
    /// steps of 1%: the outermost such gap); `None` for the zero-range criterion.
    pub fn approach_reach(&self, gamma: f64) -> Option<f64> {
        let Some(curve) = self.curve() else {
            return self.reach(gamma);
        };
        let cut = APPROACH_FRACTION * curve.peak(gamma);
        let mut g = curve.reach();
        for _ in 0..2_000 {
            if curve.pressure(gamma, g).abs() >= cut {
                break;
            }
            g *= 0.99;
        }
        Some(g)
    }

    /// The retraction step of a smooth law past its pull-off, once every gap is past its peak
    /// ([`AdhesionLaw::peak_gap`]) and the tension falls: its length ρ over [`STEPS_PER_LENGTH`], at least `fine` and at
    /// most `coarse`; `None` for the criterion and the Dugdale law (whose cohesive zone moves
    /// by elements: their fine step throughout).
    ///
    /// ```
    /// use tack_solver::{AdhesionLaw, Dugdale, Exponential};
    /// let law = AdhesionLaw::from(Exponential { range: 0.1 });
    /// assert_eq!(law.tail_step(1e-4, 1e-3), Some(1e-3));
    /// assert_eq!(law.tail_step(1e-4, 1.0), Some(0.1 / 50.0));
    /// assert_eq!(law.tail_step(0.01, 1.0), Some(0.01));
    /// assert_eq!(AdhesionLaw::from(Dugdale { sigma0: 1.0 }).tail_step(1e-4, 1e-3), None);
    /// ```
    pub fn tail_step(&self, fine: f64, coarse: f64) -> Option<f64> {
        self.curve()
            .map(|c| fine.max((c.length() / STEPS_PER_LENGTH).min(coarse)))
    }

    /// The gap of a smooth law's greatest tension, from above: the first of a geometric scan
    /// (1% apart, from 1e-6 of its length to its reach) past the largest sampled tension, so
    /// that every gap beyond it is past the peak (0 when the tension is greatest at the wall,
    /// the exponential law's); `None` for the criterion and the Dugdale law. The built-in and
    /// custom curves scale as γ, so the gap does not depend on it.
    ///
    /// ```
    /// use tack_solver::{AdhesionLaw, Exponential, LennardJones};
    /// assert_eq!(AdhesionLaw::from(Exponential { range: 0.1 }).peak_gap(), Some(0.0));
    /// let g = AdhesionLaw::from(LennardJones { range: 1.0 }).peak_gap().unwrap();
    /// assert!(g > 0.0 && g < 0.3, "{g}");
    /// ```
    pub fn peak_gap(&self) -> Option<f64> {
        self.curve().map(peak_gap_of)
    }

    /// Whether every element carries the traction of its own gap (a smooth law).
    pub fn is_smooth(&self) -> bool {
        self.curve().is_some()
    }

    /// The smooth law's curve (`None` for the criterion and the Dugdale law).
    pub fn curve(&self) -> Option<&dyn Curve> {
        match self.family() {
            Family::Smooth(c) => Some(c),
            _ => None,
        }
    }

    /// Tabor's parameter `μ = (Rγ²/(E*²ℓ³))^(1/3)` of a sphere of `radius` with the law's
    /// length ℓ ([`Law::range`]); `None` for the zero-range criterion (μ = ∞).
    pub fn tabor(&self, e_star: f64, gamma: f64, radius: f64) -> Option<f64> {
        let l = self.range(gamma)?;
        Some((radius * gamma * gamma / (e_star * e_star * l * l * l)).cbrt())
    }
}

impl std::ops::Deref for AdhesionLaw {
    type Target = dyn Law;

    fn deref(&self) -> &(dyn Law + 'static) {
        self.law()
    }
}

/// [`AdhesionLaw::peak_gap`] of a curve.
pub(super) fn peak_gap_of(curve: &dyn Curve) -> f64 {
    let tension = |g: f64| -curve.pressure(1.0, g);
    let (mut best, mut at) = (tension(0.0), 0.0);
    let mut g = 1e-6 * curve.length();
    let mut past = g;
    while g < curve.reach() {
        let t = tension(g);
        if t > best {
            (best, at) = (t, g);
            past = g * 1.01;
        }
        g *= 1.01;
    }
    if at == 0.0 { 0.0 } else { past }
}

/// Calls `$body` with `$c` bound to the traction's curve: by its own type for the built-in
/// curves, through [`Curve`] for any other.
macro_rules! on_curve {
    ($t:expr, $c:ident => $body:expr) => {
        match &$t.law {
            AdhesionLaw::Exponential($c) => $body,
            AdhesionLaw::LennardJones($c) => $body,
            other => {
                let $c = other.curve().expect("a traction holds a smooth law");
                $body
            }
        }
    };
}

/// A smooth law's traction–gap curve for work of adhesion `gamma` (the solver's handle: the
/// law and the γ that scales it).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Traction {
    pub(crate) law: AdhesionLaw,
    pub(crate) gamma: f64,
}

impl Traction {
    /// The curve of a smooth law (`None` for the others).
    pub(crate) fn new(law: AdhesionLaw, gamma: f64) -> Option<Self> {
        law.is_smooth().then_some(Self { law, gamma })
    }

    /// The pressure at gap `g ≥ 0` (negative: tension), called on the built-in curves by
    /// their own type so the hot loops inline it (a dynamic call costs them 3% of their
    /// instructions and the sharing of `exp` between pressure and slope).
    #[inline]
    pub(crate) fn pressure(&self, g: f64) -> f64 {
        on_curve!(self, c => c.pressure(self.gamma, g))
    }

    /// `dp/dg` at gap `g ≥ 0`: positive where the law softens (destabilises).
    #[inline]
    pub(crate) fn stiffness(&self, g: f64) -> f64 {
        on_curve!(self, c => c.stiffness(self.gamma, g))
    }

    /// The pressure and its slope at gap `g ≥ 0` ([`Curve::pressure_and_stiffness`]).
    #[inline]
    pub(crate) fn pressure_and_stiffness(&self, g: f64) -> (f64, f64) {
        on_curve!(self, c => c.pressure_and_stiffness(self.gamma, g))
    }

    /// Whether the law stiffens anywhere ([`Curve::stiffens`]).
    pub(crate) fn stiffens(&self) -> bool {
        on_curve!(self, c => c.stiffens())
    }

    /// A gap beyond which the tension stays at or below `cut > 0` as evaluated: the tension of
    /// a curve that falls past its peak ([`Curve::falls_past_peak`]), at `peak_gap`
    /// ([`AdhesionLaw::peak_gap`]), only falls beyond it, so the first gap found (by
    /// bisection, from above) whose tension is at most `cut·(1 − 1e-6)` bounds every gap
    /// beyond it, the margin far above the round-off of its evaluation. `None` for a curve that
    /// promises no such tail, for a `cut` that is not positive and finite, or when no gap up
    /// to 1e6 law lengths beyond the peak qualifies.
    pub(crate) fn quiet_beyond(&self, cut: f64, peak_gap: f64) -> Option<f64> {
        let falls = on_curve!(self, c => c.falls_past_peak());
        if !(falls && cut > 0.0 && cut.is_finite()) {
            return None;
        }
        let target = cut * (1.0 - 1e-6);
        let quiet = |g: f64| self.pressure(g).abs() <= target;
        let length = self.law.curve()?.length();
        let (mut lo, mut hi) = (peak_gap, peak_gap + length);
        while !quiet(hi) {
            lo = hi;
            hi = peak_gap + 2.0 * (hi - peak_gap);
            if hi > peak_gap + 1e6 * length {
                return None;
            }
        }
        // `hi` stays quiet; 60 halvings bring it to within 2^-60 of the bracket.
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if quiet(mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        Some(hi)
    }
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
    /// Checks the law ([`Law::check`]) and makes the empty zone.
    pub(crate) fn new(
        gamma: f64,
        sigma0: f64,
        surface: &Surface,
        shape: (usize, usize),
    ) -> Result<Self, SolverError> {
        let law = Dugdale { sigma0 };
        law.check(gamma, surface)?;
        Ok(Self {
            sigma0,
            range: law.h0(gamma),
            zone: Array2::from_elem(shape, false),
            loaded: Array2::from_elem(shape, false),
        })
    }
}

#[cfg(test)]
mod tests;
