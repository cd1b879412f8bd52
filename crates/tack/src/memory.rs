//! The memory a run may need, estimated from the scene before anything is allocated, and the
//! refusal of scenes that cannot fit the machine (`tack check` and the start of every run).
//!
//! The estimate is an upper bound of the run's large allocations:
//!
//! - working fields: about [`WORKING_FIELDS_FREE`] (free grids, whose FFTs are zero-padded to
//!   about twice each side) or [`WORKING_FIELDS_PERIODIC`] f64 values per grid element
//!   (surface, pressure, gap, displacement, CG vectors, kernel spectrum, FFT buffers, the
//!   result's copies);
//! - stored snapshots: [`SNAPSHOT_BYTES_PER_ELEMENT`] bytes per element and snapshot (pressure
//!   and bonded mask, held by the path result and again by the result to write), with as many
//!   snapshots as `output.snapshots` can keep over `protocol.max_steps` steps (`"all"`: every
//!   step, `{ every = k }`: one in k, `{ steps = [...] }`: the listed ones, `"pull_off"`: two);
//! - step records: [`STEP_RECORD_BYTES`] per step, `protocol.max_steps` of them.
//! - a work of adhesion that varies: [`GAMMA_MAP_FIELDS`] more fields (the problem's map, the
//!   solver's tensions, the result's copy).
//!
//! The path's length is known before it runs when it ends at `protocol.retract_to` or is an
//! indentation (`tack_solver::ApproachPath::step_bound`); a retraction that ends when contact is
//! lost is bounded by `protocol.max_steps` steps. A scene whose estimate exceeds the machine's
//! memory (`MemTotal` of `/proc/meminfo`) or, on every machine, [`HARD_LIMIT_BYTES`] is refused
//! with the bytes needed against those available, naming `grid.n`, `output.snapshots` and
//! `protocol.max_steps`.

use tack_fields as fields;
use tack_geometry::{Boundary, Grid};
use tack_solver::SnapshotRequest;

use crate::scene::SceneError;

/// f64 working values per element on a free grid (padded FFTs of about 4× the grid's area).
pub const WORKING_FIELDS_FREE: f64 = 40.0;
/// f64 working values per element on a periodic grid (FFTs of the grid's own size).
pub const WORKING_FIELDS_PERIODIC: f64 = 20.0;
/// Bytes per element and stored snapshot: pressure (8) and bonded mask (1), held twice.
pub const SNAPSHOT_BYTES_PER_ELEMENT: f64 = 18.0;
/// Bytes per step for the step record, the curve's columns and the phase.
pub const STEP_RECORD_BYTES: f64 = 256.0;
/// The largest estimate accepted on any machine (1 TiB), also where `/proc/meminfo` cannot be
/// read.
pub const HARD_LIMIT_BYTES: f64 = 1_099_511_627_776.0;

/// What a run may need, in bytes, by part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// Grid elements `nx·ny`.
    pub elements: f64,
    /// Working fields of the solver.
    pub fields: f64,
    /// Largest number of snapshots the request can keep.
    pub snapshots: f64,
    /// Bytes of those snapshots.
    pub snapshot_bytes: f64,
    /// Steps bounded by `protocol.max_steps`.
    pub steps: f64,
    /// Bytes of the step records.
    pub record_bytes: f64,
}

/// Copies of a varying work of adhesion per element (the problem's, the solver's tensions and
/// the result's), in f64 fields: added to [`Estimate::fields`] when γ varies.
pub const GAMMA_MAP_FIELDS: f64 = 3.0;

/// The refined retraction's saved solver states (`protocol.refine_pull_off`): three at most,
/// each four f64 fields (pressure, gap, displacement, the predictor's pressure) and two masks.
pub const REFINED_STATE_FIELDS: f64 = 13.0;

/// A viscoelastic solid (`material.prony`) of `arms` arms: each arm's stress, the unit-modulus
/// pressure, the history and its displacement, the body's own heights and the shifted ones.
pub fn viscoelastic_fields(arms: usize) -> f64 {
    arms as f64 + 5.0
}

impl Estimate {
    /// Adds `per_element` f64 fields of the grid's size (a varying γ: [`GAMMA_MAP_FIELDS`]).
    pub fn add_fields(&mut self, per_element: f64) {
        self.fields += self.elements * 8.0 * per_element;
    }

