//! Height arrays on tack's grids: seeded random roughness, spheres, coordinates, the paper's
//! roughness band (`tack.surface`).

use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;
use tack::fields::{self, field_name};
use tack::geometry::{Boundary, Grid, RoughSpec, Sphere, Surface, rough_surface};

use crate::errors::{Names, value_error_named};
use crate::guard::released;

/// The fields of the messages of the grid, the shapes and the roughness generator and the
/// arguments of `tack.surface` they stand for.
const SURFACE_NAMES: Names = &[
    (fields::GRID_NX, "shape[0]"),
    (fields::GRID_NY, "shape[1]"),
    (fields::GRID_DX, "dx"),
    (fields::GEOMETRY_RADIUS, "radius"),
    (fields::GEOMETRY_RADIUS_X, "radius_x"),
    (fields::GEOMETRY_RADIUS_Y, "radius_y"),
    (fields::MATERIAL_GAMMA, "gamma"),
    (fields::ADHESION_GAMMA_B, "gamma_b"),
    (fields::ADHESION_PERIOD, "period"),
    (fields::ADHESION_FRACTION, "fraction"),
    (fields::ADHESION_CONTRAST, "contrast"),
    (fields::ADHESION_CORRELATION_LENGTH, "correlation_length"),
    (fields::ROUGHNESS_HURST, "hurst"),
    (fields::ROUGHNESS_H, "rms"),
    (concat!(field_name!(roughness.q0), "/q1"), "q0/q1"),
    (fields::ROUGHNESS_Q0, "q0"),
    (fields::ROUGHNESS_Q1, "q1"),
];

/// A `TackError` with the message of `e`, fields renamed to the arguments.
fn named(e: impl std::fmt::Display) -> PyErr {
    value_error_named(e, SURFACE_NAMES)
}

fn grid(nx: usize, ny: usize, dx: f64) -> PyResult<Grid> {
    Grid::new(nx, ny, dx, Boundary::Free).map_err(named)
}

/// Seeded random roughness (`tack::geometry::rough_surface`): zero mean, rms `rms`, power law
/// of Hurst exponent `hurst` on the band `q0..q1` (default the paper's 2π/L .. π/dx).
#[pyfunction]
#[pyo3(signature = (nx, ny, *, dx, rms, hurst, seed=0, q0=None, q1=None))]
#[allow(clippy::too_many_arguments)]
fn rough(
    py: Python<'_>,
    nx: usize,
    ny: usize,
    dx: f64,
    rms: f64,
    hurst: f64,
    seed: u64,
    q0: Option<f64>,
    q1: Option<f64>,
) -> PyResult<Bound<'_, PyArray2<f64>>> {
    let grid = grid(nx, ny, dx)?;
    let defaults = RoughSpec::paper_defaults(grid, rms, hurst, seed);
    let spec = RoughSpec {
        q0: q0.unwrap_or(defaults.q0),
        q1: q1.unwrap_or(defaults.q1),
        ..defaults
    };
    let heights = released(py, || {
        rough_surface(grid, &spec)
            .map(Surface::into_heights)
            .map_err(named)
    })?;
    Ok(heights.into_pyarray(py))
}

/// The paraboloid `(x² + y²)/(2R)` sampled at the element centres.
#[pyfunction]
#[pyo3(signature = (nx, ny, *, dx, radius))]
fn sphere(
    py: Python<'_>,
    nx: usize,
    ny: usize,
    dx: f64,
    radius: f64,
) -> PyResult<Bound<'_, PyArray2<f64>>> {
    let grid = grid(nx, ny, dx)?;
    let shape = Sphere::new(radius).map_err(named)?;
    Ok(Surface::from_shape(grid, &shape)
        .into_heights()
        .into_pyarray(py))
}

/// The axisymmetric power law `c·r^m` (a cone for m = 1) sampled at the element centres.
#[pyfunction]
#[pyo3(signature = (nx, ny, *, dx, c, exponent))]
fn power_law(
    py: Python<'_>,
    nx: usize,
    ny: usize,
    dx: f64,
    c: f64,
    exponent: f64,
) -> PyResult<Bound<'_, PyArray2<f64>>> {
    let grid = grid(nx, ny, dx)?;
    let shape = tack::geometry::PowerLaw::new(c, exponent).map_err(named)?;
    Ok(Surface::from_shape(grid, &shape)
        .into_heights()
        .into_pyarray(py))
}

