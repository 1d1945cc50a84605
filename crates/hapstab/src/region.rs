//! Exact stable regions in the wall plane as closed polygons (Section V, Figs. 4–6), for
//! any loop's [`AffineFamily`] (for the paper's loop, the (α, β)-plane).
//!
//! The method, step by step (each step is one function below):
//!
//! 1. **Bounds** ([`Bounds::new`]): necessary conditions of the Schur–Cohn test cut out a
//!    convex polygon W that contains every stable wall: p(1) > 0 and (−1)^n p(−1) > 0 (the
//!    z = ±1 lines of [`crate::boundary`]) and, p being monic of degree n, the coefficient
//!    bounds |c_j| ≤ C(n, j), each a slab in the wall plane.
//! 2. **Coarse curve** ([`coarse_curve`]): the complex-pair curve C(θ), θ ∈ [0, π], sampled on
//!    a uniform grid and refined adaptively near W.
//! 3. **Search window** ([`search_window`]): every vertex of a stable region is a curve point
//!    or a crossing of the lines, so a box around those inside W, clipped to W, contains
//!    the stable region.
//! 4. **Arrangement** ([`arrangement`]): the curve, cut into chains where it runs to infinity,
//!    and the window's edges split the window into faces; crossings are refined on the curve
//!    itself (bisection in θ), so every vertex is a point where p has a root on the circle.
//! 5. **Classification** ([`stable_faces`]): the number of unstable roots is constant in a
//!    face, so one Schur–Cohn test at an interior point decides it.
//! 6. **Refinement** ([`refine_face`]): the arcs of stable faces are resampled until every
//!    chord is within `rel_tol × size` of the curve; α_max is found on the arcs from
//!    da/dθ = 0.
//!
//! Every adaptive step draws curve points from one [`Budget`]; a region that would need
//! more than [`MAX_CURVE_POINTS`] ends in an error instead of exhausting memory.

use std::sync::atomic::{AtomicUsize, Ordering};

use num_complex::Complex64;
use rayon::prelude::*;
use serde::Serialize;

use crate::boundary::{
    AlphaBeta, RootLine, curve_end, curve_point, curve_point_at, dalpha_dtheta, minus_one_line,
    plus_one_line,
};
use crate::closed_loop::AffineFamily;
use crate::error::{Error, Result};
use crate::verdict::Verdict;
use crate::verdict::{decide, inside_unit_circle};

/// What an edge of a region polygon is made of.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum EdgeKind {
    /// The z = 1 line (α = −γ for the paper's loop): a real root at z = 1.
    ZPlusOne,
    /// The z = −1 line: a real root at z = −1.
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

/// The stable region of a loop: every stable component as a polygon in wall units, the
/// largest stable stiffness and where it is reached, and the total area.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StableRegion {
    /// Stable components (possibly none).
    pub polygons: Vec<Polygon>,
    /// Largest stable a (α_max for the paper's loop; NaN when the region is empty).
    pub alpha_max: f64,
    /// b at which α_max is reached (NaN when empty).
    pub beta_at_alpha_max: f64,
    /// Total area of the stable region in wall units.
    pub area: f64,
}

impl StableRegion {
    /// True iff (a, b) lies inside one of the polygons. The polygons follow the exact boundary
    /// to their chord tolerance (`rel_tol` × [`StableRegion::size`]); a wall closer than that
    /// to [`StableRegion::boundary_distance`] is decided by the point test, not by this.
    pub fn contains(&self, p: AlphaBeta) -> bool {
        self.polygons.iter().any(|q| q.contains(p))
    }

    /// The region's size, the scale its chord tolerance is relative to: the larger side of
    /// the polygons' bounding box (0 when empty).
    pub fn size(&self) -> f64 {
        let pts = self
            .polygons
            .iter()
            .flat_map(|q| q.vertices.iter().map(|v| P::of(*v)));
        bbox(pts).map_or(0.0, |(x0, x1, y0, y1)| (x1 - x0).max(y1 - y0))
    }

    /// Euclidean distance from a wall to the nearest polygon edge (infinite when empty).
    pub fn boundary_distance(&self, p: AlphaBeta) -> f64 {
        let q = P::of(p);
        self.polygons
            .iter()
            .flat_map(|poly| {
                let v = &poly.vertices;
                (0..v.len()).map(move |i| (P::of(v[i]), P::of(v[(i + 1) % v.len()])))
            })
            .map(|(a, b)| segment_distance(q, a, b))
            .fold(f64::INFINITY, f64::min)
    }

    fn empty() -> Self {
        Self {
            polygons: Vec::new(),
            alpha_max: f64::NAN,
            beta_at_alpha_max: f64::NAN,
            area: 0.0,
        }
    }
}

/// Default chord tolerance of region polygons, relative to the stable region's size.
pub const DEFAULT_REL_TOL: f64 = 1e-9;

/// Smallest chord tolerance accepted: below 1e-13 of the size the curve points themselves
/// carry rounding errors of that order, so refinement could not converge.
pub const MIN_REL_TOL: f64 = 1e-13;

/// Most curve points one region may use. The paper's regions need 10³–10⁵; 4·10⁶ points are
/// about 100 MB, the memory bound of one region computation.
pub const MAX_CURVE_POINTS: usize = 4_000_000;

/// Computes the stable region of a loop's family (Section V; Figs. 4–6).
pub fn stable_region(fam: &AffineFamily) -> Result<StableRegion> {
    stable_region_with(fam, DEFAULT_REL_TOL)
}

/// As [`stable_region`] with a chord tolerance relative to the region's size.
pub fn stable_region_with(fam: &AffineFamily, rel_tol: f64) -> Result<StableRegion> {
    if !(rel_tol.is_finite() && (MIN_REL_TOL..=0.1).contains(&rel_tol)) {
        return Err(Error::OutOfRange {
            name: "region tolerance",
            value: rel_tol,
            range: "[1e-13, 0.1]",
        });
    }
    let budget = Budget::new(MAX_CURVE_POINTS);
    let bounds = Bounds::new(fam)?;
    let mut focus: Option<BoxF> = None;
    for i in 0..MAX_ATTEMPTS {
        let (region, checked) = attempt(fam, &bounds, (focus, i as i32), rel_tol, &budget)?;
        match verify(fam, &bounds, &region, checked, (i, rel_tol)) {
            None => return Ok(region),
            Some(zoom) => focus = Some(zoom),
        }
    }
    Err(Error::Numerical(
        "the stable region could not be resolved: its exact boundary and a direct grid of \
         Schur–Cohn tests keep disagreeing (features far smaller than the boundary curve's \
         extent); the stable intervals at fixed damping and the grid map remain available"
            .into(),
    ))
}

/// Attempts before giving up: each one zooms the coarse sampling onto where the previous
/// one disagreed with the grid, so four attempts cover a scale range of about 10¹².
const MAX_ATTEMPTS: usize = 4;

/// An axis-aligned box (a0, a1, b0, b1).
type BoxF = (f64, f64, f64, f64);

/// One pass of the method (steps 2–6 of the module doc) with an optional focus box for the
/// coarse sampling and its refinement level (the attempt's number); returns the region and the search window's box.
fn attempt(
    fam: &AffineFamily,
    bounds: &Bounds,
    focus: (Option<BoxF>, i32),
    rel_tol: f64,
    budget: &Budget,
) -> Result<(StableRegion, Checked)> {
    let coarse = coarse_curve(fam, bounds, focus, budget)?;
    let Some(window) = search_window(bounds, &coarse) else {
        let none = Checked {
            wbox: None,
            thorough: true,
        };
        return Ok((StableRegion::empty(), none));
    };
    let wbox = bbox(window.polygon.iter().map(|(p, _)| *p));
    let graph = arrangement(fam, &window, &coarse)?;
    let cycles = faces(&graph);
    let consistent = euler_holds(&graph, cycles.len());
    let faces = stable_faces(fam, &graph, cycles);
    if faces.is_empty() {
        return Ok((
            StableRegion::empty(),
            Checked {
                wbox,
                thorough: true,
            },
        ));
    }
    // The coarse faces are within the coarse tolerance of the true region, so 0.99 keeps the
    // chord tolerance below rel_tol of the true size.
    let tol = 0.99 * rel_tol * faces_size(&faces);
    let polygons = faces
        .iter()
        .map(|(f, _)| refine_face(fam, &graph, f, tol, budget))
        .collect::<Result<Vec<Polygon>>>()?;
    let area = polygons.iter().map(|p| p.area()).sum();
    let (alpha_max, beta_at_alpha_max) = alpha_max_of(fam, &polygons);
    let region = StableRegion {
        polygons,
        alpha_max,
        beta_at_alpha_max,
        area,
    };
    Ok((
        region,
        Checked {
            wbox,
            thorough: !consistent,
        },
    ))
}

