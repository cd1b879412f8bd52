//! `tack plot`: the force–approach curve of a result file (load and unload branches, the
//! pull-off point, the JKR curve for spheres) and, when stored, contact snapshots as small
//! heat maps of the bonded mask.
//!
//! Axes are normalised by |F_JKR| and |d_JKR| when the file's summary has a finite, non-zero
//! `f_jkr` and a `d_jkr` (spheres); otherwise they are in the scene's units. The force axis
//! covers the tensile part: a compressive peak more than [`CLIP_RATIO`] times the pull-off's
//! |F| is cut at [`CLIP_AT`] times it (marked off scale), so the pull-off stays visible. SVG and
//! PNG (the default `png` cargo feature) draw text with the bundled Noto Sans (crate
//! `notosans`, SIL OFL 1.1): no system font is needed.

use std::path::Path;

use anyhow::{anyhow, bail};
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use tack_io::RunResult;

/// Pixel size of the figure without snapshots.
pub const SIZE: (u32, u32) = (900, 600);
/// Height added for the row of snapshot panels.
pub const SNAPSHOT_ROW: u32 = 240;
/// At most this many snapshots are drawn (evenly chosen among the stored ones).
pub const MAX_PANELS: usize = 6;
/// Heat-map cells per panel side at most (masks are block-averaged down to this).
pub const MAX_CELLS: usize = 100;
/// A compressive peak above this many times the pull-off's |F| is cut from the force axis.
pub const CLIP_RATIO: f64 = 10.0;
/// Where the force axis is cut then, in multiples of the pull-off's |F|.
pub const CLIP_AT: f64 = 5.0;
/// Whether this `tack` writes PNG (the `png` cargo feature, on by default).
pub const PNG_BUILT: bool = cfg!(feature = "png");

/// Output format, from the file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Scalable vector graphics.
    Svg,
    /// Portable network graphics (cargo feature `png`, on by default).
    Png,
}

impl Format {
    /// The format of `path` by its extension (`.svg` or `.png`, any case).
    pub fn of(path: &Path) -> anyhow::Result<Self> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("svg") => Ok(Self::Svg),
            Some("png") => Ok(Self::Png),
            _ => bail!(
                "{}: unknown figure format: the output name must end in .svg or .png",
                path.display()
            ),
        }
    }
}

/// What the figure shows, derived from a result file.
struct Figure<'a> {
    result: &'a RunResult,
    /// Force scale |F_JKR| (1 when not normalised).
    f_scale: f64,
    /// Approach scale |d_JKR| (1 when not normalised).
    d_scale: f64,
    /// Normalised by the JKR scales.
    normalised: bool,
    /// Plot the mean pressure over p* (waviness) instead of the force.
    p_star: Option<f64>,
}

impl<'a> Figure<'a> {
    fn new(result: &'a RunResult) -> Self {
        let f_jkr = result.summary.f_jkr;
        let d_jkr = result.summary.extra.get("d_jkr").copied();
        let p_star = result
            .summary
            .extra
            .get("p_star")
            .copied()
            .filter(|p| p.is_finite() && *p > 0.0 && result.curve.mean_pressure.is_some());
        match d_jkr {
            Some(d) if f_jkr.is_finite() && f_jkr != 0.0 && d.is_finite() && d != 0.0 => Self {
                result,
                f_scale: f_jkr.abs(),
                d_scale: d.abs(),
                normalised: true,
                p_star: None,
            },
            _ => Self {
                result,
                f_scale: 1.0,
                d_scale: 1.0,
                normalised: false,
                p_star,
            },
        }
    }
}

/// Reads `input` and writes the figure to `output` (format from its extension), through a
/// temporary file renamed on success. Errors name `output`, never the temporary.
pub fn plot_file(input: &Path, output: &Path) -> anyhow::Result<()> {
    let format = Format::of(output)?;
    if format == Format::Png && !PNG_BUILT {
        return Err(png_unavailable(output));
    }
    // Before reading: an existing FIFO or device under the output name is never replaced.
    tack::engine::check_output_path(output)?;
    let result = tack_io::read_result(input)?;
    if result.curve.is_empty() {
        bail!(
            "{}: the result has no force–approach curve (a surface-only file from `tack surface`?)",
            input.display()
        );
    }
    register_font()?;
    tack_io::write_atomically(output, |tmp| {
        render(&result, tmp, format).map_err(|e| anyhow!("{}: {e:#}", output.display()))
    })
}

