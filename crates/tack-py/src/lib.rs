//! `tack._tack`: the compiled core of the Python package `tack` (PyO3 + rust-numpy).
//!
//! The public Python API lives in `python/tack/` (argument normalisation, docstrings, type
//! hints); this module binds the `tack` crate: scene runs and pull-offs of height arrays with the
//! GIL released and Ctrl-C honoured (`guard`), results as numpy arrays and dicts
//! (`result`), the non-adhesive solver (`contact`), surfaces and closed forms
//! (`surface`, `analytics`), and the exceptions (`errors`).

mod analytics;
mod body;
mod contact;
mod errors;
mod guard;
mod result;
mod run;
mod surface;

use pyo3::prelude::*;

/// The extension module `tack._tack`.
#[pymodule]
fn _tack(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("TackError", py.get_type::<errors::TackError>())?;
    m.add("SceneError", py.get_type::<errors::SceneError>())?;
    m.add("SolverError", py.get_type::<errors::SolverError>())?;
    m.add("ResultFileError", py.get_type::<errors::ResultFileError>())?;
    m.add("InternalError", py.get_type::<errors::InternalError>())?;
    m.add("__version__", tack::provenance::VERSION)?;
    m.add("GIT_REVISION", tack::provenance::GIT_REVISION)?;
    m.add("MAX_THREADS", run::MAX_THREADS)?;
    m.add("MAUGIS_LAMBDA_CRITICAL", analytics::lambda_critical())?;
    m.add_class::<result::Result>()?;
    m.add_class::<contact::ContactResult>()?;
    m.add_function(wrap_pyfunction!(run::run_scene, m)?)?;
    m.add_function(wrap_pyfunction!(run::pull_off, m)?)?;
    m.add_function(wrap_pyfunction!(result::read, m)?)?;
    m.add_function(wrap_pyfunction!(contact::contact, m)?)?;
    m.add_function(wrap_pyfunction!(guard::panic_for_tests, m)?)?;
    surface::register(m)?;
    analytics::register(m)?;
    Ok(())
}
