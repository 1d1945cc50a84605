//! Plane geometry of the region computation: points, half-planes and convex clipping,
//! polygons (area, containment, distances).

use super::*;

pub(super) fn shoelace(v: &[WallPoint]) -> f64 {
    let n = v.len();
    let mut s = 0.0;
    for i in 0..n {
        let (p, q) = (v[i], v[(i + 1) % n]);
        s += p.a * q.b - q.a * p.b;
    }
    0.5 * s
}

pub(super) fn point_in(v: &[WallPoint], p: WallPoint) -> bool {
    let n = v.len();
    let mut inside = false;
    let mut j = n.wrapping_sub(1);
    for i in 0..n {
        let (a, b) = (v[i], v[j]);
        if (a.b > p.b) != (b.b > p.b) {
            let x = a.a + (p.b - a.b) / (b.b - a.b) * (b.a - a.a);
            if p.a < x {
                inside = !inside;
            }
        }
        j = i;
    }
    inside
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct P {
    pub(super) x: f64,
    pub(super) y: f64,
}

impl P {
    pub(super) fn ab(self) -> WallPoint {
        WallPoint {
            a: self.x,
            b: self.y,
        }
    }

    pub(super) fn of(p: WallPoint) -> Self {
        P { x: p.a, y: p.b }
    }

    pub(super) fn finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite()
    }

    pub(super) fn lerp(self, q: P, t: f64) -> P {
        P {
            x: self.x + t * (q.x - self.x),
            y: self.y + t * (q.y - self.y),
        }
    }
}

pub(super) fn sub(a: P, b: P) -> P {
    P {
        x: a.x - b.x,
        y: a.y - b.y,
    }
}

/// Euclidean length (plain square root: coordinates stay far below overflow).
pub(super) fn norm(a: P) -> f64 {
    (a.x * a.x + a.y * a.y).sqrt()
}

/// Distance along the ray m + t·dir (t > 0) to the first edge of the closed polyline other
/// than edge `skip`; None when the ray meets none.
pub(super) fn ray_exit(pts: &[P], skip: usize, m: P, dir: P) -> Option<f64> {
    let n = pts.len();
    (0..n)
        .filter(|&j| j != skip)
        .filter_map(|j| {
            let (q, e) = (pts[j], sub(pts[(j + 1) % n], pts[j]));
            let den = cross(dir, e);
            if den == 0.0 {
                return None;
            }
            let w = sub(q, m);
            let (t, s) = (cross(w, e) / den, cross(w, dir) / den);
            (t > 0.0 && (0.0..=1.0).contains(&s)).then_some(t)
        })
        .min_by(f64::total_cmp)
}

