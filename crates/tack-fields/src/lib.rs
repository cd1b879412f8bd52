//! The scene fields of tack, named once: a constant per field ([`GRID_DX`] is `"grid.dx"`), the
//! table [`FIELDS`] of every field a scene file accepts (its kind and range, and a one-line
//! meaning), the scene's [`SECTIONS`], [`num`], the formatter of numbers in messages, and
//! [`rounded`], that of numbers in reports (`tack run`'s account, `tack info`).
//!
//! Every crate of the workspace names scene fields through these constants, so a message, a
//! check and the documentation (`docs/scenes.md`, checked against [`FIELDS`] by
//! `cargo xtask tidy`) spell a field alike. This crate depends on nothing.
//!
//! ```
//! use tack_fields::{FIELDS, PROTOCOL_UNLOAD_STEP, field};
//!
//! let unload = field(PROTOCOL_UNLOAD_STEP).unwrap();
//! assert_eq!((unload.section(), unload.key()), ("protocol", "unload_step"));
//! assert!(FIELDS.iter().any(|f| f.name == "grid.dx"));
//! ```

/// What a scene field must hold. The scene loader checks every field present against its
/// kind before the schema, so a wrong value is reported as `grid.n = 32.0 is invalid: must be
/// an integer in 1..=65536`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A TOML float or integer.
    Number,
    /// A TOML integer in `min..=max`, described to the user as `allowed`.
    Integer {
        /// Least value allowed.
        min: i64,
        /// Greatest value allowed.
        max: i64,
        /// The range in words, as messages give it (`an integer ≥ 1`).
        allowed: &'static str,
    },
    /// `true` or `false`.
    Bool,
    /// A string.
    Text,
    /// One of these strings.
    Choice(&'static [&'static str]),
    /// A value of several forms that the field's own parser checks (`output.snapshots`);
    /// the forms in words.
    Form(&'static str),
}

/// One field of a scene file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Field {
    /// The dotted name, `section.key` (`"grid.dx"`).
    pub name: &'static str,
    /// What the field must hold.
    pub kind: Kind,
    /// What the field means, in one line.
    pub meaning: &'static str,
}

impl Field {
    /// The section (table) of the field: `grid` for `grid.dx`.
    pub fn section(&self) -> &'static str {
        self.name.split_once('.').map_or(self.name, |(s, _)| s)
    }

    /// The key of the field within its section: `dx` for `grid.dx`.
    pub fn key(&self) -> &'static str {
        self.name.split_once('.').map_or(self.name, |(_, k)| k)
    }
}

/// The field of this dotted name, if a scene has one.
pub fn field(name: &str) -> Option<&'static Field> {
    FIELDS.iter().find(|f| f.name == name)
}

/// The sections of a scene file, each a TOML table (`version` is the only top-level key
/// besides them).
pub const SECTIONS: [&str; 9] = [
    "material",
    "body",
    "adhesion",
    "geometry",
    "roughness",
    "grid",
    "solver",
    "protocol",
    "output",
];

/// Defines, from one list, a constant per field and the macro [`field_name!`] that gives the
/// same name as a literal.
macro_rules! scene_fields {
    ($($constant:ident = $section:ident . $key:ident,)*) => {
        $(
            #[doc = concat!("`", stringify!($section), ".", stringify!($key), "`.")]
            pub const $constant: &str = concat!(stringify!($section), ".", stringify!($key));
        )*

        /// Every constant, in the order of the list (the tests hold [`FIELDS`] to it).
        #[cfg(test)]
        const CONSTANTS: &[&str] = &[$($constant),*];

        /// The name of a scene field as a string literal, for the places that need one rather
        /// than a constant: `concat!` (a `&'static str` message built at compile time) and
        /// attributes. Only the fields of [`FIELDS`] are accepted, so a typo fails to compile.
        ///
        /// ```
        /// const ALLOWED: &str = concat!("≥ ", tack_fields::field_name!(protocol.start));
        /// assert_eq!(ALLOWED, "≥ protocol.start");
        /// assert_eq!(tack_fields::field_name!(grid.dx), tack_fields::GRID_DX);
        /// ```
        #[macro_export]
        macro_rules! field_name {
            $(
                ($section . $key) => {
                    concat!(stringify!($section), ".", stringify!($key))
                };
            )*
        }
    };
}

