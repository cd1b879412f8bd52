//! SVG figures with plotters: one line/point chart helper (numerical data over closed forms)
//! and one heat-map helper (height maps, bonded masks), drawn into panels of one SVG.

use std::path::Path;

use anyhow::{Result, anyhow};
use ndarray::Array2;
use plotters::coord::Shift;
use plotters::prelude::*;

/// A drawing area of an SVG being built.
pub type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// How a series is drawn.
#[derive(Debug, Clone, PartialEq)]
pub enum Style {
    /// Solid line (numerical curves).
    Line,
    /// Dashed line (closed forms).
    Dashed,
    /// Filled circles (numerical states).
    Points,
    /// Circles with vertical error bars of the given half-lengths (one per point).
    ErrorBars(Vec<f64>),
}

/// One series of a chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend entry (empty: not in the legend).
    pub label: String,
    /// Data points.
    pub points: Vec<(f64, f64)>,
    /// Drawing style.
    pub style: Style,
    /// Index into the palette.
    pub color: usize,
}

impl Series {
    /// A series from its parts.
    pub fn new(
        label: impl Into<String>,
        points: Vec<(f64, f64)>,
        style: Style,
        color: usize,
    ) -> Self {
        Self {
            label: label.into(),
            points,
            style,
            color,
        }
    }
}

/// A chart: axes, series and optional fixed ranges.
#[derive(Debug, Clone, Default)]
pub struct Chart {
    /// Caption.
    pub title: String,
    /// Abscissa label.
    pub x_label: String,
    /// Ordinate label.
    pub y_label: String,
    /// Series, drawn in order.
    pub series: Vec<Series>,
    /// Fixed abscissa range (default: the data's, padded).
    pub x_range: Option<(f64, f64)>,
    /// Fixed ordinate range (default: the data's, padded).
    pub y_range: Option<(f64, f64)>,
}

/// A colour of the palette (tab10), cycling.
pub fn color(i: usize) -> RGBColor {
    const P: [(u8, u8, u8); 10] = [
        (31, 119, 180),
        (214, 39, 40),
        (44, 160, 44),
        (255, 127, 14),
        (148, 103, 189),
        (140, 86, 75),
        (227, 119, 194),
        (127, 127, 127),
        (188, 189, 34),
        (23, 190, 207),
    ];
    let (r, g, b) = P[i % P.len()];
    RGBColor(r, g, b)
}

fn pe<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow!("drawing: {e}")
}

/// Registers the bundled Noto Sans (crate `notosans`, OFL-1.1) as plotters' "sans-serif", once:
/// plotters' `ab_glyph` feature (enabled for the workspace, as `tack plot` needs it for PNG)
/// lays out every text with a registered font.
fn register_font() -> Result<()> {
    static REGISTERED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    let ok = REGISTERED.get_or_init(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, notosans::REGULAR_TTF)
            .is_ok()
    });
    anyhow::ensure!(*ok, "the bundled font (Noto Sans) could not be loaded");
    Ok(())
}

/// Renders an SVG of `size` pixels with `draw` and writes it to `path` (temporary + rename).
pub fn svg(path: &Path, size: (u32, u32), draw: impl FnOnce(&Area) -> Result<()>) -> Result<()> {
    register_font()?;
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
        root.fill(&WHITE).map_err(pe)?;
        draw(&root)?;
        root.present().map_err(pe)?;
    }
    tack_io::write_text_atomically(path, &text)?;
    Ok(())
}

fn padded(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = ((hi - lo) * 0.05)
        .max(hi.abs().max(lo.abs()) * 1e-3)
        .max(1e-12);
    (lo - pad, hi + pad)
}

/// Tick labels with as many decimals as the range needs.
fn ticks(lo: f64, hi: f64) -> impl Fn(&f64) -> String {
    let range = (hi - lo).abs().max(1e-300);
    let exponent = (range / 8.0).log10().floor();
    move |&v: &f64| {
        if v.abs() < range * 1e-9 {
            "0".to_owned()
        } else if !(-4.0..5.0).contains(&exponent) {
            format!("{v:.1e}")
        } else {
            format!("{v:.*}", (-exponent).max(0.0) as usize)
        }
    }
}

/// Draws `chart` into `area`; points outside a fixed range are clipped.
pub fn draw_chart(area: &Area, chart: &Chart) -> Result<()> {
    let all = || chart.series.iter().flat_map(|s| s.points.iter());
    let (x0, x1) = chart.x_range.unwrap_or_else(|| padded(all().map(|p| p.0)));
    let (y0, y1) = chart.y_range.unwrap_or_else(|| padded(all().map(|p| p.1)));
    let mut c = ChartBuilder::on(area)
        .caption(&chart.title, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(pe)?;
    c.configure_mesh()
        .x_desc(&chart.x_label)
        .y_desc(&chart.y_label)
        .x_label_formatter(&ticks(x0, x1))
        .y_label_formatter(&ticks(y0, y1))
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 15))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(pe)?;
    let inside = |&(x, y): &(f64, f64)| {
        x.is_finite() && y.is_finite() && (x0..=x1).contains(&x) && (y0..=y1).contains(&y)
    };
    let mut labelled = false;
    for s in &chart.series {
        let col = color(s.color);
        let pts: Vec<(f64, f64)> = s.points.iter().copied().filter(inside).collect();
        let anno = match &s.style {
            Style::Line => c
                .draw_series(LineSeries::new(pts.iter().copied(), col.stroke_width(2)))
                .map_err(pe)?,
            Style::Dashed => c
                .draw_series(DashedLineSeries::new(
                    pts.clone(),
                    6,
                    4,
                    col.stroke_width(2),
                ))
                .map_err(pe)?,
            Style::Points => c
                .draw_series(pts.iter().map(|&p| Circle::new(p, 3, col.filled())))
                .map_err(pe)?,
            Style::ErrorBars(err) => {
                let bars: Vec<_> = s
                    .points
                    .iter()
                    .zip(err)
                    .filter(|(p, _)| inside(p))
                    .map(|(&(x, y), &e)| {
                        PathElement::new([(x, (y - e).max(y0)), (x, (y + e).min(y1))], col)
                    })
                    .collect();
                c.draw_series(bars).map_err(pe)?;
                c.draw_series(pts.iter().map(|&p| Circle::new(p, 3, col.filled())))
                    .map_err(pe)?
            }
        };
        if !s.label.is_empty() {
            labelled = true;
            let dot = matches!(s.style, Style::Points | Style::ErrorBars(_));
            let (end, r) = if dot { (10, 3) } else { (20, 0) };
            anno.label(&s.label).legend(move |(x, y)| {
                EmptyElement::at((x, y))
                    + PathElement::new(
                        [(end - 20 + 10 * i32::from(!dot), 0), (end, 0)],
                        col.stroke_width(2),
                    )
                    + Circle::new((10, 0), r, col.filled())
            });
        }
    }
    if labelled {
        c.configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.4))
            .label_font(("sans-serif", 12))
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(pe)?;
    }
    Ok(())
}

