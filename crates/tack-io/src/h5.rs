//! Thin helpers over `hdf5`: one way to write and read a dataset, a scalar attribute and a
//! string attribute, each turning library errors into [`IoError`]s that name the path and object;
//! and the bounds every read checks first ([`check_extent`], [`Budget`]), so that a corrupt
//! file declaring more data than it holds is refused instead of allocated.

use std::path::Path;

use hdf5::types::VarLenUnicode;
use hdf5::{Container, Dataset, Group, H5Type, Location};
use ndarray::{Array, ArrayView, Dimension};

use crate::IoError;

/// Maps an HDF5 error to [`IoError::Hdf5`] naming `path` and the failed operation.
pub(crate) fn h5err(path: &Path, what: impl Into<String>) -> impl FnOnce(hdf5::Error) -> IoError {
    let (path, what) = (path.to_owned(), what.into());
    move |cause| IoError::Hdf5 { path, what, cause }
}

/// Absolute name of member `name` of `loc`, e.g. `/curve/force`.
pub(crate) fn member(loc: &Location, name: &str) -> String {
    let parent = loc.name();
    format!("{}/{name}", parent.trim_end_matches('/'))
}

fn missing(path: &Path, what: String) -> IoError {
    IoError::Missing {
        path: path.to_owned(),
        what,
    }
}

/// Creates group `name` in `parent`.
pub(crate) fn create_group(parent: &Group, name: &str, path: &Path) -> Result<Group, IoError> {
    let full = member(parent, name);
    parent
        .create_group(name)
        .map_err(h5err(path, format!("creating group `{full}`")))
}

/// Opens group `name` of `parent`, which must exist.
pub(crate) fn open_group(parent: &Group, name: &str, path: &Path) -> Result<Group, IoError> {
    let full = member(parent, name);
    if !parent.link_exists(name) {
        return Err(missing(path, format!("group `{full}`")));
    }
    parent
        .group(name)
        .map_err(h5err(path, format!("opening group `{full}`")))
}

/// Writes `data` as a new dataset `name` of `group`.
pub(crate) fn write_dataset<'d, T: H5Type + Clone, D: Dimension>(
    group: &Group,
    name: &str,
    data: ArrayView<'d, T, D>,
    path: &Path,
) -> Result<hdf5::Dataset, IoError> {
    let full = member(group, name);
    let data = data.as_standard_layout();
    group
        .new_dataset_builder()
        .with_data(data.view())
        .create(name)
        .map_err(h5err(path, format!("writing dataset `{full}`")))
}

/// Opens dataset `name` of `group`, which must exist.
pub(crate) fn open_dataset(group: &Group, name: &str, path: &Path) -> Result<Dataset, IoError> {
    let full = member(group, name);
    if !group.link_exists(name) {
        return Err(missing(path, format!("dataset `{full}`")));
    }
    group
        .dataset(name)
        .map_err(h5err(path, format!("opening dataset `{full}`")))
}

/// The shape dataset `ds` (named `full`) declares, read without touching its data.
pub(crate) fn declared_shape(ds: &Dataset, full: &str, path: &Path) -> Result<Vec<usize>, IoError> {
    ds.space().map(|space| space.shape()).map_err(h5err(
        path,
        format!("reading the shape of dataset `{full}`"),
    ))
}

/// Reads dataset `name` of `group`, which must exist and have dimension `D`, after checking its
/// declared size against [`MAX_DATASET_BYTES`] and `budget` ([`check_extent`]).
pub(crate) fn read_dataset<T: H5Type, D: Dimension>(
    group: &Group,
    name: &str,
    path: &Path,
    budget: &mut Budget,
) -> Result<Array<T, D>, IoError> {
    let full = member(group, name);
    let ds = open_dataset(group, name, path)?;
    check_extent::<T>(&ds, &format!("dataset `{full}`"), path, Some(budget))?;
    ds.read::<T, D>()
        .map_err(h5err(path, format!("reading dataset `{full}`")))
}

/// The most bytes one dataset or attribute may take in memory once read, whatever its file
/// declares: 2 GiB, 32 times the largest surface tack solves (2²⁶ f64 heights). A larger
/// declared size is refused ([`IoError::Oversized`]) before anything is allocated.
pub const MAX_DATASET_BYTES: u64 = 1 << 31;

/// How much data a file may still declare.
///
/// tack writes every dataset contiguous and uncompressed, so the datasets of one of its files
/// together hold at most the file's size on disk; each read takes its dataset's declared size
/// (elements × element size in the file) from the budget, and a dataset that does not fit is
/// refused before it is read: the file is corrupt, truncated, or not written by tack. (Files of
/// other programs may be compressed; see `read_height_map_h5` for those.)
#[derive(Debug, Clone)]
pub(crate) struct Budget {
    file_len: u64,
    remaining: u64,
}

impl Budget {
    /// The whole size on disk of the file at `path`.
    pub(crate) fn of_file(path: &Path) -> Result<Self, IoError> {
        let file_len = std::fs::metadata(path)
            .map_err(|cause| IoError::Fs {
                path: path.to_owned(),
                what: "reading its size".into(),
                cause,
            })?
            .len();
        Ok(Self {
            file_len,
            remaining: file_len,
        })
    }
}

