//! The passive region in the (K, B)-plane for a device damping b (Section VIII, Fig. 9,
//! generalized), and the largest passive stiffness.

use serde::Serialize;

use super::requirement::SampledWall;
use super::stiffness::passive_k_max;
use crate::error::Result;
use crate::param::Param;
use crate::params::Wall;

/// The passive region of a loop for a device damping b (Section VIII, Fig. 9, generalized):
/// {(K, B): W(1) ≥ 0, b_required(K, B) < b} as a counter-clockwise polygon in physical units.
///
/// b_required is convex and positively homogeneous in (K, B) (a maximum over θ of linear
/// functions, or of q + √(q² + c|X|²) which is a norm plus a linear function), so the region
/// is convex, has the origin as a corner on the line W(1) = 0, and scales linearly with b.
/// Its boundary point in each direction u is u·b/b_required(u); the polygon's vertices are
/// such exact boundary points, placed adaptively until every chord is within
/// [`PASSIVE_REL_TOL`] of the boundary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassiveRegion {
    /// The device damping b in Ns/m.
    pub device_damping: f64,
    /// Counter-clockwise vertices (K in N/m, B in Ns/m), the first not repeated; empty when
    /// b <= 0.
    pub vertices: Vec<Wall>,
    /// False when b_required <= 0 along some direction: the region is then unbounded and the
    /// polygon is cut at [`UNBOUNDED_CLIP`] times its bounded size.
    pub bounded: bool,
    /// The largest passive stiffness K in N/m (exact, not a vertex maximum; NaN when empty,
    /// infinite when unbounded in K).
    pub k_max: f64,
    /// The damping B in Ns/m at which it is reached.
    pub b_at_k_max: f64,
    /// Area in N/m · Ns/m.
    pub area: f64,
}

/// Chord tolerance of passive-region polygons, relative to the region's size in the
/// (KT/2, B)-plane: far below a plot's resolution; the largest passive stiffness is found
/// exactly on the boundary, not from the vertices.
pub const PASSIVE_REL_TOL: f64 = 1e-5;

/// An unbounded passive region is cut at this multiple of its bounded part's size.
pub const UNBOUNDED_CLIP: f64 = 10.0;

/// Initial directions of the adaptive boundary sampling (a half-turn of directions).
const INITIAL_DIRECTIONS: usize = 32;

/// Bisection depth limit of the boundary sampling: 2^-40 of a half-turn is far below any
/// tolerance; the limit only bounds the work at a corner.
const MAX_DEPTH: usize = 40;

impl PassiveRegion {
    /// True iff the wall lies inside the polygon (even-odd rule); the exact test is
    /// [`SampledWall::required_damping`] against b.
    pub fn contains(&self, wall: Wall) -> bool {
        let n = self.vertices.len();
        let mut inside = false;
        for i in 0..n {
            let (a, b) = (self.vertices[i], self.vertices[(i + 1) % n]);
            if (a.damping > wall.damping) != (b.damping > wall.damping) {
                let k = a.stiffness
                    + (wall.damping - a.damping) / (b.damping - a.damping)
                        * (b.stiffness - a.stiffness);
                if wall.stiffness < k {
                    inside = !inside;
                }
            }
        }
        inside
    }
}

/// A direction's boundary point in (κ, B) = (KT/2, B), Ns/m both; None when unbounded.
fn ray_point(sw: &SampledWall, b: f64, phi: f64) -> Option<(f64, f64)> {
    let (s, c) = crate::circle::sin_cos(phi);
    let wall = Wall {
        stiffness: 2.0 * c / sw.period(),
        damping: s,
    };
    let need = sw.required_damping(wall).b_required;
    (need > 0.0).then(|| (c * b / need, s * b / need))
}

