//! Reading a map file (heights or a work of adhesion; HDF5 by extension, else text) for a
//! scene, with the file, shape and `dx` checks and messages that name the scene's fields.

use std::path::Path;

use tack_fields as fields;
use tack_geometry::Grid;

use crate::scene::SceneError;

/// Relative tolerance on a map's `dx` against `grid.dx`.
pub const DX_MATCH_TOLERANCE: f64 = 1e-9;

/// Reads a map (heights or γ; HDF5 by extension, else text) and checks its `dx` against the
/// grid's; `names` are the fields of its path and dataset, for messages.
/// A text map without a `# dx = ...` header takes the grid's `dx`.
pub(crate) fn read_map(
    full: &Path,
    given: &Path,
    dataset: Option<&str>,
    grid: &Grid,
    names: (&'static str, &'static str),
) -> Result<ndarray::Array2<f64>, SceneError> {
    let field = |what: String| {
        SceneError::Inconsistent(format!("{} = `{}`: {what}", names.0, given.display()))
    };
    let is_h5 = full
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| matches!(e.to_ascii_lowercase().as_str(), "h5" | "hdf5"));
    match std::fs::metadata(full) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(field(format!(
                "no such file (looked for `{}`)",
                full.display()
            )));
        }
        Err(e) => {
            return Err(field(format!("cannot read `{}`: {e}", full.display())));
        }
        Ok(m) if m.is_dir() => {
            return Err(field(format!(
                "`{}` is a directory, not a map file",
                full.display()
            )));
        }
        Ok(m) if !m.is_file() => {
            return Err(field(format!(
                "`{}` is not a regular file (a device, FIFO or socket), not a map file",
                full.display()
            )));
        }
        Ok(_) => {}
    }
    let (heights, dx) = if is_h5 {
        // The grid's shape: a map declaring another is refused before its data is read.
        let read = if names.0 == fields::ADHESION_GAMMA_MAP {
            tack_io::read_gamma_map_h5
        } else {
            tack_io::read_height_map_h5
        };
        read(full, dataset, Some(grid.shape())).map_err(|e| field(e.to_string()))?
    } else {
        if dataset.is_some() {
            return Err(field(format!(
                "{} applies only to HDF5 maps (.h5, .hdf5)",
                names.1
            )));
        }
        // Parse with the grid's dx (succeeds whatever the header says), then read the
        // header's own dx: a parse error now means there is no header.
        let (heights, _) = tack_geometry::read_height_map_file(full, Some(grid.dx()))
            .map_err(|e| field(e.to_string()))?;
        match tack_geometry::read_height_map_file(full, None) {
            Ok((_, dx)) => (heights, dx),
            Err(tack_geometry::GeometryError::Parse(_)) => (heights, grid.dx()),
            Err(e) => return Err(field(e.to_string())),
        }
    };
    if ((dx - grid.dx()) / grid.dx()).abs() > DX_MATCH_TOLERANCE {
        return Err(field(format!(
            "the map's dx = {dx} differs from {dx_field} = {} (relative tolerance \
             {DX_MATCH_TOLERANCE:e}); set {dx_field} to the map's element size",
            grid.dx(),
            dx_field = fields::GRID_DX
        )));
    }
    Ok(heights)
}