/// The elliptic paraboloid `x²/(2Rx) + y²/(2Ry)` sampled at the element centres.
#[pyfunction]
#[pyo3(signature = (nx, ny, *, dx, radius_x, radius_y))]
fn ellipsoid(
    py: Python<'_>,
    nx: usize,
    ny: usize,
    dx: f64,
    radius_x: f64,
    radius_y: f64,
) -> PyResult<Bound<'_, PyArray2<f64>>> {
    let grid = grid(nx, ny, dx)?;
    let shape = tack::geometry::Ellipsoid::new(radius_x, radius_y).map_err(named)?;
    Ok(Surface::from_shape(grid, &shape)
        .into_heights()
        .into_pyarray(py))
}

/// A generated work-of-adhesion pattern (`tack::geometry::AdhesionPattern`) at the element
/// centres: `kind` is `"stripes"`, `"rings"`, `"checkerboard"` or `"random"`.
#[pyfunction]
#[pyo3(signature = (nx, ny, *, dx, kind, gamma_a, gamma_b=0.0, period=0.0, fraction=0.5, contrast=0.0, correlation_length=0.0, seed=1))]
#[allow(clippy::too_many_arguments)]
fn gamma_pattern<'py>(
    py: Python<'py>,
    nx: usize,
    ny: usize,
    dx: f64,
    kind: &str,
    gamma_a: f64,
    gamma_b: f64,
    period: f64,
    fraction: f64,
    contrast: f64,
    correlation_length: f64,
    seed: u64,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    use tack::geometry::AdhesionPattern;
    let grid = grid(nx, ny, dx)?;
    let pattern = match kind {
        "stripes" => AdhesionPattern::Stripes {
            gamma_a,
            gamma_b,
            period,
            fraction,
        },
        "rings" => AdhesionPattern::Rings {
            gamma_a,
            gamma_b,
            period,
            fraction,
        },
        "checkerboard" => AdhesionPattern::Checkerboard {
            gamma_a,
            gamma_b,
            period,
        },
        "random" => AdhesionPattern::Random {
            mean: gamma_a,
            contrast,
            correlation_length,
            seed,
        },
        other => {
            return Err(named(format!(
                "kind = {other:?} is invalid: must be \"stripes\", \"rings\", \"checkerboard\" or \"random\""
            )));
        }
    };
    Ok(pattern.field(&grid).map_err(named)?.into_pyarray(py))
}

/// Element-centre coordinates `(x, y)`: `x[i] = (i − ⌊nx/2⌋)·dx`, `y[j] = (j − ⌊ny/2⌋)·dx`.
#[pyfunction]
#[pyo3(signature = (nx, ny, *, dx))]
#[allow(clippy::type_complexity)]
fn coordinates(
    py: Python<'_>,
    nx: usize,
    ny: usize,
    dx: f64,
) -> PyResult<(Bound<'_, PyArray1<f64>>, Bound<'_, PyArray1<f64>>)> {
    let grid = grid(nx, ny, dx)?;
    let x: Vec<f64> = (0..nx).map(|i| grid.x(i)).collect();
    let y: Vec<f64> = (0..ny).map(|j| grid.y(j)).collect();
    Ok((x.into_pyarray(py), y.into_pyarray(py)))
}

/// The paper's roughness band on the grid: `(q0, q1) = (2π/L, π/dx)`, L the longer side.
#[pyfunction]
#[pyo3(signature = (nx, ny, *, dx))]
fn band(nx: usize, ny: usize, dx: f64) -> PyResult<(f64, f64)> {
    let grid = grid(nx, ny, dx)?;
    Ok(tack::problem::band(&grid, None, None))
}

/// Registers the surface functions with the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(rough, m)?)?;
    m.add_function(wrap_pyfunction!(sphere, m)?)?;
    m.add_function(wrap_pyfunction!(power_law, m)?)?;
    m.add_function(wrap_pyfunction!(ellipsoid, m)?)?;
    m.add_function(wrap_pyfunction!(gamma_pattern, m)?)?;
    m.add_function(wrap_pyfunction!(coordinates, m)?)?;
    m.add_function(wrap_pyfunction!(band, m)?)?;
    Ok(())
}
