//! From a parsed scene to a ready-to-solve problem: validated values, the grid, the surface
//! (shape plus roughness, composed by addition), the approach path and the closed-form
//! references (F_JKR, Johnson's α, α*, Kendall) that the summary compares against.
//!
//! Validation reuses the library crates' errors (they name the field) and adds the checks that
//! need the whole scene: a wavelength the grid cannot resolve, a sphere contact that does not fit
//! a free grid, a punch larger than the grid, a height map of the wrong shape or spacing, and an
//! approach path that never touches the surface.

use std::path::Path;

use tack_fields::{self as fields, field_name};

use tack_geometry::{
    Boundary, Grid, RoughSpec, Shape, Surface, Waviness1d, Waviness2d, Window, rough_surface,
};
use tack_solver::{
    AdhesionLaw, AdhesiveOptions, AdhesiveSolver, ApproachPath, Family, KAPPA, Prony, Rates,
    SnapshotRequest, contact_window,
};

use crate::scene::{
    BoundaryKind, DEFAULT_MAX_STEPS, GridSpec, Protocol, Roughness, Scene, SceneError, SceneSchema,
    num,
};

pub use crate::map_file::DX_MATCH_TOLERANCE;
pub(crate) use crate::map_file::read_map;
pub use crate::references::References;
pub use crate::shape::{
    MAX_ELLIPSOID_RATIO, MIN_PERIOD_CONTACT_DIAMETERS, MIN_PULL_OFF_RADIUS_ELEMENTS,
};

pub use crate::pull_off_path::{SPHERE_FIT_MARGIN, loaded_steps};

/// Largest number of grid elements `nx·ny` a scene may ask for (8192 × 8192): beyond it the
/// solver's fields and FFT buffers would not fit in memory, and the run would abort instead of
/// failing with a message.
pub const MAX_ELEMENTS: usize = 1 << 26;

/// The accepted range of `solver.tolerance` (relative CG residual), both ends included.
pub const TOLERANCE_RANGE: (f64, f64) = (1e-14, 1e-1);

/// The grid's size field when it is given as `nx` and `ny`.
const GRID_NX_BY_NY: &str = concat!(field_name!(grid.nx), " × ", field_name!(grid.ny));

/// Smallest wavelength, in elements, a waviness may have.
pub const MIN_ELEMENTS_PER_WAVELENGTH: f64 = 4.0;

/// A validated scene, ready to run.
#[derive(Debug, Clone)]
pub struct Problem {
    /// The grid.
    pub grid: Grid,
    /// The rigid body's heights (gap at zero approach).
    pub surface: Surface,
    /// Effective modulus `E*`.
    pub e_star: f64,
    /// Work of adhesion `γ` (the reference when it varies: see [`Problem::gamma_map`]).
    pub gamma: f64,
    /// γ of every element when it varies over the surface (`[adhesion]` map or pattern, or an
    /// array given in memory); `None`: [`Problem::gamma`] everywhere.
    pub gamma_map: Option<ndarray::Array2<f64>>,
    /// The elastic body: `None` for the half-space, or a layer on a rigid base (`[body]`).
    pub layer: Option<tack_kernels::Layer>,
    /// Pohrt–Popov constant κ (read by the zero-range law only).
    pub kappa: f64,
    /// The adhesion law: the scene's `[adhesion]` (the zero-range criterion with
    /// [`Problem::kappa`], a Dugdale cohesive zone or a smooth law), or one given in memory
    /// ([`Problem::with_law`]).
    pub law: AdhesionLaw,
    /// A viscoelastic solid and the rates of its path in time (`None`: elastic).
    pub viscoelastic: Option<(Prony, Rates)>,
    /// Solver settings.
    pub options: AdhesiveOptions,
    /// The approach path.
    pub path: ApproachPath,
    /// Which steps keep fields.
    pub snapshots: SnapshotRequest,
    /// Whether the surface goes into the result file.
    pub store_surface: bool,
    /// `grid.crop` as given.
    pub crop: bool,
    /// The window the solver runs on when cropping applies (free grids, `grid.crop = true`, and
    /// a window smaller than the grid): see `tack_solver::contact_window`.
    pub window: Option<Window>,
    /// The lowest surface height: the approach of the first touch.
    pub first_touch: f64,
    /// Seed of the random roughness, when there is one.
    pub seed: Option<u64>,
    /// Closed-form references.
    pub references: References,
    /// What makes this scene's answer less than trustworthy, known before it runs (an
    /// under-resolved pull-off, a closed-form reference that does not apply); the summary
    /// carries them on, with the run's own.
    pub warnings: Vec<String>,
    /// The body includes heights given as an array in memory ([`crate::heights`]): defined per
    /// element, so a Richardson coarse grid cannot carry it.
    pub heights_in_memory: bool,
    /// The law was given in memory ([`Problem::with_law`]), not by the scene's `[adhesion]`.
    pub law_in_memory: bool,
    /// Where the path came from when `[protocol]` left it to the default pull-off rule
    /// ([`crate::pull_off_path`]); `None` when the scene gave it.
    pub path_rule: Option<PathRule>,
}

/// The default pull-off path a scene without `protocol.load_step` got, and the radius it was
/// derived from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathRule {
    /// The sphere's radius R.
    pub radius: f64,
    /// Whether R was fitted (a least-squares paraboloid through the heights) rather than given.
    pub fitted: bool,
    /// Where a radius that was not fitted comes from: `"given"`, or the shape's own rule
    /// (`crate::shape::SceneShape::path_radius_origin`, e.g. an ellipsoid's `√(Rx·Ry)`).
    pub origin: &'static str,
    /// The rule's numbers.
    pub path: crate::pull_off_path::PullOffPath,
    /// The load step when loaded in steps from out of range (a finite-range law), `None` when
    /// loaded in one step ([`crate::pull_off_path::load_plan`]).
    pub stepped_load: Option<f64>,
    /// The refined retraction (`protocol.refine_pull_off`): coarse steps all the way.
    pub refined: bool,
    /// A smooth law's step past the pull-off once nothing touches
    /// ([`tack_solver::AdhesionLaw::tail_step`]), when longer than the fine step.
    pub tail_step: Option<f64>,
}

impl PathRule {
    /// The rule with the tail step its `path` takes under `law` on a `viscoelastic` solid or
    /// an elastic one ([`ApproachPath::tail_step`]).
    fn with_tail(self, path: &ApproachPath, law: &AdhesionLaw, viscoelastic: bool) -> Self {
        Self {
            tail_step: path.tail_step(law, viscoelastic),
            ..self
        }
    }
}

impl std::fmt::Display for PathRule {
    /// One line, numbers rounded (`tack_fields::rounded`): `default pull-off path of R = 1
    /// (given), d_s = …: one load step to d = …, retraction by … while compressive, then by …`
    /// (`loaded in steps of … from out of range` under a finite-range law; `, past the
    /// pull-off by …` under a smooth law whose tail step is longer than the fine one).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let p = &self.path;
        let r = tack_fields::rounded;
        write!(
            f,
            "default pull-off path of R = {} ({}), d_s = {}: {} to d = {}, retraction by {} {}, \
             {} {}{}",
            r(self.radius),
            if self.fitted { "fitted" } else { self.origin },
            r(p.d_s),
            match self.stepped_load {
                Some(step) => format!("loaded in steps of {} from out of range", r(step)),
                None => "one load step".to_owned(),
            },
            r(p.max_approach),
            r(p.coarse_unload_step),
            if self.refined {
                "all the way"
            } else {
                "while compressive"
            },
            if self.refined {
                "the pull-off's brackets retraced by"
            } else {
                "then by"
            },
            r(p.unload_step),
            match self.tail_step {
                Some(t) if !self.refined => format!(", past the pull-off by {}", r(t)),
                _ => String::new(),
            }
        )
    }
}

impl Problem {
    /// Validates `scene` and builds grid, surface and path.
    pub fn from_scene(scene: &Scene) -> Result<Self, SceneError> {
        Self::build(scene, None, None)
    }

    /// Validates `scene` as [`Problem::from_scene`] does, under `law` instead of the scene's
    /// `[adhesion]` law: a law held in memory, in particular a smooth law of the caller's own
    /// ([`AdhesionLaw::custom`]). The scene then names no law (`adhesion.model` left at its
    /// default, no `adhesion.range`, `adhesion.sigma0` or `solver.kappa`), and the law is
    /// checked against the scene's γ and heights ([`tack_solver::Law::check`]). Everything the
    /// law decides (the default path's start, the crop window, the mesh warning, Tabor's μ, the
    /// summary's law entries) follows it; a result names it in `/summary` (`adhesion_model`,
    /// its range and peak tension), since the scene text it stores cannot.
    pub fn with_law(scene: &Scene, law: AdhesionLaw) -> Result<Self, SceneError> {
        Self::build(scene, None, Some(&law))
    }

