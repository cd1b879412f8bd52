//! Richardson extrapolation of the pull-off of a body given as a height array (the Python
//! package's `tack.pull_off(..., richardson=True)`): the array and the array at twice the
//! element size, pulled off along the same path, extrapolated at the law's order (`2F(Δx) −
//! F(2Δx)` for the criterion and the Dugdale law, `F(Δx) + (F(Δx) − F(2Δx))/3` for the smooth
//! laws).
//!
//! [`crate::heights::run`] refuses `RunOptions::richardson`, because an array is given per
//! element and the library cannot know the body between its samples. This module takes the
//! one coarsening that keeps the body the same body wherever that can hold: the coarse grid's
//! element centres are fine element centres (`tack_geometry::coarsen_band_limited`'s rule:
//! coarse centre `i` is fine centre `2i + n/2 − 2⌊n/4⌋`), so the coarse array is the body
//! *sampled at the coarse centres* ([`coarse_heights`]). That is exact for any smooth body
//! (sphere, ellipsoid, power law: the values at those points are the body's) and for roughness
//! band-limited to the coarse grid's Nyquist wave `π/(2Δx)` (`tack.surface.random(...,
//! q1=π/(2Δx))`), which the coarse grid samples without aliasing. Roughness with content above
//! `π/(2Δx)` (the default band `q1 = π/Δx`) is aliased: the coarse run pulls off another body.
//! [`aliased_rms`] measures that content (after removing the best-fitting quadratic, so that a
//! smooth body does not count, under a Hann window, so that the array's edges do not) and the
//! result carries a warning beginning `richardson:` when it exceeds [`ALIAS_TOLERANCE`] of the
//! residual's rms. The check is a spectral estimate, not a proof: content just above
//! `π/(2Δx)` is caught only once it is a percent of the rms. Refused: odd array sides (the period could not be kept) and a γ array (given per
//! element: a pattern's edges would move).

use ndarray::Array2;

use crate::Error;
use crate::engine::{RunOptions, RunOutcome};
use crate::heights::{PullOffSpec, pull_off, pull_off_scene};
use crate::scene::SceneError;

/// Largest share of the rms of the heights' residual (about their best quadratic) above the
/// coarse Nyquist wave ([`aliased_rms`]) with which the coarse array is taken as the same body.
pub const ALIAS_TOLERANCE: f64 = 0.01;

/// The array sampled at the element centres of the grid of twice the element size: shape
/// `(nx/2, ny/2)`, a side of one element staying one; odd sides are refused.
pub fn coarse_heights(heights: &Array2<f64>) -> Result<Array2<f64>, SceneError> {
    let (nx, ny) = heights.dim();
    for (field, n) in [(tack_fields::GRID_NX, nx), (tack_fields::GRID_NY, ny)] {
        if n != 1 && n % 2 == 1 {
            return Err(SceneError::OutOfRange {
                field: field.into(),
                value: n.to_string(),
                allowed: "an even number of elements (or 1) with richardson: the grid of twice \
                          the element size keeps the array's extent and centres"
                    .into(),
            });
        }
    }
    Ok(tack_geometry::coarse_centres(heights))
}

/// `heights` minus its least-squares quadratic `c0 + c1 x + c2 y + c3 x² + c4 xy + c5 y²`
/// (terms along an axis of one element left out).
#[allow(clippy::needless_range_loop)] // the normal equations' indices
pub fn quadratic_residual(heights: &Array2<f64>) -> Array2<f64> {
    let (nx, ny) = heights.dim();
    let coord = |i: usize, n: usize| (i as f64 - (n / 2) as f64) / n.max(1) as f64;
    let basis = |i: usize, j: usize| {
        let (x, y) = (coord(i, nx), coord(j, ny));
        [1.0, x, y, x * x, x * y, y * y]
    };
    let mut a = [[0.0f64; 6]; 6];
    let mut b = [0.0f64; 6];
    for ((i, j), &h) in heights.indexed_iter() {
        let phi = basis(i, j);
        for r in 0..6 {
            b[r] += phi[r] * h;
            for c in 0..6 {
                a[r][c] += phi[r] * phi[c];
            }
        }
    }
    let coef = solve_least_squares(a, b);
    Array2::from_shape_fn((nx, ny), |(i, j)| {
        let phi = basis(i, j);
        heights[[i, j]] - (0..6).map(|k| coef[k] * phi[k]).sum::<f64>()
    })
}

