//! Fewer points for dense data, in one place for every figure and the explorer: min-max
//! decimation of a time series ([`decimate_minmax`]), and Ramer–Douglas–Peucker thinning of
//! a polyline ([`douglas_peucker`]), of a closed ring ([`simplify_ring`]) and of a region's
//! polygon edge by edge, its corners kept exactly ([`simplify_polygon`]).
//!
//! The tolerance is measured in scaled coordinates (x·sx, y·sy): pixels for a drawing, a
//! fraction of the axis ranges for a figure's outlines, the data's own units for the
//! explorer. A dropped point lies within the tolerance of the segment that replaces it, so
//! the thinned line stays within the tolerance of the original.

use hapstab::boundary::WallPoint;
use hapstab::region::Polygon;

use crate::clip::segment_distance;

/// Decimates a time series with increasing x to at most `2 · buckets` points, keeping each
/// bucket's minimum and maximum in order, so that oscillations stay visible.
pub fn decimate_minmax(points: &[(f64, f64)], buckets: usize) -> Vec<(f64, f64)> {
    if buckets == 0 || points.len() <= 2 * buckets {
        return points.to_vec();
    }
    let per = points.len().div_ceil(buckets);
    let mut out = Vec::with_capacity(2 * buckets + 1);
    for chunk in points.chunks(per) {
        let (mut imin, mut imax) = (0, 0);
        for (i, p) in chunk.iter().enumerate() {
            if p.1 < chunk[imin].1 {
                imin = i;
            }
            if p.1 > chunk[imax].1 {
                imax = i;
            }
        }
        let (a, b) = (imin.min(imax), imin.max(imax));
        out.push(chunk[a]);
        if b != a {
            out.push(chunk[b]);
        }
    }
    out
}

/// Marks in `keep` the points of each run `(i, j)` of `q` (scaled points) that
/// Douglas–Peucker keeps: the farthest point of a run from its chord splits it while it lies
/// farther than `tol` (a non-finite distance always splits). Iterative: no recursion depth.
fn mark_kept(q: &[(f64, f64)], runs: Vec<(usize, usize)>, tol: f64, keep: &mut [bool]) {
    let mut stack = runs;
    while let Some((a, b)) = stack.pop() {
        if b <= a + 1 {
            continue;
        }
        let mut best = (0.0_f64, a);
        for (i, &p) in q.iter().enumerate().take(b).skip(a + 1) {
            let dist = segment_distance(p, q[a], q[b]);
            if dist > best.0 || !dist.is_finite() {
                best = (dist, i);
            }
        }
        if best.0 > tol || !best.0.is_finite() {
            keep[best.1] = true;
            stack.push((a, best.1));
            stack.push((best.1, b));
        }
    }
}

/// The points whose `keep` flag is set.
fn kept<T: Copy>(points: &[T], keep: &[bool]) -> Vec<T> {
    points
        .iter()
        .zip(keep)
        .filter_map(|(&p, &k)| k.then_some(p))
        .collect()
}

/// Ramer–Douglas–Peucker on an open polyline: keeps both ends and every point farther than
/// `tol` from the chord of its run, distances measured on (x·sx, y·sy). A tolerance of 0 or
/// less keeps every point.
pub fn douglas_peucker(points: &[(f64, f64)], (sx, sy): (f64, f64), tol: f64) -> Vec<(f64, f64)> {
    let n = points.len();
    if n <= 2 || tol <= 0.0 {
        return points.to_vec();
    }
    let q: Vec<(f64, f64)> = points.iter().map(|p| (p.0 * sx, p.1 * sy)).collect();
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[n - 1] = true;
    mark_kept(&q, vec![(0, n - 1)], tol, &mut keep);
    kept(points, &keep)
}

/// [`douglas_peucker`] of a closed ring, returned closed (last = first): the ring is split
/// first at its vertex farthest from the first one, so that both halves have a chord.
pub fn simplify_ring(ring: &[(f64, f64)], (sx, sy): (f64, f64), tol: f64) -> Vec<(f64, f64)> {
    let mut pts: Vec<(f64, f64)> = ring.to_vec();
    if let Some(&first) = ring.first() {
        pts.push(first);
    }
    let n = pts.len();
    if n < 4 || tol <= 0.0 {
        return pts;
    }
    let q: Vec<(f64, f64)> = pts.iter().map(|p| (p.0 * sx, p.1 * sy)).collect();
    let far = (1..n - 1)
        .max_by(|&i, &j| {
            let d = |k: usize| (q[k].0 - q[0].0).hypot(q[k].1 - q[0].1);
            d(i).total_cmp(&d(j))
        })
        .unwrap_or(n / 2);
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[far] = true;
    keep[n - 1] = true;
    mark_kept(&q, vec![(0, far), (far, n - 1)], tol, &mut keep);
    kept(&pts, &keep)
}

