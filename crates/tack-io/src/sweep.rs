//! Sweep tables: the merged summary of a parameter sweep (`tack merge`), one row per point.
//!
//! The layout is documented at the crate root.

use std::path::Path;

use hdf5::types::{TypeDescriptor, VarLenUnicode};
use hdf5::{File, Group, Location};
use ndarray::Array1;

use crate::h5::{
    Budget, check_extent, create_group, h5err, open_group, read_dataset, read_str_attr,
    write_str_attr,
};
use crate::write::write_atomically;
use crate::{IoError, Provenance};

/// `/point/status` of a point whose result file is complete and matches the sweep.
pub const POINT_OK: u8 = 0;
/// `/point/status` of a point whose run failed (its error is in `/point/error`).
pub const POINT_FAILED: u8 = 1;
/// `/point/status` of a point with no (valid) result and no recorded failure.
pub const POINT_MISSING: u8 = 2;
/// `/point/status` of a point whose result file is present and matches the sweep, but whose
/// `/summary` status is not complete (e.g. stopped at `protocol.max_steps`): its results are
/// those of the incomplete path, and `/point/result_status` says how it ended.
pub const POINT_INCOMPLETE: u8 = 3;

/// The values of one varied field, one per point.
#[derive(Debug, Clone, PartialEq)]
pub enum ParameterColumn {
    /// Every value is a TOML integer: stored as i64.
    Integer(Vec<i64>),
    /// Numbers (at least one float): stored as f64.
    Float(Vec<f64>),
    /// Anything else (strings, booleans, tables): stored as text, strings unquoted and other
    /// values in TOML inline form.
    Text(Vec<String>),
}

impl ParameterColumn {
    /// Number of points in the column.
    pub fn len(&self) -> usize {
        match self {
            Self::Integer(v) => v.len(),
            Self::Float(v) => v.len(),
            Self::Text(v) => v.len(),
        }
    }

    /// Whether the column is empty.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Everything a sweep table holds (see the module documentation for the layout).
#[derive(Debug, Clone, PartialEq)]
pub struct SweepTable {
    /// The sweep file's TOML (root attribute `sweep`).
    pub sweep: String,
    /// Root attributes `tack_version`, `git_revision`, `command_line`, `created`, and `scene`
    /// (the base scene's TOML); `seed` is not written (points may differ in seed).
    pub provenance: Provenance,
    /// `/point/index`: the point index of every row.
    pub index: Vec<u64>,
    /// `/point/status`: [`POINT_OK`], [`POINT_FAILED`], [`POINT_MISSING`] or
    /// [`POINT_INCOMPLETE`] per row.
    pub status: Vec<u8>,
    /// `/point/error`: the error or absence reason per row, empty for complete points.
    pub error: Vec<String>,
    /// `/point/result_status`: the `/summary` status of the point's result (`complete`,
    /// `stopped at protocol.max_steps`, ...), empty where there is no result (failed, missing).
    /// Tables written before the column existed read back with empty entries.
    pub result_status: Vec<String>,
    /// `/point/warnings`: the `/summary` warnings of the point's result, one per line, empty
    /// where there are none (or no result). Read back empty from older tables.
    pub warnings: Vec<String>,
    /// `/parameters/<field>`, in sweep order.
    pub parameters: Vec<(String, ParameterColumn)>,
    /// `/results/<name>`, in the sweep's `collect` order.
    pub results: Vec<(String, Vec<f64>)>,
}

impl SweepTable {
    /// Number of rows (points).
    pub fn len(&self) -> usize {
        self.index.len()
    }

    /// Whether the table has no rows.
    pub fn is_empty(&self) -> bool {
        self.index.is_empty()
    }

