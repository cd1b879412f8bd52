//! Figures 1 and 2: periodic 1D and 2D waviness against Johnson's closed forms (Eq. 2, Eq. 5),
//! loaded into full contact and retracted until detached.

use std::f64::consts::PI;

use anyhow::{Result, bail};
use serde::Deserialize;
use tack::scene::Roughness;
use tack_analytics::{
    johnson_1d_mean_pressure_ratio, johnson_2d_near_full_ratio, johnson_2d_p_star,
    westergaard_p_star,
};
use tack_solver::{Phase, count_clusters};

use super::{Ctx, FigureSummary, RunFiles, Table, write_figure};
use crate::engine::{FigureRun, Keep, RunSpec, run_all};
use crate::plot::{Chart, Map, Series, Style, draw_chart, draw_maps};
use crate::spec::{FigureSpec, scene};

/// Sweep parameters of Figures 1 and 2.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Params {
    /// Johnson parameters α (Eq. 3); γ follows from the scene's h, λ and E*.
    alphas: Vec<f64>,
    /// Range of the compared abscissa: ψ = πa/λ (Fig. 1) or ψ_b = πb/λ (Fig. 2).
    compare: [f64; 2],
    /// Fig. 2: the α of the detail panel (B) with contact configurations.
    #[serde(default)]
    detail_alpha: Option<f64>,
}

