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

use ndarray::Array2;
use tack_geometry::{Boundary, Grid};

use crate::Error;
use crate::engine::{RunOptions, RunOutcome};
pub use crate::problem::HeightBody;
use crate::problem::Problem;
pub use crate::pull_off_path::{
    COARSE_PER_UNLOAD_STEP, COARSE_UNLOAD_STEP, LOAD_DEPTH, Paraboloid, UNLOAD_STEP,
    UNLOAD_STEP_PER_ELEMENT, fit_paraboloid,
};
use crate::scene::{
    AdhesionModel, AdhesionSpec, BoundaryKind, Geometry, GridSpec, Material, OutputSpec, Protocol,
    SCENE_VERSION, Scene, SceneError, SceneSchema, Snapshots, SolverSpec,
};

/// The former name of [`HeightBody`] (its field `heights` made `Heights { heights }` read
/// twice).
#[deprecated(since = "0.1.0", note = "renamed `HeightBody`")]
pub type Heights<'a> = HeightBody<'a>;

/// The scene's problem with `body.heights` added to its body: validated as
/// [`Problem::from_scene`] validates a scene (the first touch, the path, the crop window are
/// those of the sum), plus the JKR references of `body.radius`.
pub fn problem(scene: &Scene, body: &HeightBody<'_>) -> Result<Problem, SceneError> {
    Problem::build(scene, Some(body))
}

/// Runs the scene with `body.heights` added to its body, in memory, through the run engine
/// ([`crate::engine::execute`]: the pool of [`RunOptions::threads`], progress and cancellation
/// through `observer`). [`RunOptions::richardson`] is refused: the heights are given per
/// element, so the body cannot be coarsened.
pub fn run(
    scene: &Scene,
    body: &HeightBody<'_>,
    options: &RunOptions,
    observer: &mut dyn tack_solver::Observer,
) -> Result<RunOutcome, Error> {
    crate::engine::execute(scene, problem(scene, body)?, options, observer)
}

/// What [`pull_off`] needs besides the heights, and the rule of its default path.
///
/// **The default path.** The body's radius `R` is [`PullOffSpec::radius`], or else that of a
/// least-squares [`Paraboloid`] through the heights when the fit is sphere-like
/// ([`Paraboloid::is_sphere_like`]). With d_s = (Rγ²/E*²)^(1/3) (the JKR approach scale) the
/// path loads in one step to `max_approach = apex + top of the roughness +` [`LOAD_DEPTH`]`·d_s`
/// (the paper's rough-sphere runs: on a smooth sphere this bonds a disc of about 1.6 a_c, deep
/// enough for the JKR pull-off), then retracts by [`COARSE_UNLOAD_STEP`]`·d_s` while the force
/// is compressive and by `min(`[`UNLOAD_STEP`]`, `[`UNLOAD_STEP_PER_ELEMENT`]`·Δx/a_c)·d_s` through
/// the tensile part (a_c the JKR pull-off radius of R), until no element is
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
    /// Retraction step through the tensile part; `None`: the rule's (see above).
    pub unload_step: Option<f64>,
    /// Retraction step while the force is compressive; `None`: [`COARSE_UNLOAD_STEP`]·d_s.
    pub coarse_unload_step: Option<f64>,
    /// Refined retraction (`protocol.refine_pull_off`): coarse steps all the way, the pull-off's
    /// brackets retraced in steps of the unload step.
    pub refine_pull_off: bool,
    /// Pohrt–Popov constant κ; `None`: `tack_solver::KAPPA`.
    pub kappa: Option<f64>,
    /// The adhesion law (`[adhesion]`): the zero-range criterion (default) or a Dugdale
    /// cohesive zone, which approaches from out of contact in retraction steps.
    pub adhesion: AdhesionSpec,
    /// Which steps keep their fields (default: the pull-off step and the last contact).
    pub snapshots: Snapshots,
    /// The work of adhesion per element, the heights' shape (`None`: [`PullOffSpec::gamma`]
    /// everywhere). [`PullOffSpec::gamma`] stays the reference of the path and of F_JKR.
    pub gamma_map: Option<Array2<f64>>,
    /// The elastic body (`[body]`): the half-space (default) or a layer on a rigid base.
    pub body: crate::scene::BodySpec,
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
            refine_pull_off: false,
            kappa: None,
            adhesion: AdhesionSpec::default(),
            snapshots: Snapshots::PullOff,
            gamma_map: None,
            body: crate::scene::BodySpec::default(),
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
    /// The body as [`run`] takes it: `heights` with this plan's radius and roughness range
    /// (and no γ array: see [`PullOffPlan::body_with_gamma`]).
    pub fn body<'a>(&self, heights: &'a Array2<f64>) -> HeightBody<'a> {
        HeightBody {
            heights,
            roughness_range: self.fit.map(|f| f.residual_range()),
            radius: self.radius,
            gamma: None,
        }
    }

    /// [`PullOffPlan::body`] with the work of adhesion `gamma` per element.
    pub fn body_with_gamma<'a>(
        &self,
        heights: &'a Array2<f64>,
        gamma: Option<&'a Array2<f64>>,
    ) -> HeightBody<'a> {
        HeightBody {
            gamma,
            ..self.body(heights)
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
    let first_touch = crate::problem::height_surface(grid, heights)?.min();
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
    let rule = match (radius, fit) {
        (Some(r), Some(f)) => Some(crate::pull_off_path::default_pull_off_path(
            spec.e_star,
            spec.gamma,
            r,
            f.apex + f.residual_max,
            spec.dx,
        )),
        _ => None,
    };
    let d_s = rule.map(|p| p.d_s);
    let max_approach = match (spec.max_approach, rule) {
        (Some(d), _) => d,
        (None, Some(p)) => p.max_approach,
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
    let unload_step = match (spec.unload_step, rule) {
        (Some(s), _) => s,
        (None, Some(p)) => p.unload_step,
        (None, None) => {
            return Err(SceneError::Inconsistent(
                "unload_step is required with max_approach when the body has no radius (give \
                 radius, or the retraction step)"
                    .into(),
            ));
        }
    };
    let coarse_unload_step = match (spec.coarse_unload_step, rule) {
        (Some(s), _) => s,
        (None, Some(p)) => p.coarse_unload_step,
        (None, None) => COARSE_PER_UNLOAD_STEP * unload_step,
    };
    if let (Some(r), Some(f), Boundary::Free) = (radius, fit, spec.boundary) {
        crate::pull_off_path::check_contact_fits(&grid, r, &f, max_approach, first_touch)?;
    }

    // A finite range approaches from out of contact (as a scene's default path does).
    let range = match (spec.adhesion.model, spec.adhesion.sigma0) {
        (AdhesionModel::Dugdale, Some(sigma0)) if sigma0 > 0.0 => Some(spec.gamma / sigma0),
        _ => None,
    };
    let (start, load_step) =
        crate::pull_off_path::load_plan(first_touch, max_approach, unload_step, range);
    let file = SceneSchema {
        adhesion: spec.adhesion.clone(),
        body: spec.body,
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
            start: Some(start),
            max_approach: Some(max_approach),
            load_step: Some(load_step),
            indent: None,
            unload_step: Some(unload_step),
            coarse_unload_step: Some(coarse_unload_step),
            refine_pull_off: spec.refine_pull_off.then_some(true),
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
             {COARSE_UNLOAD_STEP} d_s while compressive, then by min({UNLOAD_STEP}, \
             {UNLOAD_STEP_PER_ELEMENT} dx/a_c) d_s = {unload_step:e}\n"
        ),
        _ => "# no sphere radius: the path was given\n".to_owned(),
    };
    let gamma_note = if spec.gamma_map.is_some() {
        format!(
            "# The work of adhesion is an array given in memory too (stored in the result's \
             /surface/gamma);\n# {} is the reference of the path and of F_JKR.\n",
            tack_fields::MATERIAL_GAMMA
        )
    } else {
        String::new()
    };
    scene.text = format!(
        "# tack::heights::pull_off: the rigid body is a {nx} x {ny} height array given in \
         memory\n# (stored in the result's /surface/heights), not described by this scene \
         (geometry \"none\").\n{gamma_note}{rule}{}",
        scene.text
    );
    Ok(PullOffPlan { scene, radius, fit })
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
    let body = plan.body_with_gamma(heights, spec.gamma_map.as_ref());
    run(&plan.scene, &body, options, observer)
}

