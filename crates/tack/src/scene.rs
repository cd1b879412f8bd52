//! Scene files: the TOML schema (`version = 1`, unknown fields rejected everywhere), loading
//! with `--set key=value` overrides, and the error type shared by scene handling.
//!
//! A scene names the material, the rigid body (macro shape plus optional roughness), the grid,
//! the solver settings, the approach path and what to store. `docs/scenes.md` documents every
//! field; [`crate::problem::Problem::from_scene`] validates the values and builds the surface.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use tack_fields::{self as fields, FIELDS, Field, Kind, SECTIONS, SNAPSHOT_FORMS};

pub use crate::error::{SceneError, num};
use crate::overrides::apply_overrides;

/// The only scene-file version this build reads.
pub const SCENE_VERSION: i64 = 1;

/// The top level of a scene file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSchema {
    /// Schema version; must be [`SCENE_VERSION`].
    pub version: i64,
    /// `[material]`.
    pub material: Material,
    /// `[adhesion]`: the adhesion law and the pattern of γ, optional (default: the zero-range
    /// limit, one γ everywhere).
    #[serde(default, skip_serializing_if = "AdhesionSpec::is_default")]
    pub adhesion: AdhesionSpec,
    /// `[body]`: the elastic body, optional (default: a homogeneous half-space).
    #[serde(default, skip_serializing_if = "BodySpec::is_default")]
    pub body: BodySpec,
    /// `[geometry]`: the macroscopic shape.
    pub geometry: Geometry,
    /// `[roughness]`: added to the shape, optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roughness: Option<Roughness>,
    /// `[grid]`.
    pub grid: GridSpec,
    /// `[solver]`, optional.
    #[serde(default)]
    pub solver: SolverSpec,
    /// `[protocol]`: the approach path; optional for a pull-off of a sphere-like body (the
    /// default path of [`crate::pull_off_path`]).
    #[serde(default)]
    pub protocol: Protocol,
    /// `[output]`, optional.
    #[serde(default)]
    pub output: OutputSpec,
}

/// `[material]`: the elastic half-space and the adhesion.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Effective modulus `E*` (> 0); with `prony` the relaxed modulus `E0`.
    pub e_star: f64,
    /// Work of adhesion `γ` per unit area (≥ 0; 0 is non-adhesive).
    pub gamma: f64,
    /// A viscoelastic solid: the arms `[E_k, τ_k]` of `E(t) = E0 + Σ E_k e^(−t/τ_k)` (each
    /// > 0); paths then run in time (`protocol.speed`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub prony: Option<Vec<[f64; 2]>>,
}

/// `[adhesion]`: which law turns the work of adhesion `material.gamma` into tractions, and
/// whether γ varies over the surface (a map file or a generated pattern).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AdhesionSpec {
    /// `"jkr_limit"` (default), `"dugdale"`, `"exponential"`, `"lennard_jones"` or
    /// `"smoothed_dugdale"`.
    #[serde(default)]
    pub model: AdhesionModel,
    /// Smooth laws: the range ρ of `"exponential"` (`p = −(γ/ρ) e^(−g/ρ)`) or the equilibrium
    /// separation ε of `"lennard_jones"` (> 0). Only with those models.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range: Option<f64>,
    /// Dugdale: the cohesive tension σ0 (> 0); the range is `h0 = γ/σ0`. Only with
    /// `model = "dugdale"` or `"smoothed_dugdale"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma0: Option<f64>,
    /// γ per element from a file (text or HDF5, the grid's shape; the height maps' formats),
    /// relative to the scene file's directory.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gamma_map: Option<PathBuf>,
    /// The dataset of an HDF5 γ map.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dataset: Option<String>,
    /// A generated pattern of γ (`material.gamma` is phase a, or the random field's mean).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pattern: Option<PatternKind>,
    /// Stripes, rings, checkerboard: γ of phase b (≥ 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gamma_b: Option<f64>,
    /// Stripes, rings, checkerboard: the period.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub period: Option<f64>,
    /// Stripes, rings: the share of a period that is phase b (default 0.5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fraction: Option<f64>,
    /// Random: the correlation length ℓ.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub correlation_length: Option<f64>,
    /// Random: the coefficient of variation of γ.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contrast: Option<f64>,
    /// Random: the seed (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
}

impl AdhesionSpec {
    /// The default section (left out when a scene is written).
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }
}

/// `adhesion.pattern`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PatternKind {
    /// One γ everywhere (`material.gamma`).
    #[default]
    Uniform,
    /// Stripes across x (bands parallel to y): phase b on `fraction` of each `period`, centred on x = 0.
    Stripes,
    /// Rings about the origin: phase b on a central disc of radius `fraction·period/2` and on
    /// rings about r = k·period.
    Rings,
    /// Squares of side `period/2`, phase a on the one centred at the origin.
    Checkerboard,
    /// A seeded log-normal field of mean `material.gamma`, coefficient of variation
    /// `contrast` and correlation length `correlation_length`.
    Random,
}