    /// The one problem builder: [`Problem::from_scene`], and with `body` its heights added to
    /// the scene's body, their roughness range added to the crop rule's and their radius giving
    /// the JKR references (`crate::heights`: bodies held in memory); with `law` that law instead
    /// of the scene's ([`Problem::with_law`]). It runs in stages, each a
    /// function: material, grid and memory, body (shape, roughness, heights, references), film
    /// and γ map, law, path, fits, solver options, the warnings known before the run, crop.
    pub(crate) fn build(
        scene: &Scene,
        body: Option<&HeightBody<'_>>,
        law: Option<&AdhesionLaw>,
    ) -> Result<Self, SceneError> {
        let f = &scene.file;
        let material = check_material(f.material.e_star, f.material.gamma, true)?;
        let (e_star, gamma) = (material.e_star, material.gamma);
        let grid = build_grid(&f.grid)?;
        // The working fields before anything of the grid's size is allocated; the snapshots
        // and records once the path's step count is known.
        let gamma_array = body.is_some_and(|b| b.gamma.is_some());
        check_memory(scene, &grid, None, gamma_array)?;
        let shape = f.geometry.shape();
        let built = build_body(scene, shape.as_ref(), grid, body, material)?;
        let BodyStage {
            surface,
            seed,
            roughness_range,
            mut references,
            body_radius,
        } = built;
        let mut warnings = Vec::new();
        let layer = crate::layer::body_layer(&f.body, &grid, &mut warnings)?;
        let gamma_map = crate::gamma_map::gamma_map(
            &f.adhesion,
            gamma,
            &grid,
            &scene.base_dir,
            body.and_then(|b| b.gamma),
            &mut warnings,
        )?;
        check_scales(
            material,
            &grid,
            shape.as_ref(),
            f.solver.kappa.unwrap_or(KAPPA),
        )?;
        if gamma > 0.0 {
            shape.references(material, &grid, &mut references, &mut warnings);
            if let Some(r) = body_radius {
                references.set_jkr(e_star, gamma, r);
            }
        }
        let first_touch = surface.min();
        let law_in_memory = law.is_some();
        let (law, kappa) = law_stage(f, law, &surface)?;
        resolvable(&law, (e_star, gamma), &grid, layer.is_none())?;
        criterion_mesh_rule(&law, &references, grid.dx(), &mut warnings);
        let path_sphere = shape.path_sphere();
        let (path, path_rule) = approach_path(
            &f.protocol,
            &PathBody {
                grid: &grid,
                surface: &surface,
                sphere: path_sphere.as_ref().map(|(r, s)| (*r, s.as_ref())),
                origin: shape.path_radius_origin(),
                given_radius: body_radius,
                heights_only: shape.heights_only(),
                material,
                law: &law,
            },
        )?;
        path.validate()?;
        // A radius fitted for the default path gives the references too (as for heights).
        if let Some(rule) = path_rule.filter(|r| r.fitted && gamma > 0.0)
            && references.f_jkr.is_none()
        {
            references.set_jkr(e_star, gamma, rule.radius);
        }
        if grid.boundary() == Boundary::Free {
            let fit = crate::shape::FitCheck {
                spec: &f.grid,
                grid: &grid,
                path: &path,
                first_touch,
                surface: &surface,
                default_path: path_rule.is_some(),
                film: layer.is_some(),
                material,
                finite_range: law.reach(gamma).is_some(),
            };
            shape.check_fit(&fit)?;
            warnings.extend(fit.edge_warning());
        }
        check_memory(scene, &grid, Some(path.step_bound()), gamma_array)?;
        // Random roughness and height arrays (measured surfaces); not waviness, whose
        // figures load in steps on purpose and whose contact is one patch per period.
        let span = surface.max() - surface.min();
        let random = matches!(
            f.roughness,
            Some(Roughness::Random { .. } | Roughness::File { .. })
        ) || body.is_some_and(|b| b.roughness_range.is_none_or(|r| r > 1e-9 * span));
        warnings.extend(loading_history_warning(
            &law,
            gamma,
            random,
            &path,
            first_touch,
        ));
        let options = solver_options(&f.solver)?;
        let viscoelastic = viscoelastic(f, &law, layer.is_some())?;
        if let Some(sigma0) = maugis_sigma0(&law) {
            dugdale_references(&mut references, e_star, gamma, sigma0);
        }
        if law.is_smooth() {
            smooth_references(&mut references, &law, e_star, gamma);
        }
        warnings.extend(law.mesh_warning(e_star, gamma, grid.dx()));
        if let Some(layer) = &layer {
            crate::layer::film_warnings(layer, &references, &law, gamma, grid.dx(), &mut warnings);
        }
        let window = crop_window(
            f,
            &surface,
            &path,
            roughness_range,
            material,
            &law,
            gamma_map.as_ref(),
            layer.is_some(),
        );
        Ok(Self {
            path_rule: path_rule.map(|r| r.with_tail(&path, &law, viscoelastic.is_some())),
            grid,
            surface,
            e_star,
            gamma,
            gamma_map,
            layer,
            kappa,
            law,
            viscoelastic,
            options,
            path,
            snapshots: (&f.output.snapshots).into(),
            store_surface: f.output.surface,
            crop: f.grid.crop,
            window,
            first_touch,
            seed,
            references,
            warnings,
            heights_in_memory: body.is_some(),
            law_in_memory,
        })
    }

    /// What the run may need in memory (what `tack check` prints): working fields, the
    /// snapshots `output.snapshots` keeps and the step records, over the path's step bound
    /// ([`tack_solver::ApproachPath::step_bound`]).
    pub fn memory_estimate(&self) -> crate::memory::Estimate {
        let mut e = crate::memory::estimate(&self.grid, self.path.step_bound(), &self.snapshots);
        if self.gamma_map.is_some() {
            e.add_fields(crate::memory::GAMMA_MAP_FIELDS);
        }
        if self.path.refine_pull_off {
            e.add_fields(crate::memory::REFINED_STATE_FIELDS);
        }
        if let Some((prony, _)) = &self.viscoelastic {
            e.add_fields(crate::memory::viscoelastic_fields(prony.arms().len()));
        }
        e
    }

    /// A fresh solver for this problem (builds the elastic operator: FFT plans, kernel spectrum),
    /// on the crop window when `window` is given.
    pub fn solver(&self, window: Option<&Window>) -> Result<AdhesiveSolver, SceneError> {
        let surface = match window {
            Some(w) => self.surface.window(w)?,
            None => self.surface.clone(),
        };
        let op = match &self.layer {
            Some(layer) => tack_kernels::layer_operator_for(*surface.grid(), self.e_star, layer)?,
            None => tack_kernels::operator_for(*surface.grid(), self.e_star)?,
        };
        let mut solver =
            AdhesiveSolver::with_law(op, &surface, self.gamma, self.law.clone(), self.options)?;
        if let Some(map) = &self.gamma_map {
            let view = match window {
                Some(w) => map.slice(ndarray::s![w.i0..w.i1, w.j0..w.j1]),
                None => map.view(),
            };
            solver.set_gamma_map(view)?;
        }
        if let Some((prony, rates)) = &self.viscoelastic {
            solver.set_viscoelastic(prony.clone(), *rates)?;
        }
        Ok(solver)
    }
}

/// The material's E* and γ, checked (the one place, for scenes and bodies in memory):
/// E* finite and > 0, γ finite and ≥ 0 (> 0 unless `zero_gamma`), errors naming the fields.
pub(crate) fn check_material(
    e_star: f64,
    gamma: f64,
    zero_gamma: bool,
) -> Result<crate::shape::Material, SceneError> {
    if !(e_star.is_finite() && e_star > 0.0) {
        return Err(tack_kernels::KernelError::Modulus(e_star).into());
    }
    if !(gamma.is_finite() && (gamma > 0.0 || zero_gamma && gamma == 0.0)) {
        return Err(SceneError::out_of_range(
            fields::MATERIAL_GAMMA,
            gamma,
            if zero_gamma {
                "a finite number ≥ 0"
            } else {
                "a finite number > 0 (a pull-off needs adhesion; without it use the \
                 non-adhesive tack_solver::ContactSolver)"
            },
        ));
    }
    Ok(crate::shape::Material { e_star, gamma })
}

/// The body as the build's body stage leaves it.
struct BodyStage {
    surface: Surface,
    seed: Option<u64>,
    /// Height range of what sits on the smooth shape (roughness, an array), for the crop rule.
    roughness_range: f64,
    /// The roughness's references (Johnson's α, p*, α*); the shape's come later.
    references: References,
    /// The radius a body in memory was given.
    body_radius: Option<f64>,
}

