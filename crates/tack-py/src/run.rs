//! Scene runs and pull-offs of height arrays: `tack.run` and `tack.pull_off`.

use std::path::PathBuf;

use numpy::PyReadonlyArray2;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use tack::fields::{self, field_name};
use tack::{RunOptions, Scene};

use crate::errors::{Names, to_py, value_error, value_error_named};
use crate::guard::detached;
use crate::result::Result;

/// Largest accepted `threads`.
pub const MAX_THREADS: usize = tack::MAX_THREADS;

/// The scene fields of the messages of `tack::heights::pull_off` and the arguments of
/// `tack.pull_off` they stand for (the scene is written by the library from the arguments).
const PULL_OFF_NAMES: Names = &[
    // An array's default path: a sphere-like array or a given radius, never a scene's shape.
    (
        concat!(
            "a sphere (",
            field_name!(geometry.shape),
            " = \"sphere\") or a sphere-like height map"
        ),
        "a radius (radius=...) or a sphere-like height array",
    ),
    (fields::MATERIAL_E_STAR, "e_star"),
    (fields::MATERIAL_GAMMA, "gamma"),
    (
        concat!(field_name!(grid.nx), " × ", field_name!(grid.ny)),
        "heights.shape",
    ),
    (
        concat!(field_name!(grid.nx), "/", field_name!(grid.ny)),
        "heights.shape",
    ),
    (fields::GRID_NX, "heights.shape[0]"),
    (fields::GRID_NY, "heights.shape[1]"),
    (fields::GRID_DX, "dx"),
    (fields::PROTOCOL_MAX_APPROACH, "max_approach"),
    (fields::PROTOCOL_COARSE_UNLOAD_STEP, "coarse_unload_step"),
    (fields::PROTOCOL_REFINE_PULL_OFF, "refine_pull_off"),
    (fields::PROTOCOL_UNLOAD_STEP, "unload_step"),
    (fields::PROTOCOL_LOAD_STEP, "load_step"),
    // `material.prony` stays: the attribute of `material=tack.Viscoelastic(...)`.
    (fields::PROTOCOL_UNLOAD_SPEED, "material.unload_speed"),
    (fields::PROTOCOL_DWELL_STEPS, "material.dwell_steps"),
    (fields::PROTOCOL_DWELL, "material.dwell"),
    (fields::PROTOCOL_SPEED, "material.speed"),
    (fields::SOLVER_KAPPA, "law.kappa"),
    (fields::ADHESION_SIGMA0, "law.sigma0"),
    (fields::ADHESION_RANGE, "law.range"),
    (
        concat!(field_name!(adhesion.model), " = \"dugdale\""),
        "law=tack.Dugdale(sigma0=...)",
    ),
    (
        concat!(field_name!(adhesion.model), " = \"jkr_limit\""),
        "law=tack.JkrLimit()",
    ),
    (fields::ADHESION_MODEL, "law"),
    // `pull_off` has no step cap of its own: a longer path is a scene's, run by `tack.run`.
    (
        concat!("the default ", field_name!(protocol.max_steps)),
        "pull_off's step cap",
    ),
    (
        concat!("raise ", field_name!(protocol.max_steps)),
        "run the body as a scene through tack.run with a higher [protocol] max_steps",
    ),
    (
        concat!(
            "set ",
            field_name!(protocol.max_steps),
            " (a cap of your own stops the run there)"
        ),
        "run the body as a scene through tack.run with a [protocol] max_steps of its own \
         (the run stops there)",
    ),
    (
        concat!("lower ", field_name!(protocol.max_steps)),
        "give a shorter path (a larger unload_step or a smaller max_approach)",
    ),
    (fields::PROTOCOL_MAX_STEPS, "pull_off's step cap"),
    (fields::OUTPUT_SNAPSHOTS, "snapshots"),
    // `body.thickness` and `body.poisson` stay as they are: the attributes of `body=tack.Layer(...)`.
    (fields::GRID_N, "heights.shape"),
    (fields::GRID_LENGTH, "dx"),
    (fields::PROTOCOL_START, "the load's first approach"),
    (
        "the non-adhesive tack_solver::ContactSolver",
        "tack.contact",
    ),
    ("tack_solver::ContactSolver", "tack.contact"),
];

/// Checks `threads` (1..=[`MAX_THREADS`]) before anything runs, the same way for every
/// function that takes it: the threads one solve splits its FFTs across (bit-identical results
/// on any count).
pub fn check_threads(threads: Option<i64>) -> PyResult<Option<usize>> {
    threads
        .map(|n| tack::check_threads("threads", n.into()).map_err(|e| value_error(e.to_string())))
        .transpose()
}