    /// The whole estimate.
    pub fn total(&self) -> f64 {
        self.fields + self.snapshot_bytes + self.record_bytes
    }
}

/// The estimate for a run on `grid` with at most `max_steps` steps keeping `snapshots`.
pub fn estimate(grid: &Grid, max_steps: usize, snapshots: &SnapshotRequest) -> Estimate {
    let elements = grid.nx() as f64 * grid.ny() as f64;
    let per_element = match grid.boundary() {
        Boundary::Free => WORKING_FIELDS_FREE,
        Boundary::Periodic => WORKING_FIELDS_PERIODIC,
    };
    let steps = max_steps as f64;
    let kept = match snapshots {
        SnapshotRequest::None => 0.0,
        SnapshotRequest::All => steps,
        SnapshotRequest::Every(k) => (steps / (*k).max(1) as f64).ceil(),
        SnapshotRequest::Steps(list) => {
            let mut distinct: Vec<usize> =
                list.iter().copied().filter(|&s| s < max_steps).collect();
            distinct.sort_unstable();
            distinct.dedup();
            distinct.len() as f64
        }
        SnapshotRequest::PullOff => 2.0,
    };
    Estimate {
        elements,
        fields: elements * 8.0 * per_element,
        snapshots: kept,
        snapshot_bytes: kept * elements * SNAPSHOT_BYTES_PER_ELEMENT,
        steps,
        record_bytes: steps * STEP_RECORD_BYTES,
    }
}

/// The machine's memory from `/proc/meminfo`: (`MemTotal`, `MemAvailable`) in bytes; `None`
/// where the file does not exist or lacks `MemTotal` (not Linux).
pub fn machine_memory() -> Option<(f64, Option<f64>)> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    parse_meminfo(&text)
}

fn parse_meminfo(text: &str) -> Option<(f64, Option<f64>)> {
    let field = |name: &str| {
        text.lines().find_map(|line| {
            let rest = line.strip_prefix(name)?.strip_prefix(':')?;
            let kib: f64 = rest.trim().trim_end_matches("kB").trim().parse().ok()?;
            Some(kib * 1024.0)
        })
    };
    Some((field("MemTotal")?, field("MemAvailable")))
}

/// A byte count for people: `3.2 GiB (3.4e9 bytes)`.
pub fn bytes(b: f64) -> String {
    const UNITS: [&str; 6] = ["KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    if !b.is_finite() || b < 1024.0 {
        return format!("{b:.0} bytes");
    }
    let mut value = b;
    let mut unit = "bytes";
    for u in UNITS {
        if value < 1024.0 {
            break;
        }
        value /= 1024.0;
        unit = u;
    }
    format!("{value:.1} {unit} ({b:.1e} bytes)")
}

