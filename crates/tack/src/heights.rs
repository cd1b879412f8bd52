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
    AdhesionSpec, BoundaryKind, Geometry, GridSpec, Material, OutputSpec, Protocol, SCENE_VERSION,
    Scene, SceneError, SceneSchema, Snapshots, SolverSpec,
};

/// The scene's problem with `body.heights` added to its body: validated as
/// [`Problem::from_scene`] validates a scene (the first touch, the path, the crop window are
/// those of the sum), plus the JKR references of `body.radius`.
pub fn problem(scene: &Scene, body: &HeightBody<'_>) -> Result<Problem, SceneError> {
    Problem::build(scene, Some(body), None)
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
/// bonded. The summary gets the JKR references of `R`. On a free grid the contact must fit the
/// array: the Hertz radius `sqrt(R·d)` at that depth (from the first touch) plus 30% around the
/// vertex (the scenes' rule, applied by the problem builder), and every element the one-step
/// load penetrates must keep off the array's edge (the arrays' own rule: a scene is only
/// warned of such elements). Each of `max_approach`, `unload_step`, `coarse_unload_step` can
/// be given instead; a body with no radius (flat, wavy, a strip) needs `max_approach` and `unload_step`
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
    /// The adhesion law (`[adhesion]`): the zero-range criterion (default), a Dugdale
    /// cohesive zone or a smooth law; a finite-range law approaches from out of its reach in
    /// steps (`crate::pull_off_path::load_plan`).
    pub adhesion: AdhesionSpec,
    /// Which steps keep their fields (default: the pull-off step and the last contact).
    pub snapshots: Snapshots,
    /// The work of adhesion per element, the heights' shape (`None`: [`PullOffSpec::gamma`]
    /// everywhere). [`PullOffSpec::gamma`] stays the reference of the path and of F_JKR.
    pub gamma_map: Option<Array2<f64>>,
    /// The elastic body (`[body]`): the half-space (default) or a layer on a rigid base.
    pub body: crate::scene::BodySpec,
    /// The load's step (`protocol.load_step`); `None`: the rule's (one step to the deepest
    /// approach, from out of a finite-range law's reach). A path in time needs it.
    pub load_step: Option<f64>,
    /// A viscoelastic solid and its path's rates (`material.prony`, `protocol.speed`, …);
    /// `None`: the elastic solid `e_star`.
    pub viscoelastic: Option<ViscoelasticSpec>,
}

/// A viscoelastic half-space for [`pull_off`]: `e_star` is its relaxed modulus E0, and the
/// path runs in time (docs/theory.md §3.10). It needs [`PullOffSpec::max_approach`] and
/// [`PullOffSpec::load_step`], and a finite-range law.
#[derive(Debug, Clone, PartialEq)]
pub struct ViscoelasticSpec {
    /// The Prony arms `[E_k, τ_k]` (`material.prony`).
    pub prony: Vec<[f64; 2]>,
    /// The approach rate of the loading, and of the retraction unless `unload_speed`
    /// (`protocol.speed`).
    pub speed: f64,
    /// The approach rate of the retraction (`protocol.unload_speed`); `None`: `speed`.
    pub unload_speed: Option<f64>,
    /// The time held at the deepest approach (`protocol.dwell`); `None`: no hold.
    pub dwell: Option<f64>,
    /// The hold's time steps (`protocol.dwell_steps`); `None`: the default, 20.
    pub dwell_steps: Option<usize>,
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
            load_step: None,
            viscoelastic: None,
        }
    }
}

