//! One run engine, one pool: a scene run (`tack::run`) and a pull-off of a height array held in
//! memory (`tack::heights::pull_off`, what Python's `tack.pull_off` calls) give the same bits
//! on 1 and 2 threads, and with 2 threads run every step inside a pool of 2 threads and, on a
//! machine with two free cores, are carried by both (each thread's CPU time, from
//! `/proc/self/task`). Before the engine was shared, `heights::pull_off` ignored `threads`: it
//! ran on the calling thread, outside any pool, and one thread did all the work.

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
    /// The rayon pool each step ran in: `(current_thread_index, current_num_threads)`.
    pools: Vec<(Option<usize>, usize)>,
}

impl Observer for ThreadUse {
    fn on_step(&mut self, _index: usize, _phase: Phase, _record: &StepRecord) {
        let now = thread_ticks();
        self.first.get_or_insert_with(|| now.clone());
        self.last = now;
        self.pools
            .push((rayon::current_thread_index(), rayon::current_num_threads()));
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
        let busy = deltas.iter().filter(|&&d| 4 * d >= total && d > 0).count();
        (busy, total)
    }
}

/// Runs `f` with a [`ThreadUse`] observer; the outcome and the observer.
fn watched(f: impl FnOnce(&mut ThreadUse) -> RunOutcome) -> (RunOutcome, ThreadUse) {
    let mut watch = ThreadUse::default();
    let outcome = f(&mut watch);
    (outcome, watch)
}

/// Whether two threads of this process get a core each right now: two threads spin for 150 ms
/// of wall time and read their own CPU ticks. On a machine busy with other work (a build, the
/// other tests of a loaded workstation) the scheduler shares the cores out, and CPU time says
/// nothing about what the run asked for.
fn two_cores_free() -> bool {
    let spin = || {
        let started = std::time::Instant::now();
        let mut x = 1u64;
        while started.elapsed().as_millis() < 150 {
            x = std::hint::black_box(x.wrapping_mul(31).wrapping_add(7));
        }
        let stat = std::fs::read_to_string("/proc/thread-self/stat").unwrap_or_default();
        let fields: Vec<&str> = stat
            .rfind(')')
            .map(|c| stat[c + 2..].split_whitespace().collect())
            .unwrap_or_default();
        let tick = |k: usize| fields.get(k).and_then(|v| v.parse::<u64>().ok());
        tick(11).zip(tick(12)).map_or(0, |(u, s)| u + s)
    };
    let handles = [std::thread::spawn(spin), std::thread::spawn(spin)];
    handles
        .into_iter()
        .map(|h| h.join().unwrap_or(0))
        .all(|ticks| ticks >= 11)
}

/// The run went through a pool of 2 threads (every step inside it), and, when the machine has
/// two free cores, both threads carried a quarter of the work or more.
fn assert_two_threads(watch: &ThreadUse, what: &str) {
    assert!(!watch.pools.is_empty(), "{what}: no steps");
    for (index, threads) in &watch.pools {
        assert!(
            index.is_some() && *threads == 2,
            "{what}: a step ran outside a pool of 2 threads (thread index {index:?}, pool of \
             {threads})"
        );
    }
    if two_cores_free() {
        let (busy, ticks) = watch.busy_threads();
        assert!(
            busy >= 2 && ticks >= 20,
            "{what} on 2 threads: {busy} threads carried {ticks} ticks"
        );
    } else {
        eprintln!("{what}: the machine is busy, CPU time per thread not checked");
    }
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
    let (two, watch) = watched(|w| tack::run(&scene, &threads(2), w).unwrap());
    assert_same_bits(&one, &two, "scene run");
    assert_two_threads(&watch, "scene run");

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
    let (two, watch) = watched(|w| pull_off(&heights, &spec, &threads(2), w).unwrap());
    assert_same_bits(&one, &two, "height-array pull-off");
    assert_two_threads(&watch, "height-array pull-off");
}
