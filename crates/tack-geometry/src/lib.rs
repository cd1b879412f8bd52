//! Grids, surfaces and shapes: the rigid body's gap `f(x, y)` at zero approach, sampled on a grid.
//!
//! A [`Grid`] is a validated set of square elements with a boundary kind; a [`Surface`] holds
//! one height per element. Shapes ([`Sphere`], [`Waviness1d`], [`Waviness2d`], [`FlatPunch`])
//! are analytic height functions sampled onto a grid; [`rough_surface`] generates seeded random
//! roughness and [`read_height_map_file`] imports measured heights. Surfaces compose by adding
//! heights, so a macro shape plus roughness needs no special case.

mod error;
mod grid;
mod heightmap;
mod rough;
mod shapes;
mod surface;

pub use error::GeometryError;
pub use grid::{Boundary, Grid};
pub use heightmap::{height_map_surface, read_height_map_file, read_height_map_text};
pub use rough::{RoughSpec, rough_surface};
pub use shapes::{DEFAULT_PUNCH_LIFT, FlatPunch, PunchFace, Shape, Sphere, Waviness1d, Waviness2d};
pub use surface::{Surface, Window};
