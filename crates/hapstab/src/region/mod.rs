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
    LazyCircleTable, RootLine, WallPoint, curve_end, curve_point, curve_point_at, da_dtheta,
    minus_one_line, plus_one_line,
};
use crate::closed_loop::AffineFamily;
use crate::error::{Error, Result};
use crate::param::Param;
use crate::verdict::Verdict;
use crate::verdict::{decide, inside_unit_circle};

mod arrangement;
mod bounds;
mod confirm;
mod curve;
mod faces;
mod geometry;
mod refine;
mod scan;
mod stretch;
mod verify;

use arrangement::*;
use bounds::*;
pub use confirm::{CONFIRM_REL, ConfirmedMax, SUPREMUM_REL, confirm_max, confirm_max_tabulated};
use curve::*;
use faces::*;
use geometry::*;
pub use refine::alpha_max_within;
use refine::*;
use scan::*;
use stretch::*;
use verify::*;

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
    pub vertices: Vec<WallPoint>,
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
    pub fn contains(&self, p: WallPoint) -> bool {
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
    pub a_max: f64,
    /// b at which a_max is reached, or approached where it is a supremum (NaN when empty).
    pub b_at_a_max: f64,
    /// True when a_max is attained at `b_at_a_max` (stiffnesses up to a_max·(1 − 1e-6) are
    /// stable there); false where a_max is a corner that only that one damping touches, a
    /// supremum approached as b → `b_at_a_max` ([`confirm_max`]).
    pub a_max_attained: bool,
    /// A damping at which `a_stable` is stable: `b_at_a_max` when attained, one beside it
    /// for a supremum (NaN when empty).
    pub b_stable: f64,
    /// A stiffness the verdict confirms stable at `b_stable`, within 1e-6 of a_max
    /// ([`ConfirmedMax::a_stable`]; NaN when empty).
    pub a_stable: f64,
    /// Total area of the stable region in wall units.
    pub area: f64,
}

impl StableRegion {
    /// True iff (a, b) lies inside one of the polygons. The polygons follow the exact boundary
    /// to their chord tolerance (`rel_tol` × [`StableRegion::size`]); a wall closer than that
    /// to [`StableRegion::boundary_distance`] is decided by the point test, not by this.
    pub fn contains(&self, p: WallPoint) -> bool {
        self.polygons.iter().any(|q| q.contains(p))
    }

    /// The region's size, the scale its chord tolerance is relative to: the larger side of
    /// the polygons' bounding box (0 when empty).
    pub fn size(&self) -> f64 {
        self.extent().map_or(0.0, |e| e.larger_side())
    }

    /// The bounding box of the polygons' vertices, x = α (stiffness) and y = β (damping) in
    /// the family's units (None when empty).
    pub fn extent(&self) -> Option<crate::extent::Extent> {
        crate::extent::Extent::of(
            self.polygons
                .iter()
                .flat_map(|q| q.vertices.iter().map(|v| (v.a, v.b))),
        )
    }

