//! The one-screen account of a run that `tack run` prints, and number formatting.

use std::path::Path;

use tack::RunOutcome;
use tack::fields;
use tack::scene::{Geometry, Roughness, Scene};
use tack::solver::Phase;

/// A one-screen account of a run: scene, grid, path, pull-off force against the closed forms,
/// adhesion parameter, convergence and wall time.
pub fn report(scene: &Scene, outcome: &RunOutcome, out: Option<&Path>) -> String {
    let p = &outcome.problem;
    let path = &outcome.path;
    let s = &outcome.result.summary;
    let f = &scene.file;
    let mut lines = Vec::new();
    let origin = scene
        .origin
        .as_ref()
        .map_or_else(|| "(in memory)".to_owned(), |o| o.display().to_string());
    lines.push(format!("scene       {origin}"));
    lines.push(format!(
        "body        {}",
        describe_body(&f.geometry, &f.roughness)
    ));
    let law = match p.law {
        tack::solver::AdhesionLaw::JkrLimit { kappa } => {
            format!("zero-range limit, kappa = {}", rounded(kappa))
        }
        tack::solver::AdhesionLaw::Dugdale { sigma0 } => format!(
            "Dugdale, sigma0 = {}, range = {}",
            rounded(sigma0),
            rounded(p.gamma / sigma0)
        ),
    };
    lines.push(format!(
        "material    E* = {}, gamma = {} ({law})",
        rounded(p.e_star),
        rounded(p.gamma),
    ));
    if let Some(layer) = &p.layer {
        lines.push(format!(
            "            a layer of thickness h = {}, nu = {}, {} on a rigid base",
            rounded(layer.thickness),
            layer.poisson,
            layer.interface.name()
        ));
    }
    let a = &f.adhesion;
    if let Some(path) = &a.gamma_map {
        lines.push(format!(
            "            gamma per element from {}",
            path.display()
        ));
    } else if let Some(kind) = a.pattern.filter(|k| *k != tack::PatternKind::Uniform) {
        let opt = |v: Option<f64>| v.map_or("-".to_owned(), rounded);
        lines.push(match kind {
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
        });
    }
    let boundary = match p.grid.boundary() {
        tack::geometry::Boundary::Free => "free",
        tack::geometry::Boundary::Periodic => "periodic",
    };
    lines.push(format!(
        "grid        {} x {}, dx = {}, {boundary}{}",
        p.grid.nx(),
        p.grid.ny(),
        p.grid.dx(),
        match (&p.window, p.crop) {
            (Some(w), _) => format!(
                " (cropped to the {} x {} elements that can touch)",
                w.shape().0,
                w.shape().1
            ),
            (None, true) if p.grid.boundary() == tack::geometry::Boundary::Free =>
                " (crop: nothing to remove)".to_owned(),
            _ => String::new(),
        }
    ));
    let loads = path.phases.iter().filter(|&&ph| ph == Phase::Load).count();
    // An indentation has no pull-off: only the force of its one state.
    let adhesive = p.gamma > 0.0 && !p.path.is_indentation();
    let periodic = p.grid.boundary() == tack::geometry::Boundary::Periodic;
    let stopped = if path.completed {
        String::new()
    } else if adhesive {
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
    if p.path.is_indentation() {
        lines.push(format!(
            "path        indentation: one step to d = {}{stopped}",
            rounded(p.path.max_approach)
        ));
    } else {
        lines.push(format!(
            "path        {} steps ({} load, {} unload), d from {} to {} and back{stopped}",
            path.records.len(),
            loads,
            path.records.len() - loads,
            rounded(p.path.start),
            rounded(p.path.max_approach),
        ));
    }
    if let Some(rule) = &p.path_rule {
        lines.push(format!("            {rule}"));
    }
    let full = path.records.iter().filter(|r| r.full_contact).count();
    if full > 0 {
        lines.push(format!(
            "contact     FULL CONTACT in {full} of {} steps (periodic grid: every element \
             touches; the force there is not fixed by the approach)",
            path.records.len()
        ));
    }
    if p.path.is_indentation() {
        if let Some(r) = path.records.last() {
            lines.push(format!(
                "force       F = {} at d = {}, contact area {}{}",
                rounded(r.force),
                rounded(r.approach),
                rounded(r.area),
                if r.full_contact {
                    " (full contact)"
                } else {
                    ""
                }
            ));
        }
    } else {
        match path.pull_off_step() {
            Some(i) if adhesive => lines.push(format!(
                "pull-off    F = {} at d = {}{}",
                rounded(s.pull_off_force),
                rounded(path.records[i].approach),
                if periodic {
                    " (the least force over the steps not in full contact)"
                } else {
                    " (the least force over the path)"
                }
            )),
            Some(_) => {
                let peak = path
                    .records
                    .iter()
                    .max_by(|a, b| a.force.total_cmp(&b.force));
                lines.push(format!(
                    "force       no adhesion (gamma = 0), no pull-off; peak load F = {} at d = {}",
                    rounded(peak.map_or(f64::NAN, |r| r.force)),
                    rounded(peak.map_or(f64::NAN, |r| r.approach))
                ));
            }
            None => lines.push("pull-off    none: no step outside full contact".to_owned()),
        }
    }
    if adhesive && s.f_jkr.is_finite() && s.f_jkr != 0.0 {
        lines.push(format!(
            "            F_JKR = {}, F/F_JKR = {:.4} (Eq. 7)",
            rounded(s.f_jkr),
            s.pull_off_ratio
        ));
    }
    if let (Some(&fm), Some(&lambda)) = (s.extra.get("f_maugis"), s.extra.get("maugis_lambda")) {
        lines.push(format!(
            "            F_Maugis = {}, F/F_Maugis = {:.4} (Dugdale, λ = {:.4})",
            rounded(fm),
            s.pull_off_force / fm,
            lambda
        ));
    }
    if let Some(&w) = s.extra.get("dissipated_energy").filter(|_| adhesive) {
        let jump = |a: &str, f: &str| match (s.extra.get(a), s.extra.get(f)) {
            (Some(&d), Some(&f)) => format!("d = {}, F = {}", rounded(d), rounded(f)),
            _ => "none".to_owned(),
        };
        lines.push(format!(
            "cycle       dissipated ∮F dd = {}; jump in at {}, out at {}",
            rounded(w),
            jump("jump_in_approach", "jump_in_force"),
            jump("jump_out_approach", "jump_out_force")
        ));
    }
    if let Some(&gr) = s.extra.get("apparent_gamma_retraction") {
        let approach = s
            .extra
            .get("apparent_gamma_approach")
            .map_or("no approach branch".to_owned(), |&g| {
                format!("approach {}", rounded(g))
            });
        lines.push(format!(
            "            apparent gamma (best JKR fit): {approach}, retraction {}",
            rounded(gr)
        ));
    }
    if let Some(&fm) = s.extra.get("f_mdr").filter(|_| adhesive) {
        lines.push(format!(
            "            F_MDR = {}, F/F_MDR = {:.4} (power law, exact JKR limit)",
            rounded(fm),
            s.pull_off_force / fm
        ));
    }
    if let Some(&fe) = s.extra.get("f_elliptic_jkr").filter(|_| adhesive) {
        lines.push(format!(
            "            F_JG = {}, F/F_JG = {:.4} (ellipsoid, Johnson–Greenwood approximate JKR)",
            rounded(fe),
            s.pull_off_force / fe
        ));
    }
    if let (Some(&lo), Some(&mean), Some(&hi)) = (
        s.extra.get("gamma_min"),
        s.extra.get("gamma_mean"),
        s.extra.get("gamma_max"),
    ) {
        lines.push(format!(
            "gamma       varies over the surface: {} to {}, mean {} (F_JKR and the ratios use \
             gamma = {})",
            rounded(lo),
            rounded(hi),
            rounded(mean),
            rounded(f.material.gamma)
        ));
    }
    if let Some(&fk) = s.extra.get("f_kendall").filter(|_| adhesive) {
        lines.push(format!(
            "            F_Kendall = {}, F/F_Kendall = {:.4}",
            rounded(fk),
            s.pull_off_force / fk
        ));
    }
    if let (Some(&fr), Some(&fc)) = (
        s.extra.get("pull_off_force_richardson"),
        s.extra.get("pull_off_force_coarse"),
    ) {
        let ratio = s
            .extra
            .get("pull_off_ratio_richardson")
            .map_or(String::new(), |r| format!(", F/F_JKR = {r:.4}"));
        lines.push(format!(
            "Richardson  F = {} = 2·F(Δx) − F(2Δx), F(2Δx) = {}{ratio}",
            rounded(fr),
            rounded(fc)
        ));
        if let Some(&err) = s.extra.get("pull_off_error_estimate") {
            let relative = if s.pull_off_force != 0.0 {
                format!(" ({:.2}% of F)", 100.0 * err / s.pull_off_force.abs())
            } else {
                String::new()
            };
            lines.push(format!(
                "            error estimate of F(Δx) = {}{relative}: the larger of |F(Δx) − F(2Δx)| \
                 and, for spheres, {}·(Δx/a_c)·|F|",
                rounded(err),
                tack::solver::CRITERION_ERROR_COEFFICIENT
            ));
        }
    }
    let sphere = matches!(f.geometry, Geometry::Sphere { .. });
    if let (Some(&p_star), Some(&p_min)) = (s.extra.get("p_star"), s.extra.get("min_mean_pressure"))
        && p.grid.boundary() == tack::geometry::Boundary::Periodic
    {
        lines.push(format!(
            "            min mean pressure = {} = {:.4} p* (p* = {}, complete-contact pressure)",
            rounded(p_min),
            p_min / p_star,
            rounded(p_star)
        ));
    }
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
    let bad = path.records.iter().filter(|r| !r.converged).count();
    lines.push(format!(
        "converged   {}/{} steps{}",
        path.records.len() - bad,
        path.records.len(),
        if bad > 0 {
            format!(" ({bad} NOT converged)")
        } else {
            String::new()
        }
    ));
    lines.push(format!(
        "status      {}",
        s.status.as_deref().unwrap_or("unknown")
    ));
    for warning in &s.warnings {
        lines.push(format!("WARNING     {warning}"));
    }
    match outcome.coarse_wall_time {
        Some(coarse) => lines.push(format!(
            "wall time   {:.2} s: {:.2} s for the run ({} CG iterations) + {:.2} s for the \
             coarse (2Δx) run",
            outcome.total_wall_time().as_secs_f64(),
            outcome.wall_time.as_secs_f64(),
            path.cg_iterations(),
            coarse.as_secs_f64()
        )),
        None => lines.push(format!(
            "wall time   {:.2} s ({} CG iterations)",
            outcome.wall_time.as_secs_f64(),
            path.cg_iterations()
        )),
    }
    if let Some(out) = out {
        lines.push(format!("wrote       {}", out.display()));
    }
    lines.join("\n") + "\n"
}

fn describe_body(geometry: &Geometry, roughness: &Option<Roughness>) -> String {
    let shape = match geometry {
        Geometry::Sphere { radius } => format!("sphere R = {radius}"),
        Geometry::FlatPunch {
            radius: Some(r), ..
        } => format!("circular flat punch a = {r}"),
        Geometry::FlatPunch {
            half_side: Some(s), ..
        } => format!("square flat punch half side {s}"),
        Geometry::FlatPunch { .. } => "flat punch".to_owned(),
        Geometry::PowerLaw { c, exponent } if *exponent == 1.0 => format!("cone z = {c}·r"),
        Geometry::PowerLaw { c, exponent } => format!("power law z = {c}·r^{exponent}"),
        Geometry::Ellipsoid { radius_x, radius_y } => {
            format!("ellipsoid Rx = {radius_x}, Ry = {radius_y}")
        }
        Geometry::None => "flat".to_owned(),
    };
    let rough = match roughness {
        None => String::new(),
        Some(Roughness::Waviness1d { h, lambda }) => {
            format!(" + 1D waviness h = {h}, lambda = {lambda}")
        }
        Some(Roughness::Waviness2d { h, lambda }) => {
            format!(" + 2D waviness h = {h}, lambda = {lambda}")
        }
        Some(Roughness::Random { h, hurst, seed, .. }) => {
            format!(" + random roughness rms {h}, H = {hurst}, seed {seed}")
        }
        Some(Roughness::File { path, .. }) => format!(" + height map {}", path.display()),
    };
    shape + &rough
}

/// The former name of [`rounded`] (one `num` is enough: `tack_fields::num`).
#[deprecated(since = "0.1.0", note = "renamed `rounded`")]
pub fn num(x: f64) -> String {
    rounded(x)
}

/// A number with 6 significant digits, in plain notation for magnitudes in [1e-3, 1e6): the
/// report's rounded display. Messages quoting a value use the round-trip formatter
/// `tack_fields::num` instead, which keeps every digit.
pub fn rounded(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let mag = x.abs().log10().floor();
    if (-3.0..6.0).contains(&mag) {
        let decimals = (5.0 - mag).max(0.0) as usize;
        let s = format!("{x:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_owned()
        } else {
            s
        }
    } else {
        let s = format!("{x:.5e}");
        match s.split_once('e') {
            Some((mantissa, exp)) if mantissa.contains('.') => format!(
                "{}e{exp}",
                mantissa.trim_end_matches('0').trim_end_matches('.')
            ),
            _ => s,
        }
    }
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
    }

    #[test]
    fn numbers_have_six_significant_digits() {
        assert_eq!(rounded(-5.3454057683), "-5.34541");
        assert_eq!(rounded(0.005), "0.005");
        assert_eq!(rounded(3.0), "3");
        assert_eq!(rounded(123456.7), "123457");
        assert_eq!(rounded(1.5e-7), "1.5e-7");
        assert_eq!(rounded(5e-4), "5e-4");
        assert_eq!(rounded(f64::NAN), "NaN");
        assert_eq!(rounded(0.0), "0");
    }
}
