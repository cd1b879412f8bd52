//! Analytic macro shapes (the sphere, ...) as height functions `f(x, y)` that can be sampled on a grid.

use crate::error::{GeometryError, positive};

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
            radius: positive("geometry.radius", radius)?,
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_is_parabolic_and_validated() {
        let s = Sphere::new(2.0).unwrap();
        assert_eq!(s.height(0.0, 0.0), 0.0);
        assert_eq!(s.height(2.0, 0.0), 1.0);
        assert_eq!(s.height(0.0, -2.0), 1.0);
        assert!(Sphere::new(-1.0).is_err());
        assert!(Sphere::new(f64::NAN).is_err());
    }
}