scene_fields! {
    MATERIAL_E_STAR = material.e_star,
    MATERIAL_GAMMA = material.gamma,
    MATERIAL_PRONY = material.prony,
    BODY_KIND = body.kind,
    BODY_THICKNESS = body.thickness,
    BODY_POISSON = body.poisson,
    BODY_INTERFACE = body.interface,
    ADHESION_MODEL = adhesion.model,
    ADHESION_SIGMA0 = adhesion.sigma0,
    ADHESION_RANGE = adhesion.range,
    ADHESION_GAMMA_MAP = adhesion.gamma_map,
    ADHESION_DATASET = adhesion.dataset,
    ADHESION_PATTERN = adhesion.pattern,
    ADHESION_GAMMA_B = adhesion.gamma_b,
    ADHESION_PERIOD = adhesion.period,
    ADHESION_FRACTION = adhesion.fraction,
    ADHESION_CORRELATION_LENGTH = adhesion.correlation_length,
    ADHESION_CONTRAST = adhesion.contrast,
    ADHESION_SEED = adhesion.seed,
    GEOMETRY_SHAPE = geometry.shape,
    GEOMETRY_RADIUS = geometry.radius,
    GEOMETRY_PUNCH = geometry.punch,
    GEOMETRY_HALF_SIDE = geometry.half_side,
    GEOMETRY_C = geometry.c,
    GEOMETRY_EXPONENT = geometry.exponent,
    GEOMETRY_RADIUS_X = geometry.radius_x,
    GEOMETRY_RADIUS_Y = geometry.radius_y,
    ROUGHNESS_KIND = roughness.kind,
    ROUGHNESS_H = roughness.h,
    ROUGHNESS_LAMBDA = roughness.lambda,
    ROUGHNESS_HURST = roughness.hurst,
    ROUGHNESS_Q0 = roughness.q0,
    ROUGHNESS_Q1 = roughness.q1,
    ROUGHNESS_SEED = roughness.seed,
    ROUGHNESS_PATH = roughness.path,
    ROUGHNESS_DATASET = roughness.dataset,
    GRID_N = grid.n,
    GRID_NX = grid.nx,
    GRID_NY = grid.ny,
    GRID_DX = grid.dx,
    GRID_LENGTH = grid.length,
    GRID_BOUNDARY = grid.boundary,
    GRID_CROP = grid.crop,
    SOLVER_KAPPA = solver.kappa,
    SOLVER_TOLERANCE = solver.tolerance,
    SOLVER_MAX_ITERATIONS = solver.max_iterations,
    SOLVER_MAX_ACTIVE_SET_ITERATIONS = solver.max_active_set_iterations,
    SOLVER_ROUND_TOLERANCE = solver.round_tolerance,
    SOLVER_LOCAL_RELAXATION = solver.local_relaxation,
    SOLVER_CASCADE = solver.cascade,
    PROTOCOL_INDENT = protocol.indent,
    PROTOCOL_START = protocol.start,
    PROTOCOL_MAX_APPROACH = protocol.max_approach,
    PROTOCOL_LOAD_STEP = protocol.load_step,
    PROTOCOL_UNLOAD_STEP = protocol.unload_step,
    PROTOCOL_COARSE_UNLOAD_STEP = protocol.coarse_unload_step,
    PROTOCOL_REFINE_PULL_OFF = protocol.refine_pull_off,
    PROTOCOL_RETRACT_TO = protocol.retract_to,
    PROTOCOL_MAX_STEPS = protocol.max_steps,
    PROTOCOL_SPEED = protocol.speed,
    PROTOCOL_UNLOAD_SPEED = protocol.unload_speed,
    PROTOCOL_DWELL = protocol.dwell,
    PROTOCOL_DWELL_STEPS = protocol.dwell_steps,
    OUTPUT_SNAPSHOTS = output.snapshots,
    OUTPUT_SURFACE = output.surface,
}

