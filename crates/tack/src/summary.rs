//! What a run's result holds besides the raw path: the `/summary` (pull-off force against the
//! closed forms, the run's warnings, status), the curve's columns, and the assembly of the whole
//! [`tack_io::RunResult`] that [`crate::engine`] hands back.

use tack_fields as fields;
use tack_solver::{AdhesionLaw, Cycle, PathResult, Phase};

use crate::problem::Problem;

/// The `/summary` of a run: pull-off force (the minimum force), F_JKR and the ratio (NaN for
/// bodies other than spheres, or γ = 0), Johnson's α or α*, and extras (every name of
/// [`SUMMARY_QUANTITIES`] after the fields: `d_jkr`, `f_kendall`, `f_mdr`, the law's constants,
/// the cycle's dissipated energy and jumps, the apparent work of adhesion per branch,
/// `first_touch`, step counts, ...).
pub fn summary(problem: &Problem, path: &PathResult) -> tack_io::Summary {
    let pull_off = path.pull_off_force();
    // An indentation is one state, not a pull-off.
    let pull_off = if pull_off.is_finite() && !problem.path.is_indentation() {
        pull_off
    } else {
        f64::NAN
    };
    let r = &problem.references;
    let f_jkr = r.f_jkr.unwrap_or(f64::NAN);
    let ratio = if f_jkr != 0.0 {
        pull_off / f_jkr
    } else {
        f64::NAN
    };
    let mut extra = std::collections::BTreeMap::new();
    if let Some(d) = r.d_jkr {
        extra.insert("d_jkr".to_owned(), d);
    }
    if let Some(f) = r.f_kendall {
        extra.insert("f_kendall".to_owned(), f);
    }
    if let Some(f) = r.f_mdr {
        extra.insert("f_mdr".to_owned(), f);
    }
    if let Some(f) = r.f_elliptic {
        extra.insert("f_elliptic_jkr".to_owned(), f);
    }
    if let Some(map) = &problem.gamma_map {
        let (lo, mean, hi) = crate::gamma_map::map_range(map);
        extra.insert("gamma_min".to_owned(), lo);
        extra.insert("gamma_mean".to_owned(), mean);
        extra.insert("gamma_max".to_owned(), hi);
    }
    if let Some(layer) = &problem.layer {
        extra.insert("layer_thickness".to_owned(), layer.thickness);
        extra.insert("layer_poisson".to_owned(), layer.poisson);
    }
    if let Some(p) = r.p_star {
        extra.insert("p_star".to_owned(), p);
    }
    // Full-contact steps of a periodic grid record a bound (the least admissible mean
    // pressure, about −σ_c), not a state's pressure: they are left out, as in the pull-off.
    let min_mean_pressure = path
        .records
        .iter()
        .filter(|r| !r.full_contact)
        .map(|r| r.mean_pressure)
        .fold(f64::INFINITY, f64::min);
    if min_mean_pressure.is_finite() {
        extra.insert("min_mean_pressure".to_owned(), min_mean_pressure);
    }
    law_extras(problem, r, &mut extra);
    if let Some((prony, rates)) = &problem.viscoelastic {
        extra.insert("e_instantaneous".to_owned(), prony.instantaneous());
        extra.insert("speed".to_owned(), rates.speed);
        extra.insert("unload_speed".to_owned(), rates.unload_speed);
        extra.insert("dwell".to_owned(), rates.dwell);
    }
    let cycle = path.cycle_under(&problem.law);
    // The refined retraction samples the retraction only every coarse step away from the
    // pull-off's brackets: the loop integral and the jump-out are not measured by it (the
    // trapezoids span coarse steps, and the contact may be lost anywhere in the last one), so
    // they are left out rather than reported with the coarse step's error.
    let retraction_measured = !problem.path.refine_pull_off;
    if let Some(w) = cycle.dissipated_energy.filter(|_| retraction_measured) {
        extra.insert("dissipated_energy".to_owned(), w);
        // The loop's uncertainty from the approach's sampling (the loop sampling warning's).
        if let Some(moved) = cycle.approach_sampling {
            extra.insert("dissipated_energy_sampling".to_owned(), moved);
        }
    }
    if let Some((d, f)) = cycle.jump_in {
        extra.insert("jump_in_approach".to_owned(), d);
        extra.insert("jump_in_force".to_owned(), f);
    }
    if let Some((d, f)) = cycle.jump_out.filter(|_| retraction_measured) {
        extra.insert("jump_out_approach".to_owned(), d);
        extra.insert("jump_out_force".to_owned(), f);
    }
    // The fit is to a JKR sphere on a half-space: a film on a rigid base is not one.
    if let Some(f_jkr) = r.f_jkr
        && problem.gamma > 0.0
        && !problem.path.is_indentation()
        && problem.layer.is_none()
    {
        let radius = f_jkr / (-1.5 * std::f64::consts::PI * problem.gamma);
        for (phase, branch, key) in [
            (
                Phase::Load,
                tack_analytics::CycleBranch::Approach,
                "apparent_gamma_approach",
            ),
            (
                Phase::Unload,
                tack_analytics::CycleBranch::Retraction,
                "apparent_gamma_retraction",
            ),
        ] {
            if let Some(g) = apparent_gamma(problem, path, radius, phase, branch) {
                extra.insert(key.to_owned(), g);
            }
        }
    }
    extra.insert("first_touch".to_owned(), problem.first_touch);
    let bad = path.records.iter().filter(|r| !r.converged).count();
    extra.insert("non_converged_steps".to_owned(), bad as f64);
    let edge = path.records.iter().filter(|r| r.edge_contact).count();
    extra.insert("edge_contact_steps".to_owned(), edge as f64);
    let full = path.records.iter().filter(|r| r.full_contact).count();
    extra.insert("full_contact_steps".to_owned(), full as f64);
    if let Some(w) = &problem.window {
        extra.insert("crop_rows".to_owned(), w.shape().0 as f64);
        extra.insert("crop_cols".to_owned(), w.shape().1 as f64);
    }
    let status = if path.completed {
        tack_io::Summary::COMPLETE
    } else {
        tack_io::Summary::STOPPED_AT_MAX_STEPS
    };
    tack_io::Summary {
        pull_off_force: pull_off,
        f_jkr,
        pull_off_ratio: ratio,
        johnson_alpha: r.johnson_alpha,
        alpha_star: r.alpha_star,
        extra,
        status: Some(status.to_owned()),
        adhesion_model: Some(model_name(&problem.law).to_owned()),
        warnings: warnings(problem, path, &cycle),
    }
}

