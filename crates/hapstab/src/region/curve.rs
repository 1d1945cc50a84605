//! Steps 0 and 2 of the region method: the shared point budget and the adaptive sampling
//! of the complex-pair curve C(θ), θ ∈ [0, π].

use super::*;

/// A shared count of curve points, so that every adaptive step together stays within
/// [`MAX_CURVE_POINTS`].
pub(super) struct Budget {
    pub(super) left: AtomicUsize,
}

impl Budget {
    pub(super) fn new(n: usize) -> Self {
        Self {
            left: AtomicUsize::new(n),
        }
    }

    /// Takes `n` points; false when the budget is exhausted.
    pub(super) fn take(&self, n: usize) -> bool {
        self.left
            .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |l| l.checked_sub(n))
            .is_ok()
    }

    pub(super) fn exhausted() -> Error {
        Error::Numerical(format!(
            "the stable region's boundary needs more than {MAX_CURVE_POINTS} points (a loop whose \
             boundary curve winds too often to draw); the stable intervals at fixed damping \
             (`check`, `kmax`) and the grid map remain available"
        ))
    }
}

/// How finely an arc is sampled: chord deviation tolerance, and (coarse passes) the region
/// of interest and the longest chord allowed in it.
#[derive(Clone, Copy)]
pub(super) struct Sampling<'a> {
    pub(super) tol: f64,
    /// Coarse passes: refine only chords that come near this box, and split chords longer
    /// than `maxlen` there. Fine passes: None.
    pub(super) focus: Option<(&'a BoxF, f64)>,
}

impl Sampling<'_> {
    pub(super) fn relevant(&self, p: P, q: P) -> bool {
        match self.focus {
            None => true,
            Some(((x0, x1, y0, y1), _)) => {
                p.x.min(q.x) <= *x1
                    && p.x.max(q.x) >= *x0
                    && p.y.min(q.y) <= *y1
                    && p.y.max(q.y) >= *y0
            }
        }
    }
}

/// Number of coarse knots: the curve winds about once per root of p, so 64 knots per degree.
pub(super) fn knot_count(fam: &AffineFamily) -> usize {
    64 * (fam.degree() + 2)
}

/// Samples the curve on θ ∈ [0, π] (see the module doc, step 2).
pub(super) fn coarse_curve(
    fam: &AffineFamily,
    bounds: &Bounds,
    (zoom, hint, level): (Option<BoxF>, Option<BoxF>, i32),
    budget: &Budget,
) -> Result<Vec<(f64, P)>> {
    let m = knot_count(fam);
    if !budget.take(m + 1) {
        return Err(Budget::exhausted());
    }
    let pi = std::f64::consts::PI;
    let thetas: Vec<f64> = (0..=m).map(|i| pi * i as f64 / m as f64).collect();
    let knots: Vec<(f64, Option<P>)> = thetas
        .par_iter()
        .with_min_len(128)
        .map(|&t| {
            match point(fam, t) {
                // Where the curve runs to infinity at θ = π, end just short of it so that the
                // last interval is still sampled (the far tail is cut off later).
                None if t == pi => {
                    let t = pi * (1.0 - 1e-12);
                    (t, point(fam, t))
                }
                p => (t, p),
            }
        })
        .collect();
    // The slices' box is the focus when it is far smaller than the knots' own (a region far
    // smaller than its curve's extent), else the knots inside the bounds decide.
    let focus = zoom.unwrap_or_else(|| {
        let knots_box = focus_box(bounds, &knots);
        match hint {
            Some(h) if box_size(h) < LIMIT_FRACTION * box_size(knots_box) => h,
            _ => knots_box,
        }
    });
    let size = (focus.1 - focus.0).max(focus.3 - focus.2);
    // Each retry also samples 16 times finer (4 times the points): features of the boundary
    // far below the coarse tolerance (several branches crossing within 1e-4 of the window)
    // are resolved within a few attempts.
    let fine = 0.0625_f64.powi(level);
    let s = Sampling {
        tol: 1e-3 * size * fine,
        focus: Some((&focus, 0.25 * size * fine.sqrt())),
    };
    let intervals = knots.len() - 1;
    let pieces: Vec<Result<Vec<(f64, P)>>> = (0..intervals)
        .step_by(RUN)
        .collect::<Vec<usize>>()
        .par_iter()
        .with_min_len(4)
        .map(|&i0| {
            let mut out = Vec::new();
            let mut scratch = ArcScratch::default();
            for w in knots[i0..(i0 + RUN + 1).min(knots.len())].windows(2) {
                match (w[0], w[1]) {
                    ((t0, Some(p0)), (t1, Some(p1))) => {
                        let (a, b) = ((t0, p0), (t1, p1));
                        sample_arc_into(fam, a, b, s, budget, &mut out, &mut scratch)?;
                    }
                    // a gap (no point): the next piece starts afresh at its own first knot
                    ((_, None), (t1, Some(p1))) => out.push((t1, p1)),
                    _ => {}
                }
            }
            Ok(out)
        })
        .collect();
    let mut coarse: Vec<(f64, P)> = Vec::new();
    if let (t0, Some(p0)) = knots[0] {
        coarse.push((t0, p0));
    }
    for piece in pieces {
        coarse.extend(piece?);
    }
    Ok(coarse)
}

