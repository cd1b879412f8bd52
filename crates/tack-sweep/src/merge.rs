//! Merging a sweep's output directory into one table (`tack merge`): the varied parameters and
//! the collected summary quantities of every point, with the status of each point (complete,
//! incomplete, failed, missing) and its result's warnings, so that nothing is silently dropped
//! and no untrustworthy point passes as plain ok.

use std::fmt;
use std::path::Path;

use tack::summary_quantity;
use tack_io::{
    POINT_FAILED, POINT_INCOMPLETE, POINT_MISSING, POINT_OK, ParameterColumn, SweepTable,
};

use crate::sweep::{Axis, Sweep, SweepError, point_path, verify_point};

/// How [`merge`] behaves.
#[derive(Debug, Clone, Default)]
pub struct MergeOptions {
    /// Write the table even when points are missing (their rows have status 2 and NaN results).
    pub allow_missing: bool,
    /// Command line to record; default: this process's.
    pub command_line: Option<String>,
}

/// A point that failed or is missing, for the report.
#[derive(Debug, Clone, PartialEq)]
pub struct PointIssue {
    /// The point index.
    pub index: usize,
    /// Its varied values, `field = value, ...`.
    pub label: String,
    /// The error of a failed point, or why the point counts as missing.
    pub message: String,
}

/// What [`merge`] found and did.
#[derive(Debug, Clone)]
pub struct MergeReport {
    /// Points in the sweep.
    pub total: usize,
    /// Complete points (results whose `/summary` status is complete).
    pub ok: usize,
    /// Points whose result is there but whose `/summary` status is not complete (stopped at
    /// `protocol.max_steps`): the status and warnings, in the table with status
    /// [`POINT_INCOMPLETE`].
    pub incomplete: Vec<PointIssue>,
    /// Points (complete or incomplete) whose result carries warnings.
    pub with_warnings: usize,
    /// Failed points, with their errors.
    pub failed: Vec<PointIssue>,
    /// Missing points, with the reason.
    pub missing: Vec<PointIssue>,
    /// Whether the table was written (not when points are missing without `allow_missing`).
    pub written: bool,
}

impl MergeReport {
    /// One line per incomplete, failed or missing point (`point 3 (material.e_star = -1)
    /// failed: ...`, `point 5 (...) is incomplete: stopped at protocol.max_steps; ...`).
    pub fn issues(&self) -> String {
        let incomplete = self.incomplete.iter().map(|p| (p, "is incomplete"));
        let failed = self.failed.iter().map(|p| (p, "failed"));
        let missing = self.missing.iter().map(|p| (p, "is missing"));
        incomplete
            .chain(failed)
            .chain(missing)
            .map(|(p, what)| {
                format!(
                    "point {} ({}) {what}: {}\n",
                    p.index,
                    p.label,
                    p.message.trim_end()
                )
            })
            .collect()
    }
}

impl fmt::Display for MergeReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} points: {} complete, ", self.total, self.ok)?;
        if !self.incomplete.is_empty() {
            write!(
                f,
                "{} incomplete (status not complete: see /point/result_status), ",
                self.incomplete.len()
            )?;
        }
        write!(
            f,
            "{} failed, {} missing",
            self.failed.len(),
            self.missing.len()
        )?;
        if self.with_warnings > 0 {
            write!(
                f,
                "; {} with warnings (see /point/warnings)",
                self.with_warnings
            )?;
        }
        Ok(())
    }
}