/// How an attempt's region must be verified: over which box, and whether thoroughly (exact
/// slices as well as the grid) because the arrangement broke Euler's formula or found
/// nothing stable.
#[derive(Clone, Copy)]
struct Checked {
    wbox: Option<BoxF>,
    thorough: bool,
}

/// The region's edges bucketed by damping, for point-in-region tests in O(edges/bucket)
/// instead of O(vertices) (the even-odd rule counts crossings of a ray toward −∞ in a).
struct EdgeIndex {
    y0: f64,
    h: f64,
    buckets: Vec<Vec<(P, P)>>,
}

impl EdgeIndex {
    fn new(region: &StableRegion) -> Self {
        let pts = region
            .polygons
            .iter()
            .flat_map(|p| p.vertices.iter().map(|v| P::of(*v)));
        let (_, _, y0, y1) = bbox(pts).unwrap_or((0.0, 0.0, 0.0, 0.0));
        let nb = 256;
        let h = ((y1 - y0) / nb as f64).max(f64::MIN_POSITIVE);
        // (truncation is the floor here: the argument is clamped to be non-negative)
        let bucket = |y: f64| (((y - y0) / h).max(0.0) as usize).min(nb - 1);
        let ranges: Vec<Vec<(usize, usize)>> = region
            .polygons
            .iter()
            .map(|poly| {
                let v = &poly.vertices;
                (0..v.len())
                    .map(|i| {
                        let (a, b) = (v[i].beta, v[(i + 1) % v.len()].beta);
                        (bucket(a.min(b)), bucket(a.max(b)))
                    })
                    .collect()
            })
            .collect();
        let mut counts = vec![0_usize; nb];
        for &(lo, hi) in ranges.iter().flatten() {
            for c in &mut counts[lo..=hi] {
                *c += 1;
            }
        }
        let mut buckets: Vec<Vec<(P, P)>> = counts.iter().map(|&c| Vec::with_capacity(c)).collect();
        for (poly, rs) in region.polygons.iter().zip(&ranges) {
            let v = &poly.vertices;
            for (i, &(lo, hi)) in rs.iter().enumerate() {
                let e = (P::of(v[i]), P::of(v[(i + 1) % v.len()]));
                for bucket in &mut buckets[lo..=hi] {
                    bucket.push(e);
                }
            }
        }
        Self { y0, h, buckets }
    }

    fn is_empty(&self) -> bool {
        self.buckets.iter().all(Vec::is_empty)
    }

    fn contains(&self, p: P) -> bool {
        let k = ((p.y - self.y0) / self.h).floor();
        if !(k >= 0.0 && (k as usize) < self.buckets.len()) {
            return false;
        }
        let mut inside = false;
        for &(a, b) in &self.buckets[k as usize] {
            if (a.y > p.y) != (b.y > p.y) {
                let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
                if p.x < x {
                    inside = !inside;
                }
            }
        }
        inside
    }
}

/// Side of the verification grid: the region is checked against this many × this many
/// direct Schur–Cohn tests (fewer for high degrees, where each test costs O(n²)).
fn grid_side(fam: &AffineFamily) -> usize {
    if fam.degree() <= 64 { 16 } else { 10 }
}

/// Checks the region against a grid of direct Schur–Cohn tests over the search window (and
/// the bounds' box when the window is absent), the wall-free point, and when `thorough` also
/// against the exact stable intervals on slices of constant damping; disagreements within
/// twice the chord tolerance (`rel_tol` of the size) of the polygon's edges do not count.
/// None when they agree; otherwise the box to zoom the next attempt onto: the disagreeing and
/// the stable points, two cells wide.
fn verify(
    fam: &AffineFamily,
    bounds: &Bounds,
    region: &StableRegion,
    checked: Checked,
    (attempt, rel_tol): (usize, f64),
) -> Option<BoxF> {
    let wbox = checked
        .wbox
        .or_else(|| bbox(bounds.polygon.iter().map(|(p, _)| *p)))?;
    let m = grid_side(fam);
    let index = EdgeIndex::new(region);
    let mut suspects = grid_suspects(fam, &index, wbox, m);
    if checked.thorough {
        suspects.extend(slice_suspects(fam, &index, wbox));
    }
    // "Nothing is stable" is checked exactly where it matters most, on the stiffness axis
    // (no virtual damping): a region far thinner than the window would slip between slices.
    if region.polygons.is_empty() {
        let ivs = crate::boundary::stable_alpha_intervals(fam, 0.0);
        let mids = ivs.iter().filter(|iv| iv.hi > iv.lo).map(|iv| {
            let x = 0.5 * (iv.lo.max(wbox.0) + iv.hi.min(wbox.1));
            (P { x, y: 0.0 }, false)
        });
        suspects.extend(mids);
    }
    // A region far smaller than the window may fall between the window's grid points and
    // slices: check around it too (its own box, doubled).
    if let Some(rbox) = region_box(region).filter(|r| box_size(*r) < 0.1 * box_size(wbox)) {
        suspects.extend(grid_suspects(fam, &index, rbox, m));
        if checked.thorough {
            suspects.extend(slice_suspects(fam, &index, rbox));
        }
    }
    // The wall-free point itself, decided (a root within rounding of the circle, as for an
    // undamped plant whose corner it is, makes it marginal and uninformative).
    let origin = P { x: 0.0, y: 0.0 };
    suspects.extend(probe(fam, &index, origin, &mut vec![0.0; fam.degree() + 1]));
    // A disagreement within the chord tolerance of the polygon's edges is no disagreement.
    let band = 2.0 * rel_tol * region.size();
    let wrong = suspects
        .iter()
        .any(|(p, agree)| !agree && region.boundary_distance(p.ab()) > band);
    if !wrong {
        return None;
    }
    let (x0, x1, y0, y1) = wbox;
    // Two grid cells around the suspects, shrinking fourfold with every attempt, but never
    // less than half the suspects' own extent.
    let shrink = 0.25_f64.powi(attempt as i32);
    let (a0, a1, b0, b1) = bbox(suspects.into_iter().map(|(p, _)| p))?;
    let mx = (2.0 * (x1 - x0) / m as f64 * shrink).max(0.5 * (a1 - a0));
    let my = (2.0 * (y1 - y0) / m as f64 * shrink).max(0.5 * (b1 - b0));
    Some((a0 - mx, a1 + mx, b0 - my, b1 + my))
}

/// The region's bounding box doubled about its centre (None when empty).
fn region_box(region: &StableRegion) -> Option<BoxF> {
    let pts = region
        .polygons
        .iter()
        .flat_map(|q| q.vertices.iter().map(|v| P::of(*v)));
    let (x0, x1, y0, y1) = bbox(pts)?;
    let (hx, hy) = (x1 - x0, y1 - y0);
    Some((x0 - 0.5 * hx, x1 + 0.5 * hx, y0 - 0.5 * hy, y1 + 0.5 * hy))
}

/// The larger side of a box.
fn box_size((x0, x1, y0, y1): BoxF) -> f64 {
    (x1 - x0).max(y1 - y0)
}

/// Grid points that are stable or where the region disagrees with the Schur–Cohn test,
/// each with "agrees?".
fn grid_suspects(fam: &AffineFamily, region: &EdgeIndex, wbox: BoxF, m: usize) -> Vec<(P, bool)> {
    let (x0, x1, y0, y1) = wbox;
    let (hx, hy) = ((x1 - x0) / m as f64, (y1 - y0) / m as f64);
    let mut coeffs = vec![0.0; fam.degree() + 1];
    let mut out = Vec::new();
    for i in 0..m {
        for j in 0..m {
            // Irrational offsets keep grid points off the z = ±1 lines and the axes.
            let p = P {
                x: x0 + hx * (i as f64 + 0.5 + GRID_JITTER),
                y: y0 + hy * (j as f64 + 0.5 + GRID_JITTER_Y),
            };
            out.extend(probe(fam, region, p, &mut coeffs));
        }
    }
    // Walls near the wall-free point: a damped plant is stable there, and a region much
    // smaller than the window that the grid straddles is found by them.
    let size = (x1 - x0).max(y1 - y0);
    // Probes right at the wall-free point only test an empty answer: where a region exists,
    // the wall-free point may be its corner (an undamped plant), within rounding of the
    // boundary.
    let radii: &[f64] = if region.is_empty() {
        &[PROBE_RADIUS, 1e-9]
    } else {
        &[PROBE_RADIUS]
    };
    for r in radii.iter().map(|r| r * size) {
        for k in 0..8 {
            let (s, c) = (k as f64 * std::f64::consts::FRAC_PI_4 + GRID_JITTER).sin_cos();
            out.extend(probe(fam, region, P { x: r * c, y: r * s }, &mut coeffs));
        }
    }
    out
}

/// Distance of the probes from the wall-free point, relative to the window.
const PROBE_RADIUS: f64 = 1e-3;