/// Knot intervals per parallel task of the curve sampling (one buffer and work space each).
pub(super) const RUN: usize = 16;

/// The box where the coarse curve matters: around the knots inside the bounds (all of the
/// bounds when none is), inflated by half its size.
pub(super) fn focus_box(bounds: &Bounds, knots: &[(f64, Option<P>)]) -> (f64, f64, f64, f64) {
    let whole = bbox(bounds.polygon.iter().map(|(p, _)| *p)).unwrap_or((-1.0, 1.0, -1.0, 1.0));
    let wsize = (whole.1 - whole.0).max(whole.3 - whole.2);
    let inside = knots
        .iter()
        .filter_map(|(_, p)| *p)
        .filter(|p| p.finite() && bounds.excess(*p) <= 1e-9 * wsize);
    let (x0, x1, y0, y1) = bbox(inside).unwrap_or(whole);
    let size = (x1 - x0).max(y1 - y0).max(1e-12 * wsize).max(1e-300);
    let m = 0.5 * size;
    (
        (x0 - m).max(whole.0),
        (x1 + m).min(whole.1),
        (y0 - m).max(whole.2),
        (y1 + m).min(whole.3),
    )
}

/// Coarse passes split a chord whose midpoint deviates by more than this fraction of its
/// length (a turn of about 0.2 rad per chord): a loop of any size gets at least ~30 points.
pub(super) const TURN_TOL: f64 = 0.025;

/// Deepest bisection of one arc: 2⁻⁴⁸ of a knot interval is below the resolution of θ.
pub(super) const MAX_DEPTH: u32 = 48;

/// Work space of [`sample_arc_into`], reused across arcs.
#[derive(Default)]
pub(super) struct ArcScratch {
    pub(super) stack: Vec<(ArcEnd, ArcEnd, u32)>,
    pub(super) parts: Vec<ArcEnd>,
}

/// Adaptive sampling of the curve between two points (θ, C(θ)); appends the points after
/// the first (the last included) to `out`. An explicit stack (in `scratch`, reused across
/// arcs) replaces recursion; every point drawn comes out of the budget.
pub(super) fn sample_arc_into(
    fam: &AffineFamily,
    a: (f64, P),
    b: (f64, P),
    s: Sampling<'_>,
    budget: &Budget,
    out: &mut Vec<(f64, P)>,
    scratch: &mut ArcScratch,
) -> Result<()> {
    let ArcScratch { stack, parts } = scratch;
    // Stack of pending arcs, the leftmost on top.
    stack.clear();
    stack.push(((a.0, unit(a.0), a.1), (b.0, unit(b.0), b.1), 0_u32));
    while let Some((l, r, depth)) = stack.pop() {
        match split(fam, l, r, depth, s, parts) {
            Split::Accept(mid) => {
                out.extend(mid.map(|m| (m.0, m.2)));
                out.push((r.0, r.2));
                continue;
            }
            Split::Into => {}
        }
        if !budget.take(parts.len()) {
            return Err(Budget::exhausted());
        }
        let mut right = r;
        for &p in parts.iter().rev() {
            stack.push((p, right, depth + 1));
            right = p;
        }
        stack.push((l, right, depth + 1));
    }
    Ok(())
}

/// One end of an arc: θ, z = e^{iθ} and the curve point.
pub(super) type ArcEnd = (f64, Complex64, P);

/// What to do with an arc: keep its chord (with the midpoint evaluated for the test when
/// that point is kept as well), or split it at the points left in the caller's buffer.
pub(super) enum Split {
    Accept(Option<ArcEnd>),
    Into,
}

/// Deepest level at which a chord is split into more than two parts: deeper, the curvature
/// estimate from one midpoint is no longer worth trusting for more.
pub(super) const MULTI_SPLIT_DEPTH: u32 = 8;

