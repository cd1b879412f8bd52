//! Analytic shapes (sphere, ellipsoid, power law, 1D/2D waviness, flat punch) as height functions `f(x, y)` sampled on a grid.
//!
//! Shapes compose by adding surfaces: the sphere with 2D waviness of Eq. 6 is
//! `Surface::from_shape(grid, &sphere)` followed by `add_shape(&waviness)`.

use std::f64::consts::TAU;

use tack_fields as fields;

use crate::error::{GeometryError, non_negative, positive};

/// A rigid body's height above its lowest point as a function of position.
pub trait Shape {
    /// Height `f(x, y)`: the gap between body and flat half-space at zero approach.
    fn height(&self, x: f64, y: f64) -> f64;
}

/// A sphere of radius `R` in the parabolic (Hertz) approximation: `f = (x² + y²)/(2R)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    radius: f64,
}

impl Sphere {
    /// A sphere with a finite radius `R > 0` (field `geometry.radius`).
    pub fn new(radius: f64) -> Result<Self, GeometryError> {
        Ok(Self {
            radius: positive(fields::GEOMETRY_RADIUS, radius)?,
        })
    }
    /// The radius `R`.
    pub fn radius(&self) -> f64 {
        self.radius
    }
}

impl Shape for Sphere {
    fn height(&self, x: f64, y: f64) -> f64 {
        (x * x + y * y) / (2.0 * self.radius)
    }
}

/// An ellipsoid in the parabolic (Hertz) approximation, like [`Sphere`]:
/// `f = x²/(2Rx) + y²/(2Ry)`, principal axes along x and y; `Rx = Ry = R` is the sphere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipsoid {
    radius_x: f64,
    radius_y: f64,
}

impl Ellipsoid {
    /// An ellipsoid with finite radii `Rx > 0` (field `geometry.radius_x`) and `Ry > 0` (field
    /// `geometry.radius_y`).
    pub fn new(radius_x: f64, radius_y: f64) -> Result<Self, GeometryError> {
        Ok(Self {
            radius_x: positive(fields::GEOMETRY_RADIUS_X, radius_x)?,
            radius_y: positive(fields::GEOMETRY_RADIUS_Y, radius_y)?,
        })
    }
    /// The radius of curvature `Rx` in the x–z plane.
    pub fn radius_x(&self) -> f64 {
        self.radius_x
    }
    /// The radius of curvature `Ry` in the y–z plane.
    pub fn radius_y(&self) -> f64 {
        self.radius_y
    }
}

impl Shape for Ellipsoid {
    fn height(&self, x: f64, y: f64) -> f64 {
        x * x / (2.0 * self.radius_x) + y * y / (2.0 * self.radius_y)
    }
}

/// Largest exponent of a [`PowerLaw`] body: far beyond the flat-tipped bodies of experiments
/// (the scene checks that `c·r^m` stays finite on its grid).
pub const MAX_POWER_LAW_EXPONENT: f64 = 16.0;

/// An axisymmetric power-law body `f = c·r^m`, `r² = x² + y²`: a cone for `m = 1` (tip
/// included), the paraboloid of a sphere of radius `1/(2c)` for `m = 2`, flatter tips above.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerLaw {
    c: f64,
    exponent: f64,
}

impl PowerLaw {
    /// A power law with `c > 0` (field `geometry.c`) and `1 ≤ m ≤`
    /// [`MAX_POWER_LAW_EXPONENT`] (field `geometry.exponent`).
    pub fn new(c: f64, exponent: f64) -> Result<Self, GeometryError> {
        let c = positive(fields::GEOMETRY_C, c)?;
        if !(exponent.is_finite() && (1.0..=MAX_POWER_LAW_EXPONENT).contains(&exponent)) {
            return Err(GeometryError::OutOfRange {
                field: fields::GEOMETRY_EXPONENT,
                value: exponent,
                allowed: "a number in [1, 16]",
            });
        }
        Ok(Self { c, exponent })
    }
    /// The coefficient `c`.
    pub fn c(&self) -> f64 {
        self.c
    }
    /// The exponent `m`.
    pub fn exponent(&self) -> f64 {
        self.exponent
    }
}

