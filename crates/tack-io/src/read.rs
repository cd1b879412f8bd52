//! Reading result files back, describing them for `tack info`, and reading measured
//! topographies from HDF5.

use std::path::Path;

use hdf5::{File, Group, H5Type};
use ndarray::{Array2, Ix1, Ix2};
use tack_fields::rounded;

use crate::h5::{
    Budget, check_extent, declared_shape, dims, h5err, has_attr, open_dataset, open_group,
    read_attr, read_dataset, read_opt_attr, read_str_attr,
};
use crate::model::{FIXED_COLUMNS, OPTIONAL_COLUMNS};
use crate::{Curve, IoError, LawColumn, Provenance, RunResult, Snapshot, Summary};

/// Reads a result file written by [`crate::write_result`]; snapshots come back sorted by step.
///
/// Errors name the file and the missing or malformed object (curve columns of unequal length
/// included).
///
/// Declared sizes are checked before anything is read, so a corrupt file gives an error, never
/// an allocation failure ([`IoError::Oversized`], [`IoError::ColumnLength`]): tack writes its
/// datasets uncompressed, so together they hold at most the file's size on disk; no dataset may
/// take more than [`crate::MAX_DATASET_BYTES`] in memory; curve columns all have the length of
/// `approach`; and every snapshot field has the shape of the surface (or, without a stored
/// surface, of the other snapshots).
pub fn read_result(path: &Path) -> Result<RunResult, IoError> {
    let file = open(path)?;
    let mut budget = Budget::of_file(path)?;
    let provenance = Provenance {
        tack_version: read_str_attr(&file, "tack_version", path)?,
        git_revision: read_str_attr(&file, "git_revision", path)?,
        command_line: read_str_attr(&file, "command_line", path)?,
        scene: read_str_attr(&file, "scene", path)?,
        created: read_str_attr(&file, "created", path)?,
        seed: read_opt_attr(&file, "seed", path)?,
    };
    let curve = read_curve(&file, path, &mut budget)?;
    let surface = if file.link_exists("surface/heights") {
        let bound = Bound::Ours(&mut budget);
        Some(read_heights(
            &file,
            "/surface/heights",
            None,
            bound,
            path,
            HEIGHT,
        )?)
    } else {
        None
    };
    let surface_shape = surface.as_ref().map(|(h, _)| h.dim());
    let gamma = if file.link_exists("surface/gamma") {
        let bound = Bound::Ours(&mut budget);
        Some(read_heights(&file, "/surface/gamma", surface_shape, bound, path, GAMMA)?.0)
    } else {
        None
    };
    let snapshots = read_snapshots(&file, curve.len(), surface_shape, path, &mut budget)?;
    let summary = read_summary(&file, path)?;
    Ok(RunResult {
        provenance,
        curve,
        surface,
        gamma,
        snapshots,
        summary,
    })
}

