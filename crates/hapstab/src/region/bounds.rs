//! Steps 1 and 3 of the region method: the rigorous bounds that contain every stable wall,
//! and the search window cut from them around the curve.

use super::*;
use crate::param::Param;

/// Half-planes whose intersection contains every stable wall (see the module doc).
pub(super) struct Bounds {
    pub(super) halfplanes: Vec<HalfPlane>,
    /// Their intersection as a convex polygon.
    pub(super) polygon: Convex,
}

/// Start of the clipping: a box far beyond any wall value that the coefficient bounds leave
/// possible, yet far below overflow of products of coordinates.
pub(super) const HUGE: f64 = 1e150;

impl Bounds {
    pub(super) fn new(fam: &AffineFamily) -> Result<Self> {
        let mut halfplanes: Vec<HalfPlane> = Vec::new();
        if let Some(h) = plus_one_line(fam).and_then(|l| HalfPlane::of_line(l, EdgeKind::ZPlusOne))
        {
            halfplanes.push(h);
        }
        if let Some(h) =
            minus_one_line(fam).and_then(|l| HalfPlane::of_line(l, EdgeKind::ZMinusOne))
        {
            halfplanes.push(h);
        }
        halfplanes.extend(coefficient_slabs(fam));
        let mut polygon = box_polygon(-HUGE, HUGE, -HUGE, HUGE);
        for h in &halfplanes {
            polygon = clip(&polygon, h);
        }
        let unbounded = polygon
            .iter()
            .any(|(p, _)| p.x.abs() >= 0.5 * HUGE || p.y.abs() >= 0.5 * HUGE);
        if unbounded {
            return Err(Error::Invalid {
                param: Param::Loop,
                reason: "has a wall whose stiffness and damping act alike on every coefficient of \
                         p(z), so its stable set is unbounded and has no region to draw"
                    .into(),
            });
        }
        // Only the half-planes that carry an edge of the polygon bound it (and the z = ±1
        // lines, kept for their crossings): point tests then cost O(edges), not O(degree).
        let halfplanes = active_halfplanes(&polygon, &halfplanes);
        Ok(Self {
            halfplanes,
            polygon,
        })
    }

    /// Largest extent of the bounds' polygon.
    pub(super) fn size(&self) -> f64 {
        bbox(self.polygon.iter().map(|(p, _)| *p))
            .map_or(0.0, |(x0, x1, y0, y1)| (x1 - x0).max(y1 - y0))
    }

    /// Signed excess beyond the bounds (≤ 0 inside).
    pub(super) fn excess(&self, p: P) -> f64 {
        self.halfplanes
            .iter()
            .map(|h| h.value(p))
            .fold(f64::NEG_INFINITY, f64::max)
    }
}

/// The half-planes carrying an edge of a convex polygon, plus the root lines among `all`.
pub(super) fn active_halfplanes(polygon: &Convex, all: &[HalfPlane]) -> Vec<HalfPlane> {
    let mut out: Vec<HalfPlane> = all.iter().filter(|h| h.line.is_some()).copied().collect();
    for (_, h) in polygon {
        let known = out
            .iter()
            .any(|o| o.n == h.n && o.c == h.c && o.kind == h.kind);
        if !known {
            out.push(*h);
        }
    }
    out
}

/// Relative widening of the coefficient slabs (see [`coefficient_slabs`]).
pub(super) const SLAB_SLACK: f64 = 1e-3;

/// |c_j| ≤ C(n, j) for the monic p of degree n (Vieta: c_j is a sum of C(n, j) products of
/// roots, each of modulus < 1 when p is Schur stable), as pairs of half-planes.
pub(super) fn coefficient_slabs(fam: &AffineFamily) -> Vec<HalfPlane> {
    let n = fam.degree();
    let mut out = Vec::new();
    let mut binom = 1.0_f64;
    let p0 = fam.coefficients(0.0, 0.0);
    for (j, &c0) in p0.iter().enumerate().take(n) {
        if j > 0 {
            binom *= (n - j + 1) as f64 / j as f64;
        }
        let (k, b) = (
            fam.pk.get(j).copied().unwrap_or(0.0),
            fam.pb.get(j).copied().unwrap_or(0.0),
        );
        if (k == 0.0 && b == 0.0) || !binom.is_finite() {
            continue;
        }
        let dir = P { x: k, y: b };
        let neg = P { x: -k, y: -b };
        // Inflated a little: a stable region may touch |c_j| = C(n, j) at a corner (the pure
        // mass's (0, 2) has |c0| = 1), and a window edge must not run through that corner.
        let c = binom * (1.0 + SLAB_SLACK);
        out.extend(HalfPlane::normalized(dir, c - c0, EdgeKind::Window, None));
        out.extend(HalfPlane::normalized(neg, c + c0, EdgeKind::Window, None));
    }
    out
}

/// The window: a box around the curve points and line crossings inside the bounds, plus a
/// 5 % margin, clipped to the bounds. None when nothing can be stable.
pub(super) struct Window {
    pub(super) polygon: Convex,
    pub(super) size: f64,
}

pub(super) fn search_window(bounds: &Bounds, coarse: &[(f64, P)]) -> Option<Window> {
    if bounds.polygon.len() < 3 {
        return None;
    }
    let whole = bbox(bounds.polygon.iter().map(|(p, _)| *p))?;
    let wsize = (whole.1 - whole.0).max(whole.3 - whole.2);
    let slack = 1e-6 * wsize;
    let inside = coarse
        .iter()
        .map(|(_, p)| *p)
        .filter(|p| p.finite() && bounds.excess(*p) <= slack);
    let corners = line_crossing(bounds).into_iter();
    let (x0, x1, y0, y1) = bbox(inside.chain(corners)).unwrap_or(whole);
    let size = (x1 - x0).max(y1 - y0).max(1e-12 * wsize).max(1e-300);
    let margin = 0.05 * size;
    window_of_box(bounds, (x0 - margin, x1 + margin, y0 - margin, y1 + margin))
}

/// The window cut from the bounds by a box (None when they do not overlap).
pub(super) fn window_of_box(bounds: &Bounds, (x0, x1, y0, y1): BoxF) -> Option<Window> {
    let size = (x1 - x0).max(y1 - y0);
    let boxed = box_polygon(x0, x1, y0, y1);
    let mut polygon = boxed;
    for h in &bounds.halfplanes {
        polygon = clip(&polygon, h);
    }
    (polygon.len() >= 3).then_some(Window { polygon, size })
}

pub(super) fn box_halfplanes(x0: f64, x1: f64, y0: f64, y1: f64) -> Vec<HalfPlane> {
    let h = |x: f64, y: f64, c: f64| HalfPlane {
        n: P { x, y },
        c,
        kind: EdgeKind::Window,
        line: None,
    };
    vec![
        h(-1.0, 0.0, -x0),
        h(1.0, 0.0, x1),
        h(0.0, -1.0, -y0),
        h(0.0, 1.0, y1),
    ]
}

/// Where the z = 1 and z = −1 lines cross (a possible corner of a stable region), if inside
/// the bounds.
pub(super) fn line_crossing(bounds: &Bounds) -> Option<P> {
    let lines: Vec<&HalfPlane> = bounds
        .halfplanes
        .iter()
        .filter(|h| h.line.is_some())
        .collect();
    let [a, b] = lines.as_slice() else {
        return None;
    };
    let p = geometry::line_meet(a, b)?;
    (bounds.excess(p) <= 1e-9 * norm(p).max(1.0)).then_some(p)
}
