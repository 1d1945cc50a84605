//! Exact stable regions in the (α, β)-plane as closed polygons (Section V, Figs. 4–6).
//!
//! The boundary pieces come from [`crate::boundary`]: the complex-root curve C(θ), θ ∈ [0, π],
//! the z = 1 line α = −γ and the z = −1 line. Two necessary conditions of the Schur–Cohn test,
//! (−1)^{d+3} p(−1) > 0 and |p(0)| = |n0 β| < 1, and p(1) > 0 cut out a convex window K;
//! the curve, clipped to K, splits K into faces, in each of which the number of unstable roots
//! is constant. One Schur–Cohn test per face at an interior point classifies it. The curve is
//! sampled coarsely to build the arrangement, and the arcs of stable faces are then resampled
//! adaptively in θ until every chord is within `1e-10 × size` of the curve. Intersections are
//! refined on the curve itself (bisection in θ), so every vertex is a point where p(z) has a
//! root on the unit circle.

use num_complex::Complex64;
use rayon::prelude::*;
use serde::Serialize;

use crate::boundary::{AlphaBeta, curve_point, minus_one_line};
use crate::closed_loop::PolyFamily;
use crate::stability::schur_stable;

/// What an edge of a region polygon is made of.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum EdgeKind {
    /// The line α = −γ: a real root at z = 1.
    ZPlusOne,
    /// The line α + 2β = c: a real root at z = −1.
    ZMinusOne,
    /// The complex-pair curve between angles θ0 and θ1 (root pair at e^{±iθ}).
    Complex {
        /// Angle at the edge's first vertex.
        theta_start: f64,
        /// Angle at the edge's last vertex.
        theta_end: f64,
    },
    /// A cut of the search window (never part of a correct stable region; kept for honesty).
    Window,
}

/// One edge of a polygon: its kind and the index of its first vertex.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Edge {
    /// Index in `vertices` of the edge's first vertex; it runs to the next edge's first vertex.
    pub start: usize,
    /// What the edge is.
    pub kind: EdgeKind,
}

/// A closed, counter-clockwise polygon (first vertex not repeated).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Polygon {
    /// Vertices in counter-clockwise order.
    pub vertices: Vec<AlphaBeta>,
    /// Edges in order; edge i covers vertices edges[i].start ..= edges[i+1].start.
    pub edges: Vec<Edge>,
    /// For each vertex on a complex-pair arc, the angle θ of the root pair e^{±iθ} on the
    /// unit circle there; NaN for vertices on the z = ±1 lines only.
    pub thetas: Vec<f64>,
}

impl Polygon {
    /// Signed area by the shoelace formula (positive for counter-clockwise).
    pub fn area(&self) -> f64 {
        shoelace(&self.vertices)
    }

    /// True iff the point lies inside (even-odd rule).
    pub fn contains(&self, p: AlphaBeta) -> bool {
        point_in(&self.vertices, p)
    }

    /// Indices of vertices where two edges meet (corners).
    pub fn corners(&self) -> Vec<usize> {
        self.edges.iter().map(|e| e.start).collect()
    }
}

/// The stable region for fixed (γ, δ, d): every stable component as a polygon, α_max and where
/// it is reached, and the total area.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StableRegion {
    /// Stable components (possibly none).
    pub polygons: Vec<Polygon>,
    /// Largest stable α (NaN when the region is empty).
    pub alpha_max: f64,
    /// β at which α_max is reached (NaN when empty).
    pub beta_at_alpha_max: f64,
    /// Total area of the stable region in the (α, β)-plane.
    pub area: f64,
}

impl StableRegion {
    /// True iff (α, β) lies inside one of the polygons.
    pub fn contains(&self, p: AlphaBeta) -> bool {
        self.polygons.iter().any(|q| q.contains(p))
    }
}

fn shoelace(v: &[AlphaBeta]) -> f64 {
    let n = v.len();
    let mut s = 0.0;
    for i in 0..n {
        let (p, q) = (v[i], v[(i + 1) % n]);
        s += p.alpha * q.beta - q.alpha * p.beta;
    }
    0.5 * s
}