    /// Euclidean distance from a wall to the nearest polygon edge (infinite when empty).
    pub fn boundary_distance(&self, p: WallPoint) -> f64 {
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

    /// A region whose K_max candidate (α_max, β) is yet to be confirmed ([`confirm_max`]);
    /// the area is the polygons' own.
    pub(super) fn unconfirmed(polygons: Vec<Polygon>, (alpha_max, beta): (f64, f64)) -> Self {
        let area = polygons.iter().map(Polygon::area).sum();
        Self {
            polygons,
            a_max: alpha_max,
            b_at_a_max: beta,
            a_max_attained: false,
            b_stable: f64::NAN,
            a_stable: f64::NAN,
            area,
        }
    }

    pub(super) fn empty() -> Self {
        Self {
            polygons: Vec::new(),
            a_max: f64::NAN,
            b_at_a_max: f64::NAN,
            a_max_attained: false,
            b_stable: f64::NAN,
            a_stable: f64::NAN,
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
            param: Param::RegionTolerance,
            value: rel_tol,
            range: "[1e-13, 0.1]",
        });
    }
    let budget = Budget::new(MAX_CURVE_POINTS);
    let raw_bounds = Bounds::new(fam)?;
    let raw_table = LazyCircleTable::new(fam);
    if let Some(region) = plain_attempt(fam, (&raw_bounds, &raw_table), rel_tol, &budget) {
        return Ok(region);
    }
    let slices = SliceBox::of(fam, raw_table.get(), raw_bounds.size());
    let stretch = stretch(slices);
    let stretched = stretch.map(|(sx, sy)| fam.stretched(sx, sy));
    let work = stretched.as_ref().unwrap_or(fam);
    let (bounds, table) = match &stretched {
        Some(f) => (Bounds::new(f)?, LazyCircleTable::new(f)),
        None => (raw_bounds, raw_table),
    };
    let scale = stretch.unwrap_or((1.0, 1.0));
    // The slices' box, three times its size, is where the first attempts look closely and,
    // when it is far smaller than the search window, the window the arrangement is built in.
    let hint: Option<BoxF> = slices
        .map(|b| b.focus(scale))
        .filter(|h| box_size(*h) < HINT_FRACTION * bounds.size());
    let mut zoom: Option<BoxF> = None;
    let mut limit = hint;
    let mut attempts = 0;
    let mut window: Option<BoxF> = None;
    let mut failure: Option<Error> = None;
    for _ in 0..MAX_ATTEMPTS + MAX_GROWTH {
        let level = (attempts as i32).min(MAX_ATTEMPTS as i32 - 1);
        let outcome = attempt(work, &bounds, (zoom, hint, level), limit, rel_tol, &budget);
        match outcome {
            Err(e) => {
                failure = Some(e);
                break;
            }
            Ok(Attempt::Grow(wider)) => limit = Some(wider),
            Ok(Attempt::Holed) => break,
            Ok(Attempt::Done(region, checked)) => {
                window = window.or(checked.wbox);
                let outcome = match verify(work, &bounds, &region, checked, (attempts, rel_tol)) {
                    None => confirmed(work, &table, region),
                    Some(z) => Err(z),
                };
                match outcome {
                    Ok(region) => return Ok(unstretched_by(region, stretch)),
                    Err(z) => {
                        zoom = Some(z);
                        // A zoom far smaller than the search window is also where the next
                        // arrangement is built (three times its size).
                        limit = Some(tripled(z));
                    }
                }
                attempts += 1;
                if attempts == MAX_ATTEMPTS {
                    break;
                }
            }
        }
    }
    let scan_box = window.or_else(|| bbox(bounds.polygon.iter().map(|(p, _)| *p)));
    let scanned = scan_box.and_then(|b| scanned_and_checked(work, &bounds, &table, b, rel_tol));
    if let Some(region) = scanned {
        return Ok(unstretched_by(region, stretch));
    }
    Err(failure.unwrap_or_else(|| {
        Error::Numerical(
            "the stable region could not be resolved: its exact boundary, exact slices of \
             constant damping and a direct grid of Schur–Cohn tests keep disagreeing (features \
             far smaller than the boundary curve's extent); the stable intervals at fixed \
             damping and the grid map remain available"
                .into(),
        )
    }))
}

/// The first, plain attempt (steps 1–6 without slices, stretch or focus), kept when it
/// verifies, its K_max is confirmed and it is no thinner than [`MAX_UNSTRETCHED_ASPECT`]
/// either way: the paper's regions and most loops' need nothing more, and the slices that
/// measure a thin region cost as much again.
fn plain_attempt(
    fam: &AffineFamily,
    (bounds, table): (&Bounds, &LazyCircleTable),
    rel_tol: f64,
    budget: &Budget,
) -> Option<StableRegion> {
    let Ok(Attempt::Done(region, checked)) =
        attempt(fam, bounds, (None, None, 0), None, rel_tol, budget)
    else {
        return None;
    };
    let pts = region
        .polygons
        .iter()
        .flat_map(|p| p.vertices.iter().map(|v| P::of(*v)));
    let (x0, x1, y0, y1) = bbox(pts)?;
    let aspect = (y1 - y0) / (x1 - x0);
    let square = (1.0 / MAX_UNSTRETCHED_ASPECT..=MAX_UNSTRETCHED_ASPECT).contains(&aspect);
    if !square || verify(fam, bounds, &region, checked, (0, rel_tol)).is_some() {
        return None;
    }
    confirmed(fam, table, region).ok()
}

