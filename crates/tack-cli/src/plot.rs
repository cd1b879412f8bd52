//! `tack plot`: the force–approach curve of a result file (load and unload branches, the
//! pull-off point, the JKR curve for spheres) and, when stored, contact snapshots as small
//! heat maps of the bonded mask.
//!
//! Axes are normalised by |F_JKR| and |d_JKR| when the file's summary has a finite, non-zero
//! `f_jkr` and a `d_jkr` (spheres); otherwise they are in the scene's units. SVG is always
//! available; PNG needs the `png` cargo feature (text is drawn with a TrueType font found on the
//! system, see [`FONT_PATHS`]).

use std::path::Path;

use anyhow::{anyhow, bail};
use plotters::coord::Shift;
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

/// TrueType fonts tried, in order, for PNG text (`TACK_FONT` overrides).
pub const FONT_PATHS: [&str; 4] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
];

/// Output format, from the file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Scalable vector graphics.
    Svg,
    /// Portable network graphics (cargo feature `png`).
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
/// temporary file renamed on success.
pub fn plot_file(input: &Path, output: &Path) -> anyhow::Result<()> {
    let format = Format::of(output)?;
    // Before reading: an existing FIFO or device under the output name is never replaced.
    tack::engine::check_output_path(output)?;
    let result = tack_io::read_result(input)?;
    if result.curve.is_empty() {
        bail!(
            "{}: the result has no force–approach curve (a surface-only file from `tack surface`?)",
            input.display()
        );
    }
    tack_io::write_atomically(output, |tmp| render(&result, tmp, format))
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
    register_font()?;
    let root = BitMapBackend::new(path, size).into_drawing_area();
    draw(root, &Figure::new(result))
}

#[cfg(not(feature = "png"))]
fn render_png(_result: &RunResult, path: &Path, _size: (u32, u32)) -> anyhow::Result<()> {
    bail!(
        "{}: PNG output is not built into this tack (rebuild with `--features png`); write an \
         .svg figure instead",
        path.display()
    )
}

/// Registers the first TrueType font found (`TACK_FONT`, then [`FONT_PATHS`]) as sans-serif.
#[cfg(feature = "png")]
fn register_font() -> anyhow::Result<()> {
    use std::path::PathBuf;
    use std::sync::OnceLock;
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            let candidates: Vec<PathBuf> = std::env::var_os("TACK_FONT")
                .map(PathBuf::from)
                .into_iter()
                .chain(FONT_PATHS.iter().map(PathBuf::from))
                .collect();
            let (found, bytes) = candidates
                .iter()
                .find_map(|p| std::fs::read(p).ok().map(|b| (p.clone(), b)))
                .ok_or_else(|| {
                    format!(
                        "PNG output needs a TrueType font and none was found (tried {}); set \
                         TACK_FONT to a .ttf file or write an .svg figure",
                        FONT_PATHS.join(", ")
                    )
                })?;
            // plotters keeps fonts for the life of the process.
            let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
            plotters::style::register_font("sans-serif", FontStyle::Normal, bytes)
                .map_err(|_| format!("{}: not a usable TrueType font", found.display()))
        })
        .clone()
        .map_err(|e| anyhow!(e))
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