/// Distance from q to the segment ab.
pub(super) fn segment_distance(q: P, a: P, b: P) -> f64 {
    let ab = sub(b, a);
    let len2 = ab.x * ab.x + ab.y * ab.y;
    let t = if len2 > 0.0 {
        (((q.x - a.x) * ab.x + (q.y - a.y) * ab.y) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    norm(sub(q, a.lerp(b, t)))
}

pub(super) fn cross(a: P, b: P) -> f64 {
    a.x * b.y - a.y * b.x
}

/// The curve point at θ, with its exact end points at θ = 0 and θ = π (double roots at
/// z = ±1, see [`curve_end`]).
pub(super) fn point(fam: &AffineFamily, theta: f64) -> Option<P> {
    if theta <= 0.0 {
        return curve_end(fam, true).map(P::of);
    }
    if theta >= std::f64::consts::PI {
        return curve_end(fam, false).map(P::of);
    }
    curve_point(fam, theta).map(P::of)
}

/// The curve point at z = e^{iθ} strictly inside the upper half circle; near z = 1 from θ
/// (the shifted form needs w = e^{iθ} − 1 without the cancellation of z − 1).
pub(super) fn point_at(fam: &AffineFamily, theta: f64, z: Complex64) -> Option<P> {
    if theta < crate::closed_loop::SHIFTED_THETA {
        return curve_point(fam, theta).map(P::of);
    }
    curve_point_at(fam, z).map(P::of)
}

/// e^{iθ}.
pub(super) fn unit(theta: f64) -> Complex64 {
    let (s, c) = crate::circle::sin_cos(theta);
    Complex64::new(c, s)
}

/// A half-plane n·p <= c with the kind of its boundary line.
#[derive(Clone, Copy, Debug)]
pub(super) struct HalfPlane {
    pub(super) n: P,
    pub(super) c: f64,
    pub(super) kind: EdgeKind,
    /// The root line this half-plane comes from (z = ±1), for refining crossings on it.
    pub(super) line: Option<RootLine>,
}

impl HalfPlane {
    pub(super) fn value(&self, p: P) -> f64 {
        self.n.x * p.x + self.n.y * p.y - self.c
    }

    /// n·p ≤ c from n·p + c0 ... with the normal scaled to unit length.
    pub(super) fn normalized(n: P, c: f64, kind: EdgeKind, line: Option<RootLine>) -> Option<Self> {
        let len = norm(n);
        (len > 0.0 && len.is_finite() && c.is_finite()).then(|| HalfPlane {
            n: P {
                x: n.x / len,
                y: n.y / len,
            },
            c: c / len,
            kind,
            line,
        })
    }

    /// The stable side of a z = ±1 line: s·(p0 + a·pk + b·pb) > 0.
    pub(super) fn of_line(l: RootLine, kind: EdgeKind) -> Option<Self> {
        let s = l.stable_sign;
        Self::normalized(
            P {
                x: -s * l.pk,
                y: -s * l.pb,
            },
            s * l.p0,
            kind,
            Some(l),
        )
    }
}

/// A convex polygon: each vertex with the half-plane whose boundary carries the edge that
/// starts there.
pub(super) type Convex = Vec<(P, HalfPlane)>;

/// Where the boundary lines of two half-planes cross (Cramer's rule); None if parallel.
pub(super) fn line_meet(a: &HalfPlane, b: &HalfPlane) -> Option<P> {
    let det = a.n.x * b.n.y - a.n.y * b.n.x;
    if det == 0.0 {
        return None;
    }
    let p = P {
        x: (a.c * b.n.y - b.c * a.n.y) / det,
        y: (a.n.x * b.c - b.n.x * a.c) / det,
    };
    p.finite().then_some(p)
}

/// Clips a convex polygon by a half-plane (Sutherland–Hodgman). New vertices are the
/// crossings of the two boundary lines, not interpolations along the edge, so a polygon that
/// starts as a huge box keeps full precision near the origin.
pub(super) fn clip(poly: &Convex, h: &HalfPlane) -> Convex {
    let mut out = Vec::new();
    let n = poly.len();
    for i in 0..n {
        let (a, ea) = poly[i];
        let (b, _) = poly[(i + 1) % n];
        let (va, vb) = (h.value(a), h.value(b));
        if va <= 0.0 {
            out.push((a, ea));
        }
        if (va < 0.0 && vb > 0.0) || (va > 0.0 && vb < 0.0) {
            let x = line_meet(&ea, h).unwrap_or_else(|| a.lerp(b, va / (va - vb)));
            // The new point starts the cut edge when leaving, keeps the edge when entering.
            out.push((x, if va <= 0.0 { *h } else { ea }));
        }
    }
    out
}

pub(super) fn box_polygon(x0: f64, x1: f64, y0: f64, y1: f64) -> Convex {
    let h = box_halfplanes(x0, x1, y0, y1);
    // bottom (y ≥ y0), right (x ≤ x1), top (y ≤ y1), left (x ≥ x0), counter-clockwise
    vec![
        (P { x: x0, y: y0 }, h[2]),
        (P { x: x1, y: y0 }, h[1]),
        (P { x: x1, y: y1 }, h[3]),
        (P { x: x0, y: y1 }, h[0]),
    ]
}

pub(super) fn bbox(points: impl Iterator<Item = P>) -> Option<(f64, f64, f64, f64)> {
    crate::extent::Extent::of(points.map(|p| (p.x, p.y)))
        .map(|e| (e.x_min, e.x_max, e.y_min, e.y_max))
}
