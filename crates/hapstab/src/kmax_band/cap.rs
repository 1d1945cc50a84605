//! The top of one cap of the stable region (module doc of [`super`], step 3): the smooth top
//! of an arc, the corner where two arcs of the curve meet, an arc meeting a z = ±1 line, the
//! lines meeting — and, where those are missed from the certificate's level, the cap's top
//! approached by levels of the damping axis.

use super::*;

/// The top of a cap whose ends at stiffness a lie at angles θ1, θ2 (0 or π on the z = ±1
/// lines): the smooth top of one arc, the corner where two arcs meet, where an arc meets a
/// line, or where the two lines meet.
pub(super) fn cap_top(fam: &AffineFamily, a: f64, ends: [(f64, f64); 2]) -> Option<WallPoint> {
    cap_top_with_arcs(fam, a, ends).map(|(p, _)| p)
}

/// [`cap_top`] with the angles of the two arcs that meet at a corner top, or the angle of a
/// smooth top and NaN (both NaN for a top on a line): where a neighbouring loop's search
/// starts ([`cap_corner`], [`smooth_from`]).
pub(super) fn cap_top_with_arcs(
    fam: &AffineFamily,
    a: f64,
    ends: [(f64, f64); 2],
) -> Option<(WallPoint, [f64; 2])> {
    let none = |p: WallPoint| (p, [f64::NAN; 2]);
    let on_curve = |t: f64| t > 0.0 && t < std::f64::consts::PI;
    let line_at = |t: f64| {
        if t == 0.0 {
            plus_one_line(fam)
        } else {
            minus_one_line(fam)
        }
    };
    let [(b1, t1), (b2, t2)] = ends;
    match (on_curve(t1), on_curve(t2)) {
        (true, true) => {
            smooth_top(fam, a, (b1, b2), (t1, t2)).or_else(|| cap_corner(fam, a, [t1, t2]))
        }
        (true, false) => arc_meets_line(fam, a, t1, &line_at(t2)?).map(none),
        (false, true) => arc_meets_line(fam, a, t2, &line_at(t1)?).map(none),
        (false, false) => lines_meet(&line_at(t1)?, &line_at(t2)?).map(none),
    }
}

/// Samples of a(θ) between a cap's ends that must all lie above its level for the cap to be
/// one arc's smooth top.
const ARC_SAMPLES: usize = 8;

/// The cap's top where one arc of the curve runs from one end over a stationary point of a
/// to the other, staying above the cap's level: da/dθ = 0 by Brent's method between the ends.
fn smooth_top(
    fam: &AffineFamily,
    a: f64,
    (b1, b2): (f64, f64),
    (t1, t2): (f64, f64),
) -> Option<(WallPoint, [f64; 2])> {
    let (lo, hi) = (t1.min(t2), t1.max(t2));
    let slope = |t: f64| da_dtheta(fam, t);
    if !(slope(lo) > 0.0 && slope(hi) < 0.0) {
        return None;
    }
    let above = (1..ARC_SAMPLES).all(|j| {
        let t = lo + (hi - lo) * j as f64 / ARC_SAMPLES as f64;
        curve_point(fam, t).is_some_and(|p| p.a >= a)
    });
    if !above {
        return None;
    }
    let t = crate::bracket::sign_change(lo, hi, slope);
    let p = curve_point(fam, t)?;
    (p.a >= a && p.b >= b1.min(b2) && p.b <= b1.max(b2)).then_some((p, [t, f64::NAN]))
}

/// Widening steps of [`smooth_from`]'s search for a stationary point around an angle: from
/// 1e-3 of the angle, doubling.
const SMOOTH_STEPS: usize = 8;

/// The smooth top of an arc near the angle θ (a neighbouring loop's smooth top): the
/// stationary point of a(θ) between the nearest angles around θ where da/dθ is positive below
/// and negative above, by Brent's method; with its angle.
pub(super) fn smooth_from(fam: &AffineFamily, theta: f64) -> Option<(WallPoint, [f64; 2])> {
    use std::f64::consts::PI;
    if !(theta > 0.0 && theta < PI) {
        return None;
    }
    let slope = |t: f64| da_dtheta(fam, t);
    let mut h = 1e-3 * theta.min(PI - theta);
    let (lo, hi) = (0..SMOOTH_STEPS).find_map(|_| {
        let (lo, hi) = (
            (theta - h).max(0.5 * theta),
            (theta + h).min(0.5 * (theta + PI)),
        );
        h *= 2.0;
        (slope(lo) > 0.0 && slope(hi) < 0.0).then_some((lo, hi))
    })?;
    let t = crate::bracket::sign_change(lo, hi, slope);
    Some((curve_point(fam, t)?, [t, f64::NAN]))
}

