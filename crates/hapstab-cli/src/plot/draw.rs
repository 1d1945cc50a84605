//! How a [`Figure`] is drawn with plotters: the mesh and its tick labels, each series clipped
//! and thinned to the plotting area, the annotations and the legend.

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::clip::{Rect, clip_polygon, clip_polyline};
use super::simplify::thin;
use super::{FONT, Figure, Kind, Legend, Marker, palette};

impl Figure {
    pub(super) fn draw<DB: DrawingBackend>(
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
        let linear = tick_formatter(x0, x1);
        let xfmt = |v: &f64| match self.x_log10 {
            true => crate::output::sig(10f64.powf(*v), 3),
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

/// The nominal font size for a one-line title: `nominal`, shrunk (not below 23, i.e. 18.5 px) so that
/// the text fits into `width` px (DejaVu Sans averages about 0.58 em per character; plotters
/// renders nominal/1.24 px).
pub(super) fn fit_font(nominal: f64, text: &str, width: u32) -> f64 {
    let chars = text.chars().count().max(1) as f64;
    let fit = (width as f64 - 40.0).max(1.0) * 1.24 / (0.58 * chars);
    nominal.min(fit).max(23.0).round()
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
            format!("{}{prefix}", crate::output::sig(*v / scale, 6))
        }
    }
}
