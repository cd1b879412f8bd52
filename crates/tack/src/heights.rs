//! Runs on a rigid body given as a height array held in memory (a measured map, a surface made
//! by another program; the Python package's `tack.pull_off`), with a default pull-off path.
//!
//! A scene describes its body by shape and roughness, or names a height-map *file*
//! (`roughness.kind = "file"`). Here the heights come as an [`ndarray::Array2`] instead and are
//! added to the scene's own body (normally `geometry.shape = "none"` and no roughness):
//! [`problem`] validates the combination exactly as [`Problem::from_scene`] validates a scene,
//! and [`run`] solves it as [`crate::run()`] does. [`pull_off`] writes the scene itself from a
//! [`PullOffSpec`], with the path of the paper's rough-sphere runs: one load step to
//! [`LOAD_DEPTH`]·d_s below the top of the roughness, then retraction until the contact is lost
//! (the rule is spelled out at [`PullOffSpec`]).
//!
//! Heights follow tack's conventions: shape `(nx, ny)`, element `(i, j)` centred at
//! `((i − ⌊nx/2⌋)Δx, (j − ⌊ny/2⌋)Δx)`, a height is the gap at zero approach (higher = farther
//! from the half-space), the approach is positive when pressing.
//!
//! ```
//! use tack::geometry::{Boundary, Grid, Sphere, Surface};
//! use tack::heights::{PullOffSpec, pull_off};
//!
//! // A smooth sphere R = 8 as a plain array (E* = 1, γ = 0.125: a_c = 3.05, d_s = 0.5).
//! let grid = Grid::square(32, 0.45, Boundary::Free)?;
//! let heights = Surface::from_shape(grid, &Sphere::new(8.0)?).into_heights();
//! let spec = PullOffSpec::new(0.45, 1.0, 0.125);
//! let outcome = pull_off(&heights, &spec, &tack::RunOptions::default(), &mut ())?;
//! // The radius is fitted (R = 8), so the summary has F_JKR and the ratio.
//! let ratio = outcome.pull_off_ratio();
//! assert!((1.0..1.4).contains(&ratio), "{ratio}"); // a_c/Δx ≈ 7: the criterion's +20%
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::time::Instant;

use ndarray::Array2;
use tack_geometry::{Boundary, Grid, Surface};

use crate::problem::{Problem, SPHERE_FIT_MARGIN};
use crate::run::{RunOptions, RunOutcome};
use crate::scene::{
    BoundaryKind, Geometry, GridSpec, Material, OutputSpec, Protocol, SCENE_VERSION, Scene,
    SceneError, SceneFile, Snapshots, SolverSpec,
};
use crate::{Error, provenance};

/// Default load depth of [`pull_off`], in units of d_s = (Rγ²/E*²)^(1/3): the path loads in one
/// step to this many d_s below the top of the roughness (the paper's rough-sphere runs; on a
/// smooth sphere it bonds a disc of about 1.6 a_c).
pub const LOAD_DEPTH: f64 = 3.0;

/// Default coarse retraction step of [`pull_off`] (while the force is compressive), in d_s.
pub const COARSE_UNLOAD_STEP: f64 = 0.2;

/// Default retraction step of [`pull_off`] through the tensile part, in d_s (the quick mode of
/// `cargo xtask reproduce`; the full mode uses 0.01).
pub const UNLOAD_STEP: f64 = 0.02;

/// Coarse retraction step over the fine one when no radius sets the scale.
pub const COARSE_PER_UNLOAD_STEP: f64 = 10.0;

