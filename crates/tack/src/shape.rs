//! The rigid body's macroscopic shape as a scene names it (`[geometry]`): each shape answers for
//! itself — its surface on a grid, its closed-form references, the sphere its default pull-off
//! path is built from, whether its contact fits a free grid, its one-line description — so a
//! new shape is one type implementing [`SceneShape`] and its variant of [`Geometry`] (the scene
//! schema), joined in [`Geometry::shape`], the only `match` over the geometry.

use tack_fields::{self as fields, field_name, num, rounded};
use tack_geometry::{Boundary, Ellipsoid, FlatPunch, Grid, Shape, Sphere, Surface};
use tack_solver::ApproachPath;

pub use crate::pull_off_path::{Material, count_text, round4, sphere_contact_reach};
use crate::pull_off_path::{SPHERE_FIT_MARGIN, loaded_steps};
use crate::references::References;
use crate::scene::{Geometry, GridSpec, PunchKind, SceneError};

/// Greatest ratio of an ellipsoid's radii: beyond it the elliptic Hertz and JKR references lose
/// their digits (the eccentricity rounds to 1).
pub const MAX_ELLIPSOID_RATIO: f64 = 1e6;

/// Least number of grid elements a periodic cell must span along each side, measured in
/// pull-off contact diameters 2a_c, for the isolated sphere's F_JKR to be the reference: a
/// closer neighbour (the periodic image) changes the pull-off.
pub const MIN_PERIOD_CONTACT_DIAMETERS: f64 = 2.0;

/// Least pull-off contact radius over element size, a_c/Δx (JKR radius for spheres, the punch
/// radius for circular punches), below which a run is flagged as under-resolved: the
/// detachment criterion's error grows like Δx/a_c and is +33% at 5 (`docs/theory.md` §9).
pub const MIN_PULL_OFF_RADIUS_ELEMENTS: f64 = 5.0;

/// A macroscopic shape of a scene: one type per `geometry.shape`.
pub trait SceneShape {
    /// The body's heights on `grid` (gap at zero approach, apex at 0), its parameters checked
    /// with errors naming the scene field.
    fn surface(&self, grid: Grid) -> Result<Surface, SceneError>;

    /// Sets the closed-form references of an adhesive pull-off (called with `γ > 0` only),
    /// with the length the zero-range criterion's mesh rule judges
    /// ([`References::criterion_mesh`], warned of by [`under_resolved`] under that law), and
    /// warns where they do not apply (a strip, a periodic array).
    fn references(
        &self,
        _material: Material,
        _grid: &Grid,
        _references: &mut References,
        _warnings: &mut Vec<String>,
    ) {
    }

    /// The sphere the default pull-off path is built from: its radius and the shape the top
    /// of the roughness is measured above (a sphere's own paraboloid, an ellipsoid's), or
    /// `None` where the shape has no radius (a punch, a power law) or none of its own
    /// (`shape = "none"`: see [`SceneShape::heights_only`]).
    fn path_sphere(&self) -> Option<(f64, Box<dyn Shape>)> {
        None
    }

    /// Whether the body is only the heights added to it (`shape = "none"`: a map, an array),
    /// whose radius a least-squares paraboloid may find.
    fn heights_only(&self) -> bool {
        false
    }

    /// Scales the shape derives from the material that must be normal floating-point numbers
    /// through a run: `(name, value)` pairs and the inputs they come from (for the message).
    fn scales(&self, _material: Material) -> Option<(Vec<(&'static str, f64)>, String)> {
        None
    }

    /// Checks that the contact at the deepest approach fits a free grid (called on free grids
    /// only), naming the field to raise and the path field to lower.
    fn check_fit(&self, _fit: &FitCheck<'_>) -> Result<(), SceneError> {
        Ok(())
    }

    /// Where the radius of [`SceneShape::path_sphere`] comes from, as reports say it.
    fn path_radius_origin(&self) -> &'static str {
        "given"
    }

    /// One line for reports, numbers rounded: `sphere R = 1`, `circular flat punch a = 0.5`.
    fn describe(&self) -> String;
}

