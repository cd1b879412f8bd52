//! The default pull-off path: the rule that sets the load depth and the retraction steps of a
//! pull-off from the body's radius, used by scenes without `protocol.max_approach` and by
//! [`crate::heights::pull_off`] (Python's `tack.pull_off`), and the least-squares paraboloid that
//! finds the radius of a body given only as heights.
//!
//! **The rule.** With d_s = (Rγ²/E*²)^(1/3), the JKR approach scale of a sphere of radius R,
//! the path loads in one step to [`LOAD_DEPTH`]·d_s beyond the top of the roughness (the
//! paper's rough-sphere runs: on a smooth sphere this bonds a disc of about 1.6 a_c, deep enough
//! for the JKR pull-off), then retracts by [`COARSE_UNLOAD_STEP`]·d_s while the force is
//! compressive and by `min(`[`UNLOAD_STEP`]`, `[`UNLOAD_STEP_PER_ELEMENT`]`·Δx/a_c)`·d_s through
//! the tensile part, until nothing is bonded.

use ndarray::Array2;
use tack_fields::num;
use tack_geometry::Grid;

use crate::error::SceneError;

/// Default load depth of the default pull-off path, in units of d_s = (Rγ²/E*²)^(1/3): the path loads in one
/// step to this many d_s below the top of the roughness (the paper's rough-sphere runs; on a
/// smooth sphere it bonds a disc of about 1.6 a_c).
pub const LOAD_DEPTH: f64 = 3.0;

/// Default coarse retraction step of the default pull-off path (while the force is compressive), in d_s.
pub const COARSE_UNLOAD_STEP: f64 = 0.2;

/// Largest retraction step of the default pull-off path through the tensile part, in d_s (the
/// quick mode of `cargo xtask reproduce`; the full mode uses 0.01). Fine meshes take
/// [`UNLOAD_STEP_PER_ELEMENT`] instead.
pub const UNLOAD_STEP: f64 = 0.02;

/// Retraction step through the tensile part in d_s per Δx/a_c (a_c the JKR pull-off radius of
/// the body's sphere): the default step is `min(`[`UNLOAD_STEP`]`, 0.2·Δx/a_c)·d_s`. The
/// elements of the rim detach at approaches about Δx/a_c·d_s apart, so a step of a fixed share
/// of that spacing keeps the path's share of the pull-off error a fixed small fraction of the
/// criterion's (+1.4 Δx/a_c): on the smooth sphere at most 0.7% at a_c/Δx = 10 … 80, where the
/// criterion's is +14.1% … +1.0% (`cargo run --release -p tack --example retraction_step`, README).
pub const UNLOAD_STEP_PER_ELEMENT: f64 = 0.2;

/// Under a smooth law (exponential, Lennard-Jones, a custom curve) the default path's load
/// steps from out of range are at least the law's length ρ over this, up to the coarse
/// retraction step ([`load_plan`]): the approach changes the law's forces over ρ, and a law
/// long against the JKR scale (small Tabor μ) loaded in fine retraction steps spent most of its
/// run approaching (μ = 0.1 on 128²: 18 253 load steps of its 22 925, 62 s; now 478 of 5 150,
/// 13.5 s, from where the tension is 1e-4 of the peak, `AdhesionLaw::approach_reach`). The
/// retraction's tail past the pull-off takes the same steps (`AdhesionLaw::tail_step`: 957
/// steps in all, 6.3 s by the tail alone).
pub use tack_solver::STEPS_PER_LENGTH;

/// Coarse retraction step over the fine one when no radius sets the scale.
pub const COARSE_PER_UNLOAD_STEP: f64 = 10.0;

/// The numbers of the default pull-off path of a body of radius `radius`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PullOffPath {
    /// The JKR approach scale d_s = (Rγ²/E*²)^(1/3).
    pub d_s: f64,
    /// Deepest approach: `top +` [`LOAD_DEPTH`]`·d_s`.
    pub max_approach: f64,
    /// Retraction step while the force is compressive: [`COARSE_UNLOAD_STEP`]`·d_s`.
    pub coarse_unload_step: f64,
    /// Retraction step through the tensile part:
    /// `min(`[`UNLOAD_STEP`]`, `[`UNLOAD_STEP_PER_ELEMENT`]`·Δx/a_c)·d_s`.
    pub unload_step: f64,
}