impl PatternKind {
    /// The name in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::Stripes => "stripes",
            Self::Rings => "rings",
            Self::Checkerboard => "checkerboard",
            Self::Random => "random",
        }
    }
}

/// `[body]`: the elastic body the rigid one presses on.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// `"half_space"` (default) or `"layer"`.
    #[serde(default)]
    pub kind: BodyKind,
    /// Layer: the thickness h (> 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thickness: Option<f64>,
    /// Layer: Poisson's ratio ν in (−1, 0.5] (`material.e_star` is the layer's E/(1 − ν²)).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub poisson: Option<f64>,
    /// Layer: `"bonded"` (default) or `"frictionless"` on its rigid base.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interface: Option<InterfaceKind>,
}

impl BodySpec {
    /// The default section (left out when a scene is written).
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }
}

/// `body.kind`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BodyKind {
    /// A homogeneous elastic half-space.
    #[default]
    HalfSpace,
    /// An elastic layer of thickness `body.thickness` on a rigid base.
    Layer,
}

/// `body.interface`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum InterfaceKind {
    /// Welded to the base.
    Bonded,
    /// Sliding freely on the base.
    Frictionless,
}

/// `adhesion.model`: the scene name of one of the solver's laws
/// ([`tack_solver::AdhesionLaw::models`]: `"jkr_limit"`, the default and the paper's model,
/// `"dugdale"`, `"exponential"`, `"lennard_jones"`, `"smoothed_dugdale"`). The list is the
/// solver's: a new law is named here without an edit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AdhesionModel(&'static str);

impl Default for AdhesionModel {
    /// The zero-range limit, the paper's model.
    fn default() -> Self {
        Self::of(&tack_solver::AdhesionLaw::from(tack_solver::JkrLimit {
            kappa: tack_solver::KAPPA,
        }))
    }
}

impl<'de> Deserialize<'de> for AdhesionModel {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        Self::from_name(&name).ok_or_else(|| {
            serde::de::Error::custom(format!(
                "unknown model {name:?}: expected {}",
                Self::names()
            ))
        })
    }
}

impl Serialize for AdhesionModel {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.0)
    }
}

impl AdhesionModel {
    /// The model of a scene file's name (`None`: no such model).
    pub fn from_name(name: &str) -> Option<Self> {
        tack_solver::AdhesionLaw::models()
            .find(|&m| m == name)
            .map(AdhesionModel)
    }

    /// The model that names `law`.
    pub fn of(law: &tack_solver::AdhesionLaw) -> Self {
        AdhesionModel(law.name())
    }

    /// The names, quoted and joined for messages: `"jkr_limit", "dugdale", … or "…"`.
    pub fn names() -> String {
        let quoted: Vec<String> = tack_solver::AdhesionLaw::models()
            .map(|m| format!("{m:?}"))
            .collect();
        match quoted.split_last() {
            Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
            _ => quoted.concat(),
        }
    }

    /// The name in scene files and results.
    pub fn name(self) -> &'static str {
        self.0
    }

    /// Whether the model is the zero-range criterion (the default).
    pub fn is_zero_range(self) -> bool {
        self == Self::default()
    }
}

/// `[geometry]`: the macroscopic shape, selected by `shape`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "shape", rename_all = "snake_case", deny_unknown_fields)]
pub enum Geometry {
    /// `shape = "sphere"`: a paraboloid `(x² + y²)/(2R)`.
    Sphere {
        /// Radius `R` (> 0).
        radius: f64,
    },
    /// `shape = "flat_punch"`: a rigid flat face, lifted everywhere else.
    FlatPunch {
        /// `"circle"` (needs `radius`) or `"square"` (needs `half_side`).
        punch: PunchKind,
        /// Radius of a circular face.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        radius: Option<f64>,
        /// Half the side of a square face.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        half_side: Option<f64>,
    },
    /// `shape = "power_law"`: an axisymmetric body `c·r^m` (a cone for m = 1).
    PowerLaw {
        /// Coefficient `c` (> 0).
        c: f64,
        /// Exponent `m` (1 to 16).
        exponent: f64,
    },
    /// `shape = "ellipsoid"`: a paraboloid `x²/(2Rx) + y²/(2Ry)`.
    Ellipsoid {
        /// Radius `Rx` along x (> 0).
        radius_x: f64,
        /// Radius `Ry` along y (> 0).
        radius_y: f64,
    },
    /// `shape = "none"`: a flat body (only the roughness, if any).
    None,
}

/// The face of a flat punch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PunchKind {
    /// A circular face.
    Circle,
    /// A square face, aligned with the grid.
    Square,
}

