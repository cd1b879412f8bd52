//! Thin helpers over `hdf5`: one way to write and read a dataset, a scalar attribute and a
//! string attribute, each turning library errors into [`IoError`]s that name the path and object.

use std::path::Path;

use hdf5::types::VarLenUnicode;
use hdf5::{Group, H5Type, Location};
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

/// Reads dataset `name` of `group`, which must exist and have dimension `D`.
pub(crate) fn read_dataset<T: H5Type, D: Dimension>(
    group: &Group,
    name: &str,
    path: &Path,
) -> Result<Array<T, D>, IoError> {
    let full = member(group, name);
    if !group.link_exists(name) {
        return Err(missing(path, format!("dataset `{full}`")));
    }
    group
        .dataset(name)
        .and_then(|d| d.read::<T, D>())
        .map_err(h5err(path, format!("reading dataset `{full}`")))
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