/// The law's own summary entries: `sigma_c` and `kappa` (zero-range), `sigma0`, `range`,
/// `cohesive_zone_elements` (Dugdale), `range`, `peak_tension`, `process_zone_elements` (smooth
/// laws), and the references that go with them (`tabor_mu`, `maugis_lambda`, `f_maugis`).
fn law_extras(
    problem: &Problem,
    r: &crate::references::References,
    extra: &mut std::collections::BTreeMap<String, f64>,
) {
    let (gamma, e_star, dx) = (problem.gamma, problem.e_star, problem.grid.dx());
    for (key, value) in problem.law.summary_entries(gamma, e_star, dx) {
        extra.insert(key.to_owned(), value);
    }
    if let Some(mu) = r.tabor_mu {
        extra.insert("tabor_mu".to_owned(), mu);
    }
    if let Some(l) = r.maugis_lambda {
        extra.insert("maugis_lambda".to_owned(), l);
    }
    if let Some(f) = r.f_maugis {
        extra.insert("f_maugis".to_owned(), f);
    }
}

/// The name of an adhesion law in scene files and results (`/summary` attribute
/// `adhesion_model`).
pub fn model_name(law: &AdhesionLaw) -> &'static str {
    law.name()
}

/// Least number of bonded elements at the pull-off step below which the pull-off is flagged
/// as carried by too few elements to mean anything (a disc of radius 2.5 elements).
pub const MIN_PULL_OFF_ELEMENTS: usize = 20;

