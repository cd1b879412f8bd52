//! Scene files: the TOML schema (`version = 1`, unknown fields rejected everywhere), loading
//! with `--set key=value` overrides, and the error type shared by scene handling.
//!
//! A scene names the material, the rigid body (macro shape plus optional roughness), the grid,
//! the solver settings, the approach path and what to store. `docs/scenes.md` documents every
//! field; [`crate::problem::Problem::from_scene`] validates the values and builds the surface.

use std::fmt;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::overrides::apply_overrides;

/// The only scene-file version this build reads.
pub const SCENE_VERSION: i64 = 1;

/// Everything that can be wrong with a scene; messages name the field, the value and the
/// allowed range, or the file.
#[derive(Debug, Error)]
pub enum SceneError {
    /// The scene file could not be read.
    #[error("cannot read scene `{}`: {cause}", path.display())]
    Read {
        /// The scene file.
        path: PathBuf,
        /// The operating system's error.
        cause: std::io::Error,
    },
    /// The TOML is malformed or does not fit the schema (unknown field, wrong type, missing field).
    #[error("scene{}: {message}", origin.as_ref().map(|p| format!(" `{}`", p.display())).unwrap_or_default())]
    Syntax {
        /// The scene file, when the scene came from one.
        origin: Option<PathBuf>,
        /// The parser's message (it names the line and the field).
        message: String,
    },
    /// The `version` key is missing or not supported.
    #[error(
        "version = {0} is not supported: this tack reads scene files with version = {SCENE_VERSION}"
    )]
    Version(String),
    /// A `--set key=value` override cannot be applied.
    #[error("--set {assignment}: {reason}")]
    Override {
        /// The override as given.
        assignment: String,
        /// Why it cannot be applied.
        reason: String,
    },
    /// A value outside its allowed range.
    #[error("{field} = {value} is invalid: must be {allowed}")]
    OutOfRange {
        /// The offending field, e.g. `material.e_star`.
        field: String,
        /// The value given, as written in the message.
        value: String,
        /// The allowed range.
        allowed: String,
    },
    /// A combination of fields that cannot work (the message names the fields).
    #[error("{0}")]
    Inconsistent(String),
    /// A geometry error (grid, shape, roughness, height map); names the field.
    #[error(transparent)]
    Geometry(#[from] tack_geometry::GeometryError),
    /// An elastic-operator error; names the field.
    #[error(transparent)]
    Kernel(#[from] tack_kernels::KernelError),
    /// A solver or approach-path error; names the field.
    #[error(transparent)]
    Solver(#[from] tack_solver::SolverError),
}

impl SceneError {
    /// An [`SceneError::OutOfRange`] from anything printable.
    pub fn out_of_range(
        field: impl Into<String>,
        value: impl fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        let value = value.to_string();
        // A huge or tiny f64 displays as hundreds of digits: show it as 1.797e308 instead.
        let value = match value.parse::<f64>() {
            Ok(x) if value.len() > 17 => num(x),
            _ => value,
        };
        Self::OutOfRange {
            field: field.into(),
            value,
            allowed: allowed.into(),
        }
    }
}

/// A number as a person reads it in a message: plain for moderate magnitudes, otherwise in
/// scientific notation with the shortest digits that round-trip (`1.797e308`, not 309 digits).
pub fn num(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-5..1e16).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// The top level of a scene file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Schema version; must be [`SCENE_VERSION`].
    pub version: i64,
    /// `[material]`.
    pub material: Material,
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
    /// `[protocol]`: the approach path.
    pub protocol: Protocol,
    /// `[output]`, optional.
    #[serde(default)]
    pub output: OutputSpec,
}

/// `[material]`: the elastic half-space and the adhesion.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Effective modulus `E*` (> 0).
    pub e_star: f64,
    /// Work of adhesion `γ` per unit area (≥ 0; 0 is non-adhesive).
    pub gamma: f64,
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
    /// Crop the domain to where contact can occur (default true). Parsed and recorded; the
    /// solver does not crop yet, so every run uses the full grid.
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
}

/// `[protocol]`: the load–unload approach path (approach positive = pressing).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Protocol {
    /// First approach; default the first touch, `min f + load_step`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start: Option<f64>,
    /// Deepest approach; the load phase ends exactly there.
    pub max_approach: f64,
    /// Approach increment while loading (> 0).
    pub load_step: f64,
    /// Approach decrement while retracting (> 0); default `load_step`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unload_step: Option<f64>,
    /// Approach decrement while retracting and the force is still compressive (> 0); default
    /// `unload_step` throughout (see `tack_solver::ApproachPath::coarse_unload_step`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coarse_unload_step: Option<f64>,
    /// Stop retracting below this approach; default: retract until nothing is bonded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub retract_to: Option<f64>,
    /// Cap on the number of steps (default 100000).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_steps: Option<usize>,
}

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

const SNAPSHOTS_ALLOWED: &str = "\"none\", \"all\", \"pull_off\", { every = k } with k ≥ 1, or \
                                 { steps = [i, ...] } with indices ≥ 0";

impl TryFrom<toml::Value> for Snapshots {
    type Error = String;

    fn try_from(value: toml::Value) -> Result<Self, String> {
        let bad = || {
            format!(
                "output.snapshots = {} is invalid: must be {SNAPSHOTS_ALLOWED}",
                value_text(&value)
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
    pub file: SceneFile,
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

    /// A scene from a typed [`SceneFile`] built in code (the recorded text is its serialisation).
    pub fn from_file(file: SceneFile, base_dir: impl Into<PathBuf>) -> Result<Self, SceneError> {
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
        let syntax = |e: toml::de::Error| SceneError::Syntax {
            origin: origin.clone(),
            message: e.to_string().trim_end().to_owned(),
        };
        let mut table: toml::Table = toml::from_str(text).map_err(syntax)?;
        let text = if overrides.is_empty() {
            text.to_owned()
        } else {
            apply_overrides(&mut table, overrides)?;
            toml::to_string(&table).map_err(|e| SceneError::Syntax {
                origin: origin.clone(),
                message: e.to_string(),
            })?
        };
        check_version(&table)?;
        check_sections(&table)?;
        let file: SceneFile = toml::from_str(&text).map_err(syntax)?;
        Ok(Self {
            file,
            text,
            base_dir,
            origin,
        })
    }
}

/// The sections of a scene file: each must be a table. serde would otherwise take an array
/// (`material = [1.0, 0.125]`) field by field in declaration order, silently.
const SECTIONS: [&str; 7] = [
    "material",
    "geometry",
    "roughness",
    "grid",
    "solver",
    "protocol",
    "output",
];

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
        )),
        Some(toml::Value::Integer(v)) if *v == SCENE_VERSION => Ok(()),
        Some(v) => Err(SceneError::Version(value_text(v))),
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
            ("[protocol]", "speed = 1"),
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
    fn typed_scene_round_trips_through_text() {
        let s = parse(MINIMAL).unwrap();
        let again = Scene::from_file(s.file.clone(), ".").unwrap();
        assert_eq!(again.file, s.file);
    }
}
