//! Polygon simplification for drawing: the library's region polygons are exact to 1e-9 of
//! the region's size (thousands of vertices); a plot needs a fraction of a pixel. Each edge
//! of a polygon (a run between two corners) is simplified on its own by Douglas–Peucker, so
//! every corner — every point where two boundary pieces meet — is kept exactly.

use hapstab::boundary::AlphaBeta;
use hapstab::region::Polygon;

/// Douglas–Peucker on an open polyline: keeps both ends and every point farther than `tol`
/// from the chord of its run. Iterative (no recursion depth issue).
fn douglas_peucker(pts: &[AlphaBeta], tol: f64) -> Vec<AlphaBeta> {
    let n = pts.len();
    if n <= 2 || tol <= 0.0 {
        return pts.to_vec();
    }
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[n - 1] = true;
    let mut stack = vec![(0usize, n - 1)];
    while let Some((a, b)) = stack.pop() {
        if b <= a + 1 {
            continue;
        }
        let (pa, pb) = (pts[a], pts[b]);
        let (dx, dy) = (pb.alpha - pa.alpha, pb.beta - pa.beta);
        let len = dx.hypot(dy);
        let mut best = (0.0_f64, a);
        for (i, p) in pts.iter().enumerate().take(b).skip(a + 1) {
            let (ex, ey) = (p.alpha - pa.alpha, p.beta - pa.beta);
            let dist = if len > 0.0 {
                (dx * ey - dy * ex).abs() / len
            } else {
                ex.hypot(ey)
            };
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
    pts.iter()
        .zip(keep)
        .filter_map(|(p, k)| k.then_some(*p))
        .collect()
}

/// The simplified vertex ring of a polygon (corners kept exactly) and, for each edge, the
/// index of its first vertex in the new ring.
pub fn simplify_polygon(poly: &Polygon, tol: f64) -> (Vec<AlphaBeta>, Vec<usize>) {
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
        let run: Vec<AlphaBeta> = (s..=e.max(s)).map(|i| poly.vertices[i % n]).collect();
        let simp = douglas_peucker(&run, tol);
        new_starts.push(out.len());
        // drop the run's last point: it is the next edge's first vertex
        out.extend_from_slice(&simp[..simp.len().saturating_sub(1).max(1)]);
    }
    (out, new_starts)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ab(alpha: f64, beta: f64) -> AlphaBeta {
        AlphaBeta { alpha, beta }
    }

    #[test]
    fn keeps_ends_and_far_points() {
        let pts: Vec<AlphaBeta> = (0..=100)
            .map(|i| {
                let x = i as f64 / 100.0;
                ab(x, if i == 50 { 1.0 } else { 0.0 })
            })
            .collect();
        let s = douglas_peucker(&pts, 1e-3);
        assert_eq!(s.len(), 5, "{s:?}");
        assert_eq!(s[0], pts[0]);
        assert_eq!(s[4], pts[100]);
        assert!(s.contains(&pts[50]));
    }

    #[test]
    fn circle_is_simplified_within_tolerance() {
        let pts: Vec<AlphaBeta> = (0..=10_000)
            .map(|i| {
                let t = std::f64::consts::PI * i as f64 / 10_000.0;
                ab(t.cos(), t.sin())
            })
            .collect();
        let s = douglas_peucker(&pts, 1e-4);
        assert!(s.len() < 300, "{}", s.len());
        // every dropped point lies within tol of the simplified polyline (sagitta check)
        for w in s.windows(2) {
            let mid = ab(
                0.5 * (w[0].alpha + w[1].alpha),
                0.5 * (w[0].beta + w[1].beta),
            );
            let r = mid.alpha.hypot(mid.beta);
            assert!(1.0 - r <= 1.0001e-4, "{}", 1.0 - r);
        }
    }
}