/// The warnings of a run: the problem's own (under-resolved, reference not applicable), then
/// what the path shows (stopped at `max_steps`, steps that did not converge, contact at the
/// edge of a free grid, a pull-off not resolved by the path or carried by a handful of
/// elements, a loop its approach does not resolve), from the path's `cycle`
/// ([`PathResult::cycle_under`] the problem's law, as [`summary`] has it).
pub fn warnings(problem: &Problem, path: &PathResult, cycle: &Cycle) -> Vec<String> {
    let mut out = problem.warnings.clone();
    let records = &path.records;
    let adhesive = problem.gamma > 0.0;
    if !path.completed {
        let beyond = if adhesive {
            "; the pull-off may lie beyond the last step"
        } else {
            ""
        };
        out.push(format!(
            "incomplete: the path stopped at {max_steps} = {} before contact was \
             lost{beyond} (raise {max_steps})",
            problem.path.max_steps,
            max_steps = fields::PROTOCOL_MAX_STEPS
        ));
    }
    let full = records.iter().filter(|r| r.full_contact).count();
    if full > 0 {
        let what = if adhesive {
            "their force is not fixed by the approach (the record holds the least admissible \
             mean pressure, about −σ_c, a property of the mesh) and the pull-off leaves them out"
        } else {
            "the gap is closed everywhere, so the mean pressure no longer follows from the \
             approach"
        };
        out.push(format!(
            "full contact in {full} of {} steps (periodic grid: every element in contact): \
             {what}; the approach of a periodic grid is measured from the mean plane of the \
             deformed surface",
            records.len()
        ));
    }
    let bad = records.iter().filter(|r| !r.converged).count();
    if bad > 0 {
        out.push(format!(
            "{bad} of {} steps did not converge (solver caps): their forces are not solutions",
            records.len()
        ));
    }
    let edge = records.iter().filter(|r| r.edge_contact).count();
    if edge > 0 {
        out.push(format!(
            "contact reached the edge of the free grid in {edge} steps: the domain cuts it \
             off (enlarge {n} or {length})",
            n = fields::GRID_N,
            length = fields::GRID_LENGTH
        ));
    }
    if adhesive && path.completed && !problem.path.is_indentation() {
        let tensile = records
            .iter()
            .zip(&path.phases)
            .filter(|(r, phase)| {
                **phase == Phase::Unload
                    && r.force < 0.0
                    && r.n_bonded + r.n_cohesive > 0
                    && !r.full_contact
            })
            .count();
        if tensile < MIN_TENSILE_STEPS {
            out.push(format!(
                "pull-off not resolved by the path: {tensile} retraction steps with contact \
                 have a tensile force (at least {MIN_TENSILE_STEPS} bracket the pull-off), so the \
                 retraction stepped over the tensile part; lower {unload} (or {coarse})",
                unload = fields::PROTOCOL_UNLOAD_STEP,
                coarse = fields::PROTOCOL_COARSE_UNLOAD_STEP
            ));
        } else if let Some(i) = path.pull_off_step() {
            // Under the Dugdale law the zone carries the pull-off too (all of it as the
            // contact shrinks to nothing at small λ).
            let n = records[i].n_bonded + records[i].n_cohesive;
            if n < MIN_PULL_OFF_ELEMENTS {
                out.push(format!(
                    "the pull-off is carried by {n} bonded elements (fewer than \
                     {MIN_PULL_OFF_ELEMENTS}): the mesh does not resolve it (refine {dx})",
                    dx = fields::GRID_DX
                ));
            }
        }
    }
    out.extend(loop_sampling_warning(problem, path, cycle));
    out
}

/// A recorded loop is reported with its sampling ([`tack_solver::Cycle::approach_sampling`]:
/// how far it moves when the approach keeps only every other step) when that exceeds this
/// fraction of the loop …
pub const LOOP_SAMPLING_FRACTION: f64 = 0.1;

/// … and this fraction of the loop's scale, its most tensile force times its approach range
/// (a path without tension has no adhesive loop to judge). Measured: the examples' default
/// paths move their loops by 0.06–2.9% of themselves; the exponential law at Tabor μ = 1, where
/// the retraction retraces the approach and the loop is its sampling's error at every step, on
/// a 128² sphere loaded in 20, 80 and 320 steps (1.33ρ, 0.33ρ, 0.083ρ), moves by 3.5e-3,
/// 2.7e-3 and 1.1e-3 of the scale (by 0.41, 0.89 and 1.07 of the loop), and Python's
/// `pull_off` of a sphere at μ = 1 on its default path by 3.7e-4; a sphere at
/// μ = 1 loaded in steps of 1.07ρ by 6.9e-2. So the warning marks loads coarser than about ρ/5
/// and lets a reversible cycle sampled finely pass as zero.
pub const LOOP_SAMPLING_FLOOR: f64 = 2e-3;

