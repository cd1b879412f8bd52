//! Parameter sweeps: a base scene, the scene fields to vary (lists or ranges, and zipped
//! entries that set several fields together, combined as a Cartesian product in file order)
//! and the summary quantities to collect; running the points of a sweep, or of one shard of it,
//! in parallel into a directory of result files that a rerun resumes.
//!
//! `docs/sweeps.md` documents the file format and the output directory; [`crate::merge()`]
//! gathers the directory into one table.
//!
//! # Order of the points
//!
//! The entries of `[vary]` are taken in the order they are written in the file (recovered from
//! the parser's spans, so it does not depend on how the `toml` crate orders its tables). Point
//! indices run over the Cartesian product of the entries with the first entry outermost and the
//! last fastest: with `a = [1, 2]` then `b = [10, 20, 30]`, point 0 is (1, 10), point 1 is
//! (1, 20), point 3 is (2, 10). A zipped entry (`"c, d" = [[1, 5], [2, 6]]`) is one factor of
//! the product: its rows, in order, each set all of its fields.

use std::collections::HashMap;
use std::fmt;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use rayon::prelude::*;
use serde::Deserialize;
use thiserror::Error;

use tack::{RunOptions, SUMMARY_QUANTITIES, Scene, SceneError, set_value};

/// The only sweep-file version this build reads.
pub const SWEEP_VERSION: i64 = 1;

/// Largest number of points a sweep may have.
pub const MAX_POINTS: usize = 10_000_000;

/// The copy of the sweep file in the output directory.
pub const SWEEP_COPY: &str = "sweep.toml";

/// The copy of the base scene in the output directory (the referenced file verbatim, or the
/// inline `[scene]` table serialised).
pub const SCENE_COPY: &str = "scene.toml";

/// The subdirectory of the output directory holding one result (or error) file per point.
pub const POINTS_DIR: &str = "points";

/// What `collect` defaults to: the fields of [`tack_io::Summary`].
pub const DEFAULT_COLLECT: [&str; 5] = [
    "pull_off_force",
    "f_jkr",
    "pull_off_ratio",
    "johnson_alpha",
    "alpha_star",
];

/// Everything that can go wrong with a sweep file, its output directory or a sweep run (a
/// failing *point* is not an error of the sweep: it is recorded and reported).
#[derive(Debug, Error)]
pub enum SweepError {
    /// A file could not be read.
    #[error("cannot read `{}`: {cause}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        cause: std::io::Error,
    },
    /// The sweep file is malformed or invalid; the message names the field.
    #[error("sweep `{}`: {message}", origin.display())]
    Invalid {
        /// The sweep file.
        origin: PathBuf,
        /// What is wrong, naming the field and the value.
        message: String,
    },
    /// The output directory cannot be used for this sweep.
    #[error("{}: {message}", dir.display())]
    Dir {
        /// The output directory.
        dir: PathBuf,
        /// Why not.
        message: String,
    },
    /// A file-system operation failed.
    #[error("{}: {what}: {cause}", path.display())]
    Fs {
        /// The file or directory.
        path: PathBuf,
        /// The operation.
        what: String,
        /// The operating system's error.
        cause: std::io::Error,
    },
    /// A result or sweep table could not be written or read.
    #[error(transparent)]
    Io(#[from] tack_io::IoError),
    /// The thread count is out of range (the message names `--threads`) or the pool could not
    /// be built.
    #[error("{0}")]
    Threads(String),
}

/// One varied scene field and its values, in order.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// The dotted scene field, e.g. `roughness.h`.
    pub field: String,
    /// Its values (at least one).
    pub values: Vec<toml::Value>,
    /// Index of the `[vary]` entry the field belongs to, in file order. A plain entry has one
    /// field; the fields of a zipped entry share the index, have the same number of values and
    /// take them together (value `k` of each at row `k`).
    pub entry: usize,
}

/// A parsed, validated sweep.
#[derive(Debug, Clone)]
pub struct Sweep {
    /// The sweep file's text, verbatim (copied to `DIR/sweep.toml`).
    pub text: String,
    /// The sweep file.
    pub origin: PathBuf,
    /// The base scene's text (copied to `DIR/scene.toml`).
    pub base_text: String,
    /// The base scene file, when `scene` names one.
    pub base_origin: Option<PathBuf>,
    /// Directory that relative paths in the scene (`roughness.path`) resolve against: the base
    /// scene file's directory, or the sweep file's for an inline `[scene]`.
    pub base_dir: PathBuf,
    /// The varied fields, in file order (the fields of a zipped entry in the order its key
    /// names them); the product runs over their entries, the first entry outermost.
    pub axes: Vec<Axis>,
    /// The summary quantities to collect (names from [`SUMMARY_QUANTITIES`]).
    pub collect: Vec<String>,
    /// The number of values of each `[vary]` entry, in file order.
    entry_lengths: Vec<usize>,
    base_table: toml::Table,
}

/// The top level of a sweep file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SweepFile {
    #[allow(dead_code)]
    version: i64,
    scene: toml::Value,
    #[serde(default)]
    vary: toml::Table,
    #[serde(default)]
    collect: Option<Vec<String>>,
}

