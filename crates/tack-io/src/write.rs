//! Writing a [`RunResult`] atomically: to a temporary file beside the target, renamed onto it
//! only when everything has been written and the file closed.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use hdf5::{File, Group};

use crate::h5::{create_group, h5err, write_attr, write_dataset, write_str_attr};
use crate::read::{LAW_COLUMN_ATTR, check_dx};
use crate::{Curve, IoError, Provenance, RunResult, Snapshot, Summary};

/// Distinguishes temporaries of concurrent writes from one process.
static TEMPORARIES: AtomicU64 = AtomicU64::new(0);

/// Writes `result` to `path` in the layout described in the crate documentation.
///
/// The file is first written to `.<name>.tmp-<pid>-<n>` in the same directory and renamed onto
/// `path` only on success; on any error the temporary is removed and an existing file at `path`
/// is left untouched. Errors: missing parent directory, curve columns of unequal length,
/// snapshots beyond the curve or with mismatched shapes, duplicate snapshot steps, `extra`
/// summary names that shadow a field, a non-positive `dx`, and HDF5 or file-system failures.
pub fn write_result(path: &Path, result: &RunResult) -> Result<(), IoError> {
    write_atomically(path, |tmp| write_file(tmp, path, result))
}

/// The one atomic file write of tack (result files, sweep tables, figures, the xtask's JSON):
/// runs `write` on a temporary path beside `path` (`.<name>.tmp-<pid>-<n>.<extension>`: the
/// extension last, for writers that pick a format from it) and renames the temporary onto
/// `path` when `write` succeeds; on any error the temporary is removed and an existing file at
/// `path` is left untouched. Refuses a missing parent directory and an existing `path` that is
/// not a regular file ([`not_a_regular_file`]).
pub fn write_atomically<E: From<IoError>>(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), E>,
) -> Result<(), E> {
    let tmp = temporary_path(path)?;
    let outcome = write(&tmp).and_then(|()| {
        fs::rename(&tmp, path).map_err(|cause| {
            E::from(IoError::Fs {
                path: path.to_owned(),
                what: format!("renaming the temporary `{}` onto it", tmp.display()),
                cause,
            })
        })
    });
    if outcome.is_err() {
        // The temporary may never have been created; nothing more to do if removal fails.
        let _ = fs::remove_file(&tmp);
    }
    outcome
}

fn temporary_path(path: &Path) -> Result<PathBuf, IoError> {
    let invalid = |what: &str| IoError::Invalid {
        path: path.to_owned(),
        what: what.to_owned(),
    };
    let name = path.file_name().ok_or_else(|| invalid("not a file name"))?;
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !parent.is_dir() {
        return Err(IoError::MissingParent {
            path: path.to_owned(),
            parent: parent.to_owned(),
        });
    }
    if let Some(kind) = not_a_regular_file(path) {
        return Err(invalid(&format!(
            "{kind}: refusing to replace it (name a regular file or a new path)"
        )));
    }
    let n = TEMPORARIES.fetch_add(1, Ordering::Relaxed);
    let pid = std::process::id();
    let extension = path
        .extension()
        .map_or_else(String::new, |e| format!(".{}", e.to_string_lossy()));
    Ok(parent.join(format!(
        ".{}.tmp-{pid}-{n}{extension}",
        name.to_string_lossy()
    )))
}

/// Writes `text` to `path` atomically ([`write_atomically`]): `path` holds either its old
/// content or the whole text.
pub fn write_text_atomically(path: &Path, text: &str) -> Result<(), IoError> {
    write_atomically(path, |tmp| {
        fs::write(tmp, text).map_err(|cause| IoError::Fs {
            path: path.to_owned(),
            what: format!("writing the temporary `{}`", tmp.display()),
            cause,
        })
    })
}

/// What an existing `path` is when it is not a regular file (following symbolic links): `is a
/// directory`, `is a FIFO (named pipe)`, `is a character device`, ...; `None` for a regular
/// file or a path that does not exist. Writing a result renames a temporary file onto its
/// output, which would replace a FIFO or a device node (`/dev/null`) by a regular file: such
/// outputs are refused instead.
pub fn not_a_regular_file(path: &Path) -> Option<&'static str> {
    let kind = fs::metadata(path).ok()?.file_type();
    if kind.is_file() {
        return None;
    }
    if kind.is_dir() {
        return Some("is a directory");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return Some("is a FIFO (named pipe), not a regular file");
        }
        if kind.is_char_device() {
            return Some("is a character device, not a regular file");
        }
        if kind.is_block_device() {
            return Some("is a block device, not a regular file");
        }
        if kind.is_socket() {
            return Some("is a socket, not a regular file");
        }
    }
    Some("is not a regular file")
}

fn write_file(tmp: &Path, path: &Path, result: &RunResult) -> Result<(), IoError> {
    let file = File::create(tmp).map_err(h5err(
        path,
        format!("creating the temporary `{}`", tmp.display()),
    ))?;
    write_provenance(&file, &result.provenance, path)?;
    write_curve(&file, &result.curve, path)?;
    if let Some((heights, dx)) = &result.surface {
        check_dx(*dx, "/surface/heights", path)?;
        let surface = create_group(&file, "surface", path)?;
        let heights_set = write_dataset(&surface, "heights", heights.view(), path)?;
        write_attr(&heights_set, "dx", dx, path)?;
        if let Some(gamma) = &result.gamma {
            if gamma.dim() != heights.dim() {
                return Err(IoError::Invalid {
                    path: path.to_owned(),
                    what: format!(
                        "/surface/gamma is {:?} but /surface/heights is {:?}; the work of \
                         adhesion must have the surface's shape",
                        gamma.dim(),
                        heights.dim()
                    ),
                });
            }
            let gamma_set = write_dataset(&surface, "gamma", gamma.view(), path)?;
            write_attr(&gamma_set, "dx", dx, path)?;
        }
    }
    let surface = result.surface.as_ref().map(|(h, _)| h.dim());
    write_snapshots(&file, &result.snapshots, result.curve.len(), surface, path)?;
    write_summary(&file, &result.summary, path)?;
    file.close().map_err(h5err(path, "closing the file"))
}