/// The warning of a recorded loop that its approach's steps leave uncertain (docs/theory.md
/// §3.7, "Cycle quantities"): on a cycle the retraction retraces, the loop is the trapezoids'
/// error on the coarser branch alone.
fn loop_sampling_warning(problem: &Problem, path: &PathResult, cycle: &Cycle) -> Option<String> {
    if problem.path.refine_pull_off {
        return None;
    }
    let (w, moved) = (cycle.dissipated_energy?, cycle.approach_sampling?);
    let end = path.records.last()?.approach;
    let (mut tension, mut d) = (0.0f64, (f64::INFINITY, end));
    for r in path.records.iter().filter(|r| r.approach >= end) {
        tension = tension.max(-r.force);
        d = (d.0.min(r.approach), d.1.max(r.approach));
    }
    let scale = tension * (d.1 - d.0);
    if tension <= 0.0
        || moved <= LOOP_SAMPLING_FRACTION * w.abs()
        || moved <= LOOP_SAMPLING_FLOOR * scale
    {
        return None;
    }
    Some(format!(
        "dissipated_energy: the loop {w:.3e} moves by {moved:.2e} when the approach keeps every \
         other step, so its approach's steps leave it uncertain by about that much (where the \
         retraction retraces the approach, the loop is the trapezoids' error alone, about in \
         proportion to {load_step})",
        load_step = fields::PROTOCOL_LOAD_STEP
    ))
}

/// Searched range of the apparent work of adhesion, as factors of the scene's γ: a fit at the
/// lower end of a branch without tension means the branch shows no adhesion and is recorded as
/// 0; a fit at either end otherwise is no fit (the branch is not a JKR curve) and is left out.
const APPARENT_GAMMA_RANGE: (f64, f64) = (1e-3, 1e3);

/// The apparent work of adhesion of the path's `phase` branch: the γ whose JKR sphere of
/// `radius` fits its (approach, force) points best under approach control
/// ([`tack_analytics::apparent_work_of_adhesion`]); approaches from the sphere's vertex, as
/// the JKR reference of `tack plot`. `None` when fewer than [`MIN_TENSILE_STEPS`] steps of
/// the branch carry load, and when the best fit lies at an end of [`APPARENT_GAMMA_RANGE`]
/// although the branch has a tensile force (an adhesive branch no JKR curve fits: 0 would be
/// false beside its pull-off); 0 when it lies at the lower end and the branch has no tension.
fn apparent_gamma(
    problem: &Problem,
    path: &PathResult,
    radius: f64,
    phase: Phase,
    branch: tack_analytics::CycleBranch,
) -> Option<f64> {
    let points: Vec<(f64, f64)> = path
        .records
        .iter()
        .zip(&path.phases)
        .filter(|(s, p)| **p == phase && s.approach.is_finite() && s.force.is_finite())
        .map(|(s, _)| (s.approach, s.force))
        .collect();
    if points.iter().filter(|p| p.1 != 0.0).count() < MIN_TENSILE_STEPS {
        return None;
    }
    let (lo, hi) = APPARENT_GAMMA_RANGE;
    let (lo, hi) = (lo * problem.gamma, hi * problem.gamma);
    let g =
        tack_analytics::apparent_work_of_adhesion(problem.e_star, radius, &points, branch, lo, hi)?;
    let tensile = points.iter().any(|p| p.1 < 0.0);
    let at_lower = g <= lo * (1.0 + 1e-6);
    let at_upper = g >= hi * (1.0 - 1e-6);
    match (at_lower, at_upper, tensile) {
        (true, _, false) => Some(0.0),
        (true, _, true) | (_, true, _) => None,
        _ => Some(g),
    }
}

/// Least number of retraction steps with contact and a tensile force for the path to bracket
/// the pull-off (the least force) with steps on both sides.
pub const MIN_TENSILE_STEPS: usize = 3;

/// Names of every scalar [`summary`] can record: the [`tack_io::Summary`] fields, then its
/// `extra` keys. A run need not have all of them (`d_jkr` only for spheres, `crop_rows` only
/// when cropped, ...). Parameter sweeps collect quantities by these names.
pub const SUMMARY_QUANTITIES: [&str; 49] = [
    "pull_off_force",
    "f_jkr",
    "pull_off_ratio",
    "johnson_alpha",
    "alpha_star",
    "d_jkr",
    "f_kendall",
    "f_mdr",
    "f_elliptic_jkr",
    "gamma_min",
    "gamma_mean",
    "gamma_max",
    "layer_thickness",
    "layer_poisson",
    "p_star",
    "min_mean_pressure",
    "sigma_c",
    "kappa",
    "sigma0",
    "range",
    "cohesive_zone_elements",
    "maugis_lambda",
    "f_maugis",
    "tabor_mu",
    "peak_tension",
    "process_zone_elements",
    "e_instantaneous",
    "speed",
    "unload_speed",
    "dwell",
    "dissipated_energy",
    "dissipated_energy_sampling",
    "jump_in_approach",
    "jump_in_force",
    "jump_out_approach",
    "jump_out_force",
    "apparent_gamma_approach",
    "apparent_gamma_retraction",
    "first_touch",
    "non_converged_steps",
    "edge_contact_steps",
    "full_contact_steps",
    "crop_rows",
    "crop_cols",
    "pull_off_force_coarse",
    "pull_off_force_richardson",
    "pull_off_ratio_richardson",
    "pull_off_error_estimate",
    "richardson_order",
];