/// A rigid body given as heights in memory, for [`problem`] and [`run`].
#[derive(Debug, Clone, Copy)]
pub struct Heights<'a> {
    /// Heights `(nx, ny)`, added to the scene's own body; the shape must be the scene grid's.
    pub heights: &'a Array2<f64>,
    /// Height range (max − min) of the body's roughness, its deviation from the smooth
    /// macroscopic shape, for the crop rule (`tack_solver::contact_window`); `None`: the range
    /// of the whole array (always safe, but a curved body then leaves little to crop).
    pub roughness_range: Option<f64>,
    /// Radius of the sphere the body approximates: the summary then carries the JKR references
    /// (`f_jkr`, `pull_off_ratio`, `d_jkr`) of that sphere. `None`: no references.
    pub radius: Option<f64>,
}

/// The scene's problem with `heights.heights` added to its body: validated as
/// [`Problem::from_scene`] validates a scene (the first touch, the path, the crop window are
/// those of the sum), plus the JKR references of `heights.radius`.
pub fn problem(scene: &Scene, heights: &Heights<'_>) -> Result<Problem, SceneError> {
    let range = match heights.roughness_range {
        Some(r) if r.is_finite() && r >= 0.0 => r,
        Some(r) => {
            return Err(SceneError::out_of_range(
                "roughness_range",
                r,
                "a finite number ≥ 0",
            ));
        }
        None => {
            let (lo, hi) = min_max(heights.heights.iter().copied());
            (hi - lo).max(0.0)
        }
    };
    let mut problem = Problem::build(scene, Some((heights.heights, range)))?;
    if let Some(r) = heights.radius {
        if !(r.is_finite() && r > 0.0) {
            return Err(SceneError::out_of_range("radius", r, "a finite number > 0"));
        }
        if problem.gamma > 0.0 {
            let (e_star, gamma) = (problem.e_star, problem.gamma);
            problem.references.f_jkr = Some(tack_analytics::jkr_pull_off_force(gamma, r));
            problem.references.d_jkr =
                Some(tack_analytics::jkr_pull_off_approach(e_star, gamma, r));
        }
    }
    Ok(problem)
}

/// Runs the scene with `heights` added to its body, in memory, as [`crate::run()`] runs a scene
/// (progress and cancellation through `observer`). [`RunOptions::richardson`] is refused: the
/// heights are given per element, so the body cannot be coarsened.
pub fn run(
    scene: &Scene,
    heights: &Heights<'_>,
    options: &RunOptions,
    observer: &mut dyn tack_solver::Observer,
) -> Result<RunOutcome, Error> {
    if options.richardson {
        return Err(SceneError::Inconsistent(
            "--richardson needs a geometry that does not depend on the grid; heights given as \
             an array are given per element"
                .into(),
        )
        .into());
    }
    let problem = problem(scene, heights)?;
    let started = Instant::now();
    let path = crate::run::solve(&problem, observer)?;
    let wall_time = started.elapsed();
    let command_line = options
        .command_line
        .clone()
        .unwrap_or_else(provenance::command_line);
    let prov = provenance::provenance(scene, &problem, command_line);
    let result = crate::run::result_file(&problem, &path, prov);
    Ok(RunOutcome {
        problem,
        path,
        wall_time,
        coarse_wall_time: None,
        result,
    })
}

/// The surface of a height array on `grid`; errors name `heights` (shape, a non-finite entry).
pub(crate) fn surface(grid: Grid, heights: &Array2<f64>) -> Result<Surface, SceneError> {
    let (nx, ny) = heights.dim();
    if (nx, ny) != grid.shape() {
        return Err(SceneError::Inconsistent(format!(
            "heights: the array is {nx} × {ny} but the scene's grid is {} × {}; they must agree",
            grid.nx(),
            grid.ny()
        )));
    }
    if let Some(((i, j), h)) = heights.indexed_iter().find(|(_, h)| !h.is_finite()) {
        return Err(SceneError::out_of_range(
            format!("heights[{i}, {j}]"),
            h,
            "a finite number",
        ));
    }
    Ok(Surface::new(grid, heights.clone())?)
}