/// The passive region of a loop's wall for device damping b (see [`PassiveRegion`]).
pub fn passive_region(sw: &SampledWall, b: f64) -> Result<PassiveRegion> {
    crate::error::finite(Param::DeviceDamping, b)?;
    if b <= 0.0 {
        return Ok(PassiveRegion {
            device_damping: b,
            vertices: Vec::new(),
            bounded: true,
            k_max: f64::NAN,
            b_at_k_max: f64::NAN,
            area: 0.0,
        });
    }
    let half_t = 0.5 * sw.period();
    let (lo, hi) = direction_range(sw);
    let pts = boundary_points(sw, b, lo, hi);
    let bounded = pts.iter().all(|p| p.1.is_some());
    let size = pts
        .iter()
        .filter_map(|p| p.1)
        .fold(0.0_f64, |m, (x, y)| m.max(x.hypot(y)))
        .max(f64::MIN_POSITIVE);
    let clip = UNBOUNDED_CLIP * size;
    let to_wall = |(phi, p): &(f64, Option<(f64, f64)>)| {
        let (x, y) = p.unwrap_or((clip * phi.cos(), clip * phi.sin()));
        Wall {
            stiffness: x / half_t,
            damping: y,
        }
    };
    let mut vertices = vec![Wall {
        stiffness: 0.0,
        damping: 0.0,
    }];
    vertices.extend(pts.iter().map(to_wall));
    // The end directions lie on the line W(1) = 0 exactly (cos(±π/2) rounds to 6e-17).
    let v1 = sw.dc_velocity();
    for i in [1, vertices.len() - 1] {
        vertices[i].stiffness = -vertices[i].damping * v1;
    }
    let (k_max, b_at_k_max) = match passive_k_max(sw, b) {
        Some(w) if bounded => (w.stiffness, w.damping),
        _ => (f64::INFINITY, f64::NAN),
    };
    let area = shoelace(&vertices);
    Ok(PassiveRegion {
        device_damping: b,
        vertices,
        bounded,
        k_max,
        b_at_k_max,
        area,
    })
}

type RayPoint = (f64, Option<(f64, f64)>);

/// Boundary points for directions lo..=hi, refined until chords are within tolerance.
fn boundary_points(sw: &SampledWall, b: f64, lo: f64, hi: f64) -> Vec<RayPoint> {
    let at = |phi: f64| (phi, ray_point(sw, b, phi));
    let init: Vec<RayPoint> = (0..=INITIAL_DIRECTIONS)
        .map(|i| at(lo + (hi - lo) * i as f64 / INITIAL_DIRECTIONS as f64))
        .collect();
    let size = init
        .iter()
        .filter_map(|p| p.1)
        .fold(0.0_f64, |m, (x, y)| m.max(x.hypot(y)));
    let tol = PASSIVE_REL_TOL * size;
    let mut out = vec![init[0]];
    for w in init.windows(2) {
        refine_chord(&at, w[0], w[1], tol, 0, &mut out);
        out.push(w[1]);
    }
    out
}

/// Inserts boundary points between a and b (exclusive) until the chord is within tol.
fn refine_chord(
    at: &impl Fn(f64) -> RayPoint,
    a: RayPoint,
    b: RayPoint,
    tol: f64,
    depth: usize,
    out: &mut Vec<RayPoint>,
) {
    if depth >= MAX_DEPTH {
        return;
    }
    let m = at(0.5 * (a.0 + b.0));
    let far = match (a.1, m.1, b.1) {
        (Some(pa), Some(pm), Some(pb)) => chord_distance(pa, pb, pm) > tol,
        (None, None, None) => false,
        _ => true, // where the region turns unbounded: resolve the transition
    };
    if far {
        refine_chord(at, a, m, tol, depth + 1, out);
        out.push(m);
        refine_chord(at, m, b, tol, depth + 1, out);
    }
}

/// Distance from p to the segment a–b.
fn chord_distance(a: (f64, f64), b: (f64, f64), p: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    if len2 == 0.0 {
        return (p.0 - a.0).hypot(p.1 - a.1);
    }
    let t = (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0);
    (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
}

/// The admissible directions (W(1) >= 0) in the (KT/2, B)-plane: a half-turn centred on the
/// normal of the line W(1) = 0.
fn direction_range(sw: &SampledWall) -> (f64, f64) {
    let center = sw.dc_velocity().atan2(2.0 / sw.period());
    (
        center - std::f64::consts::FRAC_PI_2,
        center + std::f64::consts::FRAC_PI_2,
    )
}

/// Shoelace area of a polygon in physical units.
fn shoelace(v: &[Wall]) -> f64 {
    let n = v.len();
    (0..n)
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % n]);
            a.stiffness * b.damping - b.stiffness * a.damping
        })
        .sum::<f64>()
        * 0.5
}