/// Where the base scene comes from while parsing.
enum Base<'a> {
    /// Resolve `scene` against the sweep file's directory.
    Resolve(&'a Path),
    /// The base scene text is given (from an output directory's `scene.toml`); relative paths
    /// resolve against the directory.
    Given(String, &'a Path),
}

impl Sweep {
    /// Reads and validates a sweep file; `scene = "..."` is resolved against its directory.
    pub fn load(path: &Path) -> Result<Self, SweepError> {
        let text = read(path)?;
        Self::parse(&text, path, Base::Resolve(&parent_dir(path)))
    }

    /// Parses sweep text as if it were the file `origin` (relative paths resolve against
    /// `origin`'s directory).
    pub fn parse_text(text: &str, origin: &Path) -> Result<Self, SweepError> {
        Self::parse(text, origin, Base::Resolve(&parent_dir(origin)))
    }

    /// The sweep of an output directory of `tack sweep`, from its `sweep.toml` and
    /// `scene.toml` (the original files are not needed).
    pub fn open_dir(dir: &Path) -> Result<Self, SweepError> {
        let copy = dir.join(SWEEP_COPY);
        if !copy.is_file() {
            return Err(SweepError::Dir {
                dir: dir.to_owned(),
                message: format!(
                    "not a sweep directory: no {SWEEP_COPY} (run `tack sweep SWEEP.toml -o {}` \
                     first)",
                    dir.display()
                ),
            });
        }
        let text = read(&copy)?;
        let base = read(&dir.join(SCENE_COPY))?;
        Self::parse(&text, &copy, Base::Given(base, dir))
    }

    fn parse(text: &str, origin: &Path, base: Base<'_>) -> Result<Self, SweepError> {
        let invalid = |message: String| SweepError::Invalid {
            origin: origin.to_owned(),
            message,
        };
        let table: toml::Table =
            toml::from_str(text).map_err(|e| invalid(e.to_string().trim_end().to_owned()))?;
        match table.get("version") {
            Some(toml::Value::Integer(v)) if *v == SWEEP_VERSION => {}
            None => {
                return Err(invalid(format!(
                    "version is missing: add `version = {SWEEP_VERSION}` at the top"
                )));
            }
            Some(v) => {
                return Err(invalid(format!(
                    "version = {v} is not supported: this tack reads sweep files with version = \
                     {SWEEP_VERSION}"
                )));
            }
        }
        let file: SweepFile =
            toml::from_str(text).map_err(|e| invalid(e.to_string().trim_end().to_owned()))?;

        let (base_text, base_origin, base_dir) = match (base, &file.scene) {
            (Base::Given(text, dir), _) => (text, None, dir.to_owned()),
            (Base::Resolve(dir), toml::Value::String(rel)) => {
                let path = dir.join(rel);
                // Named with the sweep file and its `scene` field, not as a bare path.
                let text = std::fs::read_to_string(&path).map_err(|cause| {
                    invalid(format!(
                        "scene = {rel:?}: cannot read the base scene `{}`: {cause}",
                        path.display()
                    ))
                })?;
                let base_dir = parent_dir(&path);
                (text, Some(path), base_dir)
            }
            (Base::Resolve(dir), toml::Value::Table(inline)) => {
                let mut inline = inline.clone();
                inline
                    .entry("version")
                    .or_insert(toml::Value::Integer(tack::SCENE_VERSION));
                let text = toml::to_string(&inline)
                    .map_err(|e| invalid(format!("[scene] cannot be serialised: {e}")))?;
                (text, None, dir.to_owned())
            }
            (Base::Resolve(_), other) => {
                return Err(invalid(format!(
                    "scene = {other} is invalid: must be the path of a scene file (a string, \
                     relative to the sweep file) or an inline [scene] table"
                )));
            }
        };
        let base_table: toml::Table = toml::from_str(&base_text).map_err(|e| {
            let name = base_origin
                .as_ref()
                .map_or_else(|| "[scene]".to_owned(), |p| format!("`{}`", p.display()));
            invalid(format!(
                "the base scene {name} is not valid TOML: {}",
                e.to_string().trim_end()
            ))
        })?;

        let axes = axes(text, &file.vary).map_err(invalid)?;
        let mut entry_lengths: Vec<usize> = Vec::new();
        for axis in &axes {
            if axis.entry == entry_lengths.len() {
                entry_lengths.push(axis.values.len());
            }
        }
        let mut len: usize = 1;
        for &n in &entry_lengths {
            len = len
                .checked_mul(n)
                .filter(|&n| n <= MAX_POINTS)
                .ok_or_else(|| {
                    invalid(format!(
                        "[vary] makes more than {MAX_POINTS} points; split the sweep"
                    ))
                })?;
        }
        let collect = match file.collect {
            None => DEFAULT_COLLECT.iter().map(|s| s.to_string()).collect(),
            Some(names) => names,
        };
        for (k, name) in collect.iter().enumerate() {
            if !SUMMARY_QUANTITIES.contains(&name.as_str()) {
                return Err(invalid(format!(
                    "collect: `{name}` is not a summary quantity; known: {}",
                    SUMMARY_QUANTITIES.join(", ")
                )));
            }
            if collect[..k].contains(name) {
                return Err(invalid(format!("collect: `{name}` is listed twice")));
            }
        }
        let sweep = Self {
            text: text.to_owned(),
            origin: origin.to_owned(),
            base_text,
            base_origin,
            base_dir,
            axes,
            collect,
            entry_lengths,
            base_table,
        };
        // The first point must fit the scene schema: this catches a misspelt field in [vary]
        // (unknown field) or an incomplete base scene before anything runs. Other points that
        // do not fit fail one by one, like any bad parameter.
        sweep.point_scene(0).map_err(|e| {
            invalid(format!(
                "the scene of point 0 ({}) is invalid: {e}",
                sweep.label(0)
            ))
        })?;
        Ok(sweep)
    }

    /// Number of points: the product of the `[vary]` entries' lengths (a zipped entry counts
    /// its rows once).
    pub fn len(&self) -> usize {
        self.entry_lengths.iter().product()
    }

    /// Whether the sweep has no points (never: every axis has a value).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The position of point `index` in every `[vary]` entry (first entry outermost, last
    /// fastest): the value index of a plain entry, the row of a zipped one.
    pub fn entry_indices(&self, index: usize) -> Vec<usize> {
        let mut rest = index;
        let mut at: Vec<usize> = self
            .entry_lengths
            .iter()
            .rev()
            .map(|&n| {
                let k = rest % n;
                rest /= n;
                k
            })
            .collect();
        at.reverse();
        at
    }

    /// The value of every varied field at point `index`, in the order of [`Sweep::axes`].
    pub fn point_values(&self, index: usize) -> Vec<(&str, &toml::Value)> {
        let at = self.entry_indices(index);
        self.axes
            .iter()
            .map(|axis| (axis.field.as_str(), &axis.values[at[axis.entry]]))
            .collect()
    }

    /// `field = value, ...` of point `index`, for messages.
    pub fn label(&self, index: usize) -> String {
        self.point_values(index)
            .iter()
            .map(|(field, value)| format!("{field} = {value}"))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The scene text of point `index`: the base scene with the point's values set as
    /// `--set`-style overrides (what `tack run BASE --set field=value ...` records).
    pub fn point_text(&self, index: usize) -> Result<String, SceneError> {
        let mut table = self.base_table.clone();
        for (field, value) in self.point_values(index) {
            set_value(&mut table, field, value.clone())?;
        }
        toml::to_string(&table).map_err(|e| SceneError::Syntax {
            origin: None,
            message: e.to_string(),
        })
    }

    /// The parsed scene of point `index` (schema checked; values are validated when the
    /// problem is built).
    pub fn point_scene(&self, index: usize) -> Result<Scene, SceneError> {
        Scene::parse(&self.point_text(index)?, &self.base_dir, &[])
    }
}

/// The varied fields of `[vary]`, in file order, expanded to their values.
fn axes(text: &str, vary: &toml::Table) -> Result<Vec<Axis>, String> {
    let mut leaves = Vec::new();
    flatten(vary, &mut Vec::new(), &mut leaves);
    if leaves.is_empty() {
        return Err(format!(
            "[vary] is empty: give at least one scene field to vary, e.g. `{gamma} = [0.1, 0.2]` \
             under [vary]",
            gamma = tack::fields::MATERIAL_GAMMA
        ));
    }
    let positions = vary_positions(text);
    leaves.sort_by_key(|(path, _)| positions.get(path).copied().unwrap_or(usize::MAX));
    let mut axes: Vec<Axis> = Vec::new();
    for (entry, (path, spec)) in leaves.into_iter().enumerate() {
        let zipped = path.iter().any(|part| part.contains(','));
        let new: Vec<Axis> = if zipped {
            let [key] = path.as_slice() else {
                return Err(format!(
                    "vary.{}: a zipped entry must be one quoted key directly under [vary] that \
                     names every field, e.g. \"{h}, {seed}\" = [[0.1, 1], [0.2, 2]]",
                    path.join("."),
                    h = tack::fields::ROUGHNESS_H,
                    seed = tack::fields::ROUGHNESS_SEED
                ));
            };
            let fields: Vec<String> = key.split(',').map(|f| f.trim().to_owned()).collect();
            let values = expand_zipped(&fields, spec)?;
            fields
                .into_iter()
                .zip(values)
                .map(|(field, values)| Axis {
                    field,
                    values,
                    entry,
                })
                .collect()
        } else {
            let field = path.join(".");
            let values = expand(&field, spec)?;
            vec![Axis {
                field,
                values,
                entry,
            }]
        };
        for axis in new {
            if axes.iter().any(|a| a.field == axis.field) {
                return Err(format!("vary.{} is given twice", axis.field));
            }
            axes.push(axis);
        }
    }
    Ok(axes)
}

/// The values of each field of a zipped entry (`"a, b" = [[a0, b0], [a1, b1], ...]`): one row
/// per point of the entry, one value per field in each row.
fn expand_zipped(fields: &[String], spec: &toml::Value) -> Result<Vec<Vec<toml::Value>>, String> {
    let name = format!("vary.\"{}\"", fields.join(", "));
    if let Some(k) = fields.iter().position(|f| f.is_empty()) {
        return Err(format!(
            "{name}: field {} of the zipped entry is empty: name the fields separated by commas, \
             e.g. \"{h}, {seed}\"",
            k + 1,
            h = tack::fields::ROUGHNESS_H,
            seed = tack::fields::ROUGHNESS_SEED
        ));
    }
    let form = format!(
        "a list of rows with one value per field ({}), e.g. [[{}], ...]",
        fields.join(", "),
        fields
            .iter()
            .map(|f| format!("{}0", f.rsplit('.').next().unwrap_or(f)))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let rows = match spec {
        toml::Value::Array(rows) if rows.is_empty() => {
            return Err(format!("{name} = []: give at least one row"));
        }
        toml::Value::Array(rows) => rows,
        other => return Err(format!("{name} = {other} is invalid: must be {form}")),
    };
    let mut columns: Vec<Vec<toml::Value>> = vec![Vec::with_capacity(rows.len()); fields.len()];
    for (k, row) in rows.iter().enumerate() {
        match row {
            toml::Value::Array(values) if values.len() == fields.len() => {
                for (column, value) in columns.iter_mut().zip(values) {
                    column.push(value.clone());
                }
            }
            toml::Value::Array(values) => {
                return Err(format!(
                    "{name}: row {k} has {} values but the entry names {} fields ({}): every row \
                     needs one value per field, in that order",
                    values.len(),
                    fields.len(),
                    fields.join(", ")
                ));
            }
            other => {
                return Err(format!(
                    "{name}: row {k} = {other} is invalid: must be a list of {} values, one per \
                     field ({})",
                    fields.len(),
                    fields.join(", ")
                ));
            }
        }
    }
    Ok(columns)
}

/// Whether a `[vary]` value is a range table (has `from`) rather than a nested key.
fn is_range(table: &toml::Table) -> bool {
    table.contains_key("from")
}

/// The leaves of `[vary]`: dotted keys make nested tables; a table with `from` is a range.
fn flatten<'t>(
    table: &'t toml::Table,
    prefix: &mut Vec<String>,
    out: &mut Vec<(Vec<String>, &'t toml::Value)>,
) {
    for (key, value) in table {
        prefix.push(key.clone());
        match value {
            toml::Value::Table(inner) if !is_range(inner) => flatten(inner, prefix, out),
            _ => out.push((prefix.clone(), value)),
        }
        prefix.pop();
    }
}

/// Byte offset of every leaf key of `[vary]` in the file, keyed by its path.
fn vary_positions(text: &str) -> HashMap<Vec<String>, usize> {
    fn walk(
        table: &toml::de::DeTable<'_>,
        prefix: &mut Vec<String>,
        out: &mut HashMap<Vec<String>, usize>,
    ) {
        for (key, value) in table.iter() {
            prefix.push(key.get_ref().to_string());
            match value.get_ref().as_table() {
                Some(inner) if !inner.contains_key("from") => walk(inner, prefix, out),
                _ => {
                    out.insert(prefix.clone(), key.span().start);
                }
            }
            prefix.pop();
        }
    }
    let mut out = HashMap::new();
    if let Ok(doc) = toml::de::DeTable::parse(text)
        && let Some(vary) = doc.get_ref().get("vary")
        && let Some(table) = vary.get_ref().as_table()
    {
        walk(table, &mut Vec::new(), &mut out);
    }
    out
}

const SPEC_FORMS: &str = "a list of values [a, b, ...], a range { from, to, steps } (optional \
                          log = true), or an integer range { from, count } (optional step)";

/// The values of one `[vary]` entry.
fn expand(field: &str, spec: &toml::Value) -> Result<Vec<toml::Value>, String> {
    match spec {
        toml::Value::Array(values) if values.is_empty() => {
            Err(format!("vary.{field} = []: give at least one value"))
        }
        toml::Value::Array(values) => Ok(values.clone()),
        toml::Value::Table(range) if is_range(range) => expand_range(field, range),
        other => Err(format!(
            "vary.{field} = {other} is invalid: must be {SPEC_FORMS}"
        )),
    }
}

fn expand_range(field: &str, t: &toml::Table) -> Result<Vec<toml::Value>, String> {
    let integer_range = t.contains_key("count");
    let allowed: &[&str] = if integer_range {
        &["from", "count", "step"]
    } else {
        &["from", "to", "steps", "log"]
    };
    if let Some(key) = t.keys().find(|k| !allowed.contains(&k.as_str())) {
        return Err(format!(
            "vary.{field}: unknown key `{key}` in {} range (allowed: {})",
            if integer_range {
                "an integer"
            } else {
                "a float"
            },
            allowed.join(", ")
        ));
    }
    let count_limit = |name: &str, min: i64| -> Result<usize, String> {
        match t.get(name) {
            None => Err(format!(
                "vary.{field}: the range needs `{name}`; {SPEC_FORMS}"
            )),
            Some(toml::Value::Integer(n)) if *n >= min && *n as u64 <= MAX_POINTS as u64 => {
                Ok(*n as usize)
            }
            Some(v) => Err(format!(
                "vary.{field}.{name} = {v} is invalid: must be an integer in {min}..={MAX_POINTS}"
            )),
        }
    };
    if integer_range {
        let from = match &t["from"] {
            toml::Value::Integer(i) => *i,
            v => {
                return Err(format!(
                    "vary.{field}.from = {v} is invalid: an integer range {{ from, count }} needs \
                     an integer `from` (for floats give `to` and `steps`)"
                ));
            }
        };
        let count = count_limit("count", 1)?;
        let step = match t.get("step") {
            None => 1,
            Some(toml::Value::Integer(s)) if *s != 0 => *s,
            Some(v) => {
                return Err(format!(
                    "vary.{field}.step = {v} is invalid: must be a non-zero integer"
                ));
            }
        };
        (0..count as i64)
            .map(|k| {
                k.checked_mul(step)
                    .and_then(|d| from.checked_add(d))
                    .map(toml::Value::Integer)
                    .ok_or_else(|| format!("vary.{field}: the range overflows 64-bit integers"))
            })
            .collect()
    } else {
        let number = |name: &str| -> Result<f64, String> {
            let v = match t.get(name) {
                Some(toml::Value::Integer(i)) => *i as f64,
                Some(toml::Value::Float(x)) => *x,
                None => {
                    return Err(format!(
                        "vary.{field}: the range needs `{name}`; {SPEC_FORMS}"
                    ));
                }
                Some(v) => {
                    return Err(format!(
                        "vary.{field}.{name} = {v} is invalid: must be a number"
                    ));
                }
            };
            if v.is_finite() {
                Ok(v)
            } else {
                Err(format!(
                    "vary.{field}.{name} = {v} is invalid: must be a finite number"
                ))
            }
        };
        let (from, to) = (number("from")?, number("to")?);
        let steps = count_limit("steps", 2)?;
        let log = match t.get("log") {
            None => false,
            Some(toml::Value::Boolean(b)) => *b,
            Some(v) => {
                return Err(format!(
                    "vary.{field}.log = {v} is invalid: must be true or false"
                ));
            }
        };
        if log && !(from > 0.0 && to > 0.0) {
            return Err(format!(
                "vary.{field}: a log range needs from > 0 and to > 0 (from = {from}, to = {to})"
            ));
        }
        let last = (steps - 1) as f64;
        Ok((0..steps)
            .map(|i| {
                let x = if i == 0 {
                    from
                } else if i == steps - 1 {
                    to
                } else if log {
                    (from.ln() + (to.ln() - from.ln()) * i as f64 / last).exp()
                } else {
                    from + (to - from) * i as f64 / last
                };
                toml::Value::Float(x)
            })
            .collect())
    }
}

/// Which points of a sweep one process runs: shard `index` of `count` (1-based, like
/// `SLURM_ARRAY_TASK_ID` with `--array=1-N`) runs the points whose index `i` has
/// `i % count == index - 1`. The shards `1/N ..= N/N` are disjoint and cover the sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This shard, in `1..=count`.
    pub index: usize,
    /// The number of shards, ≥ 1.
    pub count: usize,
}

impl Default for Shard {
    fn default() -> Self {
        Self { index: 1, count: 1 }
    }
}

impl Shard {
    /// Whether point `point` belongs to this shard.
    pub fn contains(&self, point: usize) -> bool {
        point % self.count == self.index - 1
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl FromStr for Shard {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let bad = |why: &str| {
            format!(
                "`{s}` is not a shard: {why} (write I/N with 1 ≤ I ≤ N: shards are numbered \
                 1..=N, like SLURM_ARRAY_TASK_ID with --array=1-N)"
            )
        };
        let (i, n) = s
            .split_once('/')
            .ok_or_else(|| bad("expected I/N, e.g. 3/8"))?;
        let i: usize = i
            .trim()
            .parse()
            .map_err(|_| bad("I is not a whole number"))?;
        let n: usize = n
            .trim()
            .parse()
            .map_err(|_| bad("N is not a whole number"))?;
        if n == 0 {
            return Err(bad("N must be at least 1"));
        }
        if i == 0 || i > n {
            return Err(bad(&format!("I = {i} is outside 1..={n}")));
        }
        Ok(Self { index: i, count: n })
    }
}

/// The most worker threads a sweep accepts (the same bound as a run's).
pub use tack::MAX_THREADS;

/// How [`run_sweep`] runs.
#[derive(Debug, Clone, Default)]
pub struct SweepOptions {
    /// Worker threads (points run concurrently); `None`: all cores (rayon's default, which
    /// honours `RAYON_NUM_THREADS`).
    pub threads: Option<usize>,
    /// Which points to run.
    pub shard: Shard,
    /// Command line recorded in the point files (with ` [point i]` appended); default: this
    /// process's.
    pub command_line: Option<String>,
}

/// Progress of a [`run_sweep`]: called from the worker threads as points finish (in any
/// order), so implementations synchronise themselves. The CLI draws a progress bar with it.
pub trait SweepObserver: Sync {
    /// The shard's point count, before any point runs.
    fn on_start(&self, _points: usize) {}
    /// A point finished: run now, found complete, or failed (`failure`).
    fn on_point(&self, _index: usize, _label: &str, _failure: Option<&str>) {}
    /// Asked before each point starts: `true` leaves the remaining points unrun (they count as
    /// neither run nor failed; a rerun resumes them).
    fn cancelled(&self) -> bool {
        false
    }
}

impl SweepObserver for () {}

/// A point that failed, with its error.
#[derive(Debug, Clone, PartialEq)]
pub struct PointFailure {
    /// The point index.
    pub index: usize,
    /// The error message (also in `points/<index>.err`).
    pub message: String,
}

/// What a [`run_sweep`] did.
#[derive(Debug, Clone)]
pub struct SweepReport {
    /// The output directory.
    pub dir: PathBuf,
    /// Points in the whole sweep.
    pub total: usize,
    /// The shard run.
    pub shard: Shard,
    /// Points in this shard.
    pub in_shard: usize,
    /// Points found complete and verified, not run again.
    pub already_complete: usize,
    /// Points run successfully now.
    pub ran: usize,
    /// Points that failed, by index.
    pub failed: Vec<PointFailure>,
    /// Wall time of the run.
    pub wall_time: Duration,
}

impl fmt::Display for SweepReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let shard = if self.shard.count > 1 {
            format!(", shard {}", self.shard)
        } else {
            String::new()
        };
        write!(
            f,
            "sweep {}: {} of {} points{shard}: {} already complete, {} run, {} failed ({:.2} s)",
            self.dir.display(),
            self.in_shard,
            self.total,
            self.already_complete,
            self.ran,
            self.failed.len(),
            self.wall_time.as_secs_f64()
        )
    }
}

/// Width of the zero-padded point index in file names: at least 5 digits, more when the sweep
/// has more than 100 000 points.
pub fn index_width(total: usize) -> usize {
    total.saturating_sub(1).to_string().len().max(5)
}

/// `DIR/points/<index>.<ext>` with the index zero-padded to [`index_width`].
pub fn point_path(dir: &Path, index: usize, total: usize, ext: &str) -> PathBuf {
    let width = index_width(total);
    dir.join(POINTS_DIR).join(format!("{index:0width$}.{ext}"))
}

/// Checks that `path` is a complete result file made from `scene_text` (the scene recorded in
/// the file equals it) and returns it; otherwise the reason.
///
/// A file that does not read back (corrupt, truncated, declaring more data than it holds) is
/// such a reason, never a crash: `tack_io::read_result` checks declared sizes before reading,
/// and a panic while reading is caught and reported, so one bad point file costs that point
/// only (`tack sweep` reruns it, `tack merge` lists it as missing).
pub fn verify_point(path: &Path, scene_text: &str) -> Result<tack_io::RunResult, String> {
    let result = catch_unwind(|| tack_io::read_result(path))
        .map_err(|panic| {
            format!(
                "{}: reading it panicked: {}",
                path.display(),
                panic_message(panic.as_ref())
            )
        })?
        .map_err(|e| e.to_string())?;
    if result.provenance.scene != scene_text {
        return Err(format!(
            "{}: made from another scene than this sweep's point (stale or foreign file)",
            path.display()
        ));
    }
    Ok(result)
}

/// Creates `dir` (and `dir/points`) for `sweep`, or checks that an existing `dir` belongs to
/// it: `dir/sweep.toml` must equal the sweep file and `dir/scene.toml` the base scene.
pub fn prepare_dir(sweep: &Sweep, dir: &Path) -> Result<(), SweepError> {
    let dir_error = |message: String| SweepError::Dir {
        dir: dir.to_owned(),
        message,
    };
    let copy = dir.join(SWEEP_COPY);
    std::fs::create_dir_all(dir).map_err(|cause| SweepError::Fs {
        path: dir.to_owned(),
        what: "creating the directory".into(),
        cause,
    })?;
    if !copy.exists() {
        // Only what `tack sweep` itself writes may be there already (shards starting at the
        // same moment); anything else means the directory is someone else's.
        let entries = std::fs::read_dir(dir).map_err(|cause| SweepError::Fs {
            path: dir.to_owned(),
            what: "listing the directory".into(),
            cause,
        })?;
        let ours = |name: &str| {
            [POINTS_DIR, SWEEP_COPY, SCENE_COPY].contains(&name)
                || [SWEEP_COPY, SCENE_COPY]
                    .iter()
                    .any(|f| name.starts_with(&format!(".{f}.tmp-")))
        };
        if let Some(foreign) = entries
            .filter_map(Result::ok)
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .find(|name| !ours(name))
        {
            return Err(dir_error(format!(
                "exists and is not a sweep directory (no {SWEEP_COPY}, but `{foreign}`); \
                 choose a new or empty output directory"
            )));
        }
    }
    let checks = [
        (
            SWEEP_COPY,
            &sweep.text,
            format!(
                "holds a different sweep: {} differs from {}; use another output directory, or \
                 delete this one to start over",
                copy.display(),
                sweep.origin.display()
            ),
        ),
        (
            SCENE_COPY,
            &sweep.base_text,
            format!(
                "the base scene has changed since this sweep started: {} differs from {}; use \
                 another output directory, or restore the scene",
                dir.join(SCENE_COPY).display(),
                sweep.base_origin.as_ref().map_or_else(
                    || "the sweep's [scene]".to_owned(),
                    |p| p.display().to_string()
                )
            ),
        ),
    ];
    for (name, text, mismatch) in checks {
        let path = dir.join(name);
        if !path.exists() {
            write_text_atomically(&path, text)?;
        }
        if read(&path)? != *text {
            return Err(dir_error(mismatch));
        }
    }
    let points = dir.join(POINTS_DIR);
    std::fs::create_dir_all(&points).map_err(|cause| SweepError::Fs {
        path: points.clone(),
        what: "creating the directory".into(),
        cause,
    })
}

/// Writes `text` to `path` atomically (`tack_io::write_text_atomically`, the one atomic write):
/// `path` holds either its old content or the whole text.
pub fn write_text_atomically(path: &Path, text: &str) -> Result<(), SweepError> {
    Ok(tack_io::write_text_atomically(path, text)?)
}

/// Removes temporaries left in `dir/points` by a killed run for the given points
/// (`.<index>.h5.tmp-*`, `.<index>.err.tmp-*`). Only this shard's points are touched: another
/// shard may be writing its own at this moment.
fn remove_stale_temporaries(dir: &Path, points: &[usize], total: usize) {
    let Ok(entries) = std::fs::read_dir(dir.join(POINTS_DIR)) else {
        return;
    };
    let width = index_width(total);
    let mine: std::collections::HashSet<usize> = points.iter().copied().collect();
    for entry in entries.filter_map(Result::ok) {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(rest) = name.strip_prefix('.') else {
            continue;
        };
        let Some((stem, tail)) = rest.split_once('.') else {
            continue;
        };
        let temporary = tail.starts_with("h5.tmp-") || tail.starts_with("err.tmp-");
        if temporary
            && stem.len() == width
            && stem.parse::<usize>().is_ok_and(|i| mine.contains(&i))
        {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// What happened to one point.
enum PointOutcome {
    AlreadyComplete,
    Ran,
    Failed(String),
}

fn run_point(sweep: &Sweep, dir: &Path, index: usize, command_line: &str) -> PointOutcome {
    let total = sweep.len();
    let h5 = point_path(dir, index, total, "h5");
    let err = point_path(dir, index, total, "err");
    let text = match sweep.point_text(index) {
        Ok(text) => text,
        Err(e) => return fail_point(&h5, &err, e.to_string()),
    };
    if h5.exists() && verify_point(&h5, &text).is_ok() {
        let _ = std::fs::remove_file(&err);
        return PointOutcome::AlreadyComplete;
    }
    let outcome = catch_unwind(AssertUnwindSafe(|| -> Result<(), tack::Error> {
        let scene = Scene::parse(&text, &sweep.base_dir, &[])?;
        let options = RunOptions {
            command_line: Some(format!("{command_line} [point {index}]")),
            richardson: false,
            // Points run concurrently on the sweep's pool; each solve's FFT lanes share it.
            threads: None,
        };
        tack::run_to_file(&scene, &h5, &options, &mut ())?;
        Ok(())
    }));
    match outcome {
        Ok(Ok(())) => {
            let _ = std::fs::remove_file(&err);
            PointOutcome::Ran
        }
        Ok(Err(e)) => fail_point(&h5, &err, format!("{e:#}")),
        Err(panic) => fail_point(
            &h5,
            &err,
            format!("panicked: {}", panic_message(panic.as_ref())),
        ),
    }
}

/// The message a panic carried (`&str` or `String`), else "unknown panic".
fn panic_message(panic: &(dyn std::any::Any + Send)) -> String {
    panic
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".to_owned())
}

/// Records a failure: the (unverified) result file goes, the error file holds the message.
fn fail_point(h5: &Path, err: &Path, message: String) -> PointOutcome {
    let _ = std::fs::remove_file(h5);
    let message = match write_text_atomically(err, &format!("{message}\n")) {
        Ok(()) => message,
        Err(e) => format!("{message} (and the error file could not be written: {e})"),
    };
    PointOutcome::Failed(message)
}

/// Runs the points of `options.shard` that are not complete yet, in parallel, writing
/// `dir/points/<index>.h5` (or `.err`) for each; see the module documentation.
///
/// Complete points (a result file that reads back and records exactly the point's scene) are
/// skipped, so a rerun resumes an interrupted sweep; failed points are run again. A failing
/// point does not stop the others: it is listed in the report and passed to the observer as
/// it happens. Each point is solved sequentially, so results do not depend on the
/// number of threads.
pub fn run_sweep(
    sweep: &Sweep,
    dir: &Path,
    options: &SweepOptions,
    observer: &dyn SweepObserver,
) -> Result<SweepReport, SweepError> {
    let started = Instant::now();
    // The thread count is checked before the directory is touched.
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(n) = options.threads {
        let n = tack::check_threads("--threads", n as i128)
            .map_err(|e| SweepError::Threads(e.to_string()))?;
        builder = builder.num_threads(n);
    }
    prepare_dir(sweep, dir)?;
    let total = sweep.len();
    let shard = options.shard;
    let points: Vec<usize> = (0..total).filter(|&i| shard.contains(i)).collect();
    remove_stale_temporaries(dir, &points, total);
    let pool = builder
        .build()
        .map_err(|e| SweepError::Threads(format!("--threads: {e}")))?;
    let command_line = options
        .command_line
        .clone()
        .unwrap_or_else(tack::command_line);
    observer.on_start(points.len());
    let already = AtomicUsize::new(0);
    let ran = AtomicUsize::new(0);
    let failed = Mutex::new(Vec::new());
    pool.install(|| {
        points.par_iter().with_max_len(1).for_each(|&index| {
            if observer.cancelled() {
                return;
            }
            let label = sweep.label(index);
            match run_point(sweep, dir, index, &command_line) {
                PointOutcome::AlreadyComplete => {
                    already.fetch_add(1, Ordering::Relaxed);
                    observer.on_point(index, &label, None);
                }
                PointOutcome::Ran => {
                    ran.fetch_add(1, Ordering::Relaxed);
                    observer.on_point(index, &label, None);
                }
                PointOutcome::Failed(message) => {
                    observer.on_point(index, &label, Some(&message));
                    let mut failed = failed.lock().unwrap_or_else(|e| e.into_inner());
                    failed.push(PointFailure { index, message });
                }
            }
        });
    });
    let mut failed = failed.into_inner().unwrap_or_else(|e| e.into_inner());
    failed.sort_by_key(|f| f.index);
    Ok(SweepReport {
        dir: dir.to_owned(),
        total,
        shard,
        in_shard: points.len(),
        already_complete: already.into_inner(),
        ran: ran.into_inner(),
        failed,
        wall_time: started.elapsed(),
    })
}

fn read(path: &Path) -> Result<String, SweepError> {
    std::fs::read_to_string(path).map_err(|cause| SweepError::Read {
        path: path.to_owned(),
        cause,
    })
}

fn parent_dir(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_owned(),
        _ => PathBuf::from("."),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = r#"
[material]
e_star = 1.0
gamma = 0.125
[geometry]
shape = "sphere"
radius = 8.0
[grid]
n = 24
dx = 0.6
[protocol]
max_approach = 3.0
load_step = 0.15
"#;

    fn sweep(vary: &str) -> Result<Sweep, SweepError> {
        let text = format!(
            "version = 1\n[vary]\n{vary}\n[scene]\n{}",
            SCENE.replace("\n[", "\n[scene.")
        );
        Sweep::parse_text(&text, Path::new("mem.toml"))
    }

    fn floats(values: &[toml::Value]) -> Vec<f64> {
        values.iter().map(|v| v.as_float().unwrap()).collect()
    }

    #[test]
    fn axes_keep_file_order_not_alphabetical() {
        let s = sweep(
            "roughness.seed = { from = 3, count = 2 }\nmaterial.gamma = [0.1, 0.2, 0.3]\n\
             geometry.radius = [8.0]\nroughness.h = [0.1]\nroughness.kind = [\"random\"]\n\
             roughness.hurst = [0.5]",
        )
        .unwrap();
        let fields: Vec<_> = s.axes.iter().map(|a| a.field.as_str()).collect();
        assert_eq!(
            fields,
            [
                "roughness.seed",
                "material.gamma",
                "geometry.radius",
                "roughness.h",
                "roughness.kind",
                "roughness.hurst"
            ]
        );
        assert_eq!(s.len(), 6);
        // First axis outermost, last fastest.
        assert_eq!(
            s.label(4),
            "roughness.seed = 4, material.gamma = 0.2, geometry.radius = 8.0, roughness.h = 0.1, \
             roughness.kind = \"random\", roughness.hurst = 0.5"
        );
        let text = s.point_text(4).unwrap();
        let scene = Scene::parse(&text, ".", &[]).unwrap();
        assert_eq!(scene.file.material.gamma, 0.2);
        assert!(text.contains("seed = 4"), "{text}");
    }

    #[test]
    fn ranges_expand_exactly() {
        let s = sweep(
            "material.gamma = { from = 0.1, to = 0.5, steps = 5 }\n\
             geometry.radius = { from = 1, to = 100, steps = 3, log = true }\n\
             grid.n = { from = 20, count = 3, step = 4 }",
        )
        .unwrap();
        let g = floats(&s.axes[0].values);
        assert_eq!(g.len(), 5);
        assert_eq!((g[0], g[4]), (0.1, 0.5));
        assert!((g[2] - 0.3).abs() < 1e-15);
        let r = floats(&s.axes[1].values);
        assert_eq!((r[0], r[2]), (1.0, 100.0));
        assert!((r[1] - 10.0).abs() < 1e-12);
        let n: Vec<_> = s.axes[2]
            .values
            .iter()
            .map(|v| v.as_integer().unwrap())
            .collect();
        assert_eq!(n, [20, 24, 28]);
        assert_eq!(s.len(), 45);
    }

    #[test]
    fn bad_sweeps_name_the_field() {
        for (vary, want) in [
            ("", "[vary] is empty"),
            ("material.gamma = []", "vary.material.gamma = []"),
            (
                "material.gamma = 0.1",
                "vary.material.gamma = 0.1 is invalid",
            ),
            (
                "material.gamma = { from = 0.1, to = 1 }",
                "vary.material.gamma: the range needs `steps`",
            ),
            (
                "material.gamma = { from = 0.1, to = 1, steps = 1 }",
                "vary.material.gamma.steps = 1 is invalid",
            ),
            (
                "material.gamma = { from = 0.0, to = 1, steps = 3, log = true }",
                "a log range needs from > 0",
            ),
            (
                "roughness.seed = { from = 0.5, count = 3 }",
                "vary.roughness.seed.from = 0.5 is invalid",
            ),
            (
                "material.gamma = { from = 0.1, to = 1, steps = 3, stride = 2 }",
                "unknown key `stride`",
            ),
            ("material.gama = [0.1, 0.2]", "unknown field `gama`"),
            (
                "material.gamma = [0.1]\n\"material.gamma\" = [0.2]",
                "vary.material.gamma is given twice",
            ),
        ] {
            let e = sweep(vary).unwrap_err().to_string();
            assert!(e.contains(want), "{vary}: {e}");
            assert!(e.starts_with("sweep `mem.toml`: "), "{e}");
        }
        let e = Sweep::parse_text("version = 1\nscene = 3\n[vary]\na = [1]\n", Path::new("x"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("scene = 3 is invalid"), "{e}");
        let e = Sweep::parse_text("version = 2\nfuture = 1\n", Path::new("x"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("version = 2 is not supported"), "{e}");
        let ok = "version = 1\n[vary]\nmaterial.gamma = [0.1]\n[scene]\n";
        let e = Sweep::parse_text(&format!("{ok}\n[extra]\n"), Path::new("x"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("unknown field `extra`"), "{e}");
        let text = format!(
            "version = 1\ncollect = [\"pull_off\"]\n[vary]\nmaterial.gamma = [0.1]\n[scene]\n{}",
            SCENE.replace("\n[", "\n[scene.")
        );
        let e = Sweep::parse_text(&text, Path::new("x"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("collect: `pull_off` is not a summary quantity"),
            "{e}"
        );
    }

    #[test]
    fn zipped_entries_are_one_factor_of_the_product_in_file_order() {
        let s = sweep(
            "material.gamma = [0.1, 0.2]\n\
             \"geometry.radius, protocol.max_approach, grid.n\" = [\n\
               [7.0, 2.5, 22],  # row 0\n\
               [8.0, 3.0, 24],\n\
               [9.0, 3.5, 26],\n\
             ]\n\
             protocol.load_step = [0.1, 0.15]",
        )
        .unwrap();
        let fields: Vec<_> = s.axes.iter().map(|a| a.field.as_str()).collect();
        assert_eq!(
            fields,
            [
                "material.gamma",
                "geometry.radius",
                "protocol.max_approach",
                "grid.n",
                "protocol.load_step"
            ]
        );
        let entries: Vec<_> = s.axes.iter().map(|a| a.entry).collect();
        assert_eq!(entries, [0, 1, 1, 1, 2]);
        // 2 × 3 × 2 points: gamma outermost, the zipped rows in the middle, load_step fastest.
        assert_eq!(s.len(), 12);
        assert_eq!(s.entry_indices(7), [1, 0, 1]);
        assert_eq!(
            s.label(7),
            "material.gamma = 0.2, geometry.radius = 7.0, protocol.max_approach = 2.5, \
             grid.n = 22, protocol.load_step = 0.15"
        );
        for i in 0..s.len() {
            let scene = s.point_scene(i).unwrap().file;
            let (g, row, load) = (i / 6, i / 2 % 3, i % 2);
            assert_eq!(scene.material.gamma, [0.1, 0.2][g], "point {i}");
            // The parsed geometry, as the scene file would write it (`shape`, `radius`).
            let geometry = toml::Value::try_from(scene.geometry).unwrap();
            assert_eq!(geometry.get("shape"), Some(&toml::Value::from("sphere")));
            assert_eq!(
                geometry.get("radius"),
                Some(&toml::Value::from([7.0, 8.0, 9.0][row])),
                "point {i}"
            );
            assert_eq!(geometry.as_table().map(|t| t.len()), Some(2), "point {i}");
            assert_eq!(
                scene.protocol.max_approach,
                Some([2.5, 3.0, 3.5][row]),
                "point {i}"
            );
            assert_eq!(scene.grid.n, Some([22, 24, 26][row]), "point {i}");
            assert_eq!(
                scene.protocol.load_step,
                Some([0.1, 0.15][load]),
                "point {i}"
            );
            // Fields outside [vary] are the base scene's.
            assert_eq!(scene.grid.dx, Some(0.6));
        }
        // A zipped entry alone (spaces after the commas are optional).
        let s = sweep("\"material.gamma,material.e_star\" = [[0.1, 1.0], [0.2, 2.0]]").unwrap();
        assert_eq!(s.len(), 2);
        let scene = s.point_scene(1).unwrap().file;
        assert_eq!((scene.material.gamma, scene.material.e_star), (0.2, 2.0));
    }

    #[test]
    fn bad_zipped_entries_name_the_file_and_the_fields() {
        for (vary, want) in [
            (
                "\"material.gamma, geometry.radius\" = [[0.1, 7.0], [0.2]]",
                "vary.\"material.gamma, geometry.radius\": row 1 has 1 values but the entry \
                 names 2 fields (material.gamma, geometry.radius)",
            ),
            (
                "\"material.gamma, geometry.radius\" = [[0.1, 7.0, 3]]",
                "row 0 has 3 values but the entry names 2 fields",
            ),
            (
                "\"material.gamma, geometry.radius\" = [0.1, 0.2]",
                "vary.\"material.gamma, geometry.radius\": row 0 = 0.1 is invalid: must be a \
                 list of 2 values",
            ),
            (
                "\"material.gamma, geometry.radius\" = []",
                "vary.\"material.gamma, geometry.radius\" = []: give at least one row",
            ),
            (
                "\"material.gamma, geometry.radius\" = { from = 0.1, to = 0.2, steps = 2 }",
                "is invalid: must be a list of rows with one value per field",
            ),
            (
                "\"material.gamma, \" = [[0.1, 0.2]]",
                "field 2 of the zipped entry is empty",
            ),
            (
                "material.\"gamma, e_star\" = [[0.1, 1.0]]",
                "a zipped entry must be one quoted key directly under [vary]",
            ),
            (
                "material.gamma = [0.1]\n\"geometry.radius, material.gamma\" = [[7.0, 0.2]]",
                "vary.material.gamma is given twice",
            ),
            (
                "\"material.gamma, material.gama\" = [[0.1, 0.2]]",
                "unknown field `gama`",
            ),
        ] {
            let e = sweep(vary).unwrap_err().to_string();
            assert!(e.contains(want), "{vary}: {e}");
            assert!(e.starts_with("sweep `mem.toml`: "), "{e}");
        }
    }

    #[test]
    fn shards_parse_and_partition() {
        assert_eq!("3/8".parse::<Shard>(), Ok(Shard { index: 3, count: 8 }));
        for bad in ["5/4", "0/4", "1/0", "1", "a/2", "-1/2"] {
            let e = bad.parse::<Shard>().unwrap_err();
            assert!(e.contains(&format!("`{bad}` is not a shard")), "{e}");
        }
        let shards: Vec<Shard> = (1..=4).map(|i| Shard { index: i, count: 4 }).collect();
        for point in 0..23 {
            assert_eq!(shards.iter().filter(|s| s.contains(point)).count(), 1);
        }
    }

    #[test]
    fn point_files_are_zero_padded() {
        let p = point_path(Path::new("out"), 42, 100, "h5");
        assert_eq!(p, Path::new("out/points/00042.h5"));
        assert_eq!(index_width(1_000_001), 7);
    }
}