/// A verification point if it is stable or the region disagrees with the Schur–Cohn test
/// there.
fn probe(fam: &AffineFamily, region: &EdgeIndex, p: P, coeffs: &mut [f64]) -> Option<(P, bool)> {
    // A wall with a root within rounding of the circle is on the boundary: either side agrees.
    let stable = match decide(fam, p.x, p.y, coeffs).verdict {
        Verdict::Marginal => return None,
        v => v == Verdict::Stable,
    };
    let agree = stable == region.contains(p);
    (stable || !agree).then_some((p, agree))
}

/// Number of constant-damping slices of a thorough check: each costs O(degree²) (a θ scan
/// of 256 samples per degree), so fewer for long delays.
fn slices(fam: &AffineFamily) -> usize {
    match fam.degree() {
        0..=64 => 48,
        65..=300 => 16,
        _ => 6,
    }
}

/// On slices of constant damping across the box, the exact stable intervals
/// ([`crate::boundary::stable_alpha_intervals`]) against the region: each interval's
/// midpoint must be inside, the midpoints of the gaps outside.
fn slice_suspects(fam: &AffineFamily, region: &EdgeIndex, wbox: BoxF) -> Vec<(P, bool)> {
    let (x0, x1, y0, y1) = wbox;
    let n = slices(fam);
    // One θ scan of the family serves every slice (the same crossings, no sine per slice).
    let table = crate::boundary::CircleTable::new(fam);
    (0..n)
        .into_par_iter()
        .flat_map_iter(|j| {
            let b = y0 + (y1 - y0) * (j as f64 + 0.5 + GRID_JITTER) / n as f64;
            let ivs = crate::boundary::stable_alpha_intervals_tabulated(fam, &table, b);
            let mut out = Vec::new();
            let mut prev_hi = x0;
            // Intervals and gaps narrower than this are the boundary itself, to rounding.
            let tiny = 1e-9 * (x1 - x0);
            for iv in &ivs {
                let (lo, hi) = (iv.lo.max(x0 - (x1 - x0)), iv.hi.min(x1 + (x1 - x0)));
                let inside = P {
                    x: 0.5 * (lo + hi),
                    y: b,
                };
                if hi - lo > tiny {
                    out.push((inside, region.contains(inside)));
                }
                if iv.lo > prev_hi + tiny {
                    let gap = P {
                        x: 0.5 * (prev_hi + iv.lo),
                        y: b,
                    };
                    out.push((gap, !region.contains(gap)));
                }
                prev_hi = prev_hi.max(iv.hi);
            }
            out
        })
        .collect()
}

/// Offset of the verification grid within its cells in a (√2 − 1.3, an irrational fraction).
const GRID_JITTER: f64 = 0.114_213_562_373_095_05;

/// Offset in b (the golden ratio's 0.618… − 0.5). It differs from [`GRID_JITTER`] and their
/// sum is irrational, so that no diagonal of the box runs through grid points: the window's
/// corners often lie on a z = ±1 line, and a grid on that line's diagonal would test walls
/// with a root exactly on the circle.
const GRID_JITTER_Y: f64 = 0.118_033_988_749_894_85;