/// A human-readable account of a result file: provenance, curve (length, approach range,
/// minimum force, the law's columns and what they count), surface, snapshots and summary
/// attributes, numbers rounded to 6 significant digits ([`tack_fields::rounded`]).
pub fn describe(path: &Path) -> Result<String, IoError> {
    let r = read_result(path)?;
    let (p, c) = (&r.provenance, &r.curve);
    let seed = p.seed.map_or_else(|| "none".to_owned(), |s| s.to_string());
    let mut lines = vec![
        path.display().to_string(),
        format!(
            "  tack {} (git {}), created {}",
            p.tack_version, p.git_revision, p.created
        ),
        format!("  command: {}", p.command_line),
        format!(
            "  seed: {seed}; scene: {} lines of TOML",
            p.scene.lines().count()
        ),
    ];
    let min_force = c.force.iter().enumerate().min_by(|a, b| a.1.total_cmp(b.1));
    lines.push(match min_force {
        Some((step, &min_force)) => {
            let lo = c.approach.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = c.approach.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let converged = c.converged.iter().filter(|&&ok| ok).count();
            format!(
                "curve: {n} steps, approach {} .. {}, min force {} at step {step}, \
                 {converged}/{n} converged",
                rounded(lo),
                rounded(hi),
                rounded(min_force),
                n = c.len(),
            )
        }
        None => "curve: empty".to_owned(),
    });
    for z in &c.law_columns {
        let most = z.values.iter().max().copied().unwrap_or(0);
        let meaning = if z.meaning.is_empty() {
            String::new()
        } else {
            format!(" ({})", z.meaning)
        };
        lines.push(format!("  law column {}{meaning}: up to {most}", z.name));
    }
    lines.push(match &r.surface {
        Some((h, dx)) => format!(
            "surface: {} x {} heights, dx = {}",
            h.nrows(),
            h.ncols(),
            rounded(*dx)
        ),
        None => "surface: not stored".to_owned(),
    });
    if let Some(g) = &r.gamma {
        let lo = g.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = g.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        lines.push(format!(
            "work of adhesion: {} x {} map, {} to {}",
            g.nrows(),
            g.ncols(),
            rounded(lo),
            rounded(hi)
        ));
    }
    let steps: Vec<String> = r.snapshots.iter().map(|s| s.step.to_string()).collect();
    lines.push(if steps.is_empty() {
        "snapshots: none".to_owned()
    } else {
        format!("snapshots: {} at steps {}", steps.len(), steps.join(", "))
    });
    lines.push("summary: (6 significant digits; the file holds every digit)".to_owned());
    if let Some(status) = &r.summary.status {
        lines.push(format!("  status = {status}"));
    }
    if let Some(model) = &r.summary.adhesion_model {
        lines.push(format!("  adhesion_model = {model}"));
    }
    for (name, value) in r.summary.attributes() {
        lines.push(format!("  {name} = {}", rounded(value)));
    }
    for warning in &r.summary.warnings {
        lines.push(format!("  WARNING {warning}"));
    }
    Ok(lines.join("\n") + "\n")
}

/// Reads a measured topography: the 2D f64 dataset `dataset` (default `heights`, falling back
/// to `/surface/heights` of tack's own result files) and its element size `dx`, an attribute of
/// the dataset or, failing that, of the file root.
///
/// `shape`, when known (the grid's `(nx, ny)`), is the shape the map must have: a map declaring
/// another is refused before its data is read. Whatever the shape, a map whose data is stored
/// uncompressed in the file (not chunked with filters, external or virtual) may not declare
/// more than the file's size, and no map more than [`crate::MAX_DATASET_BYTES`]; compressed
/// maps may be larger than their file.
///
/// Errors: missing file, missing dataset, not 2D or empty, not of `shape`, larger than the
/// file or the limit ([`IoError::Oversized`]), missing or non-positive `dx`, and NaN or
/// infinite heights (naming the first bad index in row-major order).
pub fn read_height_map_h5(
    path: &Path,
    dataset: Option<&str>,
    shape: Option<(usize, usize)>,
) -> Result<(Array2<f64>, f64), IoError> {
    read_map_h5(
        path,
        dataset,
        shape,
        ["heights", "/surface/heights"],
        HEIGHT,
    )
}

/// What a height map holds, for its errors.
const HEIGHT: &str = "height";

/// What a work-of-adhesion map holds, for its errors.
const GAMMA: &str = "work of adhesion";

/// A work-of-adhesion map from an HDF5 file: [`read_height_map_h5`] with the default datasets
/// `gamma`, then `/surface/gamma` (the map of tack's own result files), never the heights.
pub fn read_gamma_map_h5(
    path: &Path,
    dataset: Option<&str>,
    shape: Option<(usize, usize)>,
) -> Result<(Array2<f64>, f64), IoError> {
    read_map_h5(path, dataset, shape, ["gamma", "/surface/gamma"], GAMMA)
}

fn read_map_h5(
    path: &Path,
    dataset: Option<&str>,
    shape: Option<(usize, usize)>,
    defaults: [&str; 2],
    quantity: &'static str,
) -> Result<(Array2<f64>, f64), IoError> {
    let file = open(path)?;
    let name = match dataset {
        Some(name) => name,
        None => defaults
            .into_iter()
            .find(|n| file.link_exists(n))
            .ok_or_else(|| IoError::Missing {
                path: path.to_owned(),
                what: format!("dataset `{}` (nor `{}`)", defaults[0], defaults[1]),
            })?,
    };
    read_heights(&file, name, shape, Bound::Foreign, path, quantity)
}

/// Checks that `dx` (of the heights `dataset`) is a finite positive spacing.
pub(crate) fn check_dx(dx: f64, dataset: &str, path: &Path) -> Result<(), IoError> {
    if dx.is_finite() && dx > 0.0 {
        return Ok(());
    }
    Err(IoError::Invalid {
        path: path.to_owned(),
        what: format!("`dx` of `{dataset}` is {dx}; expected a finite positive spacing"),
    })
}

