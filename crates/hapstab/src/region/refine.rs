//! Step 6 of the region method: the stable faces' arcs resampled to the fine tolerance, and
//! the largest stable stiffness on them.

use super::*;

/// Rebuilds a stable face with its curve arcs resampled to the fine tolerance.
pub(super) fn refine_face(
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
                poly.vertices.reserve(keep);
                poly.thetas.reserve(keep);
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
pub(super) fn refine_arc(
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
pub(super) fn arc_end_theta(g: &Graph, v: usize) -> f64 {
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
/// complex-pair arc, da/dθ = 0 is solved by Brent's method on the analytic derivative.
pub(super) fn alpha_max_of(fam: &AffineFamily, polys: &[Polygon]) -> (f64, f64) {
    let mut best = (f64::NAN, f64::NAN);
    for poly in polys {
        let cand = polygon_alpha_max(fam, poly);
        if best.0.is_nan() || cand.0 > best.0 {
            best = cand;
        }
    }
    best
}

pub(super) fn polygon_alpha_max(fam: &AffineFamily, poly: &Polygon) -> (f64, f64) {
    let n = poly.vertices.len();
    let imax = (0..n)
        .max_by(|&i, &j| poly.vertices[i].a.total_cmp(&poly.vertices[j].a))
        .unwrap_or(0);
    refine_vertex_max(fam, poly, imax)
}

/// The largest stable stiffness with the damping restricted to [b_lo, b_hi] (a device's
/// usable damping, e.g. B ≥ 0), and the damping where it is reached: the region's maximum
/// if it lies in the band, else the best of the arcs' maxima inside the band and the exact
/// stable intervals on the band's edges, confirmed as the region's own ([`confirm_max`]).
/// None when nothing in the band is stable; an error when the candidate cannot be confirmed.
pub fn alpha_max_within(
    fam: &AffineFamily,
    region: &StableRegion,
    b_lo: f64,
    b_hi: f64,
) -> Result<Option<ConfirmedMax>> {
    let inside = |b: f64| b >= b_lo && b <= b_hi;
    if inside(region.b_at_a_max) && inside(region.b_stable) {
        return Ok(Some(ConfirmedMax {
            a: region.a_max,
            b: region.b_at_a_max,
            attained: region.a_max_attained,
            b_stable: region.b_stable,
            a_stable: region.a_stable,
        }));
    }
    let mut best: Option<WallPoint> = None;
    let mut offer = |a: f64, b: f64| {
        if a.is_finite() && best.is_none_or(|p| a > p.a) {
            best = Some(WallPoint { a, b });
        }
    };
    for poly in &region.polygons {
        let v = &poly.vertices;
        let imax = (0..v.len())
            .filter(|&i| inside(v[i].b))
            .max_by(|&i, &j| v[i].a.total_cmp(&v[j].a));
        if let Some(i) = imax {
            let (a, b) = refine_vertex_max(fam, poly, i);
            if inside(b) {
                offer(a, b);
            } else {
                offer(v[i].a, v[i].b);
            }
        }
    }
    for b in [b_lo, b_hi].into_iter().filter(|b| b.is_finite()) {
        let ivs = crate::boundary::stable_stiffness_intervals(fam, b);
        if let Some(top) = ivs
            .iter()
            .map(|iv| iv.hi)
            .filter(|h| h.is_finite())
            .reduce(f64::max)
        {
            offer(top, b);
        }
    }
    let Some(cand) = best else {
        return Ok(None);
    };
    confirm_max(fam, cand, (b_lo, b_hi), region.size())
        .map(Some)
        .ok_or_else(|| {
            Error::Numerical(format!(
                "the largest stable stiffness over the damping band, {} at b = {}, is not \
                 confirmed by the exact stable intervals there; the stable intervals at fixed \
                 damping remain available",
                cand.a, cand.b
            ))
        })
}

/// The maximum of a near vertex i on its arc: where it lies inside a complex-pair arc,
/// da/dθ = 0 solved by Brent's method on the analytic derivative.
pub(super) fn refine_vertex_max(fam: &AffineFamily, poly: &Polygon, imax: usize) -> (f64, f64) {
    let n = poly.vertices.len();
    let mut cand = (poly.vertices[imax].a, poly.vertices[imax].b);
    if poly.edges.iter().any(|e| e.start == imax) {
        return cand; // a corner
    }
    let (t0, t1) = (poly.thetas[(imax + n - 1) % n], poly.thetas[(imax + 1) % n]);
    if t0.is_finite() && t1.is_finite() {
        let (a, b) = (t0.min(t1), t0.max(t1));
        let (ga, gb) = (da_dtheta(fam, a), da_dtheta(fam, b));
        if ga.signum() != gb.signum() {
            let t = crate::bracket::sign_change(a, b, |t| da_dtheta(fam, t));
            if let Some(p) = curve_point(fam, t)
                && p.a >= cand.0
            {
                cand = (p.a, p.b);
            }
        }
    }
    cand
}