/// The body stage: the shape's surface, the roughness on it (with its references) and the
/// heights given in memory.
fn build_body(
    scene: &Scene,
    shape: &dyn crate::shape::SceneShape,
    grid: Grid,
    body: Option<&HeightBody<'_>>,
    material: crate::shape::Material,
) -> Result<BodyStage, SceneError> {
    let f = &scene.file;
    let (e_star, gamma) = (material.e_star, material.gamma);
    let mut surface = shape.surface(grid)?;
    let mut seed = None;
    let mut references = References::default();
    let mut roughness_range = 0.0;
    if let Some(roughness) = &f.roughness {
        let smooth = surface.heights().clone();
        add_roughness(&mut surface, roughness, &scene.base_dir, &f.grid, &mut seed)?;
        let rough = surface.heights() - &smooth;
        roughness_range = rough.iter().copied().fold(f64::NEG_INFINITY, f64::max)
            - rough.iter().copied().fold(f64::INFINITY, f64::min);
        match *roughness {
            Roughness::Waviness1d { h, lambda } => {
                references.johnson_alpha =
                    Some(tack_analytics::johnson_alpha(e_star, gamma, h, lambda));
                references.p_star = Some(tack_analytics::westergaard_p_star(e_star, h, lambda));
            }
            Roughness::Waviness2d { h, lambda } => {
                references.johnson_alpha =
                    Some(tack_analytics::johnson_alpha(e_star, gamma, h, lambda));
                references.p_star = Some(tack_analytics::johnson_2d_p_star(e_star, h, lambda));
            }
            Roughness::Random {
                h, hurst, q0, q1, ..
            } => {
                let (q0, q1) = band(&grid, q0, q1);
                references.alpha_star =
                    Some(tack_analytics::alpha_star(e_star, gamma, h, hurst, q0, q1));
            }
            Roughness::File { .. } => {}
        }
    }
    let mut body_radius = None;
    if let Some(body) = body {
        let array = height_surface(grid, body.heights)?;
        roughness_range += match body.roughness_range {
            Some(r) if r.is_finite() && r >= 0.0 => r,
            Some(r) => {
                return Err(SceneError::out_of_range(
                    "roughness_range",
                    r,
                    "a finite number ≥ 0",
                ));
            }
            None => (array.max() - array.min()).max(0.0),
        };
        if let Some(r) = body.radius
            && !(r.is_finite() && r > 0.0)
        {
            return Err(SceneError::out_of_range("radius", r, "a finite number > 0"));
        }
        body_radius = body.radius;
        surface.add(&array)?;
    }
    Ok(BodyStage {
        surface,
        seed,
        roughness_range,
        references,
        body_radius,
    })
}

/// The solver settings of `[solver]`, checked.
fn solver_options(s: &crate::scene::SolverSpec) -> Result<AdhesiveOptions, SceneError> {
    let defaults = AdhesiveOptions::default();
    if let Some(t) = s.tolerance
        && !(TOLERANCE_RANGE.0..=TOLERANCE_RANGE.1).contains(&t)
    {
        return Err(SceneError::out_of_range(
            fields::SOLVER_TOLERANCE,
            num(t),
            "a number in 1e-14..=0.1 (the relative CG residual; default 1e-9): below 1e-14 \
             round-off stops CG from ever converging, above 0.1 the forces are not solutions",
        ));
    }
    let options = AdhesiveOptions {
        cg: tack_solver::SolverOptions {
            tolerance: s.tolerance.unwrap_or(defaults.cg.tolerance),
            max_iterations: s.max_iterations.unwrap_or(defaults.cg.max_iterations),
        },
        max_active_set_iterations: s
            .max_active_set_iterations
            .unwrap_or(defaults.max_active_set_iterations),
        round_tolerance: match s.round_tolerance {
            None => defaults.round_tolerance,
            Some(0.0) => None,
            Some(t) if t > 0.0 && t < 1.0 => Some(t),
            Some(t) => {
                return Err(SceneError::out_of_range(
                    fields::SOLVER_ROUND_TOLERANCE,
                    t,
                    "0 (every round exact) or a number in (0, 1)",
                ));
            }
        },
        local_relaxation: s.local_relaxation.unwrap_or(defaults.local_relaxation),
        cascade: s.cascade.unwrap_or(defaults.cascade),
        ..defaults
    };
    options.cg.validate()?;
    if options.max_active_set_iterations == 0 {
        return Err(SceneError::out_of_range(
            fields::SOLVER_MAX_ACTIVE_SET_ITERATIONS,
            0,
            "an integer ≥ 1",
        ));
    }
    Ok(options)
}

/// The crop window (`grid.crop`): what can ever touch, on free grids of the half-space; a
/// cohesive zone loads elements up to the law's range above the contact and a γ map reaches
/// as far as its greatest γ, so both widen it. A film bulges beyond the half-space's reach, so
/// it runs uncropped.
#[allow(clippy::too_many_arguments)]
fn crop_window(
    f: &SceneSchema,
    surface: &Surface,
    path: &ApproachPath,
    roughness_range: f64,
    material: crate::shape::Material,
    law: &AdhesionLaw,
    gamma_map: Option<&ndarray::Array2<f64>>,
    film: bool,
) -> Option<Window> {
    if !f.grid.crop || film {
        return None;
    }
    let gamma = material.gamma;
    let gamma_max = gamma_map.map_or(gamma, |m| crate::gamma_map::map_range(m).2.max(gamma));
    contact_window(
        surface,
        path.max_approach,
        roughness_range + law.reach(gamma).unwrap_or(0.0),
        material.e_star,
        gamma_max,
    )
    .filter(|w| w.shape() != surface.grid().shape())
}

/// The σ0 of a law that Maugis' references describe: the Dugdale law's, and the smoothed
/// Dugdale law's, which tends to it.
fn maugis_sigma0(law: &AdhesionLaw) -> Option<f64> {
    match (law, law.family()) {
        (_, Family::Cohesive { sigma0 }) => Some(sigma0),
        (AdhesionLaw::SmoothedDugdale(l), _) => Some(l.sigma0),
        _ => None,
    }
}

/// The Dugdale law's references: λ and the Maugis–Dugdale pull-off of a sphere (its radius
/// read back from F_JKR).
fn dugdale_references(references: &mut References, e_star: f64, gamma: f64, sigma0: f64) {
    if let Some(f_jkr) = references.f_jkr {
        let radius = -f_jkr / (1.5 * std::f64::consts::PI * gamma);
        references.maugis_lambda =
            Some(tack_analytics::maugis_lambda(e_star, gamma, radius, sigma0));
        references.f_maugis = Some(tack_analytics::maugis_pull_off(
            e_star, gamma, radius, sigma0,
        ));
    }
}

/// The viscoelastic solid of `material.prony` and the rates of `[protocol]`, checked: the
/// rates only with `prony`; with it a half-space, a finite-range law when there is adhesion (the
/// zero-range criterion has no rate-consistent form), `speed` and a path in time
/// (`max_approach` and `load_step`, each load step lasting `load_step/speed`; no refined
/// retraction, which retraces steps).
fn viscoelastic(
    f: &SceneSchema,
    law: &AdhesionLaw,
    film: bool,
) -> Result<Option<(Prony, Rates)>, SceneError> {
    let p = &f.protocol;
    let prony_field = fields::MATERIAL_PRONY;
    let rates = [
        (fields::PROTOCOL_SPEED, p.speed.is_some()),
        (fields::PROTOCOL_UNLOAD_SPEED, p.unload_speed.is_some()),
        (fields::PROTOCOL_DWELL, p.dwell.is_some()),
        (fields::PROTOCOL_DWELL_STEPS, p.dwell_steps.is_some()),
    ];
    let Some(arms) = &f.material.prony else {
        if let Some((field, _)) = rates.iter().find(|(_, given)| *given) {
            return Err(SceneError::Inconsistent(format!(
                "{field} is a rate of a path in time, read only for a viscoelastic solid: give \
                 {prony_field} (its arms [E_k, tau_k]) or leave {field} out"
            )));
        }
        return Ok(None);
    };
    let pairs: Vec<(f64, f64)> = arms.iter().map(|&[e, t]| (e, t)).collect();
    let prony = Prony::new(f.material.e_star, &pairs)?;
    let refuse = |what: String| Err(SceneError::Inconsistent(what));
    if film {
        return refuse(format!(
            "{prony_field}: viscoelastic solids are half-spaces; {} = \"layer\" is elastic only",
            fields::BODY_KIND
        ));
    }
    if matches!(law, AdhesionLaw::JkrLimit(_)) && f.material.gamma > 0.0 {
        return refuse(format!(
            "{prony_field} with adhesion needs a finite-range law: the zero-range criterion has \
             no rate-consistent form; set {} = {}",
            fields::ADHESION_MODEL,
            finite_range_models()
        ));
    }
    let Some(speed) = p.speed else {
        return refuse(format!(
            "{prony_field} needs {}: the approach rate that turns the path's steps into time \
             steps",
            fields::PROTOCOL_SPEED
        ));
    };
    if p.indent.is_none() && (p.max_approach.is_none() || p.load_step.is_none()) {
        return refuse(format!(
            "{prony_field} needs a path in time: give {} and {} (a load step lasts \
             load_step/speed, an unload step unload_step/unload_speed)",
            fields::PROTOCOL_MAX_APPROACH,
            fields::PROTOCOL_LOAD_STEP
        ));
    }
    if p.refine_pull_off == Some(true) {
        return refuse(format!(
            "{} retraces steps, which a viscoelastic path cannot (its arms carry the time): \
             leave it out and choose unload_step for the retraction's time step",
            fields::PROTOCOL_REFINE_PULL_OFF
        ));
    }
    if p.dwell_steps.is_some() && p.dwell.is_none() {
        return refuse(format!(
            "{} cuts the hold {} into steps: give {1} too, or leave {0} out",
            fields::PROTOCOL_DWELL_STEPS,
            fields::PROTOCOL_DWELL
        ));
    }
    let rates = Rates {
        speed,
        unload_speed: p.unload_speed.unwrap_or(speed),
        dwell: p.dwell.unwrap_or(0.0),
        dwell_steps: p.dwell_steps.unwrap_or(crate::scene::DEFAULT_DWELL_STEPS),
    };
    rates.validate()?;
    Ok(Some((prony, rates)))
}