fn open(path: &Path) -> Result<File, IoError> {
    if !path.is_file() {
        return Err(IoError::MissingFile {
            path: path.to_owned(),
        });
    }
    File::open(path).map_err(h5err(path, "opening as an HDF5 file"))
}

/// The size bound a height dataset is read under.
enum Bound<'b> {
    /// Part of a tack result file: the file's running [`Budget`].
    Ours(&'b mut Budget),
    /// Another program's file: bounded by the file's size when the data is stored in it
    /// uncompressed; compressed (filtered), external or virtual data only by
    /// [`crate::MAX_DATASET_BYTES`] and the expected shape.
    Foreign,
}

/// Whether `ds` keeps its data uncompressed in its own file (contiguous, compact, or chunked
/// without filters; not external, not virtual): then its declared size cannot exceed the file's.
fn stored_plainly(ds: &hdf5::Dataset, name: &str, path: &Path) -> Result<bool, IoError> {
    use hdf5::dataset::Layout;
    let dcpl = ds.dcpl().map_err(h5err(
        path,
        format!("reading the storage properties of dataset `{name}`"),
    ))?;
    let layout = matches!(
        dcpl.layout(),
        Layout::Contiguous | Layout::Compact | Layout::Chunked
    );
    Ok(layout && dcpl.filters().is_empty() && dcpl.external().is_empty())
}

/// A 2D f64 map `name` (heights or γ: `quantity`, for the errors) and its `dx`.
fn read_heights(
    file: &File,
    name: &str,
    expected: Option<(usize, usize)>,
    bound: Bound<'_>,
    path: &Path,
    quantity: &'static str,
) -> Result<(Array2<f64>, f64), IoError> {
    let invalid = |what: String| IoError::Invalid {
        path: path.to_owned(),
        what,
    };
    if !file.link_exists(name) {
        return Err(IoError::Missing {
            path: path.to_owned(),
            what: format!("dataset `{name}`"),
        });
    }
    let ds = file
        .dataset(name)
        .map_err(h5err(path, format!("opening dataset `{name}`")))?;
    let shape = declared_shape(&ds, name, path)?;
    let &[nx, ny] = &shape[..] else {
        return Err(invalid(format!(
            "dataset `{name}` has shape {shape:?}; expected a 2D map (nx, ny)"
        )));
    };
    if shape.contains(&0) {
        return Err(invalid(format!(
            "dataset `{name}` is empty (shape {shape:?})"
        )));
    }
    if let Some((gx, gy)) = expected.filter(|&e| e != (nx, ny)) {
        return Err(invalid(format!(
            "dataset `{name}` declares a {nx} × {ny} map, but the grid is {gx} × {gy}; \
             the map must have the grid's shape (nothing was read)"
        )));
    }
    let object = format!("dataset `{name}`");
    match bound {
        Bound::Ours(budget) => check_extent::<f64>(&ds, &object, path, Some(budget))?,
        Bound::Foreign if stored_plainly(&ds, name, path)? => {
            let mut budget = Budget::of_file(path)?;
            check_extent::<f64>(&ds, &object, path, Some(&mut budget))?
        }
        Bound::Foreign => check_extent::<f64>(&ds, &object, path, None)?,
    };
    let heights: Array2<f64> = ds
        .read_2d()
        .map_err(h5err(path, format!("reading dataset `{name}` as f64")))?;
    let dx = match read_opt_attr(&ds, "dx", path)? {
        Some(dx) => dx,
        None => read_opt_attr(file, "dx", path)?.ok_or_else(|| IoError::Missing {
            path: path.to_owned(),
            what: format!("attribute `dx` (on dataset `{name}` or the file root)"),
        })?,
    };
    check_dx(dx, name, path)?;
    if let Some(((i, j), &value)) = heights.indexed_iter().find(|(_, h)| !h.is_finite()) {
        return Err(IoError::NonFinite {
            path: path.to_owned(),
            dataset: name.to_owned(),
            quantity,
            index: [i, j],
            value,
        });
    }
    Ok((heights, dx))
}

fn read_column<T: H5Type>(
    group: &Group,
    name: &str,
    path: &Path,
    budget: &mut Budget,
) -> Result<Vec<T>, IoError> {
    Ok(read_dataset::<T, Ix1>(group, name, path, budget)?
        .into_raw_vec_and_offset()
        .0)
}