impl Geometry {
    /// The shape of `[geometry]`: the one place a geometry variant becomes its type.
    pub fn shape(&self) -> Box<dyn SceneShape> {
        match *self {
            Geometry::Sphere { radius } => Box::new(SphereBody { radius }),
            Geometry::FlatPunch {
                punch,
                radius,
                half_side,
            } => Box::new(PunchBody {
                punch,
                radius,
                half_side,
            }),
            Geometry::PowerLaw { c, exponent } => Box::new(PowerLawBody { c, exponent }),
            Geometry::Ellipsoid { radius_x, radius_y } => {
                Box::new(EllipsoidBody { radius_x, radius_y })
            }
            Geometry::None => Box::new(NoShape),
        }
    }
}

/// What [`SceneShape::check_fit`] reads: the grid, the path and how the message names them.
#[derive(Debug, Clone, Copy)]
pub struct FitCheck<'a> {
    /// The scene's `[grid]` (to name `grid.n` or `grid.nx`/`grid.ny`).
    pub spec: &'a GridSpec,
    /// The grid built from it.
    pub grid: &'a Grid,
    /// The approach path.
    pub path: &'a ApproachPath,
    /// The approach of the first touch.
    pub first_touch: f64,
    /// The body's surface (a one-step load bonds every element below the deepest approach).
    pub surface: &'a Surface,
    /// The path is the default pull-off rule's (not given by `[protocol]`).
    pub default_path: bool,
    /// The body is a film on a rigid base (it bulges around the contact).
    pub film: bool,
    /// The material (adhesive spheres reach the JKR contact radius).
    pub material: Material,
    /// The law has a finite range: it attracts ahead of the contact, which then grows to the
    /// JKR radius while loading.
    pub finite_range: bool,
}

impl FitCheck<'_> {
    /// Depth of the deepest approach beyond the first touch.
    pub fn depth(&self) -> f64 {
        (self.path.max_approach - self.first_touch).max(0.0)
    }

    /// A thin film's contact reaches √2.5 times the half-space's (Shull's thin-film limit
    /// δ → 0.4a²/R instead of Hertz's a²/R).
    pub fn reach(&self) -> f64 {
        if self.film { 2.5f64.sqrt() } else { 1.0 }
    }

    /// The field that sets the grid's size.
    pub fn size_field(&self) -> &'static str {
        if self.spec.n.is_some() {
            fields::GRID_N
        } else {
            concat!(field_name!(grid.nx), "/", field_name!(grid.ny))
        }
    }

    /// The grid's size as the field gives it: `64` or `64/32`.
    pub fn size_text(&self) -> String {
        let (nx, ny) = self.grid.shape();
        if self.spec.n.is_some() {
            nx.to_string()
        } else {
            format!("{nx}/{ny}")
        }
    }

    /// What set the deepest approach, as a message names it.
    pub fn depth_field(&self) -> &'static str {
        if self.path.is_indentation() {
            fields::PROTOCOL_INDENT
        } else if self.default_path {
            "the default pull-off path's depth"
        } else {
            fields::PROTOCOL_MAX_APPROACH
        }
    }

    /// How to make the path shallower.
    pub fn shallower(&self) -> String {
        if self.default_path {
            format!(
                "give a shallower path ({} with {})",
                fields::PROTOCOL_MAX_APPROACH,
                fields::PROTOCOL_LOAD_STEP
            )
        } else {
            format!("lower {}", self.depth_field())
        }
    }

    /// Whether the path reaches its deepest approach in one load step from out of contact:
    /// that step bonds every element the body penetrates.
    pub fn one_step_load(&self) -> bool {
        !self.path.is_indentation() && loaded_steps(self.path, self.first_touch, 2) <= 1
    }

    /// The warning of a one-step load that puts elements of the grid's outermost ring below
    /// the approach where the shape's own check lets the scene run (roughness on a sphere, or
    /// a shape whose check holds only its Hertz contact): the load step may put them in
    /// contact, and whether contact stays there only the run shows (it counts the steps with
    /// contact at the edge).
    pub fn edge_warning(&self) -> Option<String> {
        if !self.one_step_load() {
            return None;
        }
        // Below the deepest approach: a one-step load penetrates them (on a rough body the
        // roughness' as well as the shape's).
        let n =
            crate::pull_off_path::bonded_on_edge(self.surface.heights(), self.path.max_approach);
        let elements = if n == 1 { "element" } else { "elements" };
        (n > 0).then(|| {
            format!(
                "the one-step load to {} = {} puts {n} {elements} of the free grid's outermost \
                 ring below the approach: the load step may put them in contact, and where \
                 contact stays there the run reports contact at the edge (a wider grid, or {})",
                self.depth_field(),
                num(round4(self.path.max_approach)),
                self.shallower()
            )
        })
    }

    /// The error of an axisymmetric contact of radius `needed` around the origin that a free
    /// grid cannot hold, or `Ok` when it fits; `what` says whose contact and by which rule.
    fn disc_fits(&self, needed: f64, what: &str) -> Result<(), SceneError> {
        let grid = self.grid;
        if needed <= grid.lx().min(grid.ly()) / 2.0 {
            return Ok(());
        }
        let n_needed = count_text((2.0 * needed / grid.dx()).ceil());
        let (nx, ny) = grid.shape();
        Err(SceneError::Inconsistent(format!(
            "{size_field} = {} is too small for {what} needs a free grid of at least {n_needed} × \
             {n_needed} elements at {dx_field} = {} (the grid is {nx} × {ny}); raise {size_field} \
             or {}",
            self.size_text(),
            num(grid.dx()),
            self.shallower(),
            size_field = self.size_field(),
            dx_field = fields::GRID_DX
        )))
    }
}

