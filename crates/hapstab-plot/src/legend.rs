//! The legend beneath the axes ([`Legend::Below`]): one entry per labelled series that draws
//! something inside the axis ranges (no entry for a series with nothing to show, none twice
//! for one label), laid out in as many columns as fit the panel's width, in a strip below the
//! x-axis label, so that it never covers data.

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::clip::{Rect, clip_polygon, clip_polyline};
use super::{FONT, Figure, Kind, Legend, Marker, RGBColor, palette};

/// One legend entry: the series' label, colour and what it draws.
#[derive(Debug, Clone)]
pub(super) struct Entry {
    label: String,
    color: RGBColor,
    kind: Kind,
    width: u32,
    size: u32,
}

/// Width of an entry's swatch and the gap before its text (px at scale 1).
const SWATCH: f64 = 36.0;
const GAP: f64 = 10.0;

impl Figure {
    /// The entries of the legend below the axes: labelled series with something inside the
    /// axis ranges, the first of each label only. Empty unless the legend is [`Legend::Below`].
    pub(super) fn below_entries(&self) -> Vec<Entry> {
        if self.legend != Legend::Below {
            return Vec::new();
        }
        let ((x0, x1), (y0, y1)) = self.ranges();
        let bounds = Rect { x0, x1, y0, y1 };
        let mut out: Vec<Entry> = Vec::new();
        for (i, s) in self.series.iter().enumerate() {
            let Some(label) = s.label.as_ref().filter(|l| !l.trim().is_empty()) else {
                continue;
            };
            let shown = match s.kind {
                Kind::Line { .. } => !clip_polyline(&s.points, &bounds).is_empty(),
                Kind::Polygon { .. } => clip_polygon(&s.points, &bounds).len() >= 3,
                Kind::Scatter { .. } => s.points.iter().any(|&p| bounds.contains(p)),
            };
            if !shown || out.iter().any(|e| &e.label == label) {
                continue;
            }
            out.push(Entry {
                label: label.clone(),
                color: s.color.unwrap_or(palette::CYCLE[i % palette::CYCLE.len()]),
                kind: s.kind,
                width: s.width.max(1),
                size: s.size.max(1),
            });
        }
        out
    }

    /// The legend's layout on a panel `width` px wide: columns, rows and the strip's height
    /// in px (0 without entries). Text is estimated at 0.6 em per character.
    pub(super) fn below_layout(&self, entries: &[Entry], width: u32) -> (usize, usize, u32) {
        if entries.is_empty() {
            return (0, 0, 0);
        }
        let s = self.font_scale;
        let col = self.column_width(entries);
        let avail = (width as f64 - 2.0 * 14.0 * s).max(col);
        let cols = ((avail / col).floor() as usize).clamp(1, entries.len());
        let rows = entries.len().div_ceil(cols);
        let height = (rows as f64 * 30.0 * s + 16.0 * s).round() as u32;
        (cols, rows, height)
    }

    fn column_width(&self, entries: &[Entry]) -> f64 {
        let s = self.font_scale;
        let em = 25.0 * s / 1.24;
        let chars = entries
            .iter()
            .map(|e| e.label.chars().count())
            .max()
            .unwrap_or(0) as f64;
        (SWATCH + GAP + 28.0) * s + 0.6 * em * chars
    }

    /// Draws the entries in `area` (the strip below the axes), centred, row by row.
    pub(super) fn draw_below<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        entries: &[Entry],
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let (cols, rows, _) = self.below_layout(entries, area.dim_in_pixel().0);
        if cols == 0 {
            return Ok(());
        }
        let s = self.font_scale;
        let col = self.column_width(entries);
        let (w, _) = area.dim_in_pixel();
        let used = col * cols.min(entries.len()) as f64;
        let left = ((w as f64 - used) / 2.0).max(0.0);
        let row_h = 30.0 * s;
        let top = 8.0 * s;
        let font = (FONT, self.px(25.0)).into_font();
        let box_w = used - 14.0 * s;
        area.draw(&Rectangle::new(
            [
                (left as i32, 2),
                (
                    (left + box_w) as i32,
                    (top * 2.0 + rows as f64 * row_h) as i32 - 2,
                ),
            ],
            RGBColor(150, 150, 150).stroke_width(1),
        ))?;
        for (k, e) in entries.iter().enumerate() {
            let (r, c) = (k / cols, k % cols);
            let x = (left + 10.0 * s + c as f64 * col) as i32;
            let y = (top + (r as f64 + 0.5) * row_h) as i32;
            swatch(area, e, (x, y), s)?;
            let at = (x + ((SWATCH + GAP) * s) as i32, y);
            let style = font.clone().color(&palette::BLACK);
            area.draw(&Text::new(
                e.label.clone(),
                at,
                style.pos(Pos::new(HPos::Left, VPos::Center)),
            ))?;
        }
        Ok(())
    }
}

