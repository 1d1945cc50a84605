//! Shared plotting for every command: a [`Figure`] (one panel) or a [`Grid`] of panels,
//! written as `<stem>.svg` and `<stem>.png` with plotters.
//!
//! Pure Rust: plotters runs without its system-font (`ttf`/font-kit/fontconfig) feature; its
//! `ab_glyph` feature rasterizes text with DejaVu Sans, embedded at compile time by the
//! `dejavu` crate (Bitstream Vera / public-domain licence) and registered once as
//! `sans-serif`, so α, β, γ, δ and other Unicode glyphs render in the PNG. The SVG keeps text
//! as `<text>` elements (searchable, selectable).
//!
//! ```ignore
//! let mut fig = Figure::new("Stable region, d = 0").x_label("α").y_label("β");
//! fig.add(Series::polygon(region).color(palette::BLUE).label("stable (exact)"));
//! fig.add(Series::dashed(linear).color(palette::BLACK).label("linear (23)"));
//! fig.add(Series::scatter(points, Marker::Circle).color(palette::VERMILLION));
//! fig.save("out/fig4")?; // out/fig4.svg and out/fig4.png
//! ```
//!
//! Data are clipped to the axis ranges here (plotters does not clip): polylines by segment
//! (Liang–Barsky), polygons by Sutherland–Hodgman, markers by containment; NaN points break
//! a polyline into pieces.

// A shared API: not every command uses every item.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::FontStyle;
use plotters::style::text_anchor::{HPos, Pos, VPos};

pub use plotters::style::RGBColor;

/// Colour-blind safe colours (Okabe–Ito) plus black and grey.
pub mod palette {
    use super::RGBColor;
    /// Black.
    pub const BLACK: RGBColor = RGBColor(0, 0, 0);
    /// Blue.
    pub const BLUE: RGBColor = RGBColor(0, 114, 178);
    /// Vermillion.
    pub const VERMILLION: RGBColor = RGBColor(213, 94, 0);
    /// Bluish green.
    pub const GREEN: RGBColor = RGBColor(0, 158, 115);
    /// Orange.
    pub const ORANGE: RGBColor = RGBColor(230, 159, 0);
    /// Reddish purple.
    pub const PURPLE: RGBColor = RGBColor(204, 121, 167);
    /// Sky blue.
    pub const SKY: RGBColor = RGBColor(86, 180, 233);
    /// Grey.
    pub const GREY: RGBColor = RGBColor(110, 110, 110);
    /// Cycle for series without an explicit colour.
    pub const CYCLE: [RGBColor; 7] = [BLUE, VERMILLION, GREEN, ORANGE, PURPLE, SKY, BLACK];
}

/// Default PNG/SVG size of a single figure (px): legible in a paper column.
pub const DEFAULT_SIZE: (u32, u32) = (900, 700);

const FONT: &str = "sans-serif";

/// Registers the embedded DejaVu Sans as `sans-serif` (once per process).
fn ensure_font() -> Result<()> {
    static OK: OnceLock<bool> = OnceLock::new();
    let ok = *OK.get_or_init(|| {
        let reg = |style, bytes| plotters::style::register_font(FONT, style, bytes).is_ok();
        reg(FontStyle::Normal, dejavu::sans::regular())
            & reg(FontStyle::Bold, dejavu::sans::bold())
            & reg(FontStyle::Oblique, dejavu::sans::oblique())
            & reg(FontStyle::Italic, dejavu::sans::oblique())
    });
    if ok {
        Ok(())
    } else {
        Err(anyhow!("the embedded DejaVu Sans font could not be loaded"))
    }
}

/// Marker shape of a scatter series.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    /// Circle.
    Circle,
    /// Square.
    Square,
    /// Upward triangle.
    Triangle,
    /// Diagonal cross.
    Cross,
}

/// What a series draws.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kind {
    /// An open polyline (NaN points break it), solid or dashed.
    Line {
        /// Dashed instead of solid.
        dashed: bool,
    },
    /// A closed polygon filled with the series colour at `alpha`, optionally outlined.
    Polygon {
        /// Fill opacity in [0, 1].
        alpha: f64,
        /// Draw the outline in the series colour.
        outline: bool,
    },
    /// One marker per point.
    Scatter {
        /// Marker shape.
        marker: Marker,
        /// Filled markers (otherwise outlined).
        filled: bool,
    },
}

/// One data series of a [`Figure`].
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// What to draw.
    pub kind: Kind,
    /// Data points (x, y).
    pub points: Vec<(f64, f64)>,
    /// Colour (None: the figure's colour cycle).
    pub color: Option<RGBColor>,
    /// Line width in px (lines and outlines).
    pub width: u32,
    /// Marker radius in px (scatter).
    pub size: u32,
    /// Legend entry, if any.
    pub label: Option<String>,
}

impl Series {
    fn with(kind: Kind, points: impl IntoIterator<Item = (f64, f64)>) -> Self {
        Self {
            kind,
            points: points.into_iter().collect(),
            color: None,
            width: 3,
            size: 7,
            label: None,
        }
    }

    /// A solid polyline.
    pub fn line(points: impl IntoIterator<Item = (f64, f64)>) -> Self {
        Self::with(Kind::Line { dashed: false }, points)
    }

