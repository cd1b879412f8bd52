//! The error type of every fallible operation of this crate.

use std::path::PathBuf;

/// What went wrong reading or writing a file; every message starts with the file's path.
#[derive(Debug, thiserror::Error)]
pub enum IoError {
    /// The file to read does not exist.
    #[error("{}: no such file", path.display())]
    MissingFile {
        /// The file asked for.
        path: PathBuf,
    },
    /// The directory a result should be written into does not exist.
    #[error("{}: parent directory `{}` does not exist", path.display(), parent.display())]
    MissingParent {
        /// The file to be written.
        path: PathBuf,
        /// Its missing parent directory.
        parent: PathBuf,
    },
    /// A required dataset, group or attribute is absent from the file.
    #[error("{}: missing {what}", path.display())]
    Missing {
        /// The file.
        path: PathBuf,
        /// The absent object, e.g. "attribute `dx` of `/heights`".
        what: String,
    },
    /// Curve columns differ in length.
    #[error(
        "{}: curve column `{column}` has {len} entries, but `approach` has {expected}",
        path.display()
    )]
    ColumnLength {
        /// The file.
        path: PathBuf,
        /// The offending column.
        column: String,
        /// Its length.
        len: usize,
        /// The length of `approach`.
        expected: usize,
    },
    /// A height or work-of-adhesion map holds a NaN or infinite value.
    #[error(
        "{}: dataset `{dataset}` holds the non-finite {quantity} {value} at index [{}, {}]",
        path.display(), index[0], index[1]
    )]
    NonFinite {
        /// The file.
        path: PathBuf,
        /// The map's dataset.
        dataset: String,
        /// What the map holds: `height` or `work of adhesion`.
        quantity: &'static str,
        /// The first bad element, in row-major order.
        index: [usize; 2],
        /// Its value.
        value: f64,
    },
    /// A dataset or attribute declares more data than its file can hold, or than one read may
    /// allocate ([`crate::MAX_DATASET_BYTES`]): the file is corrupt (or not tack's), and nothing
    /// of the object was read.
    #[error("{}: {object} declares shape {shape}: {why}", path.display())]
    Oversized {
        /// The file.
        path: PathBuf,
        /// The object, e.g. "dataset `/curve/approach`".
        object: String,
        /// The declared shape, e.g. "1048576 × 1048576".
        shape: String,
        /// Which bound it exceeds, with the numbers.
        why: String,
    },
    /// The data (to write, or read back) is inconsistent or out of range.
    #[error("{}: {what}", path.display())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// What is wrong, naming the object and the value.
        what: String,
    },
    /// The HDF5 library reported an error.
    #[error("{}: {what}: {cause}", path.display())]
    Hdf5 {
        /// The file.
        path: PathBuf,
        /// The operation that failed, naming the object.
        what: String,
        /// The library's error.
        cause: hdf5::Error,
    },
    /// A file-system operation failed.
    #[error("{}: {what}: {cause}", path.display())]
    Fs {
        /// The file.
        path: PathBuf,
        /// The operation that failed.
        what: String,
        /// The operating system's error.
        cause: std::io::Error,
    },
}