/// The entry's swatch: a short line, a filled box, or one marker, starting at `(x, y)`.
fn swatch<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    e: &Entry,
    (x, y): (i32, i32),
    s: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let len = (SWATCH * s) as i32;
    let color = e.color;
    match e.kind {
        Kind::Line { dashed: false } => area.draw(&PathElement::new(
            vec![(x, y), (x + len, y)],
            color.stroke_width(e.width),
        )),
        Kind::Line { dashed: true } => area.draw(&DashedPathElement::new(
            vec![(x, y), (x + len, y)],
            9,
            6,
            color.stroke_width(e.width),
        )),
        Kind::Polygon { alpha, outline } => {
            let h = (9.0 * s) as i32;
            area.draw(&Rectangle::new(
                [(x, y - h), (x + len, y + h)],
                color.mix(alpha).filled(),
            ))?;
            if outline {
                area.draw(&Rectangle::new(
                    [(x, y - h), (x + len, y + h)],
                    color.stroke_width(2),
                ))?;
            }
            Ok(())
        }
        Kind::Scatter { marker, filled } => {
            let style = if filled {
                color.filled()
            } else {
                color.stroke_width(2)
            };
            let p = (x + len / 2, y);
            let r = e.size as i32;
            match marker {
                Marker::Circle => area.draw(&Circle::new(p, r, style)),
                Marker::Square => area.draw(&Rectangle::new(
                    [(p.0 - r, p.1 - r), (p.0 + r, p.1 + r)],
                    style,
                )),
                Marker::Triangle => area.draw(&TriangleMarker::new(p, r + 2, style)),
                Marker::Cross => area.draw(&Cross::new(p, r, style.stroke_width(3))),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::{Figure, Legend, Marker, Series};

    #[test]
    fn below_legend_skips_series_with_nothing_drawn_and_repeated_labels() {
        let mut f = Figure::new("t").x_range(0.0, 1.0).y_range(0.0, 1.0);
        f.add(Series::line([(0.1, 0.1), (0.9, 0.9)]).label("line"));
        f.add(Series::scatter([(5.0, 5.0)], Marker::Circle).label("outside"));
        f.add(Series::line([(0.2, 0.1), (0.3, 0.9)]).label("line"));
        f.add(Series::polygon([(2.0, 2.0), (3.0, 2.0), (3.0, 3.0)]).label("far polygon"));
        f.add(Series::scatter(Vec::new(), Marker::Cross).label("no points"));
        f.add(Series::line([(0.5, 0.5), (0.6, 0.6)]).label(" "));
        f.add(Series::polygon([(0.1, 0.1), (0.5, 0.1), (0.5, 0.5)]).label("region"));
        let labels: Vec<String> = f.below_entries().into_iter().map(|e| e.label).collect();
        assert_eq!(labels, ["line", "region"]);
        // the SVG holds each drawn entry's text once and none of the others
        let dir = tempfile::tempdir().unwrap();
        let saved = f.save(dir.path().join("l")).unwrap();
        let svg = std::fs::read_to_string(saved.svg).unwrap();
        let texts: Vec<&str> = svg
            .split("<text")
            .skip(1)
            .filter_map(|c| c.split_once('>'))
            .map(|(_, r)| r.split("</text>").next().unwrap_or("").trim())
            .collect();
        assert_eq!(texts.iter().filter(|t| **t == "line").count(), 1);
        assert_eq!(texts.iter().filter(|t| **t == "region").count(), 1);
        for gone in ["outside", "far polygon", "no points"] {
            assert!(!texts.contains(&gone), "{gone} in {texts:?}");
        }
        // no legend at a corner: nothing else is listed
        assert!(f.clone().legend(Legend::Hidden).below_entries().is_empty());
    }

    #[test]
    fn below_legend_takes_as_many_columns_as_fit() {
        let mut f = Figure::new("t").x_range(0.0, 1.0).y_range(0.0, 1.0);
        for l in ["a", "b", "c", "d"] {
            f.add(Series::line([(0.1, 0.1), (0.9, 0.9)]).label(l));
        }
        let e = f.below_entries();
        // four one-letter entries fit side by side on 900 px: one row
        assert_eq!(f.below_layout(&e, 900).0, 4);
        // on 150 px only one column fits: four rows, a taller strip
        let (cols, rows, h) = f.below_layout(&e, 150);
        assert_eq!((cols, rows), (1, 4));
        assert!(h > f.below_layout(&e, 900).2);
    }
}