/// The attribute that marks a `/curve` dataset as a law's column ([`crate::LawColumn`]) and
/// holds what it counts.
pub(crate) const LAW_COLUMN_ATTR: &str = "law_column";

/// The law columns' name in files written before law columns carried their meaning.
const LEGACY_LAW_COLUMN: &str = "n_cohesive";

/// The columns of a `/curve` group: every present column's name, `approach` first, and the
/// law's columns with what each counts.
type CurveColumns = (Vec<String>, Vec<(String, String)>);

/// The columns of `/curve` present in `g`, `approach` first: the fixed ones, the optional
/// ones tack writes, then the law's (a dataset with the [`LAW_COLUMN_ATTR`] attribute, or the
/// legacy `n_cohesive`) with what each counts; other members are left alone.
fn curve_columns(g: &Group, path: &Path) -> Result<CurveColumns, IoError> {
    let mut present: Vec<String> = FIXED_COLUMNS.iter().map(|&c| c.to_owned()).collect();
    for c in OPTIONAL_COLUMNS {
        if g.link_exists(c) {
            present.push(c.to_owned());
        }
    }
    let mut law = Vec::new();
    let names = g.member_names().map_err(h5err(path, "listing `/curve`"))?;
    for name in names {
        if FIXED_COLUMNS.contains(&name.as_str()) || OPTIONAL_COLUMNS.contains(&name.as_str()) {
            continue;
        }
        let Ok(ds) = g.dataset(&name) else {
            continue;
        };
        let meaning = if has_attr(&ds, LAW_COLUMN_ATTR, path)? {
            read_str_attr(&ds, LAW_COLUMN_ATTR, path)?
        } else if name == LEGACY_LAW_COLUMN {
            String::new()
        } else {
            continue;
        };
        present.push(name.clone());
        law.push((name, meaning));
    }
    Ok((present, law))
}

/// Checks, before any is read, that `approach` fits the file (`budget`, not taken) and every
/// curve column in `columns` is 1D and declares its length.
fn check_curve_shapes(
    g: &Group,
    columns: &[String],
    path: &Path,
    budget: &Budget,
) -> Result<(), IoError> {
    let mut expected = None;
    for column in columns {
        let full = format!("/curve/{column}");
        let ds = open_dataset(g, column, path)?;
        let shape = declared_shape(&ds, &full, path)?;
        let &[len] = &shape[..] else {
            return Err(IoError::Invalid {
                path: path.to_owned(),
                what: format!(
                    "dataset `{full}` has shape {}; expected a 1D column",
                    dims(&shape)
                ),
            });
        };
        match expected {
            None => {
                let object = format!("dataset `{full}`");
                check_extent::<f64>(&ds, &object, path, Some(&mut budget.clone()))?;
                expected = Some(len);
            }
            Some(expected) if len != expected => {
                return Err(IoError::ColumnLength {
                    path: path.to_owned(),
                    column: column.clone(),
                    len,
                    expected,
                });
            }
            Some(_) => {}
        }
    }
    Ok(())
}

fn read_curve(file: &File, path: &Path, budget: &mut Budget) -> Result<Curve, IoError> {
    let g = open_group(file, "curve", path)?;
    let (columns, law) = curve_columns(&g, path)?;
    check_curve_shapes(&g, &columns, path, budget)?;
    let mut law_columns = Vec::with_capacity(law.len());
    for (name, meaning) in law {
        let values = read_column(&g, &name, path, budget)?;
        law_columns.push(LawColumn {
            name,
            meaning,
            values,
        });
    }
    let converged: Vec<u8> = read_column(&g, "converged", path, budget)?;
    let curve = Curve {
        approach: read_column(&g, "approach", path, budget)?,
        force: read_column(&g, "force", path, budget)?,
        area: read_column(&g, "area", path, budget)?,
        n_bonded: read_column(&g, "n_bonded", path, budget)?,
        n_clusters: read_column(&g, "n_clusters", path, budget)?,
        iterations: read_column(&g, "iterations", path, budget)?,
        active_set_iterations: read_column(&g, "active_set_iterations", path, budget)?,
        converged: converged.into_iter().map(|c| c != 0).collect(),
        mean_pressure: if g.link_exists("mean_pressure") {
            Some(read_column(&g, "mean_pressure", path, budget)?)
        } else {
            None
        },
        full_contact: if g.link_exists("full_contact") {
            let full: Vec<u8> = read_column(&g, "full_contact", path, budget)?;
            Some(full.into_iter().map(|c| c != 0).collect())
        } else {
            None
        },
        time: if g.link_exists("time") {
            Some(read_column(&g, "time", path, budget)?)
        } else {
            None
        },
        law_columns,
    };
    curve.check_lengths(path)?;
    Ok(curve)
}