/// `[roughness]`: added to the shape, selected by `kind`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Roughness {
    /// `kind = "waviness1d"`: `h[1 − cos(2πx/λ)]` (Eq. 1).
    Waviness1d {
        /// Amplitude `h` (≥ 0).
        h: f64,
        /// Wavelength `λ` (≥ 4·grid.dx).
        lambda: f64,
    },
    /// `kind = "waviness2d"`: `h[1 − cos(2πx/λ)cos(2πy/λ)]` (Eq. 4; Eq. 6 on a sphere).
    Waviness2d {
        /// Amplitude `h` (≥ 0).
        h: f64,
        /// Wavelength `λ` (≥ 4·grid.dx).
        lambda: f64,
    },
    /// `kind = "random"`: seeded Fourier-filtered roughness (Pohrt & Li 2014 style).
    Random {
        /// Rms height (≥ 0).
        h: f64,
        /// Hurst exponent `H` in (0, 1).
        hurst: f64,
        /// Lower cut-off wave vector; default `2π/L`, `L` the longer grid side.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        q0: Option<f64>,
        /// Upper cut-off wave vector; default `π/grid.dx`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        q1: Option<f64>,
        /// Seed of the random phases (default 0).
        #[serde(default)]
        seed: u64,
    },
    /// `kind = "file"`: a measured height map, text/CSV or HDF5.
    File {
        /// Path of the map, relative to the scene file's directory.
        path: PathBuf,
        /// HDF5 only: the dataset holding the heights (default `heights`, then `/surface/heights`).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        dataset: Option<String>,
    },
}

/// Boundary kind of the grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BoundaryKind {
    /// Non-periodic half-space (DC-FFT with zero padding).
    #[default]
    Free,
    /// One period of an infinitely repeated pattern.
    Periodic,
}

/// `[grid]`: element counts, spacing, boundary.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridSpec {
    /// Elements per side of a square grid (give either `n` or both `nx` and `ny`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub n: Option<usize>,
    /// Elements along x.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nx: Option<usize>,
    /// Elements along y.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ny: Option<usize>,
    /// Element size (give exactly one of `dx` and `length`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dx: Option<f64>,
    /// Domain length along x, `nx·dx`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
    /// `"free"` (default) or `"periodic"`.
    #[serde(default)]
    pub boundary: BoundaryKind,
    /// Crop the domain to where contact can occur (default true): a free grid is solved on the
    /// window `tack_solver::contact_window` finds (same result as the full grid); periodic grids
    /// are never cropped (docs/scenes.md, docs/theory.md §8.3).
    #[serde(default = "default_true")]
    pub crop: bool,
}

fn default_true() -> bool {
    true
}

/// `[solver]`: all optional.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    /// Pohrt–Popov constant κ of `σ_c = sqrt(E*γ/(κΔx))`; default [`tack_solver::KAPPA`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kappa: Option<f64>,
    /// Relative CG tolerance in 1e-14..=0.1; default the solver's (1e-9).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
    /// Cap on CG iterations per solve; default the solver's (5000).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_iterations: Option<usize>,
    /// Cap on detach/attach rounds per approach step; default the solver's (1000).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_active_set_iterations: Option<usize>,
    /// CG tolerance in (0, 1) of the inexact detach/attach rounds, or `0` to solve every round
    /// to `tolerance` (the exact algorithm); default the solver's (1e-3). See
    /// `tack_solver::AdhesiveOptions::round_tolerance`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub round_tolerance: Option<f64>,
    /// Relax the tension a round releases on small windows before the next round's solve (only
    /// that solve's start changes); default true. See
    /// `tack_solver::AdhesiveOptions::local_relaxation`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub local_relaxation: Option<bool>,
    /// Release, before the next solve, the elements the relaxed tension of a round's
    /// detachments puts clearly past σ_c (zero-range law, with `local_relaxation`); default
    /// true. See `tack_solver::AdhesiveOptions::cascade`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cascade: Option<bool>,
}