/// Flags a pull-off radius of fewer than [`MIN_PULL_OFF_RADIUS_ELEMENTS`] elements: the
/// zero-range criterion's mesh rule ([`References::criterion_mesh`], which the shapes set).
pub fn under_resolved(warnings: &mut Vec<String>, what: &str, radius: f64, dx: f64) {
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

/// Whether `grid` holds one isolated body (free, not a strip), where the closed forms of a
/// single body apply; otherwise the warning that says why `name` is missing.
fn single_body(grid: &Grid, name: &str, what: &str) -> Option<String> {
    (grid.nx() == 1 || grid.ny() == 1 || grid.boundary() == Boundary::Periodic).then(|| {
        format!(
            "no {name} reference: {what} is for one body on a free {} × {} grid, not a strip or \
             a periodic array",
            grid.nx(),
            grid.ny()
        )
    })
}

/// Renames the field of a geometry range error to the scene's key (the geometry crate names
/// the punch fields `geometry.punch_radius`/`punch_half_side`).
pub(crate) fn rename(field: &'static str) -> impl Fn(tack_geometry::GeometryError) -> SceneError {
    move |e| match e {
        tack_geometry::GeometryError::OutOfRange { value, allowed, .. } => {
            SceneError::out_of_range(field, value, allowed)
        }
        other => other.into(),
    }
}

/// `shape = "sphere"`: the paraboloid (x² + y²)/(2R).
#[derive(Debug, Clone, Copy)]
pub struct SphereBody {
    /// R.
    pub radius: f64,
}

impl SphereBody {
    /// After a one-step load, the disc √(2R·d) the sphere itself bonds, with d the deepest
    /// approach from its vertex lifted by the mean of the roughness on it (the surface's mean
    /// less the sphere's: 0 for random roughness, the offset of a height map): the roughness'
    /// lowest point does not move the shape's contact, and the elements it adds at the edge get
    /// the builder's warning instead ([`FitCheck::edge_warning`]). `None` when the path loads
    /// in steps.
    fn one_step_disc(&self, fit: &FitCheck<'_>) -> Option<f64> {
        fit.one_step_load().then(|| {
            // The sphere's mean height on the grid, (mean x² + mean y²)/(2R): separable, so
            // no second surface is built.
            let grid = fit.grid;
            let mean_square = |n: usize, at: &dyn Fn(usize) -> f64| {
                (0..n).map(|i| at(i).powi(2)).sum::<f64>() / n as f64
            };
            let sphere_mean = (mean_square(grid.nx(), &|i| grid.x(i))
                + mean_square(grid.ny(), &|j| grid.y(j)))
                / (2.0 * self.radius);
            let offset = fit.surface.mean() - sphere_mean;
            (2.0 * self.radius * (fit.path.max_approach - offset).max(0.0)).sqrt()
        })
    }
}

impl SceneShape for SphereBody {
    fn surface(&self, grid: Grid) -> Result<Surface, SceneError> {
        let sphere = Sphere::new(self.radius).map_err(rename(fields::GEOMETRY_RADIUS))?;
        Ok(Surface::from_shape(grid, &sphere))
    }

    fn references(
        &self,
        m: Material,
        grid: &Grid,
        references: &mut References,
        warnings: &mut Vec<String>,
    ) {
        let radius = self.radius;
        let a_c = tack_analytics::jkr_pull_off_radius(m.e_star, m.gamma, radius);
        let (lx, ly) = (grid.lx(), grid.ly());
        let span = lx.min(ly) / (2.0 * a_c);
        references.pull_off_radius = Some(a_c);
        if grid.nx() == 1 || grid.ny() == 1 {
            warnings.push(format!(
                "no F_JKR reference: a sphere on a {} × {} grid is a strip of spheres, not the \
                 isolated sphere of Eq. 7",
                grid.nx(),
                grid.ny()
            ));
        } else if grid.boundary() == Boundary::Periodic && span < MIN_PERIOD_CONTACT_DIAMETERS {
            warnings.push(format!(
                "no F_JKR reference: the periodic cell {lx:.4e} × {ly:.4e} spans {span:.2} \
                 pull-off contact diameters 2a_c = {:.4e} (at least \
                 {MIN_PERIOD_CONTACT_DIAMETERS} for the isolated sphere of Eq. 7)",
                2.0 * a_c
            ));
        } else {
            references.set_jkr(m.e_star, m.gamma, radius);
        }
        references.criterion_mesh = Some((a_c, "the JKR pull-off contact radius a_c"));
    }

    fn path_sphere(&self) -> Option<(f64, Box<dyn Shape>)> {
        let sphere = Sphere::new(self.radius).ok()?;
        Some((self.radius, Box::new(sphere)))
    }

    fn scales(&self, m: Material) -> Option<(Vec<(&'static str, f64)>, String)> {
        let (e, g, r) = (m.e_star, m.gamma, self.radius);
        Some((
            vec![
                ("F_JKR", tack_analytics::jkr_pull_off_force(g, r)),
                ("d_JKR", tack_analytics::jkr_pull_off_approach(e, g, r)),
                ("a_c", tack_analytics::jkr_pull_off_radius(e, g, r)),
            ],
            format!(
                "{} = {}, {} = {} and {} = {}",
                fields::MATERIAL_E_STAR,
                num(e),
                fields::MATERIAL_GAMMA,
                num(g),
                fields::GEOMETRY_RADIUS,
                num(r)
            ),
        ))
    }

    fn check_fit(&self, fit: &FitCheck<'_>) -> Result<(), SceneError> {
        let (needed, rule) = sphere_contact_reach(
            self.radius,
            fit.depth(),
            fit.grid.dx(),
            fit.reach(),
            fit.material,
            (self.one_step_disc(fit), fit.finite_range),
        );
        fit.disc_fits(
            needed,
            &format!(
                "the sphere: at {} = {} {rule}",
                fit.depth_field(),
                num(fit.path.max_approach)
            ),
        )
    }

    fn describe(&self) -> String {
        format!("sphere R = {}", rounded(self.radius))
    }
}

/// `shape = "flat_punch"`: a circular or square face.
#[derive(Debug, Clone, Copy)]
pub struct PunchBody {
    /// The face.
    pub punch: PunchKind,
    /// A circular face's radius.
    pub radius: Option<f64>,
    /// A square face's half side.
    pub half_side: Option<f64>,
}

impl SceneShape for PunchBody {
    fn surface(&self, grid: Grid) -> Result<Surface, SceneError> {
        let punch = match (self.punch, self.radius, self.half_side) {
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
        Ok(Surface::from_shape(grid, &punch))
    }

    fn references(
        &self,
        m: Material,
        _grid: &Grid,
        references: &mut References,
        _warnings: &mut Vec<String>,
    ) {
        if let (PunchKind::Circle, Some(a)) = (self.punch, self.radius) {
            references.f_kendall = Some(-tack_analytics::kendall_pull_off(m.e_star, m.gamma, a));
            references.pull_off_radius = Some(a);
            references.criterion_mesh = Some((a, "the punch radius a"));
        }
    }

    fn check_fit(&self, fit: &FitCheck<'_>) -> Result<(), SceneError> {
        let (field, size) = match (self.radius, self.half_side) {
            (Some(r), _) => (fields::GEOMETRY_RADIUS, r),
            (_, Some(s)) => (fields::GEOMETRY_HALF_SIDE, s),
            _ => return Ok(()),
        };
        let grid = fit.grid;
        let (nx, ny) = grid.shape();
        // The punch face needs one element to spare beyond its edge on every side. The origin
        // is the centre of element ⌊n/2⌋, so an even side reaches one element less on its
        // positive end: the outermost centre there is at (n − 1 − ⌊n/2⌋)·Δx.
        let reach = |n: usize| (n - 1 - n / 2) as f64 * grid.dx();
        let needed = size + grid.dx() * (1.0 - 1e-9);
        if reach(nx.min(ny)) >= needed {
            return Ok(());
        }
        // reach(n) = ⌊(n − 1)/2⌋·Δx, so the least n is 2⌈needed/Δx⌉ + 1 (in closed form: a
        // search over n never ended for a punch of 1e299).
        let n_needed = count_text(2.0 * (needed / grid.dx()).ceil() + 1.0);
        Err(SceneError::Inconsistent(format!(
            "{field} = {} does not fit the grid: the punch needs a free grid of at least \
             {n_needed} × {n_needed} elements at {dx_field} = {} (the grid is {nx} × {ny}); raise \
             {size_field}",
            num(size),
            num(grid.dx()),
            dx_field = fields::GRID_DX,
            size_field = fit.size_field()
        )))
    }

    fn describe(&self) -> String {
        match (self.punch, self.radius, self.half_side) {
            (PunchKind::Circle, Some(r), _) => format!("circular flat punch a = {}", rounded(r)),
            (PunchKind::Square, _, Some(s)) => {
                format!("square flat punch half side {}", rounded(s))
            }
            _ => "flat punch".to_owned(),
        }
    }
}

/// `shape = "power_law"`: the axisymmetric body c·r^m (a cone for m = 1).
#[derive(Debug, Clone, Copy)]
pub struct PowerLawBody {
    /// c.
    pub c: f64,
    /// m.
    pub exponent: f64,
}

impl SceneShape for PowerLawBody {
    fn surface(&self, grid: Grid) -> Result<Surface, SceneError> {
        let s = Surface::from_shape(grid, &tack_geometry::PowerLaw::new(self.c, self.exponent)?);
        // c·r^m at the grid's corners must stay a normal number (1e300 leaves room for the
        // approach and the roughness).
        if !(s.max().is_finite() && s.max() < 1e300) {
            return Err(SceneError::out_of_range(
                fields::GEOMETRY_C,
                self.c,
                "small enough that c·r^m stays below 1e300 on the grid",
            ));
        }
        Ok(s)
    }

    fn references(
        &self,
        m: Material,
        grid: &Grid,
        references: &mut References,
        warnings: &mut Vec<String>,
    ) {
        let (c, exponent) = (self.c, self.exponent);
        let a_f = tack_analytics::power_law_pull_off_radius(m.e_star, m.gamma, c, exponent);
        let f = tack_analytics::power_law_pull_off_force(m.e_star, m.gamma, c, exponent);
        if let Some(w) = single_body(grid, "F_MDR", "the power-law body's closed form") {
            warnings.push(w);
        } else if f.is_normal() && a_f.is_normal() {
            references.f_mdr = Some(f);
            references.pull_off_radius = Some(a_f);
        }
        references.criterion_mesh = Some((a_f, "the power law's pull-off radius a_F"));
    }

    fn check_fit(&self, fit: &FitCheck<'_>) -> Result<(), SceneError> {
        // The disc the rigid body penetrates at the deepest approach, c·r^m < d, with the
        // sphere's margin (for m = 2 the penetrated disc is √2 times the Hertz radius).
        let disc = (fit.depth() / self.c).powf(1.0 / self.exponent);
        fit.disc_fits(
            SPHERE_FIT_MARGIN * disc,
            &format!(
                "the power-law body: at {} = {} it penetrates a disc of radius (d/c)^(1/m) = {} \
                 that with a 30% margin",
                fit.depth_field(),
                num(fit.path.max_approach),
                num(round4(disc))
            ),
        )
    }

    fn describe(&self) -> String {
        if self.exponent == 1.0 {
            format!("cone z = {}·r", rounded(self.c))
        } else {
            format!(
                "power law z = {}·r^{}",
                rounded(self.c),
                rounded(self.exponent)
            )
        }
    }
}

/// `shape = "ellipsoid"`: the paraboloid x²/(2Rx) + y²/(2Ry).
#[derive(Debug, Clone, Copy)]
pub struct EllipsoidBody {
    /// Rx.
    pub radius_x: f64,
    /// Ry.
    pub radius_y: f64,
}

impl SceneShape for EllipsoidBody {
    fn surface(&self, grid: Grid) -> Result<Surface, SceneError> {
        let (radius_x, radius_y) = (self.radius_x, self.radius_y);
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
                 ellipsoid is a cylinder: the elliptic integrals of its references lose every \
                 digit)",
                num(value)
            )));
        }
        Ok(Surface::from_shape(grid, &shape))
    }

    fn references(
        &self,
        m: Material,
        grid: &Grid,
        references: &mut References,
        warnings: &mut Vec<String>,
    ) {
        let jg =
            tack_analytics::elliptic_jkr_pull_off(m.e_star, m.gamma, self.radius_x, self.radius_y)
                .approach_control;
        let shorter = jg.semi_axis_x.min(jg.semi_axis_y);
        if let Some(w) = single_body(grid, "F_JG", "the elliptic JKR approximation") {
            warnings.push(w);
        } else if jg.force.is_normal() {
            references.f_elliptic = Some(jg.force);
            references.pull_off_radius = Some(shorter);
        }
        references.criterion_mesh =
            Some((shorter, "the elliptic pull-off contact's shorter semi-axis"));
    }

    /// The default path of the sphere of the same Gaussian curvature, √(RxRy); the roughness's
    /// top is measured above the ellipsoid.
    fn path_sphere(&self) -> Option<(f64, Box<dyn Shape>)> {
        let shape = Ellipsoid::new(self.radius_x, self.radius_y).ok()?;
        Some((self.radius_x.sqrt() * self.radius_y.sqrt(), Box::new(shape)))
    }

    fn path_radius_origin(&self) -> &'static str {
        "√(Rx·Ry)"
    }

    fn check_fit(&self, fit: &FitCheck<'_>) -> Result<(), SceneError> {
        // The elliptic Hertz contact at the deepest approach, with the sphere's margin.
        let grid = fit.grid;
        let hertz =
            tack_analytics::elliptic_hertz_from_approach(1.0, self.radius_x, self.radius_y, {
                fit.depth()
            });
        let reach = fit.reach();
        let need = |semi: f64| SPHERE_FIT_MARGIN * reach * semi;
        let (mx, my) = (need(hertz.semi_axis_x), need(hertz.semi_axis_y));
        if mx <= grid.lx() / 2.0 && my <= grid.ly() / 2.0 {
            return Ok(());
        }
        let n_x = count_text((2.0 * mx / grid.dx()).ceil());
        let n_y = count_text((2.0 * my / grid.dx()).ceil());
        let (nx, ny) = grid.shape();
        Err(SceneError::Inconsistent(format!(
            "{size_field} = {} is too small for the ellipsoid: at {} = {} the contact has \
             semi-axes {} × {} (elliptic Hertz{}) that with a 30% margin need a free grid of at \
             least {n_x} × {n_y} elements at {dx_field} = {} (the grid is {nx} × {ny}); raise \
             {size_field} or {}",
            fit.size_text(),
            fit.depth_field(),
            num(fit.path.max_approach),
            num(round4(reach * hertz.semi_axis_x)),
            num(round4(reach * hertz.semi_axis_y)),
            if fit.film {
                ", times √2.5 on a thin film"
            } else {
                ""
            },
            num(grid.dx()),
            fit.shallower(),
            size_field = fit.size_field(),
            dx_field = fields::GRID_DX
        )))
    }

    fn describe(&self) -> String {
        format!(
            "ellipsoid Rx = {}, Ry = {}",
            rounded(self.radius_x),
            rounded(self.radius_y)
        )
    }
}