fn point_in(v: &[AlphaBeta], p: AlphaBeta) -> bool {
    let n = v.len();
    let mut inside = false;
    let mut j = n.wrapping_sub(1);
    for i in 0..n {
        let (a, b) = (v[i], v[j]);
        if (a.beta > p.beta) != (b.beta > p.beta) {
            let x = a.alpha + (p.beta - a.beta) / (b.beta - a.beta) * (b.alpha - a.alpha);
            if p.alpha < x {
                inside = !inside;
            }
        }
        j = i;
    }
    inside
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct P {
    x: f64,
    y: f64,
}

impl P {
    fn ab(self) -> AlphaBeta {
        AlphaBeta {
            alpha: self.x,
            beta: self.y,
        }
    }
}

fn sub(a: P, b: P) -> P {
    P {
        x: a.x - b.x,
        y: a.y - b.y,
    }
}

/// Euclidean length (plain square root: coordinates stay far below overflow).
fn norm(a: P) -> f64 {
    (a.x * a.x + a.y * a.y).sqrt()
}

fn cross(a: P, b: P) -> f64 {
    a.x * b.y - a.y * b.x
}

/// R(z) = z^d D(z)/N(z) and R'(z) at a real point z = ±1 (for the curve's end points).
fn r_and_derivative(fam: &PolyFamily, z: f64) -> Option<(f64, f64)> {
    let pl = &fam.plant;
    let d = fam.d as i32;
    let n = pl.n1 * z + pl.n0;
    if n.abs() < 1e-300 {
        return None;
    }
    let dz = z * z - pl.a1 * z + pl.a0;
    let ddz = 2.0 * z - pl.a1;
    let zd = z.powi(d);
    let zd1 = if d == 0 {
        0.0
    } else {
        d as f64 * z.powi(d - 1)
    };
    let r = zd * dz / n;
    let rp = (zd1 * dz + zd * ddz) / n - zd * dz * pl.n1 / (n * n);
    Some((r, rp))
}

/// The curve point at θ, with the exact limits at θ = 0 (on α = −γ) and θ = π (on the z = −1
/// line) from l'Hôpital's rule: C(0) = (−R(1), −R'(1)), C(π) = (2R'(−1) − R(−1), −R'(−1)).
fn point(fam: &PolyFamily, theta: f64) -> Option<P> {
    if theta <= 0.0 {
        let (r, rp) = r_and_derivative(fam, 1.0)?;
        return Some(P { x: -r, y: -rp });
    }
    if theta >= std::f64::consts::PI {
        let (r, rp) = r_and_derivative(fam, -1.0)?;
        return Some(P {
            x: 2.0 * rp - r,
            y: -rp,
        });
    }
    curve_point(fam, theta).map(|p| P {
        x: p.alpha,
        y: p.beta,
    })
}

/// The curve point at z = e^{iθ} strictly inside the upper half circle.
fn point_at(fam: &PolyFamily, z: Complex64) -> Option<P> {
    crate::boundary::curve_point_at(fam, z).map(|p| P {
        x: p.alpha,
        y: p.beta,
    })
}

/// e^{iθ}, or the exact end points for θ = 0 and θ = π.
fn unit(theta: f64) -> Complex64 {
    let (s, c) = theta.sin_cos();
    Complex64::new(c, s)
}

/// Adaptive sampling of the curve on [t0, t1]: bisect until the midpoint lies within `tol` of
/// the chord; coarse passes (finite `maxlen`) refine only where |β| <= maxlen. Appends points
/// after t0 (t1 included).
#[allow(clippy::too_many_arguments)]
fn sample(
    fam: &PolyFamily,
    t0: f64,
    p0: P,
    t1: f64,
    p1: P,
    tol: f64,
    maxlen: f64,
    depth: u32,
    out: &mut Vec<(f64, P)>,
) {
    sample_z(
        fam,
        (t0, unit(t0), p0),
        (t1, unit(t1), p1),
        tol,
        maxlen,
        depth,
        out,
    );
}

/// [`sample`] carrying z = e^{iθ}: the midpoint of an arc is (z0 + z1)/|z0 + z1| and k equal
/// parts are powers of e^{iΔθ}, so no sine or cosine is evaluated per point.
fn sample_z(
    fam: &PolyFamily,
    a: (f64, Complex64, P),
    b: (f64, Complex64, P),
    tol: f64,
    maxlen: f64,
    depth: u32,
    out: &mut Vec<(f64, P)>,
) {
    let ((t0, z0, p0), (t1, z1, p1)) = (a, b);
    let tm = 0.5 * (t0 + t1);
    let zs = z0 + z1;
    let zm = zs / zs.norm();
    // Coarse passes (finite maxlen) only refine near the |β| < band of possible stability.
    let relevant = maxlen.is_infinite() || p0.y.abs().min(p1.y.abs()) <= maxlen;
    if depth < 48
        && relevant
        && zm.im > 0.0
        && let Some(pm) = point_at(fam, zm)
    {
        let ch = sub(p1, p0);
        // Fast accept (fine passes): deviation within tol and the midpoint projecting into
        // [−1/4, 5/4] of the chord, tested without square roots.
        let q = sub(pm, p0);
        let len2 = ch.x * ch.x + ch.y * ch.y;
        if maxlen.is_infinite() && len2 > 0.0 {
            let c = cross(ch, q);
            let t = (q.x * ch.x + q.y * ch.y) / len2;
            if c * c <= tol * tol * len2 && (-0.25..=1.25).contains(&t) {
                out.push((t1, p1));
                return;
            }
        }
        let len = len2.sqrt();
        let dev = if len > 0.0 {
            cross(ch, sub(pm, p0)).abs() / len
        } else {
            norm(sub(pm, p0))
        };
        let far = norm(sub(pm, p0)) + norm(sub(pm, p1));
        // Coarse passes also bound the chord length near the band, so that a chord to a
        // far point (the curve runs to infinity where N(e^{iθ}) = 0) cannot hide a turn.
        let long = maxlen.is_finite() && depth < 30 && len > 0.25 * maxlen;
        if dev > tol || far > 1.5 * len + tol || long {
            // Split into k parts so that each chord's deviation (∝ length²) meets tol.
            let k = if far > 1.5 * len + tol || long || depth > 8 {
                2
            } else {
                ((dev / tol).sqrt().ceil() as usize).clamp(2, 64)
            };
            if k == 2 {
                sample_z(fam, a, (tm, zm, pm), tol, maxlen, depth + 1, out);
                sample_z(fam, (tm, zm, pm), b, tol, maxlen, depth + 1, out);
                return;
            }
            let w = unit((t1 - t0) / k as f64);
            let mut prev = a;
            let mut z = z0;
            for i in 1..=k {
                let next = if i == k {
                    b
                } else {
                    z *= w;
                    let Some(p) = point_at(fam, z) else { break };
                    (t0 + (t1 - t0) * i as f64 / k as f64, z, p)
                };
                sample_z(fam, prev, next, tol, maxlen, depth + 1, out);
                prev = next;
            }
            return;
        }
    }
    out.push((t1, p1));
}

/// A half-plane n·p <= c with the kind of its boundary line.
#[derive(Clone, Copy, Debug)]
struct HalfPlane {
    n: P,
    c: f64,
    kind: EdgeKind,
}

/// Clips a convex polygon (with edge labels) by a half-plane (Sutherland–Hodgman).
fn clip(poly: &[(P, EdgeKind)], h: HalfPlane) -> Vec<(P, EdgeKind)> {
    let mut out = Vec::new();
    let n = poly.len();
    let val = |p: P| h.n.x * p.x + h.n.y * p.y - h.c;
    for i in 0..n {
        let (a, ka) = poly[i];
        let (b, _) = poly[(i + 1) % n];
        let (va, vb) = (val(a), val(b));
        if va <= 0.0 {
            out.push((a, ka));
        }
        if (va < 0.0 && vb > 0.0) || (va > 0.0 && vb < 0.0) {
            let t = va / (va - vb);
            let x = P {
                x: a.x + t * (b.x - a.x),
                y: a.y + t * (b.y - a.y),
            };
            // The new point starts the cut edge when leaving, keeps ka when entering.
            out.push((x, if va <= 0.0 { h.kind } else { ka }));
        }
    }
    out
}

/// A polyline segment of the arrangement.
#[derive(Clone, Copy, Debug)]
struct Seg {
    p: P,
    q: P,
    /// Curve: θ at p and q; border: NaN.
    tp: f64,
    tq: f64,
    /// Chain id (curve chains) or usize::MAX - edge index (border).
    owner: usize,
    /// Index within the owner.
    idx: usize,
    kind: EdgeKind,
}

const BORDER: usize = usize::MAX / 2;

fn seg_intersect(a: &Seg, b: &Seg) -> Option<(f64, f64)> {
    let r = sub(a.q, a.p);
    let s = sub(b.q, b.p);
    let den = cross(r, s);
    if den == 0.0 {
        return None;
    }
    let qp = sub(b.p, a.p);
    let t = cross(qp, s) / den;
    let u = cross(qp, r) / den;
    if (0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&u) {
        Some((t, u))
    } else {
        None
    }
}

/// Refines a curve–curve crossing by repeated halving of both θ-intervals.
fn refine_cc(fam: &PolyFamily, a: &Seg, b: &Seg) -> (P, f64, f64) {
    let (mut a, mut b) = (*a, *b);
    for _ in 0..60 {
        let split = |s: &Seg| -> Option<[Seg; 2]> {
            let tm = 0.5 * (s.tp + s.tq);
            let pm = point(fam, tm)?;
            Some([
                Seg {
                    q: pm,
                    tq: tm,
                    ..*s
                },
                Seg {
                    p: pm,
                    tp: tm,
                    ..*s
                },
            ])
        };
        let (Some(sa), Some(sb)) = (split(&a), split(&b)) else {
            break;
        };
        let mut found = false;
        'o: for x in &sa {
            for y in &sb {
                if seg_intersect(x, y).is_some() {
                    a = *x;
                    b = *y;
                    found = true;
                    break 'o;
                }
            }
        }
        if !found || (a.tq - a.tp).abs() < 1e-16 && (b.tq - b.tp).abs() < 1e-16 {
            break;
        }
    }
    let (t, u) = seg_intersect(&a, &b).unwrap_or((0.5, 0.5));
    let p = P {
        x: a.p.x + t * (a.q.x - a.p.x),
        y: a.p.y + t * (a.q.y - a.p.y),
    };
    (p, a.tp + t * (a.tq - a.tp), b.tp + u * (b.tq - b.tp))
}

