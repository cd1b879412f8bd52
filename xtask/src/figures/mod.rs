//! The paper's Figures 1–8: each builds its runs from its spec, runs them, and writes
//! `figN.h5`, `figN.svg`, the runs' result files under `figN/` and a [`FigureSummary`]. Figures 1, 2
//! and 4 run through the engine (`figN/<run>.h5`); Figures 5 and 7 are tack sweeps whose point
//! files stay in `figN/sweep-<mode>/` (resumed by a rerun); Figures 6 and 8 read Figure 7's sweep
//! and copy the point files they show to `figN/<run>.h5`.
//!
//! `figN.h5` uses the tack-io layout for the figure's collected table, one entry per plotted
//! point: `/curve/approach` = abscissa, `/curve/force` = ordinate, `/curve/mean_pressure` =
//! the closed form at that abscissa (NaN where none), `/curve/area` = a spread (standard
//! deviation, or a second abscissa), `/curve/n_bonded` = series index; the other columns are
//! zero. What each column means for the figure is written into the root attribute `scene`
//! after the spec's TOML, and the summary numbers are `/summary` attributes.

mod periodic;
mod rough_sphere;
mod surfaces;
mod wavy_sphere;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{Context, Result};
use tack::heights::{COARSE_UNLOAD_STEP, LOAD_DEPTH, UNLOAD_STEP};
use tack::scene::{Geometry, SceneSchema};
use tack_analytics::jkr_approach_scale;

use crate::engine::{FigureRun, write_run};
use crate::plot::{Area, svg};
use crate::spec::FigureSpec;

/// Where a figure reads its spec and writes its outputs, and how many runs go at once.
pub struct Ctx {
    /// Directory of the figure specs (`data/figures`).
    pub specs: PathBuf,
    /// Output directory (`results`).
    pub out: PathBuf,
    /// Full mode (the paper's settings).
    pub full: bool,
    /// Worker threads of the figure sweeps (the engine runs on the current rayon pool).
    pub threads: usize,
}

impl Ctx {
    /// The spec of figure `n` in this mode.
    pub fn spec(&self, n: u8) -> Result<FigureSpec> {
        FigureSpec::load(&self.specs, n, self.full)
    }
}

/// One number of a figure's summary, with the paper's value where there is one.
#[derive(Debug, Clone, PartialEq)]
pub struct Item {
    /// Name (`snake_case`, used as an HDF5 attribute name).
    pub key: String,
    /// Measured value.
    pub value: f64,
    /// The paper's value, if it gives one.
    pub paper: Option<f64>,
}

/// The numbers a figure reports, printed with three significant digits.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FigureSummary {
    /// Figure number.
    pub figure: u8,
    /// One line on what was compared.
    pub compared: String,
    /// The numbers.
    pub items: Vec<Item>,
    /// Remarks printed after the numbers (e.g. sweep points that failed and were left out).
    pub notes: Vec<String>,
}

impl FigureSummary {
    /// An empty summary of figure `figure`.
    pub fn new(figure: u8, compared: impl Into<String>) -> Self {
        Self {
            figure,
            compared: compared.into(),
            items: Vec::new(),
            notes: Vec::new(),
        }
    }
    /// Appends a remark (printed after the numbers).
    pub fn note(&mut self, text: impl Into<String>) {
        self.notes.push(text.into());
    }
    /// Appends a number.
    pub fn add(&mut self, key: impl Into<String>, value: f64) {
        self.items.push(Item {
            key: key.into(),
            value,
            paper: None,
        });
    }
    /// Appends a number with the paper's value.
    pub fn add_vs(&mut self, key: impl Into<String>, value: f64, paper: f64) {
        self.items.push(Item {
            key: key.into(),
            value,
            paper: Some(paper),
        });
    }
    /// `key = value` lines (three significant digits), the form checked by the snapshot test.
    pub fn text(&self) -> String {
        let mut s = format!("fig{}: {}\n", self.figure, self.compared);
        for i in &self.items {
            let _ = write!(s, "{} = {}", i.key, sig3(i.value));
            if let Some(p) = i.paper {
                let _ = write!(s, " (paper {})", sig3(p));
            }
            s.push('\n');
        }
        for n in &self.notes {
            let _ = writeln!(s, "note: {n}");
        }
        s
    }
    /// A markdown table of the numbers.
    pub fn markdown(&self) -> String {
        let mut s = String::from("| quantity | measured | paper |\n|---|---|---|\n");
        for i in &self.items {
            let paper = i.paper.map_or("".into(), sig3);
            let _ = writeln!(s, "| `{}` | {} | {paper} |", i.key, sig3(i.value));
        }
        if !self.notes.is_empty() {
            s.push('\n');
            for n in &self.notes {
                let _ = writeln!(s, "- {n}");
            }
        }
        s
    }
}

