//! How a [`Figure`] is drawn with plotters: the mesh and its tick labels, each series clipped
//! and thinned to the plotting area, the annotations and the legend.

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::clip::{Rect, clip_polygon, clip_polyline};
use super::simplify::douglas_peucker;
use super::{FONT, Figure, Kind, Legend, Marker, Series, palette};

/// The chart of a figure: f64 axes on a drawing backend.
type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// A drawing step's outcome.
type Drawn<T, DB> = Result<T, DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// How far in pixels a drawn line may pass from a point that thinning drops: plotters rounds
/// vertices to whole pixels, so a dense curve would otherwise zig-zag and its thick-line
/// joins would fringe.
const THIN_PX: f64 = 0.4;

/// The plotting area's bounds in data units and its pixels per unit on each axis: where a
/// series is clipped and how finely it is thinned.
struct Window {
    bounds: Rect,
    px_scale: (f64, f64),
}

impl Window {
    /// A polyline clipped to the window, each piece thinned to [`THIN_PX`].
    fn pieces(&self, pts: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
        clip_polyline(pts, &self.bounds)
            .into_iter()
            .map(|p| douglas_peucker(&p, self.px_scale, THIN_PX))
            .collect()
    }
}

impl Figure {
    /// Draws the figure on `area`: the title lines, the mesh, every series, the annotations,
    /// the legend.
    pub(super) fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Drawn<(), DB> {
        self.draw_reserving(area, 0)
    }

    /// The height in px of the legend strip below the axes on a panel `width` px wide (0
    /// without one).
    pub(super) fn strip_height(&self, width: u32) -> u32 {
        self.below_layout(&self.below_entries(), width).2
    }

