//! Grids, surfaces and shapes: the rigid body's gap `f(x, y)` at zero approach, sampled on a grid.
//!
//! A [`Grid`] is a validated set of square elements with a boundary kind; a [`Surface`] holds
//! one height per element. Shapes ([`Sphere`], [`Ellipsoid`], [`PowerLaw`], [`Waviness1d`],
//! [`Waviness2d`], [`FlatPunch`])
//! are analytic height functions sampled onto a grid; [`rough_surface`] generates seeded random
//! roughness (one continuous surface whatever the resolution) and [`read_height_map_file`]
//! imports measured heights; [`coarsen_band_limited`] takes a band-limited map to twice its
//! element size; [`AdhesionPattern`] generates work-of-adhesion fields (stripes, rings,
//! checkerboard, seeded log-normal random) per element. Surfaces compose by adding
//! heights, so a macro shape plus roughness needs no special case.
//!
//! Element `(i, j)` has its centre at `((i − ⌊nx/2⌋)Δx, (j − ⌊ny/2⌋)Δx)`, so the sphere's apex
//! sits exactly on an element centre. Every constructor validates its input, and errors
//! ([`GeometryError`]) name the scene field, the value and the allowed range.
//!
//! ```
//! use tack_geometry::{Boundary, Grid, RoughSpec, Sphere, Surface, rough_surface};
//!
//! // A 33 × 33 free grid of 0.1-wide elements and a sphere of radius 2, f = (x² + y²)/(2R).
//! let grid = Grid::square(33, 0.1, Boundary::Free)?;
//! assert_eq!((grid.x(16), grid.y(16)), (0.0, 0.0)); // the centre element is the origin
//! let mut surface = Surface::from_shape(grid, &Sphere::new(2.0)?);
//! assert_eq!(surface.heights()[[16, 16]], 0.0); // apex: the lowest point
//! assert_eq!(surface.min(), 0.0);
//! // One unit off-centre along x (10 elements): 1²/(2·2) = 0.25.
//! assert!((surface.heights()[[26, 16]] - 0.25).abs() < 1e-12);
//!
//! // Seeded random roughness (rms 0.01, H = 0.5, the paper's band) adds to the sphere.
//! let spec = RoughSpec::paper_defaults(grid, 0.01, 0.5, 7);
//! let rough = rough_surface(grid, &spec)?;
//! assert!(rough.mean().abs() < 1e-12);
//! let rms = (rough.heights().iter().map(|h| h * h).sum::<f64>() / grid.len() as f64).sqrt();
//! assert!((rms - 0.01).abs() < 1e-12);
//! surface.add(&rough)?;
//! assert_eq!(rough_surface(grid, &spec)?, rough); // same seed, same surface
//!
//! // Invalid input names the field.
//! let err = Sphere::new(-1.0).unwrap_err();
//! assert!(err.to_string().contains("geometry.radius"));
//! # Ok::<(), tack_geometry::GeometryError>(())
//! ```

mod error;
mod grid;
mod heightmap;
mod pattern;
mod resample;
mod rough;
mod shapes;
mod surface;

pub use error::GeometryError;
pub use grid::{Boundary, Grid, MAX_ELEMENTS_PER_AXIS};
pub use heightmap::{height_map_surface, read_height_map_file, read_height_map_text};
pub use pattern::AdhesionPattern;
pub use resample::{
    BAND_LIMIT_TOLERANCE, coarse_centres, coarsen_band_limited, share_above_coarse_nyquist,
};
pub use rough::{RoughSpec, rough_surface};
pub use shapes::{
    DEFAULT_PUNCH_LIFT, Ellipsoid, FlatPunch, MAX_POWER_LAW_EXPONENT, PowerLaw, PunchFace, Shape,
    Sphere, Waviness1d, Waviness2d,
};
pub use surface::{Surface, Window};

/// The example of README.md, run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctest;