/// `x` rounded to three significant digits and printed without noise (`0.0231`, `1.02e-5`).
pub fn sig3(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    if x.fract() == 0.0 && x.abs() < 1e6 {
        return format!("{x}");
    }
    let mag = x.abs().log10().floor();
    let unit = 10f64.powf(mag - 2.0);
    let r = (x / unit).round() * unit;
    let mag = r.abs().log10().floor();
    if (-3.0..4.0).contains(&mag) {
        format!("{r:.*}", (2.0 - mag).max(0.0) as usize)
    } else {
        format!("{r:.2e}")
    }
}

/// A figure's collected table (see the module documentation for the HDF5 columns).
#[derive(Debug, Clone, Default)]
pub struct Table {
    /// What the columns mean, one `# ...` line each.
    pub legend: String,
    /// Abscissa.
    pub x: Vec<f64>,
    /// Ordinate.
    pub y: Vec<f64>,
    /// Closed form at `x` (NaN where none).
    pub reference: Vec<f64>,
    /// Spread or second abscissa.
    pub spread: Vec<f64>,
    /// Series index.
    pub series: Vec<u64>,
    /// `(run name, step)` of fields shown in the figure, written to the run files besides the
    /// pull-off step and the last contact.
    pub shown: Vec<(String, usize)>,
}

impl Table {
    /// A table whose columns mean `legend`.
    pub fn new(legend: &str) -> Self {
        Self {
            legend: legend.into(),
            ..Self::default()
        }
    }
    /// Appends one point.
    pub fn push(&mut self, series: usize, x: f64, y: f64, reference: f64, spread: f64) {
        self.series.push(series as u64);
        self.x.push(x);
        self.y.push(y);
        self.reference.push(reference);
        self.spread.push(spread);
    }
}

/// The run files of a figure.
pub enum RunFiles<'a> {
    /// Engine runs: written to `figN/<name>.h5` (`figN/` is emptied first), with the fields of
    /// their pull-off step, last contact and the steps in `table.shown`.
    Engine(&'a [Arc<FigureRun>]),
    /// The runs are the point files of the figure's sweep in `figN/sweep-<mode>/`: nothing is
    /// written, and the result files an older layout left directly in `figN/` are removed.
    Sweep,
    /// Point files of another figure's sweep, copied to `figN/<name>.h5` (`figN/` is emptied
    /// first).
    Copies(Vec<(String, PathBuf)>),
}

/// Removes `dir` and everything in it, if it exists.
fn clear_dir(dir: &Path) -> Result<()> {
    if dir.is_dir() {
        std::fs::remove_dir_all(dir).with_context(|| format!("clearing {}", dir.display()))?;
    }
    Ok(())
}