/// The error of a PNG figure asked of a `tack` built without the `png` feature.
fn png_unavailable(output: &Path) -> anyhow::Error {
    anyhow!(
        "{}: PNG output is not built into this tack (it was built with `--no-default-features`, \
         without tack-cli's `png` feature); rebuild it with the default features (`cargo install \
         --path crates/tack-cli`) or write an .svg figure (`-o {}`)",
        output.display(),
        output.with_extension("svg").display()
    )
}

fn figure_size(result: &RunResult) -> (u32, u32) {
    if result.snapshots.is_empty() {
        SIZE
    } else {
        (SIZE.0, SIZE.1 + SNAPSHOT_ROW)
    }
}

fn render(result: &RunResult, path: &Path, format: Format) -> anyhow::Result<()> {
    let size = figure_size(result);
    match format {
        Format::Svg => {
            let root = SVGBackend::new(path, size).into_drawing_area();
            draw(root, &Figure::new(result))
        }
        Format::Png => render_png(result, path, size),
    }
}

#[cfg(feature = "png")]
fn render_png(result: &RunResult, path: &Path, size: (u32, u32)) -> anyhow::Result<()> {
    let root = BitMapBackend::new(path, size).into_drawing_area();
    draw(root, &Figure::new(result))
}

#[cfg(not(feature = "png"))]
fn render_png(_result: &RunResult, path: &Path, _size: (u32, u32)) -> anyhow::Result<()> {
    Err(png_unavailable(path))
}

/// Registers the bundled Noto Sans Regular (crate `notosans`, SIL OFL 1.1) as plotters'
/// "sans-serif", once per process: plotters' `ab_glyph` feature lays out and draws every text
/// with a registered font, in SVG and PNG alike.
pub fn register_font() -> anyhow::Result<()> {
    use std::sync::OnceLock;
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = REGISTERED.get_or_init(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, notosans::REGULAR_TTF)
            .is_ok()
    });
    if *ok {
        Ok(())
    } else {
        bail!("the bundled font (Noto Sans, crate notosans) is not a usable TrueType font")
    }
}

fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, fig: &Figure) -> anyhow::Result<()>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("drawing the figure: {e}");
    root.fill(&WHITE).map_err(err)?;
    let (curve_area, snapshot_area) = if fig.result.snapshots.is_empty() {
        (root.clone(), None)
    } else {
        let (top, bottom) = root.split_vertically(SIZE.1);
        (top, Some(bottom))
    };
    draw_curve(&curve_area, fig).map_err(err)?;
    if let Some(area) = snapshot_area {
        draw_snapshots(&area, fig).map_err(err)?;
    }
    root.present().map_err(err)?;
    Ok(())
}

fn bounds(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return (-1.0, 1.0);
    }
    let pad = ((hi - lo) * 0.05)
        .max(hi.abs().max(lo.abs()) * 1e-3)
        .max(1e-300);
    (lo - pad, hi + pad)
}

/// The plotted curve: both axes scaled, the branches split at the deepest approach, the
/// reference curves, the axis ranges and the cut of the force axis.
struct Plotted {
    d: Vec<f64>,
    f: Vec<f64>,
    /// The load branch runs up to the deepest approach; the rest is the unload branch.
    turn: usize,
    jkr: Vec<(f64, f64)>,
    maugis: Vec<(f64, f64)>,
    x: (f64, f64),
    y: (f64, f64),
    /// The force axis is cut here (a compressive peak far above the pull-off); the peak.
    cut: Option<(f64, f64)>,
}