/// The runs of a periodic waviness figure: one per α, γ = α²π²h²E*/(2λ).
fn runs(spec: &FigureSpec, params: &Params, keep: Keep) -> Result<Vec<std::sync::Arc<FigureRun>>> {
    let base = spec.scene()?;
    let (h, lambda) = match base.roughness {
        Some(Roughness::Waviness1d { h, lambda } | Roughness::Waviness2d { h, lambda }) => {
            (h, lambda)
        }
        _ => bail!("{}: the scene must have a waviness", spec.path.display()),
    };
    let specs = params
        .alphas
        .iter()
        .map(|&alpha| {
            let mut file = base.clone();
            file.material.gamma =
                alpha * alpha * PI * PI * h * h * file.material.e_star / (2.0 * lambda);
            Ok(RunSpec {
                name: format!("alpha{alpha:.2}"),
                scene: scene(file, spec.dir())?,
                keep,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    run_all(&format!("fig{}", spec.figure), &specs)
}

/// Unload states at the tip of a saw tooth (the next step has fewer bonded elements: the front
/// is critical) that are not in full contact: the numerical Griffith equilibria.
fn griffith_states(r: &FigureRun) -> impl Iterator<Item = usize> + '_ {
    let rec = &r.path.records;
    (0..rec.len().saturating_sub(1)).filter(move |&k| {
        r.path.phases[k] == Phase::Unload
            && !rec[k].full_contact
            && rec[k].n_bonded > 0
            && rec[k + 1].n_bonded < rec[k].n_bonded
    })
}

/// Figure 1: p̄/p*_1D against ψ = πa/λ with Eq. 2 overlaid, for several α.
pub fn fig1(ctx: &Ctx) -> Result<FigureSummary> {
    let spec = ctx.spec(1)?;
    let params: Params = spec.params()?;
    let runs = runs(&spec, &params, Keep::default())?;
    let mut table = Table::new(
        "# approach = psi = pi a/lambda (a = n_bonded dx/2) of a Griffith state (unload, tip of a saw tooth)\n\
         # force = mean pressure / p*_1D\n# mean_pressure = Eq. 2 at psi\n# area = 0\n# n_bonded = index of alpha in the spec",
    );
    let mut summary = FigureSummary::new(
        1,
        format!(
            "max |p̄ − Eq. 2|/p*_1D over Griffith states with πa/λ in [{}, {}]",
            params.compare[0], params.compare[1]
        ),
    );
    let mut chart = Chart {
        title: "1D waviness: mean pressure vs contact half-width".into(),
        x_label: "πa/λ".into(),
        y_label: "p̄ / p*_1D".into(),
        x_range: Some((0.0, PI / 2.0)),
        y_range: Some((-1.0, 1.1)),
        ..Chart::default()
    };
    for (s, (r, &alpha)) in runs.iter().zip(&params.alphas).enumerate() {
        let grid = r.problem.grid;
        let Some(Roughness::Waviness1d { h, lambda }) = r.scene.file.roughness else {
            bail!("figure 1 needs a 1D waviness");
        };
        let p_star = westergaard_p_star(r.problem.e_star, h, lambda);
        let (mut worst, mut count) = (0.0f64, 0);
        let mut pts = Vec::new();
        for k in griffith_states(r) {
            let rec = &r.path.records[k];
            let psi = PI * rec.n_bonded as f64 * grid.dx() / (2.0 * lambda);
            let p = rec.mean_pressure / p_star;
            let eq2 = johnson_1d_mean_pressure_ratio(alpha, psi);
            table.push(s, psi, p, eq2, 0.0);
            pts.push((psi, p));
            if (params.compare[0]..=params.compare[1]).contains(&psi) {
                worst = worst.max((p - eq2).abs());
                count += 1;
            }
        }
        summary.add(format!("alpha_{alpha}_max_dev"), worst);
        summary.add(format!("alpha_{alpha}_states"), count as f64);
        let curve = (1..400)
            .map(|i| i as f64 * PI / 800.0)
            .map(|psi| (psi, johnson_1d_mean_pressure_ratio(alpha, psi)))
            .collect();
        chart.series.push(Series::new(
            format!("Eq. 2, α = {alpha}"),
            curve,
            Style::Line,
            s,
        ));
        // At most ~150 markers per α (the table keeps every state).
        let every = pts.len().div_ceil(150).max(1);
        let pts = pts.into_iter().step_by(every).collect();
        chart.series.push(Series::new("", pts, Style::Points, s));
    }
    write_figure(
        ctx,
        &spec,
        &table,
        &summary,
        RunFiles::Engine(&runs),
        (800, 600),
        |root| draw_chart(root, &chart),
    )?;
    Ok(summary)
}

/// Figure 2: p̄/p*_2D against πa*/λ (a* = sqrt(A/π)) with Eq. 5 near full contact, and the
/// break-up of the connected contact at the detail α.
///
/// The pattern h[1 − cos(2πx/λ)cos(2πy/λ)] has two troughs per λ×λ cell, at (λ/2, 0) and
/// (0, λ/2), so near full contact there are two holes per cell: the radius of one is
/// b = sqrt((λ² − A)/(2π)), and Eq. 5's curve is at πa*/λ = sqrt(π − 2ψ_b²).
pub fn fig2(ctx: &Ctx) -> Result<FigureSummary> {
    let spec = ctx.spec(2)?;
    let params: Params = spec.params()?;
    let base = spec.scene()?;
    let Some(Roughness::Waviness2d { h, lambda }) = base.roughness else {
        bail!("figure 2 needs a 2D waviness");
    };
    let keep = Keep {
        break_up: true,
        last_contact: true,
        unload_every: Some(h / 10.0),
        ..Keep::default()
    };
    let runs = runs(&spec, &params, keep)?;
    let mut table = Table::new(
        "# approach = pi a*/lambda, a* = sqrt(A/pi), every unload step\n# force = mean pressure / p*_2D\n\
         # mean_pressure = Eq. 5 at psi_b where a hole exists (NaN otherwise)\n# area = psi_b = pi b/lambda, b = sqrt((lambda^2 - A)/(2 pi)) (two holes per cell)\n\
         # n_bonded = index of alpha in the spec",
    );
    let (lo, hi) = (params.compare[0], params.compare[1]);
    let mut summary = FigureSummary::new(
        2,
        format!("max |p̄ − Eq. 5|/p*_2D over Griffith states with ψ_b = πb/λ in [{lo}, {hi}]"),
    );
    let mut chart = Chart {
        title: "(A) 2D waviness: Griffith states (lines) and Eq. 5 (dashed)".into(),
        x_label: "πa*/λ".into(),
        y_label: "p̄ / p*_2D".into(),
        x_range: Some((0.0, 1.85)),
        y_range: Some((-1.0, 1.1)),
        ..Chart::default()
    };
    let cell = lambda * lambda;
    let x_of = |area: f64| PI * (area / PI).sqrt() / lambda;
    let psi_b_of = |area: f64| PI * ((cell - area).max(0.0) / (2.0 * PI)).sqrt() / lambda;
    let mut detail = None;
    for (s, (r, &alpha)) in runs.iter().zip(&params.alphas).enumerate() {
        let p_star = johnson_2d_p_star(r.problem.e_star, h, lambda);
        let mut pts = Vec::new();
        for (_, rec) in r.unload() {
            let (x, p, psi_b) = (
                x_of(rec.area),
                rec.mean_pressure / p_star,
                psi_b_of(rec.area),
            );
            let eq5 = if rec.area < cell {
                johnson_2d_near_full_ratio(alpha, psi_b)
            } else {
                f64::NAN
            };
            table.push(s, x, p, eq5, psi_b);
        }
        let (mut worst, mut count) = (0.0f64, 0);
        for k in griffith_states(r) {
            let rec = &r.path.records[k];
            let psi_b = psi_b_of(rec.area);
            pts.push((x_of(rec.area), rec.mean_pressure / p_star));
            if (lo..=hi).contains(&psi_b) {
                let dev = rec.mean_pressure / p_star - johnson_2d_near_full_ratio(alpha, psi_b);
                worst = worst.max(dev.abs());
                count += 1;
            }
        }
        summary.add(format!("alpha_{alpha}_max_dev"), worst);
        summary.add(format!("alpha_{alpha}_states"), count as f64);
        let curve = (1..=60)
            .map(|i| i as f64 * 0.01)
            .map(|pb| {
                (
                    (PI - 2.0 * pb * pb).sqrt(),
                    johnson_2d_near_full_ratio(alpha, pb),
                )
            })
            .collect();
        chart
            .series
            .push(Series::new(format!("α = {alpha}"), pts, Style::Line, s));
        chart.series.push(Series::new("", curve, Style::Dashed, s));
        if params.detail_alpha == Some(alpha) {
            detail = Some((r.clone(), p_star, s));
        }
    }
    let Some((r, p_star, color)) = detail else {
        bail!(
            "{}: detail_alpha must be one of alphas",
            spec.path.display()
        );
    };
    let (detail_chart, maps, shown) = break_up_detail(
        &r,
        params.detail_alpha.unwrap_or(0.0),
        (p_star, color),
        &x_of,
        &mut summary,
    );
    table.shown = shown;
    write_figure(
        ctx,
        &spec,
        &table,
        &summary,
        RunFiles::Engine(&runs),
        (1400, 900),
        |root| {
            let (top, bottom) = root.split_vertically(600);
            let (a, b) = top.split_horizontally(700);
            draw_chart(&a, &chart)?;
            draw_chart(&b, &detail_chart)?;
            draw_maps(&bottom, &maps, maps.len().max(1))
        },
    )?;
    Ok(summary)
}

/// Figure 2's detail panel at `alpha` (the run `r`, with its `p*_2D` and colour): the unload
/// curve with the break-up of the connected contact (the two kept unload steps around the
/// first 1 → >1 cluster transition) marked, and the contact configurations around it as maps
/// (with the steps shown); the break-up's numbers go to `summary`.
fn break_up_detail(
    r: &FigureRun,
    alpha: f64,
    (p_star, color): (f64, usize),
    x_of: &dyn Fn(f64) -> f64,
    summary: &mut FigureSummary,
) -> (Chart, Vec<Map>, Vec<(String, usize)>) {
    // The break-up: the two kept unload steps around the first 1 → >1 cluster transition.
    let periodic = true;
    let breaks: Vec<_> = r
        .path
        .snapshots
        .windows(2)
        .filter(|w| {
            w[1].step == w[0].step + 1
                && count_clusters(&w[0].bonded, periodic) == 1
                && count_clusters(&w[1].bonded, periodic) > 1
        })
        .map(|w| (w[0].step, w[1].step))
        .collect();
    let mut detail_chart = Chart {
        title: format!("(B) α = {}: connected (C) → separated (D)", alpha),
        x_label: "πa*/λ".into(),
        y_label: "p̄ / p*_2D".into(),
        x_range: Some((0.0, 1.85)),
        y_range: Some((-1.0, 1.1)),
        ..Chart::default()
    };
    let unload: Vec<(f64, f64)> = r
        .unload()
        .filter(|(_, rec)| rec.n_bonded > 0)
        .map(|(_, rec)| (x_of(rec.area), rec.mean_pressure / p_star))
        .collect();
    detail_chart
        .series
        .push(Series::new("unload", unload, Style::Line, color));
    let (mut maps, mut shown) = (Vec::new(), Vec::new());
    if let Some(&(c, d)) = breaks.first() {
        let pt = |k: usize| {
            let rec = &r.path.records[k];
            (x_of(rec.area), rec.mean_pressure / p_star)
        };
        detail_chart.series.push(Series::new(
            "C, D: break-up",
            vec![pt(c), pt(d)],
            Style::Points,
            7,
        ));
        // Holes of the connected state just before break-up (two per cell expected).
        let holes = r
            .snapshot(c)
            .map_or(0, |s| count_clusters(&s.bonded.mapv(|b| !b), periodic));
        summary.add("detail_holes_before_break_up", holes as f64);
        summary.add("detail_break_up_x", pt(c).0);
        summary.add("detail_break_up_jump", pt(d).1 - pt(c).1);
        // Configurations: first hole (A), halfway (B), C, D, last contact (E).
        let first_hole = r
            .path
            .snapshots
            .iter()
            .find(|s| s.bonded.iter().any(|b| !b));
        let mid = r.path.snapshots.iter().rev().find(|s| s.step < c);
        let last = r
            .path
            .snapshots
            .iter()
            .rev()
            .find(|s| s.bonded.iter().any(|&b| b));
        for (label, snap) in [
            ("A", first_hole),
            (
                "B",
                mid.filter(|m| Some(m.step) != first_hole.map(|f| f.step)),
            ),
            ("C", r.snapshot(c)),
            ("D", r.snapshot(d)),
            ("E (last contact)", last),
        ] {
            if let Some(snap) = snap {
                let rec = &r.path.records[snap.step];
                shown.push((r.name.clone(), snap.step));
                maps.push(Map::mask(
                    format!(
                        "{label}: πa*/λ = {:.2}, p̄/p* = {:.2}",
                        x_of(rec.area),
                        rec.mean_pressure / p_star
                    ),
                    &snap.bonded,
                ));
            }
        }
    } else {
        summary.add("detail_holes_before_break_up", 0.0);
    }
    (detail_chart, maps, shown)
}