    /// Draws the figure with a strip of at least `strip` px kept below the axes (panels of a
    /// grid row keep their axes aligned) for the legend.
    pub(super) fn draw_reserving<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        strip: u32,
    ) -> Drawn<(), DB> {
        let body = self.draw_header(area)?;
        let entries = self.below_entries();
        let (w, h) = body.dim_in_pixel();
        let strip = self.below_layout(&entries, w).2.max(strip).min(h / 2);
        let (plot_area, legend_area) = body.split_vertically(h - strip);
        let mut chart = self.chart(&plot_area)?;
        let ((x0, x1), (y0, y1)) = self.ranges();
        let (pw, ph) = chart.plotting_area().dim_in_pixel();
        let window = Window {
            bounds: Rect { x0, x1, y0, y1 },
            px_scale: (pw as f64 / (x1 - x0), ph as f64 / (y1 - y0)),
        };
        let mut labelled = false;
        for (i, series) in self.series.iter().enumerate() {
            let color = series
                .color
                .unwrap_or(palette::CYCLE[i % palette::CYCLE.len()]);
            labelled |= match series.kind {
                Kind::Line { dashed } => draw_line(&mut chart, &window, series, color, dashed)?,
                Kind::Polygon { alpha, outline } => {
                    draw_polygon(&mut chart, &window, series, color, (alpha, outline))?
                }
                Kind::Scatter { marker, filled } => {
                    draw_scatter(&mut chart, &window, series, color, (marker, filled))?
                }
            };
        }
        self.draw_annotations(&mut chart, &window.bounds)?;
        if labelled && !matches!(self.legend, Legend::Hidden | Legend::Below) {
            self.draw_legend(&mut chart)?;
        }
        self.draw_below(&legend_area, &entries)
    }

    /// The title and the subtitle, centred above the chart; returns the area below them.
    fn draw_header<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
    ) -> Drawn<DrawingArea<DB, Shift>, DB> {
        let width = area.dim_in_pixel().0;
        let mut body = area.clone();
        if !self.title.is_empty() {
            let size = fit_font(34.0 * self.font_scale, &self.title, width);
            body = body.titled(&self.title, (FONT, size).into_font())?;
        }
        if !self.subtitle.is_empty() {
            let size = fit_font(27.0 * self.font_scale, &self.subtitle, width);
            let style = (FONT, size).into_font().color(&RGBColor(60, 60, 60));
            body = body.titled(&self.subtitle, style)?;
        }
        Ok(body)
    }

    /// A font size in pixels at the figure's scale.
    pub(super) fn px(&self, v: f64) -> u32 {
        (v * self.font_scale).round().max(1.0) as u32
    }

    /// The chart on `area` with its title, axes, mesh and tick labels.
    fn chart<'a, DB: DrawingBackend>(
        &self,
        area: &'a DrawingArea<DB, Shift>,
    ) -> Drawn<Chart<'a, DB>, DB> {
        let px = |v: f64| self.px(v);
        let ((x0, x1), (y0, y1)) = self.ranges();
        let mut builder = ChartBuilder::on(area);
        builder
            .margin(px(14.0))
            .margin_right(px(28.0))
            .x_label_area_size(px(80.0))
            // a narrow log range's labels carry more digits (`narrow_ticks`)
            .y_label_area_size(px(if self.y_log10 && log_ticks(y0, y1).len() < 2 {
                175.0
            } else {
                120.0
            }));
        let mut chart = builder.build_cartesian_2d(x0..x1, y0..y1)?;
        let linear = tick_formatter(x0, x1);
        let xfmt = |v: &f64| match self.x_log10 {
            true => crate::text::sig(10f64.powf(*v), 3),
            false => linear(v),
        };
        let yfmt = tick_formatter(y0, y1);
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
            .y_labels(if self.y_log10 { 0 } else { 9 })
            .x_label_formatter(&xfmt)
            .y_label_formatter(&yfmt)
            .max_light_lines(4)
            .light_line_style(RGBColor(240, 240, 240))
            .bold_line_style(RGBColor(212, 212, 212))
            .axis_style(BLACK.stroke_width(2))
            .draw()?;
        if self.y_log10 {
            self.draw_log_y_ticks(&mut chart, (x0, x1), (y0, y1))?;
        }
        Ok(chart)
    }

    /// The ticks of a log y axis (the data are log10 of the quantity): grid lines and labels
    /// at 1, 2, 5 × 10ⁿ (only 10ⁿ over more than 4 decades, 1 … 9 × 10ⁿ within one).
    fn draw_log_y_ticks<'a, DB: DrawingBackend + 'a>(
        &self,
        chart: &mut Chart<'a, DB>,
        (x0, x1): (f64, f64),
        (y0, y1): (f64, f64),
    ) -> Drawn<(), DB> {
        let mut ticks = log_ticks(y0, y1);
        // a range too narrow for two 1 … 9 × 10ⁿ ticks gets evenly spaced round values, each
        // label with the digits that tell it from its neighbour
        let narrow = ticks.len() < 2;
        let step = if narrow {
            let (values, step) = narrow_ticks(y0, y1);
            ticks = values.into_iter().map(|v| (v, false)).collect();
            step
        } else {
            f64::NAN
        };
        let font = (FONT, self.px(25.0)).into_font();
        let style = font.color(&BLACK).pos(Pos::new(HPos::Right, VPos::Center));
        for (v, decade) in ticks {
            let ly = v.log10();
            let grey = if decade { 212 } else { 236 };
            chart.draw_series(std::iter::once(PathElement::new(
                vec![(x0, ly), (x1, ly)],
                RGBColor(grey, grey, grey).stroke_width(1),
            )))?;
            let label = if narrow {
                let digits = (v.abs() / step).log10().ceil().max(0.0) as usize + 1;
                crate::text::sig(v, digits)
            } else {
                log_tick_label(v)
            };
            let gap = -(self.px(12.0) as i32);
            chart.draw_series(std::iter::once(
                EmptyElement::at((x0, ly))
                    + PathElement::new(vec![(0, 0), (gap / 2, 0)], BLACK.stroke_width(1))
                    + Text::new(label, (gap, 0), style.clone()),
            ))?;
        }
        Ok(())
    }

    /// Every annotation whose anchor lies inside the plotting area.
    fn draw_annotations<'a, DB: DrawingBackend + 'a>(
        &self,
        chart: &mut Chart<'a, DB>,
        bounds: &Rect,
    ) -> Drawn<(), DB> {
        let font = (FONT, self.px(25.0)).into_font();
        let lift = self.px(8.0) as i32;
        for an in self.annotations.iter().filter(|a| bounds.contains(a.at)) {
            let style = font.clone().color(&an.color);
            if an.lift {
                chart.draw_series(std::iter::once(
                    EmptyElement::at(an.at)
                        + Text::new(
                            an.text.clone(),
                            (0, -lift),
                            style.pos(Pos::new(HPos::Left, VPos::Bottom)),
                        ),
                ))?;
            } else {
                chart.draw_series(std::iter::once(Text::new(
                    an.text.clone(),
                    an.at,
                    style.pos(Pos::new(HPos::Left, VPos::Center)),
                )))?;
            }
        }
        Ok(())
    }

    /// The legend of the labelled series, at the figure's corner.
    fn draw_legend<'a, DB: DrawingBackend + 'a>(&self, chart: &mut Chart<'a, DB>) -> Drawn<(), DB> {
        let pos = match self.legend {
            Legend::UpperLeft => SeriesLabelPosition::UpperLeft,
            Legend::UpperRight | Legend::Hidden | Legend::Below => SeriesLabelPosition::UpperRight,
            Legend::LowerLeft => SeriesLabelPosition::LowerLeft,
            Legend::LowerRight => SeriesLabelPosition::LowerRight,
        };
        chart
            .configure_series_labels()
            .position(pos)
            .margin(self.px(12.0))
            .legend_area_size(self.px(50.0))
            .label_font((FONT, self.px(25.0)))
            .background_style(WHITE.mix(0.88))
            .border_style(RGBColor(120, 120, 120))
            .draw()?;
        Ok(())
    }
}