impl Plotted {
    fn new(fig: &Figure) -> Self {
        let c = &fig.result.curve;
        let d: Vec<f64> = c.approach.iter().map(|v| v / fig.d_scale).collect();
        let f: Vec<f64> = match (fig.p_star, &c.mean_pressure) {
            (Some(p_star), Some(p)) => p.iter().map(|v| v / p_star).collect(),
            _ => c.force.iter().map(|v| v / fig.f_scale).collect(),
        };
        let turn = d
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(b.1))
            .map_or(0, |(i, _)| i);
        let d_max = d.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let jkr = if fig.normalised {
            jkr_curve(&d)
        } else {
            Vec::new()
        };
        // A Dugdale sphere: Maugis' whole equilibrium curve at its λ, dashed.
        let maugis = match fig.result.summary.extra.get("maugis_lambda") {
            Some(&lambda) if fig.normalised && lambda.is_finite() && lambda > 0.0 => {
                maugis_curve(lambda, d_max)
            }
            _ => Vec::new(),
        };
        let (lo, hi) = finite_range(f.iter().copied());
        let cut = (lo < 0.0 && hi > -CLIP_RATIO * lo).then(|| (-CLIP_AT * lo, hi));
        let top = cut.map_or(1.05 * hi.max(1.0), |(top, _)| top);
        // What shows: the points below the cut and where the branches cross it.
        let shown: Vec<(f64, f64)> = clip_above(
            &d.iter().copied().zip(f.iter().copied()).collect::<Vec<_>>(),
            top,
        )
        .into_iter()
        .flatten()
        .collect();
        let x = bounds(shown.iter().map(|p| p.0));
        let in_x = |p: &&(f64, f64)| (x.0..=x.1).contains(&p.0);
        let y = bounds(
            shown
                .iter()
                .map(|p| p.1)
                .chain(cut.map(|c| c.0))
                .chain(jkr.iter().filter(in_x).map(|p| p.1).filter(|&y| y <= top)),
        );
        Self {
            d,
            f,
            turn,
            jkr,
            maugis,
            x,
            y,
            cut,
        }
    }

    /// The (d, F) points of steps `range`.
    fn points(&self, range: std::ops::Range<usize>) -> Vec<(f64, f64)> {
        range.map(|i| (self.d[i], self.f[i])).collect()
    }

    fn visible(&self, p: (f64, f64)) -> bool {
        (self.x.0..=self.x.1).contains(&p.0) && (self.y.0..=self.y.1).contains(&p.1)
    }
}

/// The least and greatest finite value (±1 when there is none).
fn finite_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if lo.is_finite() {
        (lo, hi)
    } else {
        (-1.0, 1.0)
    }
}

/// The runs of a polyline below `top`, each ending (or starting) where it crosses `top`.
fn clip_above(points: &[(f64, f64)], top: f64) -> Vec<Vec<(f64, f64)>> {
    let mut runs = Vec::new();
    let mut run = Vec::new();
    for (k, &(x, y)) in points.iter().enumerate() {
        if let Some(&(px, py)) = k.checked_sub(1).map(|j| &points[j])
            && (py <= top) != (y <= top)
        {
            let t = (top - py) / (y - py);
            run.push((px + t * (x - px), top));
            if y > top {
                runs.push(std::mem::take(&mut run));
            }
        }
        if y <= top {
            run.push((x, y));
        }
    }
    if !run.is_empty() {
        runs.push(run);
    }
    runs
}

type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;
type Drawn<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// The title: the pull-off against its closed form, or the least mean pressure.
fn title(fig: &Figure, plotted: &Plotted) -> String {
    let s = &fig.result.summary;
    match s.pull_off_ratio {
        r if r.is_finite() => format!("force–approach (F_pull-off / F_JKR = {r:.3})"),
        _ if s.extra.contains_key("f_kendall") => format!(
            "force–approach (F_pull-off / F_Kendall = {:.3})",
            s.pull_off_force / s.extra["f_kendall"]
        ),
        _ if fig.p_star.is_some() => {
            let y_min = plotted.f.iter().copied().fold(f64::INFINITY, f64::min);
            format!("mean pressure–approach (minimum p / p* = {y_min:.4})")
        }
        _ => format!(
            "force–approach (pull-off force {})",
            crate::report::rounded(s.pull_off_force)
        ),
    }
}

fn draw_curve<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, fig: &Figure) -> Drawn<DB> {
    let plotted = Plotted::new(fig);
    let ((x0, x1), (y0, y1)) = (plotted.x, plotted.y);
    let (xl, yl) = if fig.normalised {
        ("approach d / |d_JKR|", "force F / |F_JKR|")
    } else if fig.p_star.is_some() {
        ("approach d", "mean pressure p / p*")
    } else {
        ("approach d", "force F (compressive > 0)")
    };
    let mut chart = ChartBuilder::on(area)
        .caption(title(fig, &plotted), ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc(xl)
        .y_desc(yl)
        .x_label_formatter(&tick_format(x0, x1))
        .y_label_formatter(&tick_format(y0, y1))
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 16))
        .draw()?;
    chart.draw_series(LineSeries::new(
        [(x0, 0.0), (x1, 0.0)],
        BLACK.mix(0.3).stroke_width(1),
    ))?;
    draw_references(&mut chart, fig, &plotted)?;
    draw_branches(&mut chart, &plotted)?;
    draw_markers(&mut chart, fig, &plotted)?;
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .label_font(("sans-serif", 14))
        .position(SeriesLabelPosition::UpperLeft)
        .draw()?;
    Ok(())
}

