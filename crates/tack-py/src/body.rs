//! The layer arguments of `tack.contact` and `tack.pull_off` (`thickness`, `poisson`,
//! `interface`): an elastic film on a rigid base in place of the half-space.

use pyo3::prelude::*;
use tack::fields;
use tack::kernels::{Interface, Layer};

use crate::errors::{Names, value_error, value_error_named};

/// The fields of the layer's messages and the arguments they stand for.
const LAYER_NAMES: Names = &[
    (fields::BODY_THICKNESS, "thickness"),
    (fields::BODY_POISSON, "poisson"),
];

/// The layer of the `thickness`, `poisson` and `interface` arguments (`None`: a half-space); `poisson` and `interface` only with `thickness`, `poisson` required there.
pub(crate) fn layer_of(
    thickness: Option<f64>,
    poisson: Option<f64>,
    interface: Option<&str>,
) -> PyResult<Option<Layer>> {
    let Some(thickness) = thickness else {
        if poisson.is_some() || interface.is_some() {
            let name = if poisson.is_some() {
                "poisson"
            } else {
                "interface"
            };
            return Err(value_error(format!(
                "{name} is given without thickness: it describes a layer, which needs \
                 thickness (> 0); leave it out for a half-space"
            )));
        }
        return Ok(None);
    };
    let Some(poisson) = poisson else {
        return Err(value_error(
            "poisson is missing: a layer (thickness given) needs its Poisson ratio, a number \
             in (-1, 0.5]",
        ));
    };
    let interface = match interface.unwrap_or("bonded") {
        "bonded" => Interface::Bonded,
        "frictionless" => Interface::Frictionless,
        other => {
            return Err(value_error(format!(
                "interface = {other:?} is invalid: must be \"bonded\" or \"frictionless\""
            )));
        }
    };
    let layer = Layer {
        thickness,
        poisson,
        interface,
    };
    layer
        .check()
        .map_err(|e| value_error_named(&e, LAYER_NAMES))?;
    Ok(Some(layer))
}
