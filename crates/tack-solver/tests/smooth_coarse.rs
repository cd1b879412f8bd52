//! A smooth law on meshes far coarser than its process zone (Tabor μ of hundreds to thousands
//! on 32²): a step that says it converged is an equilibrium, checked element by element with
//! an operator built afresh (the contact's gaps within 1e-6 of the range, every other element
//! at its law's pressure); a range too short for round-off is refused with the least one the
//! mesh takes; the mesh warning says that the body glues there and names the zero-range
//! criterion.

use tack_geometry::{Boundary, Grid, Sphere, Surface};
use tack_kernels::operator_for;
use tack_solver::{AdhesionLaw, AdhesiveOptions, AdhesiveSolver, Exponential, SolverError};

const GAMMA: f64 = 1e-3;
const N: usize = 32;

fn surface() -> Surface {
    let grid = Grid::square(N, 1.0 / N as f64, Boundary::Free).expect("a valid grid");
    Surface::from_shape(grid, &Sphere::new(1.0).expect("a valid radius"))
}

fn solver(range: f64) -> Result<AdhesiveSolver, SolverError> {
    let surface = surface();
    let op = operator_for(*surface.grid(), 1.0).expect("a valid modulus");
    let law = AdhesionLaw::Exponential(Exponential { range });
    AdhesiveSolver::with_law(op, &surface, GAMMA, law, AdhesiveOptions::default())
}

/// ρ = 1e-5 on 32² (μ = 1000; the process zone spans 2.7e-6 elements, the peak tension γ/ρ
/// = 100 is about 10³ times the Hertz pressures here): load, press and pull. Each converged step's
/// pressure is checked against `K p` from an operator of its own. The tolerance is twice the
/// solver's own, `|g| ≤ 1e-6·ρ` on the contact (`RANGE_GAPS`) and `1e-6·ρ/k` in pressure off it:
/// the independent product's round-off on the gaps (about 1e-17 on gaps of 1e-2) reaches the
/// pressure through the law's stiffness γ/ρ² = 1e7, about 1e-10, a third of that tolerance.
/// Before, the residual's scale was the peak tension alone, which allowed contact gaps of
/// 3.5e-2·ρ here (and at ρ = 1e-12 a loaded sphere with no pressure at all); the first step
/// then fails by a factor of 360 (a pressure of 0 where the law asks −2.1e-7).
#[test]
fn a_converged_step_far_below_the_process_zone_is_an_equilibrium() {
    let range = 1e-5;
    let surface = surface();
    let mut op = operator_for(*surface.grid(), 1.0).expect("a valid modulus");
    let k = op.self_compliance();
    let mut s = solver(range).expect("a range the mesh takes");
    let gap_tol = 2e-6 * range;
    // The pressure tolerance off the contact: 1e-6·ρ/k (the same residual, in pressure), twice.
    let pressure_tol = 2e-6 * range / k;
    let mut u = ndarray::Array2::zeros((N, N));
    let mut checked = (0, 0);
    for d in [-2e-4, 0.0, 0.01, 0.02, 0.01, 0.0, -0.01] {
        let rec = s.step(d).expect("a valid approach");
        assert!(rec.converged, "d = {d}: not converged");
        let p = s.pressure().clone();
        op.apply(p.view(), u.view_mut());
        for ((i, j), &pi) in p.indexed_iter() {
            let g = surface.heights()[[i, j]] - d + u[[i, j]];
            let law = -(GAMMA / range) * (-g.max(0.0) / range).exp();
            if s.bonded()[[i, j]] {
                assert!(g.abs() <= gap_tol, "d = {d}, ({i}, {j}): contact gap {g:e}");
                assert!(
                    pi >= law - pressure_tol,
                    "d = {d}: contact below the wall's tension"
                );
                checked.0 += 1;
            } else {
                assert!(g >= -gap_tol, "d = {d}, ({i}, {j}): penetration {g:e}");
                assert!(
                    (pi - law).abs() <= pressure_tol,
                    "d = {d}, ({i}, {j}): p = {pi:e} against its law's {law:e}"
                );
                checked.1 += 1;
            }
        }
        if d > 0.0 {
            assert!(rec.force > 0.0, "d = {d}: a pressed sphere pushes back");
        }
    }
    assert!(checked.0 > 100 && checked.1 > 1000, "{checked:?}");
}

/// A range whose residual tolerance (1e-6·ρ/k in pressure) would fall below 1000 round-offs of
/// its peak tension γ/ρ is refused, naming the field and the least range this mesh takes; that
/// range is then taken, and one just below it is not.
#[test]
fn a_range_too_short_for_round_off_is_refused_with_the_least_the_mesh_takes() {
    let err = solver(1e-7).err().expect("refused");
    let message = err.to_string();
    let SolverError::BelowLeast {
        field,
        value,
        least,
        ..
    } = err
    else {
        panic!("{message}");
    };
    assert_eq!((field, value), ("adhesion.range", 1e-7));
    assert!(
        message.starts_with("adhesion.range = 1e-7 is invalid: must be at least ")
            && message.contains("jkr_limit"),
        "{message}"
    );
    // 32² with γ = 1e-3 and k = 1.1222·Δx/E*: least² = 1e3·ε·k·γ/(1e-7·10) = 7.8e-12.
    assert!((2.7e-6..2.9e-6).contains(&least), "least {least:e}");
    assert!(solver(least * 1.001).is_ok());
    assert!(solver(least * 0.999).is_err());
}

/// The mesh warning below 0.3 elements per process zone says the body glues and names the
/// zero-range criterion, with the elements in significant digits (not a bare 0); at 0.6 it
/// keeps the plain under-resolution warning.
#[test]
fn the_mesh_warning_says_a_far_coarser_mesh_glues() {
    let dx = 1.0 / N as f64;
    let far = AdhesionLaw::Exponential(Exponential { range: 1e-5 });
    let w = far.mesh_warning(1.0, GAMMA, dx).expect("under-resolved");
    assert!(
        w.contains("spans 2.7e-6 elements") && w.contains("glues") && w.contains("\"jkr_limit\""),
        "{w}"
    );
    // ρ = 3.333e-3 on 64²: 0.6 elements.
    let near = AdhesionLaw::Exponential(Exponential { range: 3.333e-3 });
    let w = near
        .mesh_warning(1.0, GAMMA, 1.0 / 64.0)
        .expect("under-resolved");
    assert!(
        w.contains("spans 0.6 elements") && !w.contains("glues"),
        "{w}"
    );
}
