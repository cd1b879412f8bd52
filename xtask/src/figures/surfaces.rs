//! Figure 3: the two rough spheres of the paper as height maps: a sphere with 2D waviness
//! (Figure 4's scene) and a sphere with random roughness (Figure 7's scene), around the apex.

use anyhow::Result;
use serde::Deserialize;
use tack::Problem;
use tack::scene::{Geometry, SceneSchema};
use tack_analytics::{jkr_pull_off_approach, jkr_pull_off_radius};

use super::{Ctx, FigureSummary, RunFiles, Table, rough_sphere, wavy_sphere, write_figure};
use crate::plot::{Chart, Map, Series, Style, draw_chart, draw_maps};
use crate::spec::scene;

/// Figure 3's choice of surfaces, `[quick]`/`[full]` of `fig3.toml`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Fig3 {
    /// Johnson parameter of the wavy sphere (Figure 4's scene).
    wavy_alpha: f64,
    /// Hurst exponent, α* and seed of the random sphere (Figure 7's scene).
    hurst: f64,
    /// α* of the random sphere.
    alpha_star: f64,
    /// Seed of the random sphere.
    seed: u64,
    /// Half-width of the shown square, in units of the JKR pull-off radius a_c.
    extent: f64,
}

/// A surface shown in Figure 3.
struct Cut {
    /// Heights in the square |x|, |y| ≤ `extent`·a_c around the apex.
    map: ndarray::Array2<f64>,
    /// The centre line y = 0 as (x/a_c, f/|d_JKR|).
    line: Vec<(f64, f64)>,
    /// The problem the surface was built for.
    problem: Problem,
}

/// The [`Cut`] of `file`.
fn cut(ctx: &Ctx, file: SceneSchema, extent: f64) -> Result<Cut> {
    let p = Problem::from_scene(&scene(file.clone(), &ctx.specs)?)?;
    let radius = match file.geometry {
        Geometry::Sphere { radius } => radius,
        _ => anyhow::bail!("figure 3 shows spheres"),
    };
    let a_c = jkr_pull_off_radius(p.e_star, p.gamma, radius);
    let d = jkr_pull_off_approach(p.e_star, p.gamma, radius).abs();
    let (nx, ny) = p.grid.shape();
    let half = ((extent * a_c / p.grid.dx()).ceil() as usize)
        .min(nx / 2)
        .min(ny / 2);
    let (ci, cj) = (nx / 2, ny / 2);
    let block = p
        .surface
        .heights()
        .slice(ndarray::s![ci - half..=ci + half, cj - half..=cj + half])
        .to_owned();
    let line = (ci - half..=ci + half)
        .map(|i| (p.grid.x(i) / a_c, p.surface.heights()[[i, cj]] / d))
        .collect();
    Ok(Cut {
        map: block,
        line,
        problem: p,
    })
}

/// Figure 3: height maps of the wavy and the randomly rough sphere, and their centre lines.
pub fn fig3(ctx: &Ctx) -> Result<FigureSummary> {
    let spec = ctx.spec(3)?;
    let p: Fig3 = spec.params()?;
    let wavy = wavy_sphere::scene_for(ctx, p.wavy_alpha)?;
    let random = rough_sphere::scene_for(ctx, p.hurst, p.alpha_star, p.seed)?;
    let Cut {
        map: wmap,
        line: wline,
        problem: wp,
    } = cut(ctx, wavy.clone(), p.extent)?;
    let Cut {
        map: rmap,
        line: rline,
        problem: rp,
    } = cut(ctx, random.clone(), p.extent)?;
    let mut table = Table::new(
        "# approach = x/a_c along y = 0, force = f(x, 0)/|d_JKR| (surface height)\n\
         # mean_pressure = NaN, area = 0, n_bonded = 0 wavy sphere, 1 random sphere",
    );
    for (s, line) in [&wline, &rline].into_iter().enumerate() {
        for &(x, f) in line {
            table.push(s, x, f, f64::NAN, 0.0);
        }
    }
    let mut summary = FigureSummary::new(
        3,
        "surfaces: sphere + 2D waviness (α) and sphere + random roughness (α*)",
    );
    summary.add(
        "wavy_alpha",
        wp.references.johnson_alpha.unwrap_or(f64::NAN),
    );
    summary.add(
        "random_alpha_star",
        rp.references.alpha_star.unwrap_or(f64::NAN),
    );
    summary.add("random_first_touch", rp.first_touch);
    let chart = Chart {
        title: "(C) centre lines y = 0".into(),
        x_label: "x / a_c".into(),
        y_label: "f / |d_JKR|".into(),
        series: vec![
            Series::new(
                format!("sphere + waviness, α = {}", p.wavy_alpha),
                wline,
                Style::Line,
                0,
            ),
            Series::new(
                format!("sphere + random, H = {}, α* = {}", p.hurst, p.alpha_star),
                rline,
                Style::Line,
                1,
            ),
        ],
        ..Chart::default()
    };
    let maps = [
        Map::heights(
            format!("(A) sphere + 2D waviness, α = {}", p.wavy_alpha),
            &wmap,
        ),
        Map::heights(
            format!(
                "(B) sphere + random roughness, H = {}, α* = {}",
                p.hurst, p.alpha_star
            ),
            &rmap,
        ),
    ];
    write_figure(
        ctx,
        &spec,
        &table,
        &summary,
        RunFiles::Engine(&[]),
        (1500, 500),
        |root| {
            let (maps_area, right) = root.split_horizontally(1000);
            draw_maps(&maps_area, &maps, 2)?;
            draw_chart(&right, &chart)
        },
    )?;
    // After write_figure, which empties fig3/.
    let dir = ctx.out.join("fig3");
    std::fs::create_dir_all(&dir)?;
    for (name, file, prob) in [("wavy", &wavy, &wp), ("random", &random, &rp)] {
        let prov = tack_io::Provenance {
            scene: toml::to_string(file)?,
            seed: prob.seed,
            ..tack_io::Provenance::current(
                tack::provenance::GIT_REVISION,
                tack::provenance::now_rfc3339(),
            )
        };
        let path = dir.join(format!("{name}.h5"));
        tack_io::write_result(&path, &tack::summary::surface_file(prob, prov))?;
    }
    Ok(summary)
}
