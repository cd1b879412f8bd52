//! The one-screen account of a run that `tack run` prints, and number formatting.

use std::path::Path;

use tack::RunOutcome;
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
    lines.push(format!(
        "material    E* = {}, gamma = {}, kappa = {}",
        num(p.e_star),
        num(p.gamma),
        num(p.kappa)
    ));
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
    lines.push(format!(
        "path        {} steps ({} load, {} unload), d from {} to {} and back{}",
        path.records.len(),
        loads,
        path.records.len() - loads,
        num(p.path.start),
        num(p.path.max_approach),
        if path.completed {
            ""
        } else {
            "; STOPPED at protocol.max_steps before detachment"
        }
    ));
    let adhesive = p.gamma > 0.0;
    match path.pull_off_step() {
        Some(i) if adhesive => lines.push(format!(
            "pull-off    F = {} at d = {} (the least force over the steps not in full contact)",
            num(s.pull_off_force),
            num(path.records[i].approach)
        )),
        Some(i) => lines.push(format!(
            "force       no adhesion (gamma = 0): no pull-off; least force {} at d = {}",
            num(s.pull_off_force),
            num(path.records[i].approach)
        )),
        None => lines.push("pull-off    none: no step outside full contact".to_owned()),
    }
    if adhesive && s.f_jkr.is_finite() && s.f_jkr != 0.0 {
        lines.push(format!(
            "            F_JKR = {}, F/F_JKR = {:.4} (Eq. 7)",
            num(s.f_jkr),
            s.pull_off_ratio
        ));
    }
    if let Some(&fk) = s.extra.get("f_kendall").filter(|_| adhesive) {
        lines.push(format!(
            "            F_Kendall = {}, F/F_Kendall = {:.4}",
            num(fk),
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
            num(fr),
            num(fc)
        ));
    }
    let sphere = matches!(f.geometry, Geometry::Sphere { .. });
    if let (Some(&p_star), Some(&p_min)) = (s.extra.get("p_star"), s.extra.get("min_mean_pressure"))
        && p.grid.boundary() == tack::geometry::Boundary::Periodic
    {
        lines.push(format!(
            "            min mean pressure = {} = {:.4} p* (p* = {}, complete-contact pressure)",
            num(p_min),
            p_min / p_star,
            num(p_star)
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
    let edge = path.records.iter().filter(|r| r.edge_contact).count();
    if edge > 0 {
        lines.push(format!(
            "WARNING     contact reached the edge of the free grid in {edge} steps: the domain \
             cuts it off; enlarge grid.n or grid.length"
        ));
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

/// A number with 6 significant digits, in plain notation for magnitudes in [1e-3, 1e6).
pub fn num(x: f64) -> String {
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
