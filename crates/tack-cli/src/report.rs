//! The one-screen account of a run that `tack run` prints: body, path, pull-off against the
//! closed forms, cycle, convergence and warnings, every number rounded ([`rounded`]).

use std::path::Path;

use tack::RunOutcome;
use tack::fields;
pub use tack::fields::rounded;
use tack::geometry::Boundary;
use tack::problem::Problem;
use tack::scene::{Geometry, Roughness, Scene};
use tack::solver::{PathResult, Phase};

/// A one-screen account of a run: scene, grid, path, pull-off force against the closed forms,
/// the cycle, adhesion parameter, convergence and wall time.
pub fn report(scene: &Scene, outcome: &RunOutcome, out: Option<&Path>) -> String {
    let mut lines = body_lines(scene, &outcome.problem);
    lines.extend(path_lines(&outcome.problem, &outcome.path));
    lines.extend(pull_off_lines(outcome));
    lines.extend(reference_lines(outcome));
    lines.extend(cycle_lines(outcome));
    lines.extend(gamma_range_lines(scene, &outcome.result.summary));
    lines.extend(alpha_lines(scene, outcome));
    lines.extend(run_lines(outcome, out));
    lines.join("\n") + "\n"
}

/// Whether the run has a pull-off to report: adhesion, and a path that retracts.
fn adhesive(p: &Problem) -> bool {
    p.gamma > 0.0 && !p.path.is_indentation()
}

/// Scene, body, material (law, layer, γ pattern) and grid.
fn body_lines(scene: &Scene, p: &Problem) -> Vec<String> {
    let f = &scene.file;
    let origin = scene
        .origin
        .as_ref()
        .map_or_else(|| "(in memory)".to_owned(), |o| o.display().to_string());
    let mut lines = vec![
        format!("scene       {origin}"),
        format!("body        {}", describe_body(&f.geometry, &f.roughness)),
    ];
    let law = p.law.describe(p.gamma, p.e_star, p.grid.dx());
    lines.push(format!(
        "material    E* = {}, gamma = {} ({law})",
        rounded(p.e_star),
        rounded(p.gamma),
    ));
    if let Some((prony, rates)) = &p.viscoelastic {
        lines.push(format!(
            "            {}",
            describe_viscoelastic(prony, rates)
        ));
    }
    if let Some(layer) = &p.layer {
        lines.push(format!(
            "            a layer of thickness h = {}, nu = {}, {} on a rigid base",
            rounded(layer.thickness),
            rounded(layer.poisson),
            layer.interface.name()
        ));
    }
    lines.extend(pattern_line(scene));
    let boundary = match p.grid.boundary() {
        Boundary::Free => "free",
        Boundary::Periodic => "periodic",
    };
    let crop = match (&p.window, p.crop) {
        (Some(w), _) => format!(
            " (cropped to the {} x {} elements that can touch)",
            w.shape().0,
            w.shape().1
        ),
        (None, true) if p.grid.boundary() == Boundary::Free => {
            " (crop: nothing to remove)".to_owned()
        }
        _ => String::new(),
    };
    lines.push(format!(
        "grid        {} x {}, dx = {}, {boundary}{crop}",
        p.grid.nx(),
        p.grid.ny(),
        rounded(p.grid.dx()),
    ));
    lines
}

/// The work of adhesion per element, when the scene gives a map or a pattern.
fn pattern_line(scene: &Scene) -> Option<String> {
    let a = &scene.file.adhesion;
    if let Some(path) = &a.gamma_map {
        return Some(format!(
            "            gamma per element from {}",
            path.display()
        ));
    }
    let kind = a.pattern.filter(|k| *k != tack::PatternKind::Uniform)?;
    let opt = |v: Option<f64>| v.map_or("-".to_owned(), rounded);
    Some(match kind {
        tack::PatternKind::Random => format!(
            "            gamma pattern random: contrast {}, correlation length {}, seed {}",
            opt(a.contrast),
            opt(a.correlation_length),
            a.seed.unwrap_or(tack::gamma_map::DEFAULT_PATTERN_SEED)
        ),
        _ => format!(
            "            gamma pattern {}: gamma_b = {}, period {}",
            kind.name(),
            opt(a.gamma_b),
            opt(a.period)
        ),
    })
}