impl Shape for PowerLaw {
    fn height(&self, x: f64, y: f64) -> f64 {
        self.c * x.hypot(y).powf(self.exponent)
    }
}

/// Checks a waviness amplitude `h ≥ 0` and wavelength `λ > 0` (fields `roughness.h`, `roughness.lambda`).
fn waviness(h: f64, lambda: f64) -> Result<(f64, f64), GeometryError> {
    Ok((
        non_negative(fields::ROUGHNESS_H, h)?,
        positive(fields::ROUGHNESS_LAMBDA, lambda)?,
    ))
}

/// One-dimensional waviness (Eq. 1): `f = h[1 − cos(2πx/λ)]`, lowest (first contact) at `x = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Waviness1d {
    h: f64,
    lambda: f64,
}

impl Waviness1d {
    /// Waviness with amplitude `h ≥ 0` and wavelength `λ > 0`, both finite.
    pub fn new(h: f64, lambda: f64) -> Result<Self, GeometryError> {
        let (h, lambda) = waviness(h, lambda)?;
        Ok(Self { h, lambda })
    }
    /// The amplitude `h`.
    pub fn h(&self) -> f64 {
        self.h
    }
    /// The wavelength `λ`.
    pub fn lambda(&self) -> f64 {
        self.lambda
    }
}

impl Shape for Waviness1d {
    fn height(&self, x: f64, _y: f64) -> f64 {
        self.h * (1.0 - (TAU * x / self.lambda).cos())
    }
}

/// Two-dimensional waviness (Eq. 4): `f = h[1 − cos(2πx/λ)·cos(2πy/λ)]`, minimum at the origin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Waviness2d {
    h: f64,
    lambda: f64,
}

impl Waviness2d {
    /// Waviness with amplitude `h ≥ 0` and wavelength `λ > 0`, both finite.
    pub fn new(h: f64, lambda: f64) -> Result<Self, GeometryError> {
        let (h, lambda) = waviness(h, lambda)?;
        Ok(Self { h, lambda })
    }
    /// The amplitude `h`.
    pub fn h(&self) -> f64 {
        self.h
    }
    /// The wavelength `λ`.
    pub fn lambda(&self) -> f64 {
        self.lambda
    }
}

impl Shape for Waviness2d {
    fn height(&self, x: f64, y: f64) -> f64 {
        let k = TAU / self.lambda;
        self.h * (1.0 - (k * x).cos() * (k * y).cos())
    }
}

/// The face of a [`FlatPunch`], centred on the origin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PunchFace {
    /// A circle of radius `radius`.
    Circle {
        /// Radius `a` of the face.
        radius: f64,
    },
    /// An axis-aligned square of side `2·half_side`.
    Square {
        /// Half the side of the face.
        half_side: f64,
    },
}

/// Default [`FlatPunch::lift_height`] in units of the face size (radius or half-side).
pub const DEFAULT_PUNCH_LIFT: f64 = 1e3;

/// A rigid flat-ended punch: height 0 on its face, [`FlatPunch::lift_height`] everywhere else.
///
/// Heights must be finite, so "never touches" is a finite lift: by default
/// [`DEFAULT_PUNCH_LIFT`] times the face size, far beyond any approach a contact run reaches.
/// A solver may treat every element with `f ≥ lift_height()` as never in contact. Element
/// centres on the rim (to 1e-12 relative) count as on the face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlatPunch {
    face: PunchFace,
    lift: f64,
}

