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
    Boundary, Ellipsoid, FlatPunch, Grid, RoughSpec, Shape, Sphere, Surface, Waviness1d,
    Waviness2d, Window, rough_surface,
};
use tack_solver::{
    AdhesionLaw, AdhesiveOptions, AdhesiveSolver, ApproachPath, KAPPA, SnapshotRequest,
    contact_window,
};

use crate::scene::{
    AdhesionModel, BoundaryKind, DEFAULT_MAX_STEPS, Geometry, GridSpec, Protocol, PunchKind,
    Roughness, Scene, SceneError, SceneSchema, num,
};

pub use crate::map_file::DX_MATCH_TOLERANCE;
pub(crate) use crate::map_file::read_map;

pub use crate::pull_off_path::SPHERE_FIT_MARGIN;

/// Largest number of grid elements `nx·ny` a scene may ask for (8192 × 8192): beyond it the
/// solver's fields and FFT buffers would not fit in memory, and the run would abort instead of
/// failing with a message.
pub const MAX_ELEMENTS: usize = 1 << 26;

/// The accepted range of `solver.tolerance` (relative CG residual), both ends included.
pub const TOLERANCE_RANGE: (f64, f64) = (1e-14, 1e-1);

/// The grid's size field when it is given as `nx` and `ny`.
const GRID_NX_BY_NY: &str = concat!(field_name!(grid.nx), " × ", field_name!(grid.ny));

/// Greatest ratio of an ellipsoid's radii: beyond it the elliptic Hertz and JKR references lose
/// their digits (the eccentricity rounds to 1).
pub const MAX_ELLIPSOID_RATIO: f64 = 1e6;

/// Smallest wavelength, in elements, a waviness may have.
pub const MIN_ELEMENTS_PER_WAVELENGTH: f64 = 4.0;

/// Closed-form reference values for the summary; `None` where they do not apply.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct References {
    /// JKR pull-off force −(3/2)πγR of the smooth sphere (Eq. 7), spheres only.
    pub f_jkr: Option<f64>,
    /// Approach at the JKR pull-off (Eq. 8), spheres only.
    pub d_jkr: Option<f64>,
    /// Johnson's parameter α (Eq. 3) of a waviness.
    pub johnson_alpha: Option<f64>,
    /// The adhesion parameter α* (Eq. 11) of random roughness.
    pub alpha_star: Option<f64>,
    /// Dugdale law on a sphere: the Maugis parameter λ = 2σ0 (R/(πγK²))^(1/3), K = 4E*/3.
    pub maugis_lambda: Option<f64>,
    /// Dugdale law on a sphere: the Maugis–Dugdale pull-off force under approach control.
    pub f_maugis: Option<f64>,
    /// Kendall's pull-off force −sqrt(8πa³E*γ) (signed: tensile) of a circular punch.
    pub f_kendall: Option<f64>,
    /// The exact JKR-limit pull-off force of a power-law body c·r^m on a free grid (method of
    /// dimensionality reduction; `tack_analytics::power_law_pull_off_force`).
    pub f_mdr: Option<f64>,
    /// The approximate (Johnson–Greenwood) JKR pull-off force of an ellipsoid under approach
    /// control, signed (tensile negative): `tack_analytics::elliptic_jkr_pull_off`.
    pub f_elliptic: Option<f64>,
    /// Mean pressure of complete non-adhesive contact of a waviness: p*_1D = πE*h/λ (Eq. 2)
    /// or p*_2D = √2πE*h/λ (Eq. 5).
    pub p_star: Option<f64>,
}

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
    /// The adhesion law (`[adhesion]`): the zero-range criterion with [`Problem::kappa`], or a
    /// Dugdale cohesive zone.
    pub law: AdhesionLaw,
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
    /// Where the path came from when `[protocol]` left it to the default pull-off rule
    /// ([`crate::pull_off_path`]); `None` when the scene gave it.
    pub path_rule: Option<PathRule>,
}

/// The default pull-off path a scene without `protocol.max_approach` got, and the radius it
/// was derived from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathRule {
    /// The sphere's radius R.
    pub radius: f64,
    /// Whether R was fitted (a least-squares paraboloid through the heights) rather than given.
    pub fitted: bool,
    /// The rule's numbers.
    pub path: crate::pull_off_path::PullOffPath,
    /// Loaded in retraction steps from out of range (a finite-range law), not in one step.
    pub stepped_load: bool,
    /// The refined retraction (`protocol.refine_pull_off`): coarse steps all the way.
    pub refined: bool,
}

impl std::fmt::Display for PathRule {
    /// One line: `default pull-off path of R = 1 (given): d_s = …, load to …, retract by …`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let p = &self.path;
        write!(
            f,
            "default pull-off path of R = {} ({}), d_s = {}: {} to d = {}, retraction by {} {}, \
             {} {}",
            num(self.radius),
            if self.fitted { "fitted" } else { "given" },
            num(p.d_s),
            if self.stepped_load {
                "loaded in retraction steps from out of range"
            } else {
                "one load step"
            },
            num(p.max_approach),
            num(p.coarse_unload_step),
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
            num(p.unload_step)
        )
    }
}

/// Least pull-off contact radius over element size, a_c/Δx (JKR radius for spheres, the punch
/// radius for circular punches), below which a run is flagged as under-resolved: the
/// detachment criterion's error grows like Δx/a_c and is +33% at 5 (`docs/theory.md` §9).
pub const MIN_PULL_OFF_RADIUS_ELEMENTS: f64 = 5.0;

/// Least number of grid elements a periodic cell must span along each side, measured in
/// pull-off contact diameters 2a_c, for the isolated sphere's F_JKR to be the reference: a
/// closer neighbour (the periodic image) changes the pull-off.
pub const MIN_PERIOD_CONTACT_DIAMETERS: f64 = 2.0;

impl Problem {
    /// Validates `scene` and builds grid, surface and path.
    pub fn from_scene(scene: &Scene) -> Result<Self, SceneError> {
        Self::build(scene, None)
    }

