//! `tack.Result`: a run's result (in memory, or read from a result file) with numpy arrays and
//! dicts built on first access and kept.

use std::path::PathBuf;

use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBytes, PyDict, PyString};

use crate::errors::to_py;
use crate::guard::released;

/// A run's result: curve, summary, snapshots, surface, provenance.
#[pyclass(module = "tack", name = "Result", frozen)]
pub struct Result {
    inner: tack::io::RunResult,
    wall_time: Option<f64>,
    curve: PyOnceLock<Py<PyDict>>,
    summary: PyOnceLock<Py<PyDict>>,
    snapshots: PyOnceLock<Py<PyDict>>,
    surface: PyOnceLock<Py<PyAny>>,
    provenance: PyOnceLock<Py<PyDict>>,
}

impl Result {
    /// Wraps a result; `wall_time` in seconds for runs made in this process.
    pub fn new(inner: tack::io::RunResult, wall_time: Option<f64>) -> Self {
        Self {
            inner,
            wall_time,
            curve: PyOnceLock::new(),
            summary: PyOnceLock::new(),
            snapshots: PyOnceLock::new(),
            surface: PyOnceLock::new(),
            provenance: PyOnceLock::new(),
        }
    }
}

/// The summary entries that count steps or elements: Python ints.
const COUNTS: &[&str] = &[
    "non_converged_steps",
    "edge_contact_steps",
    "full_contact_steps",
    "crop_rows",
    "crop_cols",
];

fn counts<'py>(py: Python<'py>, v: &[u64]) -> Bound<'py, PyArray1<i64>> {
    v.iter()
        .map(|&x| i64::try_from(x).unwrap_or(i64::MAX))
        .collect::<Vec<_>>()
        .into_pyarray(py)
}

#[pymethods]
impl Result {
    /// The force–approach curve, one entry per step: a dict of 1-D arrays `approach`, `force`,
    /// `area`, `n_bonded`, `n_clusters`, `iterations`, `active_set_iterations` (int64),
    /// `converged` (bool), and `mean_pressure`, `full_contact` and `time` (viscoelastic solids:
    /// the time at the end of each step) where the file has them, then the columns the run's
    /// adhesion law declares (int64; `n_cohesive` under the Dugdale and smooth laws: the
    /// cohesive or process zone's elements; what each counts in [`Result::law_columns`]).
    #[getter]
    fn curve(&self, py: Python<'_>) -> PyResult<Py<PyDict>> {
        let dict = self.curve.get_or_try_init(py, || -> PyResult<Py<PyDict>> {
            let c = &self.inner.curve;
            let d = PyDict::new(py);
            d.set_item("approach", c.approach.clone().into_pyarray(py))?;
            d.set_item("force", c.force.clone().into_pyarray(py))?;
            d.set_item("area", c.area.clone().into_pyarray(py))?;
            d.set_item("n_bonded", counts(py, &c.n_bonded))?;
            d.set_item("n_clusters", counts(py, &c.n_clusters))?;
            d.set_item("iterations", counts(py, &c.iterations))?;
            d.set_item(
                "active_set_iterations",
                counts(py, &c.active_set_iterations),
            )?;
            d.set_item("converged", c.converged.clone().into_pyarray(py))?;
            if let Some(p) = &c.mean_pressure {
                d.set_item("mean_pressure", p.clone().into_pyarray(py))?;
            }
            for z in &c.law_columns {
                d.set_item(&z.name, counts(py, &z.values))?;
            }
            if let Some(t) = &c.time {
                d.set_item("time", t.clone().into_pyarray(py))?;
            }
            if let Some(f) = &c.full_contact {
                d.set_item("full_contact", f.clone().into_pyarray(py))?;
            }
            Ok(d.unbind())
        })?;
        Ok(dict.clone_ref(py))
    }

    /// What each column the run's adhesion law adds to [`Result::curve`] counts: a dict
    /// `{name: meaning}` (`{"n_cohesive": "elements of the cohesive zone: ..."}` under the
    /// Dugdale law, empty under the zero-range criterion; the meaning is empty in files written
    /// before columns carried it).
    #[getter]
    fn law_columns(&self, py: Python<'_>) -> PyResult<Py<PyDict>> {
        let d = PyDict::new(py);
        for z in &self.inner.curve.law_columns {
            d.set_item(&z.name, &z.meaning)?;
        }
        Ok(d.unbind())
    }

