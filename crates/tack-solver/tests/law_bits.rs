//! The round-loop laws (the zero-range criterion and the Dugdale law) keep their bits: whole
//! load–unload paths on free and periodic grids, with and without a γ map, against fingerprints
//! of every step's force, approach, sets, rounds and CG iterations taken from the solver before
//! the two laws' loops became one (commit 945cea1; renewed once, see `expected`). A change of
//! any step's bits, round count or iteration count fails here; a change that is meant to move
//! them must say so and renew them.

use ndarray::Array2;
use tack_geometry::{Boundary, Grid, Shape, Sphere, Surface, Waviness2d};
use tack_kernels::operator_for;
use tack_solver::{
    AdhesionLaw, AdhesiveOptions, AdhesiveSolver, ApproachPath, Dugdale, JkrLimit, KAPPA,
    SnapshotRequest,
};

/// FNV-1a over 64-bit words: a fingerprint that does not depend on the standard library's
/// hasher.
fn fnv(words: impl IntoIterator<Item = u64>) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for w in words {
        for b in w.to_le_bytes() {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    }
    h
}

/// The path's fingerprint and its step count, for `law` on `shape` over an `n × n` grid of
/// side `side`, from `start` to `deepest` and back in steps `step`.
#[allow(clippy::too_many_arguments)]
fn fingerprint(
    shape: &dyn Shape,
    boundary: Boundary,
    n: usize,
    side: f64,
    gamma: f64,
    law: &AdhesionLaw,
    map: bool,
    (start, deepest, step): (f64, f64, f64),
) -> (u64, usize) {
    let grid = Grid::square(n, side / n as f64, boundary).unwrap();
    let surface = Surface::from_shape(grid, shape);
    let op = operator_for(grid, 1.0).unwrap();
    // The predicted releases (`cascade`) came after that commit and move the criterion's
    // rounds on purpose (docs/theory.md §3.4); without them the loop is the one fingerprinted.
    let options = AdhesiveOptions {
        cascade: false,
        ..AdhesiveOptions::default()
    };
    let mut solver = AdhesiveSolver::with_law(op, &surface, gamma, law.clone(), options).unwrap();
    if map {
        // Stripes of half and full γ.
        let g = Array2::from_shape_fn(
            (n, n),
            |(i, _)| if (i / 4) % 2 == 0 { gamma } else { 0.5 * gamma },
        );
        solver.set_gamma_map(g.view()).unwrap();
    }
    let path = ApproachPath {
        start,
        max_approach: deepest,
        load_step: step,
        unload_step: step,
        coarse_unload_step: None,
        refine_pull_off: false,
        retract_to: None,
        max_steps: 2_000,
    };
    let r = solver
        .run_path(&path, &SnapshotRequest::None, &mut ())
        .unwrap();
    let words = r.records.iter().flat_map(|s| {
        [
            s.approach.to_bits(),
            s.force.to_bits(),
            s.n_bonded as u64,
            s.n_cohesive as u64,
            s.active_set_iterations as u64,
            s.cg_iterations as u64,
            u64::from(s.converged) | u64::from(s.full_contact) << 1,
        ]
    });
    (fnv(words), r.records.len())
}

#[test]
fn the_criterion_and_the_dugdale_law_keep_their_bits() {
    let sphere = Sphere::new(1.0).unwrap();
    let wavy = Waviness2d::new(0.02, 1.0).unwrap();
    let free = Boundary::Free;
    let periodic = Boundary::Periodic;
    let dugdale = AdhesionLaw::Dugdale(Dugdale { sigma0: 2.0 });
    let criterion = AdhesionLaw::JkrLimit(JkrLimit { kappa: KAPPA });
    let cases: [(&str, (u64, usize)); 6] = [
        (
            "criterion, sphere, free",
            fingerprint(
                &sphere,
                free,
                64,
                1.0,
                1e-3,
                &criterion,
                false,
                (-0.01, 0.02, 0.002),
            ),
        ),
        (
            "criterion, sphere, free, γ map",
            fingerprint(
                &sphere,
                free,
                64,
                1.0,
                1e-3,
                &criterion,
                true,
                (-0.01, 0.02, 0.002),
            ),
        ),
        (
            "non-adhesive, sphere, free",
            fingerprint(
                &sphere,
                free,
                64,
                1.0,
                0.0,
                &criterion,
                false,
                (0.0, 0.02, 0.004),
            ),
        ),
        (
            "criterion, waviness, periodic",
            fingerprint(
                &wavy,
                periodic,
                32,
                1.0,
                2e-3,
                &criterion,
                false,
                (0.0, 0.05, 0.004),
            ),
        ),
        (
            "Dugdale, sphere, free",
            fingerprint(
                &sphere,
                free,
                64,
                1.0,
                1e-3,
                &dugdale,
                false,
                (-0.01, 0.02, 0.002),
            ),
        ),
        (
            "Dugdale, waviness, periodic, γ map",
            fingerprint(
                &wavy,
                periodic,
                32,
                1.0,
                2e-3,
                &dugdale,
                true,
                (-0.002, 0.05, 0.004),
            ),
        ),
    ];
    for (name, (print, steps)) in &cases {
        println!("{name}: {print:#018x}, {steps} steps");
    }
    // Taken at commit 945cea1, before the criterion's and the Dugdale law's loops became one.
    // All six were renewed when a round after a quiet one began continuing its CG
    // (docs/theory.md §3.4): the same steps, sets and rounds; CG iterations 1 130 → 935 (the
    // criterion) and 2 142 → 2 045 (the Dugdale law); forces moved by at most 6.8e-11 (the
    // criterion) and 3.3e-10 (the Dugdale law) of each path's largest force, both solutions
    // meeting the CG tolerance. The non-adhesive path was renewed again when the nested start
    // began solving its coarse grids to the first rounds' tolerance (docs/theory.md §3.4): the
    // same steps, sets and rounds; the cold start's CG 27 → 26; forces moved by at most
    // 2.3e-16 of the path's largest force.
    let expected: [(u64, usize); 6] = [
        (0xa3a5_c719_7b63_d75b, 37),
        (0x3c37_50bc_ca9c_5f46, 35),
        (0xabf8_dccc_7036_20d6, 12),
        (0x321f_f104_21c3_14e6, 33),
        (0xc993_6d63_9449_4039, 105),
        (0x0771_22c3_5f19_6b4f, 71),
    ];
    for ((name, got), want) in cases.iter().zip(expected) {
        assert_eq!(*got, want, "{name}: the path's bits changed");
    }
}
