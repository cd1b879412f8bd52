//! Running solver work from Python: the GIL released, Ctrl-C and progress callbacks through the
//! solver's `Observer`, panics caught.
//!
//! [`detached`] runs a closure with the GIL released inside `catch_unwind`, on a worker thread
//! while the calling thread watches for signals: CPython runs signal handlers on its main
//! thread only, and a run inside a rayon pool calls its observer from a pool thread. Every
//! [`CHECK_INTERVAL`] the calling thread re-attaches and runs `check_signals` (so SIGINT raises
//! `KeyboardInterrupt` in Python's handler); an exception sets a flag that the [`PyObserver`]
//! turns into `Observer::cancelled`. The observer also calls the progress callback at most
//! every [`CHECK_INTERVAL`] (after a step), from the worker thread (holding the GIL, as any
//! Python thread does); an exception from it stops the path the same way, and [`detached`]
//! raises what stopped it.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use pyo3::exceptions::PyKeyboardInterrupt;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tack::solver::{Observer, Phase, StepRecord};

use crate::errors::{InternalError, Names, to_py_named};

/// Longest time between two checks for signals (and progress reports) during a run.
pub const CHECK_INTERVAL: Duration = Duration::from_millis(100);

/// The observer of runs started from Python.
pub struct PyObserver {
    progress: Option<Py<PyAny>>,
    last_check: Instant,
    latest: Option<(usize, Phase, StepRecord)>,
    reported: Option<usize>,
    error: Option<PyErr>,
    interrupted: Arc<AtomicBool>,
}

impl PyObserver {
    /// An observer that calls `progress` (a callable taking one dict) with the latest step and
    /// stops the run once `interrupted` is set (by the thread watching for signals).
    pub fn new(progress: Option<Py<PyAny>>, interrupted: Arc<AtomicBool>) -> Self {
        Self {
            progress,
            last_check: Instant::now(),
            latest: None,
            reported: None,
            error: None,
            interrupted,
        }
    }

    /// Calls the progress callback with the latest step, unless it saw it already.
    fn report(&mut self, py: Python<'_>) -> PyResult<()> {
        let (Some(callback), Some((index, phase, record))) = (&self.progress, self.latest) else {
            return Ok(());
        };
        if self.reported == Some(index) {
            return Ok(());
        }
        self.reported = Some(index);
        let info = PyDict::new(py);
        info.set_item("step", index)?;
        let phase = match phase {
            Phase::Load => "load",
            Phase::Unload => "unload",
        };
        info.set_item("phase", phase)?;
        info.set_item("approach", record.approach)?;
        info.set_item("force", record.force)?;
        info.set_item("area", record.area)?;
        info.set_item("n_bonded", record.n_bonded)?;
        info.set_item("converged", record.converged)?;
        callback.call1(py, (info,))?;
        Ok(())
    }

    /// The last step's report, once the run is over (attached).
    pub fn finish(&mut self, py: Python<'_>) -> PyResult<()> {
        self.report(py)
    }
}

impl Observer for PyObserver {
    fn on_step(&mut self, index: usize, phase: Phase, record: &StepRecord) {
        self.latest = Some((index, phase, *record));
    }

    fn on_restart(&mut self) {
        self.latest = None;
        self.reported = None;
    }

    fn cancelled(&mut self) -> bool {
        if self.error.is_some() || self.interrupted.load(Ordering::Relaxed) {
            return true;
        }
        if self.progress.is_none() || self.last_check.elapsed() < CHECK_INTERVAL {
            return false;
        }
        let outcome = Python::attach(|py| self.report(py));
        self.last_check = Instant::now();
        if let Err(e) = outcome {
            self.error = Some(e);
            return true;
        }
        false
    }
}

/// Runs `work` with the GIL released and a [`PyObserver`] for `progress`, on a worker thread
/// while this thread checks for signals every [`CHECK_INTERVAL`]; a run stopped by the
/// observer raises what stopped it (`KeyboardInterrupt`, the callback's exception), a tack
/// error its Python exception (the fields of `names` renamed to Python arguments), a panic
/// `InternalError`.
pub fn detached<T, F>(
    py: Python<'_>,
    progress: Option<Py<PyAny>>,
    names: Names,
    work: F,
) -> PyResult<T>
where
    T: Send,
    F: FnOnce(&mut PyObserver) -> Result<T, tack::Error> + Send,
{
    let interrupted = Arc::new(AtomicBool::new(false));
    let mut observer = PyObserver::new(progress, Arc::clone(&interrupted));
    let mut signal = None;
    let outcome = py.detach(|| {
        let (done, finished) = std::sync::mpsc::channel::<()>();
        std::thread::scope(|scope| {
            let worker = scope.spawn(|| {
                let outcome = catch_unwind(AssertUnwindSafe(|| work(&mut observer)));
                // The watcher may have stopped listening already; nothing to report then.
                let _ = done.send(());
                outcome
            });
            while let Err(std::sync::mpsc::RecvTimeoutError::Timeout) =
                finished.recv_timeout(CHECK_INTERVAL)
            {
                if signal.is_none()
                    && let Err(e) = Python::attach(|py| py.check_signals())
                {
                    signal = Some(e);
                    interrupted.store(true, Ordering::Relaxed);
                }
            }
            // The worker caught its own panics; a failed join is one of those re-raised.
            worker.join().unwrap_or_else(Err)
        })
    });
    // `check_signals` consumed the signal: raise it even when the run ended before it noticed.
    if let Some(e) = signal {
        return Err(observer.error.take().unwrap_or(e));
    }
    match outcome {
        Err(panic) => Err(panic_error(panic.as_ref())),
        Ok(Err(e)) if e.is_cancelled() => Err(observer
            .error
            .take()
            .unwrap_or_else(|| PyKeyboardInterrupt::new_err(e.to_string()))),
        Ok(Err(e)) => Err(to_py_named(&e, names)),
        Ok(Ok(value)) => {
            observer.finish(py)?;
            Ok(value)
        }
    }
}

/// Runs `work` with the GIL released, a panic turned into `InternalError`; for work without an
/// observer (surfaces, the non-adhesive solver, result files).
pub fn released<T, F>(py: Python<'_>, work: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce() -> PyResult<T> + Send,
{
    py.detach(|| catch_unwind(AssertUnwindSafe(work)))
        .unwrap_or_else(|panic| Err(panic_error(panic.as_ref())))
}

/// `InternalError` with the panic's message.
fn panic_error(panic: &(dyn std::any::Any + Send)) -> PyErr {
    let message = panic
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "(no message)".to_owned());
    InternalError::new_err(format!(
        "tack panicked: {message}; this is a bug in tack, please report it with the input that \
         caused it"
    ))
}

/// Panics inside the guard, for the test that no panic crosses into Python.
#[pyfunction]
#[pyo3(name = "_panic_for_tests")]
pub fn panic_for_tests(py: Python<'_>) -> PyResult<()> {
    released(py, || -> PyResult<()> {
        panic!("a deliberate panic (test)")
    })
}