/// A Python value as a TOML value, for `overrides`; errors name `overrides['key']`.
fn toml_value(key: &str, value: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    let bad = |what: String| PyTypeError::new_err(format!("overrides['{key}']: {what}"));
    if value.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(value.extract()?));
    }
    if value.is_instance_of::<PyInt>() {
        return value
            .extract::<i64>()
            .map(toml::Value::Integer)
            .map_err(|_| {
                value_error(format!(
                    "overrides['{key}'] = {value} is invalid: must be an integer in the range of a \
                 64-bit signed integer"
                ))
            });
    }
    if value.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(value.extract()?));
    }
    if value.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(value.extract()?));
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        let items = value
            .try_iter()?
            .map(|item| toml_value(key, &item?))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(items));
    }
    if let Ok(dict) = value.cast::<PyDict>() {
        let mut table = toml::Table::new();
        for (k, v) in dict.iter() {
            let k: String = k
                .extract()
                .map_err(|_| bad("table keys must be strings".into()))?;
            let sub = toml_value(&format!("{key}.{k}"), &v)?;
            table.insert(k, sub);
        }
        return Ok(toml::Value::Table(table));
    }
    // numpy scalars and other numbers: booleans, integers (__index__), then real numbers
    // (`numbers.Real`: not complex numbers, whose conversion to float drops the imaginary part).
    let type_name = value.get_type().name()?.to_string();
    if type_name.starts_with("bool") {
        if let Ok(b) = value.extract::<bool>() {
            return Ok(toml::Value::Boolean(b));
        }
    }
    if value.hasattr("__index__")? {
        if let Ok(i) = value.extract::<i64>() {
            return Ok(toml::Value::Integer(i));
        }
    }
    let real = value.py().import("numbers")?.getattr("Real")?;
    if value.is_instance(&real)?
        && let Ok(f) = value.extract::<f64>()
    {
        return Ok(toml::Value::Float(f));
    }
    Err(bad(format!(
        "a value of type {type_name} has no TOML form (use bool, int, float, str, list or dict)"
    )))
}