/// The closed-form curves: JKR (solid grey) and, for Dugdale spheres, Maugis (dashed).
fn draw_references<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    fig: &Figure,
    plotted: &Plotted,
) -> Drawn<DB> {
    let inside = |p: &(f64, f64)| plotted.visible(*p);
    if !plotted.jkr.is_empty() {
        let grey = RGBColor(120, 120, 120);
        chart
            .draw_series(LineSeries::new(
                plotted.jkr.iter().copied().filter(inside),
                grey.stroke_width(2),
            ))?
            .label("JKR (smooth sphere)")
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], grey.stroke_width(2)));
    }
    if !plotted.maugis.is_empty() {
        let lambda = fig.result.summary.extra["maugis_lambda"];
        let purple = RGBColor(148, 103, 189);
        chart
            .draw_series(DashedLineSeries::new(
                plotted.maugis.iter().copied().filter(inside),
                6,
                4,
                purple.stroke_width(2),
            ))?
            .label(format!("Maugis–Dugdale λ = {} (equilibria)", short(lambda)))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], purple.stroke_width(2)));
    }
    Ok(())
}

/// The load and unload branches, cut at the top of the force axis, and where they leave it.
fn draw_branches<DB: DrawingBackend>(chart: &mut Chart<'_, DB>, plotted: &Plotted) -> Drawn<DB> {
    let top = plotted.cut.map_or(f64::INFINITY, |c| c.0);
    let n = plotted.d.len();
    let blue = RGBColor(31, 119, 180);
    let red = RGBColor(214, 39, 40);
    for (range, color, label) in [
        (0..plotted.turn + 1, blue, "load"),
        (plotted.turn..n, red, "unload"),
    ] {
        let runs = clip_above(&plotted.points(range), top);
        for (k, run) in runs.into_iter().enumerate() {
            // A branch of one step (a load in one step) is a dot, not an invisible line.
            let dot = (run.len() == 1).then(|| Circle::new(run[0], 3, color.filled()));
            chart.draw_series(dot)?;
            let series = chart.draw_series(LineSeries::new(run, color.stroke_width(2)))?;
            if k == 0 {
                series.label(label).legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 20, y)], color.stroke_width(2))
                });
            }
        }
    }
    if let Some((top, peak)) = plotted.cut {
        // Where the curve leaves the axis upwards or comes back into it.
        let exits: Vec<(f64, f64)> = clip_above(&plotted.points(0..n), top)
            .iter()
            .flat_map(|run| [run.first().copied(), run.last().copied()])
            .flatten()
            .filter(|p| p.1 == top)
            .collect();
        let grey = RGBColor(90, 90, 90);
        chart
            .draw_series(
                exits
                    .into_iter()
                    .map(move |p| TriangleMarker::new(p, 6, grey.filled())),
            )?
            .label(format!(
                "off scale above {} (peak {})",
                short(top),
                short(peak)
            ))
            .legend(move |(x, y)| TriangleMarker::new((x + 10, y), 5, grey.filled()));
    }
    Ok(())
}