    /// Checks that every column has one entry per row and names are usable HDF5 names.
    fn check(&self, path: &Path) -> Result<(), IoError> {
        let invalid = |what: String| IoError::Invalid {
            path: path.to_owned(),
            what,
        };
        let n = self.len();
        let columns = [
            ("/point/status", self.status.len()),
            ("/point/error", self.error.len()),
            ("/point/result_status", self.result_status.len()),
            ("/point/warnings", self.warnings.len()),
        ]
        .into_iter()
        .map(|(name, len)| (name.to_owned(), len))
        .chain(
            self.parameters
                .iter()
                .map(|(name, c)| (format!("/parameters/{name}"), c.len())),
        )
        .chain(
            self.results
                .iter()
                .map(|(name, c)| (format!("/results/{name}"), c.len())),
        );
        for (name, len) in columns {
            if len != n {
                return Err(invalid(format!(
                    "`{name}` has {len} entries, but `/point/index` has {n}"
                )));
            }
        }
        let groups = [
            (
                "/parameters",
                self.parameters.iter().map(|(n, _)| n).collect::<Vec<_>>(),
            ),
            ("/results", self.results.iter().map(|(n, _)| n).collect()),
        ];
        for (group, names) in groups {
            let mut seen = std::collections::HashSet::new();
            for name in names {
                if name.is_empty() || name == "." || name.contains('/') {
                    return Err(invalid(format!(
                        "`{name}` cannot name a dataset of `{group}` (empty, `.`, or containing `/`)"
                    )));
                }
                if !seen.insert(name) {
                    return Err(invalid(format!("`{group}/{name}` appears more than once")));
                }
            }
        }
        Ok(())
    }
}

/// Writes `table` to `path` (temporary file + rename, like [`crate::write_result`]).
///
/// Errors: columns whose length differs from `index`, names that cannot be HDF5 names (empty,
/// `.`, containing `/`), duplicate names, a missing parent directory, HDF5 or file-system
/// failures.
pub fn write_sweep_table(path: &Path, table: &SweepTable) -> Result<(), IoError> {
    table.check(path)?;
    write_atomically(path, |tmp| {
        let file = File::create(tmp).map_err(h5err(
            path,
            format!("creating the temporary `{}`", tmp.display()),
        ))?;
        let p = &table.provenance;
        for (name, value) in [
            ("sweep", &table.sweep),
            ("scene", &p.scene),
            ("tack_version", &p.tack_version),
            ("git_revision", &p.git_revision),
            ("command_line", &p.command_line),
            ("created", &p.created),
        ] {
            write_str_attr(&file, name, value, path)?;
        }
        let point = create_group(&file, "point", path)?;
        write_column(&point, "index", &table.index, path)?;
        write_column(&point, "status", &table.status, path)?;
        write_text_column(&point, "error", &table.error, path)?;
        write_text_column(&point, "result_status", &table.result_status, path)?;
        write_text_column(&point, "warnings", &table.warnings, path)?;
        let parameters = create_group(&file, "parameters", path)?;
        for (name, column) in &table.parameters {
            match column {
                ParameterColumn::Integer(v) => write_column(&parameters, name, v, path)?,
                ParameterColumn::Float(v) => write_column(&parameters, name, v, path)?,
                ParameterColumn::Text(v) => write_text_column(&parameters, name, v, path)?,
            }
        }
        let fields: Vec<&str> = table.parameters.iter().map(|(n, _)| n.as_str()).collect();
        write_str_list_attr(&parameters, "fields", &fields, path)?;
        let results = create_group(&file, "results", path)?;
        for (name, values) in &table.results {
            write_column(&results, name, values, path)?;
        }
        let names: Vec<&str> = table.results.iter().map(|(n, _)| n.as_str()).collect();
        write_str_list_attr(&results, "names", &names, path)?;
        file.close().map_err(h5err(path, "closing the file"))
    })
}

/// Reads a sweep table written by [`write_sweep_table`]; parameters and results come back in
/// the order of the `fields` and `names` attributes.
///
/// Like [`crate::read_result`], every column's declared size is checked before it is read
/// (together at most the file's size, each at most [`crate::MAX_DATASET_BYTES`] in memory), so
/// a corrupt table gives [`IoError::Oversized`], never an allocation failure.
pub fn read_sweep_table(path: &Path) -> Result<SweepTable, IoError> {
    if !path.is_file() {
        return Err(IoError::MissingFile {
            path: path.to_owned(),
        });
    }
    let file = File::open(path).map_err(h5err(path, "opening as an HDF5 file"))?;
    let budget = &mut Budget::of_file(path)?;
    let provenance = Provenance {
        tack_version: read_str_attr(&file, "tack_version", path)?,
        git_revision: read_str_attr(&file, "git_revision", path)?,
        command_line: read_str_attr(&file, "command_line", path)?,
        scene: read_str_attr(&file, "scene", path)?,
        created: read_str_attr(&file, "created", path)?,
        seed: None,
    };
    let point = open_group(&file, "point", path)?;
    let parameters_group = open_group(&file, "parameters", path)?;
    let parameters = read_str_list_attr(&parameters_group, "fields", path, budget)?
        .into_iter()
        .map(|name| {
            let column = read_parameter(&parameters_group, &name, path, budget)?;
            Ok((name, column))
        })
        .collect::<Result<_, IoError>>()?;
    let results_group = open_group(&file, "results", path)?;
    let results = read_str_list_attr(&results_group, "names", path, budget)?
        .into_iter()
        .map(|name| {
            let values = read_vec(&results_group, &name, path, budget)?;
            Ok((name, values))
        })
        .collect::<Result<_, IoError>>()?;
    let index: Vec<u64> = read_vec(&point, "index", path, budget)?;
    // Columns added later: absent in older tables, read back as empty text.
    let optional_text = |name: &str, budget: &mut Budget| {
        if point.link_exists(name) {
            read_text(&point, name, path, budget)
        } else {
            Ok(vec![String::new(); index.len()])
        }
    };
    let result_status = optional_text("result_status", budget)?;
    let warnings = optional_text("warnings", budget)?;
    let table = SweepTable {
        sweep: read_str_attr(&file, "sweep", path)?,
        provenance,
        status: read_vec(&point, "status", path, budget)?,
        error: read_text(&point, "error", path, budget)?,
        index,
        result_status,
        warnings,
        parameters,
        results,
    };
    table.check(path)?;
    Ok(table)
}

fn write_column<T: hdf5::H5Type + Clone>(
    group: &Group,
    name: &str,
    values: &[T],
    path: &Path,
) -> Result<(), IoError> {
    crate::h5::write_dataset(group, name, values.into(), path).map(drop)
}

fn to_varlen(
    values: &[impl AsRef<str>],
    what: &str,
    path: &Path,
) -> Result<Vec<VarLenUnicode>, IoError> {
    values
        .iter()
        .map(|v| {
            v.as_ref().parse().map_err(|_| IoError::Invalid {
                path: path.to_owned(),
                what: format!("{what} contains a NUL character"),
            })
        })
        .collect()
}

fn write_text_column(
    group: &Group,
    name: &str,
    values: &[String],
    path: &Path,
) -> Result<(), IoError> {
    let full = crate::h5::member(group, name);
    let data = Array1::from(to_varlen(values, &format!("`{full}`"), path)?);
    write_column(group, name, data.as_slice().unwrap_or_default(), path)
}

fn write_str_list_attr(
    loc: &Location,
    name: &str,
    values: &[&str],
    path: &Path,
) -> Result<(), IoError> {
    let data = Array1::from(to_varlen(values, &format!("attribute `{name}`"), path)?);
    loc.new_attr_builder()
        .with_data(&data)
        .create(name)
        .map(drop)
        .map_err(h5err(
            path,
            format!("writing attribute `{name}` of `{}`", loc.name()),
        ))
}

fn read_str_list_attr(
    loc: &Location,
    name: &str,
    path: &Path,
    budget: &mut Budget,
) -> Result<Vec<String>, IoError> {
    if !crate::h5::has_attr(loc, name, path)? {
        return Err(IoError::Missing {
            path: path.to_owned(),
            what: format!("attribute `{name}` of `{}`", loc.name()),
        });
    }
    let what = format!("attribute `{name}` of `{}`", loc.name());
    let attr = loc
        .attr(name)
        .map_err(h5err(path, format!("opening {what}")))?;
    check_extent::<VarLenUnicode>(&attr, &what, path, Some(budget))?;
    let values: Vec<VarLenUnicode> = attr
        .read_raw()
        .map_err(h5err(path, format!("reading {what}")))?;
    Ok(values.iter().map(|v| v.as_str().to_owned()).collect())
}

fn read_vec<T: hdf5::H5Type>(
    group: &Group,
    name: &str,
    path: &Path,
    budget: &mut Budget,
) -> Result<Vec<T>, IoError> {
    Ok(read_dataset::<T, ndarray::Ix1>(group, name, path, budget)?
        .into_raw_vec_and_offset()
        .0)
}

fn read_text(
    group: &Group,
    name: &str,
    path: &Path,
    budget: &mut Budget,
) -> Result<Vec<String>, IoError> {
    let values: Vec<VarLenUnicode> = read_vec(group, name, path, budget)?;
    Ok(values.iter().map(|v| v.as_str().to_owned()).collect())
}

fn read_parameter(
    group: &Group,
    name: &str,
    path: &Path,
    budget: &mut Budget,
) -> Result<ParameterColumn, IoError> {
    let full = crate::h5::member(group, name);
    if !group.link_exists(name) {
        return Err(IoError::Missing {
            path: path.to_owned(),
            what: format!("dataset `{full}`"),
        });
    }
    let descriptor = group
        .dataset(name)
        .and_then(|d| d.dtype())
        .and_then(|t| t.to_descriptor())
        .map_err(h5err(path, format!("reading the type of `{full}`")))?;
    Ok(match descriptor {
        TypeDescriptor::Integer(_) | TypeDescriptor::Unsigned(_) => {
            ParameterColumn::Integer(read_vec(group, name, path, budget)?)
        }
        TypeDescriptor::Float(_) => ParameterColumn::Float(read_vec(group, name, path, budget)?),
        TypeDescriptor::VarLenUnicode => {
            ParameterColumn::Text(read_text(group, name, path, budget)?)
        }
        other => {
            return Err(IoError::Invalid {
                path: path.to_owned(),
                what: format!("dataset `{full}` has type {other}; expected i64, f64 or strings"),
            });
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> SweepTable {
        SweepTable {
            sweep: "version = 1\n".into(),
            provenance: Provenance {
                scene: "version = 1\n[material]\n".into(),
                ..Provenance::current("abc", "2026-01-01T00:00:00Z")
            },
            index: vec![0, 1, 2],
            status: vec![POINT_OK, POINT_FAILED, POINT_INCOMPLETE],
            error: vec![
                String::new(),
                "material.e_star = -1 is invalid".into(),
                String::new(),
            ],
            result_status: vec![
                "complete".into(),
                String::new(),
                "stopped at protocol.max_steps".into(),
            ],
            warnings: vec![String::new(), String::new(), "a\nb".into()],
            parameters: vec![
                (
                    "roughness.seed".into(),
                    ParameterColumn::Integer(vec![3, 1, 2]),
                ),
                (
                    "material.gamma".into(),
                    ParameterColumn::Float(vec![0.5, 0.25, 1e-3]),
                ),
                (
                    "geometry.shape".into(),
                    ParameterColumn::Text(vec!["sphere".into(), "none".into(), "é".into()]),
                ),
            ],
            results: vec![
                ("pull_off_force".into(), vec![-1.5, f64::NAN, f64::NAN]),
                ("alpha_star".into(), vec![0.3, f64::NAN, f64::NAN]),
            ],
        }
    }

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("tack-io-sweep-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn round_trip_keeps_order_types_and_nan() {
        let dir = scratch("round-trip");
        let path = dir.join("sweep.h5");
        let t = table();
        write_sweep_table(&path, &t).unwrap();
        let back = read_sweep_table(&path).unwrap();
        assert_eq!(back.sweep, t.sweep);
        assert_eq!(back.provenance, t.provenance);
        assert_eq!(
            (&back.index, &back.status, &back.error),
            (&t.index, &t.status, &t.error)
        );
        assert_eq!(
            (&back.result_status, &back.warnings),
            (&t.result_status, &t.warnings)
        );
        assert_eq!(back.parameters, t.parameters);
        let names: Vec<_> = back.results.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["pull_off_force", "alpha_star"]);
        for ((_, a), (_, b)) in back.results.iter().zip(&t.results) {
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(a), bits(b));
        }
        let leftovers: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert_eq!(leftovers.len(), 1, "temporaries left behind");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn tables_without_the_status_columns_read_back_empty() {
        let dir = scratch("old");
        let path = dir.join("sweep.h5");
        write_sweep_table(&path, &table()).unwrap();
        {
            let file = File::open_rw(&path).unwrap();
            let point = file.group("point").unwrap();
            point.unlink("result_status").unwrap();
            point.unlink("warnings").unwrap();
        }
        let back = read_sweep_table(&path).unwrap();
        assert_eq!(back.result_status, vec![String::new(); 3]);
        assert_eq!(back.warnings, vec![String::new(); 3]);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn ragged_columns_and_bad_names_are_rejected() {
        let dir = scratch("bad");
        let path = dir.join("sweep.h5");
        let mut t = table();
        t.results[1].1.pop();
        let e = write_sweep_table(&path, &t).unwrap_err().to_string();
        assert!(
            e.contains("/results/alpha_star") && e.contains("2 entries"),
            "{e}"
        );
        let mut t = table();
        t.parameters[0].0 = "a/b".into();
        let e = write_sweep_table(&path, &t).unwrap_err().to_string();
        assert!(e.contains("`a/b` cannot name a dataset"), "{e}");
        assert!(!path.exists());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