/// A viscoelastic solid and its rates in one line: `viscoelastic: E* relaxes from 10 to 1 (arms
/// [E_k, tau_k] [9, 1]); speed 0.01, unload speed 0.01, dwell 1`.
pub fn describe_viscoelastic(prony: &tack::solver::Prony, rates: &tack::solver::Rates) -> String {
    let arms: Vec<String> = prony
        .arms()
        .iter()
        .map(|a| format!("[{}, {}]", rounded(a.modulus), rounded(a.time)))
        .collect();
    format!(
        "viscoelastic: E* relaxes from {} to {} (arms [E_k, tau_k] {}); speed {}, unload speed \
         {}, dwell {}",
        rounded(prony.instantaneous()),
        rounded(prony.relaxed()),
        arms.join(", "),
        rounded(rates.speed),
        rounded(rates.unload_speed),
        rounded(rates.dwell),
    )
}

/// What the path was (an indentation, one load step or several, the retraction and where it
/// ended), the default rule it came from, and full contact on periodic grids.
pub fn path_lines(p: &Problem, path: &PathResult) -> Vec<String> {
    let stopped = if path.completed {
        String::new()
    } else if adhesive(p) {
        format!(
            "; STOPPED at {} before detachment",
            fields::PROTOCOL_MAX_STEPS
        )
    } else {
        format!(
            "; STOPPED at {} before contact was lost",
            fields::PROTOCOL_MAX_STEPS
        )
    };
    let mut lines = vec![format!("path        {}{stopped}", describe_path(p, path))];
    if let Some(rule) = &p.path_rule {
        lines.push(format!("            {}", rule));
    }
    if let (Some((_, rates)), Some(end)) =
        (&p.viscoelastic, path.records.last().and_then(|r| r.time))
    {
        let hold = if rates.dwell > 0.0 {
            format!(
                ", held {} at the deepest approach in {} steps",
                rounded(rates.dwell),
                rates.dwell_steps
            )
        } else {
            String::new()
        };
        lines.push(format!(
            "time        t = 0 to {}: the first step instantly, then |Δd|/speed each{hold}",
            rounded(end)
        ));
    }
    let full = path.records.iter().filter(|r| r.full_contact).count();
    if full > 0 {
        lines.push(format!(
            "contact     FULL CONTACT in {full} of {} steps (periodic grid: every element \
             touches; the force there is not fixed by the approach)",
            path.records.len()
        ));
    }
    lines
}

/// The path as it was walked: `indentation: one step to d = …`, or `N steps: one load step to
/// d = …, M retraction steps to d = …` (`K load steps from d = … to …` when loaded gradually).
pub fn describe_path(p: &Problem, path: &PathResult) -> String {
    if p.path.is_indentation() {
        return format!(
            "indentation: one step to d = {}",
            rounded(p.path.max_approach)
        );
    }
    let phase_end = |phase: Phase| {
        let steps: Vec<f64> = path
            .records
            .iter()
            .zip(&path.phases)
            .filter(|(_, ph)| **ph == phase)
            .map(|(r, _)| r.approach)
            .collect();
        (steps.len(), steps.first().copied(), steps.last().copied())
    };
    let (loads, first, deepest) = phase_end(Phase::Load);
    let (unloads, _, last) = phase_end(Phase::Unload);
    let load = match (loads, first, deepest) {
        (1, _, Some(d)) => format!("one load step to d = {}", rounded(d)),
        (_, Some(a), Some(b)) => format!(
            "{loads} load steps from d = {} to {}",
            rounded(a),
            rounded(b)
        ),
        _ => "no load step".to_owned(),
    };
    let retraction = match last {
        Some(d) => {
            let how = match (p.path.refine_pull_off, p.path.coarse_unload_step) {
                (true, Some(_)) => {
                    " (refined: coarse steps, the pull-off's brackets retraced)".to_owned()
                }
                (false, Some(_)) => match tail_taken(p, path) {
                    Some(t) => format!(
                        " (coarse while compressive; by {} past the pull-off once nothing \
                         touches)",
                        rounded(t)
                    ),
                    None => " (coarse while compressive)".to_owned(),
                },
                _ => String::new(),
            };
            format!(
                "{unloads} retraction step{} to d = {}{how}",
                if unloads == 1 { "" } else { "s" },
                rounded(d)
            )
        }
        None => "no retraction".to_owned(),
    };
    format!("{} steps: {load}, {retraction}", path.records.len())
}

