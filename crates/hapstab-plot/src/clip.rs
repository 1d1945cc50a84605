//! Clipping to the axis ranges (plotters does not clip): polylines by segment
//! (Liang–Barsky), polygons by Sutherland–Hodgman, markers by containment.

type Pt = (f64, f64);

#[derive(Debug, Clone, Copy)]
pub(super) struct Rect {
    pub(super) x0: f64,
    pub(super) x1: f64,
    pub(super) y0: f64,
    pub(super) y1: f64,
}

impl Rect {
    pub(super) fn contains(&self, (x, y): (f64, f64)) -> bool {
        x >= self.x0 && x <= self.x1 && y >= self.y0 && y <= self.y1
    }
}

/// Clips a polyline to the rectangle (Liang–Barsky per segment); NaN or infinite points
/// break it. Returns the visible pieces (each >= 2 points).
pub(super) fn clip_polyline(points: &[(f64, f64)], r: &Rect) -> Vec<Vec<(f64, f64)>> {
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

/// Does segment a–b meet the axis-aligned box [x0, x1] × [y0, y1] given as
/// `[x0, x1, y0, y1]`? (Liang–Barsky, via `clip_segment`; false for non-finite ends.)
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

/// Distance from `p` to the segment a–b (to a when the segment is a point).
pub fn segment_distance(p: Pt, a: Pt, b: Pt) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (px, py) = (p.0 - a.0, p.1 - a.1);
    let len2 = dx * dx + dy * dy;
    if len2 > 0.0 {
        let t = ((px * dx + py * dy) / len2).clamp(0.0, 1.0);
        (px - t * dx).hypot(py - t * dy)
    } else {
        px.hypot(py)
    }
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
pub(super) fn clip_polygon(points: &[(f64, f64)], r: &Rect) -> Vec<(f64, f64)> {
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

    use crate::{decimate_minmax, output_paths};
    use std::path::{Path, PathBuf};

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