/// The default pull-off path of a sphere-like body of radius `radius` (E* `e_star`, γ `gamma`)
/// on elements of size `dx`, whose roughness reaches up to approach `top` (the vertex height
/// plus the greatest height of the roughness above the smooth shape; 0 for a smooth sphere at
/// the origin).
///
/// ```
/// use tack::pull_off_path::default_pull_off_path;
/// // E* = 1, γ = 0.125, R = 8: d_s = (8 · 0.125²)^(1/3) = 0.5, a_c = 3.05.
/// let p = default_pull_off_path(1.0, 0.125, 8.0, 0.0, 0.45);
/// assert!((p.d_s - 0.5).abs() < 1e-12);
/// assert!((p.max_approach - 1.5).abs() < 1e-12);
/// assert!((p.unload_step - 0.01).abs() < 1e-12); // 0.02 d_s: a_c/Δx = 6.8
/// // A fine mesh, a_c/Δx = 61: 0.2 Δx/a_c d_s.
/// let fine = default_pull_off_path(1.0, 0.125, 8.0, 0.0, 0.05);
/// assert!((fine.unload_step / 0.5 - 0.2 * 0.05 / 3.0466).abs() < 1e-5);
/// ```
pub fn default_pull_off_path(
    e_star: f64,
    gamma: f64,
    radius: f64,
    top: f64,
    dx: f64,
) -> PullOffPath {
    let d_s = tack_analytics::jkr_approach_scale(e_star, gamma, radius);
    let a_c = tack_analytics::jkr_pull_off_radius(e_star, gamma, radius);
    PullOffPath {
        d_s,
        max_approach: top + LOAD_DEPTH * d_s,
        coarse_unload_step: COARSE_UNLOAD_STEP * d_s,
        unload_step: UNLOAD_STEP.min(UNLOAD_STEP_PER_ELEMENT * dx / a_c) * d_s,
    }
}

/// A least-squares paraboloid `h ≈ apex + ((x − x0)² + (y − y0)²)/(2R)` through a height array
/// (tilt and offset included through the vertex), and the residual, the body's roughness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Paraboloid {
    /// Radius of curvature `R` (negative for a body curved towards the half-space).
    pub radius: f64,
    /// Vertex `(x0, y0)` in tack's coordinates.
    pub vertex: (f64, f64),
    /// Height of the vertex.
    pub apex: f64,
    /// Least residual `h − paraboloid` over the array.
    pub residual_min: f64,
    /// Greatest residual `h − paraboloid` over the array: the top of the roughness above the
    /// smooth shape.
    pub residual_max: f64,
}

impl Paraboloid {
    /// Range (max − min) of the residual: the roughness range of the crop rule.
    pub fn residual_range(&self) -> f64 {
        self.residual_max - self.residual_min
    }

    /// Whether the paraboloid describes the body as a sphere with roughness: `R > 0`, and its
    /// rise over the largest disc inside the grid, `(min(Lx, Ly)/2)²/(2R)`, is at least half
    /// the residual range (a flat rough surface fits a paraboloid too, with a rise far below
    /// its roughness).
    pub fn is_sphere_like(&self, grid: &Grid) -> bool {
        let half = 0.5 * grid.lx().min(grid.ly());
        self.radius.is_finite()
            && self.radius > 0.0
            && half * half / (2.0 * self.radius) >= 0.5 * self.residual_range()
    }
}

/// Fits a [`Paraboloid`] to `heights` on elements of size `dx` by least squares; with `radius`
/// given only the vertex and apex are fitted. `None` when the array has fewer than 3 elements
/// along an axis, or the fit is singular or flat (no curvature).
pub fn fit_paraboloid(heights: &Array2<f64>, dx: f64, radius: Option<f64>) -> Option<Paraboloid> {
    let (nx, ny) = heights.dim();
    if nx < 3 || ny < 3 || !(dx.is_finite() && dx > 0.0) {
        return None;
    }
    // Coordinates scaled to about [−1, 1] keep the normal equations well conditioned.
    let scale = 0.5 * dx * nx.max(ny) as f64;
    let uv = |i: usize, j: usize| {
        (
            (i as f64 - (nx / 2) as f64) * dx / scale,
            (j as f64 - (ny / 2) as f64) * dx / scale,
        )
    };
    // h ≈ c0 + c1 u + c2 v + c3 (u² + v²); with a given radius c3 = scale²/(2R) is fixed.
    let fixed_c3 = match radius {
        Some(r) if r.is_finite() && r != 0.0 => Some(scale * scale / (2.0 * r)),
        Some(_) => return None,
        None => None,
    };
    let m = if fixed_c3.is_some() { 3 } else { 4 };
    let mut ata = [[0.0_f64; 4]; 4];
    let mut atb = [0.0_f64; 4];
    for ((i, j), &h) in heights.indexed_iter() {
        let (u, v) = uv(i, j);
        let r2 = u * u + v * v;
        let row = [1.0, u, v, r2];
        let target = h - fixed_c3.map_or(0.0, |c3| c3 * r2);
        for a in 0..m {
            atb[a] += row[a] * target;
            for b in 0..m {
                ata[a][b] += row[a] * row[b];
            }
        }
    }
    let c = solve_small(ata, atb, m)?;
    let c3 = fixed_c3.unwrap_or(c[3]);
    if c3 == 0.0 || !c3.is_finite() {
        return None;
    }
    let (u0, v0) = (-c[1] / (2.0 * c3), -c[2] / (2.0 * c3));
    let apex = c[0] - (c[1] * c[1] + c[2] * c[2]) / (4.0 * c3);
    let (residual_min, residual_max) = min_max(heights.indexed_iter().map(|((i, j), &h)| {
        let (u, v) = uv(i, j);
        h - (c[0] + c[1] * u + c[2] * v + c3 * (u * u + v * v))
    }));
    Some(Paraboloid {
        radius: radius.unwrap_or(scale * scale / (2.0 * c3)),
        vertex: (u0 * scale, v0 * scale),
        apex,
        residual_min,
        residual_max,
    })
}