    /// A dashed polyline.
    pub fn dashed(points: impl IntoIterator<Item = (f64, f64)>) -> Self {
        Self::with(Kind::Line { dashed: true }, points)
    }

    /// A closed polygon, filled at 25 % opacity and outlined.
    pub fn polygon(points: impl IntoIterator<Item = (f64, f64)>) -> Self {
        Self::with(
            Kind::Polygon {
                alpha: 0.25,
                outline: true,
            },
            points,
        )
    }

    /// Filled markers.
    pub fn scatter(points: impl IntoIterator<Item = (f64, f64)>, marker: Marker) -> Self {
        Self::with(
            Kind::Scatter {
                marker,
                filled: true,
            },
            points,
        )
    }

    /// Sets the colour.
    pub fn color(mut self, c: RGBColor) -> Self {
        self.color = Some(c);
        self
    }

    /// Sets the line width in px.
    pub fn width(mut self, w: u32) -> Self {
        self.width = w;
        self
    }

    /// Sets the marker radius in px.
    pub fn size(mut self, s: u32) -> Self {
        self.size = s;
        self
    }

    /// Sets the fill opacity of a polygon.
    pub fn alpha(mut self, a: f64) -> Self {
        if let Kind::Polygon { alpha, .. } = &mut self.kind {
            *alpha = a.clamp(0.0, 1.0);
        }
        self
    }

    /// Polygon without outline.
    pub fn no_outline(mut self) -> Self {
        if let Kind::Polygon { outline, .. } = &mut self.kind {
            *outline = false;
        }
        self
    }

    /// Hollow markers.
    pub fn hollow(mut self) -> Self {
        if let Kind::Scatter { filled, .. } = &mut self.kind {
            *filled = false;
        }
        self
    }

    /// Sets the legend entry.
    pub fn label(mut self, l: impl Into<String>) -> Self {
        self.label = Some(l.into());
        self
    }
}

/// Where the legend goes inside the plotting area.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Legend {
    /// No legend.
    Hidden,
    /// Upper left corner.
    UpperLeft,
    /// Upper right corner.
    UpperRight,
    /// Lower left corner.
    LowerLeft,
    /// Lower right corner.
    LowerRight,
}

/// A text label at data coordinates (left-aligned, vertically centred).
#[derive(Debug, Clone, PartialEq)]
pub struct Annotation {
    /// Position (x, y) in data coordinates.
    pub at: (f64, f64),
    /// The text.
    pub text: String,
    /// Colour.
    pub color: RGBColor,
}

/// One plot panel: title, axis labels, ranges, series, annotations and legend.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// Title above the plot (may be empty).
    pub title: String,
    /// x-axis label.
    pub x_label: String,
    /// y-axis label.
    pub y_label: String,
    /// x range (None: fitted to the data with 4 % padding).
    pub x_range: Option<(f64, f64)>,
    /// y range (None: fitted to the data with 4 % padding).
    pub y_range: Option<(f64, f64)>,
    /// The series, drawn in order.
    pub series: Vec<Series>,
    /// Text labels, drawn last.
    pub annotations: Vec<Annotation>,
    /// Legend position.
    pub legend: Legend,
    /// Output size in px when saved alone.
    pub size: (u32, u32),
    /// Font scale (1.0: nominal title 34, axis labels 30, ticks and legend 25; plotters
    /// renders text at nominal/1.24 px, so ticks are 20 px).
    pub font_scale: f64,
    /// The x data are log10 of the quantity: ticks at whole decades, labelled 10^x.
    pub x_log10: bool,
}

impl Figure {
    /// An empty figure of [`DEFAULT_SIZE`] with the legend in the upper right.
    pub fn new(title: impl Into<String>) -> Self {
        Self {
            title: title.into(),
            x_label: String::new(),
            y_label: String::new(),
            x_range: None,
            y_range: None,
            series: Vec::new(),
            annotations: Vec::new(),
            legend: Legend::UpperRight,
            size: DEFAULT_SIZE,
            font_scale: 1.0,
            x_log10: false,
        }
    }

    /// Marks the x data as log10 of the quantity (a log axis): ticks at whole decades,
    /// labelled with the quantity (10^x).
    pub fn x_log10(mut self) -> Self {
        self.x_log10 = true;
        self
    }

    /// Sets the x-axis label.
    pub fn x_label(mut self, l: impl Into<String>) -> Self {
        self.x_label = l.into();
        self
    }

    /// Sets the y-axis label.
    pub fn y_label(mut self, l: impl Into<String>) -> Self {
        self.y_label = l.into();
        self
    }

    /// Fixes the x range.
    pub fn x_range(mut self, lo: f64, hi: f64) -> Self {
        self.x_range = Some((lo, hi));
        self
    }

    /// Fixes the y range.
    pub fn y_range(mut self, lo: f64, hi: f64) -> Self {
        self.y_range = Some((lo, hi));
        self
    }

    /// Sets the legend position.
    pub fn legend(mut self, l: Legend) -> Self {
        self.legend = l;
        self
    }

    /// Sets the output size in px.
    pub fn size(mut self, w: u32, h: u32) -> Self {
        self.size = (w, h);
        self
    }

    /// Sets the font scale.
    pub fn font_scale(mut self, s: f64) -> Self {
        self.font_scale = s;
        self
    }