// ---------------------------------------------------------------------------------------
// Geometry helpers

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

    fn of(p: AlphaBeta) -> Self {
        P {
            x: p.alpha,
            y: p.beta,
        }
    }

    fn finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite()
    }

    fn lerp(self, q: P, t: f64) -> P {
        P {
            x: self.x + t * (q.x - self.x),
            y: self.y + t * (q.y - self.y),
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

/// Distance along the ray m + t·dir (t > 0) to the first edge of the closed polyline other
/// than edge `skip`; None when the ray meets none.
fn ray_exit(pts: &[P], skip: usize, m: P, dir: P) -> Option<f64> {
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
fn segment_distance(q: P, a: P, b: P) -> f64 {
    let ab = sub(b, a);
    let len2 = ab.x * ab.x + ab.y * ab.y;
    let t = if len2 > 0.0 {
        (((q.x - a.x) * ab.x + (q.y - a.y) * ab.y) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    norm(sub(q, a.lerp(b, t)))
}

fn cross(a: P, b: P) -> f64 {
    a.x * b.y - a.y * b.x
}

/// The curve point at θ, with its exact end points at θ = 0 and θ = π (double roots at
/// z = ±1, see [`curve_end`]).
fn point(fam: &AffineFamily, theta: f64) -> Option<P> {
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
fn point_at(fam: &AffineFamily, theta: f64, z: Complex64) -> Option<P> {
    if theta < crate::closed_loop::SHIFTED_THETA {
        return curve_point(fam, theta).map(P::of);
    }
    curve_point_at(fam, z).map(P::of)
}

/// e^{iθ}.
fn unit(theta: f64) -> Complex64 {
    let (s, c) = theta.sin_cos();
    Complex64::new(c, s)
}

/// A half-plane n·p <= c with the kind of its boundary line.
#[derive(Clone, Copy, Debug)]
struct HalfPlane {
    n: P,
    c: f64,
    kind: EdgeKind,
    /// The root line this half-plane comes from (z = ±1), for refining crossings on it.
    line: Option<RootLine>,
}

impl HalfPlane {
    fn value(&self, p: P) -> f64 {
        self.n.x * p.x + self.n.y * p.y - self.c
    }

    /// n·p ≤ c from n·p + c0 ... with the normal scaled to unit length.
    fn normalized(n: P, c: f64, kind: EdgeKind, line: Option<RootLine>) -> Option<Self> {
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
    fn of_line(l: RootLine, kind: EdgeKind) -> Option<Self> {
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
type Convex = Vec<(P, HalfPlane)>;

/// Where the boundary lines of two half-planes cross (Cramer's rule); None if parallel.
fn line_meet(a: &HalfPlane, b: &HalfPlane) -> Option<P> {
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
fn clip(poly: &Convex, h: &HalfPlane) -> Convex {
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

fn box_polygon(x0: f64, x1: f64, y0: f64, y1: f64) -> Convex {
    let h = box_halfplanes(x0, x1, y0, y1);
    // bottom (y ≥ y0), right (x ≤ x1), top (y ≤ y1), left (x ≥ x0), counter-clockwise
    vec![
        (P { x: x0, y: y0 }, h[2]),
        (P { x: x1, y: y0 }, h[1]),
        (P { x: x1, y: y1 }, h[3]),
        (P { x: x0, y: y1 }, h[0]),
    ]
}

fn bbox(points: impl Iterator<Item = P>) -> Option<(f64, f64, f64, f64)> {
    let mut b: Option<(f64, f64, f64, f64)> = None;
    for p in points {
        let (x0, x1, y0, y1) = b.unwrap_or((p.x, p.x, p.y, p.y));
        b = Some((x0.min(p.x), x1.max(p.x), y0.min(p.y), y1.max(p.y)));
    }
    b
}

// ---------------------------------------------------------------------------------------
// Step 0: the point budget

/// A shared count of curve points, so that every adaptive step together stays within
/// [`MAX_CURVE_POINTS`].
struct Budget {
    left: AtomicUsize,
}

impl Budget {
    fn new(n: usize) -> Self {
        Self {
            left: AtomicUsize::new(n),
        }
    }

    /// Takes `n` points; false when the budget is exhausted.
    fn take(&self, n: usize) -> bool {
        self.left
            .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |l| l.checked_sub(n))
            .is_ok()
    }

    fn exhausted() -> Error {
        Error::Numerical(format!(
            "the stable region's boundary needs more than {MAX_CURVE_POINTS} points (a loop whose \
             boundary curve winds too often to draw); the stable intervals at fixed damping \
             (`check`, `kmax`) and the grid map remain available"
        ))
    }
}

// ---------------------------------------------------------------------------------------
// Step 1: rigorous bounds

/// Half-planes whose intersection contains every stable wall (see the module doc).
struct Bounds {
    halfplanes: Vec<HalfPlane>,
    /// Their intersection as a convex polygon.
    polygon: Convex,
}

/// Start of the clipping: a box far beyond any wall value that the coefficient bounds leave
/// possible, yet far below overflow of products of coordinates.
const HUGE: f64 = 1e150;

impl Bounds {
    fn new(fam: &AffineFamily) -> Result<Self> {
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
                name: "loop",
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

    /// Signed excess beyond the bounds (≤ 0 inside).
    fn excess(&self, p: P) -> f64 {
        self.halfplanes
            .iter()
            .map(|h| h.value(p))
            .fold(f64::NEG_INFINITY, f64::max)
    }
}

/// The half-planes carrying an edge of a convex polygon, plus the root lines among `all`.
fn active_halfplanes(polygon: &Convex, all: &[HalfPlane]) -> Vec<HalfPlane> {
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
const SLAB_SLACK: f64 = 1e-3;

/// |c_j| ≤ C(n, j) for the monic p of degree n (Vieta: c_j is a sum of C(n, j) products of
/// roots, each of modulus < 1 when p is Schur stable), as pairs of half-planes.
fn coefficient_slabs(fam: &AffineFamily) -> Vec<HalfPlane> {
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

// ---------------------------------------------------------------------------------------
// Step 2: the coarse curve

/// How finely an arc is sampled: chord deviation tolerance, and (coarse passes) the region
/// of interest and the longest chord allowed in it.
#[derive(Clone, Copy)]
struct Sampling<'a> {
    tol: f64,
    /// Coarse passes: refine only chords that come near this box, and split chords longer
    /// than `maxlen` there. Fine passes: None.
    focus: Option<(&'a BoxF, f64)>,
}

impl Sampling<'_> {
    fn relevant(&self, p: P, q: P) -> bool {
        match self.focus {
            None => true,
            Some(((x0, x1, y0, y1), _)) => {
                p.x.min(q.x) <= *x1
                    && p.x.max(q.x) >= *x0
                    && p.y.min(q.y) <= *y1
                    && p.y.max(q.y) >= *y0
            }
        }
    }
}

/// Number of coarse knots: the curve winds about once per root of p, so 64 knots per degree.
fn knot_count(fam: &AffineFamily) -> usize {
    64 * (fam.degree() + 2)
}

/// Samples the curve on θ ∈ [0, π] (see the module doc, step 2).
fn coarse_curve(
    fam: &AffineFamily,
    bounds: &Bounds,
    (zoom, level): (Option<BoxF>, i32),
    budget: &Budget,
) -> Result<Vec<(f64, P)>> {
    let m = knot_count(fam);
    if !budget.take(m + 1) {
        return Err(Budget::exhausted());
    }
    let pi = std::f64::consts::PI;
    let thetas: Vec<f64> = (0..=m).map(|i| pi * i as f64 / m as f64).collect();
    let knots: Vec<(f64, Option<P>)> = thetas
        .par_iter()
        .with_min_len(128)
        .map(|&t| {
            match point(fam, t) {
                // Where the curve runs to infinity at θ = π, end just short of it so that the
                // last interval is still sampled (the far tail is cut off later).
                None if t == pi => {
                    let t = pi * (1.0 - 1e-12);
                    (t, point(fam, t))
                }
                p => (t, p),
            }
        })
        .collect();
    let focus = zoom.unwrap_or_else(|| focus_box(bounds, &knots));
    let size = (focus.1 - focus.0).max(focus.3 - focus.2);
    // Each retry also samples 16 times finer (4 times the points): features of the boundary
    // far below the coarse tolerance (several branches crossing within 1e-4 of the window)
    // are resolved within a few attempts.
    let fine = 0.0625_f64.powi(level);
    let s = Sampling {
        tol: 1e-3 * size * fine,
        focus: Some((&focus, 0.25 * size * fine.sqrt())),
    };
    let intervals = knots.len() - 1;
    let pieces: Vec<Result<Vec<(f64, P)>>> = (0..intervals)
        .step_by(RUN)
        .collect::<Vec<usize>>()
        .par_iter()
        .with_min_len(4)
        .map(|&i0| {
            let mut out = Vec::new();
            let mut scratch = ArcScratch::default();
            for w in knots[i0..(i0 + RUN + 1).min(knots.len())].windows(2) {
                match (w[0], w[1]) {
                    ((t0, Some(p0)), (t1, Some(p1))) => {
                        let (a, b) = ((t0, p0), (t1, p1));
                        sample_arc_into(fam, a, b, s, budget, &mut out, &mut scratch)?;
                    }
                    // a gap (no point): the next piece starts afresh at its own first knot
                    ((_, None), (t1, Some(p1))) => out.push((t1, p1)),
                    _ => {}
                }
            }
            Ok(out)
        })
        .collect();
    let mut coarse: Vec<(f64, P)> = Vec::new();
    if let (t0, Some(p0)) = knots[0] {
        coarse.push((t0, p0));
    }
    for piece in pieces {
        coarse.extend(piece?);
    }
    Ok(coarse)
}

/// Knot intervals per parallel task of the curve sampling (one buffer and work space each).
const RUN: usize = 16;

/// The box where the coarse curve matters: around the knots inside the bounds (all of the
/// bounds when none is), inflated by half its size.
fn focus_box(bounds: &Bounds, knots: &[(f64, Option<P>)]) -> (f64, f64, f64, f64) {
    let whole = bbox(bounds.polygon.iter().map(|(p, _)| *p)).unwrap_or((-1.0, 1.0, -1.0, 1.0));
    let wsize = (whole.1 - whole.0).max(whole.3 - whole.2);
    let inside = knots
        .iter()
        .filter_map(|(_, p)| *p)
        .filter(|p| p.finite() && bounds.excess(*p) <= 1e-9 * wsize);
    let (x0, x1, y0, y1) = bbox(inside).unwrap_or(whole);
    let size = (x1 - x0).max(y1 - y0).max(1e-12 * wsize).max(1e-300);
    let m = 0.5 * size;
    (
        (x0 - m).max(whole.0),
        (x1 + m).min(whole.1),
        (y0 - m).max(whole.2),
        (y1 + m).min(whole.3),
    )
}

/// Coarse passes split a chord whose midpoint deviates by more than this fraction of its
/// length (a turn of about 0.2 rad per chord): a loop of any size gets at least ~30 points.
const TURN_TOL: f64 = 0.025;

/// Deepest bisection of one arc: 2⁻⁴⁸ of a knot interval is below the resolution of θ.
const MAX_DEPTH: u32 = 48;

/// Work space of [`sample_arc_into`], reused across arcs.
#[derive(Default)]
struct ArcScratch {
    stack: Vec<(ArcEnd, ArcEnd, u32)>,
    parts: Vec<ArcEnd>,
}

/// Adaptive sampling of the curve between two points (θ, C(θ)); appends the points after
/// the first (the last included) to `out`. An explicit stack (in `scratch`, reused across
/// arcs) replaces recursion; every point drawn comes out of the budget.
fn sample_arc_into(
    fam: &AffineFamily,
    a: (f64, P),
    b: (f64, P),
    s: Sampling<'_>,
    budget: &Budget,
    out: &mut Vec<(f64, P)>,
    scratch: &mut ArcScratch,
) -> Result<()> {
    let ArcScratch { stack, parts } = scratch;
    // Stack of pending arcs, the leftmost on top.
    stack.clear();
    stack.push(((a.0, unit(a.0), a.1), (b.0, unit(b.0), b.1), 0_u32));
    while let Some((l, r, depth)) = stack.pop() {
        match split(fam, l, r, depth, s, parts) {
            Split::Accept(mid) => {
                out.extend(mid.map(|m| (m.0, m.2)));
                out.push((r.0, r.2));
                continue;
            }
            Split::Into => {}
        }
        if !budget.take(parts.len()) {
            return Err(Budget::exhausted());
        }
        let mut right = r;
        for &p in parts.iter().rev() {
            stack.push((p, right, depth + 1));
            right = p;
        }
        stack.push((l, right, depth + 1));
    }
    Ok(())
}

/// One end of an arc: θ, z = e^{iθ} and the curve point.
type ArcEnd = (f64, Complex64, P);

/// What to do with an arc: keep its chord (with the midpoint evaluated for the test when
/// that point is kept as well), or split it at the points left in the caller's buffer.
enum Split {
    Accept(Option<ArcEnd>),
    Into,
}

/// Deepest level at which a chord is split into more than two parts: deeper, the curvature
/// estimate from one midpoint is no longer worth trusting for more.
const MULTI_SPLIT_DEPTH: u32 = 8;

/// Decides an arc: accepted when its chord follows the curve, else split at interior points
/// written to `parts`. The arc's midpoint is (z0 + z1)/|z0 + z1| and k equal parts are
/// powers of e^{iΔθ/k}, so no sine or cosine is evaluated per point. A smooth arc is split
/// into k ≈ √(dev/tol) parts at once (the deviation of a chord shrinks with the square of its
/// length). Fine passes keep the midpoint they evaluate: an arc whose midpoint is within
/// 4·tol of the chord is kept as the two half-chords, each within tol (a quarter of the
/// deviation), so that no evaluation is spent only on a test.
fn split(
    fam: &AffineFamily,
    l: ArcEnd,
    r: ArcEnd,
    depth: u32,
    s: Sampling<'_>,
    parts: &mut Vec<ArcEnd>,
) -> Split {
    let ((t0, z0, p0), (t1, z1, p1)) = (l, r);
    if depth >= MAX_DEPTH || !s.relevant(p0, p1) {
        return Split::Accept(None);
    }
    let zs = z0 + z1;
    // |z0 + z1| ≤ 2: the plain square root is exact enough and far cheaper than hypot
    let zm = zs / (zs.re * zs.re + zs.im * zs.im).sqrt();
    if zm.im <= 0.0 {
        return Split::Accept(None);
    }
    let tm = 0.5 * (t0 + t1);
    let Some(pm) = point_at(fam, tm, zm) else {
        return Split::Accept(None);
    };
    let mid = (tm, zm, pm);
    let ch = sub(p1, p0);
    let q = sub(pm, p0);
    let len2 = ch.x * ch.x + ch.y * ch.y;
    let len = len2.sqrt();
    let dev = if len > 0.0 {
        cross(ch, q).abs() / len
    } else {
        norm(q)
    };
    // Accept when the midpoint is within the limit of the chord and projects into
    // [−1/4, 5/4] of it; coarse passes also bound the turning per chord (scale-free, so that
    // loops far smaller than the focus are resolved) down to a floor below which it is noise.
    let keep_mid = s.focus.is_none();
    let limit = if keep_mid { 4.0 * s.tol } else { s.tol };
    let t = if len2 > 0.0 {
        (q.x * ch.x + q.y * ch.y) / len2
    } else {
        0.5
    };
    // A chord and midpoint all within the tolerance of one point is done whatever its
    // direction (a direction made of rounding noise would otherwise split to the depth limit).
    let tiny = norm(q) <= s.tol && norm(sub(pm, p1)) <= s.tol;
    // The half-chords of a kept midpoint deviate by a quarter of its deviation where the arc
    // is close to a parabola, which shows in a midpoint projecting near the chord's middle;
    // elsewhere the chord itself must be within tol.
    let limit = if (0.45..=0.55).contains(&t) {
        limit
    } else {
        s.tol
    };
    let within = tiny || (dev <= limit && (-0.25..=1.25).contains(&t));
    let turning = s.focus.is_some() && dev > TURN_TOL * len && dev > 1e-7 * s.tol;
    let far = norm(q) + norm(sub(pm, p1)) > 1.5 * len + s.tol;
    // Coarse passes bound the chord length near the focus, so that a chord to a far point
    // (the curve runs to infinity where the equations are dependent) cannot hide a turn.
    let long = s
        .focus
        .is_some_and(|(_, maxlen)| depth < 30 && len > maxlen);
    if within && !turning && !far && !long {
        return Split::Accept((keep_mid && !tiny).then_some(mid));
    }
    parts.clear();
    let k = if far || long || turning || depth > MULTI_SPLIT_DEPTH {
        2
    } else {
        ((dev / limit).sqrt().ceil() as usize).clamp(2, 64)
    };
    if k == 2 {
        parts.push(mid);
        return Split::Into;
    }
    let w = unit((t1 - t0) / k as f64);
    let mut z = z0;
    for i in 1..k {
        z *= w;
        let t = t0 + (t1 - t0) * i as f64 / k as f64;
        let Some(p) = point_at(fam, t, z) else {
            parts.clear();
            parts.push(mid);
            return Split::Into;
        };
        parts.push((t, z, p));
    }
    Split::Into
}

// ---------------------------------------------------------------------------------------
// Step 3: the search window

/// The window: a box around the curve points and line crossings inside the bounds, plus a
/// 5 % margin, clipped to the bounds. None when nothing can be stable.
struct Window {
    polygon: Convex,
    halfplanes: Vec<HalfPlane>,
    size: f64,
}

fn search_window(bounds: &Bounds, coarse: &[(f64, P)]) -> Option<Window> {
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
    let boxed = box_polygon(x0 - margin, x1 + margin, y0 - margin, y1 + margin);
    let mut polygon = boxed;
    for h in &bounds.halfplanes {
        polygon = clip(&polygon, h);
    }
    let halfplanes = active_halfplanes(&polygon, &bounds.halfplanes);
    (polygon.len() >= 3).then_some(Window {
        polygon,
        halfplanes,
        size: size + 2.0 * margin,
    })
}

fn box_halfplanes(x0: f64, x1: f64, y0: f64, y1: f64) -> Vec<HalfPlane> {
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
fn line_crossing(bounds: &Bounds) -> Option<P> {
    let lines: Vec<&HalfPlane> = bounds
        .halfplanes
        .iter()
        .filter(|h| h.line.is_some())
        .collect();
    let [a, b] = lines.as_slice() else {
        return None;
    };
    let det = a.n.x * b.n.y - a.n.y * b.n.x;
    if det == 0.0 {
        return None;
    }
    let p = P {
        x: (a.c * b.n.y - b.c * a.n.y) / det,
        y: (a.n.x * b.c - b.n.x * a.c) / det,
    };
    (p.finite() && bounds.excess(p) <= 1e-9 * norm(p).max(1.0)).then_some(p)
}

// ---------------------------------------------------------------------------------------
// Step 4: the arrangement of curve and window

/// A polyline segment of the arrangement.
#[derive(Clone, Copy, Debug)]
struct Seg {
    p: P,
    q: P,
    /// Curve: θ at p and q; border: NaN.
    tp: f64,
    tq: f64,
    /// Chain id (curve chains) or [`BORDER`] (window edges).
    owner: usize,
    /// Index within the owner.
    idx: usize,
    kind: EdgeKind,
}

const BORDER: usize = usize::MAX / 2;

impl Seg {
    fn is_curve(&self) -> bool {
        self.owner != BORDER
    }
    fn at(&self, t: f64) -> P {
        self.p.lerp(self.q, t)
    }
}

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
    ((0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&u)).then_some((t, u))
}

/// Halves a curve segment at its θ midpoint.
fn split_seg(fam: &AffineFamily, s: &Seg) -> Option<[Seg; 2]> {
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
}

/// Refines a curve–curve crossing by repeated halving of both θ-intervals.
fn refine_cc(fam: &AffineFamily, a: &Seg, b: &Seg) -> (P, f64, f64) {
    let (mut a, mut b) = (*a, *b);
    for _ in 0..60 {
        let (Some(sa), Some(sb)) = (split_seg(fam, &a), split_seg(fam, &b)) else {
            break;
        };
        let hit = sa
            .iter()
            .flat_map(|x| sb.iter().map(move |y| (*x, *y)))
            .find(|(x, y)| seg_intersect(x, y).is_some());
        let Some((x, y)) = hit else { break };
        // Halving further is useless once both halves are straight to rounding: the midpoint
        // just evaluated lies within 1e-14 of the coordinates' size from the old chord.
        let straight = |old: &Seg, half: &[Seg; 2]| {
            let m = half[0].q;
            let ch = sub(old.q, old.p);
            let len = norm(ch);
            len == 0.0
                || cross(ch, sub(m, old.p)).abs() / len <= 1e-14 * (norm(old.p) + norm(old.q) + len)
        };
        let done = straight(&a, &sa) && straight(&b, &sb);
        a = x;
        b = y;
        if done || ((a.tq - a.tp).abs() < 1e-16 && (b.tq - b.tp).abs() < 1e-16) {
            break;
        }
    }
    let (t, u) = seg_intersect(&a, &b).unwrap_or((0.5, 0.5));
    (a.at(t), a.tp + t * (a.tq - a.tp), b.tp + u * (b.tq - b.tp))
}

/// Refines a curve–line crossing by bisection in θ on the signed value of the line, and puts
/// the vertex exactly on the line (the residual is below the curve's rounding).
fn refine_cl(fam: &AffineFamily, a: &Seg, h: &HalfPlane) -> (P, f64) {
    let f = |t: f64| point(fam, t).map_or(f64::NAN, |p| h.value(p));
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
    let p = point(fam, t).unwrap_or(a.p);
    let r = h.value(p);
    (
        P {
            x: p.x - r * h.n.x,
            y: p.y - r * h.n.y,
        },
        t,
    )
}

/// Splits the coarse curve into chains: at gaps (no point) and where it leaves a box 10³
/// times the window's size (where the curve runs to infinity), cutting the chord at the box.
fn chains(fam: &AffineFamily, coarse: &[(f64, P)], window: &Window) -> Vec<Vec<(f64, P)>> {
    let (x0, x1, y0, y1) =
        bbox(window.polygon.iter().map(|(p, _)| *p)).unwrap_or((-1.0, 1.0, -1.0, 1.0));
    let big = 1e3 * window.size;
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let lim = P { x: big, y: big };
    let inside = |p: P| p.finite() && (p.x - cx).abs() < lim.x && (p.y - cy).abs() < lim.y;
    // The chord p→q cut where it leaves the big box (p inside, q outside).
    let exit = |(tp, p): (f64, P), (tq, q): (f64, P)| -> (f64, P) {
        let mut s: f64 = 1.0;
        for (a, b, l, c) in [(p.x, q.x, lim.x, cx), (p.y, q.y, lim.y, cy)] {
            if b.is_finite() && (b - c).abs() >= l && a != b {
                let bound = c + if b > c { l } else { -l };
                s = s.min((bound - a) / (b - a));
            }
        }
        let s = if s.is_finite() {
            s.clamp(0.0, 1.0)
        } else {
            0.0
        };
        (tp + s * (tq - tp), p.lerp(q, s))
    };
    let gap = 2.0 * std::f64::consts::PI / knot_count(fam) as f64;
    let mut out: Vec<Vec<(f64, P)>> = Vec::new();
    let mut cur: Vec<(f64, P)> = Vec::new();
    let mut last: Option<(f64, P)> = None;
    let flush = |cur: &mut Vec<(f64, P)>, out: &mut Vec<Vec<(f64, P)>>| {
        if cur.len() >= 2 {
            out.push(std::mem::take(cur));
        } else {
            cur.clear();
        }
    };
    for &(t, p) in coarse {
        let ok = inside(p);
        let contiguous = last.is_none_or(|(lt, _)| (t - lt) < gap);
        let prev_ok = last.is_some_and(|(_, lp)| inside(lp));
        if !contiguous {
            flush(&mut cur, &mut out);
        } else if ok && !prev_ok {
            if let Some(l) = last.filter(|(_, lp)| lp.finite()) {
                cur.push(exit((t, p), l));
            }
        } else if !ok && prev_ok {
            if p.finite()
                && let Some(l) = last
            {
                cur.push(exit(l, (t, p)));
            }
            flush(&mut cur, &mut out);
        }
        if ok {
            cur.push((t, p));
        }
        last = Some((t, p));
    }
    flush(&mut cur, &mut out);
    out
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

/// The curve chains and window edges as segments with their cuts, before the graph is built.
struct Pieces {
    chains: Vec<Vec<(f64, P)>>,
    segs: Vec<Seg>,
    /// Index of the first window segment.
    first_border: usize,
    verts: Vec<P>,
    cuts: Vec<Vec<Cut>>,
    chain_ends: Vec<(usize, usize)>,
}

fn arrangement(fam: &AffineFamily, window: &Window, coarse: &[(f64, P)]) -> Result<Graph> {
    let mut pieces = pieces(chains(fam, coarse, window), window);
    cut_chain_ends(&mut pieces, window.size);
    intersect(fam, window, &mut pieces)?;
    let mut g = build_graph(&pieces);
    keep_inside(&mut g, window);
    prune_dangling(&mut g);
    Ok(g)
}

/// Most crossings the arrangement may hold: a boundary curve that crosses itself more often
/// than this (a curve that retraces itself, segment over segment) would need memory and time
/// quadratic in its points; past it the region is refused with an honest error.
const MAX_CROSSINGS: usize = 1_000_000;

fn pieces(chains: Vec<Vec<(f64, P)>>, window: &Window) -> Pieces {
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
                kind: EdgeKind::Window,
            });
        }
    }
    let first_border = segs.len();
    let nw = window.polygon.len();
    for i in 0..nw {
        segs.push(Seg {
            p: window.polygon[i].0,
            q: window.polygon[(i + 1) % nw].0,
            tp: f64::NAN,
            tq: f64::NAN,
            owner: BORDER,
            idx: i,
            kind: window.polygon[i].1.kind,
        });
    }
    // Vertices: window corners and chain ends.
    let mut verts: Vec<P> = window.polygon.iter().map(|w| w.0).collect();
    let chain_ends = chains
        .iter()
        .map(|ch| {
            verts.push(ch[0].1);
            verts.push(ch[ch.len() - 1].1);
            (verts.len() - 2, verts.len() - 1)
        })
        .collect();
    let cuts = vec![Vec::new(); segs.len()];
    Pieces {
        chains,
        segs,
        first_border,
        verts,
        cuts,
        chain_ends,
    }
}

/// Chain ends lying on a window edge become cuts of that edge.
fn cut_chain_ends(pc: &mut Pieces, size: f64) {
    for ci in 0..pc.chains.len() {
        let ch = &pc.chains[ci];
        let ends = [
            (ch[0].1, pc.chain_ends[ci].0),
            (ch[ch.len() - 1].1, pc.chain_ends[ci].1),
        ];
        for (end, vid) in ends {
            for k in pc.first_border..pc.segs.len() {
                let s = &pc.segs[k];
                let d = sub(s.q, s.p);
                let len2 = d.x * d.x + d.y * d.y;
                let t = ((end.x - s.p.x) * d.x + (end.y - s.p.y) * d.y) / len2;
                let dist = cross(d, sub(end, s.p)).abs() / len2.sqrt();
                if dist <= 1e-12 * size && t > 0.0 && t < 1.0 {
                    pc.cuts[k].push((t, vid, f64::NAN));
                }
            }
        }
    }
}

/// All pairwise crossings by a sweep over bounding boxes sorted along the stiffness axis;
/// each crossing becomes a vertex refined on the curve and a cut of both segments. At most
/// [`MAX_CROSSINGS`]; beyond, an error.
fn intersect(fam: &AffineFamily, window: &Window, pc: &mut Pieces) -> Result<()> {
    let mut crossings = 0_usize;
    let lo = |s: &Seg| s.p.x.min(s.q.x);
    let hi = |s: &Seg| s.p.x.max(s.q.x);
    let mut order: Vec<usize> = (0..pc.segs.len()).collect();
    order.sort_by(|&i, &j| lo(&pc.segs[i]).total_cmp(&lo(&pc.segs[j])));
    let mut active: Vec<usize> = Vec::new();
    for &i in &order {
        let si = pc.segs[i];
        active.retain(|&j| hi(&pc.segs[j]) >= lo(&si));
        for &j in &active {
            let sj = pc.segs[j];
            let neighbours =
                si.owner == sj.owner && (si.owner == BORDER || si.idx.abs_diff(sj.idx) <= 1);
            let apart =
                si.p.y.max(si.q.y) < sj.p.y.min(sj.q.y) || sj.p.y.max(sj.q.y) < si.p.y.min(si.q.y);
            if neighbours || apart {
                continue;
            }
            let Some((t, u)) = seg_intersect(&si, &sj) else {
                continue;
            };
            crossings += 1;
            if crossings > MAX_CROSSINGS {
                return Err(Error::Numerical(format!(
                    "the stable region's boundary curve crosses itself more than \
                     {MAX_CROSSINGS} times (it retraces itself); the stable intervals at fixed \
                     damping (`check`, `kmax`) and the grid map remain available"
                )));
            }
            match (si.is_curve(), sj.is_curve()) {
                (true, true) => {
                    let (p, ti, tj) = refine_cc(fam, &si, &sj);
                    let vid = pc.verts.len();
                    pc.verts.push(p);
                    pc.cuts[i].push((t, vid, ti));
                    pc.cuts[j].push((u, vid, tj));
                }
                (true, false) => cut_curve_border(fam, window, pc, (i, t), (j, u)),
                (false, true) => cut_curve_border(fam, window, pc, (j, u), (i, t)),
                (false, false) => {}
            }
        }
        active.push(i);
    }
    Ok(())
}

/// A crossing of curve segment c (at parameter tc) with window edge b (at tb).
fn cut_curve_border(
    fam: &AffineFamily,
    window: &Window,
    pc: &mut Pieces,
    (c, tc): (usize, f64),
    (b, tb): (usize, f64),
) {
    let size = window.size;
    let sc = pc.segs[c];
    let raw = sc.at(tc);
    let at_end = pc.chain_ends.iter().any(|&(a, e)| {
        [a, e].iter().any(|&v| {
            let q = pc.verts[v];
            (q.x - raw.x).abs() + (q.y - raw.y).abs() <= 1e-9 * size
        })
    });
    if at_end {
        return;
    }
    let line = window
        .halfplanes
        .iter()
        .find(|h| h.line.is_some() && h.kind == pc.segs[b].kind);
    let (p, th) = match line {
        Some(h) => refine_cl(fam, &sc, h),
        None => (raw, sc.tp + tc * (sc.tq - sc.tp)),
    };
    // skip crossings that coincide with a chain end already cut there
    let dup = pc.cuts[b].iter().any(|&(_, v, _)| {
        let q = pc.verts[v];
        (q.x - p.x).abs() + (q.y - p.y).abs() <= 1e-12 * size
    });
    if dup {
        return;
    }
    let vid = pc.verts.len();
    pc.verts.push(p);
    pc.cuts[c].push((tc, vid, th));
    pc.cuts[b].push((tb, vid, f64::NAN));
}

/// The planar graph: chains and window edges split at their cuts.
fn build_graph(pc: &Pieces) -> Graph {
    let mut g = Graph {
        verts: pc.verts.clone(),
        edges: Vec::new(),
    };
    let sorted = |si: usize| {
        let mut cs = pc.cuts[si].clone();
        cs.sort_by(|a, b| a.0.total_cmp(&b.0));
        cs
    };
    let mut base = 0;
    for (ci, ch) in pc.chains.iter().enumerate() {
        let mut start = pc.chain_ends[ci].0;
        let mut poly: Vec<(f64, P)> = vec![ch[0]];
        for k in 0..ch.len() - 1 {
            for (_, v, th) in sorted(base + k) {
                poly.push((th, g.verts[v]));
                g.edges
                    .push((start, v, std::mem::take(&mut poly), EdgeKind::Window));
                start = v;
                poly.push((th, g.verts[v]));
            }
            poly.push(ch[k + 1]);
        }
        let end = pc.chain_ends[ci].1;
        let n = poly.len();
        poly[n - 1].1 = g.verts[end];
        g.edges.push((start, end, poly, EdgeKind::Window));
        base += ch.len() - 1;
    }
    let nw = pc.segs.len() - pc.first_border;
    for k in 0..nw {
        let si = pc.first_border + k;
        let mut start = k;
        let ends = sorted(si)
            .into_iter()
            .map(|(_, v, _)| v)
            .chain([(k + 1) % nw]);
        for v in ends {
            g.edges.push((
                start,
                v,
                vec![(f64::NAN, g.verts[start]), (f64::NAN, g.verts[v])],
                pc.segs[si].kind,
            ));
            start = v;
        }
    }
    g
}

/// Drops curve edges outside the window and labels the rest as complex-pair arcs.
fn keep_inside(g: &mut Graph, window: &Window) {
    let slack = 1e-9 * window.size;
    let inside = |p: P| window.halfplanes.iter().all(|h| h.value(p) <= slack);
    let is_curve = |e: &GraphEdge| e.3 == EdgeKind::Window && e.2.iter().any(|p| !p.0.is_nan());
    g.edges.retain(|e| e.0 != e.1 || e.2.len() > 2);
    g.edges.retain(|e| {
        if !is_curve(e) {
            return true;
        }
        let mid = if e.2.len() > 2 {
            e.2[e.2.len() / 2].1
        } else {
            e.2[0].1.lerp(e.2[1].1, 0.5)
        };
        inside(mid)
    });
    for e in g.edges.iter_mut() {
        if is_curve(e) {
            e.3 = EdgeKind::Complex {
                theta_start: e.2[0].0,
                theta_end: e.2[e.2.len() - 1].0,
            };
        }
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
    // Departure angles are taken toward the first polyline point that is clearly away from
    // the vertex: a curve that passes through a corner at a sample point leaves a segment of
    // rounding length there, whose direction means nothing.
    let size = bbox(g.verts.iter().copied()).map_or(1.0, |(x0, x1, y0, y1)| (x1 - x0).max(y1 - y0));
    let eps = 1e-10 * size;
    let departure = |from: P, mut pts: Box<dyn Iterator<Item = P> + '_>| {
        let to = pts
            .by_ref()
            .find(|p| norm(sub(*p, from)) > eps)
            .unwrap_or(from);
        (to.y - from.y).atan2(to.x - from.x)
    };
    // outgoing half-edges per vertex with their departure angle
    let mut out: Vec<Vec<(f64, usize, bool)>> = vec![Vec::new(); nv];
    for (i, e) in g.edges.iter().enumerate() {
        let n = e.2.len();
        let fwd = departure(e.2[0].1, Box::new(e.2.iter().skip(1).map(|q| q.1)));
        out[e.0].push((fwd, i, true));
        let back = departure(
            e.2[n - 1].1,
            Box::new(e.2.iter().rev().skip(1).map(|q| q.1)),
        );
        out[e.1].push((back, i, false));
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

// ---------------------------------------------------------------------------------------
// Step 5: classification

/// A face as its cycle of half-edges and its vertices.
type Face = (Vec<(usize, bool)>, Vec<AlphaBeta>);

/// Euler's formula for a planar graph with C connected components, counted in boundary
/// cycles (each component's outer cycle separately): V − E + cycles = 2C. A walk that
/// breaks it means a crossing was missed or the angular order was confused by nearly
/// coincident pieces; the region is then verified thoroughly.
fn euler_holds(g: &Graph, cycles: usize) -> bool {
    fn root(parent: &mut [usize], mut v: usize) -> usize {
        while parent[v] != v {
            parent[v] = parent[parent[v]];
            v = parent[v];
        }
        v
    }
    let mut parent: Vec<usize> = (0..g.verts.len()).collect();
    let mut used = vec![false; g.verts.len()];
    for e in &g.edges {
        used[e.0] = true;
        used[e.1] = true;
        let (a, b) = (root(&mut parent, e.0), root(&mut parent, e.1));
        parent[a] = b;
    }
    let v = used.iter().filter(|&&u| u).count();
    let c = (0..g.verts.len())
        .filter(|&i| used[i] && root(&mut parent, i) == i)
        .count();
    v + cycles == g.edges.len() + 2 * c
}

/// The counter-clockwise faces whose interior point has every root inside the unit circle
/// ([`inside_unit_circle`]: a face holds a constant number of roots inside).
fn stable_faces(fam: &AffineFamily, g: &Graph, cycles: Vec<Vec<(usize, bool)>>) -> Vec<Face> {
    let mut coeffs = vec![0.0; fam.degree() + 1];
    cycles
        .into_iter()
        .filter_map(|f| {
            let pts = face_points(g, &f);
            if pts.len() < 3 || shoelace(&pts) <= 0.0 {
                return None;
            }
            let ip = interior_point(&pts)?;
            (inside_unit_circle(fam, ip.alpha, ip.beta, &mut coeffs) == Some(true))
                .then_some((f, pts))
        })
        .collect()
}

fn face_points(g: &Graph, f: &[(usize, bool)]) -> Vec<AlphaBeta> {
    f.iter()
        .flat_map(|&(e, fwd)| {
            let poly = &g.edges[e].2;
            let n = poly.len() - 1;
            let it: Box<dyn Iterator<Item = &(f64, P)>> = if fwd {
                Box::new(poly.iter().take(n))
            } else {
                Box::new(poly.iter().rev().take(n))
            };
            it.map(|(_, p)| p.ab())
        })
        .collect()
}

/// Largest extent of the stable faces' bounding box.
fn faces_size(faces: &[Face]) -> f64 {
    let pts = faces.iter().flat_map(|(_, v)| v.iter().map(|p| P::of(*p)));
    bbox(pts).map_or(0.0, |(x0, x1, y0, y1)| (x1 - x0).max(y1 - y0))
}

/// A point strictly inside a counter-clockwise polygon, as deep inside as a few probes find:
/// halfway across the face from the midpoint of one of its longest edges, checked by the
/// even-odd rule; else a grid point inside.
fn interior_point(v: &[AlphaBeta]) -> Option<AlphaBeta> {
    let n = v.len();
    let pts: Vec<P> = v.iter().map(|q| P::of(*q)).collect();
    let mut idx: Vec<usize> = (0..n).collect();
    let len = |i: usize| norm(sub(pts[(i + 1) % n], pts[i]));
    idx.sort_by(|&a, &b| len(b).total_cmp(&len(a)));
    // From the midpoints of the longest edges, halfway across the face along the inward
    // normal: the face's edges are chords of the curve, and a point just inside a chord may
    // lie beyond the curve it approximates (outside the true face).
    let mut best: Option<(f64, P)> = None;
    for &i in idx.iter().take(4) {
        let (a, b) = (pts[i], pts[(i + 1) % n]);
        let l = len(i);
        if l == 0.0 {
            continue;
        }
        let m = a.lerp(b, 0.5);
        let dir = P {
            x: -(b.y - a.y) / l,
            y: (b.x - a.x) / l,
        };
        let Some(t) = ray_exit(&pts, i, m, dir) else {
            continue;
        };
        let p = P {
            x: m.x + 0.5 * t * dir.x,
            y: m.y + 0.5 * t * dir.y,
        };
        if best.is_none_or(|(w, _)| t > w) && point_in(v, p.ab()) {
            best = Some((t, p));
        }
    }
    if let Some((_, p)) = best {
        return Some(p.ab());
    }
    // A thin or intricate face: search a grid over its bounding box.
    let (x0, x1, y0, y1) = bbox(v.iter().map(|p| P::of(*p)))?;
    let m = 24;
    (0..m * m).find_map(|k| {
        let p = AlphaBeta {
            alpha: x0 + (x1 - x0) * ((k % m) as f64 + 0.5 + GRID_JITTER) / m as f64,
            beta: y0 + (y1 - y0) * ((k / m) as f64 + 0.5 + GRID_JITTER_Y) / m as f64,
        };
        point_in(v, p).then_some(p)
    })
}

// ---------------------------------------------------------------------------------------
// Step 6: refinement and the largest stable stiffness

/// Rebuilds a stable face with its curve arcs resampled to the fine tolerance.
fn refine_face(
    fam: &AffineFamily,
    g: &Graph,
    f: &[(usize, bool)],
    tol: f64,
    budget: &Budget,
) -> Result<Polygon> {
    let mut poly = Polygon {
        vertices: Vec::new(),
        edges: Vec::new(),
        thetas: Vec::new(),
    };
    for &(e, fwd) in f {
        let (a, b, line, kind) = &g.edges[e];
        let (va, vb) = if fwd { (*a, *b) } else { (*b, *a) };
        let start = poly.vertices.len();
        match kind {
            EdgeKind::Complex { .. } => {
                let mut knots: Vec<(f64, P)> = if fwd {
                    line.clone()
                } else {
                    line.iter().rev().copied().collect()
                };
                let n = knots.len();
                knots[0].1 = g.verts[va];
                knots[n - 1].1 = g.verts[vb];
                let (t0, t1) = (knots[0].0, knots[n - 1].0);
                let arc = refine_arc(fam, &knots, tol, budget)?;
                poly.vertices.push(g.verts[va].ab());
                poly.thetas.push(t0);
                let keep = arc.len().saturating_sub(1);
                for (t, p) in arc.into_iter().take(keep) {
                    poly.vertices.push(p.ab());
                    poly.thetas.push(t);
                }
                poly.edges.push(Edge {
                    start,
                    kind: EdgeKind::Complex {
                        theta_start: t0,
                        theta_end: t1,
                    },
                });
            }
            k => {
                poly.vertices.push(g.verts[va].ab());
                poly.thetas.push(arc_end_theta(g, va));
                poly.edges.push(Edge { start, kind: *k });
            }
        }
    }
    Ok(poly)
}

/// Resamples an arc's knots to the fine tolerance, in parallel. Every knot interval is first
/// split into 8 equal θ-parts, so that the parallel work is balanced where the curvature
/// concentrates in a few intervals. Returns the points after the first knot.
fn refine_arc(
    fam: &AffineFamily,
    knots: &[(f64, P)],
    tol: f64,
    budget: &Budget,
) -> Result<Vec<(f64, P)>> {
    if !budget.take(8 * knots.len()) {
        return Err(Budget::exhausted());
    }
    // Knots within the tolerance of the chord from the last kept knot to the next add
    // nothing (the coarse pass's geometric run near θ = 0 packs many into the corner at
    // z = 1); the fine sampling below puts back whatever the curve needs.
    let mut kept: Vec<(f64, P)> = Vec::with_capacity(knots.len());
    for (i, &k) in knots.iter().enumerate() {
        let needed = match (kept.last(), knots.get(i + 1)) {
            (Some(prev), Some(next)) => {
                let ch = sub(next.1, prev.1);
                let len = norm(ch);
                let dev = if len > tol {
                    cross(ch, sub(k.1, prev.1)).abs() / len
                } else {
                    norm(sub(k.1, prev.1))
                };
                dev > tol
            }
            _ => true,
        };
        if needed {
            kept.push(k);
        }
    }
    let knots = &kept;
    // Each task takes a run of knot intervals: splits each into 8 equal θ-parts and samples
    // every part (the 7 interior points are evaluated in the task, not before it).
    let s = Sampling { tol, focus: None };
    let starts: Vec<usize> = (0..knots.len().saturating_sub(1)).step_by(2).collect();
    let pieces: Vec<Result<Vec<(f64, P)>>> = starts
        .par_iter()
        .with_min_len(4)
        .map(|&k0| {
            let mut out = Vec::new();
            let mut scratch = ArcScratch::default();
            for w in knots[k0..(k0 + 3).min(knots.len())].windows(2) {
                let interior = w[0].0 > 0.0 && w[1].0 < std::f64::consts::PI;
                let mut left = w[0];
                for j in 1..=8 {
                    let right = if j == 8 {
                        w[1]
                    } else {
                        let t = w[0].0 + (w[1].0 - w[0].0) * j as f64 / 8.0;
                        match (interior, point(fam, t)) {
                            (true, Some(p)) => (t, p),
                            _ => continue,
                        }
                    };
                    sample_arc_into(fam, left, right, s, budget, &mut out, &mut scratch)?;
                    left = right;
                }
            }
            Ok(out)
        })
        .collect();
    let mut out = Vec::with_capacity(pieces.iter().map(|p| p.as_ref().map_or(0, Vec::len)).sum());
    for p in pieces {
        out.extend(p?);
    }
    Ok(out)
}

/// θ of a line vertex that ends a curve arc (NaN when no arc ends there).
fn arc_end_theta(g: &Graph, v: usize) -> f64 {
    g.edges
        .iter()
        .find_map(|(x, y, _, k)| match k {
            EdgeKind::Complex { theta_start, .. } if *x == v => Some(*theta_start),
            EdgeKind::Complex { theta_end, .. } if *y == v => Some(*theta_end),
            _ => None,
        })
        .unwrap_or(f64::NAN)
}

/// α_max over the polygons and the β where it is reached. Where the maximum lies inside a
/// complex-pair arc, da/dθ = 0 is solved by bisection on the analytic derivative.
fn alpha_max_of(fam: &AffineFamily, polys: &[Polygon]) -> (f64, f64) {
    let mut best = (f64::NAN, f64::NAN);
    for poly in polys {
        let cand = polygon_alpha_max(fam, poly);
        if best.0.is_nan() || cand.0 > best.0 {
            best = cand;
        }
    }
    best
}

fn polygon_alpha_max(fam: &AffineFamily, poly: &Polygon) -> (f64, f64) {
    let n = poly.vertices.len();
    let imax = (0..n)
        .max_by(|&i, &j| poly.vertices[i].alpha.total_cmp(&poly.vertices[j].alpha))
        .unwrap_or(0);
    refine_vertex_max(fam, poly, imax)
}

/// The largest stable stiffness with the damping restricted to [b_lo, b_hi] (a device's
/// usable damping, e.g. B ≥ 0), and the damping where it is reached: the region's maximum
/// if it lies in the band, else the best of the arcs' maxima inside the band and the exact
/// stable intervals on the band's edges. None when nothing in the band is stable.
pub fn alpha_max_within(
    fam: &AffineFamily,
    region: &StableRegion,
    b_lo: f64,
    b_hi: f64,
) -> Option<AlphaBeta> {
    let inside = |b: f64| b >= b_lo && b <= b_hi;
    if inside(region.beta_at_alpha_max) {
        return Some(AlphaBeta {
            alpha: region.alpha_max,
            beta: region.beta_at_alpha_max,
        });
    }
    let mut best: Option<AlphaBeta> = None;
    let mut offer = |a: f64, b: f64| {
        if a.is_finite() && best.is_none_or(|p| a > p.alpha) {
            best = Some(AlphaBeta { alpha: a, beta: b });
        }
    };
    for poly in &region.polygons {
        let v = &poly.vertices;
        let imax = (0..v.len())
            .filter(|&i| inside(v[i].beta))
            .max_by(|&i, &j| v[i].alpha.total_cmp(&v[j].alpha));
        if let Some(i) = imax {
            let (a, b) = refine_vertex_max(fam, poly, i);
            if inside(b) {
                offer(a, b);
            } else {
                offer(v[i].alpha, v[i].beta);
            }
        }
    }
    for b in [b_lo, b_hi].into_iter().filter(|b| b.is_finite()) {
        let ivs = crate::boundary::stable_alpha_intervals(fam, b);
        if let Some(top) = ivs
            .iter()
            .map(|iv| iv.hi)
            .filter(|h| h.is_finite())
            .reduce(f64::max)
        {
            offer(top, b);
        }
    }
    best
}

/// The maximum of a near vertex i on its arc: where it lies inside a complex-pair arc,
/// da/dθ = 0 solved by bisection on the analytic derivative.
fn refine_vertex_max(fam: &AffineFamily, poly: &Polygon, imax: usize) -> (f64, f64) {
    let n = poly.vertices.len();
    let mut cand = (poly.vertices[imax].alpha, poly.vertices[imax].beta);
    if poly.edges.iter().any(|e| e.start == imax) {
        return cand; // a corner
    }
    let (t0, t1) = (poly.thetas[(imax + n - 1) % n], poly.thetas[(imax + 1) % n]);
    if t0.is_finite() && t1.is_finite() {
        let (a, b) = (t0.min(t1), t0.max(t1));
        let (ga, gb) = (dalpha_dtheta(fam, a), dalpha_dtheta(fam, b));
        if ga.signum() != gb.signum() {
            let t = crate::boundary::bisect(a, b, |t| dalpha_dtheta(fam, t));
            if let Some(p) = curve_point(fam, t)
                && p.alpha >= cand.0
            {
                cand = (p.alpha, p.beta);
            }
        }
    }
    cand
}