/// Reads `/snapshots`. Before the fields of a snapshot are read, their declared shapes must
/// be 2D and equal `surface` (the stored surface's shape), or without one the first
/// snapshot's.
fn read_snapshots(
    file: &File,
    curve_len: usize,
    surface: Option<(usize, usize)>,
    path: &Path,
    budget: &mut Budget,
) -> Result<Vec<Snapshot>, IoError> {
    if !file.link_exists("snapshots") {
        return Ok(Vec::new());
    }
    let invalid = |what: String| IoError::Invalid {
        path: path.to_owned(),
        what,
    };
    let group = open_group(file, "snapshots", path)?;
    let names = group
        .member_names()
        .map_err(h5err(path, "listing `/snapshots`"))?;
    // The shape every field must have, and what set it (for the message).
    let mut want = surface.map(|s| (s, "the surface".to_owned()));
    let mut snapshots = Vec::with_capacity(names.len());
    for name in &names {
        let step = name.parse().map_err(|_| {
            invalid(format!(
                "group `/snapshots/{name}` is not named by a step number"
            ))
        })?;
        let g = open_group(&group, name, path)?;
        for field in ["pressure", "bonded"] {
            let full = format!("/snapshots/{name}/{field}");
            let shape = declared_shape(&open_dataset(&g, field, path)?, &full, path)?;
            let &[nx, ny] = &shape[..] else {
                return Err(invalid(format!(
                    "dataset `{full}` has shape {}; expected 2D (nx, ny)",
                    dims(&shape)
                )));
            };
            let (expected, source) = want.get_or_insert_with(|| ((nx, ny), format!("`{full}`")));
            if (nx, ny) != *expected {
                return Err(invalid(format!(
                    "dataset `{full}` is {nx} × {ny}, but {source} is {} × {}; every snapshot \
                     field must have the surface's shape",
                    expected.0, expected.1
                )));
            }
        }
        let bonded = read_dataset::<u8, Ix2>(&g, "bonded", path, budget)?;
        let snapshot = Snapshot {
            step,
            approach: read_attr(&g, "approach", path)?,
            pressure: read_dataset(&g, "pressure", path, budget)?,
            bonded: bonded.mapv(|b| b != 0),
        };
        snapshot.check(curve_len, path)?;
        snapshots.push(snapshot);
    }
    snapshots.sort_by_key(|s| s.step);
    Ok(snapshots)
}

fn read_summary(file: &File, path: &Path) -> Result<Summary, IoError> {
    let g = open_group(file, "summary", path)?;
    let names = g
        .attr_names()
        .map_err(h5err(path, "listing attributes of `/summary`"))?;
    let extra = names
        .into_iter()
        .filter(|n| !Summary::RESERVED.contains(&n.as_str()))
        .map(|n| Ok((n.clone(), read_attr(&g, &n, path)?)))
        .collect::<Result<_, IoError>>()?;
    Ok(Summary {
        pull_off_force: read_attr(&g, "pull_off_force", path)?,
        f_jkr: read_attr(&g, "f_jkr", path)?,
        pull_off_ratio: read_attr(&g, "pull_off_ratio", path)?,
        johnson_alpha: read_opt_attr(&g, "johnson_alpha", path)?,
        alpha_star: read_opt_attr(&g, "alpha_star", path)?,
        extra,
        status: if has_attr(&g, "status", path)? {
            Some(read_str_attr(&g, "status", path)?)
        } else {
            None
        },
        adhesion_model: if has_attr(&g, "adhesion_model", path)? {
            Some(read_str_attr(&g, "adhesion_model", path)?)
        } else {
            None
        },
        warnings: if has_attr(&g, "warnings", path)? {
            let text = read_str_attr(&g, "warnings", path)?;
            text.lines().map(str::to_owned).collect()
        } else {
            Vec::new()
        },
    })
}