    /// The one problem builder: [`Problem::from_scene`], and with `body` its heights added to
    /// the scene's body, their roughness range added to the crop rule's and their radius giving
    /// the JKR references (`crate::heights`: bodies held in memory).
    pub(crate) fn build(scene: &Scene, body: Option<&HeightBody<'_>>) -> Result<Self, SceneError> {
        let f = &scene.file;
        let (e_star, gamma) = (f.material.e_star, f.material.gamma);
        if !(e_star.is_finite() && e_star > 0.0) {
            return Err(tack_kernels::KernelError::Modulus(e_star).into());
        }
        if !(gamma.is_finite() && gamma >= 0.0) {
            return Err(SceneError::out_of_range(
                fields::MATERIAL_GAMMA,
                gamma,
                "a finite number ≥ 0",
            ));
        }
        let grid = build_grid(&f.grid)?;
        // The working fields before anything of the grid's size is allocated; the snapshots
        // and records once the path's step count is known.
        let gamma_array = body.is_some_and(|b| b.gamma.is_some());
        check_memory(scene, &grid, None, gamma_array)?;
        let mut surface = base_surface(grid, &f.geometry)?;
        let mut seed = None;
        let mut references = References::default();
        let mut roughness_range = 0.0;
        if let Some(roughness) = &f.roughness {
            let smooth = surface.heights().clone();
            add_roughness(&mut surface, roughness, &scene.base_dir, &f.grid, &mut seed)?;
            let rough = surface.heights() - &smooth;
            roughness_range = rough.iter().copied().fold(f64::NEG_INFINITY, f64::max)
                - rough.iter().copied().fold(f64::INFINITY, f64::min);
            references.johnson_alpha = match *roughness {
                Roughness::Waviness1d { h, lambda } | Roughness::Waviness2d { h, lambda } => {
                    Some(tack_analytics::johnson_alpha(e_star, gamma, h, lambda))
                }
                _ => None,
            };
            references.p_star = match *roughness {
                Roughness::Waviness1d { h, lambda } => {
                    Some(tack_analytics::westergaard_p_star(e_star, h, lambda))
                }
                Roughness::Waviness2d { h, lambda } => {
                    Some(tack_analytics::johnson_2d_p_star(e_star, h, lambda))
                }
                _ => None,
            };
            if let Roughness::Random {
                h, hurst, q0, q1, ..
            } = *roughness
            {
                let (q0, q1) = band(&grid, q0, q1);
                references.alpha_star =
                    Some(tack_analytics::alpha_star(e_star, gamma, h, hurst, q0, q1));
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
            e_star,
            gamma,
            &grid,
            &f.geometry,
            f.solver.kappa.unwrap_or(KAPPA),
        )?;
        let dx = grid.dx();
        match f.geometry {
            Geometry::Sphere { radius } if gamma > 0.0 => {
                let a_c = tack_analytics::jkr_pull_off_radius(e_star, gamma, radius);
                let (lx, ly) = (grid.lx(), grid.ly());
                let span = lx.min(ly) / (2.0 * a_c);
                if grid.nx() == 1 || grid.ny() == 1 {
                    warnings.push(format!(
                        "no F_JKR reference: a sphere on a {} × {} grid is a strip of spheres, \
                         not the isolated sphere of Eq. 7",
                        grid.nx(),
                        grid.ny()
                    ));
                } else if grid.boundary() == Boundary::Periodic
                    && span < MIN_PERIOD_CONTACT_DIAMETERS
                {
                    warnings.push(format!(
                        "no F_JKR reference: the periodic cell {lx:.4e} × {ly:.4e} spans \
                         {span:.2} pull-off contact diameters 2a_c = {:.4e} (at least \
                         {MIN_PERIOD_CONTACT_DIAMETERS} for the isolated sphere of Eq. 7)",
                        2.0 * a_c
                    ));
                } else {
                    references.f_jkr = Some(tack_analytics::jkr_pull_off_force(gamma, radius));
                    references.d_jkr =
                        Some(tack_analytics::jkr_pull_off_approach(e_star, gamma, radius));
                }
                under_resolved(
                    &mut warnings,
                    "the JKR pull-off contact radius a_c",
                    a_c,
                    dx,
                );
            }
            Geometry::FlatPunch {
                punch: PunchKind::Circle,
                radius: Some(a),
                ..
            } if gamma > 0.0 => {
                references.f_kendall = Some(-tack_analytics::kendall_pull_off(e_star, gamma, a));
                under_resolved(&mut warnings, "the punch radius a", a, dx);
            }
            Geometry::Ellipsoid { radius_x, radius_y } if gamma > 0.0 => {
                let jg = tack_analytics::elliptic_jkr_pull_off(e_star, gamma, radius_x, radius_y)
                    .approach_control;
                if grid.nx() == 1 || grid.ny() == 1 || grid.boundary() == Boundary::Periodic {
                    warnings.push(format!(
                        "no F_JG reference: the elliptic JKR approximation is for one body on a \
                         free {} × {} grid, not a strip or a periodic array",
                        grid.nx(),
                        grid.ny()
                    ));
                } else if jg.force.is_normal() {
                    references.f_elliptic = Some(jg.force);
                }
                under_resolved(
                    &mut warnings,
                    "the elliptic pull-off contact's shorter semi-axis",
                    jg.semi_axis_x.min(jg.semi_axis_y),
                    dx,
                );
            }
            Geometry::PowerLaw { c, exponent } if gamma > 0.0 => {
                let a_f = tack_analytics::power_law_pull_off_radius(e_star, gamma, c, exponent);
                let f = tack_analytics::power_law_pull_off_force(e_star, gamma, c, exponent);
                if grid.nx() == 1 || grid.ny() == 1 || grid.boundary() == Boundary::Periodic {
                    warnings.push(format!(
                        "no F_MDR reference: the power-law body's closed form is for one body on \
                         a free {} × {} grid, not a strip or a periodic array",
                        grid.nx(),
                        grid.ny()
                    ));
                } else if f.is_normal() && a_f.is_normal() {
                    references.f_mdr = Some(f);
                }
                under_resolved(
                    &mut warnings,
                    "the power law's pull-off radius a_F",
                    a_f,
                    dx,
                );
            }
            _ => {}
        }
        if let Some(r) = body_radius
            && gamma > 0.0
        {
            references.f_jkr = Some(tack_analytics::jkr_pull_off_force(gamma, r));
            references.d_jkr = Some(tack_analytics::jkr_pull_off_approach(e_star, gamma, r));
        }

        let first_touch = surface.min();
        let kappa = f.solver.kappa.unwrap_or(KAPPA);
        if !(kappa.is_finite() && kappa > 0.0) {
            return Err(SceneError::out_of_range(
                fields::SOLVER_KAPPA,
                kappa,
                "a finite number > 0",
            ));
        }
        let law = adhesion_law(f, kappa, &surface)?;
        let sphere_radius = match f.geometry {
            Geometry::Sphere { radius } => Some(radius),
            // The default path of the sphere of the same Gaussian curvature.
            Geometry::Ellipsoid { radius_x, radius_y } => Some(radius_x.sqrt() * radius_y.sqrt()),
            _ => body_radius,
        };
        let (path, path_rule) = approach_path(
            &f.protocol,
            &PathBody {
                grid: &grid,
                surface: &surface,
                sphere_radius,
                ellipsoid: match f.geometry {
                    Geometry::Ellipsoid { radius_x, radius_y } => {
                        Some(Ellipsoid::new(radius_x, radius_y)?)
                    }
                    _ => None,
                },
                heights_only: matches!(f.geometry, Geometry::None),
                e_star,
                gamma,
                law,
            },
        )?;
        path.validate()?;
        // A radius fitted for the default path gives the references too (as for heights).
        if let Some(rule) = path_rule.filter(|r| r.fitted && gamma > 0.0)
            && references.f_jkr.is_none()
        {
            references.f_jkr = Some(tack_analytics::jkr_pull_off_force(gamma, rule.radius));
            references.d_jkr = Some(tack_analytics::jkr_pull_off_approach(
                e_star,
                gamma,
                rule.radius,
            ));
        }
        check_fits(
            &f.grid,
            &grid,
            &f.geometry,
            &path,
            first_touch,
            path_rule.is_some(),
            layer.is_some(),
        )?;
        check_memory(scene, &grid, Some(path.step_bound()), gamma_array)?;
        // Random roughness and height arrays (measured surfaces); not waviness, whose
        // figures load in steps on purpose and whose contact is one patch per period.
        let span = surface.max() - surface.min();
        let random = matches!(
            f.roughness,
            Some(Roughness::Random { .. } | Roughness::File { .. })
        ) || body.is_some_and(|b| b.roughness_range.is_none_or(|r| r > 1e-9 * span));
        warnings.extend(loading_history_warning(
            law,
            gamma,
            random,
            &path,
            first_touch,
        ));

        let defaults = AdhesiveOptions::default();
        let s = &f.solver;
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
            ..defaults
        };
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
        options.cg.validate()?;
        if options.max_active_set_iterations == 0 {
            return Err(SceneError::out_of_range(
                fields::SOLVER_MAX_ACTIVE_SET_ITERATIONS,
                0,
                "an integer ≥ 1",
            ));
        }
        if let AdhesionLaw::Dugdale { sigma0 } = law {
            dugdale_references(&mut references, &mut warnings, e_star, gamma, sigma0, &grid);
        }
        if let Some(layer) = &layer {
            let named: Vec<&str> = [
                ("F_JKR", references.f_jkr.is_some()),
                ("d_JKR", references.d_jkr.is_some()),
                ("F_Maugis", references.f_maugis.is_some()),
                ("F_Kendall", references.f_kendall.is_some()),
                ("F_MDR", references.f_mdr.is_some()),
                ("F_JG", references.f_elliptic.is_some()),
                ("p*", references.p_star.is_some()),
                ("Johnson's α", references.johnson_alpha.is_some()),
                ("α*", references.alpha_star.is_some()),
            ]
            .into_iter()
            .filter_map(|(n, on)| on.then_some(n))
            .collect();
            if !named.is_empty() {
                warnings.push(format!(
                    "the closed-form references ({}) are the half-space's: the layer of {} = {} \
                     changes them, so the ratios measure the film's effect, not the error",
                    named.join(", "),
                    fields::BODY_THICKNESS,
                    num(layer.thickness)
                ));
            }
            if gamma > 0.0
                && matches!(law, AdhesionLaw::JkrLimit { .. })
                && layer.thickness < crate::layer::MIN_ADHESIVE_THICKNESS_PER_DX * dx
            {
                warnings.push(format!(
                    "under-resolved film: {} = {} spans fewer than {} elements; the criterion's κ \
                     was calibrated on the half-space and on films of 10 elements and more; \
                     refine {}",
                    fields::BODY_THICKNESS,
                    num(layer.thickness),
                    crate::layer::MIN_ADHESIVE_THICKNESS_PER_DX,
                    fields::GRID_DX
                ));
            }
        }
        // A cohesive zone loads elements up to the range above the contact: the crop keeps them.
        let range = match law {
            AdhesionLaw::Dugdale { sigma0 } => gamma / sigma0,
            AdhesionLaw::JkrLimit { .. } => 0.0,
        };
        // The reach of adhesion grows with γ: a map crops for its greatest.
        let gamma_max = gamma_map
            .as_ref()
            .map_or(gamma, |m| crate::gamma_map::map_range(m).2.max(gamma));
        // The crop's reach is the half-space's; a film bulges beyond it, so it runs uncropped.
        let window = if f.grid.crop && layer.is_none() {
            contact_window(
                &surface,
                path.max_approach,
                roughness_range + range,
                e_star,
                gamma_max,
            )
            .filter(|w| w.shape() != grid.shape())
        } else {
            None
        };
        Ok(Self {
            grid,
            surface,
            e_star,
            gamma,
            gamma_map,
            layer,
            kappa,
            law,
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
            path_rule,
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
            AdhesiveSolver::with_law(op, &surface, self.gamma, self.law, self.options)?;
        if let Some(map) = &self.gamma_map {
            let view = match window {
                Some(w) => map.slice(ndarray::s![w.i0..w.i1, w.j0..w.j1]),
                None => map.view(),
            };
            solver.set_gamma_map(view)?;
        }
        Ok(solver)
    }
}

/// Least length of a Dugdale cohesive zone, in elements, below which a result is flagged: the
/// zone's tension is then carried by a ring of elements too thin to shape it.
pub const MIN_COHESIVE_ZONE_ELEMENTS: f64 = 2.0;

/// The length `πE*γ/(4σ0²)` of the cohesive zone ahead of a straight crack under the Dugdale law
/// (Griffith's `K² = 2E*γ` in `l = (π/8)(K/σ0)²`): what the mesh must resolve.
pub fn cohesive_zone_length(e_star: f64, gamma: f64, sigma0: f64) -> f64 {
    std::f64::consts::PI * e_star * gamma / (4.0 * sigma0 * sigma0)
}

/// The Dugdale law's references and warnings: λ and the Maugis–Dugdale pull-off of a sphere
/// (its radius read back from F_JKR),
/// and a zone narrower than [`MIN_COHESIVE_ZONE_ELEMENTS`].
fn dugdale_references(
    references: &mut References,
    warnings: &mut Vec<String>,
    e_star: f64,
    gamma: f64,
    sigma0: f64,
    grid: &Grid,
) {
    if let Some(f_jkr) = references.f_jkr {
        let radius = -f_jkr / (1.5 * std::f64::consts::PI * gamma);
        references.maugis_lambda =
            Some(tack_analytics::maugis_lambda(e_star, gamma, radius, sigma0));
        references.f_maugis = Some(tack_analytics::maugis_pull_off(
            e_star, gamma, radius, sigma0,
        ));
    }
    let zone = cohesive_zone_length(e_star, gamma, sigma0);
    let elements = zone / grid.dx();
    if elements < MIN_COHESIVE_ZONE_ELEMENTS {
        warnings.push(format!(
            "under-resolved cohesive zone: its length πE*γ/(4σ0²) = {} spans {} elements (at \
             least {MIN_COHESIVE_ZONE_ELEMENTS} needed); the Dugdale law then acts element by \
             element and the forces depend on the mesh (refine {dx} or lower {sigma0_field})",
            num(zone),
            num((elements * 100.0).round() / 100.0),
            dx = fields::GRID_DX,
            sigma0_field = fields::ADHESION_SIGMA0,
        ));
    }
}

/// The adhesion law of `[adhesion]`, checked: `sigma0` only with, and always with, the Dugdale
/// model; `solver.kappa` only with the zero-range criterion; a Dugdale range `γ/σ0` above the
/// round-off of the heights.
fn adhesion_law(f: &SceneSchema, kappa: f64, surface: &Surface) -> Result<AdhesionLaw, SceneError> {
    let model = fields::ADHESION_MODEL;
    match (f.adhesion.model, f.adhesion.sigma0) {
        (AdhesionModel::JkrLimit, None) => Ok(AdhesionLaw::JkrLimit { kappa }),
        (AdhesionModel::JkrLimit, Some(s)) => Err(SceneError::Inconsistent(format!(
            "{sigma0} = {} is read by the Dugdale law only: set {model} = \"dugdale\" or leave \
             {sigma0} out (the default {model} = \"jkr_limit\" has zero range)",
            num(s),
            sigma0 = fields::ADHESION_SIGMA0,
        ))),
        (AdhesionModel::Dugdale, None) => Err(SceneError::Inconsistent(format!(
            "{sigma0} is required with {model} = \"dugdale\": the cohesive tension σ0 > 0 (the \
             range is {gamma}/σ0)",
            sigma0 = fields::ADHESION_SIGMA0,
            gamma = fields::MATERIAL_GAMMA,
        ))),
        (AdhesionModel::Dugdale, Some(sigma0)) => {
            if f.solver.kappa.is_some() {
                return Err(SceneError::Inconsistent(format!(
                    "{kappa} is the zero-range criterion's constant; {model} = \"dugdale\" does \
                     not read it: leave it out",
                    kappa = fields::SOLVER_KAPPA,
                )));
            }
            let gamma = f.material.gamma;
            if gamma <= 0.0 {
                return Err(SceneError::Inconsistent(format!(
                    "{model} = \"dugdale\" needs {gamma_field} > 0 (the range is γ/σ0); got {}",
                    num(gamma),
                    gamma_field = fields::MATERIAL_GAMMA,
                )));
            }
            // σ0 > 0 and a range above the round-off of the heights: the solver's own check.
            AdhesionLaw::Dugdale { sigma0 }.check(gamma, surface)?;
            Ok(AdhesionLaw::Dugdale { sigma0 })
        }
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
    /// The sphere's radius (`geometry.radius`, or the radius of a body given in memory; an
    /// ellipsoid's √(RxRy)).
    sphere_radius: Option<f64>,
    /// The ellipsoid whose shape the roughness sits on, when the body is one.
    ellipsoid: Option<Ellipsoid>,
    /// Whether the body is only heights (`geometry.shape = "none"`: a map, an array), whose
    /// radius a least-squares paraboloid may find; a punch has none.
    heights_only: bool,
    e_star: f64,
    gamma: f64,
    law: AdhesionLaw,
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
    let never_touches = |field: &str, d: f64, step: f64| {
        SceneError::Inconsistent(format!(
            "{field} = {d} never touches the surface: the first touch is at approach \
             {first_touch} (the lowest surface height); {field} must be > {first_touch}, e.g. {}",
            first_touch + step
        ))
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
        if d <= first_touch {
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
                if max_approach <= first_touch {
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
            (Some(_), None) => {
                return Err(SceneError::Inconsistent(format!(
                    "{load_step} is required with {max_approach} (the approach increment while \
                     loading)",
                    load_step = fields::PROTOCOL_LOAD_STEP,
                    max_approach = fields::PROTOCOL_MAX_APPROACH
                )));
            }
            (None, Some(_)) => {
                return Err(SceneError::Inconsistent(format!(
                    "{max_approach} is required with {load_step} (the deepest approach); leave \
                     both out for the default pull-off path of a sphere",
                    load_step = fields::PROTOCOL_LOAD_STEP,
                    max_approach = fields::PROTOCOL_MAX_APPROACH
                )));
            }
            (None, None) => {
                let rule = default_path(body)?;
                if p.start.is_some() || p.retract_to.is_some() {
                    return Err(SceneError::Inconsistent(format!(
                        "{start} and {retract_to} need {max_approach} and {load_step} (the \
                         default pull-off path sets its own)",
                        start = fields::PROTOCOL_START,
                        retract_to = fields::PROTOCOL_RETRACT_TO,
                        max_approach = fields::PROTOCOL_MAX_APPROACH,
                        load_step = fields::PROTOCOL_LOAD_STEP
                    )));
                }
                let unload = p.unload_step.unwrap_or(rule.path.unload_step);
                let coarse = p.coarse_unload_step.unwrap_or(rule.path.coarse_unload_step);
                let max_approach = rule.path.max_approach;
                let range = match body.law {
                    AdhesionLaw::JkrLimit { .. } => None,
                    AdhesionLaw::Dugdale { sigma0 } => Some(body.gamma / sigma0),
                };
                let (start, load) =
                    crate::pull_off_path::load_plan(first_touch, max_approach, unload, range);
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
                let rule = PathRule {
                    path: crate::pull_off_path::PullOffPath {
                        unload_step: unload,
                        coarse_unload_step: coarse,
                        ..rule.path
                    },
                    stepped_load: matches!(body.law, AdhesionLaw::Dugdale { .. }),
                    refined: path.refine_pull_off,
                    ..rule
                };
                return Ok((path, Some(rule)));
            }
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
    Ok((path, None))
}

/// The default pull-off path when `[protocol]` leaves out `max_approach` and `load_step`: the
/// rule of [`crate::pull_off_path`] for a sphere (`geometry.radius`, or a body in memory with a
/// radius) or a body whose least-squares paraboloid is sphere-like; refused, naming what is
/// missing, without adhesion or without a radius.
fn default_path(body: &PathBody<'_>) -> Result<PathRule, SceneError> {
    if body.gamma <= 0.0 {
        return Err(SceneError::Inconsistent(format!(
            "{max_approach} is required: without adhesion ({gamma} = {}) there is no pull-off \
             to find, so there is no default path; for one state give {indent} = d (one step \
             pressed in to approach d), for a load–unload curve {max_approach} and {load_step}",
            num(body.gamma),
            max_approach = fields::PROTOCOL_MAX_APPROACH,
            gamma = fields::MATERIAL_GAMMA,
            indent = fields::PROTOCOL_INDENT,
            load_step = fields::PROTOCOL_LOAD_STEP
        )));
    }
    let (radius, top, fitted) = match body.sphere_radius {
        // A sphere shape: its apex is at 0, the roughness on top of it.
        Some(r) if !body.heights_only => (r, top_above_sphere(body, r)?, false),
        // Heights only, with the radius given (a body in memory): the paraboloid of that
        // radius through the heights finds the apex and the top of the roughness on it.
        Some(r) => {
            let fit = crate::pull_off_path::fit_paraboloid(
                body.surface.heights(),
                body.grid.dx(),
                Some(r),
            )
            .ok_or_else(|| {
                SceneError::Inconsistent(format!(
                    "{} is required: no paraboloid of radius {} fits the heights (fewer than 3 \
                     elements along an axis)",
                    fields::PROTOCOL_MAX_APPROACH,
                    num(r)
                ))
            })?;
            return finish_default_path(body, r, fit, false);
        }
        None if !body.heights_only => {
            return Err(SceneError::Inconsistent(format!(
                "{max} is required: the default pull-off path needs a sphere ({shape} = \
                 \"sphere\") or a sphere-like height map on {shape} = \"none\"; a flat punch or a \
                 power-law body has no radius to set its depth and steps; give {max} and {load}",
                max = fields::PROTOCOL_MAX_APPROACH,
                shape = fields::GEOMETRY_SHAPE,
                load = fields::PROTOCOL_LOAD_STEP,
            )));
        }
        None => {
            let fit =
                crate::pull_off_path::fit_paraboloid(body.surface.heights(), body.grid.dx(), None);
            match fit {
                Some(f) if f.is_sphere_like(body.grid) => {
                    return finish_default_path(body, f.radius, f, true);
                }
                _ => {
                    return Err(SceneError::Inconsistent(format!(
                        "{max_approach} is required: the default pull-off path needs a sphere \
                         ({shape} = \"sphere\") or a sphere-like height map (its least-squares \
                         paraboloid curved away from the half-space, rising over the grid by at \
                         least half the roughness range); give {max_approach} and {load_step}",
                        max_approach = fields::PROTOCOL_MAX_APPROACH,
                        shape = fields::GEOMETRY_SHAPE,
                        load_step = fields::PROTOCOL_LOAD_STEP
                    )));
                }
            }
        }
    };
    Ok(PathRule {
        stepped_load: false,
        refined: false,
        radius,
        fitted,
        path: crate::pull_off_path::default_pull_off_path(
            body.e_star,
            body.gamma,
            radius,
            top,
            body.grid.dx(),
        ),
    })
}

/// The greatest height of the body above the sphere of radius `radius` (or above its ellipsoid)
/// on its grid: the top of the roughness (and of any array added), computed only when the
/// default path needs it.
fn top_above_sphere(body: &PathBody<'_>, radius: f64) -> Result<f64, SceneError> {
    let sphere = Sphere::new(radius).map_err(rename(fields::GEOMETRY_RADIUS))?;
    let shape: &dyn Shape = match &body.ellipsoid {
        Some(e) => e,
        None => &sphere,
    };
    let grid = body.grid;
    Ok(body
        .surface
        .heights()
        .indexed_iter()
        .map(|((i, j), h)| h - shape.height(grid.x(i), grid.y(j)))
        .fold(f64::NEG_INFINITY, f64::max))
}

/// The default path of a heights-only body whose paraboloid `fit` (radius `radius`) is known;
/// on a free grid the loaded contact must fit the array around the vertex.
fn finish_default_path(
    body: &PathBody<'_>,
    radius: f64,
    fit: crate::pull_off_path::Paraboloid,
    fitted: bool,
) -> Result<PathRule, SceneError> {
    let path = crate::pull_off_path::default_pull_off_path(
        body.e_star,
        body.gamma,
        radius,
        fit.apex + fit.residual_max,
        body.grid.dx(),
    );
    if body.grid.boundary() == Boundary::Free {
        crate::pull_off_path::check_contact_fits(
            body.grid,
            radius,
            &fit,
            path.max_approach,
            body.surface.min(),
        )?;
    }
    Ok(PathRule {
        stepped_load: false,
        refined: false,
        radius,
        fitted,
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

/// Load steps of `path` that carry the body beyond its first touch (the deepest approach
/// included), counted up to `limit` (the path's own steps, `ApproachPath::load_approaches`).
pub fn loaded_steps(path: &tack_solver::ApproachPath, first_touch: f64, limit: usize) -> usize {
    path.load_approaches()
        .filter(|&d| d > first_touch)
        .take(limit)
        .count()
}

/// The zero-range law on a rough body loaded in more than one step from its first touch: the
/// approach bonds only what penetrates (no attraction ahead of the contact), so the pull-off
/// comes out below the finite-range law's, which tends to the one-step load's as λ grows
/// (README, "Loading history"; `cargo xtask study loading`).
fn loading_history_warning(
    law: AdhesionLaw,
    gamma: f64,
    random: bool,
    path: &tack_solver::ApproachPath,
    first_touch: f64,
) -> Option<String> {
    let zero_range = matches!(law, AdhesionLaw::JkrLimit { .. });
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

/// Flags a pull-off radius of fewer than [`MIN_PULL_OFF_RADIUS_ELEMENTS`] elements.
fn under_resolved(warnings: &mut Vec<String>, what: &str, radius: f64, dx: f64) {
    let elements = radius / dx;
    if elements < MIN_PULL_OFF_RADIUS_ELEMENTS {
        warnings.push(format!(
            "under-resolved pull-off: {what} spans {elements:.3} elements (fewer than \
             {MIN_PULL_OFF_RADIUS_ELEMENTS}), where the detachment criterion's error on a sphere \
             exceeds +33%; refine {dx}",
            dx = fields::GRID_DX
        ));
    }
}

/// Checks that the scales a run derives from its inputs are finite, normal floating-point
/// numbers: the element area Δx², the detachment stress σ_c = sqrt(E*γ/(κΔx)), and for spheres
/// F_JKR, d_JKR and a_c. Huge or tiny inputs (E* = 1e308, Δx = 1e-160) pass their own range
/// checks but overflow or underflow here, and a run would end in NaN or subnormal forces; the
/// error names the input fields the failing scale comes from.
fn check_scales(
    e_star: f64,
    gamma: f64,
    grid: &Grid,
    geometry: &Geometry,
    kappa: f64,
) -> Result<(), SceneError> {
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
        if let Geometry::Sphere { radius } = *geometry {
            let inputs = format!(
                "{e_star_field} = {}, {gamma_field} = {} and {radius_field} = {}",
                num(e_star),
                num(gamma),
                num(radius),
                e_star_field = fields::MATERIAL_E_STAR,
                gamma_field = fields::MATERIAL_GAMMA,
                radius_field = fields::GEOMETRY_RADIUS
            );
            normal(
                "F_JKR",
                tack_analytics::jkr_pull_off_force(gamma, radius),
                &inputs,
            )?;
            normal(
                "d_JKR",
                tack_analytics::jkr_pull_off_approach(e_star, gamma, radius),
                &inputs,
            )?;
            normal(
                "a_c",
                tack_analytics::jkr_pull_off_radius(e_star, gamma, radius),
                &inputs,
            )?;
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

fn base_surface(grid: Grid, geometry: &Geometry) -> Result<Surface, SceneError> {
    Ok(match *geometry {
        Geometry::Sphere { radius } => Surface::from_shape(
            grid,
            &Sphere::new(radius).map_err(rename(fields::GEOMETRY_RADIUS))?,
        ),
        Geometry::FlatPunch {
            punch,
            radius,
            half_side,
        } => {
            let punch = match (punch, radius, half_side) {
                (PunchKind::Circle, Some(r), None) => {
                    FlatPunch::circular(r).map_err(rename(fields::GEOMETRY_RADIUS))?
                }
                (PunchKind::Square, None, Some(s)) => {
                    FlatPunch::square(s).map_err(rename(fields::GEOMETRY_HALF_SIDE))?
                }
                (PunchKind::Circle, _, _) => {
                    return Err(SceneError::Inconsistent(
                        "geometry: punch = \"circle\" needs `radius` (and no `half_side`)".into(),
                    ));
                }
                (PunchKind::Square, _, _) => {
                    return Err(SceneError::Inconsistent(
                        "geometry: punch = \"square\" needs `half_side` (and no `radius`)".into(),
                    ));
                }
            };
            Surface::from_shape(grid, &punch)
        }
        Geometry::PowerLaw { c, exponent } => {
            let s = Surface::from_shape(grid, &tack_geometry::PowerLaw::new(c, exponent)?);
            // c·r^m at the grid's corners must stay a normal number (1e300 leaves room for the
            // approach and the roughness).
            if !(s.max().is_finite() && s.max() < 1e300) {
                return Err(SceneError::out_of_range(
                    fields::GEOMETRY_C,
                    c,
                    "small enough that c·r^m stays below 1e300 on the grid",
                ));
            }
            s
        }
        Geometry::Ellipsoid { radius_x, radius_y } => {
            let shape = Ellipsoid::new(radius_x, radius_y)?;
            if radius_x.max(radius_y) / radius_x.min(radius_y) > MAX_ELLIPSOID_RATIO {
                let (field, value, other) = if radius_x > radius_y {
                    (
                        fields::GEOMETRY_RADIUS_X,
                        radius_x,
                        fields::GEOMETRY_RADIUS_Y,
                    )
                } else {
                    (
                        fields::GEOMETRY_RADIUS_Y,
                        radius_y,
                        fields::GEOMETRY_RADIUS_X,
                    )
                };
                return Err(SceneError::Inconsistent(format!(
                    "{field} = {} is invalid: must be within a factor 1e6 of {other} (a longer \
                     ellipsoid is a cylinder: the elliptic integrals of its references lose \
                     every digit)",
                    num(value)
                )));
            }
            Surface::from_shape(grid, &shape)
        }
        Geometry::None => Surface::flat(grid),
    })
}

/// Renames the field of a geometry range error to the scene's key (the geometry crate names
/// the punch fields `geometry.punch_radius`/`punch_half_side`).
fn rename(field: &'static str) -> impl Fn(tack_geometry::GeometryError) -> SceneError {
    move |e| match e {
        tack_geometry::GeometryError::OutOfRange { value, allowed, .. } => {
            SceneError::out_of_range(field, value, allowed)
        }
        other => other.into(),
    }
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

/// An element count for a message: exact when it is a plausible size, else `2.000e300`.
fn count_text(n: f64) -> String {
    if n < 1e15 {
        format!("{n:.0}")
    } else {
        format!("{n:.3e}")
    }
}

/// Checks that the body's contact fits a free grid: a sphere's Hertz radius at the deepest
/// approach with [`SPHERE_FIT_MARGIN`], and a punch face with one element to spare.
fn check_fits(
    spec: &GridSpec,
    grid: &Grid,
    geometry: &Geometry,
    path: &ApproachPath,
    first_touch: f64,
    default_path: bool,
    film: bool,
) -> Result<(), SceneError> {
    // A thin film bulges around the contact: its radius reaches √(2.5Rd) (Shull's thin-film
    // limit δ → 0.4a²/R) instead of Hertz's √(Rd).
    let reach = if film { 2.5f64.sqrt() } else { 1.0 };
    let radius_rule = if film {
        "sqrt(2.5·R·d) (a thin film's)"
    } else {
        "sqrt(R·d) (Hertz)"
    };
    // What set the deepest approach, as the message names it.
    let depth_field = if path.is_indentation() {
        fields::PROTOCOL_INDENT
    } else if default_path {
        "the default pull-off path's depth"
    } else {
        fields::PROTOCOL_MAX_APPROACH
    };
    let shallower = if default_path {
        format!(
            "give a shallower path ({} with {})",
            fields::PROTOCOL_MAX_APPROACH,
            fields::PROTOCOL_LOAD_STEP
        )
    } else {
        format!("lower {depth_field}")
    };
    if grid.boundary() != Boundary::Free {
        return Ok(());
    }
    let half_extent = grid.lx().min(grid.ly()) / 2.0;
    let size_field = if spec.n.is_some() {
        fields::GRID_N
    } else {
        concat!(field_name!(grid.nx), "/", field_name!(grid.ny))
    };
    let (nx, ny) = grid.shape();
    if let Geometry::Ellipsoid { radius_x, radius_y } = *geometry {
        // The elliptic Hertz contact at the deepest approach, with the sphere's margin.
        let depth = (path.max_approach - first_touch).max(0.0);
        let hertz = tack_analytics::elliptic_hertz_from_approach(1.0, radius_x, radius_y, depth);
        let need = |semi: f64| SPHERE_FIT_MARGIN * reach * semi;
        let (mx, my) = (need(hertz.semi_axis_x), need(hertz.semi_axis_y));
        if !(mx <= grid.lx() / 2.0 && my <= grid.ly() / 2.0) {
            let n_x = count_text((2.0 * mx / grid.dx()).ceil());
            let n_y = count_text((2.0 * my / grid.dx()).ceil());
            return Err(SceneError::Inconsistent(format!(
                "{size_field} = {} is too small for the ellipsoid: at {depth_field} = {} the \
                 contact has semi-axes {} × {} (elliptic Hertz{}) that with a 30% margin need a free \
                 grid of at least {n_x} × {n_y} elements at {dx_field} = {} (the grid is {nx} × \
                 {ny}); raise {size_field} or {shallower}",
                if spec.n.is_some() {
                    nx.to_string()
                } else {
                    format!("{nx}/{ny}")
                },
                num(path.max_approach),
                num(reach * hertz.semi_axis_x),
                num(reach * hertz.semi_axis_y),
                if film {
                    ", times √2.5 on a thin film"
                } else {
                    ""
                },
                num(grid.dx()),
                dx_field = fields::GRID_DX
            )));
        }
        return Ok(());
    }
    match *geometry {
        Geometry::Sphere { radius } => {
            let depth = path.max_approach - first_touch;
            let hertz = reach * (radius * depth).sqrt();
            let needed = SPHERE_FIT_MARGIN * hertz;
            if needed > half_extent {
                let n_needed = count_text((2.0 * needed / grid.dx()).ceil());
                let hertz = if (1e-4..1e6).contains(&hertz) {
                    format!("{hertz:.4}")
                } else {
                    format!("{hertz:.4e}")
                };
                return Err(SceneError::Inconsistent(format!(
                    "{size_field} = {} is too small for the sphere: at {depth_field} = {} \
                     the contact radius {radius_rule} = {hertz} plus a 30% margin needs a \
                     free grid of at least {n_needed} × {n_needed} elements at {dx_field} = {} \
                     (the grid is {nx} × {ny}); raise {size_field} or {shallower}",
                    if spec.n.is_some() {
                        nx.to_string()
                    } else {
                        format!("{nx}/{ny}")
                    },
                    num(path.max_approach),
                    num(grid.dx()),
                    dx_field = fields::GRID_DX
                )));
            }
        }
        Geometry::FlatPunch {
            radius, half_side, ..
        } => {
            let (field, size) = match (radius, half_side) {
                (Some(r), _) => (fields::GEOMETRY_RADIUS, r),
                (_, Some(s)) => (fields::GEOMETRY_HALF_SIDE, s),
                _ => return Ok(()),
            };
            // The punch face needs one element to spare beyond its edge on every side. The
            // origin is the centre of element ⌊n/2⌋, so an even side reaches one element less
            // on its positive end: the outermost centre there is at (n − 1 − ⌊n/2⌋)·Δx.
            let reach = |n: usize| (n - 1 - n / 2) as f64 * grid.dx();
            let needed = size + grid.dx() * (1.0 - 1e-9);
            if reach(nx.min(ny)) < needed {
                // reach(n) = ⌊(n − 1)/2⌋·Δx, so the least n is 2⌈needed/Δx⌉ + 1 (in closed
                // form: a search over n never ended for a punch of 1e299).
                let n_needed = count_text(2.0 * (needed / grid.dx()).ceil() + 1.0);
                return Err(SceneError::Inconsistent(format!(
                    "{field} = {} does not fit the grid: the punch needs a free grid of at \
                     least {n_needed} × {n_needed} elements at {dx_field} = {} (the grid is \
                     {nx} × {ny}); raise {size_field}",
                    num(size),
                    num(grid.dx()),
                    dx_field = fields::GRID_DX
                )));
            }
        }
        Geometry::PowerLaw { c, exponent } => {
            // The disc the rigid body penetrates at the deepest approach, c·r^m < d, with the
            // sphere's margin (for m = 2 the penetrated disc is √2 times the Hertz radius).
            let depth = path.max_approach - first_touch;
            let needed = SPHERE_FIT_MARGIN * (depth.max(0.0) / c).powf(1.0 / exponent);
            if needed > half_extent {
                let n_needed = count_text((2.0 * needed / grid.dx()).ceil());
                return Err(SceneError::Inconsistent(format!(
                    "{size_field} = {} is too small for the power-law body: at {depth_field} = \
                     {} it penetrates a disc of radius (d/c)^(1/m) = {} that with a 30% margin \
                     needs a free grid of at least {n_needed} × {n_needed} elements at \
                     {dx_field} = {} (the grid is {nx} × {ny}); raise {size_field} or \
                     {shallower}",
                    if spec.n.is_some() {
                        nx.to_string()
                    } else {
                        format!("{nx}/{ny}")
                    },
                    num(path.max_approach),
                    num(needed / SPHERE_FIT_MARGIN),
                    num(grid.dx()),
                    dx_field = fields::GRID_DX
                )));
            }
        }
        Geometry::None | Geometry::Ellipsoid { .. } => {}
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    const SPHERE: &str = r#"
version = 1
[material]
e_star = 1.0
gamma = 0.1
[geometry]
shape = "sphere"
radius = 1.0
[grid]
n = 64
dx = 0.05
[protocol]
max_approach = 0.5
load_step = 0.05
"#;

    fn build(text: &str, sets: &[&str]) -> Result<Problem, SceneError> {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        Problem::from_scene(&Scene::parse(text, ".", &sets)?)
    }

    fn err(sets: &[&str]) -> String {
        build(SPHERE, sets).unwrap_err().to_string()
    }

    /// [`SPHERE`] without its `[protocol]`.
    fn no_protocol() -> &'static str {
        SPHERE.split("[protocol]").next().unwrap()
    }

    #[test]
    fn a_scene_without_a_protocol_gets_the_pull_off_rule_of_its_sphere() {
        let p = build(no_protocol(), &[]).unwrap();
        let rule = crate::pull_off_path::default_pull_off_path(1.0, 0.1, 1.0, 0.0, 0.05);
        assert_eq!(p.path.max_approach, rule.max_approach);
        // One load step straight to the deepest approach, then the rule's retraction.
        assert_eq!(p.path.start, rule.max_approach);
        assert_eq!(p.path.unload_step, rule.unload_step);
        assert_eq!(p.path.coarse_unload_step, Some(rule.coarse_unload_step));
        assert_eq!(p.path.retract_to, None);
        // d_s = (R γ²/E*²)^(1/3) = 0.1^(2/3): 3 d_s deep, 0.02 d_s steps.
        let d_s = 0.1_f64.powf(2.0 / 3.0);
        assert!((p.path.max_approach - 3.0 * d_s).abs() < 1e-12);
        // The same numbers as the pull-off of the sphere given as an array.
        let grid = p.grid;
        let heights = Surface::from_shape(grid, &Sphere::new(1.0).unwrap()).into_heights();
        let spec = crate::heights::PullOffSpec {
            radius: Some(1.0),
            ..crate::heights::PullOffSpec::new(0.05, 1.0, 0.1)
        };
        let plan = crate::heights::pull_off_scene(&heights, &spec).unwrap();
        let q = crate::heights::problem(&plan.scene, &plan.body(&heights)).unwrap();
        assert!((q.path.max_approach - p.path.max_approach).abs() < 1e-12);
        assert_eq!(q.path.unload_step, p.path.unload_step);
        // Steps given in the scene are kept.
        let p = build(no_protocol(), &["protocol.unload_step=0.001"]).unwrap();
        assert_eq!(p.path.unload_step, 0.001);
        // Roughness raises the load depth by its top.
        let rough = format!(
            "{}[roughness]\nkind = \"waviness2d\"\nh = 0.01\nlambda = 0.8\n",
            no_protocol()
        );
        let p = build(&rough, &[]).unwrap();
        assert!(
            p.path.max_approach > rule.max_approach + 0.009,
            "{:?}",
            p.path
        );
    }

    #[test]
    fn a_scene_without_a_path_is_refused_where_no_rule_applies() {
        let e = build(no_protocol(), &["material.gamma=0"])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("protocol.max_approach is required") && e.contains("protocol.indent"),
            "{e}"
        );
        let punch = no_protocol().replace(
            "shape = \"sphere\"\nradius = 1.0",
            "shape = \"flat_punch\"\npunch = \"circle\"\nradius = 0.5",
        );
        let e = build(&punch, &[]).unwrap_err().to_string();
        assert!(e.contains("sphere-like"), "{e}");
        let e = build(no_protocol(), &["protocol.load_step=0.1"])
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("protocol.max_approach is required"), "{e}");
        let e = build(no_protocol(), &["protocol.max_approach=0.1"])
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("protocol.load_step is required"), "{e}");
    }

    #[test]
    fn a_body_in_memory_with_a_radius_loads_from_its_own_apex() {
        // The sphere given as an array with its radius, on geometry "none" and no [protocol]:
        // the same depth as the sphere scene (the array's highest point is far off the apex).
        let sphere = build(no_protocol(), &[]).unwrap();
        let heights = Surface::from_shape(sphere.grid, &Sphere::new(1.0).unwrap()).into_heights();
        let flat = no_protocol().replace("shape = \"sphere\"\nradius = 1.0", "shape = \"none\"");
        let scene = Scene::parse(&flat, ".", &[]).unwrap();
        let body = HeightBody {
            heights: &heights,
            roughness_range: Some(0.0),
            radius: Some(1.0),
            gamma: None,
        };
        let p = crate::heights::problem(&scene, &body).unwrap();
        assert!(
            (p.path.max_approach - sphere.path.max_approach).abs() < 1e-9,
            "{} vs {}",
            p.path.max_approach,
            sphere.path.max_approach
        );
        assert_eq!(p.path.unload_step, sphere.path.unload_step);
        assert!(!p.path_rule.unwrap().fitted);
        // Too deep for the array: the contact-fits check of the pull-off applies.
        let small = Surface::from_shape(
            Grid::square(12, 0.05, Boundary::Free).unwrap(),
            &Sphere::new(1.0).unwrap(),
        )
        .into_heights();
        let scene = Scene::parse(&flat.replace("n = 64", "n = 12"), ".", &[]).unwrap();
        let e = crate::heights::problem(
            &scene,
            &HeightBody {
                heights: &small,
                ..body
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("too small for the pull-off"), "{e}");
    }

    #[test]
    fn an_indentation_is_one_step_and_excludes_the_path_fields() {
        let text = format!("{}[protocol]\nindent = 0.1\n", no_protocol());
        let p = build(&text, &[]).unwrap();
        assert!(p.path.is_indentation());
        assert_eq!((p.path.start, p.path.max_approach), (0.1, 0.1));
        assert_eq!(p.path.step_bound(), 1);
        let e = build(&text, &["protocol.load_step=0.01"])
            .unwrap_err()
            .to_string();
        assert!(e.contains("leave out protocol.load_step"), "{e}");
        let e = build(&text, &["protocol.indent=-0.5"])
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("protocol.indent = -0.5 never touches the surface"),
            "{e}"
        );
        let e = build(&text, &["protocol.indent=\"deep\""])
            .unwrap_err()
            .to_string();
        assert!(e.contains("protocol.indent"), "{e}");
        // Richardson extrapolates a pull-off, which an indentation does not have.
        let scene = Scene::parse(&text, ".", &[]).unwrap();
        let e = crate::coarse::coarse_problem(&scene, &p)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("an indentation (protocol.indent) has none"),
            "{e}"
        );
        // A load-only path of several steps is not an indentation.
        let load_only = build(SPHERE, &["protocol.retract_to=0.5"]).unwrap();
        assert!(!load_only.path.is_indentation());
        // Too deep for the grid: the message names protocol.indent.
        let e = build(&text, &["protocol.indent=3.0"])
            .unwrap_err()
            .to_string();
        assert!(e.contains("at protocol.indent = 3"), "{e}");
    }

    #[test]
    fn the_memory_bound_counts_the_steps_a_finite_path_takes() {
        // Every field kept on a 512² grid: an indentation keeps one, not 100000 (439.6 GiB).
        let text = format!(
            "{}[protocol]\nindent = 0.1\n[output]\nsnapshots = \"all\"\n",
            no_protocol()
        )
        .replace("n = 64", "n = 512");
        let p = build(&text, &[]).unwrap();
        let e = p.memory_estimate();
        assert_eq!((e.steps, e.snapshots), (1.0, 1.0));
        assert!(e.total() < 1e9, "{e:?}");
        // A path down to retract_to: its load and retraction steps, an upper bound.
        let p = build(SPHERE, &["protocol.retract_to=0.0"]).unwrap();
        let loads = ((0.5 - p.path.start) / 0.05).ceil() + 1.0;
        assert_eq!(p.path.step_bound() as f64, loads + (0.5_f64 / 0.05).floor());
        // A retraction until contact is lost: only max_steps bounds it.
        let p = build(SPHERE, &[]).unwrap();
        assert_eq!(p.path.step_bound(), p.path.max_steps);
    }

    #[test]
    fn sphere_problem_has_jkr_references_and_first_touch_start() {
        let p = build(SPHERE, &[]).unwrap();
        assert_eq!(p.first_touch, 0.0);
        assert_eq!(p.path.start, 0.05);
        assert_eq!(p.path.unload_step, 0.05);
        assert_eq!(p.path.max_steps, DEFAULT_MAX_STEPS);
        assert_eq!(p.kappa, KAPPA);
        let f_jkr = p.references.f_jkr.unwrap();
        assert!((f_jkr + 1.5 * PI * 0.1).abs() < 1e-12);
        assert!(p.references.johnson_alpha.is_none());
    }

    #[test]
    fn coarse_retraction_and_pull_off_snapshots_reach_the_solver() {
        let sets = [
            "protocol.coarse_unload_step=0.2",
            "protocol.unload_step=0.01",
            "output.snapshots=\"pull_off\"",
            "grid.n=128",
        ];
        let p = build(SPHERE, &sets).unwrap();
        assert_eq!(p.path.coarse_unload_step, Some(0.2));
        assert_eq!(p.snapshots, SnapshotRequest::PullOff);
        assert!(p.window.is_some(), "the test wants a cropped run");
        let path = crate::run::solve(&p, &mut ()).unwrap();
        let r = &path.records;
        // Retraction from 0.5 by 0.2 while compressive, then by 0.01.
        let first = path
            .phases
            .iter()
            .position(|ph| *ph == tack_solver::Phase::Unload);
        assert_eq!(r[first.unwrap()].approach, 0.5 - 0.2);
        let pull_off = (0..r.len())
            .min_by(|&a, &b| r[a].force.total_cmp(&r[b].force))
            .unwrap();
        let last = r.iter().rposition(|s| s.n_bonded > 0).unwrap();
        let steps: Vec<usize> = path.snapshots.iter().map(|s| s.step).collect();
        assert_eq!(steps, [pull_off, last]);
        // On the full grid, as the result file stores them.
        for s in &path.snapshots {
            assert_eq!(s.bonded.dim(), p.grid.shape());
            assert_eq!(s.bonded.iter().filter(|&&b| b).count(), r[s.step].n_bonded);
        }
    }

    #[test]
    fn the_refined_retraction_reaches_the_solver_and_needs_a_coarse_step() {
        let sets = [
            "protocol.coarse_unload_step=0.2",
            "protocol.unload_step=0.01",
            "protocol.refine_pull_off=true",
        ];
        let p = build(SPHERE, &sets).unwrap();
        assert!(p.path.refine_pull_off && p.path.coarse_unload_step == Some(0.2));
        // Its saved states count in the memory estimate.
        let plain = build(SPHERE, &sets[..2]).unwrap();
        let extra = p.memory_estimate().fields - plain.memory_estimate().fields;
        assert_eq!(
            extra,
            64.0 * 64.0 * 8.0 * crate::memory::REFINED_STATE_FIELDS
        );
        let e = build(SPHERE, &[sets[1], sets[2]]).unwrap_err().to_string();
        assert!(
            e.contains("protocol.refine_pull_off = true needs a coarse step: set protocol.coarse_unload_step"),
            "{e}"
        );
        let e = build(SPHERE, &["protocol.refine_pull_off=1"])
            .unwrap_err()
            .to_string();
        assert!(e.contains("protocol.refine_pull_off"), "{e}");
        // The default path takes it too (its coarse step is the rule's), and is fine without.
        assert!(!build(no_protocol(), &[]).unwrap().path.refine_pull_off);
        let p = build(no_protocol(), &[sets[2]]).unwrap();
        assert!(p.path.refine_pull_off && p.path.coarse_unload_step.is_some());
        let e = build(no_protocol(), &["protocol.indent=0.1", sets[2]])
            .unwrap_err()
            .to_string();
        assert!(e.contains("leave out protocol.refine_pull_off"), "{e}");
    }

    #[test]
    fn a_punch_on_an_even_grid_needs_its_spare_element_on_the_short_side() {
        let punch = include_str!("../../../data/examples/flat_punch.toml");
        // a = 1, Δx = 0.1: the face needs centres out to 1.1 on both sides. An even n = 22
        // reaches only 1.0 on its positive side (the origin is element 11); n = 23 reaches 1.1.
        let e = build(punch, &["grid.n=22"]).unwrap_err().to_string();
        assert!(
            e.contains("geometry.radius = 1") && e.contains("23 × 23"),
            "{e}"
        );
        assert!(build(punch, &["grid.n=21"]).is_err());
        // The issue's case: a = 2 on n = 42 (reaches 2.0), accepted before and then touching
        // the edge in every step.
        let e = build(punch, &["grid.n=42", "geometry.radius=2"]).unwrap_err();
        assert!(e.to_string().contains("43 × 43"), "{e}");
        // A huge punch (below the 1e300 bound) is refused at once, in readable numbers.
        let started = std::time::Instant::now();
        let e = build(punch, &["geometry.radius=1e299"])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("geometry.radius = 1e299") && e.contains("2.000e300 × 2.000e300"),
            "{e}"
        );
        assert!(!e.contains("inf"), "{e}");
        assert!(started.elapsed() < std::time::Duration::from_secs(1));
        for n in [23, 24] {
            let p = build(
                punch,
                &[&format!("grid.n={n}"), "protocol.unload_step=0.05"],
            )
            .unwrap();
            let path = crate::run::solve(&p, &mut ()).unwrap();
            assert!(path.records.iter().all(|r| !r.edge_contact), "n = {n}");
        }
    }

    #[test]
    fn field_errors_name_the_field_and_range() {
        assert!(
            err(&["material.e_star=-1"])
                .contains("material.e_star = -1 is invalid: must be a finite number > 0")
        );
        assert!(err(&["material.e_star=nan"]).contains("material.e_star = NaN"));
        assert!(err(&["material.gamma=-0.1"]).contains("material.gamma = -0.1"));
        assert!(err(&["grid.n=0"]).contains("grid.n = 0 is invalid"));
        assert!(err(&["grid.n=65536"]).contains("grid.n = 65536 × 65536 is too large"));
        assert!(err(&["grid.dx=-1"]).contains("grid.dx = -1"));
        assert!(err(&["grid.length=3.2"]).contains("exactly one of `dx` and `length`"));
        assert!(err(&["geometry.radius=0"]).contains("geometry.radius = 0"));
        assert!(err(&["solver.tolerance=2"]).contains("solver.tolerance = 2"));
        for t in ["5e-324", "1e-15", "0.5", "nan"] {
            let e = err(&[&format!("solver.tolerance={t}")]);
            let shown = if t == "nan" { "NaN" } else { t };
            assert!(
                e.contains(&format!(
                    "solver.tolerance = {shown} is invalid: must be a number in 1e-14..=0.1"
                )),
                "{t}: {e}"
            );
        }
        let e = err(&["grid.dx=1e306"]);
        assert!(
            e.contains("grid.dx = 1e306 give the element area Δx² = an overflow")
                && !e.contains("inf"),
            "{e}"
        );
        for t in ["1e-14", "0.1", "1e-9"] {
            assert!(
                build(SPHERE, &[&format!("solver.tolerance={t}")]).is_ok(),
                "{t}"
            );
        }
        assert!(err(&["solver.kappa=-1"]).contains("solver.kappa = -1"));
        assert!(err(&["protocol.load_step=0"]).contains("protocol.load_step = 0"));
        assert!(err(&["protocol.retract_to=1"]).contains("protocol.retract_to = 1"));
        assert!(
            err(&["protocol.coarse_unload_step=0"]).contains(
                "protocol.coarse_unload_step = 0 is invalid: must be a finite number > 0"
            )
        );
    }

    #[test]
    fn runs_that_cannot_fit_in_memory_are_refused_before_they_run() {
        // Every step's fields of a 2048² grid over 100000 steps: 6.9 TiB.
        let e = err(&["grid.n=2048", "output.snapshots=\"all\""]);
        assert!(
            e.contains("may need about 6.9 TiB")
                && e.contains("output.snapshots = \"all\"")
                && e.contains("protocol.max_steps = 100000")
                && e.contains("grid.n = 2048 × 2048"),
            "{e}"
        );
        // 10^18 step records.
        let e = err(&["protocol.max_steps=1000000000000000000"]);
        assert!(
            e.contains("for 1000000000000000000 step records")
                && e.contains("protocol.max_steps = 1000000000000000000"),
            "{e}"
        );
        // A bounded path with every field fits.
        assert!(
            build(
                SPHERE,
                &["output.snapshots=\"all\"", "protocol.max_steps=2000"]
            )
            .is_ok()
        );
    }

    #[test]
    fn scene_level_checks() {
        let e = err(&["protocol.max_approach=-0.1"]);
        assert!(
            e.contains("protocol.max_approach = -0.1 never touches") && e.contains("first touch"),
            "{e}"
        );
        let e = err(&["protocol.max_approach=4"]);
        assert!(e.contains("grid.n = 64 is too small"), "{e}");
        let e = err(&[
            "roughness.kind=waviness2d",
            "roughness.h=0.01",
            "roughness.lambda=0.1",
        ]);
        assert!(
            e.contains("roughness.lambda = 0.1 is invalid: must be ≥ 4·grid.dx"),
            "{e}"
        );
        let e = err(&[
            "roughness.kind=random",
            "roughness.h=0.01",
            "roughness.hurst=0.5",
            "roughness.q1=100",
        ]);
        assert!(e.contains("roughness.q0/q1"), "{e}");
    }

    #[test]
    fn a_height_map_path_that_is_no_file_says_what_it_is() {
        let dir = std::env::temp_dir();
        let dir = dir.to_str().unwrap();
        for (path, what) in [
            (dir, "is a directory, not a map file"),
            ("/dev/null", "is not a regular file"),
            ("/no/such/map.txt", "no such file"),
        ] {
            let e = err(&["roughness.kind=file", &format!("roughness.path=\"{path}\"")]);
            assert!(
                e.contains(&format!("roughness.path = `{path}`")) && e.contains(what),
                "{path}: {e}"
            );
        }
    }

    #[test]
    fn rough_sphere_has_alpha_star_and_seed() {
        let p = build(
            SPHERE,
            &[
                "roughness.kind=random",
                "roughness.h=0.001",
                "roughness.hurst=0.5",
                "roughness.seed=7",
            ],
        )
        .unwrap();
        assert_eq!(p.seed, Some(7));
        assert!(p.first_touch < 0.0);
        assert!(p.references.alpha_star.unwrap() > 0.0);
    }

    #[test]
    fn periodic_waviness_must_fit_the_period() {
        let strip = r#"
version = 1
[material]
e_star = 1.0
gamma = 0.0
[geometry]
shape = "none"
[roughness]
kind = "waviness1d"
h = 0.01
lambda = 1.0
[grid]
nx = 64
ny = 1
length = 1.0
boundary = "periodic"
[protocol]
max_approach = 0.01
load_step = 0.001
"#;
        let p = build(strip, &[]).unwrap();
        assert!(p.references.johnson_alpha.is_some());
        let e = build(strip, &["roughness.lambda=0.3"])
            .unwrap_err()
            .to_string();
        assert!(e.contains("does not fit the periodic grid"), "{e}");
    }
}

#[cfg(test)]
mod adhesion_tests {
    use super::*;

    fn build(sets: &[&str]) -> Result<Problem, SceneError> {
        let text = "version = 1\n[material]\ne_star = 1.0\ngamma = 0.1\n[geometry]\nshape = \
                    \"sphere\"\nradius = 1.0\n[grid]\nn = 128\ndx = 0.02\n";
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        Problem::from_scene(&Scene::parse(text, ".", &sets)?)
    }

    fn err(sets: &[&str]) -> String {
        build(sets).unwrap_err().to_string()
    }

    #[test]
    fn power_law_bodies_are_read_checked_and_referenced() {
        let scene = |c: &str, m: &str| {
            format!(
                "version = 1\n[material]\ne_star = 1.0\ngamma = 0.05\n[geometry]\nshape = \
                 \"power_law\"\nc = {c}\nexponent = {m}\n[grid]\nn = 80\ndx = 0.1\n\
                 [protocol]\nmax_approach = 1.44\nload_step = 1.44\n"
            )
        };
        let p =
            Problem::from_scene(&Scene::parse(&scene("0.5", "1.0"), ".", &[]).unwrap()).unwrap();
        let f = p.references.f_mdr.unwrap();
        assert!((f + 0.343775).abs() < 1e-6, "{f}");
        assert!(p.references.f_jkr.is_none());
        for (c, m, field) in [
            ("0.0", "1.0", "geometry.c"),
            ("0.5", "0.5", "geometry.exponent"),
            ("1e300", "16.0", "geometry.c"),
        ] {
            let e = Problem::from_scene(&Scene::parse(&scene(c, m), ".", &[]).unwrap())
                .unwrap_err()
                .to_string();
            assert!(e.contains(field), "{e}");
        }
        // No reference on a periodic grid, with a warning.
        let periodic =
            scene("0.5", "1.0").replace("dx = 0.1\n", "dx = 0.1\nboundary = \"periodic\"\n");
        let p = Problem::from_scene(&Scene::parse(&periodic, ".", &[]).unwrap()).unwrap();
        assert!(p.references.f_mdr.is_none());
        assert!(
            p.warnings.iter().any(|w| w.contains("no F_MDR reference")),
            "{:?}",
            p.warnings
        );
        // A grid too small for the penetrated disc names the grid size.
        let small = scene("0.5", "1.0").replace("n = 80", "n = 30");
        let e = Problem::from_scene(&Scene::parse(&small, ".", &[]).unwrap())
            .unwrap_err()
            .to_string();
        assert!(e.contains("grid.n") && e.contains("power-law"), "{e}");
    }

    #[test]
    fn loaded_steps_count_the_steps_beyond_the_first_touch() {
        let path = |start: f64, max: f64, step: f64| tack_solver::ApproachPath {
            start,
            max_approach: max,
            load_step: step,
            unload_step: step,
            coarse_unload_step: None,
            refine_pull_off: false,
            retract_to: None,
            max_steps: 1000,
        };
        // One step straight to the depth; loads 0.1, 0.2, …, 1.0 beyond a touch at 0.35.
        let all = usize::MAX;
        assert_eq!(loaded_steps(&path(1.0, 1.0, 1.0), 0.0, all), 1);
        assert_eq!(loaded_steps(&path(1.0, 1.0, 1.0), 2.0, all), 0);
        assert_eq!(loaded_steps(&path(0.1, 1.0, 0.1), 0.35, all), 7);
        assert_eq!(loaded_steps(&path(-0.5, 1.0, 0.5), 0.0, all), 2);
        assert_eq!(loaded_steps(&path(0.5, 1.0, 0.5), -1.0, all), 2);
        // Beyond the deepest approach nothing is loaded; the solver's own steps (0.88 + k·0.01
        // below 1.04, then 1.04: 17); a tiny step is counted only up to the limit.
        assert_eq!(loaded_steps(&path(0.0, 1.0, 0.5), 2.0, all), 0);
        assert_eq!(loaded_steps(&path(0.88, 1.04, 0.01), 0.0, all), 17);
        assert_eq!(loaded_steps(&path(-1.0, 1.0, 1e-20), 0.0, 2), 0);
        assert_eq!(loaded_steps(&path(-1.0, 1.0, 1e-2), 0.0, 2), 2);
    }

    #[test]
    fn a_rough_body_loaded_in_steps_under_the_zero_range_law_is_warned() {
        let rough = [
            "roughness.kind=\"random\"",
            "roughness.h=0.002",
            "roughness.hurst=0.5",
            "roughness.seed=1",
        ];
        let warned = |p: &Problem| p.warnings.iter().any(|w| w.contains("loading history"));
        // The default path loads in one step: no warning.
        assert!(!warned(&build(&rough).unwrap()));
        let mut stepped = rough.to_vec();
        stepped.extend([
            "protocol.start=-0.02",
            "protocol.max_approach=0.1",
            "protocol.load_step=0.01",
            "protocol.unload_step=0.001",
        ]);
        let p = build(&stepped).unwrap();
        assert!(warned(&p), "{:?}", p.warnings);
        // Not for the smooth sphere, nor a waviness (its figures load in steps on purpose),
        // nor under the Dugdale law.
        assert!(!warned(&build(&stepped[4..]).unwrap()));
        let mut wavy = vec![
            "roughness.kind=\"waviness2d\"",
            "roughness.h=0.002",
            "roughness.lambda=0.2",
        ];
        wavy.extend(&stepped[4..]);
        assert!(!warned(&build(&wavy).unwrap()));
        let mut dugdale = stepped.clone();
        dugdale.extend(["adhesion.model=\"dugdale\"", "adhesion.sigma0=1.0"]);
        assert!(!warned(&build(&dugdale).unwrap()));
    }

    #[test]
    fn the_dugdale_law_is_read_and_its_inputs_are_checked() {
        let p = build(&["adhesion.model=\"dugdale\"", "adhesion.sigma0=1.0"]).unwrap();
        assert_eq!(p.law, AdhesionLaw::Dugdale { sigma0: 1.0 });
        // The default path approaches from out of range (h0 = γ/σ0 = 0.1) in its fine step.
        assert!(p.path.start < -0.1 && p.path.load_step == p.path.unload_step);
        let lambda = p.references.maugis_lambda.unwrap();
        assert!((lambda - tack_analytics::maugis_lambda(1.0, 0.1, 1.0, 1.0)).abs() < 1e-12);
        assert!(p.references.f_maugis.unwrap() < 0.0);
        assert!(build(&[]).unwrap().law == AdhesionLaw::JkrLimit { kappa: KAPPA });
        assert!(
            err(&["adhesion.sigma0=1.0"])
                .contains("adhesion.sigma0 = 1 is read by the Dugdale law only")
        );
        assert!(err(&["adhesion.model=\"dugdale\""]).contains("adhesion.sigma0 is required with"));
        for bad in ["0.0", "-1.0", "nan", "inf"] {
            let message = err(&[
                "adhesion.model=\"dugdale\"",
                &format!("adhesion.sigma0={bad}"),
            ]);
            assert!(message.starts_with("adhesion.sigma0 = "), "{message}");
            assert!(message.contains("a finite number > 0"), "{message}");
        }
        assert!(
            err(&["adhesion.model=\"dugdale\"", "adhesion.sigma0=1e20"])
                .contains("exceeds 1e-12 of the largest height")
        );
        assert!(
            err(&[
                "adhesion.model=\"dugdale\"",
                "adhesion.sigma0=1",
                "solver.kappa=0.5"
            ])
            .contains("solver.kappa is the zero-range criterion's constant")
        );
        assert!(
            err(&[
                "adhesion.model=\"dugdale\"",
                "adhesion.sigma0=1",
                "material.gamma=0"
            ])
            .contains("needs material.gamma > 0")
        );
        assert!(err(&["adhesion.model=\"dmt\""]).contains("adhesion.model"));
    }

    #[test]
    fn an_unresolved_cohesive_zone_warns() {
        // l = πE*γ/(4σ0²) = 0.0785 at σ0 = 1: 3.9 elements of 0.02; at σ0 = 2: 0.98.
        let fine = build(&["adhesion.model=\"dugdale\"", "adhesion.sigma0=1.0"]).unwrap();
        assert!(!fine.warnings.iter().any(|w| w.contains("cohesive zone")));
        let coarse = build(&["adhesion.model=\"dugdale\"", "adhesion.sigma0=2.0"]).unwrap();
        assert!(
            coarse
                .warnings
                .iter()
                .any(|w| w.starts_with("under-resolved cohesive zone") && w.contains("0.98")),
            "{:?}",
            coarse.warnings
        );
    }
}