/// `a × b × ...`, the way messages write shapes (`[]`, a scalar, as `1`).
pub(crate) fn dims(shape: &[usize]) -> String {
    match shape {
        [] => "1 (a scalar)".to_owned(),
        _ => shape
            .iter()
            .map(usize::to_string)
            .collect::<Vec<_>>()
            .join(" × "),
    }
}

/// Checks the extent that `obj` (a dataset or attribute, described as `object`, e.g. "dataset
/// `/curve/force`") declares, before it is read as `T`: the element count must be countable;
/// given a `budget`, its size in the file must fit what is left of the budget (which it then
/// takes); and its size in memory must be at most [`MAX_DATASET_BYTES`]. Returns the declared
/// shape.
pub(crate) fn check_extent<T: H5Type>(
    obj: &Container,
    object: &str,
    path: &Path,
    budget: Option<&mut Budget>,
) -> Result<Vec<usize>, IoError> {
    let shape = obj
        .space()
        .map(|space| space.shape())
        .map_err(h5err(path, format!("reading the shape of {object}")))?;
    let file_elem = obj
        .dtype()
        .map(|t| t.size() as u64)
        .map_err(h5err(path, format!("reading the type of {object}")))?;
    let mem_elem = std::mem::size_of::<T>() as u64;
    let oversized = |why: String| IoError::Oversized {
        path: path.to_owned(),
        object: object.to_owned(),
        shape: dims(&shape),
        why,
    };
    let count = shape
        .iter()
        .try_fold(1_u64, |n, &d| n.checked_mul(d as u64));
    let sizes = count.and_then(|n| Some((n, n.checked_mul(mem_elem)?, n.checked_mul(file_elem)?)));
    let Some((count, in_memory, in_file)) = sizes else {
        return Err(oversized(
            "more bytes than 64 bits can count: the file is corrupt".into(),
        ));
    };
    if let Some(budget) = budget {
        if in_file > budget.remaining {
            let held = if budget.remaining == budget.file_len {
                format!("the whole file is {} bytes", budget.file_len)
            } else {
                format!(
                    "the file ({} bytes) has only {} bytes beside the data read before it",
                    budget.file_len, budget.remaining
                )
            };
            return Err(oversized(format!(
                "{count} elements of {file_elem} bytes are {in_file} bytes, but {held}: the \
                 file is corrupt or truncated"
            )));
        }
        budget.remaining -= in_file;
    }
    if in_memory > MAX_DATASET_BYTES {
        return Err(oversized(format!(
            "{count} elements of {mem_elem} bytes are {in_memory} bytes, more than the \
             {MAX_DATASET_BYTES} bytes one read may take: the file is corrupt, or not a tack \
             input"
        )));
    }
    Ok(shape)
}

/// Writes the scalar attribute `name` of `loc`.
pub(crate) fn write_attr<T: H5Type>(
    loc: &Location,
    name: &str,
    value: &T,
    path: &Path,
) -> Result<(), IoError> {
    loc.new_attr::<T>()
        .shape(())
        .create(name)
        .and_then(|a| a.write_scalar(value))
        .map_err(h5err(
            path,
            format!("writing attribute `{name}` of `{}`", loc.name()),
        ))
}

/// Writes `value` as the variable-length UTF-8 string attribute `name` of `loc`.
pub(crate) fn write_str_attr(
    loc: &Location,
    name: &str,
    value: &str,
    path: &Path,
) -> Result<(), IoError> {
    let value: VarLenUnicode = value.parse().map_err(|_| IoError::Invalid {
        path: path.to_owned(),
        what: format!("attribute `{name}` contains a NUL character"),
    })?;
    write_attr(loc, name, &value, path)
}

/// Whether `loc` has the attribute `name`.
pub(crate) fn has_attr(loc: &Location, name: &str, path: &Path) -> Result<bool, IoError> {
    let names = loc.attr_names().map_err(h5err(
        path,
        format!("listing attributes of `{}`", loc.name()),
    ))?;
    Ok(names.iter().any(|n| n == name))
}

/// Reads the scalar attribute `name` of `loc`, or `None` when absent.
pub(crate) fn read_opt_attr<T: H5Type>(
    loc: &Location,
    name: &str,
    path: &Path,
) -> Result<Option<T>, IoError> {
    if !has_attr(loc, name, path)? {
        return Ok(None);
    }
    loc.attr(name)
        .and_then(|a| a.read_scalar::<T>())
        .map(Some)
        .map_err(h5err(
            path,
            format!("reading attribute `{name}` of `{}`", loc.name()),
        ))
}

/// Reads the scalar attribute `name` of `loc`, which must exist.
pub(crate) fn read_attr<T: H5Type>(loc: &Location, name: &str, path: &Path) -> Result<T, IoError> {
    read_opt_attr(loc, name, path)?
        .ok_or_else(|| missing(path, format!("attribute `{name}` of `{}`", loc.name())))
}

/// Reads the variable-length UTF-8 string attribute `name` of `loc`, which must exist.
pub(crate) fn read_str_attr(loc: &Location, name: &str, path: &Path) -> Result<String, IoError> {
    let value: VarLenUnicode = read_attr(loc, name, path)?;
    // hdf5 does not check the bytes are UTF-8; do it here rather than trust the file.
    String::from_utf8(value.as_bytes().to_vec()).map_err(|_| IoError::Invalid {
        path: path.to_owned(),
        what: format!("attribute `{name}` of `{}` is not valid UTF-8", loc.name()),
    })
}
