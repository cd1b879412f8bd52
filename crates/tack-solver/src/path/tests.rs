//! Tests of the approach paths: path rules, refined retraction, observers and snapshots.

use super::*;
use crate::AdhesiveOptions;
use tack_geometry::{Boundary, Grid, Sphere, Surface};

/// A smooth adhesive sphere in JKR units (R = E* = γ = 1) on a small free grid, a_c/Δx ≈ 4.
fn sphere_solver() -> AdhesiveSolver {
    let dx = 0.38;
    let grid = Grid::square(19, dx, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    let op = tack_kernels::operator_for(grid, 1.0).unwrap();
    AdhesiveSolver::new(op, &surface, 1.0, crate::KAPPA, AdhesiveOptions::default()).unwrap()
}

const COARSE: f64 = 1.0;

fn path(coarse: Option<f64>) -> ApproachPath {
    ApproachPath {
        start: 1.0,
        max_approach: 6.0,
        load_step: 1.0,
        unload_step: 0.05,
        coarse_unload_step: coarse,
        refine_pull_off: false,
        retract_to: None,
        max_steps: 10_000,
    }
}

fn unload_approaches(r: &PathResult) -> Vec<f64> {
    r.records
        .iter()
        .zip(&r.phases)
        .filter(|(_, p)| **p == Phase::Unload)
        .map(|(s, _)| s.approach)
        .collect()
}

#[test]
fn an_indentation_is_complete_after_its_one_step_even_at_the_step_cap() {
    for max_steps in [1, 100] {
        let path = ApproachPath {
            max_steps,
            ..ApproachPath::indentation(1.5).unwrap()
        };
        let r = sphere_solver()
            .run_path(&path, &SnapshotRequest::None, &mut ())
            .unwrap();
        assert_eq!(r.records.len(), 1);
        assert!(r.completed, "max_steps = {max_steps}");
        assert_eq!(r.phases, vec![Phase::Load]);
    }
    // A load cut short by the cap is not complete and does not retract.
    let cut = ApproachPath {
        max_steps: 2,
        retract_to: Some(6.0),
        ..path(None)
    };
    let r = sphere_solver()
        .run_path(&cut, &SnapshotRequest::None, &mut ())
        .unwrap();
    assert_eq!(r.records.len(), 2);
    assert!(!r.completed);
}

#[test]
fn a_step_that_would_overflow_the_path_is_refused() {
    let e = ApproachPath::load_retract(0.0, 1.0, 0.1, 1e308)
        .unwrap_err()
        .to_string();
    assert!(e.contains("protocol.unload_step = 1e308"), "{e}");
    assert!(e.contains("≤ 1e300"), "{e}");
    assert!(ApproachPath::load_retract(0.0, 1.0, 0.1, 1e290).is_ok());
}

#[test]
fn coarse_retraction_switches_to_the_unload_step_once_the_force_is_tensile() {
    let fine = sphere_solver()
        .run_path(&path(None), &SnapshotRequest::None, &mut ())
        .unwrap();
    let coarse = sphere_solver()
        .run_path(&path(Some(COARSE)), &SnapshotRequest::None, &mut ())
        .unwrap();
    assert!(fine.completed && coarse.completed);
    // Without a coarse step: d = max − k·unload_step, bit for bit.
    for (k, d) in unload_approaches(&fine).into_iter().enumerate() {
        assert_eq!(d.to_bits(), (6.0 - (k + 1) as f64 * 0.05).to_bits());
    }
    // With one: d = max − k·COARSE until a force ≤ 0, then d₀ − k·0.05 from that step's d₀.
    let first_unload = coarse
        .phases
        .iter()
        .position(|p| *p == Phase::Unload)
        .unwrap();
    let records = &coarse.records;
    let (mut anchor, mut stride, mut k, mut switched_at) = (6.0, COARSE, 1, None);
    for i in first_unload..records.len() {
        let previous = &records[i - 1];
        if stride == COARSE && previous.force <= 0.0 {
            (anchor, stride, k, switched_at) = (previous.approach, 0.05, 1, Some(i));
        }
        let want: f64 = anchor - k as f64 * stride;
        assert_eq!(records[i].approach.to_bits(), want.to_bits(), "step {i}");
        k += 1;
    }
    let switched_at = switched_at.expect("the retraction never became tensile");
    // The coarse part is compressive except its last step, and far shorter than the fine one.
    assert!(switched_at > first_unload + 1, "no compressive coarse step");
    assert!(
        records[first_unload..switched_at - 1]
            .iter()
            .all(|r| r.force > 0.0)
    );
    assert!(records[switched_at - 1].force <= 0.0);
    assert!(switched_at - first_unload < 10);
    assert!(coarse.records.len() < fine.records.len());
    // The pull-off lies in the tensile part: both paths find it, within the resolution of the
    // unload step (the coarse path's compressive contact is pinned as the fine one's).
    let (a, b) = (fine.pull_off_force(), coarse.pull_off_force());
    assert!(a < 0.0 && (a - b).abs() < 0.02 * a.abs(), "{a} vs {b}");
}

#[test]
fn coarse_retraction_respects_retract_to_and_max_steps() {
    let p = ApproachPath {
        retract_to: Some(3.5),
        ..path(Some(COARSE))
    };
    let r = sphere_solver()
        .run_path(&p, &SnapshotRequest::None, &mut ())
        .unwrap();
    assert!(r.completed);
    assert_eq!(unload_approaches(&r), [5.0, 4.0]);
    let p = ApproachPath {
        max_steps: 8,
        ..path(Some(COARSE))
    };
    let r = sphere_solver()
        .run_path(&p, &SnapshotRequest::None, &mut ())
        .unwrap();
    assert!(!r.completed);
    assert_eq!(r.records.len(), 8);
}

fn refined(coarse: f64) -> ApproachPath {
    ApproachPath {
        refine_pull_off: true,
        ..path(Some(coarse))
    }
}

#[test]
fn refined_retraction_finds_the_fine_pull_off_in_fewer_steps() {
    let fine = sphere_solver()
        .run_path(&path(None), &SnapshotRequest::None, &mut ())
        .unwrap();
    let r = sphere_solver()
        .run_path(&refined(0.25), &SnapshotRequest::All, &mut ())
        .unwrap();
    assert!(r.completed && r.all_converged());
    let d = unload_approaches(&r);
    // In path order, and every step either on the coarse lattice 6 − k/4 or a retraced
    // fine step 0.05 below the one before it.
    for w in d.windows(2) {
        let gap = w[0] - w[1];
        let on_lattice = ((6.0 - w[1]) / 0.25 - ((6.0 - w[1]) / 0.25).round()).abs() < 1e-9;
        assert!(gap > 0.0, "{d:?}");
        assert!(
            (gap - 0.05).abs() < 1e-9 || on_lattice,
            "{} → {}",
            w[0],
            w[1]
        );
    }
    // The pull-off lies inside a retraced stretch.
    let i = r.pull_off_step().unwrap();
    let step = |j: usize| r.records[j - 1].approach - r.records[j].approach;
    assert!((step(i) - 0.05).abs() < 1e-9 && (step(i + 1) - 0.05).abs() < 1e-9);
    assert!(
        r.records.len() < fine.records.len() / 2,
        "{}",
        r.records.len()
    );
    // The same pull-off as the fine path to well within the change of one fine step.
    let (a, b) = (fine.pull_off_force(), r.pull_off_force());
    assert!((a - b).abs() < 2e-3 * a.abs(), "{a} vs {b}");
    // Observers and snapshots saw the kept steps only, each once, in order.
    assert_eq!(r.snapshots.len(), r.records.len());
    for (k, s) in r.snapshots.iter().enumerate() {
        assert_eq!(s.step, k);
        let force: f64 = s.pressure.sum() * 0.38 * 0.38;
        assert!((force - r.records[k].force).abs() <= 1e-12 * force.abs().max(1.0));
        let n = s.bonded.iter().filter(|&&b| b).count();
        assert_eq!(n, r.records[k].n_bonded);
    }
}

#[test]
fn refined_retraction_respects_retract_to_and_max_steps_and_needs_a_coarse_step() {
    // A coarse step under 1.5 unload steps rounds to one: the fine path, bit for bit.
    let fine = sphere_solver()
        .run_path(&path(None), &SnapshotRequest::None, &mut ())
        .unwrap();
    for c in [0.05, 0.06] {
        let r = sphere_solver()
            .run_path(&refined(c), &SnapshotRequest::None, &mut ())
            .unwrap();
        assert_eq!(r.records, fine.records, "coarse {c}");
        assert!(r.completed);
    }
    let p = ApproachPath {
        retract_to: Some(3.6),
        ..refined(1.0)
    };
    let r = sphere_solver()
        .run_path(&p, &SnapshotRequest::None, &mut ())
        .unwrap();
    assert!(r.completed);
    assert_eq!(unload_approaches(&r), [5.0, 4.0], "compressive: no bracket");
    assert!(p.step_bound() >= r.records.len());
    for cap in [3, 9] {
        let p = ApproachPath {
            max_steps: cap,
            ..refined(1.0)
        };
        let r = sphere_solver()
            .run_path(&p, &SnapshotRequest::None, &mut ())
            .unwrap();
        assert!(!r.completed && r.records.len() == cap, "cap {cap}");
    }
    let e = ApproachPath {
        refine_pull_off: true,
        ..path(None)
    }
    .validate()
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with(
            "protocol.refine_pull_off = true needs a coarse step: set protocol.coarse_unload_step"
        ),
        "{e}"
    );
}

