//! The coarse (2Δx) problem of a Richardson extrapolation: the same body on a grid of twice the
//! element size, or a refusal naming what makes the body depend on the grid.

use tack_fields as fields;

use crate::problem::Problem;
use crate::scene::{Roughness, Scene, SceneError};

/// The scene's problem on a grid of twice the element size over (at least) the same domain,
/// for the Richardson extrapolation of `tack run --richardson` at the law's order
/// (`tack_solver::Law::convergence_order`): the Pohrt–Popov criterion converges at first order
/// in Δx, so `2·F(Δx) − F(2Δx)` cancels the leading error (smooth sphere: +6.9% at
/// a_c/Δx = 20 becomes −0.3%); the smooth laws at second order, `F(Δx) + (F(Δx) − F(2Δx))/3`.
///
/// The body must be the same on both grids. Shapes are analytic. Random roughness is one
/// continuous surface per band (`tack_geometry::rough_surface`), so it needs a band the coarse
/// grid holds, `roughness.q1 ≤ π/(2Δx)` given explicitly (the default `q1 = π/Δx` follows the
/// grid), and even grid sides (the period is kept). A height map (`roughness.kind = "file"`)
/// must be band-limited to `π/(2Δx)` and is read at the coarse centres
/// (`tack_geometry::coarsen_band_limited`). Periodic grids need even sides.
pub fn coarse_problem(scene: &Scene, problem: &Problem) -> Result<Problem, SceneError> {
    let refuse = |reason: String| SceneError::Inconsistent(format!("--richardson {reason}"));
    if problem.path.is_indentation() {
        return Err(refuse(format!(
            "extrapolates the pull-off force; an indentation ({}) has none",
            tack_fields::PROTOCOL_INDENT
        )));
    }
    if problem.heights_in_memory {
        return Err(refuse(
            "needs a geometry that does not depend on the grid; heights given as an array are \
             given per element"
                .into(),
        ));
    }
    if scene.file.adhesion.gamma_map.is_some() {
        return Err(refuse(format!(
            "needs a work of adhesion that does not depend on the grid; {} is given per \
             element (a generated {} is not)",
            fields::ADHESION_GAMMA_MAP,
            fields::ADHESION_PATTERN
        )));
    }
    let grid = problem.grid;
    let (nx, ny) = grid.shape();
    let odd = |n: usize| n % 2 == 1 && n > 1;
    check_pattern(scene, &grid)?;
    let q_coarse = std::f64::consts::PI / (2.0 * grid.dx());
    let mut file = scene.file.clone();
    let mut coarse_map = None;
    match &scene.file.roughness {
        Some(Roughness::Random { q1, .. }) => {
            let Some(q1) = *q1 else {
                return Err(refuse(format!(
                    "with {kind} = \"random\" needs a band the coarse (2Δx) grid holds: \
                     set {q1_field} ≤ π/(2Δx) = {} (by default q1 = π/Δx follows the grid, \
                     so each grid would sample another surface)",
                    crate::scene::num(q_coarse),
                    kind = fields::ROUGHNESS_KIND,
                    q1_field = fields::ROUGHNESS_Q1
                )));
            };
            if q1 > q_coarse * (1.0 + 1e-9) {
                return Err(refuse(format!(
                    "with {kind} = \"random\": {q1_field} = {} is above π/(2Δx) = {}, \
                     the Nyquist wave of the coarse (2Δx) grid; allowed: q0 < q1 ≤ {}",
                    crate::scene::num(q1),
                    crate::scene::num(q_coarse),
                    crate::scene::num(q_coarse),
                    kind = fields::ROUGHNESS_KIND,
                    q1_field = fields::ROUGHNESS_Q1
                )));
            }
            if odd(nx) || odd(ny) {
                return Err(refuse(format!(
                    "with {kind} = \"random\" needs even grid sides (the coarse grid \
                     keeps the period of the surface); the grid is {nx} × {ny}",
                    kind = fields::ROUGHNESS_KIND
                )));
            }
        }
        Some(Roughness::File { path, dataset }) => {
            let fine = crate::map_file::read_map(
                &scene.base_dir.join(path),
                path,
                dataset.as_deref(),
                &grid,
                (fields::ROUGHNESS_PATH, fields::ROUGHNESS_DATASET),
            )?;
            let map =
                tack_geometry::coarsen_band_limited(&fine, tack_geometry::BAND_LIMIT_TOLERANCE)
                    .map_err(|e| {
                        refuse(format!(
                            "{field} = `{}`: {e}",
                            path.display(),
                            field = fields::ROUGHNESS_PATH
                        ))
                    })?;
            file.roughness = None;
            // The fine map's range, so both runs crop by the same rule.
            let (lo, hi) = fine
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &h| {
                    (lo.min(h), hi.max(h))
                });
            coarse_map = Some((map, (hi - lo).max(0.0)));
        }
        _ => {}
    }
    let periodic = grid.boundary() == tack_geometry::Boundary::Periodic;
    // A periodic strip may be one element wide along y only (as before); nx = 1 is refused.
    if periodic && (nx % 2 == 1 || odd(ny)) {
        return Err(refuse(
            "on a periodic grid needs even grid sides (the coarse grid keeps the period)".into(),
        ));
    }
    // The same path on both grids: a default pull-off path is written out as the fine grid
    // found it (the coarse grid would see the roughness's top at other centres).
    let p = &mut file.protocol;
    if p.indent.is_none() && p.max_approach.is_none() {
        let path = &problem.path;
        p.start = Some(path.start);
        p.max_approach = Some(path.max_approach);
        p.load_step = Some(path.load_step);
        p.unload_step = Some(path.unload_step);
        p.coarse_unload_step = path.coarse_unload_step;
    }
    let half = |n: usize| if n == 1 { 1 } else { n.div_ceil(2) };
    (file.grid.n, file.grid.length) = (None, None);
    file.grid.nx = Some(half(nx));
    file.grid.ny = Some(half(ny));
    file.grid.dx = Some(2.0 * grid.dx());
    let text = toml::to_string(&file).map_err(|e| refuse(e.to_string()))?;
    let coarse = Scene {
        file,
        text: format!("# tack run --richardson: the coarse (2Δx) scene\n{text}"),
        base_dir: scene.base_dir.clone(),
        origin: scene.origin.clone(),
    };
    // A law held in memory is not in the scene: the coarse run takes the fine one's.
    let law = problem.law_in_memory.then_some(&problem.law);
    let built = match &coarse_map {
        Some((map, range)) => Problem::build(
            &coarse,
            Some(&crate::problem::HeightBody {
                heights: map,
                roughness_range: Some(*range),
                radius: None,
                gamma: None,
            }),
            law,
        ),
        None => Problem::build(&coarse, None, law),
    };
    // A limit the fine grid meets may not hold on the coarse one (a smooth law's least range
    // grows with Δx): the message says which grid refused. What only the operator tells (that
    // least range on a periodic grid or a film) is checked by building the coarse solver,
    // before the fine solve.
    built
        .and_then(|coarse| coarse.solver(None).map(|_| coarse))
        .map_err(|e| {
            refuse(format!(
                "runs the scene again on a coarse grid of {} = {}, which refuses it: {e}",
                fields::GRID_DX,
                crate::scene::num(2.0 * grid.dx())
            ))
        })
}

