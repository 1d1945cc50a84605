//! The check of a computed region against direct point tests and exact slices of constant
//! damping, and the box the next attempt zooms onto when they disagree.

use super::*;

/// The region's edges bucketed by damping, for point-in-region tests in O(edges/bucket)
/// instead of O(vertices) (the even-odd rule counts crossings of a ray toward −∞ in a).
/// The buckets are one array of edge numbers in bucket order (compressed rows): a region of
/// 10⁴–10⁵ vertices is indexed with three small allocations, where a vector per bucket of
/// copied edges cost more in fresh memory pages than every point test together.
pub(super) struct EdgeIndex<'a> {
    vertices: Vec<&'a [WallPoint]>,
    /// First edge number of each polygon (edge i of polygon j is starts[j] + i).
    starts: Vec<u32>,
    y0: f64,
    h: f64,
    /// Bucket k holds edges[offsets[k]..offsets[k + 1]].
    offsets: Vec<u32>,
    edges: Vec<u32>,
}

/// Buckets of an [`EdgeIndex`].
const EDGE_BUCKETS: usize = 256;

impl<'a> EdgeIndex<'a> {
    pub(super) fn new(region: &'a StableRegion) -> Self {
        let vertices: Vec<&[WallPoint]> = region
            .polygons
            .iter()
            .map(|p| p.vertices.as_slice())
            .collect();
        let pts = vertices.iter().flat_map(|v| v.iter().map(|q| P::of(*q)));
        let (_, _, y0, y1) = bbox(pts).unwrap_or((0.0, 0.0, 0.0, 0.0));
        let nb = EDGE_BUCKETS;
        let h = ((y1 - y0) / nb as f64).max(f64::MIN_POSITIVE);
        let per = 1.0 / h;
        // each vertex's bucket, once (truncation is the floor: the argument is non-negative)
        let buckets: Vec<Vec<u16>> = vertices
            .iter()
            .map(|v| {
                v.iter()
                    .map(|q| (((q.b - y0) * per).max(0.0) as usize).min(nb - 1) as u16)
                    .collect()
            })
            .collect();
        let span = |k: &[u16], i: usize| {
            let (a, b) = (k[i], k[(i + 1) % k.len()]);
            (a.min(b) as usize, a.max(b) as usize)
        };
        let mut starts = Vec::with_capacity(vertices.len());
        let mut offsets = vec![0_u32; nb + 1];
        let mut total = 0_u32;
        for k in &buckets {
            starts.push(total);
            total += k.len() as u32;
            for i in 0..k.len() {
                let (lo, hi) = span(k, i);
                for c in &mut offsets[lo + 1..=hi + 1] {
                    *c += 1;
                }
            }
        }
        for k in 0..nb {
            offsets[k + 1] += offsets[k];
        }
        let mut fill = offsets.clone();
        let mut edges = vec![0_u32; offsets[nb] as usize];
        for (k, &start) in buckets.iter().zip(&starts) {
            for i in 0..k.len() {
                let (lo, hi) = span(k, i);
                for f in &mut fill[lo..=hi] {
                    edges[*f as usize] = start + i as u32;
                    *f += 1;
                }
            }
        }
        Self {
            vertices,
            starts,
            y0,
            h,
            offsets,
            edges,
        }
    }

    pub(super) fn is_empty(&self) -> bool {
        self.edges.is_empty()
    }

    /// The end points of edge number e.
    fn edge(&self, e: u32) -> (P, P) {
        let j = self.starts.partition_point(|&s| s <= e) - 1;
        let v = self.vertices[j];
        let i = (e - self.starts[j]) as usize;
        (P::of(v[i]), P::of(v[(i + 1) % v.len()]))
    }