#[test]
fn a_state_restores_only_into_a_solver_of_its_grid_and_law() {
    let mut a = sphere_solver();
    a.step(1.0).unwrap();
    let saved = a.save_state();
    let grid = Grid::square(19, 0.38, Boundary::Free).unwrap();
    let surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
    let with_law = |law: crate::AdhesionLaw| {
        let op = tack_kernels::operator_for(grid, 1.0).unwrap();
        AdhesiveSolver::with_law(op, &surface, 1.0, law, AdhesiveOptions::default()).unwrap()
    };
    let dugdale = crate::AdhesionLaw::from(crate::Dugdale { sigma0: 1.0 });
    let exponential = crate::AdhesionLaw::from(crate::Exponential { range: 0.1 });
    for (law, kind) in [
        (dugdale, "a cohesive zone"),
        (exponential.clone(), "a smooth law"),
    ] {
        let e = with_law(law).restore_state(&saved).unwrap_err().to_string();
        assert!(
            e.contains(&format!(
                "(19 × 19 grid, zero range) does not fit this solver (19 × 19 grid, {kind})"
            )),
            "{e}"
        );
    }
    let mut smooth = with_law(exponential);
    smooth.step(0.5).unwrap();
    let e = a
        .restore_state(&smooth.save_state())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("(19 × 19 grid, a smooth law) does not fit"),
        "{e}"
    );
    // The same kind of law with another parameter: refused too, naming both.
    let wider = with_law(crate::AdhesionLaw::from(crate::Exponential { range: 0.2 }));
    let e = { wider }
        .restore_state(&smooth.save_state())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("(the law exponential with adhesion.range = 0.1) does not fit this solver (the law exponential with adhesion.range = 0.2)"),
        "{e}"
    );
    smooth.restore_state(&smooth.save_state()).unwrap();
    let small = Grid::square(7, 0.38, Boundary::Free).unwrap();
    let op = tack_kernels::operator_for(small, 1.0).unwrap();
    let s = Surface::from_shape(small, &Sphere::new(1.0).unwrap());
    let mut c = AdhesiveSolver::new(op, &s, 1.0, crate::KAPPA, AdhesiveOptions::default()).unwrap();
    assert!(c.restore_state(&saved).is_err());
    // Into its own solver: the next step is the one taken right after the save.
    let x = a.step(0.5).unwrap();
    a.restore_state(&saved).unwrap();
    assert_eq!(a.step(0.5).unwrap(), x);
}