impl FlatPunch {
    /// A circular punch of radius `a > 0` (field `geometry.punch_radius`).
    pub fn circular(radius: f64) -> Result<Self, GeometryError> {
        let radius = positive("geometry.punch_radius", radius)?;
        Self::with_face(PunchFace::Circle { radius }, radius)
    }
    /// A square punch of half-side `s > 0` (field `geometry.punch_half_side`).
    pub fn square(half_side: f64) -> Result<Self, GeometryError> {
        let half_side = positive("geometry.punch_half_side", half_side)?;
        Self::with_face(PunchFace::Square { half_side }, half_side)
    }
    fn with_face(face: PunchFace, size: f64) -> Result<Self, GeometryError> {
        if !(DEFAULT_PUNCH_LIFT * size).is_finite() {
            // The lift outside the face is DEFAULT_PUNCH_LIFT times the size: name the size.
            return Err(GeometryError::OutOfRange {
                field: match face {
                    PunchFace::Circle { .. } => "geometry.punch_radius",
                    PunchFace::Square { .. } => "geometry.punch_half_side",
                },
                value: size,
                allowed: "a finite number > 0 and ≤ 1e300",
            });
        }
        Self { face, lift: 1.0 }.with_lift(DEFAULT_PUNCH_LIFT * size)
    }
    /// The same punch with another finite lift `> 0` outside the face (field `geometry.punch_lift`).
    pub fn with_lift(self, lift: f64) -> Result<Self, GeometryError> {
        Ok(Self {
            lift: positive("geometry.punch_lift", lift)?,
            ..self
        })
    }
    /// The face shape and size.
    pub fn face(&self) -> PunchFace {
        self.face
    }
    /// The height of every point off the face.
    pub fn lift_height(&self) -> f64 {
        self.lift
    }
    /// Whether `(x, y)` lies on the face (rim included).
    pub fn on_face(&self, x: f64, y: f64) -> bool {
        const RIM: f64 = 1.0 + 1e-12;
        match self.face {
            PunchFace::Circle { radius } => x * x + y * y <= radius * radius * RIM * RIM,
            PunchFace::Square { half_side } => x.abs().max(y.abs()) <= half_side * RIM,
        }
    }
}

impl Shape for FlatPunch {
    fn height(&self, x: f64, y: f64) -> f64 {
        if self.on_face(x, y) { 0.0 } else { self.lift }
    }
}

#[cfg(test)]
mod tests {

    #[test]
    fn power_law_heights_and_checks() {
        let cone = PowerLaw::new(0.5, 1.0).unwrap();
        assert_eq!(cone.height(3.0, 4.0), 2.5);
        assert_eq!(cone.height(0.0, 0.0), 0.0);
        let sphere = PowerLaw::new(0.25, 2.0).unwrap();
        let r2 = Sphere::new(2.0).unwrap();
        assert!((sphere.height(0.3, -0.7) - r2.height(0.3, -0.7)).abs() < 1e-15);
        for (c, m, field) in [
            (0.0, 2.0, "geometry.c"),
            (f64::NAN, 2.0, "geometry.c"),
            (1.0, 0.5, "geometry.exponent"),
            (1.0, 17.0, "geometry.exponent"),
            (1.0, f64::INFINITY, "geometry.exponent"),
        ] {
            let e = PowerLaw::new(c, m).unwrap_err().to_string();
            assert!(e.starts_with(field), "{e}");
        }
    }

    use super::*;

    #[test]
    fn a_punch_too_large_for_its_lift_names_its_size_compactly() {
        let e = FlatPunch::circular(1e306).unwrap_err().to_string();
        assert!(e.contains("geometry.punch_radius = 1e306"), "{e}");
        assert!(!e.contains("inf"), "{e}");
        let e = FlatPunch::square(1e306).unwrap_err().to_string();
        assert!(e.contains("geometry.punch_half_side = 1e306"), "{e}");
        assert!(FlatPunch::circular(1e300).is_ok());
    }

    #[test]
    fn sphere_is_parabolic_and_validated() {
        let s = Sphere::new(2.0).unwrap();
        assert_eq!(s.height(0.0, 0.0), 0.0);
        assert_eq!(s.height(2.0, 0.0), 1.0);
        assert_eq!(s.height(0.0, -2.0), 1.0);
        assert!(Sphere::new(-1.0).is_err());
        assert!(Sphere::new(f64::NAN).is_err());
    }

