//! The elastic body of a scene (`[body]`): the homogeneous half-space, or a layer on a rigid
//! base (`tack_kernels::Layer`), checked against the grid and the scene's other fields.

use tack_fields as fields;
use tack_geometry::{Boundary, Grid};
use tack_kernels::{Interface, Layer};

use crate::scene::{BodyKind, BodySpec, InterfaceKind, SceneError, num};

/// Least layer thickness relative to Δx: a thinner film's compliance is below the round-off
/// of the half-space terms it is built from.
pub const MIN_THICKNESS_PER_DX: f64 = 1e-9;

/// Least film thickness, in elements, of an adhesive run: the criterion's κ was calibrated on
/// the half-space and checked on films of 10 elements and more (`tests/layer.rs`).
pub const MIN_ADHESIVE_THICKNESS_PER_DX: f64 = 4.0;

/// The free layer operator integrates each element's influence with up to 64 sub-squares per
/// side (`tack_kernels::FreeLayerOperator`): a thinner layer than `Δx/64` is flagged.
pub const FREE_LAYER_RESOLVED_PER_DX: f64 = 1.0 / 64.0;

/// The layer of `[body]` (`None`: the half-space), checked: its fields only with
/// `kind = "layer"`, thickness and ν required there, a thickness above
/// [`MIN_THICKNESS_PER_DX`]`·Δx`; warnings for what the result cannot be trusted on.
pub(crate) fn body_layer(
    spec: &BodySpec,
    grid: &Grid,
    warnings: &mut Vec<String>,
) -> Result<Option<Layer>, SceneError> {
    if spec.kind == BodyKind::HalfSpace {
        let given = [
            (fields::BODY_THICKNESS, spec.thickness.is_some()),
            (fields::BODY_POISSON, spec.poisson.is_some()),
            (fields::BODY_INTERFACE, spec.interface.is_some()),
        ];
        if let Some((field, _)) = given.iter().find(|(_, g)| *g) {
            return Err(SceneError::Inconsistent(format!(
                "{field} is read by {} = \"layer\" only: set it or leave {field} out (the default \
                 body is a half-space)",
                fields::BODY_KIND
            )));
        }
        return Ok(None);
    }
    let required = |field: &'static str, v: Option<f64>, what: String| {
        v.ok_or_else(|| {
            SceneError::Inconsistent(format!(
                "{field} is required with {} = \"layer\": {what}",
                fields::BODY_KIND
            ))
        })
    };
    let layer = Layer {
        thickness: required(
            fields::BODY_THICKNESS,
            spec.thickness,
            "the thickness h > 0".into(),
        )?,
        poisson: required(
            fields::BODY_POISSON,
            spec.poisson,
            format!(
                "Poisson's ratio ν in (−1, 0.5] ({} is the layer's E/(1 − ν²))",
                fields::MATERIAL_E_STAR
            ),
        )?,
        interface: match spec.interface.unwrap_or(InterfaceKind::Bonded) {
            InterfaceKind::Bonded => Interface::Bonded,
            InterfaceKind::Frictionless => Interface::Frictionless,
        },
    };
    layer.check()?;
    if layer.thickness < MIN_THICKNESS_PER_DX * grid.dx() {
        return Err(SceneError::out_of_range(
            fields::BODY_THICKNESS,
            num(layer.thickness),
            concat!(
                "at least 1e-9·",
                tack_fields::field_name!(grid.dx),
                ": a thinner film's compliance is below the round-off of the operator"
            ),
        ));
    }
    if grid.boundary() == Boundary::Free && layer.thickness < FREE_LAYER_RESOLVED_PER_DX * grid.dx()
    {
        warnings.push(format!(
            "under-resolved layer: {} = {} is below {dx}/64, where the free layer operator's \
             element integrals are not resolved; refine {dx} or use a periodic grid",
            fields::BODY_THICKNESS,
            num(layer.thickness),
            dx = fields::GRID_DX
        ));
    }
    Ok(Some(layer))
}

/// The warnings a film adds once the references and the law are known: the closed-form
/// references are the half-space's, and a film thinner than
/// [`MIN_ADHESIVE_THICKNESS_PER_DX`] elements under the zero-range criterion, whose κ was
/// calibrated on the half-space.
pub(crate) fn film_warnings(
    layer: &Layer,
    references: &crate::references::References,
    law: &tack_solver::AdhesionLaw,
    gamma: f64,
    dx: f64,
    warnings: &mut Vec<String>,
) {
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
        && matches!(law, tack_solver::AdhesionLaw::JkrLimit(_))
        && layer.thickness < MIN_ADHESIVE_THICKNESS_PER_DX * dx
    {
        warnings.push(format!(
            "under-resolved film: {} = {} spans fewer than {} elements; the criterion's κ was \
             calibrated on the half-space and on films of 10 elements and more; refine {}",
            fields::BODY_THICKNESS,
            num(layer.thickness),
            MIN_ADHESIVE_THICKNESS_PER_DX,
            fields::GRID_DX
        ));
    }
}