/// The path a scene asks for, before it runs (`tack check`): `indentation: one step to d = …`,
/// or the load (`one load step to d = …`, `load from d = … to … by …`) and the retraction.
pub fn describe_planned_path(
    path: &tack::solver::ApproachPath,
    law: &tack::solver::AdhesionLaw,
    viscoelastic: bool,
) -> String {
    if path.is_indentation() {
        return format!(
            "indentation: one step to d = {}",
            rounded(path.max_approach)
        );
    }
    let load = if path.start == path.max_approach {
        format!("one load step to d = {}", rounded(path.max_approach))
    } else {
        format!(
            "load from d = {} to {} by {}",
            rounded(path.start),
            rounded(path.max_approach),
            rounded(path.load_step)
        )
    };
    let steps = match (path.refine_pull_off, path.coarse_unload_step) {
        (true, Some(c)) => format!(
            "by {}, the pull-off's brackets retraced by {}",
            rounded(c),
            rounded(path.unload_step)
        ),
        (false, Some(c)) => format!(
            "by {} while compressive, then by {}{}",
            rounded(c),
            rounded(path.unload_step),
            path.tail_step(law, viscoelastic)
                .map_or(String::new(), |t| format!(
                    " (by {} past the pull-off once nothing touches)",
                    rounded(t)
                ))
        ),
        _ => format!("by {}", rounded(path.unload_step)),
    };
    let end = match path.retract_to {
        Some(r) if r == path.max_approach => return format!("{load}, no retraction"),
        Some(r) => format!("down to d = {}", rounded(r)),
        None => "until contact is lost".to_owned(),
    };
    format!("{load}, retraction {steps} {end}")
}

/// The tail step of `p`'s path ([`tack::solver::ApproachPath::tail_step`]) when the run took
/// one: two retraction steps that far apart, the second touching nothing.
fn tail_taken(p: &Problem, path: &PathResult) -> Option<f64> {
    let t = p.path.tail_step(&p.law, p.viscoelastic.is_some())?;
    let unloads: Vec<_> = path
        .records
        .iter()
        .zip(&path.phases)
        .filter(|(_, ph)| **ph == Phase::Unload)
        .map(|(r, _)| r)
        .collect();
    unloads
        .windows(2)
        .any(|w| w[1].n_bonded == 0 && ((w[0].approach - w[1].approach) - t).abs() <= 1e-9 * t)
        .then_some(t)
}

/// The force of an indentation, or the pull-off (or, without adhesion, the peak load).
fn pull_off_lines(outcome: &RunOutcome) -> Vec<String> {
    let (p, path, s) = (&outcome.problem, &outcome.path, &outcome.result.summary);
    if p.path.is_indentation() {
        return path
            .records
            .last()
            .map(|r| {
                format!(
                    "force       F = {} at d = {}, contact area {}{}",
                    rounded(r.force),
                    rounded(r.approach),
                    rounded(r.area),
                    if r.full_contact {
                        " (full contact)"
                    } else {
                        ""
                    }
                )
            })
            .into_iter()
            .collect();
    }
    let periodic = p.grid.boundary() == Boundary::Periodic;
    vec![match path.pull_off_step() {
        Some(i) if adhesive(p) => format!(
            "pull-off    F = {} at d = {}{}",
            rounded(s.pull_off_force),
            rounded(path.records[i].approach),
            if periodic {
                " (the least force over the steps not in full contact)"
            } else {
                " (the least force over the path)"
            }
        ),
        Some(_) => {
            let peak = path
                .records
                .iter()
                .max_by(|a, b| a.force.total_cmp(&b.force));
            format!(
                "force       no adhesion (gamma = 0), no pull-off; peak load F = {} at d = {}",
                rounded(peak.map_or(f64::NAN, |r| r.force)),
                rounded(peak.map_or(f64::NAN, |r| r.approach))
            )
        }
        None => "pull-off    none: no step outside full contact".to_owned(),
    }]
}