/// A smooth law's reference: Tabor's μ of the sphere (its radius read back from F_JKR).
fn smooth_references(references: &mut References, law: &AdhesionLaw, e_star: f64, gamma: f64) {
    if let Some(f_jkr) = references.f_jkr {
        let radius = -f_jkr / (1.5 * std::f64::consts::PI * gamma);
        references.tabor_mu = law.tabor(e_star, gamma, radius);
    }
}

/// The adhesion law of `[adhesion]`, checked: each law's parameter (`Law::parameter`) only
/// with, and always with, its model (`sigma0` with `"dugdale"`, `range` with the smooth laws,
/// `solver.kappa`, defaulted, with the zero-range criterion); γ > 0 and the law's own checks
/// (`Law::check`) for the finite-range laws. Every law of the solver is read the same way.
fn adhesion_law(f: &SceneSchema, kappa: f64, surface: &Surface) -> Result<AdhesionLaw, SceneError> {
    let model_field = fields::ADHESION_MODEL;
    let name = f.adhesion.model.name();
    let given = law_parameters(f);
    // The law's own field, from a probe of the model (its value is set below).
    let probe = AdhesionLaw::from_model(name, 1.0).ok_or_else(|| {
        SceneError::Inconsistent(format!("{model_field} = \"{name}\" names no law"))
    })?;
    let own = probe.parameter().0;
    for (field, value) in given {
        let Some(value) = value.filter(|_| field != own) else {
            continue;
        };
        return Err(SceneError::Inconsistent(format!(
            "{field} = {} is read by {model_field} = {} only: \"{name}\" does not read it; \
             leave it out or set {model_field}",
            num(value),
            readers(field),
        )));
    }
    let value = match given.iter().find(|g| g.0 == own).and_then(|g| g.1) {
        Some(v) => v,
        None if own == fields::SOLVER_KAPPA => kappa,
        None => {
            return Err(SceneError::Inconsistent(format!(
                "{own} is required with {model_field} = \"{name}\": {}",
                probe.meaning(),
            )));
        }
    };
    let gamma = f.material.gamma;
    // A law bound to the mesh (the smoothed Dugdale law) takes this run's.
    let law = AdhesionLaw::from_model(name, value)
        .expect("a model the probe found")
        .on_mesh(gamma, f.material.e_star, surface.grid().dx());
    if own == fields::SOLVER_KAPPA {
        return Ok(law);
    }
    finite_range_gamma(&format!("{model_field} = \"{name}\""), gamma)?;
    // Positive, finite parameters and a range above the round-off of the heights.
    law.check(gamma, surface)?;
    Ok(law)
}

/// A smooth law the grid cannot resolve to round-off ([`AdhesionLaw::smooth_tolerance`]) is
/// refused before running, as the solver would refuse it: on a free half-space (`half_space`
/// and a free grid) with the free operator's self-compliance
/// ([`tack_kernels::FreeOperator::self_compliance_of`]); periodic grids and films are checked
/// with their own operator's when run.
fn resolvable(
    law: &AdhesionLaw,
    (e_star, gamma): (f64, f64),
    grid: &Grid,
    half_space: bool,
) -> Result<(), SceneError> {
    if half_space && grid.boundary() == tack_geometry::Boundary::Free {
        let k = tack_kernels::FreeOperator::self_compliance_of(grid.dx(), e_star);
        law.smooth_tolerance(gamma, e_star, grid.dx(), k)?;
    }
    Ok(())
}

/// The law and κ: `law` given in memory, or the scene's `[adhesion]` law; κ is checked either
/// way (the problem carries it).
fn law_stage(
    f: &SceneSchema,
    law: Option<&AdhesionLaw>,
    surface: &Surface,
) -> Result<(AdhesionLaw, f64), SceneError> {
    let kappa = f.solver.kappa.unwrap_or(KAPPA);
    if !(kappa.is_finite() && kappa > 0.0) {
        return Err(SceneError::out_of_range(
            fields::SOLVER_KAPPA,
            kappa,
            "a finite number > 0",
        ));
    }
    let (law, kappa) = match law {
        Some(law) => {
            let law = checked_law_in_memory(f, law, surface)?;
            // The zero-range criterion given in memory brings its own κ.
            let kappa = match law.family() {
                Family::Criterion { kappa } => kappa,
                _ => kappa,
            };
            (law, kappa)
        }
        None => (adhesion_law(f, kappa, surface)?, kappa),
    };
    unread_by_law(f, &law)?;
    Ok((law, kappa))
}

/// The pull-off radius' mesh rule ([`References::criterion_mesh`],
/// [`crate::shape::under_resolved`]) is the zero-range criterion's (its error grows like
/// Δx/a_c): a finite-range law's own warning judges its zone.
fn criterion_mesh_rule(
    law: &AdhesionLaw,
    references: &References,
    dx: f64,
    warnings: &mut Vec<String>,
) {
    if let (Family::Criterion { .. }, Some((radius, what))) =
        (law.family(), references.criterion_mesh)
    {
        crate::shape::under_resolved(warnings, what, radius, dx);
    }
}

/// The `[solver]` settings a law does not read are refused, so none is silently ignored: the
/// round loop's (`tolerance`, `max_active_set_iterations`, `round_tolerance`: the zero-range
/// criterion and the Dugdale law) under a smooth law, which has no rounds (its Newton
/// iteration solves every element to a fixed fraction of the peak tension, docs/theory.md
/// §3.9); the local relaxation's (`local_relaxation`, `cascade`: the criterion's detachments
/// only) under both finite-range laws.
fn unread_by_law(f: &SceneSchema, law: &AdhesionLaw) -> Result<(), SceneError> {
    let smooth = law.curve().is_some();
    let criterion = matches!(law.family(), Family::Criterion { .. });
    let s = &f.solver;
    let show = |v: Option<f64>| v.map(num);
    let flag = |v: Option<bool>| v.map(|b| b.to_string());
    let rounds = "\"jkr_limit\" and \"dugdale\"";
    let given = [
        (fields::SOLVER_TOLERANCE, show(s.tolerance), rounds, smooth),
        (
            fields::SOLVER_MAX_ACTIVE_SET_ITERATIONS,
            s.max_active_set_iterations.map(|n| n.to_string()),
            rounds,
            smooth,
        ),
        (
            fields::SOLVER_ROUND_TOLERANCE,
            show(s.round_tolerance),
            rounds,
            smooth,
        ),
        (
            fields::SOLVER_LOCAL_RELAXATION,
            flag(s.local_relaxation),
            "\"jkr_limit\"",
            !criterion,
        ),
        (
            fields::SOLVER_CASCADE,
            flag(s.cascade),
            "\"jkr_limit\"",
            !criterion,
        ),
    ];
    let Some((field, value, readers)) =
        given.into_iter().find_map(|(field, v, readers, refused)| {
            v.filter(|_| refused).map(|v| (field, v, readers))
        })
    else {
        return Ok(());
    };
    let why = if smooth {
        format!(
            "the smooth law \"{}\" has no detach/attach rounds: Newton's method solves every \
             element to 1e-7 of its peak tension or tighter (docs/theory.md §3.9)",
            law.name()
        )
    } else {
        "the Dugdale law's rounds relax no detachments locally".to_owned()
    };
    Err(SceneError::Inconsistent(format!(
        "{field} = {value} is read by {} = {readers} only: {why}; leave {field} out",
        fields::ADHESION_MODEL,
    )))
}