    /// Adds a series.
    pub fn add(&mut self, s: Series) -> &mut Self {
        self.series.push(s);
        self
    }

    /// Adds a series (by value, for chaining).
    pub fn with(mut self, s: Series) -> Self {
        self.series.push(s);
        self
    }

    /// Adds a text label at data coordinates.
    pub fn annotate(&mut self, x: f64, y: f64, text: impl Into<String>) -> &mut Self {
        self.annotations.push(Annotation {
            at: (x, y),
            text: text.into(),
            color: palette::BLACK,
        });
        self
    }

    /// The axis ranges used for drawing: the fixed ones, or the finite data's bounding box
    /// padded by 4 % (a degenerate extent is widened).
    pub fn ranges(&self) -> ((f64, f64), (f64, f64)) {
        let pts = || {
            self.series
                .iter()
                .flat_map(|s| s.points.iter().copied())
                .chain(self.annotations.iter().map(|a| a.at))
                .filter(|(x, y)| x.is_finite() && y.is_finite())
        };
        let fit = |vals: &mut dyn Iterator<Item = f64>| {
            let (lo, hi) = vals.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            });
            padded(lo, hi)
        };
        let xr = match self.x_range {
            Some(r) => r,
            None => fit(&mut pts().map(|p| p.0)),
        };
        let yr = match self.y_range {
            Some(r) => r,
            None => fit(&mut pts().map(|p| p.1)),
        };
        (xr, yr)
    }

    /// Writes `<stem>.svg` and `<stem>.png` (an `.svg`/`.png` extension on `stem` is
    /// dropped; missing parent folders are created).
    pub fn save(&self, stem: impl AsRef<Path>) -> Result<Saved> {
        save_both(self, stem.as_ref())
    }

    fn check(&self) -> Result<()> {
        let ((x0, x1), (y0, y1)) = self.ranges();
        for (name, lo, hi) in [("x", x0, x1), ("y", y0, y1)] {
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(anyhow!(
                    "plot '{}': invalid {name} range [{lo}, {hi}]",
                    self.title
                ));
            }
        }
        Ok(())
    }

    fn draw<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let s = self.font_scale;
        let px = |v: f64| (v * s).round().max(1.0) as u32;
        let ((x0, x1), (y0, y1)) = self.ranges();
        let mut builder = ChartBuilder::on(area);
        builder
            .margin(px(14.0))
            .margin_right(px(28.0))
            .x_label_area_size(px(80.0))
            .y_label_area_size(px(120.0));
        if !self.title.is_empty() {
            let size = fit_font(34.0 * s, &self.title, area.dim_in_pixel().0);
            builder.caption(&self.title, (FONT, size).into_font());
        }
        let mut chart = builder.build_cartesian_2d(x0..x1, y0..y1)?;
        let linear = tick_formatter(x1 - x0);
        let xfmt = |v: &f64| match self.x_log10 {
            true => crate::output::sig(10f64.powf(*v), 3),
            false => linear(v),
        };
        let yfmt = tick_formatter(y1 - y0);
        chart
            .configure_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .axis_desc_style((FONT, px(30.0)))
            .label_style((FONT, px(25.0)))
            .x_labels(match self.x_log10 {
                true => ((x1 - x0).floor() as usize + 1).clamp(2, 12),
                false => 9,
            })
            .y_labels(9)
            .x_label_formatter(&xfmt)
            .y_label_formatter(&yfmt)
            .max_light_lines(4)
            .light_line_style(RGBColor(240, 240, 240))
            .bold_line_style(RGBColor(212, 212, 212))
            .axis_style(BLACK.stroke_width(2))
            .draw()?;
        let bounds = Rect { x0, x1, y0, y1 };
        let (pw, ph) = chart.plotting_area().dim_in_pixel();
        let px_scale = (pw as f64 / (x1 - x0), ph as f64 / (y1 - y0));
        // Clip, then simplify to 0.4 px (see `thin`).
        let pieces_of = |pts: &[(f64, f64)]| -> Vec<Vec<(f64, f64)>> {
            clip_polyline(pts, &bounds)
                .into_iter()
                .map(|p| thin(&p, px_scale, 0.4))
                .collect()
        };
        let mut labelled = false;
        for (i, series) in self.series.iter().enumerate() {
            let color = series
                .color
                .unwrap_or(palette::CYCLE[i % palette::CYCLE.len()]);
            let w = series.width.max(1);
            let line_style = color.stroke_width(w);
            match series.kind {
                Kind::Line { dashed: false } => {
                    let pieces = pieces_of(&series.points);
                    let a = chart
                        .draw_series(pieces.into_iter().map(|p| PathElement::new(p, line_style)))?;
                    if let Some(l) = &series.label {
                        labelled = true;
                        a.label(l).legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 36, y)], color.stroke_width(w))
                        });
                    }
                }
                Kind::Line { dashed: true } => {
                    let pieces = pieces_of(&series.points);
                    let (dash, gap) = ((4 * w + 6) as i32, (2 * w + 5) as i32);
                    let a = chart.draw_series(
                        pieces
                            .into_iter()
                            .map(|p| DashedPathElement::new(p, dash, gap, line_style)),
                    )?;
                    if let Some(l) = &series.label {
                        labelled = true;
                        a.label(l).legend(move |(x, y)| {
                            DashedPathElement::new(
                                vec![(x, y), (x + 36, y)],
                                9,
                                6,
                                color.stroke_width(w),
                            )
                        });
                    }
                }
                Kind::Polygon { alpha, outline } => {
                    let poly = thin(&clip_polygon(&series.points, &bounds), px_scale, 0.4);
                    if poly.len() < 3 {
                        continue;
                    }
                    let a = chart.draw_series(std::iter::once(Polygon::new(
                        poly,
                        color.mix(alpha).filled(),
                    )))?;
                    if let Some(l) = &series.label {
                        labelled = true;
                        a.label(l).legend(move |(x, y)| {
                            let fill =
                                Rectangle::new([(0, -9), (36, 9)], color.mix(alpha).filled());
                            let edge = Rectangle::new(
                                [(0, -9), (36, 9)],
                                color.stroke_width(if outline { 2 } else { 0 }),
                            );
                            EmptyElement::at((x, y)) + fill + edge
                        });
                    }
                    if outline {
                        // Outline only along the true edges, not along the clip window.
                        let mut ring = series.points.clone();
                        ring.push(series.points[0]);
                        let pieces = pieces_of(&ring);
                        chart.draw_series(
                            pieces.into_iter().map(|p| PathElement::new(p, line_style)),
                        )?;
                    }
                }
                Kind::Scatter { marker, filled } => {
                    let r = series.size.max(1) as i32;
                    let style = if filled {
                        color.filled()
                    } else {
                        color.stroke_width(2)
                    };
                    let pts: Vec<(f64, f64)> = series
                        .points
                        .iter()
                        .copied()
                        .filter(|&p| bounds.contains(p))
                        .collect();
                    // One element type per marker (plotters' series need concrete types).
                    macro_rules! scatter {
                        ($p:ident => $e:expr) => {{
                            let a = chart.draw_series(pts.iter().map(|&$p| $e))?;
                            if let Some(l) = &series.label {
                                labelled = true;
                                a.label(l).legend(move |(x, y)| {
                                    let $p = (x + 18, y);
                                    $e
                                });
                            }
                        }};
                    }
                    match marker {
                        Marker::Circle => scatter!(p => Circle::new(p, r, style)),
                        Marker::Square => scatter!(p => EmptyElement::at(p)
                            + Rectangle::new([(-r, -r), (r, r)], style)),
                        Marker::Triangle => scatter!(p => TriangleMarker::new(p, r + 2, style)),
                        Marker::Cross => scatter!(p => Cross::new(p, r, style.stroke_width(3))),
                    }
                }
            }
        }
        let font = (FONT, px(25.0)).into_font();
        for an in &self.annotations {
            if bounds.contains(an.at) {
                let style = font.clone().color(&an.color);
                chart.draw_series(std::iter::once(Text::new(
                    an.text.clone(),
                    an.at,
                    style.pos(Pos::new(HPos::Left, VPos::Center)),
                )))?;
            }
        }
        if labelled && self.legend != Legend::Hidden {
            let pos = match self.legend {
                Legend::UpperLeft => SeriesLabelPosition::UpperLeft,
                Legend::UpperRight | Legend::Hidden => SeriesLabelPosition::UpperRight,
                Legend::LowerLeft => SeriesLabelPosition::LowerLeft,
                Legend::LowerRight => SeriesLabelPosition::LowerRight,
            };
            chart
                .configure_series_labels()
                .position(pos)
                .margin(px(12.0))
                .legend_area_size(px(50.0))
                .label_font((FONT, px(25.0)))
                .background_style(WHITE.mix(0.88))
                .border_style(RGBColor(120, 120, 120))
                .draw()?;
        }
        Ok(())
    }
}