/// Refuses an estimate above `machine` (`(MemTotal, MemAvailable)`, when known) or above
/// [`HARD_LIMIT_BYTES`]. `grid_field` names the grid size (`grid.n` or `grid.nx × grid.ny`),
/// `steps_from` where the step count `max_steps` comes from (`protocol.max_steps = N`, or the
/// path's own count), `snapshots_text` the value of `output.snapshots` as written.
pub fn check(
    e: &Estimate,
    machine: Option<(f64, Option<f64>)>,
    grid_field: &str,
    grid: &Grid,
    max_steps: usize,
    steps_from: &str,
    snapshots_text: &str,
) -> Result<(), SceneError> {
    let total = e.total();
    let (limit, against) = match machine {
        Some((mem_total, available)) if mem_total < HARD_LIMIT_BYTES => (
            mem_total,
            format!(
                "this machine has {} of memory in all (MemTotal){}",
                bytes(mem_total),
                available.map_or_else(String::new, |a| format!(", {} available now", bytes(a)))
            ),
        ),
        _ => (
            HARD_LIMIT_BYTES,
            format!(
                "tack refuses runs above {} on any machine",
                bytes(HARD_LIMIT_BYTES)
            ),
        ),
    };
    if total <= limit {
        return Ok(());
    }
    Err(SceneError::Inconsistent(format!(
        "the run may need about {} of memory, more than available: {against}. The estimate: \
         {} of working fields for {grid_field} = {} × {} elements, {} for up to {} snapshots \
         ({snapshots} = {snapshots_text} over {max_steps} steps at most: {steps_from}), {} \
         for {max_steps} step records; lower {max_steps_field}, keep fewer \
         snapshots ({snapshots} = \"pull_off\" or {{ every = k }}) or use a smaller \
         {grid_field}",
        bytes(total),
        bytes(e.fields),
        grid.nx(),
        grid.ny(),
        bytes(e.snapshot_bytes),
        e.snapshots,
        bytes(e.record_bytes),
        snapshots = fields::OUTPUT_SNAPSHOTS,
        max_steps_field = fields::PROTOCOL_MAX_STEPS,
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(n: usize) -> Grid {
        Grid::square(n, 0.1, Boundary::Free).unwrap()
    }

    #[test]
    fn estimate_counts_fields_snapshots_and_records() {
        let g = grid(100);
        let e = estimate(&g, 1000, &SnapshotRequest::None);
        assert_eq!(e.fields, 1e4 * 8.0 * WORKING_FIELDS_FREE);
        assert_eq!((e.snapshots, e.snapshot_bytes), (0.0, 0.0));
        assert_eq!(e.record_bytes, 1000.0 * STEP_RECORD_BYTES);
        let all = estimate(&g, 1000, &SnapshotRequest::All);
        assert_eq!(
            all.snapshot_bytes,
            1000.0 * 1e4 * SNAPSHOT_BYTES_PER_ELEMENT
        );
        assert_eq!(
            estimate(&g, 1000, &SnapshotRequest::Every(300)).snapshots,
            4.0
        );
        let listed = SnapshotRequest::Steps(vec![5, 5, 7, 5000]);
        assert_eq!(estimate(&g, 1000, &listed).snapshots, 2.0);
        assert_eq!(estimate(&g, 1000, &SnapshotRequest::PullOff).snapshots, 2.0);
    }

    #[test]
    fn what_does_not_fit_is_refused_naming_the_fields_and_the_bytes() {
        let g = grid(2048);
        let e = estimate(&g, 100_000, &SnapshotRequest::All);
        let machine = Some((16.0 * 1024f64.powi(3), Some(8.0 * 1024f64.powi(3))));
        let err = check(
            &e,
            machine,
            "grid.n",
            &g,
            100_000,
            "protocol.max_steps = 100000",
            "\"all\"",
        )
        .unwrap_err()
        .to_string();
        for part in [
            "output.snapshots = \"all\"",
            "protocol.max_steps = 100000",
            "grid.n = 2048 × 2048",
            "this machine has 16.0 GiB",
            "in all (MemTotal), 8.0 GiB",
            "available now",
            "may need about 6.9 TiB",
        ] {
            assert!(err.contains(part), "{part:?} missing: {err}");
        }
        // Without /proc/meminfo, the hard bound.
        let err = check(
            &e,
            None,
            "grid.n",
            &g,
            100_000,
            "protocol.max_steps = 100000",
            "\"all\"",
        )
        .unwrap_err()
        .to_string();
        assert!(err.contains("refuses runs above 1.0 TiB"), "{err}");
        // 10^18 steps of records alone, on any machine.
        let small = grid(32);
        let e = estimate(&small, 1_000_000_000_000_000_000, &SnapshotRequest::None);
        assert!(
            check(
                &e,
                None,
                "grid.n",
                &small,
                1_000_000_000_000_000_000,
                "protocol.max_steps",
                "\"none\""
            )
            .is_err()
        );
        // What fits passes.
        let e = estimate(&small, 100_000, &SnapshotRequest::Every(100));
        assert!(
            check(
                &e,
                machine,
                "grid.n",
                &small,
                100_000,
                "",
                "{ every = 100 }"
            )
            .is_ok()
        );
    }

    #[test]
    fn meminfo_is_read_in_kib() {
        let text = "MemTotal:       24684084 kB\nMemFree:        22885108 kB\n\
                    MemAvailable:   23702904 kB\n";
        assert_eq!(
            parse_meminfo(text),
            Some((24684084.0 * 1024.0, Some(23702904.0 * 1024.0)))
        );
        assert_eq!(parse_meminfo("MemFree: 1 kB\n"), None);
        assert_eq!(parse_meminfo("MemTotal: 2 kB\n"), Some((2048.0, None)));
    }
}