/// `shape = "none"`: a flat body, only what is added to it (roughness, a map, an array).
#[derive(Debug, Clone, Copy)]
pub struct NoShape;

impl SceneShape for NoShape {
    fn surface(&self, grid: Grid) -> Result<Surface, SceneError> {
        Ok(Surface::flat(grid))
    }

    fn heights_only(&self) -> bool {
        true
    }

    fn describe(&self) -> String {
        "flat".to_owned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_geometry_answers_for_itself() {
        let grid = Grid::square(64, 0.1, Boundary::Free).unwrap();
        let m = Material {
            e_star: 1.0,
            gamma: 0.01,
        };
        let shapes = [
            Geometry::Sphere { radius: 2.0 },
            Geometry::FlatPunch {
                punch: PunchKind::Circle,
                radius: Some(1.0),
                half_side: None,
            },
            Geometry::PowerLaw {
                c: 1.0,
                exponent: 4.0,
            },
            Geometry::Ellipsoid {
                radius_x: 2.0,
                radius_y: 8.0,
            },
            Geometry::None,
        ];
        let mut with_reference = 0;
        for g in shapes {
            let shape = g.shape();
            let s = shape.surface(grid).unwrap();
            assert_eq!(s.heights().dim(), (64, 64));
            let mut r = References::default();
            let mut w = Vec::new();
            shape.references(m, &grid, &mut r, &mut w);
            if r != References::default() {
                with_reference += 1;
                assert!(r.pull_off_radius.is_some(), "{g:?}: {r:?}");
            }
            assert!(!shape.describe().is_empty());
            assert_eq!(shape.heights_only(), g == Geometry::None);
        }
        // Sphere, circular punch, power law, ellipsoid.
        assert_eq!(with_reference, 4);
        // The ellipsoid's path sphere has its Gaussian curvature.
        let e = Geometry::Ellipsoid {
            radius_x: 2.0,
            radius_y: 8.0,
        };
        assert!((e.shape().path_sphere().unwrap().0 - 4.0).abs() < 1e-12);
    }

    /// The sphere's fit check after a one-step load holds the disc √(2R·d) the sphere itself
    /// bonds, d from its vertex, not from the lowest height: a pit at the vertex does not move
    /// it. Roughness that puts elements of the grid's outermost ring below the approach gets a
    /// warning (they bond first; the run shows whether contact stays there), on every side.
    #[test]
    fn a_one_step_load_is_checked_on_the_sphere_and_warned_of_at_the_edge() {
        let n = 64;
        let grid = Grid::square(n, 1.0 / n as f64, Boundary::Free).unwrap();
        let spec = GridSpec {
            n: Some(n),
            nx: None,
            ny: None,
            dx: Some(grid.dx()),
            length: None,
            boundary: crate::scene::BoundaryKind::Free,
            crop: true,
        };
        let body = SphereBody { radius: 1.0 };
        let max_approach = 0.05;
        // Whether `path` loads `surface` in one step, the sphere's check and the edge warning.
        let judge = |surface: &Surface, path: &ApproachPath| {
            let fit = FitCheck {
                spec: &spec,
                grid: &grid,
                path,
                first_touch: surface.min(),
                surface,
                default_path: false,
                film: false,
                material: Material {
                    e_star: 1.0,
                    gamma: 1e-6,
                },
                finite_range: false,
            };
            (
                fit.one_step_load(),
                body.check_fit(&fit).map_err(|e| e.to_string()),
                fit.edge_warning(),
            )
        };
        // The sphere with one element's height `dip.2` at (dip.0, dip.1), loaded in one step
        // to `depth`: the check's error and the edge warning.
        let check = |dip: (usize, usize, f64), depth: f64| {
            let path = ApproachPath::pull_off_only(depth, 1e-3, 1e-4).unwrap();
            let mut h = body.surface(grid).unwrap().heights().clone();
            h[[dip.0, dip.1]] = dip.2;
            let (one_step, fits, warning) = judge(&Surface::new(grid, h).unwrap(), &path);
            assert!(one_step);
            (fits, warning)
        };
        let centre = (n / 2, n / 2, 0.0);
        // The smooth sphere: √(2·0.05) = 0.32 < 0.5.
        assert_eq!(check(centre, max_approach), (Ok(()), None));
        // A pit of −0.09 at the vertex: from the lowest height d = 0.14, whose disc √(2Rd) =
        // 0.53 would pass the edge (while 1.3·√(Rd) = 0.49 fits), but the sphere bonds the
        // same disc of 0.32 (and the pit).
        assert_eq!(check((n / 2, n / 2, -0.09), max_approach), (Ok(()), None));
        // A dip on the outermost ring below the approach: it runs, warned of, on every side
        // (the even grid's positive side ends one element nearer the origin, at 0.5 − Δx).
        for (i, j) in [(0, n / 2), (n - 1, n / 2), (n / 2, 0), (n / 2, n - 1)] {
            let (fits, warning) = check((i, j, 0.0), max_approach);
            assert_eq!(fits, Ok(()));
            let w = warning.expect("an edge warning");
            assert!(
                w.contains("puts 1 element of") && w.contains("outermost ring"),
                "{w}"
            );
        }
        // One element inside the ring, or on it just above the approach: no warning.
        assert_eq!(check((1, n / 2, 0.0), max_approach), (Ok(()), None));
        assert_eq!(check((n - 2, n / 2, 0.0), max_approach), (Ok(()), None));
        let above = (0, n / 2, max_approach + 1e-9);
        assert_eq!(check(above, max_approach), (Ok(()), None));
        // At the approach exactly it is not below it.
        assert_eq!(
            check((0, n / 2, max_approach), max_approach),
            (Ok(()), None)
        );
        // A load whose disc the grid cannot hold is refused, naming the size it needs.
        let (fits, _) = check(centre, 0.2);
        let e = fits.unwrap_err();
        let needed = ((2.0 * (0.4f64).sqrt() + 2.0 / n as f64) * n as f64).ceil();
        assert!(
            e.contains("sqrt(2·R·d) = 0.6325") && e.contains(&format!("at least {needed} ×")),
            "{e}"
        );
        // The same load on the sphere lifted by 0.1 (a height map's offset): d = 0.1 from the
        // lifted vertex, a disc of 0.45, which fits; loaded in steps, no one-step rule.
        let lifted = Surface::new(grid, body.surface(grid).unwrap().heights() + 0.1).unwrap();
        for (path, one_step) in [
            (ApproachPath::pull_off_only(0.2, 1e-3, 1e-4).unwrap(), true),
            (
                ApproachPath::load_retract(0.1, 0.2, 0.01, 1e-3).unwrap(),
                false,
            ),
        ] {
            assert_eq!(judge(&lifted, &path), (one_step, Ok(()), None));
        }
    }

    #[test]
    fn the_reach_of_a_one_step_load_is_the_penetrated_disc() {
        let m = Material {
            e_star: 1.0,
            gamma: 1e-4,
        };
        // Deep load (d ≫ d_s): the penetrated disc √(2Rd) beats 1.3·√(Rd) after one step.
        let (needed, rule) =
            sphere_contact_reach(1.0, 0.01, 1e-3, 1.0, m, (Some(0.02f64.sqrt()), false));
        assert!(
            (needed - ((0.02f64).sqrt() + 1e-3)).abs() < 1e-12,
            "{needed}"
        );
        assert!(rule.contains("one-step load"), "{rule}");
        // Loaded in steps under the zero-range law: the contact stays near Hertz.
        let (needed, rule) = sphere_contact_reach(1.0, 0.01, 1e-3, 1.0, m, (None, false));
        assert!((needed - 1.3 * 0.1).abs() < 1e-12, "{needed}");
        assert!(rule.contains("Hertz"), "{rule}");
        // Shallow under strong adhesion and a finite range: the JKR contact radius exceeds
        // 1.3·√(Rd); the zero-range law loaded in steps stays with Hertz.
        let strong = Material {
            e_star: 1.0,
            gamma: 1e-2,
        };
        let (needed, rule) = sphere_contact_reach(1.0, 1e-3, 1e-4, 1.0, strong, (None, true));
        let a = tack_analytics::jkr_radius_from_approach(1.0, 1e-2, 1.0, 1e-3).unwrap();
        assert!((needed - (a + 1e-4)).abs() < 1e-12, "{needed} {a}");
        assert!(rule.contains("JKR"), "{rule}");
        let (needed, _) = sphere_contact_reach(1.0, 1e-3, 1e-4, 1.0, strong, (None, false));
        assert!((needed - 1.3 * 1e-3f64.sqrt()).abs() < 1e-12, "{needed}");
    }

    #[test]
    fn numbers_in_messages_keep_four_digits() {
        assert_eq!(round4(0.009847450218426965), 0.009847);
        assert_eq!(round4(123456.0), 123500.0);
        assert_eq!(round4(0.0), 0.0);
    }
}
