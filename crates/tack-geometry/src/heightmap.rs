//! Height-map import from plain text / CSV: one line per x index, one cell per y index.
//!
//! Line `i` of data holds `heights[[i, 0..ny]]` (the layout `numpy.savetxt` writes for an
//! `(nx, ny)` array). Cells are separated by commas, else semicolons, else tabs/spaces; blank
//! lines and lines starting with `#` are skipped, and a comment `# dx = 0.001` (or `# dx: ...`)
//! supplies the element size unless the caller passes one.

use std::path::Path;

use ndarray::Array2;

use crate::error::{GeometryError, positive};
use crate::{Boundary, Grid, Surface};

fn parse_error(message: String) -> GeometryError {
    GeometryError::Parse(message)
}

/// The value of a `dx = ...` / `dx: ...` header comment, if `comment` is one.
fn dx_header(comment: &str) -> Option<&str> {
    let rest = comment.trim().strip_prefix("dx")?.trim_start();
    rest.strip_prefix('=')
        .or_else(|| rest.strip_prefix(':'))
        .map(str::trim)
}

/// Parses a height map; returns the heights `(nx, ny)` and the element size `dx`.
///
/// `dx` given here wins over a `# dx = ...` header; with neither, the error names
/// `heightmap.dx`. Errors name the line (1-based, counting every line) and column of a ragged
/// row, an unparseable or non-finite cell, and reject an empty map.
pub fn read_height_map_text(
    text: &str,
    dx: Option<f64>,
) -> Result<(Array2<f64>, f64), GeometryError> {
    let mut header_dx: Option<f64> = None;
    let mut values = Vec::new();
    let (mut rows, mut cols) = (0, 0);
    for (index, line) in text.trim_start_matches('\u{feff}').lines().enumerate() {
        let (line_no, line) = (index + 1, line.trim());
        if let Some(comment) = line.strip_prefix('#') {
            if let Some(value) = dx_header(comment) {
                let parsed = value.parse::<f64>().map_err(|_| {
                    parse_error(format!(
                        "line {line_no}: dx header value `{value}` is not a number"
                    ))
                })?;
                if header_dx.is_some_and(|d| d != parsed) {
                    return Err(parse_error(format!(
                        "line {line_no}: second dx header ({parsed}) contradicts the first ({})",
                        header_dx.unwrap_or_default()
                    )));
                }
                header_dx = Some(parsed);
            }
            continue;
        }
        if line.is_empty() {
            continue;
        }
        let cells: Vec<&str> = match [',', ';'].into_iter().find(|&c| line.contains(c)) {
            Some(sep) => line.split(sep).map(str::trim).collect(),
            None => line.split_whitespace().collect(),
        };
        if rows == 0 {
            cols = cells.len();
        } else if cells.len() != cols {
            return Err(parse_error(format!(
                "line {line_no}: expected {cols} columns (as in the first data row), found {}",
                cells.len()
            )));
        }
        for (column, cell) in cells.iter().enumerate() {
            let value = cell.parse::<f64>().ok().filter(|v| v.is_finite());
            values.push(value.ok_or_else(|| {
                parse_error(format!(
                    "line {line_no}, column {}: `{cell}` is not a finite number",
                    column + 1
                ))
            })?);
        }
        rows += 1;
    }
    if rows == 0 {
        return Err(parse_error("empty height map: no data rows".into()));
    }
    let dx = dx.or(header_dx).ok_or_else(|| {
        parse_error(
            "heightmap.dx is missing: pass dx or add a `# dx = <element size>` header line".into(),
        )
    })?;
    let heights = Array2::from_shape_vec((rows, cols), values)
        .map_err(|e| GeometryError::Mismatch(e.to_string()))?;
    Ok((heights, positive("heightmap.dx", dx)?))
}

/// Reads a height-map file (see [`read_height_map_text`]); errors name the path.
pub fn read_height_map_file(
    path: &Path,
    dx: Option<f64>,
) -> Result<(Array2<f64>, f64), GeometryError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| parse_error(format!("cannot read `{}`: {e}", path.display())))?;
    read_height_map_text(&text, dx).map_err(|e| match e {
        GeometryError::Parse(m) => parse_error(format!("{}: {m}", path.display())),
        other => other,
    })
}