fn write_provenance(file: &File, p: &Provenance, path: &Path) -> Result<(), IoError> {
    for (name, value) in [
        ("tack_version", &p.tack_version),
        ("git_revision", &p.git_revision),
        ("command_line", &p.command_line),
        ("scene", &p.scene),
        ("created", &p.created),
    ] {
        write_str_attr(file, name, value, path)?;
    }
    match &p.seed {
        Some(seed) => write_attr(file, "seed", seed, path),
        None => Ok(()),
    }
}

fn write_curve(file: &File, curve: &Curve, path: &Path) -> Result<(), IoError> {
    curve.check_lengths(path)?;
    curve.check_law_columns(path)?;
    let group = create_group(file, "curve", path)?;
    let mean_pressure = curve.mean_pressure.as_ref().map(|p| ("mean_pressure", p));
    for (name, data) in [
        ("approach", &curve.approach),
        ("force", &curve.force),
        ("area", &curve.area),
    ]
    .into_iter()
    .chain(mean_pressure)
    {
        write_dataset(&group, name, data.into(), path)?;
    }
    for (name, data) in [
        ("n_bonded", &curve.n_bonded),
        ("n_clusters", &curve.n_clusters),
        ("iterations", &curve.iterations),
        ("active_set_iterations", &curve.active_set_iterations),
    ] {
        write_dataset(&group, name, data.into(), path)?;
    }
    let flags = |column: &[bool]| column.iter().map(|&c| u8::from(c)).collect::<Vec<u8>>();
    write_dataset(&group, "converged", (&flags(&curve.converged)).into(), path)?;
    if let Some(full) = &curve.full_contact {
        write_dataset(&group, "full_contact", (&flags(full)).into(), path)?;
    }
    if let Some(time) = &curve.time {
        write_dataset(&group, "time", time.into(), path)?;
    }
    for c in &curve.law_columns {
        let ds = write_dataset(&group, &c.name, (&c.values).into(), path)?;
        write_str_attr(&ds, LAW_COLUMN_ATTR, &c.meaning, path)?;
    }
    Ok(())
}

/// Writes `/snapshots`; every snapshot must have the shape of the `surface` (when stored, else
/// of the first snapshot), as `read_result` requires.
fn write_snapshots(
    file: &File,
    snapshots: &[Snapshot],
    curve_len: usize,
    surface: Option<(usize, usize)>,
    path: &Path,
) -> Result<(), IoError> {
    let group = create_group(file, "snapshots", path)?;
    let mut seen = BTreeSet::new();
    let mut want = surface.map(|s| (s, "the surface".to_owned()));
    for s in snapshots {
        s.check(curve_len, path)?;
        let (nx, ny) = s.pressure.dim();
        let (expected, source) =
            want.get_or_insert_with(|| ((nx, ny), format!("snapshot {}", s.step)));
        if (nx, ny) != *expected {
            return Err(IoError::Invalid {
                path: path.to_owned(),
                what: format!(
                    "snapshot {}: `pressure` is {nx} × {ny}, but {source} is {} × {}; every \
                     snapshot must have the surface's shape",
                    s.step, expected.0, expected.1
                ),
            });
        }
        if !seen.insert(s.step) {
            return Err(IoError::Invalid {
                path: path.to_owned(),
                what: format!("snapshot step {} appears more than once", s.step),
            });
        }
        let step: Group = create_group(&group, &s.step.to_string(), path)?;
        write_attr(&step, "approach", &s.approach, path)?;
        write_dataset(&step, "pressure", s.pressure.view(), path)?;
        write_dataset(&step, "bonded", s.bonded.mapv(u8::from).view(), path)?;
    }
    Ok(())
}

fn write_summary(file: &File, summary: &Summary, path: &Path) -> Result<(), IoError> {
    if let Some(name) = summary
        .extra
        .keys()
        .find(|n| Summary::RESERVED.contains(&n.as_str()))
    {
        return Err(IoError::Invalid {
            path: path.to_owned(),
            what: format!("summary extra `{name}` shadows the field of the same name"),
        });
    }
    let group = create_group(file, "summary", path)?;
    summary
        .attributes()
        .into_iter()
        .try_for_each(|(name, value)| write_attr(&group, name, &value, path))?;
    if let Some(status) = &summary.status {
        write_str_attr(&group, "status", status, path)?;
    }
    if let Some(model) = &summary.adhesion_model {
        write_str_attr(&group, "adhesion_model", model, path)?;
    }
    if summary.warnings.iter().any(|w| w.contains('\n')) {
        return Err(IoError::Invalid {
            path: path.to_owned(),
            what: "a summary warning contains a line break (warnings are stored one per line)"
                .into(),
        });
    }
    write_str_attr(&group, "warnings", &summary.warnings.join("\n"), path)
}