/// `[protocol]`: the load–unload approach path (approach positive = pressing). Three forms:
/// `indent = d` alone (one step pressed in to `d`, no retraction); `max_approach` with
/// `load_step` (and the optional fields below); or neither, for the default pull-off path of a
/// sphere-like body (`crate::pull_off_path`; `unload_step` and `coarse_unload_step` may still
/// be given).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Protocol {
    /// One step pressed in to this approach and no retraction (an indentation); excludes every
    /// other field but `max_steps`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub indent: Option<f64>,
    /// First approach; default the first touch, `min f + load_step`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start: Option<f64>,
    /// Deepest approach; the load phase ends exactly there. Default: the pull-off rule.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_approach: Option<f64>,
    /// Approach increment while loading (> 0); required with `max_approach`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub load_step: Option<f64>,
    /// Approach decrement while retracting (> 0); default `load_step`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unload_step: Option<f64>,
    /// Approach decrement while retracting and the force is still compressive (> 0); default
    /// `unload_step` throughout (see `tack_solver::ApproachPath::coarse_unload_step`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coarse_unload_step: Option<f64>,
    /// Refined retraction: coarse steps all the way, the brackets that may hold the pull-off
    /// retraced in steps of `unload_step` (needs a coarse step; see
    /// `tack_solver::ApproachPath::refine_pull_off`). Default false.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub refine_pull_off: Option<bool>,
    /// Stop retracting below this approach; default: retract until nothing is bonded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub retract_to: Option<f64>,
    /// Cap on the number of steps (default 100000).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_steps: Option<usize>,
    /// Viscoelastic solids (`material.prony`): the approach rate of the loading, and of the
    /// retraction unless `unload_speed` (> 0; required there).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed: Option<f64>,
    /// Viscoelastic solids: the approach rate of the retraction (> 0); default `speed`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unload_speed: Option<f64>,
    /// Viscoelastic solids: the time held at the deepest approach (≥ 0); default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dwell: Option<f64>,
    /// Viscoelastic solids: the time steps of the hold (≥ 1); default
    /// [`DEFAULT_DWELL_STEPS`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dwell_steps: Option<usize>,
}

/// Default of [`Protocol::dwell_steps`]: the hold in 20 equal time steps.
pub const DEFAULT_DWELL_STEPS: usize = 20;

/// Default of [`Protocol::max_steps`].
pub const DEFAULT_MAX_STEPS: usize = 100_000;

/// `[output]`: which fields go into the result file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Which steps keep their pressure field and bonded mask (default none).
    #[serde(default)]
    pub snapshots: Snapshots,
    /// Store the surface heights (default true).
    #[serde(default = "default_true")]
    pub surface: bool,
}

impl Default for OutputSpec {
    fn default() -> Self {
        Self {
            snapshots: Snapshots::None,
            surface: true,
        }
    }
}

/// `output.snapshots`: `"none"`, `"all"`, `"pull_off"`, `{ every = k }` or `{ steps = [i, ...] }`.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(try_from = "toml::Value", into = "toml::Value")]
pub enum Snapshots {
    /// No fields.
    #[default]
    None,
    /// Every step.
    All,
    /// Every k-th step, starting with step 0.
    Every(usize),
    /// The listed step indices.
    Steps(Vec<usize>),
    /// The pull-off step (least force) and the last step with a bonded element.
    PullOff,
}

impl TryFrom<toml::Value> for Snapshots {
    type Error = String;

    fn try_from(value: toml::Value) -> Result<Self, String> {
        let bad = || {
            format!(
                "{field} = {} is invalid: must be {SNAPSHOT_FORMS}",
                value_text(&value),
                field = fields::OUTPUT_SNAPSHOTS
            )
        };
        match &value {
            toml::Value::String(s) if s == "none" => Ok(Self::None),
            toml::Value::String(s) if s == "all" => Ok(Self::All),
            toml::Value::String(s) if s == "pull_off" => Ok(Self::PullOff),
            toml::Value::Table(t) if t.len() == 1 => {
                if let Some(every) = t.get("every") {
                    match every.as_integer() {
                        Some(k) if k >= 1 => Ok(Self::Every(k as usize)),
                        _ => Err(bad()),
                    }
                } else if let Some(steps) = t.get("steps") {
                    let steps = steps.as_array().ok_or_else(bad)?;
                    steps
                        .iter()
                        .map(|s| match s.as_integer() {
                            Some(i) if i >= 0 => Ok(i as usize),
                            _ => Err(bad()),
                        })
                        .collect::<Result<Vec<_>, _>>()
                        .map(Self::Steps)
                } else {
                    Err(bad())
                }
            }
            _ => Err(bad()),
        }
    }
}

impl From<Snapshots> for toml::Value {
    fn from(s: Snapshots) -> Self {
        let table = |key: &str, v: toml::Value| {
            let mut t = toml::Table::new();
            t.insert(key.to_owned(), v);
            toml::Value::Table(t)
        };
        match s {
            Snapshots::None => toml::Value::String("none".into()),
            Snapshots::All => toml::Value::String("all".into()),
            Snapshots::PullOff => toml::Value::String("pull_off".into()),
            Snapshots::Every(k) => table("every", toml::Value::Integer(k as i64)),
            Snapshots::Steps(steps) => table(
                "steps",
                toml::Value::Array(
                    steps
                        .into_iter()
                        .map(|i| toml::Value::Integer(i as i64))
                        .collect(),
                ),
            ),
        }
    }
}

impl From<&Snapshots> for tack_solver::SnapshotRequest {
    fn from(s: &Snapshots) -> Self {
        match s {
            Snapshots::None => Self::None,
            Snapshots::All => Self::All,
            Snapshots::Every(k) => Self::Every(*k),
            Snapshots::Steps(v) => Self::Steps(v.clone()),
            Snapshots::PullOff => Self::PullOff,
        }
    }
}