/// Where the arc through θ at stiffness a meets a z = ±1 line, by the secant method on the
/// line's value along the curve.
fn arc_meets_line(fam: &AffineFamily, a: f64, theta: f64, l: &RootLine) -> Option<WallPoint> {
    let value = |t: f64| curve_point(fam, t).map(|p| l.value(p));
    let h = 1e-6 * theta.min(std::f64::consts::PI - theta);
    let (mut t0, mut t1) = (theta, theta + h);
    let (mut v0, mut v1) = (value(t0)?, value(t1)?);
    for _ in 0..CAP_STEPS {
        let t2 = t1 - v1 * (t1 - t0) / (v1 - v0);
        if !(t2 > 0.0 && t2 < std::f64::consts::PI) {
            return None;
        }
        (t0, v0) = (t1, v1);
        (t1, v1) = (t2, value(t2)?);
        if (t1 - t0).abs() <= SETTLED * t1 || v1 == 0.0 {
            return curve_point(fam, t1).filter(|p| p.a >= a);
        }
    }
    None
}

/// A Newton step below this relative size has settled (a few ulps of a(θ)'s rounding).
const SETTLED: f64 = 1e-14;

/// A Newton step that no longer halves has settled at the rounding of the function when it is
/// below this relative size.
const NEAR: f64 = 1e-10;

/// Newton steps at most on the meeting of two arcs, and on a point of an arc at a stiffness.
const CAP_STEPS: usize = 60;

/// The corner where a cap closes (or a neighbouring loop's corner moves to): the two arcs
/// through its ends (angles θ1, θ2 at stiffness a0) meet at the stiffness a where b(θ2(a)) − b(θ1(a)) = 0, by Newton's method in a (each
/// arc followed by Newton's method in θ on a(θ) = a), with the two arcs' angles there. None
/// where an arc turns back (a smooth top that the stationary points should have held) or the
/// iteration does not settle.
pub(super) fn cap_corner(
    fam: &AffineFamily,
    a0: f64,
    [t1, t2]: [f64; 2],
) -> Option<(WallPoint, [f64; 2])> {
    let mut a = a0;
    let mut arcs = (arc_at(fam, t1, a)?, arc_at(fam, t2, a)?);
    let mut last = f64::INFINITY;
    let mut gap = f64::INFINITY;
    let slope0 = arcs.0.2.abs().max(arcs.1.2.abs());
    for _ in 0..CAP_STEPS {
        let ((t1, b1, s1), (t2, b2, s2)) = arcs;
        if (b2 - b1).abs() > STALLED * gap && s1.abs().max(s2.abs()) > TURNING * slope0 {
            // the arcs do not close in and one steepens: it turns back at its smooth top first
            let steeper = if s1.abs() > s2.abs() { t1 } else { t2 };
            if let Some(top) = smooth_from(fam, steeper).filter(|(p, _)| p.a >= a0) {
                return Some(top);
            }
        }
        gap = (b2 - b1).abs();
        let mut step = (b2 - b1) / (s2 - s1);
        if !step.is_finite() {
            return None;
        }
        // damped: halve a step that leaves either arc (it turned back on the way)
        let next = (0..DAMPING_HALVINGS).find_map(|_| {
            let pair = arc_at(fam, t1, a - step).zip(arc_at(fam, t2, a - step));
            if pair.is_none() {
                step *= 0.5;
            }
            pair
        })?;
        a -= step;
        arcs = next;
        if step.abs() <= SETTLED * a.abs()
            || (step.abs() >= 0.5 * last && step.abs() <= NEAR * a.abs())
        {
            let p = WallPoint { a, b: arcs.0.1 };
            return Some((p, [arcs.0.0, arcs.1.0]));
        }
        last = step.abs();
    }
    None
}

/// Levels tried at most by [`cap_by_levels`] (growing the bracket, then closing it).
const LEVEL_STEPS: usize = 80;

/// [`cap_by_levels`] closes its bracket to this relative width; the top's stiffness is then
/// read from the exact stable intervals at its damping.
const LEVEL_REL: f64 = 1e-12;

/// A level of a cap: a stiffness a and the ends (b, θ) of the cap's stable damping interval
/// there (θ 0 or π on the z = ±1 lines).
#[derive(Debug, Clone, Copy)]
pub(super) struct Level {
    pub(super) a: f64,
    pub(super) ends: [(f64, f64); 2],
}

impl Level {
    fn width(&self) -> f64 {
        self.ends[1].0 - self.ends[0].0
    }

    /// The cap's continuation at stiffness a: the one stable damping interval of the axis
    /// there that overlaps this level's.
    fn next(&self, fam: &AffineFamily, cf: &CayleyFamily, a: f64) -> Option<Level> {
        let ivs = stable_intervals_with_angles(fam, cf, &damping_axis(a));
        let (lo, hi) = (self.ends[0].0, self.ends[1].0);
        let mut within = ivs.iter().filter(|(iv, _)| iv.lo < hi && iv.hi > lo);
        match (within.next(), within.next()) {
            (Some((iv, [t0, t1])), None) => Some(Level {
                a,
                ends: [(iv.lo, *t0), (iv.hi, *t1)],
            }),
            _ => None,
        }
    }
}