/// A heat map panel.
#[derive(Debug, Clone)]
pub struct Map {
    /// Caption.
    pub title: String,
    /// Values `(nx, ny)`; x runs right, y up.
    pub values: Array2<f64>,
    /// Value range mapped onto the colour scale.
    pub range: (f64, f64),
}

impl Map {
    /// A bonded mask as a map (1 = bonded).
    pub fn mask(title: impl Into<String>, mask: &Array2<bool>) -> Self {
        Self {
            title: title.into(),
            values: mask.mapv(|b| f64::from(u8::from(b))),
            range: (0.0, 1.0),
        }
    }
    /// A height map scaled from its minimum to its maximum.
    pub fn heights(title: impl Into<String>, h: &Array2<f64>) -> Self {
        let range = padded(h.iter().copied());
        Self {
            title: title.into(),
            values: h.clone(),
            range,
        }
    }
}

/// Largest number of cells per side drawn (maps are block-averaged down to it).
const MAX_CELLS: usize = 96;

fn block_average(v: &Array2<f64>) -> Array2<f64> {
    let (nx, ny) = v.dim();
    let b = nx.max(ny).div_ceil(MAX_CELLS).max(1);
    let (cx, cy) = (nx.div_ceil(b), ny.div_ceil(b));
    let mut sum = Array2::<f64>::zeros((cx, cy));
    let mut n = Array2::<f64>::zeros((cx, cy));
    for ((i, j), &x) in v.indexed_iter() {
        sum[[i / b, j / b]] += x;
        n[[i / b, j / b]] += 1.0;
    }
    sum / n
}

/// A perceptually ordered colour scale (dark blue → yellow, viridis-like) for `t ∈ [0, 1]`.
fn scale(t: f64) -> RGBColor {
    const STOPS: [(f64, f64, f64); 5] = [
        (68.0, 1.0, 84.0),
        (59.0, 82.0, 139.0),
        (33.0, 145.0, 140.0),
        (94.0, 201.0, 98.0),
        (253.0, 231.0, 37.0),
    ];
    let t = t.clamp(0.0, 1.0) * 4.0;
    let k = (t.floor() as usize).min(3);
    let f = t - k as f64;
    let (a, b) = (STOPS[k], STOPS[k + 1]);
    let mix = |x: f64, y: f64| (x + f * (y - x)).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Draws `maps` into `area` as a grid of `cols` square panels, row by row.
pub fn draw_maps(area: &Area, maps: &[Map], cols: usize) -> Result<()> {
    let cols = cols.max(1);
    let rows = maps.len().div_ceil(cols).max(1);
    let panels = area.split_evenly((rows, cols));
    for (panel, map) in panels.iter().zip(maps) {
        let cells = block_average(&map.values);
        let (cx, cy) = cells.dim();
        let (w, h) = panel.dim_in_pixel();
        let (w, h) = (f64::from(w) - 16.0, f64::from(h) - 34.0);
        let s = (w / cx as f64).min(h / cy as f64).max(0.0);
        let (mx, my) = (
            ((w - s * cx as f64) / 2.0) as i32,
            ((h - s * cy as f64) / 2.0) as i32,
        );
        let panel = panel.margin(my.max(0), my.max(0), mx.max(0), mx.max(0));
        let mut c = ChartBuilder::on(&panel)
            .caption(&map.title, ("sans-serif", 13))
            .margin(6)
            .build_cartesian_2d(0..cx, 0..cy)
            .map_err(pe)?;
        let (lo, hi) = map.range;
        let span = (hi - lo).max(1e-300);
        // Colours quantised to 32 levels; runs of equal colour along x become one rectangle,
        // which keeps the SVG small.
        let level = |v: f64| (((v - lo) / span).clamp(0.0, 1.0) * 31.0).round() as u8;
        let mut rects = Vec::new();
        for j in 0..cy {
            let mut i = 0;
            while i < cx {
                let l = level(cells[[i, j]]);
                let mut e = i + 1;
                while e < cx && level(cells[[e, j]]) == l {
                    e += 1;
                }
                let color = scale(f64::from(l) / 31.0);
                rects.push(Rectangle::new([(i, j), (e, j + 1)], color.filled()));
                i = e;
            }
        }
        c.draw_series(rects).map_err(pe)?;
        c.draw_series(std::iter::once(Rectangle::new(
            [(0, 0), (cx, cy)],
            BLACK.mix(0.5).stroke_width(1),
        )))
        .map_err(pe)?;
    }
    Ok(())
}