/// Decides an arc: accepted when its chord follows the curve, else split at interior points
/// written to `parts`. The arc's midpoint is (z0 + z1)/|z0 + z1| and k equal parts are
/// powers of e^{iΔθ/k}, so no sine or cosine is evaluated per point. A smooth arc is split
/// into k ≈ √(dev/tol) parts at once (the deviation of a chord shrinks with the square of its
/// length). Fine passes keep the midpoint they evaluate: an arc whose midpoint is within
/// 4·tol of the chord is kept as the two half-chords, each within tol (a quarter of the
/// deviation), so that no evaluation is spent only on a test.
pub(super) fn split(
    fam: &AffineFamily,
    l: ArcEnd,
    r: ArcEnd,
    depth: u32,
    s: Sampling<'_>,
    parts: &mut Vec<ArcEnd>,
) -> Split {
    let ((t0, z0, p0), (t1, z1, p1)) = (l, r);
    if depth >= MAX_DEPTH || !s.relevant(p0, p1) {
        return Split::Accept(None);
    }
    let zs = z0 + z1;
    // |z0 + z1| ≤ 2: the plain square root is exact enough and far cheaper than hypot
    let zm = zs / (zs.re * zs.re + zs.im * zs.im).sqrt();
    if zm.im <= 0.0 {
        return Split::Accept(None);
    }
    let tm = 0.5 * (t0 + t1);
    let Some(pm) = point_at(fam, tm, zm) else {
        return Split::Accept(None);
    };
    let mid = (tm, zm, pm);
    let ch = sub(p1, p0);
    let q = sub(pm, p0);
    let len2 = ch.x * ch.x + ch.y * ch.y;
    let len = len2.sqrt();
    let dev = if len > 0.0 {
        cross(ch, q).abs() / len
    } else {
        norm(q)
    };
    // Accept when the midpoint is within the limit of the chord and projects into
    // [−1/4, 5/4] of it; coarse passes also bound the turning per chord (scale-free, so that
    // loops far smaller than the focus are resolved) down to a floor below which it is noise.
    let keep_mid = s.focus.is_none();
    let t = if len2 > 0.0 {
        (q.x * ch.x + q.y * ch.y) / len2
    } else {
        0.5
    };
    // A chord and midpoint all within the tolerance of one point is done whatever its
    // direction (a direction made of rounding noise would otherwise split to the depth limit).
    let tiny = norm(q) <= s.tol && norm(sub(pm, p1)) <= s.tol;
    // A kept midpoint's half-chords deviate by about a quarter of its deviation where the arc
    // is close to a parabola, which shows in a midpoint projecting near the chord's middle;
    // the midpoint itself must still be within tol (near a pole of the curve the arc is far
    // from a parabola, and a quarter would be a promise the halves do not keep).
    let central = (0.45..=0.55).contains(&t);
    // A fine pass verifies both halves of a chord whose midpoint is off-centre: one point on
    // the chord says nothing of a half whose parametrization runs unevenly (the arc from
    // θ = 0, where the curve starts with zero speed, has its midpoint a quarter along).
    let unverified = keep_mid && !central && !tiny;
    let limit = if keep_mid && central {
        4.0 * s.tol
    } else {
        s.tol
    };
    let within = !unverified && (tiny || (dev <= limit && (-0.25..=1.25).contains(&t)));
    let turning = s.focus.is_some() && dev > TURN_TOL * len && dev > 1e-7 * s.tol;
    let far = norm(q) + norm(sub(pm, p1)) > 1.5 * len + s.tol;
    // Coarse passes bound the chord length near the focus, so that a chord to a far point
    // (the curve runs to infinity where the equations are dependent) cannot hide a turn.
    let long = s
        .focus
        .is_some_and(|(_, maxlen)| depth < 30 && len > maxlen);
    if within && !turning && !far && !long {
        return Split::Accept((keep_mid && !tiny).then_some(mid));
    }
    parts.clear();
    let k = if far || long || turning || depth > MULTI_SPLIT_DEPTH {
        2
    } else {
        ((dev / limit).sqrt().ceil() as usize).clamp(2, 64)
    };
    if k == 2 {
        parts.push(mid);
        return Split::Into;
    }
    let w = unit((t1 - t0) / k as f64);
    let mut z = z0;
    for i in 1..k {
        z *= w;
        let t = t0 + (t1 - t0) * i as f64 / k as f64;
        let Some(p) = point_at(fam, t, z) else {
            parts.clear();
            parts.push(mid);
            return Split::Into;
        };
        parts.push((t, z, p));
    }
    Split::Into
}
