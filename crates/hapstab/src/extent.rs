//! The bounding box of a set of points in a plane (a region's polygons, a figure's curves):
//! one fold that the region's own geometry, its size and every front end's figure bounds use.

use serde::Serialize;

/// The smallest axis-aligned box holding a set of points (x horizontal, y vertical).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Extent {
    /// Smallest x.
    pub x_min: f64,
    /// Largest x.
    pub x_max: f64,
    /// Smallest y.
    pub y_min: f64,
    /// Largest y.
    pub y_max: f64,
}

impl Extent {
    /// The box of the points (None when there are none); NaN coordinates are skipped by the
    /// min/max fold unless every point has them.
    pub fn of(points: impl IntoIterator<Item = (f64, f64)>) -> Option<Self> {
        let mut points = points.into_iter();
        let (x, y) = points.next()?;
        let first = Self {
            x_min: x,
            x_max: x,
            y_min: y,
            y_max: y,
        };
        Some(points.fold(first, |e, (x, y)| Self {
            x_min: e.x_min.min(x),
            x_max: e.x_max.max(x),
            y_min: e.y_min.min(y),
            y_max: e.y_max.max(y),
        }))
    }

    /// The box's larger side.
    pub fn larger_side(&self) -> f64 {
        (self.x_max - self.x_min).max(self.y_max - self.y_min)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_of_points() {
        let e = Extent::of([(1.0, -2.0), (-3.0, 4.0), (0.5, 0.0)]).unwrap();
        assert_eq!((e.x_min, e.x_max, e.y_min, e.y_max), (-3.0, 1.0, -2.0, 4.0));
        assert_eq!(e.larger_side(), 6.0);
        assert!(Extent::of(std::iter::empty()).is_none());
    }
}