/// Solves the leading `m × m` block of `a x = b` by Gaussian elimination with partial pivoting;
/// `None` when singular.
fn solve_small(mut a: [[f64; 4]; 4], mut b: [f64; 4], m: usize) -> Option<[f64; 4]> {
    let norm = a.iter().flatten().fold(0.0_f64, |s, v| s.max(v.abs()));
    for col in 0..m {
        let pivot = (col..m).max_by(|&p, &q| a[p][col].abs().total_cmp(&a[q][col].abs()))?;
        if a[pivot][col].is_nan() || a[pivot][col].abs() <= 1e-12 * norm {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..m {
            let f = a[row][col] / a[col][col];
            let pivot_row = a[col];
            for (value, p) in a[row][col..m].iter_mut().zip(&pivot_row[col..m]) {
                *value -= f * p;
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = [0.0; 4];
    for row in (0..m).rev() {
        let s: f64 = (row + 1..m).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - s) / a[row][row];
    }
    Some(x)
}

fn min_max(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}

/// Margin on the Hertz contact radius `sqrt(R·d)` when checking that a sphere's loaded contact
/// fits a free grid.
pub const SPHERE_FIT_MARGIN: f64 = 1.3;

/// On a free grid the loaded contact must lie inside the array around the paraboloid's vertex:
/// the reach of [`sphere_contact_reach`] (Hertz with the 30% margin of the scene
/// check; under a law of finite `range`, loaded in steps, the JKR contact radius), measured
/// from the vertex to the array's edge; and under the zero-range law, loaded in one step, the
/// elements that step bonds — every element the body penetrates, `h < max_approach`, exactly,
/// whatever the body's shape — must keep off the array's outermost ring.
#[allow(clippy::too_many_arguments)]
pub(crate) fn check_contact_fits(
    heights: &Array2<f64>,
    grid: &Grid,
    radius: f64,
    fit: &Paraboloid,
    max_approach: f64,
    first_touch: f64,
    material: Material,
    range: Option<f64>,
) -> Result<(), SceneError> {
    let depth = (max_approach - first_touch).max(0.0);
    let dx = grid.dx();
    let (needed, rule) =
        sphere_contact_reach(radius, depth, dx, 1.0, material, (None, range.is_some()));
    if range.is_none() {
        check_one_step_load(heights, grid, max_approach)?;
    }
    // A vertex within round-off of an element centre prints as that centre.
    let snap = |v: f64| if v.abs() < 1e-9 * dx { 0.0 } else { v };
    let (x0, y0) = (snap(fit.vertex.0), snap(fit.vertex.1));
    let (x_lo, x_hi) = (grid.x(0) - 0.5 * dx, grid.x(grid.nx() - 1) + 0.5 * dx);
    let (y_lo, y_hi) = (grid.y(0) - 0.5 * dx, grid.y(grid.ny() - 1) + 0.5 * dx);
    let room = (x0 - x_lo).min(x_hi - x0).min(y0 - y_lo).min(y_hi - y0);
    if needed > room {
        let r4 = |x: f64| tack_fields::num(round4(x));
        return Err(SceneError::Inconsistent(format!(
            "heights: the {} × {} array at {} = {} is too small for the pull-off: at {} = {} \
             (R = {}, d = {} from the first touch) {rule} reaches {} from the vertex at ({}, \
             {}), but the array's edge is {} away; use a larger array (at least {} elements \
             across) or a smaller {}",
            grid.nx(),
            grid.ny(),
            tack_fields::GRID_DX,
            tack_fields::num(dx),
            tack_fields::PROTOCOL_MAX_APPROACH,
            r4(max_approach),
            r4(radius),
            r4(depth),
            r4(needed),
            r4(x0),
            r4(y0),
            r4(room),
            count_text((2.0 * needed / dx).ceil() + 1.0),
            tack_fields::PROTOCOL_MAX_APPROACH,
        )));
    }
    Ok(())
}

/// The one-step load to `max_approach` bonds every element with `h < max_approach`: none of
/// them may lie on the array's outermost ring (the run would report contact at the edge).
fn check_one_step_load(
    heights: &Array2<f64>,
    grid: &Grid,
    max_approach: f64,
) -> Result<(), SceneError> {
    let (nx, ny) = heights.dim();
    let on_edge = bonded_on_edge(heights, max_approach);
    if on_edge == 0 {
        return Ok(());
    }
    Err(SceneError::Inconsistent(format!(
        "heights: the {nx} × {ny} array at {} = {} is too small for the pull-off: the one-step \
         load to {} = {} bonds every element the body penetrates (height < {}), and {on_edge} \
         of them lie on the array's edge, where the contact would be cut; use a larger array \
         or a smaller {}",
        tack_fields::GRID_DX,
        tack_fields::num(grid.dx()),
        tack_fields::PROTOCOL_MAX_APPROACH,
        tack_fields::num(round4(max_approach)),
        tack_fields::num(round4(max_approach)),
        tack_fields::PROTOCOL_MAX_APPROACH,
    )))
}

/// How many elements on the array's outermost ring a one-step load to `max_approach` bonds
/// (those with `h < max_approach`).
pub(crate) fn bonded_on_edge(heights: &Array2<f64>, max_approach: f64) -> usize {
    let (nx, ny) = heights.dim();
    heights
        .indexed_iter()
        .filter(|&((i, j), &h)| {
            (i == 0 || j == 0 || i + 1 == nx || j + 1 == ny) && h < max_approach
        })
        .count()
}

/// How the default path loads, as `(start, load_step)`, from its retraction steps `(fine,
/// coarse)`: under the zero-range law one step from the first touch straight to
/// `max_approach` (at least the fine step); with a finite `range` (the Dugdale law's γ/σ0, a
/// smooth law's reach) from just before the first element comes within range,
/// `first_touch − range − load_step`, in fine steps (quasi-static: the approach branch is
/// physical), or in steps of a smooth law's `length` ρ over [`STEPS_PER_LENGTH`] where that is
/// longer, but no longer than the coarse step (the loaded contact and the jump in stay
/// resolved as the compressive retraction is).
///
/// ```
/// use tack::pull_off_path::load_plan;
/// // The zero-range criterion: one step from the first touch at 0 to 0.03.
/// assert_eq!(load_plan(0.0, 0.03, (2e-4, 2e-3), None, None), (0.03, 0.03));
/// // The Dugdale law (no length): retraction steps from out of its range 0.1.
/// let (start, step) = load_plan(0.0, 0.03, (2e-4, 2e-3), Some(0.1), None);
/// assert!((start + 0.1002).abs() < 1e-15 && step == 2e-4);
/// // A smooth law of length 0.05 (reach 0.92): steps of 0.05/50 = 0.001.
/// let (start, step) = load_plan(0.0, 0.03, (2e-4, 2e-3), Some(0.92), Some(0.05));
/// assert!((start + 0.921).abs() < 1e-15 && step == 0.001);
/// // Of length 1: the coarse step 0.002, not 1/50.
/// assert_eq!(load_plan(0.0, 0.03, (2e-4, 2e-3), Some(18.4), Some(1.0)).1, 2e-3);
/// ```
pub fn load_plan(
    first_touch: f64,
    max_approach: f64,
    (fine, coarse): (f64, f64),
    range: Option<f64>,
    length: Option<f64>,
) -> (f64, f64) {
    match range {
        None => (max_approach, (max_approach - first_touch).max(fine)),
        Some(range) => {
            let step = length.map_or(fine, |l| fine.max((l / STEPS_PER_LENGTH).min(coarse)));
            (first_touch - range - step, step)
        }
    }
}

/// What a shape's references and checks read besides its own parameters.
#[derive(Debug, Clone, Copy)]
pub struct Material {
    /// Effective modulus E*.
    pub e_star: f64,
    /// The reference work of adhesion γ (0: no adhesion, no adhesive references).
    pub gamma: f64,
}

/// The radius a sphere-like contact reaches at approach `depth` beyond the first touch, and
/// the rule that gives it, with what must stay free around it: the Hertz radius √(R·d) (times
/// √2.5 on a film) with [`SPHERE_FIT_MARGIN`]; under a `finite_range` law (which attracts
/// ahead of the contact) also the JKR contact radius a(d) plus one element; after a one-step
/// load (`bonded`: the disc √(2R·d) it bonds) also that disc plus one element (the step bonds
/// every penetrated element under either law). The zero-range criterion loaded in steps bonds
/// only what penetrates, so its contact stays near Hertz's.
pub fn sphere_contact_reach(
    radius: f64,
    depth: f64,
    dx: f64,
    reach: f64,
    material: Material,
    (bonded, finite_range): (Option<f64>, bool),
) -> (f64, String) {
    let hertz = reach * (radius * depth).sqrt();
    let mut needed = SPHERE_FIT_MARGIN * hertz;
    let mut rule = format!(
        "the contact radius {} = {} plus a 30% margin",
        if reach > 1.0 {
            "sqrt(2.5·R·d) (a thin film's)"
        } else {
            "sqrt(R·d) (Hertz)"
        },
        num(round4(hertz))
    );
    if finite_range
        && material.gamma > 0.0
        && let Some(a) =
            tack_analytics::jkr_radius_from_approach(material.e_star, material.gamma, radius, depth)
        && reach * a + dx > needed
    {
        needed = reach * a + dx;
        rule = format!(
            "the JKR contact radius a(d) = {} plus one element",
            num(round4(reach * a))
        );
    }
    if let Some(bonded) = bonded
        && bonded + dx > needed
    {
        needed = bonded + dx;
        rule = format!(
            "the disc the one-step load bonds, sqrt(2·R·d) = {} (d from the vertex), plus one \
             element",
            num(round4(bonded))
        );
    }
    (needed, rule)
}

/// `x` to four significant digits, for messages.
pub fn round4(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let scale = 10f64.powi(3 - x.abs().log10().floor() as i32);
    (x * scale).round() / scale
}

/// An element count for a message: exact when it is a plausible size, else `2.000e300`.
pub fn count_text(n: f64) -> String {
    if n < 1e15 {
        format!("{n:.0}")
    } else {
        format!("{n:.3e}")
    }
}

/// Load steps of `path` that carry the body beyond its first touch (the deepest approach
/// included), counted up to `limit` (the path's own steps, `ApproachPath::load_approaches`).
pub fn loaded_steps(path: &tack_solver::ApproachPath, first_touch: f64, limit: usize) -> usize {
    path.load_approaches()
        .filter(|&d| d > first_touch)
        .take(limit)
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;
    use tack_geometry::{Boundary, RoughSpec, rough_surface};

    #[test]
    fn the_fit_recovers_an_offset_paraboloid() {
        let (nx, ny, dx) = (40, 30, 0.1);
        let grid = Grid::new(nx, ny, dx, Boundary::Free).unwrap();
        let h = Array2::from_shape_fn((nx, ny), |(i, j)| {
            let (x, y) = (grid.x(i) - 0.7, grid.y(j) + 0.4);
            3.0 + (x * x + y * y) / (2.0 * 5.0)
        });
        for radius in [None, Some(5.0)] {
            let f = fit_paraboloid(&h, dx, radius).unwrap();
            assert!((f.radius - 5.0).abs() < 1e-9, "{f:?}");
            assert!((f.vertex.0 - 0.7).abs() < 1e-9 && (f.vertex.1 + 0.4).abs() < 1e-9);
            assert!((f.apex - 3.0).abs() < 1e-9);
            assert!(f.residual_range() < 1e-9);
            assert!(f.is_sphere_like(&grid));
        }
        // A strip has no paraboloid; a flat rough surface is not sphere-like.
        assert!(fit_paraboloid(&Array2::zeros((64, 1)), dx, None).is_none());
        let grid = Grid::square(64, dx, Boundary::Free).unwrap();
        let rough = rough_surface(grid, &RoughSpec::paper_defaults(grid, 0.01, 0.5, 3)).unwrap();
        let f = fit_paraboloid(rough.heights(), dx, None);
        assert!(f.is_none_or(|f| !f.is_sphere_like(&grid)), "{f:?}");
    }
}
