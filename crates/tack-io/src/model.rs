//! The plain data model of a result file, filled by the CLI from the solver's states.

use std::collections::BTreeMap;
use std::path::Path;

use ndarray::Array2;

use crate::IoError;

/// Where a result came from: written as root attributes of every result file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Provenance {
    /// `tack` version that produced the file.
    pub tack_version: String,
    /// Git revision of the source tree, or `unknown`.
    pub git_revision: String,
    /// The command line that produced the file.
    pub command_line: String,
    /// The full scene TOML the run was made from.
    pub scene: String,
    /// Creation time, RFC 3339 in UTC.
    pub created: String,
    /// Seed of the random surface, when the scene has one.
    pub seed: Option<u64>,
}

impl Provenance {
    /// Provenance of the current process with a caller-supplied revision and timestamp; `scene`
    /// starts empty and `seed` unset (fill them with struct-update syntax).
    pub fn current(git_revision: impl Into<String>, created: impl Into<String>) -> Self {
        Self {
            tack_version: env!("CARGO_PKG_VERSION").to_owned(),
            git_revision: git_revision.into(),
            command_line: std::env::args().collect::<Vec<_>>().join(" "),
            scene: String::new(),
            created: created.into(),
            seed: None,
        }
    }
}

/// The force–approach curve: one entry per step of the approach path in every column.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Curve {
    /// Rigid approach `d` (positive = pressing).
    pub approach: Vec<f64>,
    /// Total force (positive = compressive).
    pub force: Vec<f64>,
    /// Contact area.
    pub area: Vec<f64>,
    /// Number of bonded (in-contact) elements.
    pub n_bonded: Vec<u64>,
    /// Number of connected contact clusters.
    pub n_clusters: Vec<u64>,
    /// Conjugate-gradient iterations of the solve (under a smooth law, its operator products:
    /// Newton's Krylov iterations, line-search trials and the landings' CG iterations).
    pub iterations: Vec<u64>,
    /// Outer (active-set / detachment) iterations of the solve.
    pub active_set_iterations: Vec<u64>,
    /// Whether the solve converged within its caps.
    pub converged: Vec<bool>,
    /// Mean pressure over the grid, when recorded.
    pub mean_pressure: Option<Vec<f64>>,
    /// Whether the step is in periodic full contact, whose force and mean pressure are the
    /// least admissible ones (a bound), not a state's; `None` in files written before the
    /// column existed.
    pub full_contact: Option<Vec<bool>>,
    /// The per-step columns the run's adhesion law declares (the Dugdale law's cohesive zone
    /// and a smooth law's process zone: `n_cohesive`); none for the zero-range criterion.
    pub law_columns: Vec<LawColumn>,
    /// Viscoelastic solids: the time at the end of each step; `None` for elastic solids and in
    /// files written before the column existed.
    pub time: Option<Vec<f64>>,
}

/// A per-step count column declared by the run's adhesion law: `/curve/<name>`, with what it
/// counts in its `law_column` attribute.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct LawColumn {
    /// The column's name: lower-case letters, digits and `_`, not a fixed column's name.
    pub name: String,
    /// What it counts, in a sentence (empty in files written before columns carried it).
    pub meaning: String,
    /// One count per step.
    pub values: Vec<u64>,
}

/// The columns every curve has, `approach` first.
pub(crate) const FIXED_COLUMNS: [&str; 8] = [
    "approach",
    "force",
    "area",
    "n_bonded",
    "n_clusters",
    "iterations",
    "active_set_iterations",
    "converged",
];

/// The optional columns tack itself writes.
pub(crate) const OPTIONAL_COLUMNS: [&str; 3] = ["mean_pressure", "full_contact", "time"];

impl Curve {
    /// The law's column `name`, if the curve has it.
    pub fn law_column(&self, name: &str) -> Option<&LawColumn> {
        self.law_columns.iter().find(|c| c.name == name)
    }

    /// Number of steps (the length of `approach`).
    pub fn len(&self) -> usize {
        self.approach.len()
    }

    /// Whether the curve has no steps.
    pub fn is_empty(&self) -> bool {
        self.approach.is_empty()
    }