/// Refines a curve–line crossing by bisection in θ on the signed distance to the line.
fn refine_cl(fam: &PolyFamily, a: &Seg, h: &HalfPlane) -> (P, f64) {
    let f = |t: f64| point(fam, t).map_or(f64::NAN, |p| h.n.x * p.x + h.n.y * p.y - h.c);
    let (mut lo, mut hi) = (a.tp, a.tq);
    let flo = f(lo);
    for _ in 0..200 {
        let m = 0.5 * (lo + hi);
        if m == lo || m == hi {
            break;
        }
        let fm = f(m);
        if fm.is_nan() {
            break;
        }
        if (fm > 0.0) == (flo > 0.0) {
            lo = m;
        } else {
            hi = m;
        }
    }
    let t = 0.5 * (lo + hi);
    let mut p = point(fam, t).unwrap_or(a.p);
    // Put the vertex exactly on the line (the residual is below rounding of the curve).
    let nn = h.n.x * h.n.x + h.n.y * h.n.y;
    let r = (h.n.x * p.x + h.n.y * p.y - h.c) / nn;
    p.x -= r * h.n.x;
    p.y -= r * h.n.y;
    (p, t)
}

/// A cut on a segment: parameter along it, vertex id, θ (curve) or NaN.
type Cut = (f64, usize, f64);

/// Graph edge: end vertex ids, polyline (θ, point) and kind.
type GraphEdge = (usize, usize, Vec<(f64, P)>, EdgeKind);

