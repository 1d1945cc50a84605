//! Step 4 of the region method: the arrangement of the curve chains and the window's edges as
//! a planar graph, every crossing refined on the curve itself.

use super::*;

/// A polyline segment of the arrangement.
#[derive(Clone, Copy, Debug)]
pub(super) struct Seg {
    pub(super) p: P,
    pub(super) q: P,
    /// Curve: θ at p and q; border: NaN.
    pub(super) tp: f64,
    pub(super) tq: f64,
    /// Chain id (curve chains) or [`BORDER`] (window edges).
    pub(super) owner: usize,
    /// Index within the owner.
    pub(super) idx: usize,
    pub(super) kind: EdgeKind,
}

pub(super) const BORDER: usize = usize::MAX / 2;

impl Seg {
    pub(super) fn is_curve(&self) -> bool {
        self.owner != BORDER
    }
    pub(super) fn at(&self, t: f64) -> P {
        self.p.lerp(self.q, t)
    }
}

pub(super) fn seg_intersect(a: &Seg, b: &Seg) -> Option<(f64, f64)> {
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
pub(super) fn split_seg(fam: &AffineFamily, s: &Seg) -> Option<[Seg; 2]> {
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
pub(super) fn refine_cc(fam: &AffineFamily, a: &Seg, b: &Seg) -> (P, f64, f64) {
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
pub(super) fn refine_cl(fam: &AffineFamily, a: &Seg, h: &HalfPlane) -> (P, f64) {
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
pub(super) fn chains(
    fam: &AffineFamily,
    coarse: &[(f64, P)],
    window: &Window,
) -> Vec<Vec<(f64, P)>> {
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
pub(super) type Cut = (f64, usize, f64);

/// Graph edge: end vertex ids, polyline (θ, point) and kind.
pub(super) type GraphEdge = (usize, usize, Vec<(f64, P)>, EdgeKind);

pub(super) struct Graph {
    pub(super) verts: Vec<P>,
    /// Edges: vertex ids, polyline (with θ for curve points), kind.
    pub(super) edges: Vec<GraphEdge>,
}

/// The curve chains and window edges as segments with their cuts, before the graph is built.
pub(super) struct Pieces {
    pub(super) chains: Vec<Vec<(f64, P)>>,
    pub(super) segs: Vec<Seg>,
    /// Index of the first window segment.
    pub(super) first_border: usize,
    pub(super) verts: Vec<P>,
    pub(super) cuts: Vec<Vec<Cut>>,
    pub(super) chain_ends: Vec<(usize, usize)>,
}

pub(super) fn arrangement(
    fam: &AffineFamily,
    window: &Window,
    coarse: &[(f64, P)],
) -> Result<Graph> {
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
pub(super) const MAX_CROSSINGS: usize = 1_000_000;

pub(super) fn pieces(chains: Vec<Vec<(f64, P)>>, window: &Window) -> Pieces {
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
pub(super) fn cut_chain_ends(pc: &mut Pieces, size: f64) {
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
pub(super) fn intersect(fam: &AffineFamily, window: &Window, pc: &mut Pieces) -> Result<()> {
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
pub(super) fn cut_curve_border(
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
pub(super) fn build_graph(pc: &Pieces) -> Graph {
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
pub(super) fn keep_inside(g: &mut Graph, window: &Window) {
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

pub(super) fn prune_dangling(g: &mut Graph) {
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
