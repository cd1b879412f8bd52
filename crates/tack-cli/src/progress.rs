//! Progress bars on stderr: a spinner over a run's steps (a solver [`Observer`]) and a bar over
//! a sweep's points (a [`SweepObserver`]); drawn only on a terminal.

use std::io::IsTerminal;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use tack::solver::{Observer, Phase, StepRecord};
use tack_sweep::SweepObserver;

use crate::report::rounded;

/// Drives a progress spinner from the solver's step hook.
pub struct Progress {
    bar: ProgressBar,
}

impl Progress {
    /// A spinner on stderr, drawn only when stderr is a terminal and `quiet` is false.
    pub fn new(quiet: bool) -> Self {
        let bar = if quiet || !std::io::stderr().is_terminal() {
            ProgressBar::hidden()
        } else {
            let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
            let style =
                ProgressStyle::with_template("{spinner} [{elapsed_precise}] step {pos} {msg}")
                    .unwrap_or_else(|_| ProgressStyle::default_spinner());
            bar.set_style(style);
            bar.enable_steady_tick(Duration::from_millis(120));
            bar
        };
        Self { bar }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}

impl Observer for Progress {
    fn on_step(&mut self, _index: usize, phase: Phase, r: &StepRecord) {
        let phase = match phase {
            Phase::Load => "load",
            Phase::Unload => "unload",
        };
        self.bar.set_message(format!(
            "{phase}: d = {}, F = {}, bonded {}{}",
            rounded(r.approach),
            rounded(r.force),
            r.n_bonded,
            if r.converged { "" } else { " (not converged)" }
        ));
        self.bar.inc(1);
    }
}

/// A bar over a sweep's points; failed points are printed above it as they happen.
pub struct SweepProgress {
    bar: ProgressBar,
}

impl SweepProgress {
    /// A bar on stderr, drawn only when stderr is a terminal and `quiet` is false (failures are
    /// printed either way).
    pub fn new(quiet: bool) -> Self {
        let bar = if quiet || !std::io::stderr().is_terminal() {
            ProgressBar::hidden()
        } else {
            let bar = ProgressBar::with_draw_target(Some(0), ProgressDrawTarget::stderr());
            let style = ProgressStyle::with_template(
                "[{elapsed_precise}] {bar:30} {pos}/{len} points, eta {eta} {msg}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar());
            bar.set_style(style);
            bar.enable_steady_tick(Duration::from_millis(250));
            bar
        };
        Self { bar }
    }
}

impl Drop for SweepProgress {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}

impl SweepObserver for SweepProgress {
    fn on_start(&self, points: usize) {
        self.bar.set_length(points as u64);
    }

    fn on_point(&self, index: usize, label: &str, failure: Option<&str>) {
        if let Some(message) = failure {
            self.bar
                .suspend(|| eprintln!("point {index} ({label}) failed: {message}"));
        }
        self.bar.inc(1);
    }
}
