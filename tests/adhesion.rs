//! Adhesive contact against closed forms: JKR sphere, Kendall punch, Johnson's 1D waviness.

use tack_solver::KAPPA;
use tack_tests::JkrSphere;

#[test]
fn probe_jkr() {
    for ratio in [5.0, 10.0, 20.0] {
        let t = std::time::Instant::now();
        let run = JkrSphere::new(ratio, KAPPA).run();
        eprintln!(
            "a_c/dx={ratio}: err {:+.4} jump-off d {:.3} steps {} cg {} conv {} extent {} / {} time {:.2}",
            run.pull_off_error,
            run.last_contact_approach,
            run.result.records.len(),
            run.result.cg_iterations(),
            run.result.all_converged(),
            run.max_extent,
            run.grid.nx() / 2,
            t.elapsed().as_secs_f64()
        );
        let load: usize = run
            .result
            .records
            .iter()
            .zip(&run.result.phases)
            .filter(|(_, p)| **p == tack_solver::Phase::Load)
            .map(|(r, _)| r.cg_iterations)
            .sum();
        let rounds: usize = run
            .result
            .records
            .iter()
            .map(|r| r.active_set_iterations)
            .sum();
        let changed = run
            .result
            .records
            .iter()
            .filter(|r| r.active_set_iterations > 1)
            .count();
        eprintln!("  load cg {load}, AS rounds {rounds}, steps with set changes {changed}");
    }
}
