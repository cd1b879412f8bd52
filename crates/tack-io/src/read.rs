//! Reading result files back, describing them for `tack info`, and reading measured
//! topographies from HDF5.

use std::path::Path;

use hdf5::{File, Group, H5Type};
use ndarray::{Array2, Ix1, Ix2};

use crate::h5::{h5err, open_group, read_attr, read_dataset, read_opt_attr, read_str_attr};
use crate::{Curve, IoError, Provenance, RunResult, Snapshot, Summary};

/// Reads a result file written by [`crate::write_result`]; snapshots come back sorted by step.
///
/// Errors name the file and the missing or malformed object (curve columns of unequal length
/// included).
pub fn read_result(path: &Path) -> Result<RunResult, IoError> {
    let file = open(path)?;
    let provenance = Provenance {
        tack_version: read_str_attr(&file, "tack_version", path)?,
        git_revision: read_str_attr(&file, "git_revision", path)?,
        command_line: read_str_attr(&file, "command_line", path)?,
        scene: read_str_attr(&file, "scene", path)?,
        created: read_str_attr(&file, "created", path)?,
        seed: read_opt_attr(&file, "seed", path)?,
    };
    let curve = read_curve(&file, path)?;
    let surface = if file.link_exists("surface/heights") {
        Some(read_heights(&file, "/surface/heights", path)?)
    } else {
        None
    };
    let snapshots = read_snapshots(&file, curve.len(), path)?;
    let summary = read_summary(&file, path)?;
    Ok(RunResult {
        provenance,
        curve,
        surface,
        snapshots,
        summary,
    })
}

/// A human-readable account of a result file: provenance, curve (length, approach range,
/// minimum force), surface, snapshots and summary attributes.
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
                num(lo),
                num(hi),
                num(min_force),
                n = c.len(),
            )
        }
        None => "curve: empty".to_owned(),
    });
    lines.push(match &r.surface {
        Some((h, dx)) => format!(
            "surface: {} x {} heights, dx = {}",
            h.nrows(),
            h.ncols(),
            num(*dx)
        ),
        None => "surface: not stored".to_owned(),
    });
    let steps: Vec<String> = r.snapshots.iter().map(|s| s.step.to_string()).collect();
    lines.push(if steps.is_empty() {
        "snapshots: none".to_owned()
    } else {
        format!("snapshots: {} at steps {}", steps.len(), steps.join(", "))
    });
    lines.push("summary:".to_owned());
    for (name, value) in r.summary.attributes() {
        lines.push(format!("  {name} = {}", num(value)));
    }
    Ok(lines.join("\n") + "\n")
}

/// Reads a measured topography: the 2D f64 dataset `dataset` (default `heights`, falling back
/// to `/surface/heights` of tack's own result files) and its element size `dx`, an attribute of
/// the dataset or, failing that, of the file root.
///
/// Errors: missing file, missing dataset, not 2D or empty, missing or non-positive `dx`, and
/// NaN or infinite heights (naming the first bad index in row-major order).
pub fn read_height_map_h5(
    path: &Path,
    dataset: Option<&str>,
) -> Result<(Array2<f64>, f64), IoError> {
    let file = open(path)?;
    let name = match dataset {
        Some(name) => name,
        None => ["heights", "/surface/heights"]
            .into_iter()
            .find(|n| file.link_exists(n))
            .ok_or_else(|| IoError::Missing {
                path: path.to_owned(),
                what: "dataset `heights` (nor `/surface/heights`)".to_owned(),
            })?,
    };
    read_heights(&file, name, path)
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

fn read_heights(file: &File, name: &str, path: &Path) -> Result<(Array2<f64>, f64), IoError> {
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
    let shape = ds.shape();
    if shape.len() != 2 {
        return Err(invalid(format!(
            "dataset `{name}` has shape {shape:?}; expected 2D heights (nx, ny)"
        )));
    }
    if shape.contains(&0) {
        return Err(invalid(format!(
            "dataset `{name}` is empty (shape {shape:?})"
        )));
    }
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
            index: [i, j],
            value,
        });
    }
    Ok((heights, dx))
}

fn read_column<T: H5Type>(group: &Group, name: &str, path: &Path) -> Result<Vec<T>, IoError> {
    Ok(read_dataset::<T, Ix1>(group, name, path)?
        .into_raw_vec_and_offset()
        .0)
}

fn read_curve(file: &File, path: &Path) -> Result<Curve, IoError> {
    let g = open_group(file, "curve", path)?;
    let converged: Vec<u8> = read_column(&g, "converged", path)?;
    let curve = Curve {
        approach: read_column(&g, "approach", path)?,
        force: read_column(&g, "force", path)?,
        area: read_column(&g, "area", path)?,
        n_bonded: read_column(&g, "n_bonded", path)?,
        n_clusters: read_column(&g, "n_clusters", path)?,
        iterations: read_column(&g, "iterations", path)?,
        active_set_iterations: read_column(&g, "active_set_iterations", path)?,
        converged: converged.into_iter().map(|c| c != 0).collect(),
        mean_pressure: if g.link_exists("mean_pressure") {
            Some(read_column(&g, "mean_pressure", path)?)
        } else {
            None
        },
        full_contact: if g.link_exists("full_contact") {
            let full: Vec<u8> = read_column(&g, "full_contact", path)?;
            Some(full.into_iter().map(|c| c != 0).collect())
        } else {
            None
        },
    };
    curve.check_lengths(path)?;
    Ok(curve)
}

fn read_snapshots(file: &File, curve_len: usize, path: &Path) -> Result<Vec<Snapshot>, IoError> {
    if !file.link_exists("snapshots") {
        return Ok(Vec::new());
    }
    let group = open_group(file, "snapshots", path)?;
    let names = group
        .member_names()
        .map_err(h5err(path, "listing `/snapshots`"))?;
    let mut snapshots = names
        .iter()
        .map(|name| {
            let step = name.parse().map_err(|_| IoError::Invalid {
                path: path.to_owned(),
                what: format!("group `/snapshots/{name}` is not named by a step number"),
            })?;
            let g = open_group(&group, name, path)?;
            let bonded = read_dataset::<u8, Ix2>(&g, "bonded", path)?;
            let snapshot = Snapshot {
                step,
                approach: read_attr(&g, "approach", path)?,
                pressure: read_dataset(&g, "pressure", path)?,
                bonded: bonded.mapv(|b| b != 0),
            };
            snapshot.check(curve_len, path)?;
            Ok(snapshot)
        })
        .collect::<Result<Vec<_>, IoError>>()?;
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
    })
}

/// Formats `x` compactly: plain decimal for moderate magnitudes, scientific otherwise.
fn num(x: f64) -> String {
    if x == 0.0 || (1e-3..1e6).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}