/// Wraps imported heights `(nx, ny)` with element size `dx` into a surface on a matching grid.
pub fn height_map_surface(
    boundary: Boundary,
    heights: Array2<f64>,
    dx: f64,
) -> Result<Surface, GeometryError> {
    let (nx, ny) = heights.dim();
    Surface::new(Grid::new(nx, ny, dx, boundary)?, heights)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str, dx: Option<f64>) -> String {
        read_height_map_text(text, dx).unwrap_err().to_string()
    }

    #[test]
    fn reads_every_separator_and_the_dx_header() {
        let want = ndarray::array![[1.0, 2.0, 3.0], [4.0, 5.0, -6e-3]];
        for text in [
            "# dx = 0.5\n1,2,3\n4, 5 ,-6e-3\n",
            "# measured profile\n#dx: 0.5\n\n1;2;3\r\n4;5;-6e-3",
            "\u{feff}# dx=0.5\n1\t2\t3\n  4  5\t-6e-3\n\n",
        ] {
            let (h, dx) = read_height_map_text(text, None).unwrap();
            assert_eq!((h, dx), (want.clone(), 0.5), "{text:?}");
        }
        let (_, dx) = read_height_map_text("# dx = 0.5\n1 2\n", Some(0.25)).unwrap();
        assert_eq!(dx, 0.25, "the argument wins over the header");
    }

    #[test]
    fn reports_each_error_with_line_column_or_field() {
        let cases = [
            ("1 2\n", None, "heightmap.dx"),
            ("1 2\n", Some(0.0), "heightmap.dx"),
            ("# dx = -1\n1 2\n", None, "heightmap.dx"),
            ("# dx = abc\n1 2\n", None, "line 1: dx header"),
            ("# dx = 1\n# dx = 2\n1\n", None, "line 2: second dx header"),
            ("1,2,3\n\n4,5\n", Some(1.0), "line 3: expected 3 columns"),
            ("1 2\n3 x\n", Some(1.0), "line 2, column 2: `x`"),
            ("1 NaN\n", Some(1.0), "line 1, column 2: `NaN`"),
            ("1,inf\n", Some(1.0), "line 1, column 2: `inf`"),
            ("1,2,\n", Some(1.0), "line 1, column 3: ``"),
            ("# dx = 1\n\n", None, "empty height map"),
            ("", Some(1.0), "empty height map"),
        ];
        for (text, dx, want) in cases {
            let e = err(text, dx);
            assert!(e.contains(want), "{text:?}: {e}");
        }
    }

    #[test]
    fn reads_a_file_into_a_surface_and_names_missing_paths() {
        let path = std::env::temp_dir().join(format!(
            "tack-geometry-heightmap-{}-{:?}.csv",
            std::process::id(),
            std::thread::current().id()
        ));
        std::fs::write(&path, "# dx = 1e-3\n0,1\n2,3\n4,5\n").unwrap();
        let read = read_height_map_file(&path, None);
        let bad = std::fs::write(&path, "0,1\n2\n").map(|_| read_height_map_file(&path, None));
        std::fs::remove_file(&path).unwrap();
        let (h, dx) = read.unwrap();
        let s = height_map_surface(Boundary::Free, h, dx).unwrap();
        assert_eq!((s.grid().shape(), s.grid().dx()), ((3, 2), 1e-3));
        assert_eq!(s.heights()[[2, 1]], 5.0);
        let e = bad.unwrap().unwrap_err().to_string();
        assert!(
            e.contains(&*path.to_string_lossy()) && e.contains("line 2"),
            "{e}"
        );
        let e = read_height_map_file(&path, Some(1.0))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("cannot read") && e.contains(&*path.to_string_lossy()),
            "{e}"
        );
        let e = height_map_surface(Boundary::Free, Array2::zeros((2, 2)), -1.0).unwrap_err();
        assert!(e.to_string().contains("grid.dx"), "{e}");
    }
}