/// A grid of panels saved as one image: `cols` columns, rows as needed, panels in reading
/// order, each of `panel_size` px, with an optional overall title.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// Overall title (may be empty).
    pub title: String,
    /// Number of columns (>= 1).
    pub cols: usize,
    /// Panels in reading order.
    pub panels: Vec<Figure>,
    /// Size of one panel in px.
    pub panel_size: (u32, u32),
}

impl Grid {
    /// An empty grid with `cols` columns of 900×700 px panels.
    pub fn new(title: impl Into<String>, cols: usize) -> Self {
        Self {
            title: title.into(),
            cols: cols.max(1),
            panels: Vec::new(),
            panel_size: DEFAULT_SIZE,
        }
    }

    /// Sets the size of one panel in px.
    pub fn panel_size(mut self, w: u32, h: u32) -> Self {
        self.panel_size = (w, h);
        self
    }

    /// Adds a panel.
    pub fn push(&mut self, f: Figure) -> &mut Self {
        self.panels.push(f);
        self
    }

    fn rows(&self) -> usize {
        self.panels.len().div_ceil(self.cols).max(1)
    }

    fn title_height(&self) -> u32 {
        if self.title.is_empty() { 0 } else { 56 }
    }

    /// Writes `<stem>.svg` and `<stem>.png` (see [`Figure::save`]).
    pub fn save(&self, stem: impl AsRef<Path>) -> Result<Saved> {
        save_both(self, stem.as_ref())
    }
}