/// The scene [`pull_off`] runs, and what it was derived from.
#[derive(Debug, Clone)]
pub struct PullOffPlan {
    /// The scene: material, grid of the array's shape, `geometry.shape = "none"` (the body
    /// is the array), the path's fields as given (the builder completes them by the rule).
    pub scene: Scene,
    /// The radius of the path and the references: given, or fitted.
    pub radius: Option<f64>,
    /// The radius as given ([`PullOffSpec::radius`]).
    pub given_radius: Option<f64>,
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
            // A fitted radius is found again by the default path's rule (and reported as
            // fitted); a path given in full (`load_step`) has no rule, so the fitted radius
            // comes along for the references (F_JKR and the ratios).
            radius: if self.scene.file.protocol.load_step.is_some() {
                self.radius
            } else {
                self.given_radius
            },
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

/// The scene of a pull-off of `heights` by the rule of [`PullOffSpec`]: the material, a grid
/// of the array's shape, `geometry.shape = "none"` (the body is the array) and a `[protocol]`
/// without `load_step` unless the spec gives one, so [`Problem`]'s builder sets the default
/// pull-off path (the rule of [`crate::pull_off_path`], the same for scenes and arrays) from
/// the given or fitted radius; a `load_step` gives the path in full.
/// Errors name the scene fields the spec's values go to (`material.gamma`,
/// `protocol.unload_step`, …) and `radius`.
pub fn pull_off_scene(
    heights: &Array2<f64>,
    spec: &PullOffSpec,
) -> Result<PullOffPlan, SceneError> {
    let (nx, ny) = heights.dim();
    let grid = Grid::new(nx, ny, spec.dx, spec.boundary)?;
    // Shape and finiteness first: everything below reads the heights.
    crate::problem::height_surface(grid, heights)?;
    crate::problem::check_material(spec.e_star, spec.gamma, false)?;
    let positive = |field: &str, v: Option<f64>| match v {
        Some(x) if !(x.is_finite() && x > 0.0) => {
            Err(SceneError::out_of_range(field, x, "a finite number > 0"))
        }
        _ => Ok(()),
    };
    positive("radius", spec.radius)?;
    positive(tack_fields::PROTOCOL_UNLOAD_STEP, spec.unload_step)?;
    positive(tack_fields::PROTOCOL_LOAD_STEP, spec.load_step)?;
    positive(
        tack_fields::PROTOCOL_COARSE_UNLOAD_STEP,
        spec.coarse_unload_step,
    )?;
    if let Some(d) = spec.max_approach
        && !d.is_finite()
    {
        return Err(SceneError::out_of_range(
            tack_fields::PROTOCOL_MAX_APPROACH,
            d,
            "a finite number",
        ));
    }
    let fit = fit_paraboloid(heights, spec.dx, spec.radius);
    let radius = match (spec.radius, fit) {
        (Some(r), _) => Some(r),
        (None, Some(f)) if f.is_sphere_like(&grid) => Some(f.radius),
        _ => None,
    };
    let file = SceneSchema {
        adhesion: spec.adhesion.clone(),
        body: spec.body,
        version: SCENE_VERSION,
        material: Material {
            e_star: spec.e_star,
            gamma: spec.gamma,
            prony: spec.viscoelastic.as_ref().map(|v| v.prony.clone()),
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
            start: None,
            max_approach: spec.max_approach,
            load_step: spec.load_step,
            indent: None,
            unload_step: spec.unload_step,
            coarse_unload_step: spec.coarse_unload_step,
            refine_pull_off: spec.refine_pull_off.then_some(true),
            retract_to: None,
            max_steps: None,
            speed: spec.viscoelastic.as_ref().map(|v| v.speed),
            unload_speed: spec.viscoelastic.as_ref().and_then(|v| v.unload_speed),
            dwell: spec.viscoelastic.as_ref().and_then(|v| v.dwell),
            dwell_steps: spec.viscoelastic.as_ref().and_then(|v| v.dwell_steps),
        },
        output: OutputSpec {
            snapshots: spec.snapshots.clone(),
            surface: true,
        },
    };
    let mut scene = Scene::from_file(file, ".")?;
    let gamma_note = if spec.gamma_map.is_some() {
        format!(
            "# The work of adhesion is an array given in memory too (stored in the result's \
             /surface/gamma);\n# {} is the reference of the path and of F_JKR.\n",
            tack_fields::MATERIAL_GAMMA
        )
    } else {
        String::new()
    };
    let radius_note = match (spec.radius, radius) {
        (Some(r), _) => format!(
            "# The body's radius was given: R = {}.\n",
            tack_fields::num(r)
        ),
        (None, Some(r)) => format!(
            "# The body's radius is fitted (least-squares paraboloid): R = {}.\n",
            tack_fields::num(r)
        ),
        (None, None) => String::new(),
    };
    scene.text = format!(
        "# tack::heights::pull_off: the rigid body is a {nx} x {ny} height array given in \
         memory\n# (stored in the result's /surface/heights), not described by this scene \
         (geometry \"none\").\n{gamma_note}{radius_note}{}",
        scene.text
    );
    Ok(PullOffPlan {
        scene,
        radius,
        given_radius: spec.radius,
        fit,
    })
}

/// The pull-off of a body given as `heights` by the rule of [`PullOffSpec`]: the scene of
/// [`pull_off_scene`] run by [`run`]. The result file stores the heights (`/surface/heights`)
/// and the scene text, with the default path's numbers in a comment on top.
pub fn pull_off(
    heights: &Array2<f64>,
    spec: &PullOffSpec,
    options: &RunOptions,
    observer: &mut dyn tack_solver::Observer,
) -> Result<RunOutcome, Error> {
    let mut plan = pull_off_scene(heights, spec)?;
    let body = plan.body_with_gamma(heights, spec.gamma_map.as_ref());
    let problem = problem(&plan.scene, &body)?;
    if let Some(rule) = &problem.path_rule {
        plan.scene.text = format!("# {rule}\n{}", plan.scene.text);
    }
    crate::engine::execute(&plan.scene, problem, options, observer)
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
    fn a_viscoelastic_spec_becomes_the_scene_material_and_rates() {
        let heights = sphere(16, 0.075, 1.0);
        let spec = PullOffSpec {
            max_approach: Some(0.02),
            load_step: Some(0.002),
            adhesion: AdhesionSpec {
                model: crate::AdhesionModel::from_name("exponential").unwrap(),
                range: Some(0.01),
                ..AdhesionSpec::default()
            },
            viscoelastic: Some(ViscoelasticSpec {
                prony: vec![[9.0, 1.0]],
                speed: 1e-3,
                unload_speed: Some(1e-2),
                dwell: Some(1.0),
                dwell_steps: Some(4),
            }),
            ..PullOffSpec::new(0.075, 1.0, 1e-3)
        };
        let plan = pull_off_scene(&heights, &spec).unwrap();
        assert_eq!(plan.scene.file.material.prony, Some(vec![[9.0, 1.0]]));
        let p = &plan.scene.file.protocol;
        assert_eq!(
            (p.speed, p.unload_speed, p.dwell, p.dwell_steps, p.load_step),
            (Some(1e-3), Some(1e-2), Some(1.0), Some(4), Some(0.002))
        );
        let built = problem(&plan.scene, &plan.body(&heights)).unwrap();
        let (prony, rates) = built.viscoelastic.as_ref().unwrap();
        assert_eq!((prony.instantaneous(), rates.dwell_steps), (10.0, 4));
        // The path is given in full, and the fitted radius still gives F_JKR.
        let f_jkr = built.references.f_jkr.unwrap();
        assert!((f_jkr / (-1.5 * std::f64::consts::PI * 1e-3) - 1.0).abs() < 1e-9);
        // Without the load step the path has no time: refused, naming the field.
        let bad = PullOffSpec {
            load_step: None,
            ..spec
        };
        let e = pull_off_scene(&heights, &bad)
            .and_then(|p| problem(&p.scene, &p.body(&heights)).map(|_| ()))
            .unwrap_err()
            .to_string();
        assert!(e.contains("protocol.load_step"), "{e}");
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
        // d_s = (8 · 0.125²)^(1/3) = 0.5: load to 3 d_s, retract by 0.1, then by 0.01 (the
        // builder's default path, the scene's rule).
        let built = problem(&plan.scene, &plan.body(&heights)).unwrap();
        let rule = built.path_rule.unwrap();
        assert!(
            rule.fitted && (rule.radius / radius - 1.0).abs() < 1e-12,
            "{rule:?}"
        );
        let p = built.path;
        assert!((p.max_approach - 1.5).abs() < 1e-12, "{p:?}");
        assert!((p.coarse_unload_step.unwrap() - 0.1).abs() < 1e-12);
        assert!((p.unload_step - 0.01).abs() < 1e-12);
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
        // The two differ in the heights' round-off, so their CG solves stop at other iterates
        // within the tolerance (1e-10 of the displacement scale): forces agree to 1.1e-9 of the
        // path's largest (measured), checked at 1e-8; another contact set would differ by 1e-3.
        let largest = b.iter().fold(0.0f64, |m, f| m.max(f.abs()));
        for (x, y) in a.iter().zip(b) {
            assert!(
                (x - y).abs() <= 1e-8 * largest,
                "{x} vs {y} (largest {largest})"
            );
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
    fn the_array_check_holds_the_disc_the_one_step_load_bonds() {
        // R = 8, E* = 1, γ = 0.125: the default path loads in one step to d = 3 d_s = 1.5,
        // bonding the penetrated disc √(2Rd) = 4.90; Hertz with the 30% margin says 4.50.
        let (dx, spec) = (0.3, PullOffSpec::new(0.3, 1.0, 0.125));
        // 32 elements (half width 4.8) passed the old Hertz check and then ran into the edge.
        let small = sphere(32, dx, 8.0);
        let e = pull_off_scene(&small, &spec)
            .and_then(|plan| problem(&plan.scene, &plan.body(&small)).map(|_| ()))
            .unwrap_err()
            .to_string();
        assert!(e.contains("bonds every element the body penetrates"), "{e}");
        assert!(e.contains("too small for the pull-off"), "{e}");
        // An array whose edge the penetrated disc misses runs without touching the edge.
        let n = 2 * ((2.0f64 * 8.0 * 1.5).sqrt() / dx).ceil() as usize + 2;
        let fits = sphere(n, dx, 8.0);
        let outcome = pull_off(&fits, &spec, &RunOptions::default(), &mut ()).unwrap();
        let warnings = &outcome.result.summary.warnings;
        assert!(!warnings.iter().any(|w| w.contains("edge")), "{warnings:?}");
        // The scene text carries the path the builder set.
        assert!(
            outcome.result.provenance.scene.contains("# default pull-off path of R = 8 (fitted), d_s = 0.5: one load step to d = 1.5, retraction by 0.1 while compressive, then by 0.009847"),
            "{}",
            outcome.result.provenance.scene
        );
    }

    #[test]
    fn bad_inputs_name_the_field() {
        let heights = sphere(32, 0.45, 8.0);
        // Errors of the spec and of the builder's default path, as a run meets them.
        let err = |spec: &PullOffSpec, h: &Array2<f64>| {
            pull_off_scene(h, spec)
                .and_then(|plan| problem(&plan.scene, &plan.body(h)).map(|_| ()))
                .unwrap_err()
                .to_string()
        };
        let spec = PullOffSpec::new(0.45, 1.0, 0.125);
        let mut nan = heights.clone();
        nan[[1, 2]] = f64::NAN;
        assert!(err(&spec, &nan).starts_with("heights[1, 2] = NaN is invalid"));
        let e = err(&PullOffSpec::new(0.45, 1.0, 0.0), &heights);
        assert!(e.starts_with("material.gamma = 0 is invalid"), "{e}");
        let e = err(&PullOffSpec::new(-1.0, 1.0, 0.1), &heights);
        assert!(e.contains("grid.dx = -1"), "{e}");
        let e = err(
            &PullOffSpec {
                unload_step: Some(-0.1),
                ..spec.clone()
            },
            &heights,
        );
        assert!(
            e.starts_with("protocol.unload_step = -0.1 is invalid"),
            "{e}"
        );
        // A flat body has no radius: the path must be given.
        let flat = Array2::zeros((16, 16));
        let e = err(&spec, &flat);
        assert!(e.starts_with("protocol.max_approach is required"), "{e}");
        let e = err(
            &PullOffSpec {
                max_approach: Some(0.1),
                ..spec.clone()
            },
            &flat,
        );
        assert!(e.starts_with("protocol.unload_step is required"), "{e}");
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
