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
    /// The piece it belongs to.
    pub(super) owner: usize,
    /// Index within the owner.
    pub(super) idx: usize,
}

impl Seg {
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

/// The crossing of curve segments a and b (chords crossing at (t, u)) refined on the curve
/// ([`refine_cc`]), or the chords' own crossing where the refinement strays further than the
/// two chords are long (the curve between their ends runs off to infinity: the chords do not
/// follow it there).
fn refined_crossing(fam: &AffineFamily, a: &Seg, b: &Seg, (t, u): (f64, f64)) -> (P, f64, f64) {
    let (p, ta, tb) = refine_cc(fam, a, b);
    let raw = a.at(t);
    let reach = norm(sub(a.q, a.p)) + norm(sub(b.q, b.p));
    if p.finite() && norm(sub(p, raw)) <= reach {
        return (p, ta, tb);
    }
    (raw, a.tp + t * (a.tq - a.tp), b.tp + u * (b.tq - b.tp))
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

/// Graph edge: end vertex ids, polyline (θ, point) and kind.
pub(super) type GraphEdge = (usize, usize, Vec<(f64, P)>, EdgeKind);

pub(super) struct Graph {
    pub(super) verts: Vec<P>,
    /// Edges: vertex ids, polyline (with θ for curve points), kind.
    pub(super) edges: Vec<GraphEdge>,
}

/// The arrangement of step 4: the curve's chains clipped to the window, their crossings, and
/// the window's edges split where the curve meets them, as a planar graph.
pub(super) fn arrangement(
    fam: &AffineFamily,
    window: &Window,
    coarse: &[(f64, P)],
) -> Result<Graph> {
    let mut b = Builder::new(window);
    for chain in chains(fam, coarse, window) {
        for piece in clip_chain(fam, window, &chain) {
            b.add_piece(piece);
        }
    }
    b.intersect(fam)?;
    let mut g = b.graph();
    prune_dangling(&mut g);
    Ok(g)
}

/// Most crossings the arrangement may hold: a boundary curve that crosses itself more often
/// than this (a curve that retraces itself, segment over segment) would need memory and time
/// quadratic in its points; past it the region is refused with an honest error.
pub(super) const MAX_CROSSINGS: usize = 1_000_000;

/// Points within this fraction of the window's size of a window edge lie on it: the curve's
/// ends on the z = ±1 lines are computed to rounding, and a window corner on such a line must
/// catch them.
const ON_EDGE: f64 = 1e-12;

/// Vertices on one window edge closer than this fraction of the window's size are one vertex:
/// the curve passing through one wall at two angles (an undamped mode's z = e^{iθ_r} at the
/// wall-free point, beside the curve's end at z = 1) meets the edge there twice, to rounding.
const SNAP: f64 = 1e-10;

/// A piece of a chain inside the window: its points, and the window edge each end lies on
/// (None for an end inside the window).
pub(super) struct Piece {
    pts: Vec<(f64, P)>,
    ends: [Option<usize>; 2],
}

/// Where segment p→q is inside the window: the parameter range [t0, t1] and the window edges
/// it enters and leaves by (None when an end of the range is an end of the segment).
fn clip_segment(window: &Window, p: P, q: P) -> Option<(f64, f64, Option<usize>, Option<usize>)> {
    let slack = ON_EDGE * window.size;
    let (mut t0, mut t1, mut e0, mut e1) = (0.0_f64, 1.0_f64, None, None);
    for (i, (_, h)) in window.polygon.iter().enumerate() {
        let (vp, vq) = (h.value(p), h.value(q));
        if vp > slack && vq > slack {
            return None;
        }
        if vp > slack {
            let t = vp / (vp - vq);
            if t > t0 {
                (t0, e0) = (t, Some(i));
            }
        } else if vq > slack {
            let t = vp / (vp - vq);
            if t < t1 {
                (t1, e1) = (t, Some(i));
            }
        }
    }
    (t0 <= t1).then_some((t0, t1, e0, e1))
}

/// The window edge a point lies on (within [`ON_EDGE`]), if any.
fn edge_of(window: &Window, p: P) -> Option<usize> {
    let slack = ON_EDGE * window.size;
    window
        .polygon
        .iter()
        .enumerate()
        .map(|(i, (_, h))| (i, h.value(p).abs()))
        .filter(|&(_, v)| v <= slack)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}

/// The point where curve segment (tp, p)→(tq, q) crosses window edge `e` at parameter t: on a
/// z = ±1 line refined on the curve itself (bisection in θ), else interpolated; then put on
/// the edge's line exactly.
fn crossing_on_edge(
    fam: &AffineFamily,
    window: &Window,
    (tp, p): (f64, P),
    (tq, q): (f64, P),
    (t, e): (f64, usize),
) -> (f64, P) {
    let h = &window.polygon[e].1;
    let raw = p.lerp(q, t);
    if h.line.is_some() {
        let seg = Seg {
            p,
            q,
            tp,
            tq,
            owner: 0,
            idx: 0,
        };
        let (x, th) = refine_cl(fam, &seg, h);
        // A bisection that strays beyond the chord has found the curve's pole, not the line.
        if x.finite() && norm(sub(x, raw)) <= norm(sub(q, p)) {
            return (th, x);
        }
    }
    let r = h.value(raw);
    let x = raw;
    (
        tp + t * (tq - tp),
        P {
            x: x.x - r * h.n.x,
            y: x.y - r * h.n.y,
        },
    )
}

/// Clips one chain to the (convex) window: the pieces inside, each end on the window edge it
/// crosses (or None inside the window).
fn clip_chain(fam: &AffineFamily, window: &Window, chain: &[(f64, P)]) -> Vec<Piece> {
    let mut out = Vec::new();
    let mut cur: Option<Piece> = None;
    for w in chain.windows(2) {
        let (a, b) = (w[0], w[1]);
        let Some((t0, t1, e0, e1)) = clip_segment(window, a.1, b.1) else {
            out.extend(cur.take());
            continue;
        };
        let mut pc = cur.take().unwrap_or_else(|| {
            let (start, edge) = match e0 {
                Some(e) => (crossing_on_edge(fam, window, a, b, (t0, e)), Some(e)),
                None => (a, edge_of(window, a.1)),
            };
            Piece {
                pts: vec![start],
                ends: [edge, None],
            }
        });
        match e1 {
            Some(e) => {
                pc.pts.push(crossing_on_edge(fam, window, a, b, (t1, e)));
                pc.ends[1] = Some(e);
                out.push(pc);
            }
            None => {
                pc.pts.push(b);
                cur = Some(pc);
            }
        }
    }
    if let Some(mut pc) = cur {
        pc.ends[1] = pc.pts.last().and_then(|l| edge_of(window, l.1));
        out.push(pc);
    }
    out.retain(|pc| pc.pts.len() >= 2);
    out
}

/// A piece's points (θ, point) and the vertex ids of its two ends.
type PlacedPiece = (Vec<(f64, P)>, [usize; 2]);

/// A cut of a segment or window edge: parameter along it and vertex id.
type Cut = (f64, usize);

/// The graph under construction: window corners and edges, the curve pieces as segments, the
/// cuts of both.
struct Builder<'a> {
    window: &'a Window,
    verts: Vec<P>,
    /// Each piece's points and its two end vertices.
    pieces: Vec<PlacedPiece>,
    segs: Vec<Seg>,
    /// Cuts per curve segment (θ of the crossing with each).
    seg_cuts: Vec<Vec<(f64, usize, f64)>>,
    /// Cuts per window edge.
    edge_cuts: Vec<Vec<Cut>>,
}

impl<'a> Builder<'a> {
    fn new(window: &'a Window) -> Self {
        let n = window.polygon.len();
        Builder {
            window,
            verts: window.polygon.iter().map(|w| w.0).collect(),
            pieces: Vec::new(),
            segs: Vec::new(),
            seg_cuts: Vec::new(),
            edge_cuts: vec![Vec::new(); n],
        }
    }