/// A TOML value as it would be written in a scene (inline form).
pub(crate) fn value_text(value: &toml::Value) -> String {
    match value {
        toml::Value::String(s) => format!("{s:?}"),
        toml::Value::Table(t) => {
            let items: Vec<String> = t
                .iter()
                .map(|(k, v)| format!("{k} = {}", value_text(v)))
                .collect();
            format!("{{ {} }}", items.join(", "))
        }
        other => other.to_string(),
    }
}

/// A parsed scene: the typed schema, the exact TOML it came from (after overrides), and the
/// directory relative paths in it are resolved against.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The typed content.
    pub file: SceneSchema,
    /// The full TOML text after `--set` overrides (the original text when there were none);
    /// recorded verbatim in result files.
    pub text: String,
    /// Directory for relative paths (`roughness.path`): the scene file's directory.
    pub base_dir: PathBuf,
    /// The scene file, when the scene came from one.
    pub origin: Option<PathBuf>,
}

impl Scene {
    /// Reads and parses a scene file, applying `overrides` (`key.path=value`) first.
    pub fn load(path: &Path, overrides: &[String]) -> Result<Self, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|cause| SceneError::Read {
            path: path.to_owned(),
            cause,
        })?;
        let base_dir = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_owned(),
            _ => PathBuf::from("."),
        };
        Self::parse_with_origin(&text, base_dir, overrides, Some(path.to_owned()))
    }

    /// Parses scene text; relative paths resolve against `base_dir`.
    pub fn parse(
        text: &str,
        base_dir: impl Into<PathBuf>,
        overrides: &[String],
    ) -> Result<Self, SceneError> {
        Self::parse_with_origin(text, base_dir.into(), overrides, None)
    }

    /// A scene from a typed [`SceneSchema`] built in code (the recorded text is its serialisation).
    pub fn from_file(file: SceneSchema, base_dir: impl Into<PathBuf>) -> Result<Self, SceneError> {
        let text = toml::to_string(&file).map_err(|e| SceneError::Syntax {
            origin: None,
            message: e.to_string(),
        })?;
        Self::parse(&text, base_dir, &[])
    }

    fn parse_with_origin(
        text: &str,
        base_dir: PathBuf,
        overrides: &[String],
        origin: Option<PathBuf>,
    ) -> Result<Self, SceneError> {
        let table: toml::Table = toml::from_str(text).map_err(|e| SceneError::Syntax {
            origin: origin.clone(),
            message: e.to_string().trim_end().to_owned(),
        })?;
        if overrides.is_empty() {
            let file = typed(&table).map_err(|fault| located(fault, text, &origin))?;
            return Ok(Self {
                file,
                text: text.to_owned(),
                base_dir,
                origin,
            });
        }
        let mut full = table.clone();
        apply_overrides(&mut full, overrides)?;
        let rewritten = toml::to_string(&full).map_err(|e| SceneError::Syntax {
            origin: origin.clone(),
            message: e.to_string(),
        })?;
        match typed(&full) {
            Ok(file) => Ok(Self {
                file,
                text: rewritten,
                base_dir,
                origin,
            }),
            Err(fault) => Err(blame(fault, text, &table, overrides, &origin)),
        }
    }
}

/// Why a TOML table is not a scene: the error, and the dotted field it is about when known.
struct Fault {
    field: Option<String>,
    error: SceneError,
}

impl From<SceneError> for Fault {
    fn from(error: SceneError) -> Self {
        Self { field: None, error }
    }
}

/// The typed scene of a TOML table: version, sections, the types and ranges of every known
/// field ([`FIELDS`], so the message names the field and what it allows), then the schema.
fn typed(table: &toml::Table) -> Result<SceneSchema, Fault> {
    check_version(table)?;
    check_sections(table)?;
    check_fields(table)?;
    toml::Value::Table(table.clone())
        .try_into::<SceneSchema>()
        .map_err(|e| Fault {
            field: None,
            error: SceneError::Syntax {
                origin: None,
                message: e.message().trim_end().to_owned(),
            },
        })
}

/// The scene's own text failed: the error with the file and the line it is about.
fn located(fault: Fault, text: &str, origin: &Option<PathBuf>) -> SceneError {
    let span = match &fault.field {
        Some(field) => key_span(text, field),
        // A schema error (unknown or missing field, unknown variant): the unknown key's own
        // line, else the parser's span unless it starts the document (the whole document:
        // a missing section).
        None => unknown_key_span(text, &plain(&fault.error)).or_else(|| {
            toml::from_str::<SceneSchema>(text)
                .err()
                .and_then(|e| e.span())
                .filter(|s| s.start > 0)
        }),
    };
    let Some(span) = span else {
        return match fault.error {
            SceneError::Syntax { message, .. } => SceneError::Syntax {
                origin: origin.clone(),
                message,
            },
            other => other,
        };
    };
    let start = span.start.min(text.len());
    let line = text[..start].matches('\n').count() + 1;
    let source = text.lines().nth(line - 1).unwrap_or("").trim();
    SceneError::Syntax {
        origin: origin.clone(),
        message: format!("line {line} (`{source}`): {}", plain(&fault.error)),
    }
}