/// The region mapped back from a stretched plane (unchanged without a stretch).
fn unstretched_by(region: StableRegion, stretch: Option<(f64, f64)>) -> StableRegion {
    stretch.map_or(region.clone(), |s| unstretched(region, s))
}

/// The region from exact slices ([`scanned_region`]) where the arrangement could not resolve
/// it: scanned over the window, then again over the found region's own box at the chord
/// tolerance of its size, verified thoroughly and its K_max confirmed; None when any of that
/// fails.
fn scanned_and_checked(
    fam: &AffineFamily,
    bounds: &Bounds,
    table: &LazyCircleTable,
    wbox: BoxF,
    rel_tol: f64,
) -> Option<StableRegion> {
    let first = scanned_region(fam, wbox, rel_tol * box_size(wbox))?;
    let region = match bbox(
        first
            .polygons
            .iter()
            .flat_map(|p| p.vertices.iter().map(|v| P::of(*v))),
    ) {
        None => first,
        Some(own) => {
            let (x0, x1, y0, y1) = own;
            let m = 0.05 * (x1 - x0).max(y1 - y0);
            let grown = (x0 - m, x1 + m, (y0 - m).max(wbox.2), (y1 + m).min(wbox.3));
            scanned_region(fam, grown, 0.99 * rel_tol * first.size())?
        }
    };
    let checked = Checked {
        wbox: Some(wbox),
        thorough: true,
    };
    if verify(fam, bounds, &region, checked, (MAX_ATTEMPTS, rel_tol)).is_some() {
        return None;
    }
    confirmed(fam, table, region).ok()
}

/// Attempts before giving up: each one zooms the coarse sampling onto where the previous
/// one disagreed with the grid, so four attempts cover a scale range of about 10¹².
const MAX_ATTEMPTS: usize = 4;

/// Times a limited window may grow (fourfold each) because a stable face reached its edge:
/// 4¹² covers the 10⁷ between a slices' box and the widest search window.
const MAX_GROWTH: usize = 12;

/// A limited window is used when the slices' box is smaller than this fraction of the search
/// window: the arrangement's tolerances are relative to its window, so a region 10⁶ times
/// smaller than the curve's extent is built in a window of its own size.
const LIMIT_FRACTION: f64 = 1e-3;

/// The slices' box guides the first attempts only when it is smaller than this fraction of
/// the bounds: a region about as large as its bounds (the paper's) is sampled well without
/// a focus, whose finer coarse pass would cost more than the arrangement.
const HINT_FRACTION: f64 = 0.1;

/// An axis-aligned box (a0, a1, b0, b1).
type BoxF = (f64, f64, f64, f64);

/// What one attempt found: a region to verify, or a stable face that reached the edge of a
/// limited window (the box to build the next window in), or a region with a hole.
enum Attempt {
    Done(StableRegion, Checked),
    Grow(BoxF),
    /// A stable face with an unstable island inside (a hole): built from exact slices
    /// instead, as polygons around the hole.
    Holed,
}