/// Writes a figure's outputs: `figN.h5` (table + summary), `figN.svg` (drawn by `draw` on a
/// canvas of `size` pixels) and the run files under `figN/` (see [`RunFiles`]).
pub fn write_figure(
    ctx: &Ctx,
    spec: &FigureSpec,
    table: &Table,
    summary: &FigureSummary,
    runs: RunFiles,
    size: (u32, u32),
    draw: impl FnOnce(&Area) -> Result<()>,
) -> Result<()> {
    let n = spec.figure;
    std::fs::create_dir_all(&ctx.out)?;
    let dir = ctx.out.join(format!("fig{n}"));
    match runs {
        RunFiles::Engine(runs) => {
            // The run directory holds exactly this invocation's runs.
            clear_dir(&dir)?;
            for r in runs {
                let steps: Vec<usize> = table
                    .shown
                    .iter()
                    .filter(|(name, _)| *name == r.name)
                    .map(|&(_, k)| k)
                    .collect();
                write_run(&dir, r, &steps)?;
            }
        }
        RunFiles::Sweep => {
            // Keep the sweep directories (both modes); drop run files of the engine layout.
            for entry in std::fs::read_dir(&dir)
                .with_context(|| format!("listing {}", dir.display()))?
                .filter_map(Result::ok)
            {
                let path = entry.path();
                if path.is_file() && path.extension().is_some_and(|e| e == "h5") {
                    std::fs::remove_file(&path)
                        .with_context(|| format!("removing {}", path.display()))?;
                }
            }
        }
        RunFiles::Copies(files) => {
            clear_dir(&dir)?;
            std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
            for (name, from) in files {
                let to = dir.join(format!("{name}.h5"));
                std::fs::copy(&from, &to)
                    .with_context(|| format!("copying {} to {}", from.display(), to.display()))?;
            }
        }
    }
    let zeros = vec![0u64; table.x.len()];
    let mut extra = std::collections::BTreeMap::new();
    for i in &summary.items {
        extra.insert(i.key.clone(), i.value);
        if let Some(p) = i.paper {
            extra.insert(format!("{}_paper", i.key), p);
        }
    }
    let result = tack_io::RunResult {
        provenance: tack_io::Provenance {
            tack_version: tack::provenance::VERSION.into(),
            git_revision: tack::provenance::GIT_REVISION.into(),
            command_line: tack::provenance::command_line(),
            scene: format!(
                "{}\n# mode: {}\n# figN.h5 columns:\n{}{}",
                spec.text,
                if spec.full { "full" } else { "quick" },
                table.legend,
                summary
                    .notes
                    .iter()
                    .map(|n| format!("\n# note: {n}"))
                    .collect::<String>()
            ),
            created: tack::provenance::now_rfc3339(),
            seed: None,
        },
        curve: tack_io::Curve {
            law_columns: Vec::new(),
            time: None,
            approach: table.x.clone(),
            force: table.y.clone(),
            area: table.spread.clone(),
            n_bonded: table.series.clone(),
            n_clusters: zeros.clone(),
            iterations: zeros.clone(),
            active_set_iterations: zeros,
            converged: vec![true; table.x.len()],
            mean_pressure: Some(table.reference.clone()),
            full_contact: None,
        },
        surface: None,
        gamma: None,
        snapshots: Vec::new(),
        summary: tack_io::Summary {
            pull_off_force: f64::NAN,
            f_jkr: f64::NAN,
            pull_off_ratio: f64::NAN,
            johnson_alpha: None,
            alpha_star: None,
            extra,
            ..Default::default()
        },
    };
    let h5 = ctx.out.join(format!("fig{n}.h5"));
    tack_io::write_result(&h5, &result).with_context(|| format!("writing {}", h5.display()))?;
    svg(&ctx.out.join(format!("fig{n}.svg")), size, draw)
}

/// Where the REPORT says figure `n`'s runs are (relative to the output directory).
pub fn runs_location(n: u8, full: bool) -> String {
    let mode = if full { "full" } else { "quick" };
    match n {
        5 | 7 => format!(
            "runs in `fig{n}/sweep-{mode}/` (a `tack sweep` directory, one result file per \
             point in `points/`; `tack merge fig{n}/sweep-{mode} -o table.h5` gathers their \
             summaries)"
        ),
        6 | 8 => {
            format!("the runs shown copied to `fig{n}/` from Figure 7's sweep `fig7/sweep-{mode}/`")
        }
        _ => format!("runs in `fig{n}/`"),
    }
}

/// Runs figure `n` (1–8) and returns its summary.
pub fn run(n: u8, ctx: &Ctx) -> Result<FigureSummary> {
    match n {
        1 => periodic::fig1(ctx),
        2 => periodic::fig2(ctx),
        3 => surfaces::fig3(ctx),
        4 => wavy_sphere::fig4(ctx),
        5 => wavy_sphere::fig5(ctx),
        6 => rough_sphere::fig6(ctx),
        7 => rough_sphere::fig7(ctx),
        8 => rough_sphere::fig8(ctx),
        _ => anyhow::bail!("there is no figure {n} (figures are 1–8)"),
    }
}