/// The forms `output.snapshots` takes, in words (the [`Kind::Form`] of [`OUTPUT_SNAPSHOTS`]).
pub const SNAPSHOT_FORMS: &str = "\"none\", \"all\", \"pull_off\", { every = k } with k ≥ 1, or \
                                  { steps = [i, ...] } with indices ≥ 0";

/// An integer ≥ 1 (counts and caps).
const AT_LEAST_ONE: Kind = Kind::Integer {
    min: 1,
    max: i64::MAX,
    allowed: "an integer ≥ 1",
};

/// An element count of a grid side.
const ELEMENTS: Kind = Kind::Integer {
    min: 1,
    max: 65536,
    allowed: "an integer in 1..=65536",
};

/// Shorthand for a table entry.
const fn f(name: &'static str, kind: Kind, meaning: &'static str) -> Field {
    Field {
        name,
        kind,
        meaning,
    }
}

/// Every field a scene file accepts, section by section in the order of `docs/scenes.md`,
/// with what it must hold and what it means. The ranges of numbers (`> 0`, finite, ...) are
/// checked when a scene is validated; the kinds here when it is read.
pub const FIELDS: &[Field] = &[
    f(MATERIAL_E_STAR, Kind::Number, "effective modulus E*"),
    f(
        MATERIAL_GAMMA,
        Kind::Number,
        "work of adhesion γ per unit area (0: non-adhesive)",
    ),
    f(
        MATERIAL_PRONY,
        Kind::Form("a list of arms [E_k, tau_k], each a pair of numbers > 0"),
        "viscoelastic arms of E(t) = E0 + Σ E_k e^(−t/τ_k), E0 = material.e_star relaxed",
    ),
    f(
        BODY_KIND,
        Kind::Choice(&["half_space", "layer"]),
        "the elastic body: a half-space or a layer on a rigid base",
    ),
    f(BODY_THICKNESS, Kind::Number, "layer: thickness h"),
    f(BODY_POISSON, Kind::Number, "layer: Poisson ratio ν"),
    f(
        BODY_INTERFACE,
        Kind::Choice(&["bonded", "frictionless"]),
        "layer: how it meets its rigid base",
    ),
    f(
        ADHESION_MODEL,
        Kind::Choice(&[
            "jkr_limit",
            "dugdale",
            "exponential",
            "lennard_jones",
            "smoothed_dugdale",
        ]),
        "zero-range criterion, a Dugdale cohesive zone, or a smooth law (exponential, \
         Lennard-Jones 9–3, the Dugdale law smoothed over an element) with a hard wall",
    ),
    f(
        ADHESION_SIGMA0,
        Kind::Number,
        "Dugdale and smoothed Dugdale: cohesive tension σ0 (the range is γ/σ0)",
    ),
    f(
        ADHESION_RANGE,
        Kind::Number,
        "smooth laws: the range ρ of the exponential law, the equilibrium separation ε of the \
         Lennard-Jones law",
    ),
    f(
        ADHESION_GAMMA_MAP,
        Kind::Text,
        "work of adhesion per element: a map file (text or HDF5, the grid's shape), relative to \
         the scene file's directory",
    ),
    f(
        ADHESION_DATASET,
        Kind::Text,
        "HDF5 dataset of a work-of-adhesion map",
    ),
    f(
        ADHESION_PATTERN,
        Kind::Choice(&["uniform", "stripes", "rings", "checkerboard", "random"]),
        "a generated work-of-adhesion pattern (material.gamma is phase a)",
    ),
    f(
        ADHESION_GAMMA_B,
        Kind::Number,
        "stripes, rings, checkerboard: the work of adhesion of phase b (≥ 0)",
    ),
    f(
        ADHESION_PERIOD,
        Kind::Number,
        "stripes, rings, checkerboard: the period of the pattern",
    ),
    f(
        ADHESION_FRACTION,
        Kind::Number,
        "stripes, rings: the share of each period that is phase b (0 to 1, default 0.5)",
    ),
    f(
        ADHESION_CORRELATION_LENGTH,
        Kind::Number,
        "random: the correlation length ℓ of the log-normal γ field",
    ),
    f(
        ADHESION_CONTRAST,
        Kind::Number,
        "random: the coefficient of variation of γ (std/mean, ≥ 0)",
    ),
    f(
        ADHESION_SEED,
        Kind::Integer {
            min: 0,
            max: i64::MAX,
            allowed: "an integer ≥ 0 (the seed of the random γ field)",
        },
        "random: the seed of the γ field (default 1)",
    ),
    f(
        GEOMETRY_SHAPE,
        Kind::Choice(&["sphere", "flat_punch", "power_law", "ellipsoid", "none"]),
        "the macroscopic body",
    ),
    f(
        GEOMETRY_RADIUS,
        Kind::Number,
        "radius of a sphere or of a circular punch face",
    ),
    f(
        GEOMETRY_PUNCH,
        Kind::Choice(&["circle", "square"]),
        "the face of a flat punch",
    ),
    f(
        GEOMETRY_HALF_SIDE,
        Kind::Number,
        "half the side of a square punch face",
    ),
    f(
        GEOMETRY_C,
        Kind::Number,
        "power law z = c·r^m: the coefficient c",
    ),
    f(
        GEOMETRY_EXPONENT,
        Kind::Number,
        "power law z = c·r^m: the exponent m (1 = cone, 2 = paraboloid)",
    ),
    f(
        GEOMETRY_RADIUS_X,
        Kind::Number,
        "ellipsoid z = x²/(2Rx) + y²/(2Ry): the radius Rx along x",
    ),
    f(
        GEOMETRY_RADIUS_Y,
        Kind::Number,
        "ellipsoid z = x²/(2Rx) + y²/(2Ry): the radius Ry along y",
    ),
    f(
        ROUGHNESS_KIND,
        Kind::Choice(&["waviness1d", "waviness2d", "random", "file"]),
        "the type of roughness added to the shape",
    ),
    f(
        ROUGHNESS_H,
        Kind::Number,
        "amplitude of a waviness, rms height of random roughness",
    ),
    f(ROUGHNESS_LAMBDA, Kind::Number, "wavelength of a waviness"),
    f(
        ROUGHNESS_HURST,
        Kind::Number,
        "Hurst exponent H of random roughness",
    ),
    f(
        ROUGHNESS_Q0,
        Kind::Number,
        "lower cut-off wave vector of random roughness",
    ),
    f(
        ROUGHNESS_Q1,
        Kind::Number,
        "upper cut-off wave vector of random roughness",
    ),
    f(
        ROUGHNESS_SEED,
        Kind::Integer {
            min: 0,
            max: i64::MAX,
            allowed: "an integer ≥ 0 (the seed of the random phases)",
        },
        "seed of the random phases",
    ),
    f(
        ROUGHNESS_PATH,
        Kind::Text,
        "measured height map, relative to the scene file's directory",
    ),
    f(
        ROUGHNESS_DATASET,
        Kind::Text,
        "HDF5 dataset of a measured height map",
    ),
    f(GRID_N, ELEMENTS, "elements per side of a square grid"),
    f(GRID_NX, ELEMENTS, "elements along x"),
    f(GRID_NY, ELEMENTS, "elements along y"),
    f(GRID_DX, Kind::Number, "element size"),
    f(GRID_LENGTH, Kind::Number, "domain length along x, nx·dx"),
    f(
        GRID_BOUNDARY,
        Kind::Choice(&["free", "periodic"]),
        "non-periodic half-space or one period of a repeated pattern",
    ),
    f(
        GRID_CROP,
        Kind::Bool,
        "crop the domain to where contact can occur",
    ),
    f(
        SOLVER_KAPPA,
        Kind::Number,
        "Pohrt–Popov constant κ of σ_c = sqrt(E*γ/(κΔx))",
    ),
    f(SOLVER_TOLERANCE, Kind::Number, "relative CG tolerance"),
    f(
        SOLVER_MAX_ITERATIONS,
        AT_LEAST_ONE,
        "cap on CG iterations per solve",
    ),
    f(
        SOLVER_MAX_ACTIVE_SET_ITERATIONS,
        AT_LEAST_ONE,
        "cap on detach/attach rounds per approach step",
    ),
    f(
        SOLVER_ROUND_TOLERANCE,
        Kind::Number,
        "CG tolerance of the inexact detach/attach rounds (0: every round exact)",
    ),
    f(
        SOLVER_LOCAL_RELAXATION,
        Kind::Bool,
        "relax each round's released tension on small windows before the next solve",
    ),
    f(
        SOLVER_CASCADE,
        Kind::Bool,
        "release what the relaxed tension puts clearly past the criterion before the next solve",
    ),
    f(
        PROTOCOL_INDENT,
        Kind::Number,
        "one step pressed in to this approach, no retraction",
    ),
    f(PROTOCOL_START, Kind::Number, "first approach"),
    f(PROTOCOL_MAX_APPROACH, Kind::Number, "deepest approach"),
    f(
        PROTOCOL_LOAD_STEP,
        Kind::Number,
        "approach increment while loading",
    ),
    f(
        PROTOCOL_UNLOAD_STEP,
        Kind::Number,
        "approach decrement while retracting",
    ),
    f(
        PROTOCOL_COARSE_UNLOAD_STEP,
        Kind::Number,
        "approach decrement while retracting and the force is still compressive",
    ),
    f(
        PROTOCOL_REFINE_PULL_OFF,
        Kind::Bool,
        "coarse steps throughout the retraction, the pull-off's brackets retraced in fine steps",
    ),
    f(
        PROTOCOL_RETRACT_TO,
        Kind::Number,
        "stop retracting below this approach",
    ),
    f(
        PROTOCOL_MAX_STEPS,
        AT_LEAST_ONE,
        "cap on the number of steps",
    ),
    f(
        PROTOCOL_SPEED,
        Kind::Number,
        "viscoelastic: approach rate of the loading (and of the retraction unless unload_speed)",
    ),
    f(
        PROTOCOL_UNLOAD_SPEED,
        Kind::Number,
        "viscoelastic: approach rate of the retraction",
    ),
    f(
        PROTOCOL_DWELL,
        Kind::Number,
        "viscoelastic: time held at the deepest approach before the retraction",
    ),
    f(
        PROTOCOL_DWELL_STEPS,
        AT_LEAST_ONE,
        "viscoelastic: time steps of the hold",
    ),
    f(
        OUTPUT_SNAPSHOTS,
        Kind::Form(SNAPSHOT_FORMS),
        "which steps store their pressure field and bonded mask",
    ),
    f(OUTPUT_SURFACE, Kind::Bool, "store the surface heights"),
];

