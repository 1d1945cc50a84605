//! The data series a figure draws (lines, polygons, markers) and their builders.

use super::RGBColor;

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

/// One data series of a [`Figure`](super::Figure).
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