    /// The scalar results: `pull_off_force`, `f_jkr`, `pull_off_ratio` (NaN where F_JKR does
    /// not apply), `johnson_alpha`, `alpha_star` (None where they do not apply), then the
    /// extras (`d_jkr`, `sigma_c`, `kappa`, `first_touch`, `non_converged_steps`, ...), then
    /// `status` (`"complete"`, `"stopped at protocol.max_steps"`; None in old files),
    /// `adhesion_model` (`"jkr_limit"`, `"dugdale"`, `"exponential"`, `"lennard_jones"`,
    /// `"smoothed_dugdale"`, or a custom law's name; None in old files) and
    /// `warnings` (a list of sentences: why the result may not be trusted).
    #[getter]
    fn summary(&self, py: Python<'_>) -> PyResult<Py<PyDict>> {
        let dict = self
            .summary
            .get_or_try_init(py, || -> PyResult<Py<PyDict>> {
                let s = &self.inner.summary;
                let d = PyDict::new(py);
                d.set_item("pull_off_force", s.pull_off_force)?;
                d.set_item("f_jkr", s.f_jkr)?;
                d.set_item("pull_off_ratio", s.pull_off_ratio)?;
                d.set_item("johnson_alpha", s.johnson_alpha)?;
                d.set_item("alpha_star", s.alpha_star)?;
                for (name, value) in &s.extra {
                    if COUNTS.contains(&name.as_str()) {
                        // Counts are integers (None where a file has no number).
                        let count = (value.is_finite() && *value >= 0.0).then_some(*value as u64);
                        d.set_item(name, count)?;
                    } else {
                        d.set_item(name, value)?;
                    }
                }
                d.set_item("status", s.status.as_deref())?;
                d.set_item("adhesion_model", s.adhesion_model.as_deref())?;
                d.set_item("warnings", &s.warnings)?;
                Ok(d.unbind())
            })?;
        Ok(dict.clone_ref(py))
    }

    /// The Richardson extrapolation of the pull-off force (`tack.run(richardson=True)`,
    /// `tack.pull_off(richardson=True)`), or None for a run without one: a dict of `fine`,
    /// `coarse` (the pull-off forces at Δx and 2Δx), `extrapolated` (`fine + (fine −
    /// coarse)/(2^order − 1)`: `2·fine − coarse` at first order), `error_estimate` (how far
    /// `fine` may be from converged), `order` (the law's order in Δx: 1 for the criterion and
    /// the Dugdale law, 2 for the smooth laws), `ratio` (`extrapolated / f_jkr`, or None) and
    /// `aliased_rms` (height arrays only: the content the coarse array aliases, or None).
    #[getter]
    fn richardson(&self, py: Python<'_>) -> PyResult<Option<Py<PyDict>>> {
        let s = &self.inner.summary;
        let get = |key: &str| s.extra.get(key).copied();
        let (Some(coarse), Some(extrapolated)) = (
            get("pull_off_force_coarse"),
            get("pull_off_force_richardson"),
        ) else {
            return Ok(None);
        };
        let d = PyDict::new(py);
        d.set_item("fine", s.pull_off_force)?;
        d.set_item("coarse", coarse)?;
        d.set_item("extrapolated", extrapolated)?;
        d.set_item("error_estimate", get("pull_off_error_estimate"))?;
        d.set_item("order", get("richardson_order").unwrap_or(1.0))?;
        d.set_item("ratio", get("pull_off_ratio_richardson"))?;
        d.set_item("aliased_rms", get("richardson_aliased_rms"))?;
        Ok(Some(d.unbind()))
    }

    /// The stored contact configurations: `{step: {"pressure": 2-D array, "bonded": 2-D bool
    /// array, "approach": float}}`, in step order.
    #[getter]
    fn snapshots(&self, py: Python<'_>) -> PyResult<Py<PyDict>> {
        let dict = self
            .snapshots
            .get_or_try_init(py, || -> PyResult<Py<PyDict>> {
                let d = PyDict::new(py);
                for s in &self.inner.snapshots {
                    let snap = PyDict::new(py);
                    snap.set_item("pressure", s.pressure.clone().into_pyarray(py))?;
                    snap.set_item("bonded", s.bonded.clone().into_pyarray(py))?;
                    snap.set_item("approach", s.approach)?;
                    d.set_item(s.step, snap)?;
                }
                Ok(d.unbind())
            })?;
        Ok(dict.clone_ref(py))
    }

    /// The rigid body's heights, `{"heights": 2-D array, "dx": float}` (and `"gamma"`, the
    /// work of adhesion per element, when it varies), or None when the result does not store
    /// them (`output.surface = false`).
    #[getter]
    fn surface(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let value = self
            .surface
            .get_or_try_init(py, || -> PyResult<Py<PyAny>> {
                Ok(match &self.inner.surface {
                    None => py.None(),
                    Some((heights, dx)) => {
                        let d = PyDict::new(py);
                        d.set_item("heights", heights.clone().into_pyarray(py))?;
                        d.set_item("dx", dx)?;
                        if let Some(gamma) = &self.inner.gamma {
                            d.set_item("gamma", gamma.clone().into_pyarray(py))?;
                        }
                        d.into_any().unbind()
                    }
                })
            })?;
        Ok(value.clone_ref(py))
    }