/// A number as a person reads it in a message: plain for moderate magnitudes (and for 0, NaN
/// and infinities), otherwise in scientific notation with the shortest digits that round-trip
/// (`1.797e308`, not 309 digits; `5e-324`).
pub fn num(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-5..1e16).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// A count of elements (across a law's process zone, say) as warnings and reports show it: two
/// decimals, trailing zeros dropped, and two significant digits below 0.01, where two decimals
/// would read as none.
///
/// ```
/// assert_eq!(tack_fields::elements(1.2704), "1.27");
/// assert_eq!(tack_fields::elements(0.6), "0.6");
/// assert_eq!(tack_fields::elements(543.2549), "543.25");
/// assert_eq!(tack_fields::elements(5.41e-6), "5.4e-6");
/// ```
pub fn elements(x: f64) -> String {
    if x.abs() < 0.01 && x != 0.0 {
        format!("{x:.1e}")
    } else {
        num((x * 100.0).round() / 100.0)
    }
}

/// A number as a report shows it: 6 significant digits, in plain notation for magnitudes in
/// [1e-3, 1e6), trailing zeros dropped (`0.00984745`, not `0.009847450218426965`). Messages that
/// quote a value a user gave use [`num`] instead, which keeps every digit.
///
/// ```
/// assert_eq!(tack_fields::rounded(0.009847450218426965), "0.00984745");
/// assert_eq!(tack_fields::rounded(-5.3454057683), "-5.34541");
/// ```
pub fn rounded(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let mag = x.abs().log10().floor();
    if (-3.0..6.0).contains(&mag) {
        let decimals = (5.0 - mag).max(0.0) as usize;
        let s = format!("{x:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_owned()
        } else {
            s
        }
    } else {
        let s = format!("{x:.5e}");
        match s.split_once('e') {
            Some((mantissa, exp)) if mantissa.contains('.') => format!(
                "{}e{exp}",
                mantissa.trim_end_matches('0').trim_end_matches('.')
            ),
            _ => s,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reports_round_to_six_significant_digits() {
        assert_eq!(rounded(-5.3454057683), "-5.34541");
        assert_eq!(rounded(0.005), "0.005");
        assert_eq!(rounded(3.0), "3");
        assert_eq!(rounded(123456.7), "123457");
        assert_eq!(rounded(1.5e-7), "1.5e-7");
        assert_eq!(rounded(5e-4), "5e-4");
        assert_eq!(rounded(0.009847450218426965), "0.00984745");
        assert_eq!(rounded(0.8772053214638599), "0.877205");
        assert_eq!(rounded(f64::NAN), "NaN");
        assert_eq!(rounded(0.0), "0");
    }

    #[test]
    fn names_are_unique_dotted_and_in_known_sections() {
        for (i, f) in FIELDS.iter().enumerate() {
            assert!(SECTIONS.contains(&f.section()), "{}", f.name);
            assert!(!f.key().is_empty() && !f.key().contains('.'), "{}", f.name);
            assert!(
                FIELDS[..i].iter().all(|g| g.name != f.name),
                "{} twice",
                f.name
            );
            assert!(!f.meaning.is_empty(), "{}", f.name);
        }
        assert_eq!(FIELDS.len(), 65);
    }

    #[test]
    fn the_table_has_every_constant_in_order() {
        let names: Vec<&str> = FIELDS.iter().map(|f| f.name).collect();
        assert_eq!(names, CONSTANTS);
    }

    #[test]
    fn constants_and_literals_agree() {
        assert_eq!(field_name!(protocol.unload_step), PROTOCOL_UNLOAD_STEP);
        assert_eq!(field_name!(output.surface), FIELDS[FIELDS.len() - 1].name);
        assert_eq!(MATERIAL_E_STAR, "material.e_star");
    }

    #[test]
    fn lookup_by_name() {
        assert_eq!(field(GRID_DX).map(|f| f.kind), Some(Kind::Number));
        assert_eq!(field("grid.dy"), None);
        let unload = field(PROTOCOL_UNLOAD_STEP).unwrap();
        assert_eq!(
            (unload.section(), unload.key()),
            ("protocol", "unload_step")
        );
    }

    #[test]
    fn numbers_are_plain_or_shortest_scientific() {
        assert_eq!(num(0.0), "0");
        assert_eq!(num(0.25), "0.25");
        assert_eq!(num(-3.0), "-3");
        assert_eq!(num(1e-5), "0.00001");
        assert_eq!(num(1.5e-7), "1.5e-7");
        assert_eq!(num(1.797e308), "1.797e308");
        assert_eq!(num(5e-324), "5e-324");
        assert_eq!(num(1e16), "1e16");
        assert_eq!(num(f64::NAN), "NaN");
        assert_eq!(num(f64::NEG_INFINITY), "-inf");
    }
}

/// The example of README.md, run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctest;