/// The files written by a save.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct Saved {
    /// The SVG file.
    pub svg: PathBuf,
    /// The PNG file.
    pub png: PathBuf,
}

trait Render {
    fn pixels(&self) -> (u32, u32);
    fn check(&self) -> Result<()>;
    fn render<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>;
}

impl Render for Figure {
    fn pixels(&self) -> (u32, u32) {
        self.size
    }
    fn check(&self) -> Result<()> {
        Figure::check(self)
    }
    fn render<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        self.draw(root)
    }
}

impl Render for Grid {
    fn pixels(&self) -> (u32, u32) {
        let (w, h) = self.panel_size;
        (
            w * self.cols as u32,
            h * self.rows() as u32 + self.title_height(),
        )
    }
    fn check(&self) -> Result<()> {
        if self.panels.is_empty() {
            return Err(anyhow!("plot '{}': no panels", self.title));
        }
        self.panels.iter().try_for_each(Figure::check)
    }
    fn render<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let body = if self.title.is_empty() {
            root.clone()
        } else {
            let size = fit_font(40.0, &self.title, root.dim_in_pixel().0);
            root.titled(&self.title, (FONT, size).into_font())?
        };
        let areas = body.split_evenly((self.rows(), self.cols));
        for (panel, area) in self.panels.iter().zip(areas.iter()) {
            panel.draw(area)?;
        }
        Ok(())
    }
}

/// `<stem>.svg` and `<stem>.png`; a trailing `.svg`/`.png` on the stem is dropped.
pub fn output_paths(stem: &Path) -> (PathBuf, PathBuf) {
    let base = match stem.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("svg") || e.eq_ignore_ascii_case("png") => {
            stem.with_extension("")
        }
        _ => stem.to_path_buf(),
    };
    let with = |ext: &str| {
        let mut s = base.clone().into_os_string();
        s.push(".");
        s.push(ext);
        PathBuf::from(s)
    };
    (with("svg"), with("png"))
}

fn save_both<R: Render>(r: &R, stem: &Path) -> Result<Saved> {
    if stem.as_os_str().is_empty() {
        return Err(anyhow!("empty plot file name"));
    }
    let (svg, png) = output_paths(stem);
    write_files(r, &[&svg, &png])?;
    Ok(Saved { svg, png })
}

/// What `path` asks for: only an SVG for a `.svg` extension, only a PNG for `.png`, both
/// `<path>.svg` and `<path>.png` for any other name.
pub fn requested_paths(path: &Path) -> Vec<PathBuf> {
    match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("svg") || e.eq_ignore_ascii_case("png") => {
            vec![path.to_path_buf()]
        }
        _ => {
            let (svg, png) = output_paths(path);
            vec![svg, png]
        }
    }
}

/// Writes the files that `path` names ([`requested_paths`]) and returns them.
fn save_requested<R: Render>(r: &R, path: &Path) -> Result<Vec<PathBuf>> {
    if path.as_os_str().is_empty() {
        return Err(anyhow!("empty plot file name"));
    }
    let paths = requested_paths(path);
    let refs: Vec<&Path> = paths.iter().map(PathBuf::as_path).collect();
    write_files(r, &refs)?;
    Ok(paths)
}

impl Figure {
    /// Writes the file that `path` names: an SVG for `.svg`, a PNG for `.png`, both
    /// `<path>.svg` and `<path>.png` for any other name ([`requested_paths`]).
    pub fn save_as(&self, path: impl AsRef<Path>) -> Result<Vec<PathBuf>> {
        save_requested(self, path.as_ref())
    }
}

impl Grid {
    /// Writes the file that `path` names (see [`Figure::save_as`]).
    pub fn save_as(&self, path: impl AsRef<Path>) -> Result<Vec<PathBuf>> {
        save_requested(self, path.as_ref())
    }
}

/// Renders `r` into each path, as SVG or PNG by its extension (missing parent folders are
/// created); every failure names the file.
fn write_files<R: Render>(r: &R, paths: &[&Path]) -> Result<()> {
    r.check()?;
    ensure_font()?;
    for path in paths {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .map_err(|e| anyhow!("cannot create folder {}: {e}", dir.display()))?;
        }
        let size = r.pixels();
        let fail = |e: &dyn std::fmt::Display| anyhow!("writing {}: {e}", path.display());
        let svg = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
        if svg {
            let root = SVGBackend::new(path, size).into_drawing_area();
            root.fill(&WHITE).map_err(|e| fail(&e))?;
            r.render(&root).map_err(|e| fail(&e))?;
            root.present().map_err(|e| fail(&e))?;
        } else {
            let root = BitMapBackend::new(path, size).into_drawing_area();
            root.fill(&WHITE).map_err(|e| fail(&e))?;
            r.render(&root).map_err(|e| fail(&e))?;
            root.present().map_err(|e| fail(&e))?;
        }
        // plotters reports some write failures only on drop: make sure the file is there.
        if !path.is_file() {
            return Err(anyhow!("could not write {}", path.display()));
        }
    }
    Ok(())
}

/// The nominal font size for a one-line title: `nominal`, shrunk (not below 23, i.e. 18.5 px) so that
/// the text fits into `width` px (DejaVu Sans averages about 0.58 em per character; plotters
/// renders nominal/1.24 px).
fn fit_font(nominal: f64, text: &str, width: u32) -> f64 {
    let chars = text.chars().count().max(1) as f64;
    let fit = (width as f64 - 40.0).max(1.0) * 1.24 / (0.58 * chars);
    nominal.min(fit).max(23.0).round()
}