    /// The vertex for a point on window edge e: a corner or an earlier cut within
    /// [`SNAP`] of it, else a new cut.
    fn edge_vertex(&mut self, e: usize, p: P) -> usize {
        let n = self.window.polygon.len();
        let (a, b) = (self.window.polygon[e].0, self.window.polygon[(e + 1) % n].0);
        let tol = SNAP * self.window.size;
        if norm(sub(p, a)) <= tol {
            return e;
        }
        if norm(sub(p, b)) <= tol {
            return (e + 1) % n;
        }
        if let Some(&(_, v)) = self.edge_cuts[e]
            .iter()
            .find(|&&(_, v)| norm(sub(self.verts[v], p)) <= tol)
        {
            return v;
        }
        let d = sub(b, a);
        let t = ((p.x - a.x) * d.x + (p.y - a.y) * d.y) / (d.x * d.x + d.y * d.y);
        let v = self.verts.len();
        self.verts.push(p);
        self.edge_cuts[e].push((t.clamp(0.0, 1.0), v));
        v
    }

    /// Adds a piece: its ends become vertices (on the window's edges where they lie there),
    /// its chords segments.
    fn add_piece(&mut self, mut pc: Piece) {
        let mut ends = [0; 2];
        for (k, end) in ends.iter_mut().enumerate() {
            let i = if k == 0 { 0 } else { pc.pts.len() - 1 };
            let p = pc.pts[i].1;
            *end = match pc.ends[k] {
                Some(e) => self.edge_vertex(e, p),
                None => {
                    self.verts.push(p);
                    self.verts.len() - 1
                }
            };
            pc.pts[i].1 = self.verts[*end];
        }
        let owner = self.pieces.len();
        for (i, w) in pc.pts.windows(2).enumerate() {
            self.segs.push(Seg {
                p: w[0].1,
                q: w[1].1,
                tp: w[0].0,
                tq: w[1].0,
                owner,
                idx: i,
            });
            self.seg_cuts.push(Vec::new());
        }
        self.pieces.push((pc.pts, ends));
    }