/// Gaussian elimination with partial pivoting; a column whose pivot vanishes (a basis
/// function that is constant or repeated on the grid) gets the coefficient 0.
#[allow(clippy::needless_range_loop)] // row and column indices of a 6 × 6 system
fn solve_least_squares(mut a: [[f64; 6]; 6], mut b: [f64; 6]) -> [f64; 6] {
    let scale = (0..6).map(|k| a[k][k].abs()).fold(0.0, f64::max);
    let mut pivots = [None; 6];
    let mut row = 0;
    for col in 0..6 {
        let Some(p) = (row..6).max_by(|&r, &s| a[r][col].abs().total_cmp(&a[s][col].abs())) else {
            break;
        };
        if a[p][col].abs() <= 1e-12 * scale {
            continue;
        }
        a.swap(row, p);
        b.swap(row, p);
        for r in 0..6 {
            if r != row {
                let f = a[r][col] / a[row][col];
                for c in 0..6 {
                    a[r][c] -= f * a[row][c];
                }
                b[r] -= f * b[row];
            }
        }
        pivots[col] = Some(row);
        row += 1;
    }
    let mut x = [0.0; 6];
    for (col, p) in pivots.iter().enumerate() {
        if let Some(r) = *p {
            x[col] = b[r] / a[r][col];
        }
    }
    x
}

/// The rms of the heights' content above the Nyquist wave of the grid of twice the element
/// size, and the rms it is measured against: the heights minus their best-fitting quadratic
/// ([`quadratic_residual`]: a smooth body does not count), about its mean, under a Hann window
/// (the array need not be periodic: the window removes the jumps at its edges, which would
/// otherwise count as content at every wave number), measured by
/// `tack_geometry::share_above_coarse_nyquist`. Returns `(share · rms, rms)` of that residual.
/// On 128² spheres: 0.16% (H = 0.5) and 0.07% (H = 0.8) for roughness band-limited to
/// `π/(2Δx)`, 11% and 4.4% for the full band `π/Δx`, 4.8% for a band 20% beyond `π/(2Δx)`.
pub fn aliased_rms(heights: &Array2<f64>) -> (f64, f64) {
    let residual = quadratic_residual(heights);
    let (nx, ny) = residual.dim();
    let mean = residual.mean().unwrap_or(0.0);
    let rms = (residual.iter().map(|r| (r - mean).powi(2)).sum::<f64>()
        / residual.len().max(1) as f64)
        .sqrt();
    let hann = |i: usize, n: usize| {
        if n <= 1 {
            1.0
        } else {
            0.5 * (1.0 - (std::f64::consts::TAU * i as f64 / (n - 1) as f64).cos())
        }
    };
    let windowed = Array2::from_shape_fn((nx, ny), |(i, j)| {
        (residual[[i, j]] - mean) * hann(i, nx) * hann(j, ny)
    });
    (
        tack_geometry::share_above_coarse_nyquist(&windowed) * rms,
        rms,
    )
}

/// Whether the coarse array aliases: its content above the coarse Nyquist wave
/// ([`aliased_rms`]) is above [`ALIAS_TOLERANCE`] of the residual's rms, and the residual is
/// more than the rounding of the heights (a smooth body's residual is rounding noise).
pub fn aliases(heights: &Array2<f64>) -> (bool, f64, f64) {
    let (aliased, rms) = aliased_rms(heights);
    let range = heights.iter().fold(0.0f64, |m, h| m.max(h.abs()));
    let real = rms > 1e-9 * range;
    (real && aliased > ALIAS_TOLERANCE * rms, aliased, rms)
}