    /// Where the result came from: `tack_version`, `git_revision`, `command_line`, `scene`
    /// (the full TOML after overrides), `created` (UTC, RFC 3339), `seed` (None without random
    /// roughness).
    #[getter]
    fn provenance(&self, py: Python<'_>) -> PyResult<Py<PyDict>> {
        let dict = self
            .provenance
            .get_or_try_init(py, || -> PyResult<Py<PyDict>> {
                let p = &self.inner.provenance;
                let d = PyDict::new(py);
                d.set_item("tack_version", &p.tack_version)?;
                d.set_item("git_revision", &p.git_revision)?;
                d.set_item("command_line", &p.command_line)?;
                d.set_item("scene", &p.scene)?;
                d.set_item("created", &p.created)?;
                d.set_item("seed", p.seed)?;
                Ok(d.unbind())
            })?;
        Ok(dict.clone_ref(py))
    }

    /// The pull-off force: the least force of the curve (negative when adhesive).
    #[getter]
    fn pull_off_force(&self) -> f64 {
        self.inner.summary.pull_off_force
    }

    /// The pull-off force over F_JKR of the sphere (NaN for other bodies).
    #[getter]
    fn pull_off_ratio(&self) -> f64 {
        self.inner.summary.pull_off_ratio
    }

    /// Index of the step with the pull-off force (periodic full-contact steps left out), or
    /// None for an empty curve or a run without a pull-off (an indentation: `pull_off_force`
    /// is NaN).
    #[getter]
    fn pull_off_step(&self) -> Option<usize> {
        if self.inner.summary.pull_off_force.is_nan() {
            return None;
        }
        let c = &self.inner.curve;
        let full = |i: usize| {
            c.full_contact
                .as_ref()
                .and_then(|f| f.get(i).copied())
                .unwrap_or(false)
        };
        tack::solver::pull_off_step(c.force.iter().enumerate().map(|(i, &f)| (f, full(i))))
    }

    /// Wall time of the solve in seconds (None for a result read from a file).
    #[getter]
    fn wall_time(&self) -> Option<f64> {
        self.wall_time
    }

    /// The scene TOML the run was made from (after overrides).
    #[getter]
    fn scene(&self) -> &str {
        &self.inner.provenance.scene
    }

    /// Writes the HDF5 result file atomically (temporary file + rename); `path` is a `str` or
    /// `os.PathLike`, and its parent directory must exist.
    fn write(&self, py: Python<'_>, path: &Bound<'_, PyAny>) -> PyResult<()> {
        let path = path_argument("path", path)?;
        released(py, || {
            tack::engine::check_output_path(&path).map_err(|e| to_py(&e))?;
            tack::io::write_result(&path, &self.inner).map_err(|e| to_py(&e.into()))
        })
    }

    /// Number of steps of the curve.
    fn __len__(&self) -> usize {
        self.inner.curve.len()
    }

    fn __repr__(&self) -> String {
        let s = &self.inner.summary;
        format!(
            "<tack.Result: {} steps, {} snapshots, pull_off_force = {:.6e}, pull_off_ratio = \
             {:.4}>",
            self.inner.curve.len(),
            self.inner.snapshots.len(),
            s.pull_off_force,
            s.pull_off_ratio
        )
    }
}

/// A path argument: a `str` or an `os.PathLike` (whose path may be `bytes`, decoded as
/// `os.fsdecode` does); anything else is a `TypeError` naming `name`.
fn path_argument(name: &str, value: &Bound<'_, PyAny>) -> PyResult<PathBuf> {
    let py = value.py();
    let os = py.import("os")?;
    if value.is_instance_of::<PyString>() || value.is_instance(&os.getattr("PathLike")?)? {
        return os.call_method1("fsdecode", (value,))?.extract();
    }
    let type_name = value.get_type().name()?;
    let hint = if value.is_instance_of::<PyBytes>() {
        " (decode it with os.fsdecode)"
    } else {
        ""
    };
    Err(PyTypeError::new_err(format!(
        "{name}: expected a path (str or os.PathLike), got {type_name}{hint}"
    )))
}

/// Reads a result file written by `tack run`, `Result.write` or `tack surface`.
#[pyfunction]
pub fn read(py: Python<'_>, path: PathBuf) -> PyResult<Result> {
    let inner = released(py, || {
        tack::io::read_result(&path).map_err(|e| to_py(&e.into()))
    })?;
    Ok(Result::new(inner, None))
}