/// The pull-off point, the jumps of the cycle and the snapshots' steps.
fn draw_markers<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    fig: &Figure,
    plotted: &Plotted,
) -> Drawn<DB> {
    let (d, f) = (&plotted.d, &plotted.f);
    if let Some((i, _)) = f.iter().enumerate().min_by(|a, b| a.1.total_cmp(b.1)) {
        chart
            .draw_series(std::iter::once(Circle::new(
                (d[i], f[i]),
                5,
                BLACK.filled(),
            )))?
            .label("pull-off (minimum force)")
            .legend(|(x, y)| Circle::new((x + 10, y), 4, BLACK.filled()));
    }
    // The jumps of the cycle (tack_solver::cycle), where the result has them.
    let extra = &fig.result.summary.extra;
    let jumps: Vec<(f64, f64)> = [
        ("jump_in_approach", "jump_in_force"),
        ("jump_out_approach", "jump_out_force"),
    ]
    .iter()
    .filter_map(|(a, f)| Some((extra.get(*a)? / fig.d_scale, extra.get(*f)? / fig.f_scale)))
    .filter(|p| fig.p_star.is_none() && plotted.visible(*p))
    .collect();
    if !jumps.is_empty() {
        let orange = RGBColor(255, 127, 14);
        chart
            .draw_series(
                jumps
                    .into_iter()
                    .map(move |p| Cross::new(p, 7, orange.stroke_width(3))),
            )?
            .label("jump in / out")
            .legend(move |(x, y)| Cross::new((x + 10, y), 5, orange.stroke_width(3)));
    }
    let snaps: Vec<(f64, f64)> = chosen_snapshots(fig.result)
        .iter()
        .filter(|s| s.step < d.len())
        .map(|s| (d[s.step], f[s.step]))
        .filter(|p| plotted.visible(*p))
        .collect();
    if !snaps.is_empty() {
        let green = RGBColor(44, 160, 44);
        chart
            .draw_series(
                snaps
                    .into_iter()
                    .map(move |p| TriangleMarker::new(p, 6, green.filled())),
            )?
            .label("snapshots (below)")
            .legend(move |(x, y)| TriangleMarker::new((x + 10, y), 5, green.filled()));
    }
    Ok(())
}

/// Three significant digits.
fn short(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let mag = x.abs().log10().floor();
    if (-3.0..4.0).contains(&mag) {
        let decimals = (2.0 - mag).max(0.0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.2e}")
    }
}

/// Tick labels with as many decimals as the axis range needs; scientific notation for very
/// small or large ranges.
fn tick_format(lo: f64, hi: f64) -> impl Fn(&f64) -> String {
    let range = (hi - lo).abs().max(lo.abs().max(hi.abs()) * 1e-12);
    let exponent = (range / 10.0).log10().floor();
    move |&v: &f64| {
        if v == 0.0 || v.abs() < range * 1e-9 {
            "0".to_owned()
        } else if !(-4.0..5.0).contains(&exponent) {
            format!("{v:.1e}")
        } else {
            let decimals = (-exponent).max(0.0) as usize;
            format!("{v:.decimals$}")
        }
    }
}

/// The JKR force–approach curve in normalised units (F/|F_JKR|, d/|d_JKR|), from the jump-off
/// point â³ = π/8 up to the deepest approach of the data, in steps of 0.01 in â
/// ([`tack::analytics::jkr_curve_normalised`]).
fn jkr_curve(d: &[f64]) -> Vec<(f64, f64)> {
    let d_max = d.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    tack::analytics::jkr_curve_normalised(d_max, 0.01)
}

/// Maugis' (1992) equilibrium curve at `lambda` in the units of [`jkr_curve`] (F/|F_JKR|,
/// d/|d_JKR|), unstable parts included: the separated branch from C = 0 to its junction, then
/// the contact branch by m from 10⁴ down towards 1, up to the first point beyond `d_max`.
/// With P̄ = F/(πγR) and Δ̄ = d/D, D = (π²γ²R/K²)^(1/3), K = 4E*/3: F/|F_JKR| = P̄/1.5 and
/// d/|d_JKR| = Δ̄·D/|d_JKR|.
fn maugis_curve(lambda: f64, d_max: f64) -> Vec<(f64, f64)> {
    use tack::analytics::{maugis_point, maugis_separated_point};
    // D and |d_JKR| for R = E* = γ = 1 (the ratio is the same for every body).
    let d_maugis = (9.0 * std::f64::consts::PI.powi(2) / 16.0).cbrt();
    let x_scale = d_maugis / tack::analytics::jkr_pull_off_approach(1.0, 1.0, 1.0).abs();
    let to_plot = |p: tack::analytics::MaugisPoint| (p.approach_hat * x_scale, p.force_hat / 1.5);
    let c0 = maugis_point(lambda, 1e4).c_hat;
    let mut out: Vec<(f64, f64)> = (0..=100)
        .map(|k| to_plot(maugis_separated_point(lambda, c0 * k as f64 / 100.0)))
        .collect();
    // m = 1 + 10^t for t from 4 down to −8.
    for k in 0..=1200 {
        let m = 1.0 + 10f64.powf(4.0 - k as f64 / 100.0);
        let p = to_plot(maugis_point(lambda, m));
        out.push(p);
        if p.0 > d_max {
            break;
        }
    }
    out
}