fn padded(lo: f64, hi: f64) -> (f64, f64) {
    if !(lo.is_finite() && hi.is_finite()) {
        return (0.0, 1.0);
    }
    let span = hi - lo;
    if span <= 1e-12 * lo.abs().max(hi.abs()) || span == 0.0 {
        let w = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        return (lo - w, hi + w);
    }
    (lo - 0.04 * span, hi + 0.04 * span)
}

/// From this magnitude on, tick labels are written as 2.5e5 rather than 250000, so that nine
/// of them fit side by side in a panel (stiffness axes in N/m reach 10⁶).
const TICK_SCIENTIFIC_FROM: f64 = 1e5;

/// Tick labels with up to 6 significant digits; values within 1e-9 of the span of zero
/// print as 0 (no "1e-17" at the origin); large values in short scientific form (2.5e5).
fn tick_formatter(span: f64) -> impl Fn(&f64) -> String {
    move |v: &f64| {
        if v.abs() < 1e-9 * span.abs() {
            "0".to_string()
        } else if v.abs() >= TICK_SCIENTIFIC_FROM {
            let rounded: f64 = format!("{v:.5e}").parse().unwrap_or(*v);
            format!("{rounded:e}")
        } else {
            crate::output::sig(*v, 6)
        }
    }
}

/// Decimates a time series with increasing x to at most `2 · buckets` points, keeping each
/// bucket's minimum and maximum in order, so that oscillations stay visible.
pub fn decimate_minmax(points: &[(f64, f64)], buckets: usize) -> Vec<(f64, f64)> {
    if buckets == 0 || points.len() <= 2 * buckets {
        return points.to_vec();
    }
    let per = points.len().div_ceil(buckets);
    let mut out = Vec::with_capacity(2 * buckets + 1);
    for chunk in points.chunks(per) {
        let (mut imin, mut imax) = (0, 0);
        for (i, p) in chunk.iter().enumerate() {
            if p.1 < chunk[imin].1 {
                imin = i;
            }
            if p.1 > chunk[imax].1 {
                imax = i;
            }
        }
        let (a, b) = (imin.min(imax), imin.max(imax));
        out.push(chunk[a]);
        if b != a {
            out.push(chunk[b]);
        }
    }
    out
}

type Pt = (f64, f64);

#[derive(Debug, Clone, Copy)]
struct Rect {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
}

impl Rect {
    fn contains(&self, (x, y): (f64, f64)) -> bool {
        x >= self.x0 && x <= self.x1 && y >= self.y0 && y <= self.y1
    }
}

/// Clips a polyline to the rectangle (Liang–Barsky per segment); NaN or infinite points
/// break it. Returns the visible pieces (each >= 2 points).
fn clip_polyline(points: &[(f64, f64)], r: &Rect) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut cur: Vec<(f64, f64)> = Vec::new();
    let flush = |cur: &mut Vec<(f64, f64)>, out: &mut Vec<Vec<(f64, f64)>>| {
        if cur.len() >= 2 {
            out.push(std::mem::take(cur));
        } else {
            cur.clear();
        }
    };
    let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
    if points.len() == 1 && finite(&points[0]) && r.contains(points[0]) {
        return Vec::new();
    }
    for w in points.windows(2) {
        let (a, b) = (w[0], w[1]);
        if !finite(&a) || !finite(&b) {
            flush(&mut cur, &mut out);
            continue;
        }
        match clip_segment(a, b, r) {
            Some((p, q, cut_end)) => {
                if cur.last() != Some(&p) {
                    flush(&mut cur, &mut out);
                    cur.push(p);
                }
                cur.push(q);
                if cut_end {
                    flush(&mut cur, &mut out);
                }
            }
            None => flush(&mut cur, &mut out),
        }
    }
    flush(&mut cur, &mut out);
    out
}

/// Ramer–Douglas–Peucker simplification in pixel space: drops points within `tol_px` pixels
/// of the chord that replaces them (first and last kept). plotters rounds vertices to whole
/// pixels, so a dense curve would otherwise zig-zag and its thick-line joins would fringe.
fn thin(points: &[(f64, f64)], (sx, sy): (f64, f64), tol_px: f64) -> Vec<(f64, f64)> {
    let n = points.len();
    if n <= 2 {
        return points.to_vec();
    }
    let px = |p: (f64, f64)| (p.0 * sx, p.1 * sy);
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[n - 1] = true;
    let mut stack = vec![(0usize, n - 1)];
    while let Some((i, j)) = stack.pop() {
        if j <= i + 1 {
            continue;
        }
        let (a, b) = (px(points[i]), px(points[j]));
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len = dx.hypot(dy);
        let (mut worst, mut at) = (-1.0, i);
        for (k, &p) in points.iter().enumerate().take(j).skip(i + 1) {
            let q = px(p);
            let d = if len > 0.0 {
                ((q.0 - a.0) * dy - (q.1 - a.1) * dx).abs() / len
            } else {
                (q.0 - a.0).hypot(q.1 - a.1)
            };
            if d > worst {
                worst = d;
                at = k;
            }
        }
        if worst > tol_px {
            keep[at] = true;
            stack.push((i, at));
            stack.push((at, j));
        }
    }
    points
        .iter()
        .zip(keep)
        .filter_map(|(&p, k)| k.then_some(p))
        .collect()
}