/// The message of an error without the `scene ...:` prefix of [`SceneError::Syntax`].
fn plain(error: &SceneError) -> String {
    match error {
        SceneError::Syntax { message, .. } => message.clone(),
        other => other.to_string(),
    }
}

/// For `unknown field `name``: the span of that key in a section that does not know it (the
/// schema points at the section header of tagged sections such as `[roughness]`).
fn unknown_key_span(text: &str, message: &str) -> Option<std::ops::Range<usize>> {
    let name = message.strip_prefix("unknown field `")?.split('`').next()?;
    let document = toml::de::DeTable::parse(text).ok()?;
    let root = document.get_ref();
    if let Some((key, _)) = root.iter().find(|(k, _)| k.get_ref() == name)
        && !SECTIONS.contains(&name)
        && name != "version"
    {
        return Some(key.span());
    }
    root.iter().find_map(|(section, value)| {
        let known = |f: &Field| f.section() == section.get_ref() && f.key() == name;
        if FIELDS.iter().any(known) {
            return None;
        }
        let table = value.get_ref().as_table()?;
        table
            .iter()
            .find(|(k, _)| k.get_ref() == name)
            .map(|(k, _)| k.span())
    })
}

/// A scene with `--set` overrides failed with `fault`: blame the file (with its own line) when
/// it fails the same way without the overrides, else the first override after which it does
/// (never a line of the rewritten document, which the user has not seen).
fn blame(
    fault: Fault,
    text: &str,
    table: &toml::Table,
    overrides: &[String],
    origin: &Option<PathBuf>,
) -> SceneError {
    let message = plain(&fault.error);
    let same = |f: &Fault| plain(&f.error) == message;
    if let Err(own) = typed(table)
        && same(&own)
    {
        return located(own, text, origin);
    }
    let mut partial = table.clone();
    for assignment in overrides {
        if apply_overrides(&mut partial, std::slice::from_ref(assignment)).is_err() {
            break;
        }
        if let Err(f) = typed(&partial)
            && same(&f)
        {
            return SceneError::Override {
                assignment: assignment.clone(),
                reason: message,
            };
        }
    }
    fault.error
}

/// The span of the key `field` (dotted, `grid.n`) in scene text, when the text holds it.
fn key_span(text: &str, field: &str) -> Option<std::ops::Range<usize>> {
    let document = toml::de::DeTable::parse(text).ok()?;
    let mut table = document.get_ref();
    let mut parts = field.split('.').peekable();
    while let Some(part) = parts.next() {
        let (key, value) = table.iter().find(|(k, _)| k.get_ref() == part)?;
        if parts.peek().is_none() {
            return Some(key.span());
        }
        table = value.get_ref().as_table()?;
    }
    None
}

/// Checks the type (and for integers the range) of every field of [`FIELDS`] present, so that a
/// wrong value is reported as `grid.n = 32.0 is invalid: must be an integer in 1..=65536`
/// rather than as the schema's `invalid type: floating point 32.0, expected usize`.
fn check_fields(table: &toml::Table) -> Result<(), Fault> {
    for field in FIELDS {
        let Some(value) = table
            .get(field.section())
            .and_then(toml::Value::as_table)
            .and_then(|t| t.get(field.key()))
        else {
            continue;
        };
        let allowed = match field.kind {
            Kind::Number if value.is_float() || value.is_integer() => continue,
            Kind::Number => "a number".to_owned(),
            Kind::Integer { min, max, allowed } => match value.as_integer() {
                Some(v) if (min..=max).contains(&v) => continue,
                _ => allowed.to_owned(),
            },
            Kind::Bool if value.is_bool() => continue,
            Kind::Bool => "true or false".to_owned(),
            Kind::Text if value.is_str() => continue,
            Kind::Text => "a string (in quotes)".to_owned(),
            Kind::Choice(choices) => {
                if value.as_str().is_some_and(|v| choices.contains(&v)) {
                    continue;
                }
                let quoted: Vec<String> = choices.iter().map(|c| format!("\"{c}\"")).collect();
                format!("one of {}", quoted.join(", "))
            }
            // Checked by its own parser (`output.snapshots`: [`Snapshots`]).
            Kind::Form(_) => continue,
        };
        return Err(Fault {
            field: Some(field.name.to_owned()),
            error: SceneError::OutOfRange {
                field: field.name.to_owned(),
                value: value_text(value),
                allowed,
            },
        });
    }
    Ok(())
}

