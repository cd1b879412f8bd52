//! The work of adhesion as a field: `[adhesion]`'s map file or generated pattern, or a γ array
//! given in memory, checked and sampled on the scene's grid (docs/scenes.md, `[adhesion]`).

use ndarray::Array2;
use std::path::Path;
use tack_fields as fields;
use tack_geometry::{AdhesionPattern, Grid};

use crate::scene::{AdhesionSpec, PatternKind, SceneError, num};

/// Default seed of the random γ field.
pub const DEFAULT_PATTERN_SEED: u64 = 1;

/// Elements per pattern period (or correlation length) below which a result is flagged: the
/// pattern's boundaries are then stair-stepped at the scale of the front's own error.
pub const MIN_PATTERN_ELEMENTS: f64 = 4.0;

/// How γ varies: what the scene or the caller gave, before it is sampled.
pub(crate) enum Source<'a> {
    File(&'a Path, Option<&'a str>),
    Pattern(AdhesionPattern),
    Array(&'a Array2<f64>),
}

/// The γ of every element of `grid` when it varies (`None`: `material.gamma` everywhere), and
/// the warnings of an under-resolved pattern. `gamma` is `material.gamma` (phase a of stripes
/// and checkerboards, the random field's mean, the reference of a map); `array` a γ array given
/// in memory ([`crate::HeightBody::gamma`]).
pub(crate) fn gamma_map(
    spec: &AdhesionSpec,
    gamma: f64,
    grid: &Grid,
    base_dir: &Path,
    array: Option<&Array2<f64>>,
    warnings: &mut Vec<String>,
) -> Result<Option<Array2<f64>>, SceneError> {
    let Some(source) = source(spec, gamma, array)? else {
        return Ok(None);
    };
    if gamma <= 0.0 {
        return Err(SceneError::Inconsistent(format!(
            "{gamma_field} = {} is invalid with a work of adhesion that varies: must be > 0 (the \
             reference of F_JKR, of the ratios and of the default path; phase a of a pattern, \
             the mean of a random field)",
            num(gamma),
            gamma_field = fields::MATERIAL_GAMMA
        )));
    }
    let map = match source {
        Source::Pattern(pattern) => {
            let scale = match pattern {
                AdhesionPattern::Stripes { period, .. }
                | AdhesionPattern::Rings { period, .. }
                | AdhesionPattern::Checkerboard { period, .. } => (fields::ADHESION_PERIOD, period),
                AdhesionPattern::Random {
                    correlation_length, ..
                } => (fields::ADHESION_CORRELATION_LENGTH, correlation_length),
            };
            let map = pattern.field(grid)?;
            // Extreme parameters (a contrast near 1e154, ℓ of 1e154 periods) overflow the field.
            let what = match pattern {
                AdhesionPattern::Random { .. } => format!(
                    "{} = \"random\" ({}, {})",
                    fields::ADHESION_PATTERN,
                    fields::ADHESION_CONTRAST,
                    fields::ADHESION_CORRELATION_LENGTH
                ),
                _ => fields::ADHESION_PATTERN.to_owned(),
            };
            check_array(&map, grid, &what)?;
            if let AdhesionPattern::Stripes {
                period, fraction, ..
            }
            | AdhesionPattern::Rings {
                period, fraction, ..
            } = pattern
                && fraction > 0.0
                && fraction < 1.0
                && fraction.min(1.0 - fraction) * period < 2.0 * grid.dx()
            {
                warnings.push(format!(
                    "under-resolved pattern: the narrower phase, min({f}, 1 − {f})·{p} = {}, spans \
                     fewer than 2 elements; refine {}",
                    num(fraction.min(1.0 - fraction) * period),
                    fields::GRID_DX,
                    f = fields::ADHESION_FRACTION,
                    p = fields::ADHESION_PERIOD,
                ));
            }
            let elements = scale.1 / grid.dx();
            if elements < MIN_PATTERN_ELEMENTS {
                warnings.push(format!(
                    "under-resolved pattern: {} = {} spans {elements:.3} elements (fewer than \
                     {MIN_PATTERN_ELEMENTS}); refine {}",
                    scale.0,
                    num(scale.1),
                    fields::GRID_DX
                ));
            }
            map
        }
        Source::File(path, dataset) => {
            let full = base_dir.join(path);
            let names = (fields::ADHESION_GAMMA_MAP, fields::ADHESION_DATASET);
            let map = crate::map_file::read_map(&full, path, dataset, grid, names)?;
            check_array(&map, grid, &format!("{} = `{}`", names.0, path.display()))?;
            map
        }
        Source::Array(a) => {
            check_array(a, grid, "gamma")?;
            a.clone()
        }
    };
    Ok(Some(map))
}