/// The coarse grid must hold the same γ pattern: a period of 2 coarse elements, a correlation
/// length of 4 (where the fine and coarse samples of one field agree to 1e-9), even sides for
/// a random field (its period is kept).
fn check_pattern(scene: &Scene, grid: &tack_geometry::Grid) -> Result<(), SceneError> {
    let refuse = |reason: String| SceneError::Inconsistent(format!("--richardson {reason}"));
    let (nx, ny) = grid.shape();
    let odd = |n: usize| n % 2 == 1 && n > 1;
    let a = &scene.file.adhesion;
    let dx = grid.dx();
    let patterned = a
        .pattern
        .is_some_and(|p| p != crate::scene::PatternKind::Uniform);
    if let Some(period) = a
        .period
        .filter(|&p| patterned && p < 4.0 * dx * (1.0 - 1e-9))
    {
        return Err(refuse(format!(
            "needs a pattern the coarse (2Δx) grid holds: {} = {} is below 4·{} = {}",
            fields::ADHESION_PERIOD,
            crate::scene::num(period),
            fields::GRID_DX,
            crate::scene::num(4.0 * dx)
        )));
    }
    if let Some(l) = a.correlation_length.filter(|&l| patterned && l < 8.0 * dx) {
        return Err(refuse(format!(
            "needs a random γ field the coarse (2Δx) grid samples alike: {} = {} is below 8·{} \
             = {}",
            fields::ADHESION_CORRELATION_LENGTH,
            crate::scene::num(l),
            fields::GRID_DX,
            crate::scene::num(8.0 * dx)
        )));
    }
    if a.pattern == Some(crate::scene::PatternKind::Random) && (odd(nx) || odd(ny)) {
        return Err(refuse(format!(
            "with {} = \"random\" needs even grid sides (the coarse grid keeps the period of \
             the γ field); the grid is {nx} × {ny}",
            fields::ADHESION_PATTERN
        )));
    }
    Ok(())
}