/// The pull-off against the closed forms (JKR, Maugis, MDR, Johnson–Greenwood, Kendall),
/// Richardson, and p* of periodic grids.
fn reference_lines(outcome: &RunOutcome) -> Vec<String> {
    let (p, s) = (&outcome.problem, &outcome.result.summary);
    let mut lines = Vec::new();
    let adhesive = adhesive(p);
    let ratio = |f: f64| rounded_ratio(s.pull_off_force / f);
    if adhesive && s.f_jkr.is_finite() && s.f_jkr != 0.0 {
        let whose = if p.layer.is_some() {
            "Eq. 7, of a half-space"
        } else {
            "Eq. 7"
        };
        lines.push(format!(
            "            F_JKR = {}, F/F_JKR = {} ({whose})",
            rounded(s.f_jkr),
            rounded_ratio(s.pull_off_ratio)
        ));
    }
    let get = |k: &str| s.extra.get(k).copied().filter(|_| adhesive);
    if let (Some(fm), Some(lambda)) = (get("f_maugis"), get("maugis_lambda")) {
        lines.push(format!(
            "            F_Maugis = {}, F/F_Maugis = {} (Dugdale, λ = {:.4})",
            rounded(fm),
            ratio(fm),
            lambda
        ));
    }
    if let Some(mu) = get("tabor_mu") {
        lines.push(format!(
            "            Tabor mu = {} (JKR 1.5 pi gamma R as mu grows, DMT 2 pi gamma R as it \
             vanishes); process zone {} elements",
            if mu < 1e4 {
                format!("{mu:.4}")
            } else {
                format!("{mu:.4e}")
            },
            get("process_zone_elements").map_or_else(|| "?".to_owned(), fields::elements)
        ));
    }
    if let Some(fm) = get("f_mdr") {
        lines.push(format!(
            "            F_MDR = {}, F/F_MDR = {} (power law, exact JKR limit)",
            rounded(fm),
            ratio(fm)
        ));
    }
    if let Some(fe) = get("f_elliptic_jkr") {
        lines.push(format!(
            "            F_JG = {}, F/F_JG = {} (ellipsoid, Johnson–Greenwood approximate JKR)",
            rounded(fe),
            ratio(fe)
        ));
    }
    if let Some(fk) = get("f_kendall") {
        lines.push(format!(
            "            F_Kendall = {}, F/F_Kendall = {}",
            rounded(fk),
            ratio(fk)
        ));
    }
    lines.extend(richardson_lines(s));
    if let (Some(&p_star), Some(&p_min)) = (s.extra.get("p_star"), s.extra.get("min_mean_pressure"))
        && p.grid.boundary() == Boundary::Periodic
    {
        lines.push(format!(
            "            min mean pressure = {} = {} p* (p* = {}, complete-contact pressure)",
            rounded(p_min),
            rounded_ratio(p_min / p_star),
            rounded(p_star)
        ));
    }
    lines
}

/// The range of a γ that varies over the surface, beside the γ the closed forms use.
fn gamma_range_lines(scene: &Scene, s: &tack_io::Summary) -> Vec<String> {
    let mut lines = Vec::new();
    if let (Some(&lo), Some(&mean), Some(&hi)) = (
        s.extra.get("gamma_min"),
        s.extra.get("gamma_mean"),
        s.extra.get("gamma_max"),
    ) {
        lines.push(format!(
            "gamma       varies over the surface: {} to {}, mean {} (the closed forms and their \
             ratios use gamma = {})",
            rounded(lo),
            rounded(hi),
            rounded(mean),
            rounded(scene.file.material.gamma)
        ));
    }
    lines
}

/// A ratio to 4 decimals (the closed forms' agreement, not their digits).
fn rounded_ratio(r: f64) -> String {
    format!("{r:.4}")
}