/// A cap's top where [`cap_top`] from the certificate's level missed it (its Newton steps
/// start too far below a corner): the cap's stable damping interval shrinks to the top as
/// the stiffness rises, so levels closer to the top are taken — the bracket [a0, a1] (cap at
/// a0, none at a1; a1 from `guess` or grown by doubling) closed by the secant of the
/// interval's width (linear at a corner), alternating with bisection — and [`cap_top`] is
/// tried again from each level whose width has fallen below a third of the last try's; to
/// [`LEVEL_REL`] at worst, the top's damping then the last interval's middle. Each top is
/// confirmed by the exact stable intervals at its damping ([`exact_top`]): (a, b), or None.
pub(super) fn cap_by_levels(
    fam: &AffineFamily,
    cf: &CayleyFamily,
    start: Level,
    guess: f64,
) -> Option<(f64, f64)> {
    let (mut prev, mut lo) = (start, start);
    let mut hi = if guess.is_finite() && guess > start.a {
        guess
    } else {
        start.a + start.a.abs().max(f64::MIN_POSITIVE)
    };
    let mut tried = start.width();
    let mut top_from = |l: &Level| -> Option<(f64, f64)> {
        if l.width() > tried / 3.0 {
            return None;
        }
        tried = l.width();
        let c = cap_top(fam, l.a, l.ends).filter(|c| c.a > l.a)?;
        exact_top(fam, cf, c.a, c.b).map(|a| (a, c.b))
    };
    let mut steps = 0;
    // grow the bracket until the cap is gone
    while let Some(l) = lo.next(fam, cf, hi) {
        (prev, lo) = (lo, l);
        if let Some(top) = top_from(&lo) {
            return Some(top);
        }
        hi = lo.a + 2.0 * (lo.a - prev.a);
        steps += 1;
        if steps > LEVEL_STEPS || !hi.is_finite() {
            return None;
        }
    }
    let mut secant_last = false;
    while hi - lo.a > LEVEL_REL * hi.abs() && steps < LEVEL_STEPS {
        steps += 1;
        let (w0, w1) = (prev.width(), lo.width());
        let secant = lo.a + w1 * (lo.a - prev.a) / (w0 - w1);
        let a = if !secant_last && secant > lo.a && secant < hi && w0 > w1 {
            secant
        } else {
            0.5 * (lo.a + hi)
        };
        secant_last = a == secant;
        match lo.next(fam, cf, a) {
            Some(l) => {
                (prev, lo) = (lo, l);
                if let Some(top) = top_from(&lo) {
                    return Some(top);
                }
            }
            None => hi = a,
        }
    }
    let b = 0.5 * (lo.ends[0].0 + lo.ends[1].0);
    exact_top(fam, cf, lo.a, b).map(|a| (a, b))
}

/// A Newton step of [`cap_corner`] that leaves the gap between the two arcs above this
/// fraction of the last has stalled (Newton's method near a simple corner shrinks it by
/// orders of magnitude per step); with one arc steepening ([`TURNING`]), that arc approaches
/// its smooth top, where db/da diverges, before the arcs meet.
const STALLED: f64 = 0.9;

/// An arc whose db/da has grown this many times over [`cap_corner`]'s start approaches its
/// smooth top (da/dθ = 0).
const TURNING: f64 = 3.0;

/// Halvings of a Newton step in a that leaves an arc before the corner search gives up.
const DAMPING_HALVINGS: usize = 40;

/// The point of the curve's arc through θ at stiffness a: (θ, b, db/da there), by Newton's
/// method on a(θ) = a with slopes from central differences.
fn arc_at(fam: &AffineFamily, theta: f64, a: f64) -> Option<(f64, f64, f64)> {
    use std::f64::consts::PI;
    let mut th = theta;
    let mut last = f64::INFINITY;
    for _ in 0..ARC_STEPS {
        let p = curve_point(fam, th)?;
        // forward differences: a relative error of 1e-7 in the slope keeps Newton's
        // convergence at a ratio of 1e-7 per step
        let h = SLOPE_STEP * th.min(PI - th);
        let q = curve_point(fam, th + h)?;
        let (da, db) = ((q.a - p.a) / h, (q.b - p.b) / h);
        let step = (p.a - a) / da;
        let next = th - step;
        if !(next > 0.0 && next < PI) || step.abs() > last {
            return None; // off the arc, or diverging: the arc does not reach a
        }
        // settled: a step at the rounding of a(θ), or one that no longer shrinks near it
        if step.abs() <= SETTLED * th || (step.abs() >= 0.5 * last && step.abs() <= NEAR * th) {
            let p = curve_point(fam, next)?;
            return Some((next, p.b, db / da));
        }
        th = next;
        last = step.abs();
    }
    None
}

/// Newton steps at most on a point of an arc (quadratic convergence from a nearby angle
/// needs a handful; more means the arc does not reach the stiffness).
const ARC_STEPS: usize = 20;

/// Relative step of the forward differences of the curve in θ.
const SLOPE_STEP: f64 = 1e-7;