    pub(super) fn contains(&self, p: P) -> bool {
        let k = ((p.y - self.y0) / self.h).floor();
        if !(k >= 0.0 && (k as usize) < EDGE_BUCKETS) {
            return false;
        }
        let k = k as usize;
        let mut inside = false;
        for &e in &self.edges[self.offsets[k] as usize..self.offsets[k + 1] as usize] {
            let (a, b) = self.edge(e);
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
pub(super) fn grid_side(fam: &AffineFamily) -> usize {
    if fam.degree() <= 64 { 16 } else { 10 }
}

/// Checks the region against a grid of direct Schur–Cohn tests over the search window (and
/// the bounds' box when the window is absent), the wall-free point, and when `thorough` also
/// against the exact stable intervals on slices of constant damping; disagreements within
/// twice the chord tolerance (`rel_tol` of the size) of the polygon's edges do not count.
/// None when they agree; otherwise the box to zoom the next attempt onto: the disagreeing and
/// the stable points, two cells wide.
pub(super) fn verify(
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
    // Every vertex of a stable region lies in the search window by construction; one outside
    // means a chord did not follow the curve (it ran off to infinity between samples).
    if vertex_outside(region, wbox).is_some() {
        return Some(wbox);
    }
    let index = EdgeIndex::new(region);
    let mut suspects = grid_suspects(fam, &index, wbox, m);
    if checked.thorough {
        suspects.extend(slice_suspects(fam, &index, wbox));
    }
    // "Nothing is stable" is checked exactly where it matters most, on the stiffness axis
    // (no virtual damping): a region far thinner than the window would slip between slices.
    if region.polygons.is_empty() {
        let ivs = crate::boundary::stable_stiffness_intervals(fam, 0.0);
        let mids = ivs.iter().filter(|iv| iv.hi > iv.lo).map(|iv| {
            let x = 0.5 * (iv.lo.max(wbox.0) + iv.hi.min(wbox.1));
            (P { x, y: 0.0 }, false)
        });
        suspects.extend(mids);
        suspects.extend(ray_suspects(fam, wbox));
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

/// Decades of the geometric slices an empty answer is checked on: stiffness axes at
/// b = ±10^{−k} and damping axes at a = ±10^{−k} of the window's size, k = 0..EMPTY_DECADES.
/// An undamped plant's region is a sliver at the wall-free point, far smaller than any grid
/// of the window and often thinner than a ray's angle, that one of these slices crosses.
const EMPTY_DECADES: i32 = 13;

/// The midpoints of the stable intervals on the geometric slices (each a disagreement with an
/// empty answer), clipped to the box.
fn ray_suspects(fam: &AffineFamily, (x0, x1, y0, y1): BoxF) -> Vec<(P, bool)> {
    let size = (x1 - x0).max(y1 - y0);
    let table = crate::boundary::CircleTable::new(fam);
    let mut out = Vec::new();
    for k in 0..EMPTY_DECADES {
        for sign in [1.0, -1.0] {
            let v = sign * size * 10f64.powi(-k) * (1.0 + GRID_JITTER);
            let lines = [
                (crate::boundary::WallLine::stiffness_axis(v), false),
                (
                    crate::boundary::WallLine {
                        from: WallPoint { a: v, b: 0.0 },
                        dir: WallPoint { a: 0.0, b: 1.0 },
                    },
                    true,
                ),
            ];
            for (line, vertical) in lines {
                let cr = crate::boundary::line_crossings_tabulated(fam, &table, &line);
                for iv in crate::boundary::stable_between(fam, &line, &cr) {
                    if iv.hi <= iv.lo || iv.hi.is_nan() || iv.lo.is_nan() {
                        continue;
                    }
                    let t = match (iv.lo.is_finite(), iv.hi.is_finite()) {
                        (true, true) => 0.5 * (iv.lo + iv.hi),
                        (true, false) => iv.lo + size,
                        (false, true) => iv.hi - size,
                        (false, false) => 0.0,
                    };
                    let p = if vertical {
                        P { x: v, y: t }
                    } else {
                        P { x: t, y: v }
                    };
                    if p.finite() && p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1 {
                        out.push((p, false));
                    }
                }
            }
        }
    }
    out
}

/// A polygon vertex outside the box (beyond a rounding slack of its size), if any.
pub(super) fn vertex_outside(region: &StableRegion, (x0, x1, y0, y1): BoxF) -> Option<WallPoint> {
    let slack = 1e-9 * (x1 - x0).max(y1 - y0);
    region
        .polygons
        .iter()
        .flat_map(|q| q.vertices.iter())
        .find(|v| v.a < x0 - slack || v.a > x1 + slack || v.b < y0 - slack || v.b > y1 + slack)
        .copied()
}

/// The region's bounding box doubled about its centre (None when empty).
pub(super) fn region_box(region: &StableRegion) -> Option<BoxF> {
    let pts = region
        .polygons
        .iter()
        .flat_map(|q| q.vertices.iter().map(|v| P::of(*v)));
    let (x0, x1, y0, y1) = bbox(pts)?;
    let (hx, hy) = (x1 - x0, y1 - y0);
    Some((x0 - 0.5 * hx, x1 + 0.5 * hx, y0 - 0.5 * hy, y1 + 0.5 * hy))
}

/// The larger side of a box.
pub(super) fn box_size((x0, x1, y0, y1): BoxF) -> f64 {
    (x1 - x0).max(y1 - y0)
}

/// Grid points that are stable or where the region disagrees with the Schur–Cohn test,
/// each with "agrees?".
pub(super) fn grid_suspects(
    fam: &AffineFamily,
    region: &EdgeIndex,
    wbox: BoxF,
    m: usize,
) -> Vec<(P, bool)> {
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
            let (s, c) =
                crate::circle::sin_cos(k as f64 * std::f64::consts::FRAC_PI_4 + GRID_JITTER);
            out.extend(probe(fam, region, P { x: r * c, y: r * s }, &mut coeffs));
        }
    }
    out
}

/// Distance of the probes from the wall-free point, relative to the window.
pub(super) const PROBE_RADIUS: f64 = 1e-3;

/// A verification point if it is stable or the region disagrees with the Schur–Cohn test
/// there.
pub(super) fn probe(
    fam: &AffineFamily,
    region: &EdgeIndex,
    p: P,
    coeffs: &mut [f64],
) -> Option<(P, bool)> {
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
pub(super) fn slices(fam: &AffineFamily) -> usize {
    match fam.degree() {
        0..=64 => 48,
        65..=300 => 16,
        _ => 6,
    }
}

/// On slices of constant damping across the box, the exact stable intervals
/// ([`crate::boundary::stable_stiffness_intervals`]) against the region: each interval's
/// midpoint must be inside, the midpoints of the gaps outside.
pub(super) fn slice_suspects(fam: &AffineFamily, region: &EdgeIndex, wbox: BoxF) -> Vec<(P, bool)> {
    let (x0, x1, y0, y1) = wbox;
    let n = slices(fam);
    // One θ scan of the family serves every slice (the same crossings, no sine per slice).
    let table = crate::boundary::CircleTable::new(fam);
    (0..n)
        .into_par_iter()
        .flat_map_iter(|j| {
            let b = y0 + (y1 - y0) * (j as f64 + 0.5 + GRID_JITTER) / n as f64;
            let ivs = crate::boundary::stable_stiffness_intervals_tabulated(fam, &table, b);
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
pub(super) const GRID_JITTER: f64 = 0.114_213_562_373_095_05;

/// Offset in b (the golden ratio's 0.618… − 0.5). It differs from [`GRID_JITTER`] and their
/// sum is irrational, so that no diagonal of the box runs through grid points: the window's
/// corners often lie on a z = ±1 line, and a grid on that line's diagonal would test walls
/// with a root exactly on the circle.
pub(super) const GRID_JITTER_Y: f64 = 0.118_033_988_749_894_85;