/// The Richardson extrapolation of the pull-off and its error estimate (`--richardson`).
fn richardson_lines(s: &tack_io::Summary) -> Vec<String> {
    let (Some(&fr), Some(&fc)) = (
        s.extra.get("pull_off_force_richardson"),
        s.extra.get("pull_off_force_coarse"),
    ) else {
        return Vec::new();
    };
    let ratio = s
        .extra
        .get("pull_off_ratio_richardson")
        .map_or(String::new(), |&r| {
            format!(", F/F_JKR = {}", rounded_ratio(r))
        });
    // The law's order: 2·F(Δx) − F(2Δx) at first order, F(Δx) + (F(Δx) − F(2Δx))/3 at second.
    let rule = match s.extra.get("richardson_order").copied() {
        Some(2.0) => "F(Δx) + (F(Δx) − F(2Δx))/3 (second order)".to_owned(),
        Some(p) if p != 1.0 => format!("F(Δx) + (F(Δx) − F(2Δx))/(2^{p} − 1)"),
        _ => "2·F(Δx) − F(2Δx)".to_owned(),
    };
    let mut lines = vec![format!(
        "Richardson  F = {} = {rule}, F(2Δx) = {}{ratio}",
        rounded(fr),
        rounded(fc)
    )];
    if let Some(&err) = s.extra.get("pull_off_error_estimate") {
        let relative = if s.pull_off_force != 0.0 {
            format!(" ({:.2}% of F)", 100.0 * err / s.pull_off_force.abs())
        } else {
            String::new()
        };
        lines.push(format!(
            "            error estimate of F(Δx) = {}{relative}: the larger of |F(Δx) − F(2Δx)| \
             and, for the zero-range criterion on a sphere, {}·(Δx/a_c)·|F|",
            rounded(err),
            tack::solver::CRITERION_ERROR_COEFFICIENT
        ));
    }
    lines
}

/// The cycle: dissipated energy and jumps (or why they are not measured), and the apparent
/// work of adhesion of each branch.
fn cycle_lines(outcome: &RunOutcome) -> Vec<String> {
    let (p, s) = (&outcome.problem, &outcome.result.summary);
    if !adhesive(p) {
        return Vec::new();
    }
    let mut lines = Vec::new();
    let get = |k: &str| s.extra.get(k).copied();
    let jump = |a: &str, f: &str| match (get(a), get(f)) {
        (Some(d), Some(f)) => format!("d = {}, F = {}", rounded(d), rounded(f)),
        _ => "none".to_owned(),
    };
    if let Some(w) = get("dissipated_energy") {
        let sampling = get("dissipated_energy_sampling")
            .map(|m| format!(" (± {} by the approach's steps)", rounded(m)))
            .unwrap_or_default();
        lines.push(format!(
            "cycle       dissipated ∮F dd = {}{sampling}; jump in at {}, out at {}",
            rounded(w),
            jump("jump_in_approach", "jump_in_force"),
            jump("jump_out_approach", "jump_out_force")
        ));
    } else if p.path.refine_pull_off && get("jump_in_approach").is_some() {
        lines.push(format!(
            "cycle       jump in at {}; dissipated energy and jump-out not measured: the refined \
             retraction ({} = true) steps by {} away from the pull-off",
            jump("jump_in_approach", "jump_in_force"),
            fields::PROTOCOL_REFINE_PULL_OFF,
            fields::PROTOCOL_COARSE_UNLOAD_STEP
        ));
    }
    let branch = |k: &str, name: &str| {
        get(k).map(|g| {
            if g == 0.0 {
                format!("{name} 0 (no adhesion)")
            } else {
                format!("{name} {}", rounded(g))
            }
        })
    };
    let fits: Vec<String> = [
        branch("apparent_gamma_approach", "approach"),
        branch("apparent_gamma_retraction", "retraction"),
    ]
    .into_iter()
    .flatten()
    .collect();
    if !fits.is_empty() {
        lines.push(format!(
            "            apparent gamma (best JKR fit): {}",
            fits.join(", ")
        ));
    }
    lines
}