    /// Name and length of every present column, `approach` first.
    pub(crate) fn column_lengths(&self) -> Vec<(&str, usize)> {
        let mut cols = vec![
            ("approach", self.approach.len()),
            ("force", self.force.len()),
            ("area", self.area.len()),
            ("n_bonded", self.n_bonded.len()),
            ("n_clusters", self.n_clusters.len()),
            ("iterations", self.iterations.len()),
            ("active_set_iterations", self.active_set_iterations.len()),
            ("converged", self.converged.len()),
        ];
        if let Some(p) = &self.mean_pressure {
            cols.push(("mean_pressure", p.len()));
        }
        if let Some(f) = &self.full_contact {
            cols.push(("full_contact", f.len()));
        }
        if let Some(t) = &self.time {
            cols.push(("time", t.len()));
        }
        for c in &self.law_columns {
            cols.push((c.name.as_str(), c.values.len()));
        }
        cols
    }

    /// Checks that every law column has a name of lower-case letters, digits and `_` that no
    /// other column has.
    pub(crate) fn check_law_columns(&self, path: &Path) -> Result<(), IoError> {
        for (k, c) in self.law_columns.iter().enumerate() {
            let well_formed = !c.name.is_empty()
                && c.name
                    .bytes()
                    .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'_');
            let taken = FIXED_COLUMNS.contains(&c.name.as_str())
                || OPTIONAL_COLUMNS.contains(&c.name.as_str())
                || self.law_columns[..k].iter().any(|o| o.name == c.name);
            if !well_formed || taken {
                return Err(IoError::Invalid {
                    path: path.to_owned(),
                    what: format!(
                        "law column `{}`: a name of lower-case letters, digits and `_` that no \
                         other curve column has is required",
                        c.name
                    ),
                });
            }
        }
        Ok(())
    }

    /// Checks that every column has the length of `approach`.
    pub(crate) fn check_lengths(&self, path: &Path) -> Result<(), IoError> {
        let expected = self.len();
        match self
            .column_lengths()
            .into_iter()
            .find(|&(_, len)| len != expected)
        {
            Some((column, len)) => Err(IoError::ColumnLength {
                path: path.to_owned(),
                column: column.to_owned(),
                len,
                expected,
            }),
            None => Ok(()),
        }
    }
}

/// The contact configuration at one step of the curve.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    /// Index into the curve; also the group name under `/snapshots`.
    pub step: usize,
    /// Approach at this step.
    pub approach: f64,
    /// Element pressures `(nx, ny)`.
    pub pressure: Array2<f64>,
    /// Bonded (in-contact) elements `(nx, ny)`, stored as u8 0/1.
    pub bonded: Array2<bool>,
}

impl Snapshot {
    /// Checks that the step indexes a curve of `curve_len` steps and the arrays agree in shape.
    pub(crate) fn check(&self, curve_len: usize, path: &Path) -> Result<(), IoError> {
        let what = if self.step >= curve_len {
            format!(
                "snapshot step {} is beyond the curve's {curve_len} steps",
                self.step
            )
        } else if self.pressure.dim() != self.bonded.dim() {
            format!(
                "snapshot {}: `pressure` is {:?} but `bonded` is {:?}",
                self.step,
                self.pressure.dim(),
                self.bonded.dim()
            )
        } else {
            return Ok(());
        };
        Err(IoError::Invalid {
            path: path.to_owned(),
            what,
        })
    }
}

