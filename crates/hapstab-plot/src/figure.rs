//! One plot panel: its title, axis labels, ranges, series, annotations and legend, with the
//! builders and the axis ranges fitted to the data.

use std::path::Path;

use super::save::{Saved, save_both};
use super::{DEFAULT_SIZE, PlotError, RGBColor, Result, Series, palette};

/// Where the legend goes: beneath the axes (covering no data), or inside the plotting area
/// at a corner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Legend {
    /// No legend.
    Hidden,
    /// Below the axes, in as many columns as fit (see `legend`): never covers data.
    Below,
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
    /// Written above the point (its bottom a few pixels over it) rather than centred on
    /// it: a tag lifted off a line drawn through the point.
    pub lift: bool,
}

/// One plot panel: title, axis labels, ranges, series, annotations and legend.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// Title above the plot (may be empty).
    pub title: String,
    /// A second, smaller title line (may be empty): which loop is shown.
    pub subtitle: String,
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
    /// The y data are log10 of the quantity (a log axis): ticks at 1, 2, 5 × 10ⁿ, labelled
    /// with the quantity.
    pub y_log10: bool,
}

impl Figure {
    /// An empty figure of [`DEFAULT_SIZE`] with the legend below the axes.
    pub fn new(title: impl Into<String>) -> Self {
        Self {
            title: title.into(),
            subtitle: String::new(),
            x_label: String::new(),
            y_label: String::new(),
            x_range: None,
            y_range: None,
            series: Vec::new(),
            annotations: Vec::new(),
            legend: Legend::Below,
            size: DEFAULT_SIZE,
            font_scale: 1.0,
            x_log10: false,
            y_log10: false,
        }
    }

    /// Sets the second title line.
    pub fn subtitle(mut self, s: impl Into<String>) -> Self {
        self.subtitle = s.into();
        self
    }

    /// Marks the y data as log10 of the quantity (a log axis, see [`Figure::y_log10`]).
    pub fn y_log10(mut self) -> Self {
        self.y_log10 = true;
        self
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
            lift: false,
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

    pub(super) fn check(&self) -> Result<()> {
        let ((x0, x1), (y0, y1)) = self.ranges();
        for (name, lo, hi) in [("x", x0, x1), ("y", y0, y1)] {
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(PlotError::Figure {
                    title: self.title.clone(),
                    what: format!("invalid {name} range [{lo}, {hi}]"),
                });
            }
        }
        Ok(())
    }
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