/// The summary quantity `name` (a field of [`tack_io::Summary`] or a key of its `extra`), NaN
/// when the summary does not have it.
pub fn summary_quantity(summary: &tack_io::Summary, name: &str) -> f64 {
    match name {
        "pull_off_force" => summary.pull_off_force,
        "f_jkr" => summary.f_jkr,
        "pull_off_ratio" => summary.pull_off_ratio,
        "johnson_alpha" => summary.johnson_alpha.unwrap_or(f64::NAN),
        "alpha_star" => summary.alpha_star.unwrap_or(f64::NAN),
        other => summary.extra.get(other).copied().unwrap_or(f64::NAN),
    }
}

/// The curve of a path run under `law`, one entry per step, with the column the law declares
/// ([`tack_solver::Law::step_column`]: `n_cohesive` under the Dugdale and smooth laws).
pub fn curve(path: &PathResult, law: &dyn tack_solver::Law) -> tack_io::Curve {
    let r = &path.records;
    let law_columns = law
        .step_column()
        .map(|c| tack_io::LawColumn {
            name: c.name.to_owned(),
            meaning: c.meaning,
            values: r.iter().map(|s| s.n_cohesive as u64).collect(),
        })
        .into_iter()
        .collect();
    tack_io::Curve {
        approach: r.iter().map(|s| s.approach).collect(),
        force: r.iter().map(|s| s.force).collect(),
        area: r.iter().map(|s| s.area).collect(),
        n_bonded: r.iter().map(|s| s.n_bonded as u64).collect(),
        n_clusters: r.iter().map(|s| s.n_clusters as u64).collect(),
        iterations: r.iter().map(|s| s.cg_iterations as u64).collect(),
        active_set_iterations: r.iter().map(|s| s.active_set_iterations as u64).collect(),
        converged: r.iter().map(|s| s.converged).collect(),
        mean_pressure: Some(r.iter().map(|s| s.mean_pressure).collect()),
        full_contact: Some(r.iter().map(|s| s.full_contact).collect()),
        time: r
            .iter()
            .map(|s| s.time)
            .collect::<Option<Vec<f64>>>()
            .filter(|t| !t.is_empty()),
        law_columns,
    }
}

/// Everything the result file holds: provenance, curve, surface (when stored), snapshots
/// (on the full grid) and summary. Writes nothing; [`crate::RunOutcome::write`] does.
pub fn assemble_result(
    problem: &Problem,
    path: &PathResult,
    provenance: tack_io::Provenance,
) -> tack_io::RunResult {
    tack_io::RunResult {
        provenance,
        curve: curve(path, &*problem.law),
        surface: problem
            .store_surface
            .then(|| (problem.surface.heights().clone(), problem.grid.dx())),
        gamma: problem.gamma_map.clone().filter(|_| problem.store_surface),
        snapshots: snapshots(path),
        summary: summary(problem, path),
    }
}

/// The path's kept fields as the result file stores them, with each step's approach.
pub fn snapshots(path: &PathResult) -> Vec<tack_io::Snapshot> {
    path.snapshots
        .iter()
        .map(|s| tack_io::Snapshot {
            step: s.step,
            approach: path.records[s.step].approach,
            pressure: s.pressure.clone(),
            bonded: s.bonded.clone(),
        })
        .collect()
}

/// A surface-only result file: provenance, the heights and an empty curve (`tack surface`).
pub fn surface_file(problem: &Problem, provenance: tack_io::Provenance) -> tack_io::RunResult {
    tack_io::RunResult {
        provenance,
        curve: tack_io::Curve {
            mean_pressure: None,
            full_contact: None,
            ..tack_io::Curve::default()
        },
        surface: Some((problem.surface.heights().clone(), problem.grid.dx())),
        gamma: problem.gamma_map.clone(),
        snapshots: Vec::new(),
        summary: tack_io::Summary {
            pull_off_force: f64::NAN,
            f_jkr: problem.references.f_jkr.unwrap_or(f64::NAN),
            pull_off_ratio: f64::NAN,
            johnson_alpha: problem.references.johnson_alpha,
            alpha_star: problem.references.alpha_star,
            extra: Default::default(),
            status: None,
            adhesion_model: Some(model_name(&problem.law).to_owned()),
            warnings: problem.warnings.clone(),
        },
    }
}