#[test]
fn bad_coarse_unload_step_names_the_field() {
    for bad in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        let e = path(Some(bad)).validate().unwrap_err().to_string();
        assert!(
            e.starts_with("protocol.coarse_unload_step = ")
                && e.ends_with("is invalid: must be a finite number > 0"),
            "{e}"
        );
        let run = sphere_solver().run_path(&path(Some(bad)), &SnapshotRequest::None, &mut ());
        assert!(run.is_err());
    }
    assert!(path(Some(1e-3)).validate().is_ok());
}

#[test]
fn pull_off_snapshots_are_the_least_force_and_the_last_contact() {
    let p = path(Some(COARSE));
    let all = sphere_solver()
        .run_path(&p, &SnapshotRequest::All, &mut ())
        .unwrap();
    let kept = sphere_solver()
        .run_path(&p, &SnapshotRequest::PullOff, &mut ())
        .unwrap();
    assert_eq!(all.records, kept.records);
    let r = &all.records;
    let pull_off = (0..r.len())
        .min_by(|&a, &b| r[a].force.total_cmp(&r[b].force))
        .unwrap();
    let last = r.iter().rposition(|s| s.n_bonded > 0).unwrap();
    assert!(
        pull_off < last && last + 1 == r.len() - 1,
        "{pull_off} {last}"
    );
    assert_eq!(r[pull_off].force, all.pull_off_force());
    let steps: Vec<usize> = kept.snapshots.iter().map(|s| s.step).collect();
    assert_eq!(steps, [pull_off, last]);
    for s in &kept.snapshots {
        assert_eq!(s, &all.snapshots[s.step], "step {}", s.step);
    }
    assert!(kept.snapshots[1].bonded.iter().any(|&b| b));

    // A path cut off while bonded keeps its last step; one snapshot when the two coincide.
    let short = ApproachPath { max_steps: 8, ..p };
    let kept = sphere_solver()
        .run_path(&short, &SnapshotRequest::PullOff, &mut ())
        .unwrap();
    let r = &kept.records;
    let least = (0..r.len())
        .min_by(|&a, &b| r[a].force.total_cmp(&r[b].force))
        .unwrap();
    let steps: Vec<usize> = kept.snapshots.iter().map(|s| s.step).collect();
    if least == r.len() - 1 {
        assert_eq!(steps, [least]);
    } else {
        assert_eq!(steps, [least, r.len() - 1]);
    }
}

