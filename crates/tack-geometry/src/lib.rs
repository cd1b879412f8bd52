//! Grids, surfaces and shapes: the rigid body's gap `f(x, y)` at zero approach, sampled on a grid.
//!
//! A [`Grid`] is a validated set of square elements with a boundary kind; a [`Surface`] holds
//! one height per element. Shapes ([`Sphere`], ...) are analytic height functions sampled onto a
//! grid; surfaces compose by adding heights, so a macro shape plus roughness needs no special case.

mod error;
mod grid;
mod shapes;
mod surface;

pub use error::GeometryError;
pub use grid::{Boundary, Grid};
pub use shapes::{Shape, Sphere};
pub use surface::Surface;