/// A solid or dashed line, clipped and thinned; true when it has a legend entry.
fn draw_line<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    window: &Window,
    series: &Series,
    color: RGBColor,
    dashed: bool,
) -> Drawn<bool, DB> {
    let w = series.width.max(1);
    let line_style = color.stroke_width(w);
    let pieces = window.pieces(&series.points);
    if dashed {
        let (dash, gap) = ((4 * w + 6) as i32, (2 * w + 5) as i32);
        let a = chart.draw_series(
            pieces
                .into_iter()
                .map(|p| DashedPathElement::new(p, dash, gap, line_style)),
        )?;
        if let Some(l) = &series.label {
            a.label(l).legend(move |(x, y)| {
                DashedPathElement::new(vec![(x, y), (x + 36, y)], 9, 6, color.stroke_width(w))
            });
        }
    } else {
        let a = chart.draw_series(pieces.into_iter().map(|p| PathElement::new(p, line_style)))?;
        if let Some(l) = &series.label {
            a.label(l).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 36, y)], color.stroke_width(w))
            });
        }
    }
    Ok(series.label.is_some())
}

/// A filled polygon clipped to the window, outlined along its true edges only (not along the
/// clip window) when `outline`; true when it has a legend entry.
fn draw_polygon<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    window: &Window,
    series: &Series,
    color: RGBColor,
    (alpha, outline): (f64, bool),
) -> Drawn<bool, DB> {
    let poly = douglas_peucker(
        &clip_polygon(&series.points, &window.bounds),
        window.px_scale,
        THIN_PX,
    );
    if poly.len() < 3 {
        return Ok(false);
    }
    let a = chart.draw_series(std::iter::once(Polygon::new(
        poly,
        color.mix(alpha).filled(),
    )))?;
    if let Some(l) = &series.label {
        a.label(l).legend(move |(x, y)| {
            let fill = Rectangle::new([(0, -9), (36, 9)], color.mix(alpha).filled());
            let edge = Rectangle::new(
                [(0, -9), (36, 9)],
                color.stroke_width(if outline { 2 } else { 0 }),
            );
            EmptyElement::at((x, y)) + fill + edge
        });
    }
    if outline {
        let mut ring = series.points.clone();
        ring.push(series.points[0]);
        let line_style = color.stroke_width(series.width.max(1));
        chart.draw_series(
            window
                .pieces(&ring)
                .into_iter()
                .map(|p| PathElement::new(p, line_style)),
        )?;
    }
    Ok(series.label.is_some())
}