/// Johnson's α (waviness) and α* (random roughness) with what they predict.
fn alpha_lines(scene: &Scene, outcome: &RunOutcome) -> Vec<String> {
    let (f, s) = (&scene.file, &outcome.result.summary);
    let sphere = matches!(f.geometry, Geometry::Sphere { .. });
    let mut lines = Vec::new();
    if let Some(a) = s.johnson_alpha {
        let tail = match (&f.roughness, sphere) {
            (Some(Roughness::Waviness2d { .. }), true) => format!(
                "; Eq. 9 predicts F/F_JKR = {:.3} (fit for lambda/R = 0.05)",
                tack::analytics::lambda_fit(a)
            ),
            (Some(Roughness::Waviness1d { .. }), false) => format!(
                "; 1D critical value {:.4}: {}",
                tack::analytics::JOHNSON_1D_CRITICAL_ALPHA,
                if a > tack::analytics::JOHNSON_1D_CRITICAL_ALPHA {
                    "jumps into full contact at first touch"
                } else {
                    "partial contact is stable"
                }
            ),
            _ => String::new(),
        };
        lines.push(format!("alpha       Johnson alpha = {a:.4} (Eq. 3){tail}"));
    }
    if let Some(a) = s.alpha_star {
        let tail = if sphere {
            format!(
                "; Eq. 12 predicts |F/F_JKR| = {:.3}",
                tack::analytics::lambda_star(a)
            )
        } else {
            String::new()
        };
        lines.push(format!("alpha*      {a:.4} (Eq. 11){tail}"));
    }
    lines
}

/// Convergence, status, warnings, wall time and the file written.
fn run_lines(outcome: &RunOutcome, out: Option<&Path>) -> Vec<String> {
    let (path, s) = (&outcome.path, &outcome.result.summary);
    let bad = path.records.iter().filter(|r| !r.converged).count();
    let mut lines = vec![
        format!(
            "converged   {}/{} steps{}",
            path.records.len() - bad,
            path.records.len(),
            if bad > 0 {
                format!(" ({bad} NOT converged)")
            } else {
                String::new()
            }
        ),
        format!("status      {}", s.status.as_deref().unwrap_or("unknown")),
    ];
    lines.extend(s.warnings.iter().map(|w| format!("WARNING     {w}")));
    // A smooth law's count is of operator products (Newton's Krylov iterations, its line
    // search's trials and the landings' CG iterations), not of CG iterations alone.
    let work = if outcome.problem.law.is_smooth() {
        "operator products"
    } else {
        "CG iterations"
    };
    lines.push(match outcome.coarse_wall_time {
        Some(coarse) => format!(
            "wall time   {:.2} s: {:.2} s for the run ({} {work}) + {:.2} s for the \
             coarse (2Δx) run",
            outcome.total_wall_time().as_secs_f64(),
            outcome.wall_time.as_secs_f64(),
            path.cg_iterations(),
            coarse.as_secs_f64()
        ),
        None => format!(
            "wall time   {:.2} s ({} {work})",
            outcome.wall_time.as_secs_f64(),
            path.cg_iterations()
        ),
    });
    if let Some(out) = out {
        lines.push(format!("wrote       {}", out.display()));
    }
    lines
}

fn describe_body(geometry: &Geometry, roughness: &Option<Roughness>) -> String {
    let r = |x: f64| rounded(x);
    let shape = geometry.shape().describe();
    let rough = match roughness {
        None => String::new(),
        Some(Roughness::Waviness1d { h, lambda }) => {
            format!(" + 1D waviness h = {}, lambda = {}", r(*h), r(*lambda))
        }
        Some(Roughness::Waviness2d { h, lambda }) => {
            format!(" + 2D waviness h = {}, lambda = {}", r(*h), r(*lambda))
        }
        Some(Roughness::Random { h, hurst, seed, .. }) => {
            format!(
                " + random roughness rms {}, H = {}, seed {seed}",
                r(*h),
                r(*hurst)
            )
        }
        Some(Roughness::File { path, .. }) => format!(" + height map {}", path.display()),
    };
    shape + &rough
}

#[cfg(test)]
mod tests {
    use super::*;
    use tack::RunOptions;

    fn run(text: &str, sets: &[&str]) -> (Scene, RunOutcome) {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let scene = Scene::parse(text, ".", &sets).unwrap();
        let outcome = tack::run(&scene, &RunOptions::default(), &mut ()).unwrap();
        (scene, outcome)
    }

    const WAVY_1D: &str = include_str!("../../../data/examples/wavy_1d_periodic.toml");
    const SPHERE: &str = include_str!("../../../data/examples/smooth_jkr_sphere.toml");