/// Does segment a–b meet the axis-aligned box [x0, x1] × [y0, y1] given as
/// `[x0, x1, y0, y1]`? (Liang–Barsky, via [`clip_segment`]; false for non-finite ends.)
pub fn segment_meets_box(a: Pt, b: Pt, bx: [f64; 4]) -> bool {
    let finite = a.0.is_finite() && a.1.is_finite() && b.0.is_finite() && b.1.is_finite();
    let r = Rect {
        x0: bx[0],
        x1: bx[1],
        y0: bx[2],
        y1: bx[3],
    };
    finite && clip_segment(a, b, &r).is_some()
}

/// Liang–Barsky: the visible part of segment a→b, and whether its end was cut.
fn clip_segment(a: Pt, b: Pt, r: &Rect) -> Option<(Pt, Pt, bool)> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.0 - r.x0),
        (dx, r.x1 - a.0),
        (-dy, a.1 - r.y0),
        (dy, r.y1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| {
        if t == 0.0 {
            a
        } else if t == 1.0 {
            b
        } else {
            (a.0 + t * dx, a.1 + t * dy)
        }
    };
    Some((at(t0), at(t1), t1 < 1.0))
}

/// Sutherland–Hodgman clipping of a closed polygon to the rectangle (non-finite vertices
/// dropped).
fn clip_polygon(points: &[(f64, f64)], r: &Rect) -> Vec<(f64, f64)> {
    let mut poly: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    type Inside = fn(&Rect, (f64, f64)) -> bool;
    type Cut = fn(&Rect, (f64, f64), (f64, f64)) -> (f64, f64);
    let edges: [(Inside, Cut); 4] = [
        (
            |r, p| p.0 >= r.x0,
            |r, a, b| {
                let t = (r.x0 - a.0) / (b.0 - a.0);
                (r.x0, a.1 + t * (b.1 - a.1))
            },
        ),
        (
            |r, p| p.0 <= r.x1,
            |r, a, b| {
                let t = (r.x1 - a.0) / (b.0 - a.0);
                (r.x1, a.1 + t * (b.1 - a.1))
            },
        ),
        (
            |r, p| p.1 >= r.y0,
            |r, a, b| {
                let t = (r.y0 - a.1) / (b.1 - a.1);
                (a.0 + t * (b.0 - a.0), r.y0)
            },
        ),
        (
            |r, p| p.1 <= r.y1,
            |r, a, b| {
                let t = (r.y1 - a.1) / (b.1 - a.1);
                (a.0 + t * (b.0 - a.0), r.y1)
            },
        ),
    ];
    for (inside, cut) in edges {
        if poly.is_empty() {
            break;
        }
        let input = std::mem::take(&mut poly);
        let n = input.len();
        for i in 0..n {
            let cur = input[i];
            let prev = input[(i + n - 1) % n];
            let (ci, pi) = (inside(r, cur), inside(r, prev));
            if ci {
                if !pi {
                    poly.push(cut(r, prev, cur));
                }
                poly.push(cur);
            } else if pi {
                poly.push(cut(r, prev, cur));
            }
        }
    }
    poly
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_figure() -> Figure {
        let circle: Vec<(f64, f64)> = (0..100)
            .map(|i| {
                let t = i as f64 / 100.0 * std::f64::consts::TAU;
                (0.5 + 0.4 * t.cos(), 0.5 + 0.4 * t.sin())
            })
            .collect();
        let mut f = Figure::new("Test: stable region")
            .x_label("virtual stiffness α")
            .y_label("virtual damping β")
            .x_range(-0.2, 1.2)
            .y_range(-0.2, 1.2);
        f.add(Series::polygon(circle).color(palette::BLUE).label("region"));
        f.add(
            Series::dashed([(-1.0, -1.0), (2.0, 2.0)])
                .color(palette::BLACK)
                .label("dashed, clipped"),
        );
        f.add(Series::line([
            (0.0, 1.0),
            (f64::NAN, 0.0),
            (1.0, 0.0),
            (0.5, 0.5),
        ]));
        f.add(
            Series::scatter([(0.2, 0.2), (0.8, 0.8), (5.0, 5.0)], Marker::Circle)
                .color(palette::VERMILLION)
                .label("2 %"),
        );
        f.add(
            Series::scatter([(0.3, 0.7)], Marker::Square)
                .color(palette::GREEN)
                .hollow()
                .label("5 %"),
        );
        f.annotate(0.1, 1.05, "γ = 0.001, δ = 0.015");
        f
    }

    fn check_png(path: &Path, size: (u32, u32)) {
        let img = image::open(path).unwrap().to_rgb8();
        assert_eq!(img.dimensions(), size);
        let non_white = img.pixels().filter(|p| p.0 != [255, 255, 255]).count();
        let total = (size.0 * size.1) as usize;
        // Axes, text and a filled region: clearly not blank, clearly not all ink.
        assert!(non_white > total / 50, "{non_white} of {total}");
        assert!(non_white < total * 3 / 4, "{non_white} of {total}");
        // The 25 % blue fill blends to about (191, 220, 236).
        let colored = img
            .pixels()
            .filter(|p| p.0[2] > 200 && p.0[0] < 210 && p.0[0] > 170)
            .count();
        assert!(colored > total / 50, "fill missing: {colored}");
    }

    #[test]
    fn figure_writes_svg_and_png_with_labels() {
        let dir = tempfile::tempdir().unwrap();
        let f = sample_figure();
        let saved = f.save(dir.path().join("sub").join("fig.svg")).unwrap();
        assert_eq!(saved.svg, dir.path().join("sub/fig.svg"));
        assert_eq!(saved.png, dir.path().join("sub/fig.png"));
        check_png(&saved.png, DEFAULT_SIZE);
        let svg = std::fs::read_to_string(&saved.svg).unwrap();
        assert!(svg.starts_with("<svg"), "{}", &svg[..80.min(svg.len())]);
        for t in [
            "virtual stiffness α",
            "virtual damping β",
            "Test: stable region",
            "γ = 0.001, δ = 0.015",
            "dashed, clipped",
        ] {
            assert!(svg.contains(t), "SVG lacks {t}");
        }
        assert!(svg.contains("<polygon"), "no filled polygon");
        // Every text is at least 18 px (readable when a paper column prints 900 px wide).
        let sizes: Vec<f64> = svg
            .split("font-size=\"")
            .skip(1)
            .map(|t| t.split('"').next().unwrap().parse().unwrap())
            .collect();
        assert!(sizes.len() > 10, "{sizes:?}");
        assert!(sizes.iter().all(|&v| v >= 18.0), "{sizes:?}");
        assert!(svg.contains("opacity=\"0.25\""), "no alpha fill");
    }

    #[test]
    fn grid_writes_one_image_of_all_panels() {
        let dir = tempfile::tempdir().unwrap();
        let mut g = Grid::new("Two panels", 2).panel_size(600, 450);
        g.push(sample_figure().x_label("left α"));
        g.push(sample_figure().x_label("right β"));
        g.push(sample_figure().x_label("third"));
        let saved = g.save(dir.path().join("grid")).unwrap();
        check_png(&saved.png, (1200, 900 + 56));
        let svg = std::fs::read_to_string(&saved.svg).unwrap();
        for t in ["left α", "right β", "third", "Two panels"] {
            assert!(svg.contains(t), "SVG lacks {t}");
        }
    }

    #[test]
    fn bad_ranges_and_paths_are_errors() {
        let dir = tempfile::tempdir().unwrap();
        let f = Figure::new("x").x_range(1.0, 1.0);
        assert!(f.save(dir.path().join("a")).is_err());
        let f = Figure::new("x").y_range(0.0, f64::NAN);
        assert!(f.save(dir.path().join("b")).is_err());
        assert!(sample_figure().save("").is_err());
        // A file where a folder is needed.
        std::fs::write(dir.path().join("file"), "x").unwrap();
        assert!(sample_figure().save(dir.path().join("file/fig")).is_err());
        // Auto range of an empty figure is usable.
        assert_eq!(Figure::new("e").ranges(), ((0.0, 1.0), (0.0, 1.0)));
    }

    #[test]
    fn clipping() {
        let r = Rect {
            x0: 0.0,
            x1: 1.0,
            y0: 0.0,
            y1: 1.0,
        };
        let pieces = clip_polyline(&[(-1.0, 0.5), (0.5, 0.5), (2.0, 0.5), (0.5, 0.2)], &r);
        assert_eq!(
            pieces,
            vec![
                vec![(0.0, 0.5), (0.5, 0.5), (1.0, 0.5)],
                vec![(1.0, 0.30000000000000004), (0.5, 0.2)]
            ]
        );
        let nan = clip_polyline(
            &[
                (0.1, 0.1),
                (0.2, 0.2),
                (f64::NAN, 0.0),
                (0.3, 0.3),
                (0.4, 0.4),
            ],
            &r,
        );
        assert_eq!(nan.len(), 2);
        let sq = clip_polygon(&[(-1.0, -1.0), (2.0, -1.0), (2.0, 2.0), (-1.0, 2.0)], &r);
        let area = 0.5
            * (0..sq.len())
                .map(|i| {
                    let (a, b) = (sq[i], sq[(i + 1) % sq.len()]);
                    a.0 * b.1 - b.0 * a.1
                })
                .sum::<f64>();
        assert!((area - 1.0).abs() < 1e-12, "{sq:?}");
        assert!(clip_polygon(&[(2.0, 2.0), (3.0, 2.0), (3.0, 3.0)], &r).is_empty());
        let d = decimate_minmax(
            &(0..1000)
                .map(|i| (i as f64, (i as f64).sin()))
                .collect::<Vec<_>>(),
            50,
        );
        assert!(d.len() <= 100 && d.len() >= 50);
        assert!(d.windows(2).all(|w| w[0].0 < w[1].0));
        assert_eq!(
            output_paths(Path::new("a/b.v2")).0,
            PathBuf::from("a/b.v2.svg")
        );
        assert_eq!(
            output_paths(Path::new("a/b.PNG")).1,
            PathBuf::from("a/b.png")
        );
    }
}