fn draw_curve<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    fig: &Figure,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let c = &fig.result.curve;
    let d: Vec<f64> = c.approach.iter().map(|v| v / fig.d_scale).collect();
    let f: Vec<f64> = match (fig.p_star, &c.mean_pressure) {
        (Some(p_star), Some(p)) => p.iter().map(|v| v / p_star).collect(),
        _ => c.force.iter().map(|v| v / fig.f_scale).collect(),
    };
    // The load branch runs up to the deepest approach; the rest is the unload branch.
    let turn = d
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map_or(0, |(i, _)| i);
    let jkr = if fig.normalised {
        jkr_curve(&d)
    } else {
        Vec::new()
    };
    // A Dugdale sphere: Maugis' whole equilibrium curve at its λ, dashed.
    let maugis = match fig.result.summary.extra.get("maugis_lambda") {
        Some(&lambda) if fig.normalised && lambda.is_finite() && lambda > 0.0 => {
            let d_max = d.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            maugis_curve(lambda, d_max)
        }
        _ => Vec::new(),
    };
    let (x0, x1) = bounds(d.iter().copied());
    let (y0, y1) = bounds(
        f.iter().copied().chain(
            jkr.iter().map(|p| p.1).filter(|&y| {
                y <= 1.05 * f.iter().copied().fold(f64::NEG_INFINITY, f64::max).max(1.0)
            }),
        ),
    );
    let (xl, yl) = if fig.normalised {
        ("approach d / |d_JKR|", "force F / |F_JKR|")
    } else if fig.p_star.is_some() {
        ("approach d", "mean pressure p / p*")
    } else {
        ("approach d", "force F (compressive > 0)")
    };
    let y_min = f.iter().copied().fold(f64::INFINITY, f64::min);
    let title = match fig.result.summary.pull_off_ratio {
        r if r.is_finite() => format!("force–approach (F_pull-off / F_JKR = {r:.3})"),
        _ if fig.result.summary.extra.contains_key("f_kendall") => format!(
            "force–approach (F_pull-off / F_Kendall = {:.3})",
            fig.result.summary.pull_off_force / fig.result.summary.extra["f_kendall"]
        ),
        _ if fig.p_star.is_some() => {
            format!("mean pressure–approach (minimum p / p* = {y_min:.4})")
        }
        _ => format!(
            "force–approach (pull-off force {})",
            crate::report::rounded(fig.result.summary.pull_off_force)
        ),
    };
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 22))
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
    if !jkr.is_empty() {
        chart
            .draw_series(LineSeries::new(
                jkr.into_iter()
                    .filter(|&(x, y)| (x0..=x1).contains(&x) && (y0..=y1).contains(&y)),
                RGBColor(120, 120, 120).stroke_width(2),
            ))?
            .label("JKR (smooth sphere)")
            .legend(|(x, y)| {
                PathElement::new(
                    [(x, y), (x + 20, y)],
                    RGBColor(120, 120, 120).stroke_width(2),
                )
            });
    }
    if !maugis.is_empty() {
        let lambda = fig.result.summary.extra["maugis_lambda"];
        let purple = RGBColor(148, 103, 189);
        chart
            .draw_series(DashedLineSeries::new(
                maugis
                    .into_iter()
                    .filter(|&(x, y)| (x0..=x1).contains(&x) && (y0..=y1).contains(&y)),
                6,
                4,
                purple.stroke_width(2),
            ))?
            .label(format!("Maugis–Dugdale λ = {} (equilibria)", short(lambda)))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], purple.stroke_width(2)));
    }
    let blue = RGBColor(31, 119, 180);
    let red = RGBColor(214, 39, 40);
    chart
        .draw_series(LineSeries::new(
            d[..=turn].iter().copied().zip(f[..=turn].iter().copied()),
            blue.stroke_width(2),
        ))?
        .label("load")
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], blue.stroke_width(2)));
    chart
        .draw_series(LineSeries::new(
            d[turn..].iter().copied().zip(f[turn..].iter().copied()),
            red.stroke_width(2),
        ))?
        .label("unload")
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], red.stroke_width(2)));
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
    .filter(|_| fig.p_star.is_none())
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
        .collect();
    if !snaps.is_empty() {
        chart
            .draw_series(
                snaps
                    .into_iter()
                    .map(|p| TriangleMarker::new(p, 6, RGBColor(44, 160, 44).filled())),
            )?
            .label("snapshots (below)")
            .legend(|(x, y)| TriangleMarker::new((x + 10, y), 5, RGBColor(44, 160, 44).filled()));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .label_font(("sans-serif", 14))
        .position(SeriesLabelPosition::UpperLeft)
        .draw()?;
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
