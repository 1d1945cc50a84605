//! Step 5 of the region method: the faces of the planar graph and their classification by
//! the roots inside the unit circle at an interior point.

use super::*;

/// Faces of the planar graph as cycles of (edge, forward?) with the face on the left.
pub(super) fn faces(g: &Graph) -> Vec<Vec<(usize, bool)>> {
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

/// A face as its cycle of half-edges and its vertices.
pub(super) type Face = (Vec<(usize, bool)>, Vec<WallPoint>);

/// Euler's formula for a planar graph with C connected components, counted in boundary
/// cycles (each component's outer cycle separately): V − E + cycles = 2C. A walk that
/// breaks it means a crossing was missed or the angular order was confused by nearly
/// coincident pieces; the region is then verified thoroughly.
pub(super) fn euler_holds(g: &Graph, cycles: usize) -> bool {
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

/// True when an island lies inside a face that is not bounded by the island itself: the
/// face has a hole.
pub(super) fn has_hole(islands: &[(WallPoint, Vec<usize>)], faces: &[Face]) -> bool {
    islands.iter().any(|(p, edges)| {
        faces
            .iter()
            .any(|(f, v)| f.iter().all(|(e, _)| !edges.contains(e)) && point_in(v, *p))
    })
}

/// The counter-clockwise faces whose interior point has every root inside the unit circle
/// ([`inside_unit_circle`]: a face holds a constant number of roots inside).
pub(super) fn stable_faces(
    fam: &AffineFamily,
    g: &Graph,
    cycles: Vec<Vec<(usize, bool)>>,
) -> Vec<Face> {
    let mut coeffs = vec![0.0; fam.degree() + 1];
    cycles
        .into_iter()
        .filter_map(|f| {
            let pts = face_points(g, &f);
            if pts.len() < 3 || shoelace(&pts) <= 0.0 {
                return None;
            }
            let ip = interior_point(&pts)?;
            (inside_unit_circle(fam, ip.a, ip.b, &mut coeffs) == Some(true)).then_some((f, pts))
        })
        .collect()
}

/// A vertex of each clockwise cycle made of curve edges only (the outer boundary of a closed
/// curve loop, an island, seen from the face around it), with the cycle's edges.
pub(super) fn island_points(
    g: &Graph,
    cycles: &[Vec<(usize, bool)>],
) -> Vec<(WallPoint, Vec<usize>)> {
    cycles
        .iter()
        .filter(|f| {
            f.iter()
                .all(|&(e, _)| matches!(g.edges[e].3, EdgeKind::Complex { .. }))
        })
        .filter_map(|f| {
            let pts = face_points(g, f);
            let edges = f.iter().map(|&(e, _)| e).collect();
            (pts.len() >= 3 && shoelace(&pts) < 0.0).then(|| (pts[0], edges))
        })
        .collect()
}

pub(super) fn face_points(g: &Graph, f: &[(usize, bool)]) -> Vec<WallPoint> {
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
pub(super) fn faces_size(faces: &[Face]) -> f64 {
    let pts = faces.iter().flat_map(|(_, v)| v.iter().map(|p| P::of(*p)));
    bbox(pts).map_or(0.0, |(x0, x1, y0, y1)| (x1 - x0).max(y1 - y0))
}

/// A point strictly inside a counter-clockwise polygon, as deep inside as a few probes find:
/// halfway across the face from the midpoint of one of its longest edges, checked by the
/// even-odd rule; else a grid point inside.
pub(super) fn interior_point(v: &[WallPoint]) -> Option<WallPoint> {
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
        let p = WallPoint {
            a: x0 + (x1 - x0) * ((k % m) as f64 + 0.5 + GRID_JITTER) / m as f64,
            b: y0 + (y1 - y0) * ((k / m) as f64 + 0.5 + GRID_JITTER_Y) / m as f64,
        };
        point_in(v, p).then_some(p)
    })
}