/// Markers at the points inside the window; true when the series has a legend entry.
fn draw_scatter<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    window: &Window,
    series: &Series,
    color: RGBColor,
    (marker, filled): (Marker, bool),
) -> Drawn<bool, DB> {
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
        .filter(|&p| window.bounds.contains(p))
        .collect();
    // One element type per marker (plotters' series need concrete types).
    macro_rules! scatter {
        ($p:ident => $e:expr) => {{
            let a = chart.draw_series(pts.iter().map(|&$p| $e))?;
            if let Some(l) = &series.label {
                a.label(l).legend(move |(x, y)| {
                    let $p = (x + 18, y);
                    $e
                });
            }
        }};
    }
    match marker {
        Marker::Circle => scatter!(p => Circle::new(p, r, style)),
        Marker::Square => {
            scatter!(p => EmptyElement::at(p) + Rectangle::new([(-r, -r), (r, r)], style))
        }
        Marker::Triangle => scatter!(p => TriangleMarker::new(p, r + 2, style)),
        Marker::Cross => scatter!(p => Cross::new(p, r, style.stroke_width(3))),
    }
    Ok(series.label.is_some())
}

/// The nominal font size for a one-line title: `nominal`, shrunk (not below 23, i.e. 18.5 px) so that
/// the text fits into `width` px (DejaVu Sans averages about 0.58 em per character; plotters
/// renders nominal/1.24 px).
pub(super) fn fit_font(nominal: f64, text: &str, width: u32) -> f64 {
    let chars = text.chars().count().max(1) as f64;
    let fit = (width as f64 - 40.0).max(1.0) * 1.24 / (0.58 * chars);
    nominal.min(fit).max(23.0).round()
}

/// The ticks of a log axis over log10 values lo … hi: (value, whether it is a power of
/// ten) at 1, 2, 5 × 10ⁿ; only 10ⁿ when that gives more than 12 (every k-th decade, at most
/// about 10), 1 … 9 × 10ⁿ when 1, 2, 5 give fewer than 3.
fn log_ticks(lo: f64, hi: f64) -> Vec<(f64, bool)> {
    let pick = |mantissas: &[f64]| -> Vec<(f64, bool)> {
        let (n0, n1) = (lo.floor() as i32, hi.ceil() as i32);
        (n0..=n1)
            .flat_map(|n| {
                mantissas
                    .iter()
                    .map(move |&m| (m * 10f64.powi(n), m == 1.0))
            })
            .filter(|(v, _)| (lo..=hi).contains(&v.log10()))
            .collect()
    };
    let t = pick(&[1.0, 2.0, 5.0]);
    if t.len() > 12 {
        // whole decades, every k-th over many of them
        let decades = pick(&[1.0]);
        let k = decades.len().div_ceil(10).max(1) as i32;
        decades
            .into_iter()
            .filter(|(v, _)| v.log10().round() as i32 % k == 0)
            .collect()
    } else if t.len() < 3 {
        pick(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0])
    } else {
        t
    }
}

/// Ticks of a log axis over [lo, hi] (log10 of the values) too narrow for two 1 … 9 × 10ⁿ
/// ticks: the multiples of a 1, 2 or 5 × 10ᵏ step, about five of them, with the step (none
/// for an empty range).
fn narrow_ticks(lo: f64, hi: f64) -> (Vec<f64>, f64) {
    let (a, b) = (10f64.powf(lo), 10f64.powf(hi));
    let raw = (b - a) / 5.0;
    if !(raw > 0.0 && raw.is_finite()) {
        return (Vec::new(), f64::NAN);
    }
    let magnitude = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * magnitude)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * magnitude);
    let (first, last) = ((a / step).ceil(), (b / step).floor());
    let count = (last - first).max(-1.0) as i64 + 1;
    let ticks = (0..count).map(|k| (first + k as f64) * step).collect();
    (ticks, step)
}