/// A least-squares paraboloid `h ≈ apex + ((x − x0)² + (y − y0)²)/(2R)` through a height array
/// (tilt and offset included through the vertex), and the residual, the body's roughness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Paraboloid {
    /// Radius of curvature `R` (negative for a body curved towards the half-space).
    pub radius: f64,
    /// Vertex `(x0, y0)` in tack's coordinates.
    pub vertex: (f64, f64),
    /// Height of the vertex.
    pub apex: f64,
    /// Least residual `h − paraboloid` over the array.
    pub residual_min: f64,
    /// Greatest residual `h − paraboloid` over the array: the top of the roughness above the
    /// smooth shape.
    pub residual_max: f64,
}

impl Paraboloid {
    /// Range (max − min) of the residual: the roughness range of the crop rule.
    pub fn residual_range(&self) -> f64 {
        self.residual_max - self.residual_min
    }

    /// Whether the paraboloid describes the body as a sphere with roughness: `R > 0`, and its
    /// rise over the largest disc inside the grid, `(min(Lx, Ly)/2)²/(2R)`, is at least half
    /// the residual range (a flat rough surface fits a paraboloid too, with a rise far below
    /// its roughness).
    pub fn is_sphere_like(&self, grid: &Grid) -> bool {
        let half = 0.5 * grid.lx().min(grid.ly());
        self.radius.is_finite()
            && self.radius > 0.0
            && half * half / (2.0 * self.radius) >= 0.5 * self.residual_range()
    }
}

/// Fits a [`Paraboloid`] to `heights` on elements of size `dx` by least squares; with `radius`
/// given only the vertex and apex are fitted. `None` when the array has fewer than 3 elements
/// along an axis, or the fit is singular or flat (no curvature).
pub fn fit_paraboloid(heights: &Array2<f64>, dx: f64, radius: Option<f64>) -> Option<Paraboloid> {
    let (nx, ny) = heights.dim();
    if nx < 3 || ny < 3 || !(dx.is_finite() && dx > 0.0) {
        return None;
    }
    // Coordinates scaled to about [−1, 1] keep the normal equations well conditioned.
    let scale = 0.5 * dx * nx.max(ny) as f64;
    let uv = |i: usize, j: usize| {
        (
            (i as f64 - (nx / 2) as f64) * dx / scale,
            (j as f64 - (ny / 2) as f64) * dx / scale,
        )
    };
    // h ≈ c0 + c1 u + c2 v + c3 (u² + v²); with a given radius c3 = scale²/(2R) is fixed.
    let fixed_c3 = match radius {
        Some(r) if r.is_finite() && r != 0.0 => Some(scale * scale / (2.0 * r)),
        Some(_) => return None,
        None => None,
    };
    let m = if fixed_c3.is_some() { 3 } else { 4 };
    let mut ata = [[0.0_f64; 4]; 4];
    let mut atb = [0.0_f64; 4];
    for ((i, j), &h) in heights.indexed_iter() {
        let (u, v) = uv(i, j);
        let r2 = u * u + v * v;
        let row = [1.0, u, v, r2];
        let target = h - fixed_c3.map_or(0.0, |c3| c3 * r2);
        for a in 0..m {
            atb[a] += row[a] * target;
            for b in 0..m {
                ata[a][b] += row[a] * row[b];
            }
        }
    }
    let c = solve_small(ata, atb, m)?;
    let c3 = fixed_c3.unwrap_or(c[3]);
    if c3 == 0.0 || !c3.is_finite() {
        return None;
    }
    let (u0, v0) = (-c[1] / (2.0 * c3), -c[2] / (2.0 * c3));
    let apex = c[0] - (c[1] * c[1] + c[2] * c[2]) / (4.0 * c3);
    let (residual_min, residual_max) = min_max(heights.indexed_iter().map(|((i, j), &h)| {
        let (u, v) = uv(i, j);
        h - (c[0] + c[1] * u + c[2] * v + c3 * (u * u + v * v))
    }));
    Some(Paraboloid {
        radius: radius.unwrap_or(scale * scale / (2.0 * c3)),
        vertex: (u0 * scale, v0 * scale),
        apex,
        residual_min,
        residual_max,
    })
}