/// Each of the [`SECTIONS`] must be a table: serde would otherwise take an array
/// (`material = [1.0, 0.125]`) field by field in declaration order, silently.
fn check_sections(table: &toml::Table) -> Result<(), SceneError> {
    for name in SECTIONS {
        if let Some(value) = table.get(name)
            && !value.is_table()
        {
            return Err(SceneError::OutOfRange {
                field: name.to_owned(),
                value: value_text(value),
                allowed: format!(
                    "a table: a [{name}] section with named keys (or an inline table {{ ... }}), \
                     not {} {}",
                    if value.is_array() || value.is_integer() {
                        "an"
                    } else {
                        "a"
                    },
                    value.type_str()
                ),
            });
        }
    }
    Ok(())
}

/// The `version` key must be present and equal to [`SCENE_VERSION`]; checked before the schema
/// so a future file gets a version error rather than an unknown-field error.
fn check_version(table: &toml::Table) -> Result<(), SceneError> {
    match table.get("version") {
        None => Err(SceneError::Version(
            "(missing; add `version = 1` at the top)".into(),
            SCENE_VERSION,
        )),
        Some(toml::Value::Integer(v)) if *v == SCENE_VERSION => Ok(()),
        Some(v) => Err(SceneError::Version(value_text(v), SCENE_VERSION)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sections_written_as_arrays_are_refused() {
        let text = MINIMAL.replace("[material]\ne_star = 1.0\ngamma = 0.5\n", "");
        let text = format!("material = [1.0, 0.125]\n{text}");
        let e = Scene::parse(&text, ".", &[]).unwrap_err().to_string();
        assert!(
            e.contains("material = [1.0, 0.125]") && e.contains("a table"),
            "{e}"
        );
        let e = Scene::parse(MINIMAL, ".", &["solver=[0.5]".into()])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("solver = [0.5]") && e.contains("not an array"),
            "{e}"
        );
    }

    const MINIMAL: &str = r#"
version = 1
[material]
e_star = 1.0
gamma = 0.5
[geometry]
shape = "sphere"
radius = 2.0
[grid]
n = 32
dx = 0.1
[protocol]
max_approach = 0.5
load_step = 0.05
"#;

    fn parse(text: &str) -> Result<Scene, SceneError> {
        Scene::parse(text, ".", &[])
    }

    #[test]
    fn minimal_scene_gets_defaults() {
        let s = parse(MINIMAL).unwrap();
        assert_eq!(s.file.geometry, Geometry::Sphere { radius: 2.0 });
        assert!(s.file.grid.crop);
        assert_eq!(s.file.grid.boundary, BoundaryKind::Free);
        assert_eq!(s.file.output.snapshots, Snapshots::None);
        assert!(s.file.output.surface);
        assert_eq!(s.file.solver, SolverSpec::default());
        assert_eq!(s.text, MINIMAL);
    }

    #[test]
    fn unknown_fields_are_rejected_in_every_section() {
        for (section, extra) in [
            ("[material]", "colour = 1"),
            ("[geometry]", "height = 1"),
            ("[grid]", "m = 3"),
            ("[protocol]", "velocity = 1"),
        ] {
            let text = MINIMAL.replace(section, &format!("{section}\n{extra}"));
            let e = parse(&text).unwrap_err().to_string();
            let key = extra.split(' ').next().unwrap();
            assert!(e.contains(&format!("unknown field `{key}`")), "{e}");
        }
        let e = parse(&format!(
            "{MINIMAL}[roughness]\nkind = \"waviness2d\"\nh = 1\nlambda = 1\nphase = 0\n"
        ))
        .unwrap_err()
        .to_string();
        assert!(e.contains("unknown field `phase`"), "{e}");
        let e = parse(&format!("{MINIMAL}[extra]\na = 1\n"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("unknown field `extra`"), "{e}");
    }

    #[test]
    fn version_is_checked_first() {
        let e = parse(&MINIMAL.replace("version = 1", "version = 2\nfuture = true"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("version = 2 is not supported"), "{e}");
        let e = parse(&MINIMAL.replace("version = 1", ""))
            .unwrap_err()
            .to_string();
        assert!(e.contains("version"), "{e}");
    }

    #[test]
    fn snapshot_forms() {
        for (text, want) in [
            ("\"all\"", Snapshots::All),
            ("\"none\"", Snapshots::None),
            ("{ every = 3 }", Snapshots::Every(3)),
            ("{ steps = [0, 4] }", Snapshots::Steps(vec![0, 4])),
            ("\"pull_off\"", Snapshots::PullOff),
        ] {
            let s = parse(&format!("{MINIMAL}[output]\nsnapshots = {text}\n")).unwrap();
            assert_eq!(s.file.output.snapshots, want, "{text}");
            let again = Scene::from_file(s.file.clone(), ".").unwrap();
            assert_eq!(again.file.output.snapshots, want, "{text} round trip");
        }
        for text in [
            "\"some\"",
            "\"pull-off\"",
            "{ every = 0 }",
            "{ steps = [-1] }",
            "3",
        ] {
            let e = parse(&format!("{MINIMAL}[output]\nsnapshots = {text}\n"))
                .unwrap_err()
                .to_string();
            assert!(e.contains("output.snapshots"), "{text}: {e}");
        }
    }

    #[test]
    fn overrides_change_the_recorded_text() {
        let s = Scene::parse(
            MINIMAL,
            ".",
            &[
                "material.gamma=0.25".into(),
                "roughness.kind=waviness2d".into(),
            ],
        );
        // roughness without h/lambda fails through the schema, naming the missing field.
        let e = s.unwrap_err().to_string();
        assert!(e.contains("missing field `h`"), "{e}");
        let s = Scene::parse(MINIMAL, ".", &["material.gamma=0.25".into()]).unwrap();
        assert_eq!(s.file.material.gamma, 0.25);
        assert!(s.text.contains("gamma = 0.25"), "{}", s.text);
    }

    #[test]
    fn wrong_types_name_the_field_the_value_the_range_and_the_line() {
        // In the file: its own line.
        let text = MINIMAL.replace("n = 32", "n = 32.0");
        let e = parse(&text).unwrap_err().to_string();
        assert!(
            e.contains(
                "line 10 (`n = 32.0`): grid.n = 32.0 is invalid: must be an integer in 1..=65536"
            ),
            "{e}"
        );
        let seed =
            format!("{MINIMAL}[roughness]\nkind = \"random\"\nh = 0.01\nhurst = 0.5\nseed = -1\n");
        let e = parse(&seed).unwrap_err().to_string();
        assert!(
            e.contains(
                "line 19 (`seed = -1`): roughness.seed = -1 is invalid: must be an integer ≥ 0"
            ),
            "{e}"
        );
        // An unknown key of a tagged section: its own line, not the section header.
        let phase = seed.replace("seed = -1", "phase = 0");
        let e = parse(&phase).unwrap_err().to_string();
        assert!(
            e.contains("line 19 (`phase = 0`): unknown field `phase`"),
            "{e}"
        );
        for (line, expected) in [
            (
                "h = \"x\"",
                "roughness.h = \"x\" is invalid: must be a number",
            ),
            (
                "crop = 1",
                "grid.crop = 1 is invalid: must be true or false",
            ),
            (
                "kind = \"fractal\"",
                "roughness.kind = \"fractal\" is invalid: must be one of",
            ),
        ] {
            let (key, _) = line.split_once(" = ").unwrap();
            let text = if key == "crop" {
                MINIMAL.replace("dx = 0.1", &format!("dx = 0.1\n{line}"))
            } else {
                seed.replace(
                    &format!("{key} = {}", if key == "h" { "0.01" } else { "\"random\"" }),
                    line,
                )
            };
            let e = parse(&text).unwrap_err().to_string();
            assert!(
                e.contains(&format!("(`{line}`): {expected}")),
                "{line}: {e}"
            );
        }
    }

    #[test]
    fn override_errors_name_the_override_or_the_file_line() {
        let set = |sets: &[&str], text: &str| {
            let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
            Scene::parse(text, ".", &sets).unwrap_err().to_string()
        };
        // The override is at fault: named, with no line of the rewritten document.
        let e = set(&["material.gamma=0.25", "grid.n=32.0"], MINIMAL);
        assert!(
            e.starts_with(
                "--set grid.n=32.0: grid.n = 32.0 is invalid: must be an integer in 1..=65536"
            ),
            "{e}"
        );
        assert!(!e.contains("line"), "{e}");
        let e = set(&["roughness.seed=-1", "roughness.kind=random"], MINIMAL);
        assert!(
            e.starts_with("--set roughness.seed=-1: roughness.seed = -1"),
            "{e}"
        );
        let e = set(&["material.colour=1"], MINIMAL);
        assert!(
            e.starts_with("--set material.colour=1: unknown field `colour`"),
            "{e}"
        );
        // The file is at fault (and the overrides are fine): the file's own line.
        let bad = MINIMAL.replace("n = 32", "n = 32.0");
        let e = set(&["material.gamma=0.25"], &bad);
        assert!(e.contains("line 10 (`n = 32.0`): grid.n = 32.0"), "{e}");
        // An override fixing the file's value passes.
        assert!(Scene::parse(&bad, ".", &["grid.n=32".into()]).is_ok());
    }

    #[test]
    fn typed_scene_round_trips_through_text() {
        let s = parse(MINIMAL).unwrap();
        let again = Scene::from_file(s.file.clone(), ".").unwrap();
        assert_eq!(again.file, s.file);
    }
}