/// A law given in memory ([`Problem::with_law`]), checked: the scene names none of its own
/// (`adhesion.model` at its default, no law parameter), γ > 0 for a finite-range law, and the
/// law's own checks.
fn checked_law_in_memory(
    f: &SceneSchema,
    law: &AdhesionLaw,
    surface: &Surface,
) -> Result<AdhesionLaw, SceneError> {
    let model_field = fields::ADHESION_MODEL;
    let default = crate::AdhesionModel::default().name();
    if f.adhesion.model.name() != default {
        return Err(SceneError::Inconsistent(format!(
            "{model_field} = \"{}\" names a law but the law \"{}\" is given in memory; leave \
             {model_field} out",
            f.adhesion.model.name(),
            law.name(),
        )));
    }
    if let Some((field, value)) = law_parameters(f)
        .iter()
        .find_map(|(f, v)| v.map(|v| (f, v)))
    {
        return Err(SceneError::Inconsistent(format!(
            "{field} = {} is a parameter of the scene's law, but the law \"{}\" is given in \
             memory with its own; leave {field} out",
            num(value),
            law.name(),
        )));
    }
    let gamma = f.material.gamma;
    if law.range(gamma).is_some() {
        finite_range_gamma(
            &format!("the law \"{}\" given in memory", law.name()),
            gamma,
        )?;
    }
    law.check(gamma, surface)?;
    Ok(law.clone())
}

/// The scene's law parameters and their values: `adhesion.sigma0`, `adhesion.range`,
/// `solver.kappa`.
fn law_parameters(f: &SceneSchema) -> [(&'static str, Option<f64>); 3] {
    [
        (fields::ADHESION_SIGMA0, f.adhesion.sigma0),
        (fields::ADHESION_RANGE, f.adhesion.range),
        (fields::SOLVER_KAPPA, f.solver.kappa),
    ]
}

/// A finite-range law (`who`) needs γ > 0: it spreads γ over its range.
fn finite_range_gamma(who: &str, gamma: f64) -> Result<(), SceneError> {
    if gamma <= 0.0 {
        return Err(SceneError::Inconsistent(format!(
            "{who} needs {} > 0 (a finite-range law spreads γ over its range); got {}",
            fields::MATERIAL_GAMMA,
            num(gamma),
        )));
    }
    Ok(())
}

/// The models of a finite range, quoted and joined: `"dugdale", "exponential" or
/// "lennard_jones"`.
fn finite_range_models() -> String {
    models_where(|l| l.range(1.0).is_some())
}

/// The models whose parameter is `field`, quoted and joined: `"dugdale"`, or
/// `"exponential" or "lennard_jones"`.
fn readers(field: &str) -> String {
    models_where(|l| l.parameter().0 == field)
}

/// The registry's models whose law (at parameter 1) passes `keep`, quoted and joined by `, `
/// and a last ` or `.
fn models_where(keep: impl Fn(&AdhesionLaw) -> bool) -> String {
    let quoted: Vec<String> = AdhesionLaw::models()
        .filter(|m| AdhesionLaw::from_model(m, 1.0).is_some_and(|l| keep(&l)))
        .map(|m| format!("{m:?}"))
        .collect();
    match quoted.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => quoted.join(""),
    }
}

/// A rigid body given as heights in memory, added to a scene's body (`crate::heights::problem`,
/// `crate::heights::run`).
#[derive(Debug, Clone, Copy)]
pub struct HeightBody<'a> {
    /// Heights `(nx, ny)`, added to the scene's own body; the shape must be the scene grid's.
    pub heights: &'a ndarray::Array2<f64>,
    /// Height range (max − min) of the body's roughness, its deviation from the smooth
    /// macroscopic shape, for the crop rule (`tack_solver::contact_window`); `None`: the range
    /// of the whole array (always safe, but a curved body then leaves little to crop).
    pub roughness_range: Option<f64>,
    /// Radius of the sphere the body approximates: the summary then carries the JKR references
    /// (`f_jkr`, `pull_off_ratio`, `d_jkr`) of that sphere, and a scene without
    /// `protocol.max_approach` gets the default pull-off path of that radius. `None`: no
    /// references.
    pub radius: Option<f64>,
    /// Work of adhesion per element `(nx, ny)`, finite and ≥ 0 (`None`: `material.gamma`
    /// everywhere, which stays the reference of F_JKR and the path).
    pub gamma: Option<&'a ndarray::Array2<f64>>,
}

/// The surface of a height array on `grid`; errors name `heights` (shape, a non-finite entry).
pub(crate) fn height_surface(
    grid: Grid,
    heights: &ndarray::Array2<f64>,
) -> Result<Surface, SceneError> {
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

/// What the approach path is built from besides `[protocol]`.
struct PathBody<'a> {
    grid: &'a Grid,
    surface: &'a Surface,
    /// The shape's own sphere ([`crate::shape::SceneShape::path_sphere`]): its radius and the
    /// shape the roughness's top is measured above.
    sphere: Option<(f64, &'a dyn Shape)>,
    /// Where that sphere's radius comes from (`SceneShape::path_radius_origin`).
    origin: &'static str,
    /// The radius a body in memory was given.
    given_radius: Option<f64>,
    /// Whether the body is only heights (`geometry.shape = "none"`: a map, an array), whose
    /// radius a least-squares paraboloid may find; a punch has none.
    heights_only: bool,
    material: crate::shape::Material,
    law: &'a AdhesionLaw,
}

/// The approach path of `[protocol]`: an indentation (`indent`), the given load–unload path
/// (`max_approach` with `load_step`), or the default pull-off path of a sphere-like body
/// ([`crate::pull_off_path`]) when neither is given.
fn approach_path(
    p: &Protocol,
    body: &PathBody<'_>,
) -> Result<(ApproachPath, Option<PathRule>), SceneError> {
    let first_touch = body.surface.min();
    let max_steps = p.max_steps.unwrap_or(DEFAULT_MAX_STEPS);
    let finite = |field: &str, v: f64| {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(SceneError::out_of_range(field, v, "a finite number"))
        }
    };
    // A finite-range law acts ahead of the surface: a path that stays out of contact but
    // within the law's reach is a path (the tension of the approach, a non-contact pull-off).
    let reach = body.law.reach(body.material.gamma);
    let nearest = first_touch - reach.unwrap_or(0.0);
    let never_touches = |field: &str, d: f64, step: f64| match reach {
        None => SceneError::Inconsistent(format!(
            "{field} = {d} never touches the surface: the first touch is at approach \
             {first_touch} (the lowest surface height); {field} must be > {first_touch}, e.g. {}",
            first_touch + step
        )),
        Some(reach) => SceneError::Inconsistent(format!(
            "{field} = {d} never comes within the law's reach of the surface: the first touch \
             is at approach {first_touch} (the lowest surface height) and the law reaches {} \
             ahead of it; {field} must be > {}",
            fields::rounded(reach),
            num(nearest)
        )),
    };
    if let Some(d) = p.indent {
        let others = [
            (fields::PROTOCOL_START, p.start.is_some()),
            (fields::PROTOCOL_MAX_APPROACH, p.max_approach.is_some()),
            (fields::PROTOCOL_LOAD_STEP, p.load_step.is_some()),
            (fields::PROTOCOL_UNLOAD_STEP, p.unload_step.is_some()),
            (
                fields::PROTOCOL_COARSE_UNLOAD_STEP,
                p.coarse_unload_step.is_some(),
            ),
            (fields::PROTOCOL_RETRACT_TO, p.retract_to.is_some()),
            (
                fields::PROTOCOL_REFINE_PULL_OFF,
                p.refine_pull_off.is_some(),
            ),
        ];
        if let Some((field, _)) = others.iter().find(|(_, given)| *given) {
            return Err(SceneError::Inconsistent(format!(
                "{indent} is one step pressed in with no retraction: leave out {field} \
                 (or drop {indent} for a load–unload path)",
                indent = fields::PROTOCOL_INDENT
            )));
        }
        let d = finite(fields::PROTOCOL_INDENT, d)?;
        if d <= nearest {
            return Err(never_touches(
                fields::PROTOCOL_INDENT,
                d,
                0.01 * body.grid.dx().max(first_touch.abs()),
            ));
        }
        let mut path = ApproachPath::indentation(d)?;
        path.max_steps = max_steps;
        return Ok((path, None));
    }
    let (max_approach, load_step, unload_step, coarse_unload_step) =
        match (p.max_approach, p.load_step) {
            (Some(max_approach), Some(load_step)) => {
                finite(fields::PROTOCOL_MAX_APPROACH, max_approach)?;
                finite(fields::PROTOCOL_LOAD_STEP, load_step)?;
                if load_step <= 0.0 {
                    return Err(SceneError::out_of_range(
                        fields::PROTOCOL_LOAD_STEP,
                        load_step,
                        "a finite number > 0",
                    ));
                }
                if max_approach <= nearest {
                    return Err(never_touches(
                        fields::PROTOCOL_MAX_APPROACH,
                        max_approach,
                        10.0 * load_step,
                    ));
                }
                (
                    max_approach,
                    load_step,
                    p.unload_step.unwrap_or(load_step),
                    p.coarse_unload_step,
                )
            }
            (None, Some(_)) => {
                return Err(SceneError::Inconsistent(format!(
                    "{max_approach} is required with {load_step} (the deepest approach); leave \
                     both out for the default pull-off path of a sphere",
                    load_step = fields::PROTOCOL_LOAD_STEP,
                    max_approach = fields::PROTOCOL_MAX_APPROACH
                )));
            }
            (depth, None) => return default_branch(p, body, depth, max_steps),
        };
    let path = ApproachPath {
        start: p
            .start
            .unwrap_or((first_touch + load_step).min(max_approach)),
        max_approach,
        load_step,
        unload_step,
        coarse_unload_step,
        refine_pull_off: p.refine_pull_off.unwrap_or(false),
        retract_to: p.retract_to,
        max_steps,
    };
    // A path whose load alone takes the default cap would stop before retracting (a cap the
    // scene sets is its own: a short look at the load).
    let load_steps = path.load_steps();
    if p.max_steps.is_none() && load_steps >= max_steps as f64 {
        return Err(SceneError::Inconsistent(format!(
            "the path loads from d = {} to {} in steps of {}: {} load steps, not fewer than the \
             default {max_steps_field} = {max_steps}, so it would stop before retracting; \
             raise {load_step}, or set {max_steps_field} (a cap of your own stops the run there)",
            fields::rounded(path.start),
            fields::rounded(path.max_approach),
            fields::rounded(path.load_step),
            fields::rounded(load_steps),
            max_steps_field = fields::PROTOCOL_MAX_STEPS,
            load_step = fields::PROTOCOL_LOAD_STEP,
        )));
    }
    Ok((path, None))
}

