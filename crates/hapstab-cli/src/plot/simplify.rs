//! Fewer points for dense data: min-max decimation of a time series, and Ramer–Douglas–Peucker
//! thinning in pixel space before drawing.

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

/// Ramer–Douglas–Peucker simplification in pixel space: drops points within `tol_px` pixels
/// of the chord that replaces them (first and last kept). plotters rounds vertices to whole
/// pixels, so a dense curve would otherwise zig-zag and its thick-line joins would fringe.
pub(super) fn thin(points: &[(f64, f64)], (sx, sy): (f64, f64), tol_px: f64) -> Vec<(f64, f64)> {
    let n = points.len();
    if n <= 2 {
        return points.to_vec();
    }
    let px = |p: (f64, f64)| (p.0 * sx, p.1 * sy);
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[n - 1] = true;
    let mut stack = vec![(0usize, n - 1)];
    while let Some((i, j)) = stack.pop() {
        if j <= i + 1 {
            continue;
        }
        let (a, b) = (px(points[i]), px(points[j]));
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len = dx.hypot(dy);
        let (mut worst, mut at) = (-1.0, i);
        for (k, &p) in points.iter().enumerate().take(j).skip(i + 1) {
            let q = px(p);
            let d = if len > 0.0 {
                ((q.0 - a.0) * dy - (q.1 - a.1) * dx).abs() / len
            } else {
                (q.0 - a.0).hypot(q.1 - a.1)
            };
            if d > worst {
                worst = d;
                at = k;
            }
        }
        if worst > tol_px {
            keep[at] = true;
            stack.push((i, at));
            stack.push((at, j));
        }
    }
    points
        .iter()
        .zip(keep)
        .filter_map(|(&p, k)| k.then_some(p))
        .collect()
}