/// The pull-off of `heights` by the rule of [`PullOffSpec`] ([`pull_off`]), and the same body
/// at twice the element size ([`coarse_heights`]) along the same path (the fine run's
/// `max_approach`, steps and radius), extrapolated. The fine outcome is returned with the
/// summary entries of `tack run --richardson` (`pull_off_force_coarse`,
/// `pull_off_force_richardson`, `pull_off_error_estimate`, `pull_off_ratio_richardson` where
/// F_JKR applies) and `richardson_order` (the law's, `tack_solver::Law::convergence_order`),
/// `richardson_aliased_rms`; a warning
/// beginning `richardson:` when the heights alias on the coarse grid. The error estimate is
/// `tack_solver::pull_off_error_estimate`, with the criterion's floor 1.4·(Δx/a_c)·|F| for
/// the zero-range law on a body with a radius; `|F(Δx) − F(2Δx)|` otherwise.
pub fn pull_off_richardson(
    heights: &Array2<f64>,
    spec: &PullOffSpec,
    options: &RunOptions,
    observer: &mut dyn tack_solver::Observer,
) -> Result<RunOutcome, Error> {
    if spec.gamma_map.is_some() {
        return Err(SceneError::Inconsistent(
            "richardson needs a work of adhesion that does not depend on the grid; gamma is \
             given as an array, per element (a pattern's edges would move on the coarse grid)"
                .into(),
        )
        .into());
    }
    let coarse = coarse_heights(heights)?;
    let plan = pull_off_scene(heights, spec)?;
    let single = RunOptions {
        richardson: false,
        ..options.clone()
    };
    // The fine problem's path (the builder's default rule, or as given), taken by the coarse
    // run too: the coarse grid would see the roughness's top at other centres.
    let fine = crate::heights::problem(&plan.scene, &plan.body(heights))?;
    let path = &fine.path;
    let coarse_spec = PullOffSpec {
        dx: 2.0 * spec.dx,
        radius: fine.path_rule.map(|r| r.radius).or(spec.radius),
        max_approach: Some(path.max_approach),
        unload_step: Some(path.unload_step),
        coarse_unload_step: path.coarse_unload_step,
        ..spec.clone()
    };
    // Both problems are checked before the (longer) fine solve.
    let coarse_problem = pull_off_scene(&coarse, &coarse_spec)
        .and_then(|plan| crate::heights::problem(&plan.scene, &plan.body(&coarse)))
        // What only the operator tells (a smooth law's least range on a periodic grid or a
        // film) is checked by building the coarse solver.
        .and_then(|problem| problem.solver(None).map(|_| problem));
    if let Err(e) = coarse_problem {
        let (nx, ny) = coarse.dim();
        return Err(SceneError::Inconsistent(format!(
            "richardson runs the body again on the coarse array (every second element: {nx} × \
             {ny} at {} = {}), which fails where the fine one passes: {e}",
            tack_fields::GRID_DX,
            tack_fields::num(2.0 * spec.dx)
        ))
        .into());
    }
    let mut outcome = pull_off(heights, spec, &single, observer)?;
    let started = std::time::Instant::now();
    let coarse_f = pull_off(&coarse, &coarse_spec, &single, observer)?.pull_off_force();
    outcome.coarse_wall_time = Some(started.elapsed());
    let dx_over_a_c = match (plan.radius, spec.adhesion.model) {
        (Some(r), m) if m.is_zero_range() => {
            Some(spec.dx / tack_analytics::jkr_pull_off_radius(spec.e_star, spec.gamma, r))
        }
        _ => None,
    };
    let (aliasing, aliased, rms) = aliases(heights);
    let forces = (outcome.pull_off_force(), coarse_f);
    let summary = &mut outcome.result.summary;
    crate::engine::insert_richardson(summary, &outcome.problem, forces, dx_over_a_c);
    summary
        .extra
        .insert("richardson_aliased_rms".into(), aliased);
    if aliasing {
        summary.warnings.push(format!(
            "richardson: the heights hold content above the coarse grid's Nyquist wave \
             π/(2·dx) ({:.2}% of their rms about the best quadratic; at most {}% taken as the \
             same body): the coarse run samples another body (aliasing), so the extrapolated \
             pull-off and its error estimate do not hold; make the roughness band-limited to \
             q1 ≤ π/(2·dx)",
            100.0 * aliased / rms,
            100.0 * ALIAS_TOLERANCE
        ));
    }
    Ok(outcome)
}

#[cfg(test)]
mod tests {
    use super::*;
    use tack_geometry::{Boundary, Grid, RoughSpec, Sphere, Surface, rough_surface};