    #[test]
    fn ellipsoid_is_a_paraboloid_and_validated() {
        let e = Ellipsoid::new(2.0, 0.5).unwrap();
        assert_eq!((e.radius_x(), e.radius_y()), (2.0, 0.5));
        assert_eq!(e.height(0.0, 0.0), 0.0);
        assert_eq!(e.height(2.0, 0.0), 1.0);
        assert_eq!(e.height(0.0, -1.0), 1.0);
        assert_eq!(e.height(2.0, 1.0), 2.0);
        let round = Ellipsoid::new(1.5, 1.5).unwrap();
        let sphere = Sphere::new(1.5).unwrap();
        for (x, y) in [(0.3, -0.7), (1.0, 2.0), (-4.0, 0.1)] {
            assert!((round.height(x, y) - sphere.height(x, y)).abs() < 1e-15);
        }
        for (rx, ry, field) in [
            (0.0, 1.0, "geometry.radius_x"),
            (f64::NAN, 1.0, "geometry.radius_x"),
            (1.0, -1.0, "geometry.radius_y"),
            (1.0, f64::INFINITY, "geometry.radius_y"),
        ] {
            let e = Ellipsoid::new(rx, ry).unwrap_err().to_string();
            assert!(e.starts_with(field), "{e}");
        }
    }

    #[test]
    fn waviness_follows_eqs_1_and_4() {
        let w1 = Waviness1d::new(0.5, 2.0).unwrap();
        let w2 = Waviness2d::new(0.5, 2.0).unwrap();
        assert_eq!(w1.height(0.0, 0.3), 0.0);
        assert!((w1.height(1.0, 0.7) - 1.0).abs() < 1e-15);
        assert!((w1.height(0.5, 0.0) - 0.5).abs() < 1e-15);
        assert_eq!(w2.height(0.0, 0.0), 0.0);
        assert!((w2.height(1.0, 0.0) - 1.0).abs() < 1e-15);
        assert!((w2.height(1.0, 1.0)).abs() < 1e-15);
        assert!((w2.height(0.5, 0.3) - 0.5).abs() < 1e-15);
        assert!(Waviness2d::new(0.0, 1.0).is_ok());
    }

    #[test]
    fn waviness_rejects_bad_parameters_naming_the_field() {
        for (h, lambda, field) in [
            (-1.0, 1.0, "roughness.h"),
            (f64::NAN, 1.0, "roughness.h"),
            (1.0, 0.0, "roughness.lambda"),
            (1.0, f64::INFINITY, "roughness.lambda"),
        ] {
            for e in [
                Waviness1d::new(h, lambda).unwrap_err(),
                Waviness2d::new(h, lambda).unwrap_err(),
            ] {
                assert!(e.to_string().contains(field), "{e}");
            }
        }
    }

    #[test]
    fn flat_punch_is_flat_on_its_face_and_lifted_off_it() {
        let c = FlatPunch::circular(1.0).unwrap();
        assert_eq!(c.lift_height(), 1e3);
        assert_eq!(c.height(0.6, 0.8), 0.0);
        assert_eq!(c.height(0.0, -1.0), 0.0);
        assert_eq!(c.height(0.8, 0.8), 1e3);
        let s = FlatPunch::square(1.0).unwrap().with_lift(5.0).unwrap();
        assert_eq!(s.height(-1.0, 1.0), 0.0);
        assert_eq!(s.height(1.01, 0.0), 5.0);
        assert_eq!(s.face(), PunchFace::Square { half_side: 1.0 });
        for (e, field) in [
            (
                FlatPunch::circular(0.0).unwrap_err(),
                "geometry.punch_radius",
            ),
            (
                FlatPunch::square(f64::NAN).unwrap_err(),
                "geometry.punch_half_side",
            ),
            (
                c.with_lift(f64::INFINITY).unwrap_err(),
                "geometry.punch_lift",
            ),
        ] {
            assert!(e.to_string().contains(field), "{e}");
        }
    }
}