/// At most [`MAX_PANELS`] snapshots, evenly spread over the stored ones.
fn chosen_snapshots(result: &RunResult) -> Vec<&tack_io::Snapshot> {
    let all = &result.snapshots;
    if all.len() <= MAX_PANELS {
        return all.iter().collect();
    }
    (0..MAX_PANELS)
        .map(|k| &all[k * (all.len() - 1) / (MAX_PANELS - 1)])
        .collect()
}

/// Block-averages a bonded mask to at most [`MAX_CELLS`] cells per side: fraction bonded.
fn downsample(mask: &ndarray::Array2<bool>) -> ndarray::Array2<f64> {
    let (nx, ny) = mask.dim();
    let (bx, by) = (nx.div_ceil(MAX_CELLS).max(1), ny.div_ceil(MAX_CELLS).max(1));
    let (cx, cy) = (nx.div_ceil(bx), ny.div_ceil(by));
    let mut out = ndarray::Array2::<f64>::zeros((cx, cy));
    let mut count = ndarray::Array2::<f64>::zeros((cx, cy));
    for ((i, j), &b) in mask.indexed_iter() {
        out[[i / bx, j / by]] += f64::from(u8::from(b));
        count[[i / bx, j / by]] += 1.0;
    }
    out / count
}

fn draw_snapshots<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    fig: &Figure,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let snaps = chosen_snapshots(fig.result);
    let panels = area.split_evenly((1, snaps.len().max(1)));
    for (panel, snap) in panels.iter().zip(snaps) {
        let cells = downsample(&snap.bonded);
        let (cx, cy) = cells.dim();
        if cx == 0 || cy == 0 {
            continue;
        }
        let title = format!("#{}: d = {}", snap.step, short(snap.approach / fig.d_scale));
        // Keep the cells square: shrink the panel to the mask's aspect ratio, centred.
        let (w, h) = panel.dim_in_pixel();
        let (w, h) = (f64::from(w) - 16.0, f64::from(h) - 36.0);
        // Strips (ny = 1) are stretched to at least 1/8 of their width to stay visible.
        let cy_shown = (cy as f64).max(cx as f64 / 8.0);
        let scale = (w / cx as f64).min(h / cy_shown).max(0.0);
        let (pw, ph) = (scale * cx as f64, scale * cy_shown);
        let (mx, my) = (
            ((w - pw) / 2.0).max(0.0) as i32,
            ((h - ph) / 2.0).max(0.0) as i32,
        );
        let panel = panel.margin(my, my, mx, mx);
        let mut chart = ChartBuilder::on(&panel)
            .caption(title, ("sans-serif", 13))
            .margin(8)
            .build_cartesian_2d(0..cx, 0..cy)?;
        chart.plotting_area().fill(&RGBColor(245, 245, 245))?;
        chart.draw_series(cells.indexed_iter().filter(|(_, v)| **v > 0.0).map(
            |((i, j), &v)| {
                let shade = (235.0 * (1.0 - v)) as u8;
                Rectangle::new(
                    [(i, j), (i + 1, j + 1)],
                    RGBColor(shade, shade, 255 - (v * 100.0) as u8).filled(),
                )
            },
        ))?;
        chart.draw_series(std::iter::once(Rectangle::new(
            [(0, 0), (cx, cy)],
            BLACK.mix(0.5).stroke_width(1),
        )))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn format_from_extension() {
        assert_eq!(Format::of(Path::new("a/b.SVG")).unwrap(), Format::Svg);
        assert_eq!(Format::of(Path::new("b.png")).unwrap(), Format::Png);
        assert!(Format::of(Path::new("b.pdf")).is_err());
        assert!(Format::of(Path::new("b")).is_err());
    }

    #[test]
    fn clipping_keeps_the_runs_below_the_top_with_their_crossings() {
        let line = [(0.0, 0.0), (1.0, 2.0), (2.0, 0.0), (3.0, -1.0), (4.0, 3.0)];
        let runs = clip_above(&line, 1.0);
        assert_eq!(
            runs,
            vec![
                vec![(0.0, 0.0), (0.5, 1.0)],
                vec![(1.5, 1.0), (2.0, 0.0), (3.0, -1.0), (3.5, 1.0)],
            ]
        );
        assert_eq!(clip_above(&line, 5.0), vec![line.to_vec()]);
        assert!(clip_above(&[(0.0, 2.0)], 1.0).is_empty());
    }

    fn result_with_forces(force: Vec<f64>) -> RunResult {
        let n = force.len();
        RunResult {
            provenance: tack_io::Provenance::current("test", "2026-01-01T00:00:00Z"),
            curve: tack_io::Curve {
                approach: (0..n).map(|i| (n - i) as f64).collect(),
                force,
                ..tack_io::Curve::default()
            },
            surface: None,
            gamma: None,
            snapshots: Vec::new(),
            summary: tack_io::Summary {
                f_jkr: f64::NAN,
                ..tack_io::Summary::default()
            },
        }
    }

    #[test]
    fn a_compressive_peak_far_above_the_pull_off_is_cut() {
        // A soft film: 400 |F_pull-off| of load beside a pull-off of 1.
        let film = result_with_forces(vec![400.0, 50.0, 2.0, -1.0, -0.5, 0.0]);
        let plotted = Plotted::new(&Figure::new(&film));
        assert_eq!(plotted.cut, Some((CLIP_AT, 400.0)));
        assert!(
            plotted.y.1 < 1.1 * CLIP_AT && plotted.y.0 < -1.0,
            "{:?}",
            plotted.y
        );
        // The x range is that of what shows: from the crossing of the cut on.
        assert!(plotted.x.1 < 5.0, "{:?}", plotted.x);
        // A load within CLIP_RATIO times the pull-off is shown whole.
        let sphere = result_with_forces(vec![8.0, 2.0, -1.0, 0.0]);
        let plotted = Plotted::new(&Figure::new(&sphere));
        assert_eq!(plotted.cut, None);
        assert!(plotted.y.1 > 8.0);
    }

    #[test]
    fn downsampling_keeps_the_bonded_fraction() {
        let mut m = ndarray::Array2::from_elem((128, 1), false);
        m[[0, 0]] = true;
        m[[1, 0]] = true;
        let d = downsample(&m);
        assert_eq!(d.dim(), (64, 1));
        assert_eq!(d[[0, 0]], 1.0);
        assert_eq!(d[[1, 0]], 0.0);
    }

    #[test]
    fn maugis_curve_has_its_pull_off_and_tends_to_jkr() {
        // The least force of the curve is Maugis' pull-off over 1.5 (units of |F_JKR|).
        for lambda in [0.3, 1.0, 5.0] {
            let c = maugis_curve(lambda, 3.0);
            let least = c.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
            let expected = tack::analytics::maugis_pull_off_hat(lambda) / 1.5;
            assert!(
                (least - expected).abs() < 2e-3,
                "λ = {lambda}: {least} vs {expected}"
            );
            assert!(c.last().unwrap().0 > 3.0);
        }
        // At large λ the curve lies on JKR's: the pull-off (−1, −1) in these units (the
        // minimum is flat, so its sampled abscissa is loose), and the force at d = 2|d_JKR|.
        let c = maugis_curve(1e3, 2.5);
        let lowest = c.iter().min_by(|a, b| a.1.total_cmp(&b.1)).unwrap();
        assert!(
            (lowest.0 + 1.0).abs() < 0.05 && (lowest.1 + 1.0).abs() < 1e-3,
            "{lowest:?}"
        );
        let at = |curve: &[(f64, f64)], x: f64| {
            let k = curve
                .windows(2)
                .position(|w| w[0].0 <= x && x < w[1].0)
                .unwrap();
            let (a, b) = (curve[k], curve[k + 1]);
            a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0)
        };
        let jkr = tack::analytics::jkr_curve_normalised(2.5, 0.001);
        assert!((at(&c, 2.0) - at(&jkr, 2.0)).abs() < 2e-3);
    }

    #[test]
    fn jkr_curve_reaches_the_pull_off_point() {
        let c = jkr_curve(&[3.0]);
        let min = c.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        assert!((min + 1.0).abs() < 1e-3, "{min}");
        assert!(c.last().unwrap().0 > 3.0);
    }
}