/// The simplified vertex ring of a region's polygon and, for each edge, the index of its
/// first vertex in the new ring. Each edge (the run between two corners, where two boundary
/// pieces meet) is thinned on its own by [`douglas_peucker`] to `tol` in (α, β), so every
/// corner is kept exactly.
pub fn simplify_polygon(poly: &Polygon, tol: f64) -> (Vec<WallPoint>, Vec<usize>) {
    let n = poly.vertices.len();
    if n == 0 {
        return (Vec::new(), Vec::new());
    }
    let mut starts: Vec<usize> = poly.edges.iter().map(|e| e.start.min(n - 1)).collect();
    if starts.is_empty() || !starts.windows(2).all(|w| w[0] < w[1]) {
        starts = vec![0];
    }
    let mut out = Vec::with_capacity(n.min(4096));
    let mut new_starts = Vec::with_capacity(starts.len());
    for (k, &s) in starts.iter().enumerate() {
        let e = if k + 1 < starts.len() {
            starts[k + 1]
        } else {
            starts[0] + n
        };
        // vertices s ..= e (indices mod n); e is the next edge's first vertex
        let run: Vec<(f64, f64)> = (s..=e.max(s))
            .map(|i| poly.vertices[i % n])
            .map(|v| (v.a, v.b))
            .collect();
        let simp = douglas_peucker(&run, (1.0, 1.0), tol);
        new_starts.push(out.len());
        // drop the run's last point: it is the next edge's first vertex
        let head = &simp[..simp.len().saturating_sub(1).max(1)];
        out.extend(
            head.iter()
                .map(|&(alpha, beta)| WallPoint { a: alpha, b: beta }),
        );
    }
    (out, new_starts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_ends_and_far_points() {
        let pts: Vec<(f64, f64)> = (0..=100)
            .map(|i| (i as f64 / 100.0, if i == 50 { 1.0 } else { 0.0 }))
            .collect();
        let s = douglas_peucker(&pts, (1.0, 1.0), 1e-3);
        assert_eq!(s.len(), 5, "{s:?}");
        assert_eq!(s[0], pts[0]);
        assert_eq!(s[4], pts[100]);
        assert!(s.contains(&pts[50]));
        // the same line on axes ten times wider: the spike is a tenth as far in x
        assert_eq!(douglas_peucker(&pts, (10.0, 1.0), 1e-3).len(), 5);
        // no tolerance, no thinning
        assert_eq!(douglas_peucker(&pts, (1.0, 1.0), 0.0).len(), 101);
    }

    #[test]
    fn circle_is_simplified_within_tolerance() {
        let pts: Vec<(f64, f64)> = (0..=10_000)
            .map(|i| {
                let t = std::f64::consts::PI * i as f64 / 10_000.0;
                (t.cos(), t.sin())
            })
            .collect();
        let s = douglas_peucker(&pts, (1.0, 1.0), 1e-4);
        assert!(s.len() < 300, "{}", s.len());
        // every dropped point lies within tol of the simplified polyline (sagitta check)
        for w in s.windows(2) {
            let mid = (0.5 * (w[0].0 + w[1].0), 0.5 * (w[0].1 + w[1].1));
            let r = mid.0.hypot(mid.1);
            assert!(1.0 - r <= 1.0001e-4, "{}", 1.0 - r);
        }
    }

    #[test]
    fn a_ring_stays_closed_and_keeps_its_far_side() {
        let ring: Vec<(f64, f64)> = (0..1000)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / 1000.0;
                (2.0 * t.cos(), t.sin())
            })
            .collect();
        let s = simplify_ring(&ring, (0.5, 1.0), 1e-3);
        assert!(s.len() < 200 && s.len() > 8, "{}", s.len());
        assert_eq!(s.first(), s.last());
        assert!(s.contains(&ring[500]), "the vertex farthest from the first");
    }

    #[test]
    fn non_finite_points_are_kept() {
        let pts = [(0.0, 0.0), (0.5, f64::NAN), (1.0, 0.0)];
        assert_eq!(douglas_peucker(&pts, (1.0, 1.0), 0.1).len(), 3);
    }
}