/// Gathers the per-point summaries of the sweep in `dir` into the sweep table `out` (written
/// atomically; layout in `tack_io`'s documentation).
///
/// A point is complete when `points/<index>.h5` reads back, records exactly the point's scene
/// and its `/summary` status is complete; incomplete when such a result has another status
/// (its results are filled in, its row has status [`POINT_INCOMPLETE`]); failed when its `points/<index>.err` exists instead; missing otherwise (never run, or
/// a stale or unreadable result). Failed and missing points get NaN results and are listed in
/// the report. With missing points and without `allow_missing` nothing is written.
pub fn merge(dir: &Path, out: &Path, options: &MergeOptions) -> Result<MergeReport, SweepError> {
    if let Some(kind) = tack_io::not_a_regular_file(out) {
        return Err(tack_io::IoError::Invalid {
            path: out.to_owned(),
            what: format!("{kind}: refusing to replace it (name a regular file or a new path)"),
        }
        .into());
    }
    let sweep = Sweep::open_dir(dir)?;
    let total = sweep.len();
    let mut status = Vec::with_capacity(total);
    let mut errors = Vec::with_capacity(total);
    let mut result_status = Vec::with_capacity(total);
    let mut warnings = Vec::with_capacity(total);
    let mut results: Vec<Vec<f64>> = vec![Vec::with_capacity(total); sweep.collect.len()];
    let mut report = MergeReport {
        total,
        ok: 0,
        incomplete: Vec::new(),
        with_warnings: 0,
        failed: Vec::new(),
        missing: Vec::new(),
        written: false,
    };
    for index in 0..total {
        let h5 = point_path(dir, index, total, "h5");
        let err = point_path(dir, index, total, "err");
        let verified = sweep
            .point_text(index)
            .map_err(|e| e.to_string())
            .and_then(|text| {
                if h5.exists() {
                    verify_point(&h5, &text).map(Some)
                } else {
                    Ok(None)
                }
            });
        let issue = |message: String| PointIssue {
            index,
            label: sweep.label(index),
            message,
        };
        let (code, message) = match verified {
            Ok(Some(result)) => {
                let summary = &result.summary;
                for (column, name) in results.iter_mut().zip(&sweep.collect) {
                    column.push(summary_quantity(summary, name));
                }
                let status = summary
                    .status
                    .clone()
                    .unwrap_or_else(|| tack_io::Summary::COMPLETE.to_owned());
                if !summary.warnings.is_empty() {
                    report.with_warnings += 1;
                }
                result_status.push(status.clone());
                warnings.push(summary.warnings.join("\n"));
                if summary.is_complete() {
                    report.ok += 1;
                    (POINT_OK, String::new())
                } else {
                    let mut message = format!("status `{status}`");
                    for w in &summary.warnings {
                        message.push_str("; ");
                        message.push_str(w);
                    }
                    report.incomplete.push(issue(message));
                    (POINT_INCOMPLETE, String::new())
                }
            }
            other => {
                result_status.push(String::new());
                warnings.push(String::new());
                results.iter_mut().for_each(|c| c.push(f64::NAN));
                if err.is_file() {
                    let message = std::fs::read_to_string(&err)
                        .map(|m| m.trim_end().to_owned())
                        .unwrap_or_else(|e| format!("{}: unreadable: {e}", err.display()));
                    report.failed.push(issue(message.clone()));
                    (POINT_FAILED, message)
                } else {
                    let message = match other {
                        Err(reason) => reason,
                        _ => format!(
                            "no result file {} and no error file: the point has not run",
                            h5.display()
                        ),
                    };
                    report.missing.push(issue(message.clone()));
                    (POINT_MISSING, message)
                }
            }
        };
        status.push(code);
        errors.push(message);
    }
    if !report.missing.is_empty() && !options.allow_missing {
        return Ok(report);
    }
    let command_line = options
        .command_line
        .clone()
        .unwrap_or_else(tack::command_line);
    let table = SweepTable {
        sweep: sweep.text.clone(),
        provenance: tack_io::Provenance {
            tack_version: tack::VERSION.to_owned(),
            git_revision: tack::GIT_REVISION.to_owned(),
            command_line,
            scene: sweep.base_text.clone(),
            created: tack::now_rfc3339(),
            seed: None,
        },
        index: (0..total as u64).collect(),
        status,
        error: errors,
        result_status,
        warnings,
        parameters: sweep
            .axes
            .iter()
            .map(|axis| (axis.field.clone(), parameter_column(&sweep, axis)))
            .collect(),
        results: sweep.collect.iter().cloned().zip(results).collect(),
    };
    tack_io::write_sweep_table(out, &table)?;
    report.written = true;
    Ok(report)
}

/// The values of `axis` at every point: i64 when all its values are integers, f64 when all are
/// numbers, else text (strings unquoted, other values as TOML).
fn parameter_column(sweep: &Sweep, axis: &Axis) -> ParameterColumn {
    let position = sweep
        .axes
        .iter()
        .position(|a| a.field == axis.field)
        .unwrap_or(0);
    let values: Vec<&toml::Value> = (0..sweep.len())
        .map(|i| sweep.point_values(i)[position].1)
        .collect();
    if values.iter().all(|v| v.is_integer()) {
        ParameterColumn::Integer(values.iter().filter_map(|v| v.as_integer()).collect())
    } else if values.iter().all(|v| v.is_integer() || v.is_float()) {
        ParameterColumn::Float(
            values
                .iter()
                .map(|v| {
                    v.as_float()
                        .or(v.as_integer().map(|i| i as f64))
                        .unwrap_or(f64::NAN)
                })
                .collect(),
        )
    } else {
        ParameterColumn::Text(
            values
                .iter()
                .map(|v| match v {
                    toml::Value::String(s) => s.clone(),
                    other => other.to_string(),
                })
                .collect(),
        )
    }
}