    #[test]
    fn a_coarse_array_that_does_not_hold_the_contact_is_named() {
        // The 36² sphere array passes alone; its coarse array loses a fine element at the
        // positive edge, where the one-step load's disc then reaches.
        let heights = sphere(36, 0.3, 8.0);
        let spec = PullOffSpec::new(0.3, 1.0, 0.125);
        let e = pull_off_richardson(&heights, &spec, &RunOptions::default(), &mut ())
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("richardson runs the body again on the coarse array"),
            "{e}"
        );
        assert!(e.contains("18 × 18 at grid.dx = 0.6"), "{e}");
    }

    fn sphere(n: usize, dx: f64, radius: f64) -> Array2<f64> {
        let grid = Grid::square(n, dx, Boundary::Free).unwrap();
        Surface::from_shape(grid, &Sphere::new(radius).unwrap()).into_heights()
    }

    #[test]
    fn the_coarse_array_is_the_sphere_at_the_coarse_centres() {
        for n in [32, 34] {
            let fine = sphere(n, 0.45, 8.0);
            let want = sphere(n / 2, 0.9, 8.0);
            let got = coarse_heights(&fine).unwrap();
            assert_eq!(got.dim(), want.dim());
            for (a, b) in got.iter().zip(&want) {
                assert!((a - b).abs() < 1e-12, "{n}: {a} vs {b}");
            }
        }
        let e = coarse_heights(&Array2::zeros((33, 32)))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("grid.nx = 33 is invalid"), "{e}");
    }

    #[test]
    fn smooth_and_band_limited_bodies_do_not_alias_and_the_default_band_does() {
        let (n, dx) = (64, 1.0 / 64.0);
        let smooth = sphere(n, dx, 1.0);
        assert!(!aliases(&smooth).0, "{:?}", aliases(&smooth));
        let grid = Grid::square(n, dx, Boundary::Free).unwrap();
        let rough = |q1: f64| {
            let spec = RoughSpec {
                q1,
                ..RoughSpec::paper_defaults(grid, 1e-3, 0.5, 3)
            };
            rough_surface(grid, &spec).unwrap().into_heights() + &smooth
        };
        let (aliasing, limited, rms) = aliases(&rough(std::f64::consts::PI / (2.0 * dx)));
        assert!(!aliasing, "{limited:e} of {rms:e}");
        let (aliasing, full, rms) = aliases(&rough(std::f64::consts::PI / dx));
        assert!(aliasing && full > 0.05 * rms, "{full:e} of {rms:e}");
    }

    #[test]
    fn a_sphere_array_extrapolates_like_the_sphere_scene() {
        // R = 8, E* = 1, γ = 0.125 (a_c = 3.05) on 32² elements of 0.45 and 16² of 0.9.
        let heights = sphere(32, 0.45, 8.0);
        let spec = PullOffSpec::new(0.45, 1.0, 0.125);
        let outcome =
            pull_off_richardson(&heights, &spec, &RunOptions::default(), &mut ()).unwrap();
        let s = &outcome.result.summary;
        let (f, c) = (s.pull_off_force, s.extra["pull_off_force_coarse"]);
        assert_eq!(s.extra["pull_off_force_richardson"], 2.0 * f - c);
        assert!(s.warnings.iter().all(|w| !w.starts_with("richardson")));
        // The coarse run is the sphere scene at 2Δx along the fine path.
        let plan = pull_off_scene(&heights, &spec).unwrap();
        let mut file = plan.scene.file.clone();
        file.geometry = crate::scene::Geometry::Sphere { radius: 8.0 };
        let scene = crate::Scene::from_file(file, ".").unwrap();
        let options = RunOptions {
            richardson: true,
            ..RunOptions::default()
        };
        let reference = crate::run(&scene, &options, &mut ()).unwrap();
        let r = &reference.result.summary.extra;
        assert!((r["pull_off_force_coarse"] / c - 1.0).abs() < 1e-9, "{c}");
        let want = r["pull_off_error_estimate"];
        let got = s.extra["pull_off_error_estimate"];
        assert!((got / want - 1.0).abs() < 1e-9, "{got} vs {want}");
        // The extrapolation moves the ratio towards 1 (the criterion's first-order error).
        let ratio = s.extra["pull_off_ratio_richardson"];
        assert!(
            (ratio - 1.0).abs() < (s.pull_off_ratio - 1.0).abs(),
            "{ratio} vs {}",
            s.pull_off_ratio
        );
        // A γ array is refused.
        let patterned = PullOffSpec {
            gamma_map: Some(Array2::from_elem((32, 32), 0.125)),
            ..spec
        };
        let e = pull_off_richardson(&heights, &patterned, &RunOptions::default(), &mut ())
            .unwrap_err()
            .to_string();
        assert!(e.contains("gamma is given as an array"), "{e}");
    }
}