/// Tensile retraction step of the full mode, in units of d_s = (Rγ²/E*²)^(1/3): half of tack's
/// default [`UNLOAD_STEP`] (0.02 d_s, which the quick mode uses), i.e. 0.01 d_s, so that the
/// paper-grade figures sample the pull-off twice as finely. `cargo xtask convergence` uses it too.
pub const FULL_UNLOAD_STEP: f64 = 0.5 * UNLOAD_STEP;

/// The approach path of a sphere pull-off in JKR units, for the sphere figures (4–8): the load
/// depth and coarse step of tack's default pull-off rule (`tack::pull_off_path`) and the
/// paper's fixed tensile step, [`UNLOAD_STEP`] (the rule's cap) in quick mode and
/// [`FULL_UNLOAD_STEP`] in full mode; the rule's own step, `min(0.02, 0.2·Δx/a_c)·d_s`, would
/// refine it on the figures' finer meshes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PullOff {
    /// Deepest approach below the highest point of the roughness (the `offset` of
    /// [`sphere_scene`]), in units of (Rγ²/E*²)^(1/3). With one load step (the figures'
    /// setting) every element with f ≤ d bonds, at least a disc of radius
    /// sqrt(2·load_depth)·(R²γ/E*)^(1/3): [`LOAD_DEPTH`] = 3 gives about 1.6 a_c
    /// (docs/theory.md §3.5).
    pub load_depth: f64,
    /// Number of load steps from the first touch.
    pub load_steps: usize,
    /// Retraction step, in units of (Rγ²/E*²)^(1/3).
    pub unload_step: f64,
    /// Retraction step while the force is still compressive (same units; `None`:
    /// `unload_step`): the pull-off lies in the tensile part, which uses `unload_step`
    /// (`protocol.coarse_unload_step` of the scenes).
    pub coarse_unload_step: Option<f64>,
}

impl PullOff {
    /// The sphere figures' path in quick or full mode: one load step to [`LOAD_DEPTH`] below
    /// the top of the roughness, retraction by [`COARSE_UNLOAD_STEP`] while the force is
    /// compressive, then by [`UNLOAD_STEP`] (quick) or [`FULL_UNLOAD_STEP`] (full), in d_s.
    pub fn for_mode(full: bool) -> Self {
        Self {
            load_depth: LOAD_DEPTH,
            load_steps: 1,
            unload_step: if full { FULL_UNLOAD_STEP } else { UNLOAD_STEP },
            coarse_unload_step: Some(COARSE_UNLOAD_STEP),
        }
    }
}

/// A sphere run's scene: `file` with the path `path` down to `load_depth` below the mean
/// surface `offset` (h for a waviness, 0 for zero-mean roughness), element size `dx` and `n`
/// elements per side; `n = None` sizes the free grid to hold the contact window of a roughness
/// of height range `range` (tack-cli crops the grid to that window).
pub fn sphere_scene(
    mut file: SceneSchema,
    offset: f64,
    range: f64,
    dx: f64,
    n: Option<usize>,
    path: &PullOff,
) -> Result<SceneSchema> {
    let Geometry::Sphere { radius } = file.geometry else {
        anyhow::bail!(
            "a sphere figure needs {} = \"sphere\"",
            tack_fields::GEOMETRY_SHAPE
        );
    };
    let (e, g) = (file.material.e_star, file.material.gamma);
    let ds = jkr_approach_scale(e, g, radius);
    let d_max = offset + path.load_depth * ds;
    let n = n.unwrap_or_else(|| {
        // contact_window: f ≤ d_max + range + sqrt(2πγℓ/E*), ℓ the window's half-diagonal.
        let level = d_max + range;
        let ell = (2.0 * radius * level).sqrt() * std::f64::consts::SQRT_2;
        let reach = tack_solver::adhesive_reach(e, g, ell);
        2 * ((2.0 * radius * (level + reach)).sqrt() / dx).ceil() as usize + 11
    });
    file.grid.n = Some(n);
    (file.grid.nx, file.grid.ny, file.grid.length) = (None, None, None);
    file.grid.dx = Some(dx);
    let p = &mut file.protocol;
    p.start = None;
    p.max_approach = Some(d_max);
    p.load_step = Some((d_max + range) / path.load_steps.max(1) as f64);
    p.unload_step = Some(path.unload_step * ds);
    p.coarse_unload_step = path.coarse_unload_step.map(|c| c * ds);
    p.retract_to = None;
    Ok(file)
}