/// A log-axis tick label with its own engineering prefix: 500, 2k, 50k, 1M, 0.01.
fn log_tick_label(v: f64) -> String {
    let (scale, prefix) = match v {
        v if v >= 1e12 => (1e12, "T"),
        v if v >= 1e9 => (1e9, "G"),
        v if v >= 1e6 => (1e6, "M"),
        v if v >= 1e3 => (1e3, "k"),
        _ => (1.0, ""),
    };
    format!("{}{prefix}", crate::text::sig(v / scale, 3))
}

/// From this magnitude of an axis on, its tick labels carry an engineering prefix shared by
/// every tick (20k, 150k; 1.2M), so that nine fit side by side in a panel (stiffness axes in
/// N/m reach 10⁶) and no axis mixes 20000 with 1.2e5.
const TICK_PREFIX_FROM: f64 = 1e4;

/// Tick labels of an axis from lo to hi: up to 6 significant digits; values within 1e-9 of
/// the span of zero print as 0 (no "1e-17" at the origin); from [`TICK_PREFIX_FROM`] on, one
/// engineering prefix (k, M, G, T) for the whole axis.
fn tick_formatter(lo: f64, hi: f64) -> impl Fn(&f64) -> String {
    let span = hi - lo;
    let top = lo.abs().max(hi.abs());
    let (scale, prefix) = match top {
        t if t >= 1e12 => (1e12, "T"),
        t if t >= 1e9 => (1e9, "G"),
        t if t >= 1e6 => (1e6, "M"),
        t if t >= TICK_PREFIX_FROM => (1e3, "k"),
        _ => (1.0, ""),
    };
    move |v: &f64| {
        if v.abs() < 1e-9 * span.abs() {
            "0".to_string()
        } else {
            format!("{}{prefix}", crate::text::sig(*v / scale, 6))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{log_tick_label, log_ticks, narrow_ticks};

    #[test]
    fn a_narrow_log_range_gets_round_evenly_spaced_ticks() {
        // K_max from 9443.894 to 9443.918 N/m: no 1 … 9 × 10ⁿ value inside
        let (lo, hi) = (9443.894f64.log10(), 9443.918f64.log10());
        assert!(log_ticks(lo, hi).len() < 2);
        let (t, step) = narrow_ticks(lo, hi);
        assert!((step - 0.005).abs() < 1e-12, "{step}");
        assert_eq!(t.len(), 5, "{t:?}");
        assert!(
            (t[0] - 9443.895).abs() < 1e-6 && (t[4] - 9443.915).abs() < 1e-6,
            "{t:?}"
        );
    }

    #[test]
    fn log_ticks_at_one_two_five_per_decade() {
        let t: Vec<f64> = log_ticks(300f64.log10(), 70e3f64.log10())
            .into_iter()
            .map(|(v, _)| v)
            .collect();
        let want = [500.0, 1e3, 2e3, 5e3, 1e4, 2e4, 5e4];
        assert_eq!(t.len(), want.len(), "{t:?}");
        for (a, b) in t.iter().zip(want) {
            assert!((a / b - 1.0).abs() < 1e-12, "{t:?}");
        }
        let labels: Vec<String> = t.iter().map(|v| log_tick_label(*v)).collect();
        assert_eq!(labels, ["500", "1k", "2k", "5k", "10k", "20k", "50k"]);
        // 31 decades: whole decades only, every fourth (ceil(31 / 10)), evenly spaced
        let many: Vec<i32> = log_ticks(-27.0, 3.0)
            .into_iter()
            .map(|(v, d)| {
                assert!(d, "{v} is no power of ten");
                v.log10().round() as i32
            })
            .collect();
        assert_eq!(many, [-24, -20, -16, -12, -8, -4, 0]);
        // within one decade: 1 … 9
        assert_eq!(log_ticks(2.0f64.log10(), 8.5f64.log10()).len(), 7);
    }
}