#[cfg(test)]
mod tests {
    use super::*;
    use tack_geometry::{Sphere, Surface};

    fn sphere(n: usize, dx: f64, radius: f64) -> Array2<f64> {
        let grid = Grid::square(n, dx, Boundary::Free).unwrap();
        Surface::from_shape(grid, &Sphere::new(radius).unwrap()).into_heights()
    }

    #[test]
    fn a_layer_spec_becomes_the_scene_body_and_its_problem() {
        let heights = sphere(32, 0.45, 8.0);
        let body = crate::scene::BodySpec {
            kind: crate::scene::BodyKind::Layer,
            thickness: Some(2.0),
            poisson: Some(0.4),
            interface: Some(crate::scene::InterfaceKind::Frictionless),
        };
        let spec = PullOffSpec {
            body,
            ..PullOffSpec::new(0.45, 1.0, 0.125)
        };
        let plan = pull_off_scene(&heights, &spec).unwrap();
        assert_eq!(plan.scene.file.body, body);
        assert!(
            plan.scene.text.contains("kind = \"layer\""),
            "{}",
            plan.scene.text
        );
        let layer = problem(&plan.scene, &plan.body(&heights))
            .unwrap()
            .layer
            .unwrap();
        assert_eq!((layer.thickness, layer.poisson), (2.0, 0.4));
        // A bad layer is refused by the scene's checks, naming the field.
        let bad = PullOffSpec {
            body: crate::scene::BodySpec {
                thickness: Some(-1.0),
                ..body
            },
            ..spec
        };
        let e = pull_off_scene(&heights, &bad)
            .and_then(|p| problem(&p.scene, &p.body(&heights)).map(|_| ()))
            .unwrap_err()
            .to_string();
        assert!(e.contains("body.thickness = -1"), "{e}");
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
        assert!((p.max_approach.unwrap() - 1.5).abs() < 1e-12, "{p:?}");
        assert!((p.coarse_unload_step.unwrap() - 0.1).abs() < 1e-12);
        assert!((p.unload_step.unwrap() - 0.01).abs() < 1e-12);
        assert!(plan.scene.text.starts_with("# tack::heights::pull_off"));
        let outcome = run(
            &plan.scene,
            &plan.body(&heights),
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
        let e = run(&plan.scene, &plan.body(&heights), &options, &mut ())
            .unwrap_err()
            .to_string();
        assert!(e.contains("--richardson"), "{e}");
        // The array must have the scene grid's shape.
        let e = problem(
            &plan.scene,
            &HeightBody {
                heights: &Array2::zeros((8, 8)),
                roughness_range: None,
                radius: None,
                gamma: None,
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("heights: the array is 8 × 8"), "{e}");
    }
}