/// The one source of a varying γ, with the fields that belong to another refused.
fn source<'a>(
    spec: &'a AdhesionSpec,
    gamma: f64,
    array: Option<&'a Array2<f64>>,
) -> Result<Option<Source<'a>>, SceneError> {
    let pattern = spec.pattern.unwrap_or_default();
    let given = [
        (fields::ADHESION_GAMMA_B, spec.gamma_b),
        (fields::ADHESION_PERIOD, spec.period),
        (fields::ADHESION_FRACTION, spec.fraction),
        (fields::ADHESION_CORRELATION_LENGTH, spec.correlation_length),
        (fields::ADHESION_CONTRAST, spec.contrast),
        (fields::ADHESION_SEED, spec.seed.map(|s| s as f64)),
    ];
    let reads: &[&str] = match pattern {
        PatternKind::Uniform => &[],
        PatternKind::Stripes | PatternKind::Rings => &[
            fields::ADHESION_GAMMA_B,
            fields::ADHESION_PERIOD,
            fields::ADHESION_FRACTION,
        ],
        PatternKind::Checkerboard => &[fields::ADHESION_GAMMA_B, fields::ADHESION_PERIOD],
        PatternKind::Random => &[
            fields::ADHESION_CORRELATION_LENGTH,
            fields::ADHESION_CONTRAST,
            fields::ADHESION_SEED,
        ],
    };
    if let Some((field, _)) = given
        .iter()
        .find(|(f, v)| v.is_some() && !reads.contains(f))
    {
        return Err(SceneError::Inconsistent(format!(
            "{field} is not read with {} = \"{}\": leave it out{}",
            fields::ADHESION_PATTERN,
            pattern.name(),
            match pattern {
                PatternKind::Uniform => format!(" or set {}", fields::ADHESION_PATTERN),
                _ => String::new(),
            }
        )));
    }
    if spec.dataset.is_some() && spec.gamma_map.is_none() {
        return Err(SceneError::Inconsistent(format!(
            "{} names the dataset of {}; give the map or leave it out",
            fields::ADHESION_DATASET,
            fields::ADHESION_GAMMA_MAP
        )));
    }
    let required = |field: &'static str, v: Option<f64>| {
        v.ok_or_else(|| {
            SceneError::Inconsistent(format!(
                "{field} is required with {} = \"{}\"",
                fields::ADHESION_PATTERN,
                pattern.name()
            ))
        })
    };
    let generated = match pattern {
        PatternKind::Uniform => None,
        PatternKind::Stripes => Some(AdhesionPattern::Stripes {
            gamma_a: gamma,
            gamma_b: required(fields::ADHESION_GAMMA_B, spec.gamma_b)?,
            period: required(fields::ADHESION_PERIOD, spec.period)?,
            fraction: spec.fraction.unwrap_or(0.5),
        }),
        PatternKind::Rings => Some(AdhesionPattern::Rings {
            gamma_a: gamma,
            gamma_b: required(fields::ADHESION_GAMMA_B, spec.gamma_b)?,
            period: required(fields::ADHESION_PERIOD, spec.period)?,
            fraction: spec.fraction.unwrap_or(0.5),
        }),
        PatternKind::Checkerboard => Some(AdhesionPattern::Checkerboard {
            gamma_a: gamma,
            gamma_b: required(fields::ADHESION_GAMMA_B, spec.gamma_b)?,
            period: required(fields::ADHESION_PERIOD, spec.period)?,
        }),
        PatternKind::Random => Some(AdhesionPattern::Random {
            mean: gamma,
            contrast: required(fields::ADHESION_CONTRAST, spec.contrast)?,
            correlation_length: required(
                fields::ADHESION_CORRELATION_LENGTH,
                spec.correlation_length,
            )?,
            seed: spec.seed.unwrap_or(DEFAULT_PATTERN_SEED),
        }),
    };
    let sources = [
        spec.gamma_map.as_ref().map(|_| fields::ADHESION_GAMMA_MAP),
        generated.map(|_| fields::ADHESION_PATTERN),
        array.map(|_| "gamma (an array)"),
    ];
    let named: Vec<&str> = sources.iter().flatten().copied().collect();
    if named.len() > 1 {
        return Err(SceneError::Inconsistent(format!(
            "{} give the work of adhesion twice: give one of them",
            named.join(" and ")
        )));
    }
    Ok(if let Some(path) = &spec.gamma_map {
        Some(Source::File(path, spec.dataset.as_deref()))
    } else if let Some(p) = generated {
        Some(Source::Pattern(p))
    } else {
        array.map(Source::Array)
    })
}

/// A γ array of the grid's shape, finite and ≥ 0 everywhere; errors name `what` and the
/// first bad element.
fn check_array(map: &Array2<f64>, grid: &Grid, what: &str) -> Result<(), SceneError> {
    let (nx, ny) = map.dim();
    if (nx, ny) != grid.shape() {
        return Err(SceneError::Inconsistent(format!(
            "{what}: the γ map is {nx} × {ny} but the grid is {} × {}; the map must have the \
             grid's shape",
            grid.nx(),
            grid.ny()
        )));
    }
    if let Some(((i, j), &g)) = map
        .indexed_iter()
        .find(|(_, g)| !(g.is_finite() && **g >= 0.0))
    {
        return Err(SceneError::Inconsistent(format!(
            "{what}: element ({i}, {j}) holds γ = {}, which is invalid: every element must be a \
             finite number ≥ 0",
            num(g)
        )));
    }
    Ok(())
}

/// Least, mean and greatest γ of a map.
pub fn map_range(map: &Array2<f64>) -> (f64, f64, f64) {
    let lo = map.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = map.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (lo, map.mean().unwrap_or(0.0), hi)
}