/// The default pull-off path (`[protocol]` without `load_step`): the rule of
/// [`crate::pull_off_path`] for a body with a radius, to the rule's depth or to
/// `protocol.max_approach` when given; a body without a radius needs `max_approach` and
/// `unload_step` (the coarse step is then [`crate::pull_off_path::COARSE_PER_UNLOAD_STEP`]
/// times the fine one). It loads in one step under the zero-range law and in steps from out of
/// range under a finite-range law ([`crate::pull_off_path::load_plan`]).
fn default_branch(
    p: &Protocol,
    body: &PathBody<'_>,
    depth: Option<f64>,
    max_steps: usize,
) -> Result<(ApproachPath, Option<PathRule>), SceneError> {
    if p.start.is_some() || p.retract_to.is_some() {
        return Err(SceneError::Inconsistent(format!(
            "{start} and {retract_to} need {max_approach} and {load_step} (the default pull-off \
             path sets its own)",
            start = fields::PROTOCOL_START,
            retract_to = fields::PROTOCOL_RETRACT_TO,
            max_approach = fields::PROTOCOL_MAX_APPROACH,
            load_step = fields::PROTOCOL_LOAD_STEP
        )));
    }
    let first_touch = body.surface.min();
    if let Some(d) = depth
        && d <= first_touch
    {
        return Err(SceneError::Inconsistent(format!(
            "{field} = {} never touches the surface: the first touch is at approach {} (the \
             lowest surface height); {field} must be greater",
            num(d),
            num(first_touch),
            field = fields::PROTOCOL_MAX_APPROACH
        )));
    }
    let rule = match (default_path(body, depth), depth, p.unload_step) {
        (Ok(rule), _, _) => Some(rule),
        // No radius, but the depth and the step are given: the path needs none.
        (Err(NoRule::NoRadius(_)), Some(_), Some(_)) => None,
        (Err(NoRule::NoRadius(_)), Some(_), None) => {
            return Err(SceneError::Inconsistent(format!(
                "{unload} is required with {max} when the body has no radius to set the \
                 retraction step (give {unload}, or {load} for a load–unload path)",
                unload = fields::PROTOCOL_UNLOAD_STEP,
                max = fields::PROTOCOL_MAX_APPROACH,
                load = fields::PROTOCOL_LOAD_STEP,
            )));
        }
        (Err(NoRule::NoRadius(e) | NoRule::Error(e)), _, _) => return Err(e),
    };
    // A path without a rule has its unload step (above).
    let unload = p
        .unload_step
        .or(rule.map(|r| r.path.unload_step))
        .unwrap_or_default();
    let coarse = match (p.coarse_unload_step, rule) {
        (Some(s), _) => s,
        (None, Some(r)) => r.path.coarse_unload_step,
        (None, None) => crate::pull_off_path::COARSE_PER_UNLOAD_STEP * unload,
    };
    let max_approach = depth
        .or(rule.map(|r| r.path.max_approach))
        .unwrap_or_default();
    // From where the law's tension is 1e-4 of the peak (a smooth law) or its range (Dugdale).
    let range = body.law.approach_reach(body.material.gamma);
    let length = body.law.curve().map(|c| c.length());
    let (start, load) =
        crate::pull_off_path::load_plan(first_touch, max_approach, (unload, coarse), range, length);
    // A law whose reach is many retraction steps long would spend every step the default cap
    // allows loading, and the result would hold no retraction at all (a cap the scene sets is
    // its own: a short look at the load is a run, stopped at the cap).
    let path = ApproachPath {
        start,
        max_approach,
        load_step: load,
        unload_step: unload,
        coarse_unload_step: Some(coarse),
        refine_pull_off: p.refine_pull_off.unwrap_or(false),
        retract_to: None,
        max_steps,
    };
    let load_steps = path.load_steps();
    if let Some(reach) = range
        && p.max_steps.is_none()
        && load_steps >= max_steps as f64
    {
        return Err(SceneError::Inconsistent(format!(
            "the default path loads from out of the law's reach ({} before the first touch) in \
             steps of {}: {} load steps, not fewer than the default \
             {max_steps} = {max_steps_value}, so it would never retract; give a path of your own \
             ({max_approach}, {load_step} and {unload_step}), raise {max_steps}, or shorten the \
             law's reach ({parameter})",
            fields::rounded(reach),
            fields::rounded(load),
            fields::rounded(load_steps),
            max_steps = fields::PROTOCOL_MAX_STEPS,
            max_steps_value = max_steps,
            max_approach = fields::PROTOCOL_MAX_APPROACH,
            load_step = fields::PROTOCOL_LOAD_STEP,
            unload_step = fields::PROTOCOL_UNLOAD_STEP,
            parameter = body.law.parameter().0,
        )));
    }
    let rule = rule.map(|rule| PathRule {
        path: crate::pull_off_path::PullOffPath {
            unload_step: unload,
            coarse_unload_step: coarse,
            max_approach,
            ..rule.path
        },
        stepped_load: range.is_some().then_some(load),
        refined: path.refine_pull_off,
        // Set with the solid (`PathRule::with_tail`).
        tail_step: None,
        ..rule
    });
    Ok((path, rule))
}

/// Why a body has no default pull-off rule: it has no radius (a message for when the path is
/// not given), or another error.
enum NoRule {
    NoRadius(SceneError),
    Error(SceneError),
}

impl From<SceneError> for NoRule {
    fn from(e: SceneError) -> Self {
        NoRule::Error(e)
    }
}

/// The default pull-off rule of a body: a sphere (`geometry.radius`, an ellipsoid's
/// √(RxRy)), a body in memory with a radius, or a body whose least-squares paraboloid is
/// sphere-like; refused, naming what is missing, without adhesion or without a radius. With
/// `depth`, the loaded contact at that depth is checked against the array instead of the
/// rule's.
fn default_path(body: &PathBody<'_>, depth: Option<f64>) -> Result<PathRule, NoRule> {
    let (e_star, gamma) = (body.material.e_star, body.material.gamma);
    if gamma <= 0.0 {
        return Err(NoRule::Error(SceneError::Inconsistent(format!(
            "{max_approach} is required: without adhesion ({gamma_field} = {}) there is no \
             pull-off to find, so there is no default path; for one state give {indent} = d (one \
             step pressed in to approach d), for a load–unload curve {max_approach} and \
             {load_step}",
            num(gamma),
            max_approach = fields::PROTOCOL_MAX_APPROACH,
            gamma_field = fields::MATERIAL_GAMMA,
            indent = fields::PROTOCOL_INDENT,
            load_step = fields::PROTOCOL_LOAD_STEP
        ))));
    }
    // A shape with a sphere of its own: its apex is at 0, the roughness on top of it.
    if let (Some((radius, shape)), false) = (body.sphere, body.heights_only) {
        let grid = body.grid;
        let top = body
            .surface
            .heights()
            .indexed_iter()
            .map(|((i, j), h)| h - shape.height(grid.x(i), grid.y(j)))
            .fold(f64::NEG_INFINITY, f64::max);
        return Ok(PathRule {
            stepped_load: None,
            refined: false,
            tail_step: None,
            radius,
            fitted: false,
            origin: body.origin,
            path: crate::pull_off_path::default_pull_off_path(
                e_star,
                gamma,
                radius,
                top,
                grid.dx(),
            ),
        });
    }
    if !body.heights_only {
        return Err(NoRule::NoRadius(SceneError::Inconsistent(format!(
            "{max} is required: the default pull-off path needs a sphere ({shape} = \"sphere\") \
             or a sphere-like height map on {shape} = \"none\"; a flat punch or a power-law \
             body has no radius to set its depth and steps; give {max} and {load}",
            max = fields::PROTOCOL_MAX_APPROACH,
            shape = fields::GEOMETRY_SHAPE,
            load = fields::PROTOCOL_LOAD_STEP,
        ))));
    }
    let heights = body.surface.heights();
    let dx = body.grid.dx();
    match body.given_radius {
        // Heights only, with the radius given (a body in memory): the paraboloid of that
        // radius through the heights finds the apex and the top of the roughness on it.
        Some(r) => {
            let fit =
                crate::pull_off_path::fit_paraboloid(heights, dx, Some(r)).ok_or_else(|| {
                    SceneError::Inconsistent(format!(
                        "{} is required: no paraboloid of radius {} fits the heights (fewer \
                         than 3 elements along an axis)",
                        fields::PROTOCOL_MAX_APPROACH,
                        num(r)
                    ))
                })?;
            Ok(finish_default_path(body, r, fit, false, depth)?)
        }
        None => match crate::pull_off_path::fit_paraboloid(heights, dx, None) {
            Some(f) if f.is_sphere_like(body.grid) => {
                Ok(finish_default_path(body, f.radius, f, true, depth)?)
            }
            fit => Err(NoRule::NoRadius(SceneError::Inconsistent(format!(
                "{max_approach} is required: the default pull-off path needs a sphere ({shape} = \
                 \"sphere\") or a sphere-like height map (its least-squares paraboloid curved \
                 away from the half-space, rising over the grid by at least half the roughness \
                 range){}; give {max_approach} and {load_step}",
                match fit {
                    None => " and no paraboloid fits (fewer than 3 elements along an axis, or \
                             no curvature)"
                        .to_owned(),
                    Some(f) => format!(
                        ", but the least-squares paraboloid has R = {} and rises less than half \
                         the roughness range {}",
                        num(crate::shape::round4(f.radius)),
                        num(crate::shape::round4(f.residual_range()))
                    ),
                },
                max_approach = fields::PROTOCOL_MAX_APPROACH,
                shape = fields::GEOMETRY_SHAPE,
                load_step = fields::PROTOCOL_LOAD_STEP
            )))),
        },
    }
}

