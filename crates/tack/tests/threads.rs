//! One run engine, one pool: a scene run (`tack::run`) and a pull-off of a height array held in
//! memory (`tack::heights::pull_off`, what Python's `tack.pull_off` calls) give the same bits
//! on 1 and 2 threads, and with 2 threads are carried by two threads (each thread's CPU time,
//! from `/proc/self/task`). Before the engine was shared, `heights::pull_off` ignored
//! `threads`: one thread did all the work.

use std::collections::BTreeMap;

use tack::geometry::{Boundary, Grid, Surface, Waviness2d};
use tack::heights::{PullOffSpec, pull_off};
use tack::solver::{Observer, Phase, StepRecord};
use tack::{RunOptions, RunOutcome, Scene};

/// CPU ticks (user + system, 1/100 s) of every thread of this process, from
/// `/proc/self/task/<tid>/stat` (fields 14 and 15).
fn thread_ticks() -> BTreeMap<u64, u64> {
    let mut out = BTreeMap::new();
    let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
        return out;
    };
    for task in tasks.flatten() {
        let Ok(tid) = task.file_name().to_string_lossy().parse::<u64>() else {
            continue;
        };
        let Ok(stat) = std::fs::read_to_string(task.path().join("stat")) else {
            continue;
        };
        // The command name (field 2) is in parentheses and may hold spaces: count after it.
        let Some(close) = stat.rfind(')') else {
            continue;
        };
        let fields: Vec<&str> = stat[close + 2..].split_whitespace().collect();
        // The slice starts at field 3 (state): utime is field 14, stime field 15.
        let tick = |k: usize| fields.get(k).and_then(|v| v.parse::<u64>().ok());
        if let (Some(user), Some(system)) = (tick(11), tick(12)) {
            out.insert(tid, user + system);
        }
    }
    out
}

/// Samples every thread's CPU ticks after each step: the threads that worked during the run
/// (from the first step to the last), counted on the CPU they got, so a loaded machine (other
/// builds on the same cores) slows the run without hiding which threads carried it.
#[derive(Default)]
struct ThreadUse {
    first: Option<BTreeMap<u64, u64>>,
    last: BTreeMap<u64, u64>,
}

impl Observer for ThreadUse {
    fn on_step(&mut self, _index: usize, _phase: Phase, _record: &StepRecord) {
        let now = thread_ticks();
        self.first.get_or_insert_with(|| now.clone());
        self.last = now;
    }
}

impl ThreadUse {
    /// Threads that each did at least a quarter of the work done after the first step, and the
    /// ticks of that work.
    fn busy_threads(&self) -> (usize, u64) {
        let Some(first) = &self.first else {
            return (0, 0);
        };
        let deltas: Vec<u64> = self
            .last
            .iter()
            .map(|(tid, t)| t - first.get(tid).copied().unwrap_or(0))
            .collect();
        let total: u64 = deltas.iter().sum();
        eprintln!("thread ticks: {deltas:?} {:?}", self.last);
        let busy = deltas.iter().filter(|&&d| 4 * d >= total && d > 0).count();
        (busy, total)
    }
}

/// Runs `f` with a [`ThreadUse`] observer; the outcome and the threads that carried the run.
fn watched(f: impl FnOnce(&mut ThreadUse) -> RunOutcome) -> (RunOutcome, (usize, u64)) {
    let mut watch = ThreadUse::default();
    let outcome = f(&mut watch);
    (outcome, watch.busy_threads())
}

fn threads(n: usize) -> RunOptions {
    RunOptions {
        threads: Some(n),
        ..RunOptions::default()
    }
}

/// Same curve, summary and snapshots, bit for bit.
fn assert_same_bits(a: &RunOutcome, b: &RunOutcome, what: &str) {
    let (ca, cb) = (&a.result.curve, &b.result.curve);
    assert_eq!(ca.force.len(), cb.force.len(), "{what}: step counts");
    for (x, y) in ca.force.iter().zip(&cb.force) {
        assert_eq!(x.to_bits(), y.to_bits(), "{what}: forces {x} vs {y}");
    }
    assert_eq!(ca.iterations, cb.iterations, "{what}: CG iterations");
    assert_eq!(
        a.pull_off_force().to_bits(),
        b.pull_off_force().to_bits(),
        "{what}"
    );
    for (sa, sb) in a.result.snapshots.iter().zip(&b.result.snapshots) {
        assert_eq!(
            sa.pressure, sb.pressure,
            "{what}: snapshot of step {}",
            sa.step
        );
    }
}

/// A periodic 2D waviness, 192 × 192 elements: its FFTs split into lanes (at least 128 × 128)
/// and its CG vectors into several chunks, about a second on one core. (A sphere's bonded
/// sub-grid stays too small for lanes below about 512 × 512, too slow for every CI run.)
const SCENE: &str = r#"
version = 1
[material]
e_star = 1.0
gamma = 1.0e-4
[geometry]
shape = "none"
[roughness]
kind = "waviness2d"
h = 0.01
lambda = 1.0
[grid]
n = 192
length = 1.0
boundary = "periodic"
[protocol]
max_approach = 0.009
load_step = 0.0045
unload_step = 0.001
"#;

#[test]
fn scene_runs_and_height_array_pull_offs_use_every_thread_and_keep_the_bits() {
    if std::thread::available_parallelism().map_or(1, |n| n.get()) < 2 {
        eprintln!("skipped: one core");
        return;
    }
    let scene = Scene::parse(SCENE, ".", &[]).unwrap();
    let (one, _) = watched(|w| tack::run(&scene, &threads(1), w).unwrap());
    let (two, (busy, ticks)) = watched(|w| tack::run(&scene, &threads(2), w).unwrap());
    assert_same_bits(&one, &two, "scene run");
    assert!(
        busy >= 2 && ticks >= 20,
        "scene run on 2 threads: {busy} threads carried {ticks} ticks"
    );

    // The same body as an array, pulled off from the same depth.
    let grid = Grid::square(192, 1.0 / 192.0, Boundary::Periodic).unwrap();
    let heights = Surface::from_shape(grid, &Waviness2d::new(0.01, 1.0).unwrap()).into_heights();
    let spec = PullOffSpec {
        boundary: Boundary::Periodic,
        max_approach: Some(0.009),
        unload_step: Some(0.001),
        coarse_unload_step: Some(0.001),
        ..PullOffSpec::new(1.0 / 192.0, 1.0, 1.0e-4)
    };
    let (one, _) = watched(|w| pull_off(&heights, &spec, &threads(1), w).unwrap());
    let (two, (busy, ticks)) = watched(|w| pull_off(&heights, &spec, &threads(2), w).unwrap());
    assert_same_bits(&one, &two, "height-array pull-off");
    assert!(
        busy >= 2 && ticks >= 20,
        "height-array pull-off on 2 threads: {busy} threads carried {ticks} ticks"
    );
}