    /// The first and last segment of each piece with the vertex its end is.
    fn end_vertex(&self, s: &Seg, at_start: bool) -> Option<usize> {
        let (pts, ends) = &self.pieces[s.owner];
        if at_start && s.idx == 0 {
            Some(ends[0])
        } else if !at_start && s.idx + 2 == pts.len() {
            Some(ends[1])
        } else {
            None
        }
    }

    /// True when a crossing of segments i and j at (t, u) is only their shared end vertex.
    fn shared_end(&self, si: &Seg, sj: &Seg, t: f64, u: f64) -> bool {
        let near = |x: f64| !(1e-9..=1.0 - 1e-9).contains(&x);
        if !(near(t) && near(u)) {
            return false;
        }
        let vi = self.end_vertex(si, t < 0.5);
        let vj = self.end_vertex(sj, u < 0.5);
        vi.is_some() && vi == vj
    }

    /// All curve–curve crossings by a sweep over bounding boxes sorted along the stiffness
    /// axis; each becomes a vertex refined on the curve and a cut of both segments. At most
    /// [`MAX_CROSSINGS`]; beyond, an error.
    fn intersect(&mut self, fam: &AffineFamily) -> Result<()> {
        let mut crossings = 0_usize;
        let lo = |s: &Seg| s.p.x.min(s.q.x);
        let hi = |s: &Seg| s.p.x.max(s.q.x);
        let mut order: Vec<usize> = (0..self.segs.len()).collect();
        order.sort_by(|&i, &j| lo(&self.segs[i]).total_cmp(&lo(&self.segs[j])));
        let mut active: Vec<usize> = Vec::new();
        for &i in &order {
            let si = self.segs[i];
            active.retain(|&j| hi(&self.segs[j]) >= lo(&si));
            for &j in &active {
                let sj = self.segs[j];
                let neighbours = si.owner == sj.owner && si.idx.abs_diff(sj.idx) <= 1;
                let apart = si.p.y.max(si.q.y) < sj.p.y.min(sj.q.y)
                    || sj.p.y.max(sj.q.y) < si.p.y.min(si.q.y);
                if neighbours || apart {
                    continue;
                }
                let Some((t, u)) = seg_intersect(&si, &sj) else {
                    continue;
                };
                if self.shared_end(&si, &sj, t, u) {
                    continue;
                }
                crossings += 1;
                if crossings > MAX_CROSSINGS {
                    return Err(Error::Numerical(format!(
                        "the stable region's boundary curve crosses itself more than \
                         {MAX_CROSSINGS} times (it retraces itself); the stable intervals at \
                         fixed damping (`check`, `kmax`) and the grid map remain available"
                    )));
                }
                let (p, ti, tj) = refined_crossing(fam, &si, &sj, (t, u));
                let vid = self.verts.len();
                self.verts.push(p);
                self.seg_cuts[i].push((t, vid, ti));
                self.seg_cuts[j].push((u, vid, tj));
            }
            active.push(i);
        }
        Ok(())
    }

    /// The planar graph: pieces split at their crossings, window edges at their cuts.
    fn graph(self) -> Graph {
        let mut edges: Vec<GraphEdge> = Vec::new();
        let mut base = 0;
        for (pts, ends) in &self.pieces {
            let mut start = ends[0];
            let mut poly: Vec<(f64, P)> = vec![pts[0]];
            for k in 0..pts.len() - 1 {
                let mut cuts = self.seg_cuts[base + k].clone();
                cuts.sort_by(|a, b| a.0.total_cmp(&b.0));
                for (_, v, th) in cuts {
                    poly.push((th, self.verts[v]));
                    edges.push((start, v, std::mem::take(&mut poly), EdgeKind::Window));
                    start = v;
                    poly.push((th, self.verts[v]));
                }
                poly.push(pts[k + 1]);
            }
            edges.push((start, ends[1], poly, EdgeKind::Window));
            base += pts.len() - 1;
        }
        for e in edges.iter_mut() {
            e.3 = EdgeKind::Complex {
                theta_start: e.2[0].0,
                theta_end: e.2[e.2.len() - 1].0,
            };
        }
        edges.retain(|e| e.0 != e.1 || e.2.len() > 2);
        let n = self.window.polygon.len();
        for (k, cuts) in self.edge_cuts.iter().enumerate() {
            let mut cuts = cuts.clone();
            cuts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let kind = self.window.polygon[k].1.kind;
            let mut start = k;
            for v in cuts.into_iter().map(|(_, v)| v).chain([(k + 1) % n]) {
                let line = vec![(f64::NAN, self.verts[start]), (f64::NAN, self.verts[v])];
                edges.push((start, v, line, kind));
                start = v;
            }
        }
        Graph {
            verts: self.verts,
            edges,
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