/// Scalar results of a run, written as attributes of `/summary`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Summary {
    /// Pull-off force (the most tensile force of the curve).
    pub pull_off_force: f64,
    /// JKR pull-off force of the smooth sphere.
    pub f_jkr: f64,
    /// `pull_off_force / f_jkr`.
    pub pull_off_ratio: f64,
    /// Johnson's adhesion parameter α, when the surface is a single waviness.
    pub johnson_alpha: Option<f64>,
    /// The roughness parameter α*, when the surface is random.
    pub alpha_star: Option<f64>,
    /// Further named scalars; names must differ from the fields above. Read back in name order.
    pub extra: BTreeMap<String, f64>,
    /// How the run ended ([`Summary::COMPLETE`], [`Summary::STOPPED_AT_MAX_STEPS`], ...), the
    /// string attribute `status`; `None` in files written before it existed.
    pub status: Option<String>,
    /// The adhesion law, the string attribute `adhesion_model` (`jkr_limit`, `dugdale`,
    /// `exponential`, `lennard_jones`, or the name of a custom law given in memory); `None`
    /// in files written before it existed (the zero-range criterion).
    pub adhesion_model: Option<String>,
    /// What makes the result less than trustworthy (under-resolved pull-off, pull-off not
    /// bracketed by the path, a closed-form reference that does not apply, ...), one sentence
    /// each; the string attribute `warnings`, one per line (empty: none).
    pub warnings: Vec<String>,
}

impl Summary {
    /// `status` of a path that ran to its end (contact lost, or `retract_to` reached).
    pub const COMPLETE: &'static str = "complete";
    /// `status` of a path stopped by `protocol.max_steps` before it ended: the pull-off may lie
    /// beyond the last step.
    pub const STOPPED_AT_MAX_STEPS: &'static str =
        concat!("stopped at ", tack_fields::field_name!(protocol.max_steps));

    /// Names of the attributes modelled by fields, which `extra` may not use.
    pub(crate) const RESERVED: [&'static str; 8] = [
        "pull_off_force",
        "f_jkr",
        "pull_off_ratio",
        "johnson_alpha",
        "alpha_star",
        "status",
        "adhesion_model",
        "warnings",
    ];

    /// Whether the run ended as planned (`status` is [`Summary::COMPLETE`]; files without a
    /// status count as complete).
    pub fn is_complete(&self) -> bool {
        self.status.as_deref().is_none_or(|s| s == Self::COMPLETE)
    }

    /// Every attribute to write: the fields that are set, then `extra`.
    pub(crate) fn attributes(&self) -> Vec<(&str, f64)> {
        let optional = [
            ("johnson_alpha", self.johnson_alpha),
            ("alpha_star", self.alpha_star),
        ];
        [
            ("pull_off_force", self.pull_off_force),
            ("f_jkr", self.f_jkr),
            ("pull_off_ratio", self.pull_off_ratio),
        ]
        .into_iter()
        .chain(optional.into_iter().filter_map(|(n, v)| Some((n, v?))))
        .chain(self.extra.iter().map(|(n, &v)| (n.as_str(), v)))
        .collect()
    }
}

/// Everything a result file holds.
#[derive(Debug, Clone, PartialEq)]
pub struct RunResult {
    /// Root attributes.
    pub provenance: Provenance,
    /// `/curve`.
    pub curve: Curve,
    /// `/surface/heights` `(nx, ny)` and its `dx`, when asked for.
    pub surface: Option<(Array2<f64>, f64)>,
    /// `/surface/gamma` `(nx, ny)`: the work of adhesion per element, when it varies over the
    /// surface (written only with [`RunResult::surface`], and of its shape).
    pub gamma: Option<Array2<f64>>,
    /// `/snapshots/<step>`, in any order when writing; read back sorted by step.
    pub snapshots: Vec<Snapshot>,
    /// `/summary`.
    pub summary: Summary,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn current_records_version_and_command_line() {
        let p = Provenance::current("abc123", "2026-01-01T00:00:00Z");
        assert_eq!(p.tack_version, env!("CARGO_PKG_VERSION"));
        assert_eq!(p.git_revision, "abc123");
        assert!(!p.command_line.is_empty());
        assert!(p.scene.is_empty() && p.seed.is_none());
    }

    #[test]
    fn summary_writes_only_set_attributes() {
        let mut s = Summary {
            pull_off_force: -1.0,
            f_jkr: 2.0,
            pull_off_ratio: 0.5,
            alpha_star: Some(0.3),
            ..Summary::default()
        };
        s.extra.insert("w".into(), 0.1);
        let names: Vec<_> = s.attributes().into_iter().map(|(n, _)| n).collect();
        assert_eq!(
            names,
            [
                "pull_off_force",
                "f_jkr",
                "pull_off_ratio",
                "alpha_star",
                "w"
            ]
        );
    }
}