/// The default path of a heights-only body whose paraboloid `fit` (radius `radius`) is known;
/// on a free grid the loaded contact must fit the array around the vertex.
fn finish_default_path(
    body: &PathBody<'_>,
    radius: f64,
    fit: crate::pull_off_path::Paraboloid,
    fitted: bool,
    depth: Option<f64>,
) -> Result<PathRule, SceneError> {
    let path = crate::pull_off_path::default_pull_off_path(
        body.material.e_star,
        body.material.gamma,
        radius,
        fit.apex + fit.residual_max,
        body.grid.dx(),
    );
    if body.grid.boundary() == Boundary::Free {
        crate::pull_off_path::check_contact_fits(
            body.surface.heights(),
            body.grid,
            radius,
            &fit,
            depth.unwrap_or(path.max_approach),
            body.surface.min(),
            body.material,
            body.law.reach(body.material.gamma),
        )?;
    }
    Ok(PathRule {
        stepped_load: None,
        refined: false,
        tail_step: None,
        radius,
        fitted,
        origin: "given",
        path,
    })
}

/// Refuses a scene whose run cannot fit the machine's memory (see [`crate::memory`]). With
/// `steps: None` only the working fields count (checked before the surface or anything else of
/// the grid's size is allocated); with the path's step bound, also its snapshots and records.
fn check_memory(
    scene: &Scene,
    grid: &Grid,
    steps: Option<usize>,
    gamma_array: bool,
) -> Result<(), SceneError> {
    let f = &scene.file;
    let (max_steps, request) = match steps {
        Some(n) => (n, (&f.output.snapshots).into()),
        None => (0, SnapshotRequest::None),
    };
    let mut estimate = crate::memory::estimate(grid, max_steps, &request);
    let a = &f.adhesion;
    if gamma_array
        || a.gamma_map.is_some()
        || a.pattern
            .is_some_and(|p| p != crate::scene::PatternKind::Uniform)
    {
        estimate.add_fields(crate::memory::GAMMA_MAP_FIELDS);
    }
    if f.protocol.refine_pull_off == Some(true) {
        estimate.add_fields(crate::memory::REFINED_STATE_FIELDS);
    }
    if let Some(arms) = &f.material.prony {
        estimate.add_fields(crate::memory::viscoelastic_fields(arms.len()));
    }
    let grid_field = if f.grid.n.is_some() {
        fields::GRID_N
    } else {
        GRID_NX_BY_NY
    };
    let snapshots = crate::scene::value_text(&f.output.snapshots.clone().into());
    let cap = f.protocol.max_steps.unwrap_or(DEFAULT_MAX_STEPS);
    let steps_from = if max_steps < cap {
        "the path's own step count".to_owned()
    } else {
        format!(
            "{} = {cap}, as retraction ends only when contact is lost",
            fields::PROTOCOL_MAX_STEPS
        )
    };
    crate::memory::check(
        &estimate,
        crate::memory::machine_memory(),
        grid_field,
        grid,
        max_steps,
        &steps_from,
        &snapshots,
    )
}

/// The zero-range law on a rough body loaded in more than one step from its first touch: the
/// approach bonds only what penetrates (no attraction ahead of the contact), so the pull-off
/// comes out below the finite-range law's, which tends to the one-step load's as λ grows
/// (README, "Loading history"; `cargo xtask study loading`).
fn loading_history_warning(
    law: &AdhesionLaw,
    gamma: f64,
    random: bool,
    path: &tack_solver::ApproachPath,
    first_touch: f64,
) -> Option<String> {
    let zero_range = matches!(law, AdhesionLaw::JkrLimit(_));
    let stepped = loaded_steps(path, first_touch, 2) > 1;
    (zero_range && gamma > 0.0 && random && stepped && !path.is_indentation())
        .then(|| {
            format!(
                "loading history: a randomly rough body loaded in several steps under the \
                 zero-range \
                 law bonds only where it penetrates, so its pull-off can lie well below the \
                 finite-range (Dugdale) answer, which approaches the one-step load's as the \
                 range shrinks (one rough sphere, eight seeds: 0.46 … 0.96 F_JKR loaded in 20 \
                 steps, 0.62 … 1.22 in one; README \"Loading history\"); load in one step ({start} = {max}) or use \
                 {model} = \"dugdale\"",
                start = fields::PROTOCOL_START,
                max = fields::PROTOCOL_MAX_APPROACH,
                model = fields::ADHESION_MODEL,
            )
        })
}

/// Checks that the scales a run derives from its inputs are finite, normal floating-point
/// numbers: the element area Δx², the detachment stress σ_c = sqrt(E*γ/(κΔx)), and for spheres
/// F_JKR, d_JKR and a_c. Huge or tiny inputs (E* = 1e308, Δx = 1e-160) pass their own range
/// checks but overflow or underflow here, and a run would end in NaN or subnormal forces; the
/// error names the input fields the failing scale comes from.
fn check_scales(
    material: crate::shape::Material,
    grid: &Grid,
    shape: &dyn crate::shape::SceneShape,
    kappa: f64,
) -> Result<(), SceneError> {
    let (e_star, gamma) = (material.e_star, material.gamma);
    let dx = grid.dx();
    let normal = |name: &str, value: f64, inputs: &str| {
        if value.is_normal() && value.abs() < 1e300 {
            Ok(())
        } else {
            // Never `inf` or `0` in the message: say what happened to the number.
            let value = if value.is_infinite() {
                "an overflow (beyond 1.8e308)".to_owned()
            } else if value == 0.0 {
                "an underflow (below 5e-324, rounded to 0)".to_owned()
            } else {
                num(value)
            };
            Err(SceneError::Inconsistent(format!(
                "{inputs} give {name} = {value}, outside what double precision can carry \
                 through a run (finite, between 1e-300 and 1e300 in magnitude); rescale the \
                 units of the scene (e.g. mm and MPa instead of m and Pa)"
            )))
        }
    };
    normal(
        "the element area Δx²",
        dx * dx,
        &format!("{} = {}", fields::GRID_DX, num(dx)),
    )?;
    normal(
        "the stiffness scale E*·Δx",
        e_star * dx,
        &format!(
            "{e_star_field} = {} and {dx_field} = {}",
            num(e_star),
            num(dx),
            e_star_field = fields::MATERIAL_E_STAR,
            dx_field = fields::GRID_DX
        ),
    )?;
    // (An invalid κ is refused, naming solver.kappa, after this.)
    if gamma > 0.0 && kappa.is_finite() && kappa > 0.0 {
        let sigma_c = (e_star * gamma / (kappa * dx)).sqrt();
        normal(
            "σ_c = sqrt(E*γ/(κΔx))",
            sigma_c,
            &format!(
                "{e_star_field} = {}, {gamma_field} = {} and {dx_field} = {}",
                num(e_star),
                num(gamma),
                num(dx),
                e_star_field = fields::MATERIAL_E_STAR,
                gamma_field = fields::MATERIAL_GAMMA,
                dx_field = fields::GRID_DX
            ),
        )?;
        normal(
            "the adhesive force per element σ_c·Δx²",
            sigma_c * dx * dx,
            &format!(
                "{e_star_field} = {}, {gamma_field} = {} and {dx_field} = {}",
                num(e_star),
                num(gamma),
                num(dx),
                e_star_field = fields::MATERIAL_E_STAR,
                gamma_field = fields::MATERIAL_GAMMA,
                dx_field = fields::GRID_DX
            ),
        )?;
        if let Some((scales, inputs)) = shape.scales(material) {
            for (name, value) in scales {
                normal(name, value, &inputs)?;
            }
        }
    }
    Ok(())
}