/// One pass of the method (steps 2–6 of the module doc) with the coarse sampling's focus (a
/// zoom from the verification, the slices' hint) and its refinement level (the attempt's
/// number), and an optional limit box for the window.
fn attempt(
    fam: &AffineFamily,
    bounds: &Bounds,
    focus: (Option<BoxF>, Option<BoxF>, i32),
    limit: Option<BoxF>,
    rel_tol: f64,
    budget: &Budget,
) -> Result<Attempt> {
    let coarse = coarse_curve(fam, bounds, focus, budget)?;
    let Some(full) = search_window(bounds, &coarse) else {
        let none = Checked {
            wbox: None,
            thorough: true,
        };
        return Ok(Attempt::Done(StableRegion::empty(), none));
    };
    let wbox = bbox(full.polygon.iter().map(|(p, _)| *p));
    let limited = limit
        .filter(|l| box_size(*l) < LIMIT_FRACTION * full.size)
        .and_then(|l| window_of_box(bounds, l).map(|w| (l, w)));
    let window = limited.as_ref().map_or(&full, |(_, w)| w);
    let graph = arrangement(fam, window, &coarse)?;
    let cycles = faces(&graph);
    let consistent = euler_holds(&graph, cycles.len());
    let islands = island_points(&graph, &cycles);
    let faces = stable_faces(fam, &graph, cycles);
    if has_hole(&islands, &faces) {
        return Ok(Attempt::Holed);
    }
    if let Some((l, _)) = limited
        && faces.iter().any(|(f, _)| touches_window_cut(&graph, f))
    {
        return Ok(Attempt::Grow(grown(l)));
    }
    let checked = Checked {
        wbox,
        thorough: faces.is_empty() || !consistent,
    };
    if faces.is_empty() {
        return Ok(Attempt::Done(StableRegion::empty(), checked));
    }
    // The coarse faces are within the coarse tolerance of the true region, so 0.99 keeps the
    // chord tolerance below rel_tol of the true size.
    let tol = 0.99 * rel_tol * faces_size(&faces);
    let polygons = faces
        .iter()
        .map(|(f, _)| refine_face(fam, &graph, f, tol, budget))
        .collect::<Result<Vec<Polygon>>>()?;
    let max = alpha_max_of(fam, &polygons);
    Ok(Attempt::Done(
        StableRegion::unconfirmed(polygons, max),
        checked,
    ))
}

/// True when a face has an edge cut by the window's box (not a z = ±1 line nor the curve): the
/// stable set goes on beyond the window.
fn touches_window_cut(g: &Graph, f: &[(usize, bool)]) -> bool {
    f.iter().any(|&(e, _)| g.edges[e].3 == EdgeKind::Window)
}

/// The region with its K_max confirmed ([`confirm_max`]), or the box around K_max to zoom the
/// next attempt onto when the exact intervals or the verdict contradict it. An empty region
/// is returned as it is.
fn confirmed(
    fam: &AffineFamily,
    table: &LazyCircleTable,
    mut r: StableRegion,
) -> std::result::Result<StableRegion, BoxF> {
    if r.polygons.is_empty() {
        return Ok(r);
    }
    let cand = WallPoint {
        a: r.a_max,
        b: r.b_at_a_max,
    };
    let size = r.size();
    match confirm_max_tabulated(fam, table, cand, (f64::NEG_INFINITY, f64::INFINITY), size) {
        Some(c) => {
            r.a_max = c.a;
            r.b_at_a_max = c.b;
            r.a_max_attained = c.attained;
            r.b_stable = c.b_stable;
            r.a_stable = c.a_stable;
            Ok(r)
        }
        None => {
            let h = 1e-3 * size;
            Err((cand.a - h, cand.a + h, cand.b - h, cand.b + h))
        }
    }
}

/// A box three times as large about the same centre.
fn tripled((x0, x1, y0, y1): BoxF) -> BoxF {
    let (hx, hy) = (x1 - x0, y1 - y0);
    (x0 - hx, x1 + hx, y0 - hy, y1 + hy)
}

/// A box four times as large about the same centre.
fn grown((x0, x1, y0, y1): BoxF) -> BoxF {
    let (cx, cy, hx, hy) = (
        0.5 * (x0 + x1),
        0.5 * (y0 + y1),
        2.0 * (x1 - x0),
        2.0 * (y1 - y0),
    );
    (cx - hx, cx + hx, cy - hy, cy + hy)
}

/// How an attempt's region must be verified: over which box, and whether thoroughly (exact
/// slices as well as the grid) because the arrangement broke Euler's formula or found
/// nothing stable.
#[derive(Clone, Copy)]
struct Checked {
    pub(super) wbox: Option<BoxF>,
    pub(super) thorough: bool,
}