#[test]
fn observers_see_every_step_with_its_fields() {
    #[derive(Default)]
    struct Seen(Vec<(usize, usize, bool)>);
    impl Observer for Seen {
        fn on_fields(
            &mut self,
            index: usize,
            _: Phase,
            record: &StepRecord,
            pressure: &Array2<f64>,
            bonded: &Array2<bool>,
        ) {
            let n = bonded.iter().filter(|&&b| b).count();
            assert_eq!(n, record.n_bonded);
            assert_eq!(pressure.dim(), bonded.dim());
            self.0.push((index, n, false));
        }
        fn on_step(&mut self, index: usize, _: Phase, _: &StepRecord) {
            let last = self.0.last_mut().expect("on_fields comes first");
            assert_eq!(last.0, index);
            last.2 = true;
        }
    }
    let mut seen = Seen::default();
    let r = sphere_solver()
        .run_path(&path(Some(COARSE)), &SnapshotRequest::None, &mut seen)
        .unwrap();
    assert_eq!(seen.0.len(), r.records.len());
    assert!(seen.0.iter().enumerate().all(|(k, s)| s.0 == k && s.2));
}

#[test]
fn snapshots_are_kept_beside_the_callers_observer() {
    /// Counts steps and cancels after `stop` of them.
    struct Stop {
        stop: usize,
        seen: usize,
    }
    impl Observer for Stop {
        fn on_step(&mut self, _: usize, _: Phase, _: &StepRecord) {
            self.seen += 1;
        }
        fn cancelled(&mut self) -> bool {
            self.seen >= self.stop
        }
    }
    let p = path(Some(COARSE));
    let all = sphere_solver()
        .run_path(&p, &SnapshotRequest::All, &mut ())
        .unwrap();
    let mut counting = Stop {
        stop: usize::MAX,
        seen: 0,
    };
    let every = sphere_solver()
        .run_path(&p, &SnapshotRequest::Every(3), &mut counting)
        .unwrap();
    assert_eq!(counting.seen, all.records.len());
    let steps: Vec<usize> = every.snapshots.iter().map(|s| s.step).collect();
    assert_eq!(steps, (0..all.records.len()).step_by(3).collect::<Vec<_>>());
    for s in &every.snapshots {
        assert_eq!(s, &all.snapshots[s.step]);
    }
    let listed = sphere_solver()
        .run_path(&p, &SnapshotRequest::Steps(vec![4, 1, 10_000]), &mut ())
        .unwrap();
    let steps: Vec<usize> = listed.snapshots.iter().map(|s| s.step).collect();
    assert_eq!(steps, [1, 4]);
    // The caller's observer still cancels.
    let mut stop = Stop { stop: 3, seen: 0 };
    let e = sphere_solver()
        .run_path(&p, &SnapshotRequest::All, &mut stop)
        .unwrap_err();
    assert_eq!(e, SolverError::Cancelled { steps: 3 });
    // A restart forgets what was kept.
    let request = SnapshotRequest::PullOff;
    let mut keeper = SnapshotKeeper::new(&request);
    let mut solver = sphere_solver();
    let rec = solver.step(1.0).unwrap();
    keeper.on_fields(0, Phase::Load, &rec, solver.pressure(), solver.bonded());
    assert_eq!(keeper.into_snapshots().len(), 1);
    let mut keeper = SnapshotKeeper::new(&request);
    keeper.on_fields(0, Phase::Load, &rec, solver.pressure(), solver.bonded());
    keeper.on_restart();
    assert!(keeper.into_snapshots().is_empty());
}