/// The roughness band with the paper's defaults: `q0 = 2π/L` (longer side), `q1 = π/Δx`.
pub fn band(grid: &Grid, q0: Option<f64>, q1: Option<f64>) -> (f64, f64) {
    let d = RoughSpec::paper_defaults(*grid, 0.0, 0.5, 0);
    (q0.unwrap_or(d.q0), q1.unwrap_or(d.q1))
}

/// The paper's random roughness on `grid` (band `q0 = 2π/L` … `q1 = π/Δx`, Hurst exponent
/// `hurst`, phases from `seed`) with the rms height that gives the adhesion parameter
/// `alpha_star` for material `e_star`, `gamma` (Eq. 11 inverted, `docs/theory.md` §7.2).
///
/// ```
/// use tack::geometry::{Boundary, Grid};
/// let grid = Grid::square(128, 1.0 / 128.0, Boundary::Free)?;
/// let spec = tack::problem::rough_spec_for_alpha_star(grid, 1.0, 1e-4, 0.3, 0.5, 7)?;
/// let a = tack::analytics::alpha_star(1.0, 1e-4, spec.rms, 0.5, spec.q0, spec.q1);
/// assert!((a - 0.3).abs() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn rough_spec_for_alpha_star(
    grid: Grid,
    e_star: f64,
    gamma: f64,
    alpha_star: f64,
    hurst: f64,
    seed: u64,
) -> Result<RoughSpec, SceneError> {
    let positive = |field: &str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(SceneError::OutOfRange {
                field: field.into(),
                value: v.to_string(),
                allowed: "a finite number > 0".into(),
            })
        }
    };
    positive(fields::MATERIAL_E_STAR, e_star)?;
    positive(fields::MATERIAL_GAMMA, gamma)?;
    positive("alpha_star", alpha_star)?;
    if !(hurst > 0.0 && hurst < 1.0) {
        return Err(SceneError::OutOfRange {
            field: fields::ROUGHNESS_HURST.into(),
            value: hurst.to_string(),
            allowed: "0 < H < 1".into(),
        });
    }
    let mut spec = RoughSpec::paper_defaults(grid, 0.0, hurst, seed);
    spec.rms = tack_analytics::rms_height_from_alpha_star(
        e_star, gamma, alpha_star, hurst, spec.q0, spec.q1,
    );
    Ok(spec)
}

fn count(field: &str, n: usize) -> Result<usize, SceneError> {
    if (1..=MAX_ELEMENTS_PER_AXIS).contains(&n) {
        Ok(n)
    } else {
        Err(SceneError::out_of_range(
            field,
            n,
            "an integer in 1..=65536",
        ))
    }
}

/// Largest number of elements per axis the geometry crate accepts (`grid.rs` there).
const MAX_ELEMENTS_PER_AXIS: usize = 1 << 16;

fn build_grid(g: &GridSpec) -> Result<Grid, SceneError> {
    let (nx, ny) = match (g.n, g.nx, g.ny) {
        (Some(n), None, None) => {
            let n = count(fields::GRID_N, n)?;
            (n, n)
        }
        (None, Some(nx), Some(ny)) => (count(fields::GRID_NX, nx)?, count(fields::GRID_NY, ny)?),
        (Some(_), _, _) => {
            return Err(SceneError::Inconsistent(
                "grid: give either `n` (square grid) or both `nx` and `ny`, not both forms".into(),
            ));
        }
        _ => {
            return Err(SceneError::Inconsistent(
                "grid: give either `n` (square grid) or both `nx` and `ny`".into(),
            ));
        }
    };
    if nx * ny > MAX_ELEMENTS {
        let field = if g.n.is_some() {
            fields::GRID_N
        } else {
            GRID_NX_BY_NY
        };
        return Err(SceneError::Inconsistent(format!(
            "{field} = {nx} × {ny} is too large: {} elements exceed the limit of {MAX_ELEMENTS} \
             (8192 × 8192)",
            nx * ny
        )));
    }
    let dx = match (g.dx, g.length) {
        (Some(dx), None) => dx,
        (None, Some(length)) => {
            if !(length.is_finite() && length > 0.0) {
                return Err(SceneError::out_of_range(
                    fields::GRID_LENGTH,
                    length,
                    "a finite number > 0",
                ));
            }
            length / nx as f64
        }
        (Some(_), Some(_)) => {
            return Err(SceneError::Inconsistent(
                "grid: give exactly one of `dx` and `length` (found both)".into(),
            ));
        }
        (None, None) => {
            return Err(SceneError::Inconsistent(
                "grid: give exactly one of `dx` (element size) and `length` (domain length along x)"
                    .into(),
            ));
        }
    };
    let boundary = match g.boundary {
        BoundaryKind::Free => Boundary::Free,
        BoundaryKind::Periodic => Boundary::Periodic,
    };
    Ok(Grid::new(nx, ny, dx, boundary)?)
}

fn add_roughness(
    surface: &mut Surface,
    roughness: &Roughness,
    base_dir: &Path,
    spec: &GridSpec,
    seed: &mut Option<u64>,
) -> Result<(), SceneError> {
    let grid = *surface.grid();
    match roughness {
        Roughness::Waviness1d { h, lambda } => {
            let w = Waviness1d::new(*h, *lambda)?;
            check_wavelength(&grid, *lambda, false)?;
            surface.add_shape(&w);
        }
        Roughness::Waviness2d { h, lambda } => {
            let w = Waviness2d::new(*h, *lambda)?;
            check_wavelength(&grid, *lambda, true)?;
            surface.add_shape(&w);
        }
        Roughness::Random {
            h,
            hurst,
            q0,
            q1,
            seed: s,
        } => {
            let (q0, q1) = band(&grid, *q0, *q1);
            let rough = rough_surface(
                grid,
                &RoughSpec {
                    rms: *h,
                    hurst: *hurst,
                    q0,
                    q1,
                    seed: *s,
                },
            )?;
            surface.add(&rough)?;
            *seed = Some(*s);
        }
        Roughness::File { path, dataset } => {
            let full = base_dir.join(path);
            let names = (fields::ROUGHNESS_PATH, fields::ROUGHNESS_DATASET);
            let heights = read_map(&full, path, dataset.as_deref(), &grid, names)?;
            let (nx, ny) = heights.dim();
            if (nx, ny) != grid.shape() {
                return Err(SceneError::Inconsistent(format!(
                    "{path_field} = `{}`: the height map is {nx} × {ny} but the grid is {} × {} \
                     ({}); the map must have the grid's shape",
                    path.display(),
                    grid.nx(),
                    grid.ny(),
                    if spec.n.is_some() {
                        fields::GRID_N
                    } else {
                        GRID_NX_BY_NY
                    },
                    path_field = fields::ROUGHNESS_PATH
                )));
            }
            surface.add(&Surface::new(grid, heights)?)?;
        }
    }
    Ok(())
}

/// A waviness must span at least [`MIN_ELEMENTS_PER_WAVELENGTH`] elements; on a periodic grid
/// the period must hold a whole number of wavelengths (along x; and along y for 2D waviness).
fn check_wavelength(grid: &Grid, lambda: f64, two_d: bool) -> Result<(), SceneError> {
    let min = MIN_ELEMENTS_PER_WAVELENGTH * grid.dx();
    if lambda < min * (1.0 - 1e-12) {
        return Err(SceneError::Inconsistent(format!(
            "{lambda_field} = {lambda} is invalid: must be ≥ 4·{dx_field} = {min} to be resolved \
             ({dx_field} = {})",
            grid.dx(),
            lambda_field = fields::ROUGHNESS_LAMBDA,
            dx_field = fields::GRID_DX
        )));
    }
    if grid.boundary() == Boundary::Periodic {
        let mut sides = vec![("x", grid.lx())];
        if two_d {
            sides.push(("y", grid.ly()));
        }
        for (axis, length) in sides {
            let waves = length / lambda;
            if (waves - waves.round()).abs() > 1e-6 * waves.max(1.0) || waves.round() < 1.0 {
                return Err(SceneError::Inconsistent(format!(
                    "{lambda_field} = {lambda} does not fit the periodic grid: the period along \
                     {axis} is {length} = {waves} wavelengths; it must be a whole number ≥ 1 \
                     (adjust {dx_field}, {n_field}/nx/ny or {lambda_field})",
                    lambda_field = fields::ROUGHNESS_LAMBDA,
                    dx_field = fields::GRID_DX,
                    n_field = fields::GRID_N
                )));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