/// Solves the leading `m × m` block of `a x = b` by Gaussian elimination with partial pivoting;
/// `None` when singular.
fn solve_small(mut a: [[f64; 4]; 4], mut b: [f64; 4], m: usize) -> Option<[f64; 4]> {
    let norm = a.iter().flatten().fold(0.0_f64, |s, v| s.max(v.abs()));
    for col in 0..m {
        let pivot = (col..m).max_by(|&p, &q| a[p][col].abs().total_cmp(&a[q][col].abs()))?;
        if a[pivot][col].is_nan() || a[pivot][col].abs() <= 1e-12 * norm {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..m {
            let f = a[row][col] / a[col][col];
            let pivot_row = a[col];
            for (value, p) in a[row][col..m].iter_mut().zip(&pivot_row[col..m]) {
                *value -= f * p;
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = [0.0; 4];
    for row in (0..m).rev() {
        let s: f64 = (row + 1..m).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - s) / a[row][row];
    }
    Some(x)
}

fn min_max(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}

/// What [`pull_off`] needs besides the heights, and the rule of its default path.
///
/// **The default path.** The body's radius `R` is [`PullOffSpec::radius`], or else that of a
/// least-squares [`Paraboloid`] through the heights when the fit is sphere-like
/// ([`Paraboloid::is_sphere_like`]). With d_s = (Rγ²/E*²)^(1/3) (the JKR approach scale) the
/// path loads in one step to `max_approach = apex + top of the roughness +` [`LOAD_DEPTH`]`·d_s`
/// (the paper's rough-sphere runs: on a smooth sphere this bonds a disc of about 1.6 a_c, deep
/// enough for the JKR pull-off), then retracts by [`COARSE_UNLOAD_STEP`]`·d_s` while the force
/// is compressive and by [`UNLOAD_STEP`]`·d_s` through the tensile part, until no element is
/// bonded. The summary gets the JKR references of `R`. On a free grid the Hertz contact radius
/// `sqrt(R·d)` at that depth (from the first touch) plus 30% must fit inside the array around
/// the vertex. Each of `max_approach`, `unload_step`, `coarse_unload_step` can be given
/// instead; a body with no radius (flat, wavy, a strip) needs `max_approach` and `unload_step`
/// (the coarse step is then [`COARSE_PER_UNLOAD_STEP`] times the fine one).
#[derive(Debug, Clone, PartialEq)]
pub struct PullOffSpec {
    /// Element size Δx (> 0).
    pub dx: f64,
    /// Free (non-periodic half-space, default) or periodic.
    pub boundary: Boundary,
    /// Effective modulus E* (> 0).
    pub e_star: f64,
    /// Work of adhesion γ (> 0).
    pub gamma: f64,
    /// Radius of the sphere the body approximates; `None`: fitted.
    pub radius: Option<f64>,
    /// Deepest approach; `None`: the default rule.
    pub max_approach: Option<f64>,
    /// Retraction step through the tensile part; `None`: [`UNLOAD_STEP`]·d_s.
    pub unload_step: Option<f64>,
    /// Retraction step while the force is compressive; `None`: [`COARSE_UNLOAD_STEP`]·d_s.
    pub coarse_unload_step: Option<f64>,
    /// Pohrt–Popov constant κ; `None`: `tack_solver::KAPPA`.
    pub kappa: Option<f64>,
    /// Which steps keep their fields (default: the pull-off step and the last contact).
    pub snapshots: Snapshots,
}

impl PullOffSpec {
    /// A free grid of element size `dx`, material `e_star`, `gamma`, everything else default.
    pub fn new(dx: f64, e_star: f64, gamma: f64) -> Self {
        Self {
            dx,
            boundary: Boundary::Free,
            e_star,
            gamma,
            radius: None,
            max_approach: None,
            unload_step: None,
            coarse_unload_step: None,
            kappa: None,
            snapshots: Snapshots::PullOff,
        }
    }
}

/// The scene [`pull_off`] runs, and what it was derived from.
#[derive(Debug, Clone)]
pub struct PullOffPlan {
    /// The scene: material, grid of the array's shape, the path, `geometry.shape = "none"`
    /// (the body is the array), the rule's numbers in a comment on top.
    pub scene: Scene,
    /// The radius used for the path and the references: given, or fitted.
    pub radius: Option<f64>,
    /// The paraboloid through the heights (with the given radius, if any).
    pub fit: Option<Paraboloid>,
}

impl PullOffPlan {
    /// The heights as [`run`] takes them, with this plan's radius and roughness range.
    pub fn heights<'a>(&self, heights: &'a Array2<f64>) -> Heights<'a> {
        Heights {
            heights,
            roughness_range: self.fit.map(|f| f.residual_range()),
            radius: self.radius,
        }
    }
}

/// The scene of a pull-off of `heights` by the rule of [`PullOffSpec`].
pub fn pull_off_scene(
    heights: &Array2<f64>,
    spec: &PullOffSpec,
) -> Result<PullOffPlan, SceneError> {
    let (nx, ny) = heights.dim();
    let grid = Grid::new(nx, ny, spec.dx, spec.boundary)?;
    // Shape and finiteness first: everything below reads the heights.
    let first_touch = surface(grid, heights)?.min();
    if !(spec.e_star.is_finite() && spec.e_star > 0.0) {
        return Err(tack_kernels::KernelError::Modulus(spec.e_star).into());
    }
    if !(spec.gamma.is_finite() && spec.gamma > 0.0) {
        return Err(SceneError::out_of_range(
            "gamma",
            spec.gamma,
            "a finite number > 0 (a pull-off needs adhesion; without it use the \
             non-adhesive tack_solver::ContactSolver)",
        ));
    }
    let positive = |field: &str, v: Option<f64>| match v {
        Some(x) if !(x.is_finite() && x > 0.0) => {
            Err(SceneError::out_of_range(field, x, "a finite number > 0"))
        }
        _ => Ok(()),
    };
    positive("radius", spec.radius)?;
    positive("unload_step", spec.unload_step)?;
    positive("coarse_unload_step", spec.coarse_unload_step)?;
    if let Some(d) = spec.max_approach
        && !d.is_finite()
    {
        return Err(SceneError::out_of_range(
            "max_approach",
            d,
            "a finite number",
        ));
    }

    let fit = fit_paraboloid(heights, spec.dx, spec.radius);
    let (radius, how) = match (spec.radius, fit) {
        (Some(r), _) => (Some(r), "given"),
        (None, Some(f)) if f.is_sphere_like(&grid) => (Some(f.radius), "fitted"),
        _ => (None, "none"),
    };
    let d_s = radius.map(|r| tack_analytics::jkr_approach_scale(spec.e_star, spec.gamma, r));
    let max_approach = match (spec.max_approach, d_s, fit) {
        (Some(d), _, _) => d,
        (None, Some(d_s), Some(f)) => f.apex + f.residual_max + LOAD_DEPTH * d_s,
        _ => {
            let why = match fit {
                None => "no paraboloid fits the array (fewer than 3 elements along an axis, or \
                         no curvature)"
                    .to_owned(),
                Some(f) => format!(
                    "the least-squares paraboloid has R = {:.4e}, which does not describe a \
                     sphere with roughness (R must be > 0 and its rise over the grid at least \
                     half the roughness range {:.4e})",
                    f.radius,
                    f.residual_range()
                ),
            };
            return Err(SceneError::Inconsistent(format!(
                "max_approach is required: the default pull-off path needs the radius R of the \
                 body, and {why}; give max_approach and unload_step, or radius"
            )));
        }
    };
    let unload_step = match (spec.unload_step, d_s) {
        (Some(s), _) => s,
        (None, Some(d_s)) => UNLOAD_STEP * d_s,
        (None, None) => {
            return Err(SceneError::Inconsistent(
                "unload_step is required with max_approach when the body has no radius (give \
                 radius, or the retraction step)"
                    .into(),
            ));
        }
    };
    let coarse_unload_step = match (spec.coarse_unload_step, d_s) {
        (Some(s), _) => s,
        (None, Some(d_s)) => COARSE_UNLOAD_STEP * d_s,
        (None, None) => COARSE_PER_UNLOAD_STEP * unload_step,
    };
    if let (Some(r), Some(f), Boundary::Free) = (radius, fit, spec.boundary) {
        check_contact_fits(&grid, r, &f, max_approach, first_touch)?;
    }

    let file = SceneFile {
        version: SCENE_VERSION,
        material: Material {
            e_star: spec.e_star,
            gamma: spec.gamma,
        },
        geometry: Geometry::None,
        roughness: None,
        grid: GridSpec {
            n: None,
            nx: Some(nx),
            ny: Some(ny),
            dx: Some(spec.dx),
            length: None,
            boundary: match spec.boundary {
                Boundary::Free => BoundaryKind::Free,
                Boundary::Periodic => BoundaryKind::Periodic,
            },
            crop: true,
        },
        solver: SolverSpec {
            kappa: spec.kappa,
            ..SolverSpec::default()
        },
        protocol: Protocol {
            start: Some(max_approach),
            max_approach,
            load_step: (max_approach - first_touch).max(unload_step),
            unload_step: Some(unload_step),
            coarse_unload_step: Some(coarse_unload_step),
            retract_to: None,
            max_steps: None,
        },
        output: OutputSpec {
            snapshots: spec.snapshots.clone(),
            surface: true,
        },
    };
    let mut scene = Scene::from_file(file, ".")?;
    let rule = match (radius, d_s) {
        (Some(r), Some(d_s)) => format!(
            "# sphere radius R = {r:e} ({how}), d_s = (R gamma^2/E*^2)^(1/3) = {d_s:e}; default \
             path: one load step to apex + top of the roughness + {LOAD_DEPTH} d_s, retraction by \
             {COARSE_UNLOAD_STEP} d_s while compressive, then by {UNLOAD_STEP} d_s\n"
        ),
        _ => "# no sphere radius: the path was given\n".to_owned(),
    };
    scene.text = format!(
        "# tack::heights::pull_off: the rigid body is a {nx} x {ny} height array given in \
         memory\n# (stored in the result's /surface/heights), not described by this scene \
         (geometry \"none\").\n{rule}{}",
        scene.text
    );
    Ok(PullOffPlan { scene, radius, fit })
}

/// On a free grid the loaded contact (Hertz radius at the deepest approach, with the 30%
/// margin of the scene check) must lie inside the array around the paraboloid's vertex.
fn check_contact_fits(
    grid: &Grid,
    radius: f64,
    fit: &Paraboloid,
    max_approach: f64,
    first_touch: f64,
) -> Result<(), SceneError> {
    let depth = (max_approach - first_touch).max(0.0);
    let hertz = (radius * depth).sqrt();
    let needed = SPHERE_FIT_MARGIN * hertz;
    let dx = grid.dx();
    let (x0, y0) = fit.vertex;
    let (x_lo, x_hi) = (grid.x(0) - 0.5 * dx, grid.x(grid.nx() - 1) + 0.5 * dx);
    let (y_lo, y_hi) = (grid.y(0) - 0.5 * dx, grid.y(grid.ny() - 1) + 0.5 * dx);
    let room = (x0 - x_lo).min(x_hi - x0).min(y0 - y_lo).min(y_hi - y0);
    if needed > room {
        return Err(SceneError::Inconsistent(format!(
            "heights: the {} × {} array at dx = {dx} is too small for the pull-off: at \
             max_approach = {max_approach:.6e} the Hertz contact radius sqrt(R·d) = {hertz:.4e} \
             (R = {radius:.4e}, d = {depth:.4e} from the first touch) plus a 30% margin reaches \
             {needed:.4e} from the vertex at ({x0:.4e}, {y0:.4e}), but the array's edge is \
             {room:.4e} away; use a larger array or a smaller max_approach",
            grid.nx(),
            grid.ny()
        )));
    }
    Ok(())
}

/// The pull-off of a body given as `heights` by the rule of [`PullOffSpec`]: the scene of
/// [`pull_off_scene`] run by [`run`]. The result file stores the heights (`/surface/heights`)
/// and the scene text with the rule's numbers.
pub fn pull_off(
    heights: &Array2<f64>,
    spec: &PullOffSpec,
    options: &RunOptions,
    observer: &mut dyn tack_solver::Observer,
) -> Result<RunOutcome, Error> {
    let plan = pull_off_scene(heights, spec)?;
    run(&plan.scene, &plan.heights(heights), options, observer)
}

#[cfg(test)]
mod tests {
    use super::*;
    use tack_geometry::{RoughSpec, Sphere, rough_surface};

    fn sphere(n: usize, dx: f64, radius: f64) -> Array2<f64> {
        let grid = Grid::square(n, dx, Boundary::Free).unwrap();
        Surface::from_shape(grid, &Sphere::new(radius).unwrap()).into_heights()
    }

    #[test]
    fn the_fit_recovers_an_offset_paraboloid() {
        let (nx, ny, dx) = (40, 30, 0.1);
        let grid = Grid::new(nx, ny, dx, Boundary::Free).unwrap();
        let h = Array2::from_shape_fn((nx, ny), |(i, j)| {
            let (x, y) = (grid.x(i) - 0.7, grid.y(j) + 0.4);
            3.0 + (x * x + y * y) / (2.0 * 5.0)
        });
        for radius in [None, Some(5.0)] {
            let f = fit_paraboloid(&h, dx, radius).unwrap();
            assert!((f.radius - 5.0).abs() < 1e-9, "{f:?}");
            assert!((f.vertex.0 - 0.7).abs() < 1e-9 && (f.vertex.1 + 0.4).abs() < 1e-9);
            assert!((f.apex - 3.0).abs() < 1e-9);
            assert!(f.residual_range() < 1e-9);
            assert!(f.is_sphere_like(&grid));
        }
        // A strip has no paraboloid; a flat rough surface is not sphere-like.
        assert!(fit_paraboloid(&Array2::zeros((64, 1)), dx, None).is_none());
        let grid = Grid::square(64, dx, Boundary::Free).unwrap();
        let rough = rough_surface(grid, &RoughSpec::paper_defaults(grid, 0.01, 0.5, 3)).unwrap();
        let f = fit_paraboloid(rough.heights(), dx, None);
        assert!(f.is_none_or(|f| !f.is_sphere_like(&grid)), "{f:?}");
    }

    #[test]
    fn a_sphere_given_as_heights_runs_like_the_sphere_scene() {
        let (n, dx, radius) = (32, 0.45, 8.0);
        let heights = sphere(n, dx, radius);
        let spec = PullOffSpec::new(dx, 1.0, 0.125);
        let plan = pull_off_scene(&heights, &spec).unwrap();
        let fitted = plan.radius.unwrap();
        assert!((fitted / radius - 1.0).abs() < 1e-12, "{fitted}");
        // d_s = (8 · 0.125²)^(1/3) = 0.5: load to 3 d_s, retract by 0.1, then by 0.01.
        let p = plan.scene.file.protocol;
        assert!((p.max_approach - 1.5).abs() < 1e-12, "{p:?}");
        assert!((p.coarse_unload_step.unwrap() - 0.1).abs() < 1e-12);
        assert!((p.unload_step.unwrap() - 0.01).abs() < 1e-12);
        assert!(plan.scene.text.starts_with("# tack::heights::pull_off"));
        let outcome = run(
            &plan.scene,
            &plan.heights(&heights),
            &RunOptions::default(),
            &mut (),
        )
        .unwrap();

        // The same path on the sphere scene gives the same curve.
        let mut file = plan.scene.file.clone();
        file.geometry = Geometry::Sphere { radius };
        let scene = Scene::from_file(file, ".").unwrap();
        let reference = crate::run(&scene, &RunOptions::default(), &mut ()).unwrap();
        let (a, b) = (&outcome.result.curve.force, &reference.result.curve.force);
        assert_eq!(a.len(), b.len());
        for (x, y) in a.iter().zip(b) {
            assert!((x - y).abs() <= 1e-9 * y.abs().max(1e-3), "{x} vs {y}");
        }
        let (s, r) = (&outcome.result.summary, &reference.result.summary);
        assert!((s.f_jkr / r.f_jkr - 1.0).abs() < 1e-12);
        assert!((s.pull_off_ratio / r.pull_off_ratio - 1.0).abs() < 1e-9);
        assert!(
            (1.0..1.4).contains(&s.pull_off_ratio),
            "{}",
            s.pull_off_ratio
        );
        // The body is in the result, the pull-off and last-contact fields too.
        assert_eq!(outcome.result.surface.as_ref().unwrap().0, heights);
        assert_eq!(outcome.result.snapshots.len(), 2);
    }

    #[test]
    fn bad_inputs_name_the_field() {
        let heights = sphere(32, 0.45, 8.0);
        let err =
            |spec: &PullOffSpec, h: &Array2<f64>| pull_off_scene(h, spec).unwrap_err().to_string();
        let spec = PullOffSpec::new(0.45, 1.0, 0.125);
        let mut nan = heights.clone();
        nan[[1, 2]] = f64::NAN;
        assert!(err(&spec, &nan).starts_with("heights[1, 2] = NaN is invalid"));
        let e = err(&PullOffSpec::new(0.45, 1.0, 0.0), &heights);
        assert!(e.starts_with("gamma = 0 is invalid"), "{e}");
        let e = err(&PullOffSpec::new(-1.0, 1.0, 0.1), &heights);
        assert!(e.contains("grid.dx = -1"), "{e}");
        let e = err(
            &PullOffSpec {
                unload_step: Some(-0.1),
                ..spec.clone()
            },
            &heights,
        );
        assert!(e.starts_with("unload_step = -0.1 is invalid"), "{e}");
        // A flat body has no radius: the path must be given.
        let flat = Array2::zeros((16, 16));
        let e = err(&spec, &flat);
        assert!(e.starts_with("max_approach is required"), "{e}");
        let e = err(
            &PullOffSpec {
                max_approach: Some(0.1),
                ..spec.clone()
            },
            &flat,
        );
        assert!(e.starts_with("unload_step is required"), "{e}");
        // Too deep for the array.
        let e = err(
            &PullOffSpec {
                max_approach: Some(5.0),
                ..spec.clone()
            },
            &heights,
        );
        assert!(e.contains("too small for the pull-off"), "{e}");
        // Richardson needs a grid-independent body.
        let plan = pull_off_scene(&heights, &spec).unwrap();
        let options = RunOptions {
            richardson: true,
            ..RunOptions::default()
        };
        let e = run(&plan.scene, &plan.heights(&heights), &options, &mut ())
            .unwrap_err()
            .to_string();
        assert!(e.contains("--richardson"), "{e}");
        // The array must have the scene grid's shape.
        let e = problem(
            &plan.scene,
            &Heights {
                heights: &Array2::zeros((8, 8)),
                roughness_range: None,
                radius: None,
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("heights: the array is 8 × 8"), "{e}");
    }
}