/// The smooth sphere's JKR force–approach curve normalised by |F_JKR| and |d_JKR| (Eq. 7, 8),
/// from the jump-off point (â³ = π/8) up to `x_max`, in steps of 0.005 in â
/// ([`tack_analytics::jkr_curve_normalised`]).
pub fn jkr_curve(x_max: f64) -> Vec<(f64, f64)> {
    tack_analytics::jkr_curve_normalised(x_max, 0.005)
}

/// Crops maps to the common bounding box of their non-zero cells, grown by `pad` cells (maps of
/// one row of contact configurations share one frame).
pub fn crop_maps(maps: Vec<crate::plot::Map>, pad: usize) -> Vec<crate::plot::Map> {
    let (mut i0, mut i1, mut j0, mut j1) = (usize::MAX, 0, usize::MAX, 0);
    for m in &maps {
        for ((i, j), &v) in m.values.indexed_iter() {
            if v != 0.0 {
                (i0, i1, j0, j1) = (i0.min(i), i1.max(i + 1), j0.min(j), j1.max(j + 1));
            }
        }
    }
    if i1 == 0 {
        return maps;
    }
    maps.into_iter()
        .map(|mut m| {
            let (nx, ny) = m.values.dim();
            let (a0, a1) = (i0.saturating_sub(pad), (i1 + pad).min(nx));
            let (b0, b1) = (j0.saturating_sub(pad), (j1 + pad).min(ny));
            m.values = m.values.slice(ndarray::s![a0..a1, b0..b1]).to_owned();
            m
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use tack::geometry::{Boundary, Grid, Sphere, Surface};
    use tack::heights::{PullOffSpec, pull_off_scene};

    /// The quick mode's path is tack's default pull-off path (`tack::heights`) where that path
    /// takes its largest tensile step (a_c/Δx ≤ 10, as at dx = 0.01R here): on a smooth sphere,
    /// `sphere_scene` loads to the same depth and retracts by the same steps as
    /// `pull_off_scene`; the full mode differs only in its tensile step, half as large.
    #[test]
    fn the_figure_path_is_tacks_pull_off_rule() {
        let spec = crate::spec::FigureSpec::load(&crate::reproduce::default_specs(), 4, false)
            .expect("fig4.toml");
        let mut file = spec.scene().expect("fig4's scene");
        file.roughness = None;
        let Geometry::Sphere { radius } = file.geometry else {
            panic!("fig4 is a sphere")
        };
        let (e, g) = (file.material.e_star, file.material.gamma);
        let (n, dx) = (41, 0.01 * radius);
        let protocol = |full: bool| {
            sphere_scene(
                file.clone(),
                0.0,
                0.0,
                dx,
                Some(n),
                &PullOff::for_mode(full),
            )
            .expect("sphere scene")
            .protocol
        };
        let (quick, full) = (protocol(false), protocol(true));
        let grid = Grid::square(n, dx, Boundary::Free).expect("grid");
        let heights =
            Surface::from_shape(grid, &Sphere::new(radius).expect("sphere")).into_heights();
        let plan = pull_off_scene(
            &heights,
            &PullOffSpec {
                radius: Some(radius),
                ..PullOffSpec::new(dx, e, g)
            },
        )
        .expect("tack's pull-off scene");
        // The builder completes the plan's path by the default rule.
        let lib = tack::heights::problem(&plan.scene, &plan.body(&heights))
            .expect("tack's pull-off problem")
            .path;
        assert_eq!(quick.unload_step, Some(lib.unload_step));
        assert_eq!(quick.coarse_unload_step, lib.coarse_unload_step);
        // The library loads from the fitted apex (0 to rounding for this exact paraboloid).
        let d_s = jkr_approach_scale(e, g, radius);
        let (q, l) = (quick.max_approach.unwrap(), lib.max_approach);
        assert!((q - l).abs() < 1e-9 * d_s, "{q} vs {l}");
        assert_eq!(full.max_approach, quick.max_approach);
        assert_eq!(full.coarse_unload_step, quick.coarse_unload_step);
        let (tensile_full, tensile_quick) = (full.unload_step.unwrap(), quick.unload_step.unwrap());
        assert!((tensile_full / tensile_quick - 0.5).abs() < 1e-15);
    }
}