    #[test]
    fn the_pull_off_approach_is_that_of_the_step_carrying_the_force() {
        // Pressed past the mean height, the waviness is in full contact, whose steps record the
        // least admissible force (a bound), lower than the pull-off force.
        let (scene, outcome) = run(WAVY_1D, &["protocol.max_approach=0.012"]);
        let records = &outcome.path.records;
        let least = records
            .iter()
            .min_by(|a, b| a.force.total_cmp(&b.force))
            .unwrap();
        assert!(
            least.full_contact,
            "the scene must hit the full-contact bound"
        );
        let i = outcome.path.pull_off_step().unwrap();
        assert!(!records[i].full_contact);
        assert_eq!(records[i].force, outcome.pull_off_force());
        let text = report(&scene, &outcome, None);
        let want = format!(
            "F = {} at d = {} ",
            rounded(records[i].force),
            rounded(records[i].approach)
        );
        assert!(text.contains(&want), "{text}\nwants {want}");
        assert!(
            !text.contains(&format!("at d = {} ", rounded(least.approach))),
            "{text}"
        );
        // The least mean pressure is a state's, not the full-contact bound.
        let p_min = outcome.result.summary.extra["min_mean_pressure"];
        assert!(least.mean_pressure < p_min, "{p_min}");
        let states = records.iter().filter(|r| !r.full_contact);
        let want = states
            .map(|r| r.mean_pressure)
            .fold(f64::INFINITY, f64::min);
        assert_eq!(p_min, want);
    }

    #[test]
    fn without_adhesion_no_pull_off_or_jkr_ratio_is_printed() {
        let (scene, outcome) = run(SPHERE, &["material.gamma=0"]);
        let text = report(&scene, &outcome, None);
        assert!(!text.contains("NaN") && !text.contains("F_JKR"), "{text}");
        assert!(!text.contains("pull-off    F"), "{text}");
        assert!(text.contains("no adhesion (gamma = 0)"), "{text}");
        let peak = outcome
            .path
            .records
            .iter()
            .map(|r| r.force)
            .fold(0.0, f64::max);
        assert!(
            text.contains(&format!("peak load F = {}", rounded(peak))),
            "{text}"
        );
    }

    #[test]
    fn the_richardson_wall_time_includes_the_coarse_run() {
        let scene = Scene::parse(SPHERE, ".", &[]).unwrap();
        let options = RunOptions {
            command_line: None,
            richardson: true,
            threads: None,
        };
        let outcome = tack::run(&scene, &options, &mut ()).unwrap();
        let text = report(&scene, &outcome, None);
        let total = format!(
            "wall time   {:.2} s",
            outcome.total_wall_time().as_secs_f64()
        );
        assert!(
            text.contains(&total) && text.contains("coarse (2Δx) run"),
            "{text}"
        );
        let s = &outcome.result.summary;
        let err = s.extra["pull_off_error_estimate"];
        assert_eq!(
            err,
            (s.pull_off_force - s.extra["pull_off_force_coarse"]).abs()
        );
        assert!(
            text.contains(&format!("error estimate of F(Δx) = {}", rounded(err))),
            "{text}"
        );
        assert!(text.contains("= 2·F(Δx) − F(2Δx)"), "{text}");
    }

    /// The report names the rule the law's order gave: second order for a smooth law, first
    /// for a file without `richardson_order` (written before it, extrapolated at first order).
    #[test]
    fn the_richardson_line_names_the_laws_order() {
        let mut s = tack_io::Summary {
            pull_off_force: -1.0,
            ..Default::default()
        };
        s.extra.insert("pull_off_force_coarse".into(), -1.2);
        s.extra
            .insert("pull_off_force_richardson".into(), -1.0 + 0.2 / 3.0);
        s.extra.insert("richardson_order".into(), 2.0);
        let second = richardson_lines(&s).join("\n");
        assert!(
            second.contains("F(Δx) + (F(Δx) − F(2Δx))/3 (second order)"),
            "{second}"
        );
        s.extra.remove("richardson_order");
        let first = richardson_lines(&s).join("\n");
        assert!(first.contains("2·F(Δx) − F(2Δx)"), "{first}");
    }
}