struct Graph {
    verts: Vec<P>,
    /// Edges: vertex ids, polyline (with θ for curve points), kind.
    edges: Vec<GraphEdge>,
}

/// Computes the stable region of p(z) for fixed (γ, δ, d) (Section V; Figs. 4–6).
pub fn stable_region(fam: &PolyFamily) -> StableRegion {
    stable_region_with(fam, DEFAULT_REL_TOL)
}

/// Default chord tolerance of region polygons, relative to the stable region's size.
pub const DEFAULT_REL_TOL: f64 = 1e-9;

/// As [`stable_region`] with a chord tolerance relative to the region's size.
pub fn stable_region_with(fam: &PolyFamily, rel_tol: f64) -> StableRegion {
    let pi = std::f64::consts::PI;
    let gamma = fam.plant.gamma;
    // |p(0)| = |n0 β| < 1 and p(1) > 0 and the z = −1 condition: the window K.
    let n0 = fam.plant.n0.abs().max(1e-300);
    let bmax = 1.0 / n0;
    // Coarse curve samples: a uniform θ grid, each interval refined adaptively (in parallel).
    let m = 64 * (fam.d + 2);
    let knots: Vec<(f64, Option<P>)> = (0..=m)
        .into_par_iter()
        .map(|i| {
            let t = pi * i as f64 / m as f64;
            match point(fam, t) {
                // Where N(−1) = 0 (δ = 0) the curve runs to infinity as θ → π: end just
                // short of it so that the last interval is still sampled (the far tail is cut
                // off below).
                None if i == m => {
                    let t = pi * (1.0 - 1e-12);
                    (t, point(fam, t))
                }
                p => (t, p),
            }
        })
        .collect();
    let pieces: Vec<Vec<(f64, P)>> = knots
        .par_windows(2)
        .with_min_len(8)
        .map(|w| {
            let mut out = Vec::new();
            match (w[0], w[1]) {
                ((t0, Some(p0)), (t1, Some(p1))) => {
                    sample(fam, t0, p0, t1, p1, 1e-3 * bmax, 1.5 * bmax, 0, &mut out)
                }
                // a gap (no point): the next piece starts afresh at its own first knot
                ((_, None), (t1, Some(p1))) => out.push((t1, p1)),
                _ => {}
            }
            out
        })
        .collect();
    let mut coarse: Vec<(f64, P)> = Vec::new();
    if let (t0, Some(p0)) = knots[0] {
        coarse.push((t0, p0));
    }
    for piece in pieces {
        coarse.extend(piece);
    }
    let mline = minus_one_line(fam);
    // α extent of the window. Every boundary point of the region with |β| < bmax is a curve
    // point or a crossing of the curve with a line, so the coarse curve bounds it (plus a
    // margin). A rigorous cap: a monic Schur-stable polynomial has |c_k| < C(n, k), so the
    // z² coefficient bounds |α + β| < (C(n, 2) + |a0| + |a1|)/|n1|.
    let nn = fam.degree() as f64;
    let pl = &fam.plant;
    let a_rig =
        (nn * (nn - 1.0) / 2.0 + pl.a0.abs() + pl.a1.abs()) / pl.n1.abs().max(1e-300) + bmax;
    let mut amax = -gamma;
    for (_, p) in &coarse {
        if p.y.abs() <= 1.05 * bmax && p.x.is_finite() {
            amax = amax.max(p.x);
        }
    }
    let amax = amax.min(a_rig);
    let size = (amax + gamma).max(2.0 * bmax).max(1e-300);
    let margin = 0.05 * size;
    let (x0, x1, y0, y1) = (
        -gamma - margin,
        amax + margin,
        -bmax - margin,
        bmax + margin,
    );
    let mut window: Vec<(P, EdgeKind)> = vec![
        (P { x: x0, y: y0 }, EdgeKind::Window),
        (P { x: x1, y: y0 }, EdgeKind::Window),
        (P { x: x1, y: y1 }, EdgeKind::Window),
        (P { x: x0, y: y1 }, EdgeKind::Window),
    ];
    let h1 = HalfPlane {
        n: P { x: -1.0, y: 0.0 },
        c: gamma,
        kind: EdgeKind::ZPlusOne,
    };
    window = clip(&window, h1);
    let mut halfplanes = vec![h1];
    if let Some((a, c)) = mline {
        let pl = &fam.plant;
        let nm1 = pl.n0 - pl.n1;
        let s = if (fam.d + 1).is_multiple_of(2) {
            nm1
        } else {
            -nm1
        };
        // s(α + 2β) < D(−1)·sign: α + aβ < c when s > 0, > c when s < 0.
        let h = if s > 0.0 {
            HalfPlane {
                n: P { x: 1.0, y: a },
                c,
                kind: EdgeKind::ZMinusOne,
            }
        } else {
            HalfPlane {
                n: P { x: -1.0, y: -a },
                c: -c,
                kind: EdgeKind::ZMinusOne,
            }
        };
        window = clip(&window, h);
        halfplanes.push(h);
    }
    let empty = StableRegion {
        polygons: Vec::new(),
        alpha_max: f64::NAN,
        beta_at_alpha_max: f64::NAN,
        area: 0.0,
    };
    if window.len() < 3 {
        return empty;
    }
    let inside_k = |p: P, slack: f64| {
        halfplanes
            .iter()
            .all(|h| h.n.x * p.x + h.n.y * p.y - h.c <= slack)
            && p.x >= x0 - slack
            && p.x <= x1 + slack
            && p.y >= y0 - slack
            && p.y <= y1 + slack
    };
    // Chains: split the coarse curve where it leaves a generous box (poles of R).
    let big = 1e3 * size;
    let lim = P {
        x: big + x1.abs(),
        y: big + bmax,
    };
    let inside_big =
        |p: P| p.x.is_finite() && p.y.is_finite() && p.x.abs() < lim.x && p.y.abs() < lim.y;
    // Cut the chord p→q where it leaves the big box (q outside, p inside).
    let exit = |(tp, p): (f64, P), (tq, q): (f64, P)| -> (f64, P) {
        let mut s: f64 = 1.0;
        for (a, b, l) in [(p.x, q.x, lim.x), (p.y, q.y, lim.y)] {
            if b.is_finite() && b.abs() >= l && a != b {
                let bound = if b > 0.0 { l } else { -l };
                s = s.min((bound - a) / (b - a));
            }
        }
        let s = if s.is_finite() {
            s.clamp(0.0, 1.0)
        } else {
            0.0
        };
        (
            tp + s * (tq - tp),
            P {
                x: p.x + s * (q.x - p.x),
                y: p.y + s * (q.y - p.y),
            },
        )
    };
    let mut chains: Vec<Vec<(f64, P)>> = Vec::new();
    let mut cur: Vec<(f64, P)> = Vec::new();
    let mut last: Option<(f64, P)> = None;
    for &(t, p) in &coarse {
        let ok = inside_big(p);
        let contiguous = last.is_none_or(|(lt, _)| (t - lt) < 2.0 * pi / m as f64);
        let prev_ok = last.is_some_and(|(_, lp)| inside_big(lp));
        if !contiguous {
            if cur.len() >= 2 {
                chains.push(std::mem::take(&mut cur));
            } else {
                cur.clear();
            }
        } else if ok && !prev_ok && p.x.is_finite() && p.y.is_finite() {
            // entering the big box: start at the crossing
            if let Some(l) = last.filter(|(_, lp)| lp.x.is_finite() && lp.y.is_finite()) {
                cur.push(exit((t, p), l));
            }
        } else if !ok && prev_ok {
            if p.x.is_finite()
                && p.y.is_finite()
                && let Some(l) = last
            {
                cur.push(exit(l, (t, p)));
            }
            if cur.len() >= 2 {
                chains.push(std::mem::take(&mut cur));
            } else {
                cur.clear();
            }
        }
        if ok {
            cur.push((t, p));
        }
        last = Some((t, p));
    }
    if cur.len() >= 2 {
        chains.push(cur);
    }
    // Segments.
    let mut segs: Vec<Seg> = Vec::new();
    for (ci, ch) in chains.iter().enumerate() {
        for (i, w) in ch.windows(2).enumerate() {
            segs.push(Seg {
                p: w[0].1,
                q: w[1].1,
                tp: w[0].0,
                tq: w[1].0,
                owner: ci,
                idx: i,
                kind: EdgeKind::Complex {
                    theta_start: w[0].0,
                    theta_end: w[1].0,
                },
            });
        }
    }
    let nw = window.len();
    for i in 0..nw {
        segs.push(Seg {
            p: window[i].0,
            q: window[(i + 1) % nw].0,
            tp: f64::NAN,
            tq: f64::NAN,
            owner: BORDER,
            idx: i,
            kind: window[i].1,
        });
    }
    // Vertices: window corners and chain ends.
    let mut verts: Vec<P> = window.iter().map(|w| w.0).collect();
    let mut cuts: Vec<Vec<Cut>> = vec![Vec::new(); segs.len()];
    let mut chain_ends: Vec<(usize, usize)> = Vec::new();
    for ch in &chains {
        let a = verts.len();
        verts.push(ch[0].1);
        let b = verts.len();
        verts.push(ch[ch.len() - 1].1);
        chain_ends.push((a, b));
    }
    // Chain ends lying on a window edge become cuts of that edge.
    let nseg_curve = segs.len() - nw;
    for (ci, ch) in chains.iter().enumerate() {
        for (end, vid) in [
            (ch[0].1, chain_ends[ci].0),
            (ch[ch.len() - 1].1, chain_ends[ci].1),
        ] {
            for k in 0..nw {
                let s = &segs[nseg_curve + k];
                let d = sub(s.q, s.p);
                let len2 = d.x * d.x + d.y * d.y;
                let t = ((end.x - s.p.x) * d.x + (end.y - s.p.y) * d.y) / len2;
                let dist = cross(d, sub(end, s.p)).abs() / len2.sqrt();
                if dist <= 1e-12 * size && t > 0.0 && t < 1.0 {
                    cuts[nseg_curve + k].push((t, vid, f64::NAN));
                }
            }
        }
    }
    // Pairwise intersections by sweep over α-sorted bounding boxes.
    let mut order: Vec<usize> = (0..segs.len()).collect();
    let lo = |s: &Seg| s.p.x.min(s.q.x);
    let hi = |s: &Seg| s.p.x.max(s.q.x);
    order.sort_by(|&i, &j| lo(&segs[i]).total_cmp(&lo(&segs[j])));
    let mut active: Vec<usize> = Vec::new();
    for &i in &order {
        let si = segs[i];
        active.retain(|&j| hi(&segs[j]) >= lo(&si));
        for &j in &active {
            let sj = segs[j];
            if si.owner == sj.owner && (si.owner == BORDER || si.idx.abs_diff(sj.idx) <= 1) {
                continue;
            }
            if si.p.y.max(si.q.y) < sj.p.y.min(sj.q.y) || sj.p.y.max(sj.q.y) < si.p.y.min(si.q.y) {
                continue;
            }
            let Some((t, u)) = seg_intersect(&si, &sj) else {
                continue;
            };
            let (ci, cj) = (si.owner != BORDER, sj.owner != BORDER);
            let vid = verts.len();
            match (ci, cj) {
                (true, true) => {
                    let (p, ti, tj) = refine_cc(fam, &si, &sj);
                    verts.push(p);
                    cuts[i].push((t, vid, ti));
                    cuts[j].push((u, vid, tj));
                }
                (true, false) | (false, true) => {
                    let (c, b, tc, tb) = if ci { (i, j, t, u) } else { (j, i, u, t) };
                    let sc = &segs[c];
                    let raw = P {
                        x: sc.p.x + tc * (sc.q.x - sc.p.x),
                        y: sc.p.y + tc * (sc.q.y - sc.p.y),
                    };
                    let at_end = chain_ends.iter().any(|&(a, e)| {
                        [a, e].iter().any(|&v| {
                            let q = verts[v];
                            (q.x - raw.x).abs() + (q.y - raw.y).abs() <= 1e-9 * size
                        })
                    });
                    if at_end {
                        continue;
                    }
                    let h = halfplanes.iter().find(|h| h.kind == segs[b].kind);
                    let (p, th) = match h {
                        Some(h) => refine_cl(fam, &segs[c], h),
                        None => {
                            let s = &segs[c];
                            (
                                P {
                                    x: s.p.x + tc * (s.q.x - s.p.x),
                                    y: s.p.y + tc * (s.q.y - s.p.y),
                                },
                                s.tp + tc * (s.tq - s.tp),
                            )
                        }
                    };
                    // skip crossings that coincide with a chain end already cut there
                    let dup = cuts[b].iter().any(|&(_, v, _)| {
                        let q = verts[v];
                        (q.x - p.x).abs() + (q.y - p.y).abs() <= 1e-12 * size
                    });
                    if dup {
                        continue;
                    }
                    verts.push(p);
                    cuts[c].push((tc, vid, th));
                    cuts[b].push((tb, vid, f64::NAN));
                }
                (false, false) => {}
            }
        }
        active.push(i);
    }
    // Edges of the graph.
    let mut g = Graph {
        verts,
        edges: Vec::new(),
    };
    for (ci, ch) in chains.iter().enumerate() {
        let base = segs.iter().position(|s| s.owner == ci).unwrap_or(0);
        let mut start = chain_ends[ci].0;
        let mut poly: Vec<(f64, P)> = vec![ch[0]];
        for k in 0..ch.len() - 1 {
            let si = base + k;
            let mut cs = cuts[si].clone();
            cs.sort_by(|a, b| a.0.total_cmp(&b.0));
            for (_, v, th) in cs {
                poly.push((th, g.verts[v]));
                g.edges
                    .push((start, v, std::mem::take(&mut poly), EdgeKind::Window));
                start = v;
                poly.push((th, g.verts[v]));
            }
            poly.push(ch[k + 1]);
        }
        let end = chain_ends[ci].1;
        let n = poly.len();
        poly[n - 1].1 = g.verts[end];
        g.edges.push((start, end, poly, EdgeKind::Window));
    }
    for k in 0..nw {
        let si = nseg_curve + k;
        let s = segs[si];
        let mut cs = cuts[si].clone();
        cs.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut start = k;
        for (_, v, _) in cs {
            g.edges.push((
                start,
                v,
                vec![(f64::NAN, g.verts[start]), (f64::NAN, g.verts[v])],
                s.kind,
            ));
            start = v;
        }
        let end = (k + 1) % nw;
        g.edges.push((
            start,
            end,
            vec![(f64::NAN, g.verts[start]), (f64::NAN, g.verts[end])],
            s.kind,
        ));
    }
    // Label curve edges and drop those outside K.
    let slack = 1e-9 * size;
    g.edges.retain(|e| e.0 != e.1 || e.2.len() > 2);
    g.edges.retain(|e| {
        if e.3 != EdgeKind::Window || e.2.iter().all(|p| p.0.is_nan()) {
            return true;
        }
        let mid = e.2[e.2.len() / 2].1;
        let mid2 = P {
            x: 0.5 * (e.2[0].1.x + e.2[1].1.x),
            y: 0.5 * (e.2[0].1.y + e.2[1].1.y),
        };
        inside_k(if e.2.len() > 2 { mid } else { mid2 }, -slack * 0.0 + slack)
    });
    for e in g.edges.iter_mut() {
        if e.3 == EdgeKind::Window && e.2.iter().any(|p| !p.0.is_nan()) {
            e.3 = EdgeKind::Complex {
                theta_start: e.2[0].0,
                theta_end: e.2[e.2.len() - 1].0,
            };
        }
    }
    prune_dangling(&mut g);
    let faces = faces(&g);
    let mut coeffs = vec![0.0; fam.degree() + 1];
    let mut stable_faces = Vec::new();
    for f in faces {
        let pts: Vec<AlphaBeta> = f
            .iter()
            .flat_map(|&(e, fwd)| {
                let poly = &g.edges[e].2;
                let it: Box<dyn Iterator<Item = &(f64, P)>> = if fwd {
                    Box::new(poly.iter().take(poly.len() - 1))
                } else {
                    Box::new(poly.iter().rev().take(poly.len() - 1))
                };
                it.map(|(_, p)| p.ab())
            })
            .collect();
        if pts.len() < 3 || shoelace(&pts) <= 0.0 {
            continue;
        }
        let Some(ip) = interior_point(&pts) else {
            continue;
        };
        fam.coefficients_into(ip.alpha, ip.beta, &mut coeffs);
        if !schur_stable(&coeffs) {
            continue;
        }
        stable_faces.push((f, pts));
    }
    // Size of the stable region (bounding box of the coarse faces) sets the fine tolerance.
    let (mut bx0, mut bx1, mut by0, mut by1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for (_, pts) in &stable_faces {
        for p in pts {
            bx0 = bx0.min(p.alpha);
            bx1 = bx1.max(p.alpha);
            by0 = by0.min(p.beta);
            by1 = by1.max(p.beta);
        }
    }
    // The coarse faces are within 1e-3·bmax of the true region, so 0.99 keeps the chord
    // tolerance below rel_tol of the true size.
    let rsize = (bx1 - bx0).max(by1 - by0);
    let polygons: Vec<Polygon> = stable_faces
        .iter()
        .map(|(f, _)| refine_face(fam, &g, f, 0.99 * rel_tol * rsize))
        .collect();
    let area = polygons.iter().map(|p| p.area()).sum();
    let (alpha_max, beta_at_alpha_max) = alpha_max_of(fam, &polygons);
    StableRegion {
        polygons,
        alpha_max,
        beta_at_alpha_max,
        area,
    }
}

fn prune_dangling(g: &mut Graph) {
    loop {
        let mut deg = vec![0usize; g.verts.len()];
        for e in &g.edges {
            deg[e.0] += 1;
            deg[e.1] += 1;
        }
        let before = g.edges.len();
        g.edges.retain(|e| deg[e.0] >= 2 && deg[e.1] >= 2);
        if g.edges.len() == before {
            break;
        }
    }
}

/// Faces of the planar graph as cycles of (edge, forward?) with the face on the left.
fn faces(g: &Graph) -> Vec<Vec<(usize, bool)>> {
    let nv = g.verts.len();
    // outgoing half-edges per vertex with their departure angle
    let mut out: Vec<Vec<(f64, usize, bool)>> = vec![Vec::new(); nv];
    for (i, e) in g.edges.iter().enumerate() {
        let (a, b) = (e.2[0].1, e.2[1].1);
        out[e.0].push(((b.y - a.y).atan2(b.x - a.x), i, true));
        let n = e.2.len();
        let (a, b) = (e.2[n - 1].1, e.2[n - 2].1);
        out[e.1].push(((b.y - a.y).atan2(b.x - a.x), i, false));
    }
    for o in out.iter_mut() {
        o.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    let mut used = vec![[false; 2]; g.edges.len()];
    let mut result = Vec::new();
    for start in 0..g.edges.len() {
        for dir in [true, false] {
            if used[start][dir as usize] {
                continue;
            }
            let mut cyc = Vec::new();
            let (mut e, mut fwd) = (start, dir);
            let mut guard = 0;
            while !used[e][fwd as usize] && guard < 4 * g.edges.len() + 8 {
                guard += 1;
                used[e][fwd as usize] = true;
                cyc.push((e, fwd));
                let v = if fwd { g.edges[e].1 } else { g.edges[e].0 };
                // the twin leaves v; take the next half-edge clockwise from it
                let list = &out[v];
                let pos = list
                    .iter()
                    .position(|&(_, ei, f)| ei == e && f != fwd)
                    .unwrap_or(0);
                let next = list[(pos + list.len() - 1) % list.len()];
                e = next.1;
                fwd = next.2;
            }
            result.push(cyc);
        }
    }
    result
}

/// A point strictly inside a counter-clockwise polygon: the midpoint of a long edge moved a
/// little to its left, checked by the even-odd rule.
fn interior_point(v: &[AlphaBeta]) -> Option<AlphaBeta> {
    let n = v.len();
    let mut idx: Vec<usize> = (0..n).collect();
    let len = |i: usize| {
        let (a, b) = (v[i], v[(i + 1) % n]);
        (b.alpha - a.alpha).hypot(b.beta - a.beta)
    };
    idx.sort_by(|&a, &b| len(b).total_cmp(&len(a)));
    for &i in idx.iter().take(16) {
        let (a, b) = (v[i], v[(i + 1) % n]);
        let l = len(i);
        if l == 0.0 {
            continue;
        }
        for f in [1e-3, 1e-2, 1e-4, 0.1] {
            let p = AlphaBeta {
                alpha: 0.5 * (a.alpha + b.alpha) - f * (b.beta - a.beta),
                beta: 0.5 * (a.beta + b.beta) + f * (b.alpha - a.alpha),
            };
            if point_in(v, p) {
                return Some(p);
            }
        }
    }
    None
}

/// Rebuilds a stable face with its curve arcs resampled to the fine tolerance; the coarse
/// knot intervals are refined in parallel.
fn refine_face(fam: &PolyFamily, g: &Graph, f: &[(usize, bool)], tol: f64) -> Polygon {
    let mut vertices: Vec<AlphaBeta> = Vec::new();
    let mut thetas: Vec<f64> = Vec::new();
    let mut edges = Vec::new();
    for &(e, fwd) in f {
        let (a, b, poly, kind) = &g.edges[e];
        let (va, vb) = if fwd { (*a, *b) } else { (*b, *a) };
        let start = vertices.len();
        match kind {
            EdgeKind::Complex { .. } => {
                let mut knots: Vec<(f64, P)> = if fwd {
                    poly.clone()
                } else {
                    poly.iter().rev().copied().collect()
                };
                let n = knots.len();
                knots[0].1 = g.verts[va];
                knots[n - 1].1 = g.verts[vb];
                let (t0, t1) = (knots[0].0, knots[n - 1].0);
                // Split every knot interval into 8 equal θ-parts first, so that the parallel
                // refinement is balanced where the curvature concentrates in a few intervals.
                let mut fine: Vec<(f64, P)> = Vec::with_capacity(8 * n);
                for (k, w) in knots.windows(2).enumerate() {
                    if k == 0 {
                        fine.push(w[0]);
                    }
                    let interior = w[0].0 > 0.0 && w[1].0 < std::f64::consts::PI;
                    for j in 1..8 {
                        let t = w[0].0 + (w[1].0 - w[0].0) * j as f64 / 8.0;
                        if let (true, Some(p)) = (interior, point(fam, t)) {
                            fine.push((t, p));
                        }
                    }
                    fine.push(w[1]);
                }
                let pieces: Vec<Vec<(f64, P)>> = fine
                    .par_windows(2)
                    .with_min_len(4)
                    .map(|w| {
                        let mut out = Vec::new();
                        sample(
                            fam,
                            w[0].0,
                            w[0].1,
                            w[1].0,
                            w[1].1,
                            tol,
                            f64::INFINITY,
                            0,
                            &mut out,
                        );
                        out
                    })
                    .collect();
                vertices.push(g.verts[va].ab());
                thetas.push(t0);
                let total: usize = pieces.iter().map(|p| p.len()).sum();
                for (t, p) in pieces.into_iter().flatten().take(total.saturating_sub(1)) {
                    vertices.push(p.ab());
                    thetas.push(t);
                }
                edges.push(Edge {
                    start,
                    kind: EdgeKind::Complex {
                        theta_start: t0,
                        theta_end: t1,
                    },
                });
            }
            k => {
                vertices.push(g.verts[va].ab());
                // a line vertex that ends a curve arc keeps that arc's θ
                let th = g
                    .edges
                    .iter()
                    .find_map(|(x, y, pl, kk)| match kk {
                        EdgeKind::Complex {
                            theta_start,
                            theta_end,
                        } => {
                            if *x == va {
                                Some(*theta_start)
                            } else if *y == va {
                                Some(*theta_end)
                            } else {
                                None
                            }
                        }
                        _ => {
                            let _ = pl;
                            None
                        }
                    })
                    .unwrap_or(f64::NAN);
                thetas.push(th);
                edges.push(Edge { start, kind: *k });
            }
        }
    }
    Polygon {
        vertices,
        edges,
        thetas,
    }
}

/// dα/dθ on the curve, analytically: α = Im(R(z)(1 − z))/sin θ with R = z^d D/N.
fn dalpha(fam: &PolyFamily, theta: f64) -> f64 {
    let pl = &fam.plant;
    let z = Complex64::from_polar(1.0, theta);
    let d = fam.d as f64;
    let zd = Complex64::from_polar(1.0, theta * d);
    let dz = pl.denominator(z);
    let ddz = z * 2.0 - pl.a1;
    let n = pl.numerator(z);
    let r = zd * dz / n;
    let rp = (zd / z * d * dz + zd * ddz) / n - zd * dz * pl.n1 / (n * n);
    let w = r * (1.0 - z);
    let dw = (rp * (1.0 - z) - r) * Complex64::i() * z;
    let (s, c) = theta.sin_cos();
    (dw.im * s - w.im * c) / (s * s)
}

/// α_max over the polygons and the β where it is reached. Where the maximum lies inside a
/// complex-pair arc, dα/dθ = 0 is solved by bisection on the analytic derivative.
fn alpha_max_of(fam: &PolyFamily, polys: &[Polygon]) -> (f64, f64) {
    let mut best = (f64::NAN, f64::NAN);
    for poly in polys {
        let n = poly.vertices.len();
        let (imax, _) =
            poly.vertices
                .iter()
                .enumerate()
                .fold((0, f64::NEG_INFINITY), |(bi, bv), (i, p)| {
                    if p.alpha > bv { (i, p.alpha) } else { (bi, bv) }
                });
        let mut cand = (poly.vertices[imax].alpha, poly.vertices[imax].beta);
        let corner = poly.edges.iter().any(|e| e.start == imax);
        if !corner {
            let (t0, t1) = (poly.thetas[(imax + n - 1) % n], poly.thetas[(imax + 1) % n]);
            if t0.is_finite() && t1.is_finite() {
                let (a, b) = (t0.min(t1), t0.max(t1));
                let (ga, gb) = (dalpha(fam, a), dalpha(fam, b));
                if ga.signum() != gb.signum() {
                    let t = crate::boundary::bisect(a, b, |t| dalpha(fam, t));
                    if let Some(p) = curve_point(fam, t)
                        && p.alpha >= cand.0
                    {
                        cand = (p.alpha, p.beta);
                    }
                }
            }
        }
        if best.0.is_nan() || cand.0 > best.0 {
            best = cand;
        }
    }
    best
}