/// `overrides` as `--set key=value` assignments, values as TOML literals.
fn assignments(overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<String>> {
    let Some(overrides) = overrides else {
        return Ok(Vec::new());
    };
    overrides
        .iter()
        .map(|(k, v)| {
            let key: String = k
                .extract()
                .map_err(|_| PyTypeError::new_err("overrides: keys must be dotted strings"))?;
            let value = toml_value(&key, &v)?;
            Ok(format!("{key}={value}"))
        })
        .collect()
}

/// Runs a scene given as a file (`path`) or as TOML text (`text`, relative paths against
/// `base_dir`) in memory.
#[pyfunction]
#[pyo3(signature = (*, path=None, text=None, base_dir=None, overrides=None, richardson=false, threads=None, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn run_scene(
    py: Python<'_>,
    path: Option<PathBuf>,
    text: Option<String>,
    base_dir: Option<PathBuf>,
    overrides: Option<Bound<'_, PyDict>>,
    richardson: bool,
    threads: Option<i64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Result> {
    let threads = check_threads(threads)?;
    let overrides = assignments(overrides.as_ref())?;
    let scene = match (path, text) {
        (Some(path), None) => Scene::load(&path, &overrides),
        (None, Some(text)) => Scene::parse(
            &text,
            base_dir.unwrap_or_else(|| PathBuf::from(".")),
            &overrides,
        ),
        _ => return Err(value_error("run_scene: give exactly one of path and text")),
    }
    .map_err(|e| to_py(&overrides_named(e).into()))?;
    let options = RunOptions {
        command_line: Some(command_line(py)),
        richardson,
        threads,
    };
    let outcome = detached(py, progress, &[], |observer| {
        tack::run(&scene, &options, observer)
    })?;
    let wall_time = outcome.total_wall_time().as_secs_f64();
    Ok(Result::new(outcome.result, Some(wall_time)))
}

/// A scene error with an override (the CLI's `--set key=value`) named as the Python argument
/// that gave it: `overrides["key"] = value`.
fn overrides_named(e: tack::SceneError) -> tack::SceneError {
    match e {
        tack::SceneError::Override { assignment, reason } => {
            let shown = match assignment.split_once('=') {
                Some((key, value)) => format!("overrides[\"{key}\"] = {value}"),
                None => format!("overrides[\"{assignment}\"]"),
            };
            tack::SceneError::Inconsistent(format!("{shown}: {reason}"))
        }
        other => other,
    }
}

/// The command line recorded in provenance: the Python process's `sys.argv`.
fn command_line(py: Python<'_>) -> String {
    let argv: Vec<String> = py
        .import("sys")
        .and_then(|sys| sys.getattr("argv"))
        .and_then(|argv| argv.extract())
        .unwrap_or_default();
    let mut line = String::from("python");
    for a in argv {
        line.push(' ');
        if a.is_empty() || a.contains(char::is_whitespace) {
            line.push_str(&format!("{a:?}"));
        } else {
            line.push_str(&a);
        }
    }
    line
}

/// The pull-off of a body given as heights (`tack::heights::pull_off`).
#[pyfunction]
#[pyo3(signature = (heights, *, dx, e_star, gamma, gamma_map=None, periodic=false, radius=None, max_approach=None, unload_step=None, coarse_unload_step=None, refine_pull_off=false, kappa=None, model="jkr_limit", sigma0=None, range=None, snapshots=None, threads=None, progress=None, thickness=None, poisson=None, interface=None, richardson=false, load_step=None, prony=None, speed=None, unload_speed=None, dwell=None, dwell_steps=None))]
#[allow(clippy::too_many_arguments)]
pub fn pull_off(
    py: Python<'_>,
    heights: PyReadonlyArray2<'_, f64>,
    dx: f64,
    e_star: f64,
    gamma: f64,
    gamma_map: Option<PyReadonlyArray2<'_, f64>>,
    periodic: bool,
    radius: Option<f64>,
    max_approach: Option<f64>,
    unload_step: Option<f64>,
    coarse_unload_step: Option<f64>,
    refine_pull_off: bool,
    kappa: Option<f64>,
    model: &str,
    sigma0: Option<f64>,
    range: Option<f64>,
    snapshots: Option<Bound<'_, PyAny>>,
    threads: Option<i64>,
    progress: Option<Py<PyAny>>,
    thickness: Option<f64>,
    poisson: Option<f64>,
    interface: Option<String>,
    richardson: bool,
    load_step: Option<f64>,
    prony: Option<Vec<(f64, f64)>>,
    speed: Option<f64>,
    unload_speed: Option<f64>,
    dwell: Option<f64>,
    dwell_steps: Option<usize>,
) -> PyResult<Result> {
    let threads = check_threads(threads)?;
    // `tack.Viscoelastic` gives the arms and the speed together; the rates alone are refused
    // by the scene's own check, which names them.
    let viscoelastic = match (prony, speed) {
        (Some(arms), Some(speed)) => Some(tack::heights::ViscoelasticSpec {
            prony: arms.into_iter().map(|(e, t)| [e, t]).collect(),
            speed,
            unload_speed,
            dwell,
            dwell_steps,
        }),
        (None, None) => None,
        _ => {
            return Err(value_error(
                "material: a viscoelastic solid needs both its arms (prony) and its speed"
                    .to_string(),
            ));
        }
    };
    let body = match crate::body::layer_of(thickness, poisson, interface.as_deref())? {
        None => tack::scene::BodySpec::default(),
        Some(layer) => tack::scene::BodySpec {
            kind: tack::scene::BodyKind::Layer,
            thickness: Some(layer.thickness),
            poisson: Some(layer.poisson),
            interface: Some(match layer.interface {
                tack::kernels::Interface::Bonded => tack::scene::InterfaceKind::Bonded,
                tack::kernels::Interface::Frictionless => tack::scene::InterfaceKind::Frictionless,
            }),
        },
    };
    let snapshots = match snapshots {
        None => tack::scene::Snapshots::PullOff,
        Some(value) => {
            let value = toml_value("snapshots", &value)?;
            tack::scene::Snapshots::try_from(value)
                .map_err(|e| value_error_named(e, PULL_OFF_NAMES))?
        }
    };
    let model = tack::AdhesionModel::from_name(model).ok_or_else(|| {
        value_error(format!(
            "model = {model:?} is invalid: must be {}",
            tack::AdhesionModel::names()
        ))
    })?;
    let spec = tack::heights::PullOffSpec {
        dx,
        boundary: if periodic {
            tack::geometry::Boundary::Periodic
        } else {
            tack::geometry::Boundary::Free
        },
        e_star,
        gamma,
        radius,
        max_approach,
        unload_step,
        coarse_unload_step,
        refine_pull_off,
        kappa,
        adhesion: tack::AdhesionSpec {
            model,
            sigma0,
            range,
            ..tack::AdhesionSpec::default()
        },
        snapshots,
        gamma_map: gamma_map.map(|g| g.as_array().to_owned()),
        body,
        load_step,
        viscoelastic,
    };
    let heights = heights.as_array().to_owned();
    let options = RunOptions {
        command_line: Some(command_line(py)),
        richardson: false,
        threads,
    };
    let mut outcome = detached(py, progress, PULL_OFF_NAMES, |observer| {
        if richardson {
            tack::heights_richardson::pull_off_richardson(&heights, &spec, &options, observer)
        } else {
            tack::heights::pull_off(&heights, &spec, &options, observer)
        }
    })?;
    // The warnings name the arguments, as the errors do.
    for w in &mut outcome.result.summary.warnings {
        *w = crate::errors::rename(w, PULL_OFF_NAMES);
    }
    let wall_time = outcome.total_wall_time().as_secs_f64();
    Ok(Result::new(outcome.result, Some(wall_time)))
}
