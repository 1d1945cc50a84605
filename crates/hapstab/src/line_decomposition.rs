//! The D-decomposition along a wall line without a θ grid (Section V): every crossing of the
//! unit circle from the positive roots of the line's Cayley crossing polynomial
//! ([`CayleyFamily::line_polynomial`], [`crate::real_roots`]), the gaps between them
//! classified by the point test, and the ends of the stable intervals polished on the circle
//! itself — what [`crate::boundary::stable_line_intervals`] computes from a scan, for the
//! stiffness axis at a damping, the damping axis at a stiffness, or any line.
//!
//! On the line from + t·dir, with Q = P0 + from·(PK, PB) and D = dir·(PK, PB), a crossing at
//! u = tan²(θ/2) has t = −Re(Q·conj D)/|D|², first from the transformed parts (enough to
//! order the crossings and place the gaps' midpoints), then — for the ends of the stable
//! intervals only — by Newton's method on Im(Q·conj D) on the circle and t from the circle's
//! values there.

use std::f64::consts::PI;

use crate::boundary::{
    Interval, LineCrossing, WallLine, crossing_function, crossing_slope, minus_one_line,
    plus_one_line, root_line_t, stable_between,
};
use crate::cayley::CayleyFamily;
use crate::closed_loop::AffineFamily;
use crate::poly::eval_real;

/// Newton steps that polish a crossing located on the Cayley polynomial (each doubles its
/// correct digits; the polynomial's root is good to ~2^{−N} relative near θ = π/2).
const POLISH_STEPS: usize = 4;

/// Largest relative Newton step taken while polishing: the located root is within ~1e-7 of
/// the crossing (seven digits left at [`crate::cayley::MAX_DEGREE`]); a longer step is a
/// neighbouring crossing's pull, and the located root is kept.
const POLISH_REACH: f64 = 1e-6;

/// The crossings of a wall line with t from the transformed parts (not polished): the
/// z = ±1 lines exactly, the complex pairs to the Cayley polynomial's precision. Sorted by t.
pub(crate) fn located_crossings(
    fam: &AffineFamily,
    cf: &CayleyFamily,
    line: &WallLine,
) -> Vec<LineCrossing> {
    located_crossings_with_roots(fam, cf, line).0
}

/// [`located_crossings`] with every positive root u = tan²(θ/2) of the line's crossing
/// polynomial ([`CayleyFamily::line_polynomial`]), increasing, including those whose crossing
/// is dropped (t not finite).
pub(crate) fn located_crossings_with_roots(
    fam: &AffineFamily,
    cf: &CayleyFamily,
    line: &WallLine,
) -> (Vec<LineCrossing>, Vec<f64>) {
    let mut out: Vec<LineCrossing> = Vec::new();
    for (l, theta) in [(plus_one_line(fam), 0.0), (minus_one_line(fam), PI)] {
        if let Some(t) = l.and_then(|l| root_line_t(&l, line)) {
            out.push(LineCrossing { t, theta });
        }
    }
    let [(e0, o0), (ek, ok), (eb, ob)] = &cf.parts;
    let (f, d) = (line.from, line.dir);
    let roots = crate::real_roots::positive_roots(&cf.line_polynomial(line));
    for &u in &roots {
        let at = |c: &[f64]| eval_real(c, u).0;
        let (ke, ko, be, bo) = (at(ek), at(ok), at(eb), at(ob));
        let qe = at(e0) + f.a * ke + f.b * be;
        let qo = at(o0) + f.a * ko + f.b * bo;
        let (de, do_) = (d.a * ke + d.b * be, d.a * ko + d.b * bo);
        let t = -(qe * de + u * qo * do_) / (de * de + u * do_ * do_);
        let theta = 2.0 * u.sqrt().atan();
        if t.is_finite() && theta > 0.0 && theta < PI {
            out.push(LineCrossing { t, theta });
        }
    }
    out.sort_by(|a, b| a.t.total_cmp(&b.t));
    (out, roots)
}

/// A complex-pair crossing polished on the circle (Newton's method on Im(Q conj PK), the
/// function the θ scan brackets), with its a from the circle's values; a crossing on the
/// z = ±1 lines is exact already.
fn polished(fam: &AffineFamily, line: &WallLine, c: LineCrossing) -> LineCrossing {
    if c.theta == 0.0 || c.theta == PI {
        return c;
    }
    let mut th = c.theta;
    let mut last = f64::INFINITY;
    for _ in 0..POLISH_STEPS {
        let step = crossing_function(fam, line, th).0 / crossing_slope(fam, line, th);
        let reach = POLISH_REACH * th.min(PI - th);
        if !step.is_finite() || step.abs() >= last || step.abs() > reach {
            break;
        }
        th -= step;
        last = step.abs();
        if last <= 2.0 * f64::EPSILON * th {
            break;
        }
    }
    let t = crossing_function(fam, line, th).1;
    if t.is_finite() {
        LineCrossing { t, theta: th }
    } else {
        c
    }
}

/// Every crossing of a wall line, polished, sorted by t (see the module doc): the crossings [`crate::boundary::line_crossings`] finds on its scan, and any pair
/// the scan's grid would miss.
pub fn line_crossings(fam: &AffineFamily, cf: &CayleyFamily, line: &WallLine) -> Vec<LineCrossing> {
    let mut out: Vec<LineCrossing> = located_crossings(fam, cf, line)
        .into_iter()
        .map(|c| polished(fam, line, c))
        .collect();
    out.sort_by(|a, b| a.t.total_cmp(&b.t));
    out.dedup_by(|a, b| (a.t - b.t).abs() <= 1e-15 * a.t.abs().max(b.t.abs()));
    out
}

/// The stable intervals of t on a wall line (Section V), as
/// [`crate::boundary::stable_line_intervals`] defines them: the gaps between the located
/// crossings classified by the point test, and each finite end of a stable interval polished
/// on the circle.
pub fn stable_intervals(fam: &AffineFamily, cf: &CayleyFamily, line: &WallLine) -> Vec<Interval> {
    stable_intervals_with_angles(fam, cf, line)
        .into_iter()
        .map(|(iv, _)| iv)
        .collect()
}

/// [`stable_intervals`] with the angle θ of the root on the circle at each end (0 or π on the
/// z = ±1 lines, NaN at an infinite end).
pub fn stable_intervals_with_angles(
    fam: &AffineFamily,
    cf: &CayleyFamily,
    line: &WallLine,
) -> Vec<(Interval, [f64; 2])> {
    stable_intervals_located(fam, line, &located_crossings(fam, cf, line))
}

/// [`stable_intervals_with_angles`] from the line's located crossings
/// ([`located_crossings`]), computed once for several uses.
pub(crate) fn stable_intervals_located(
    fam: &AffineFamily,
    line: &WallLine,
    located: &[LineCrossing],
) -> Vec<(Interval, [f64; 2])> {
    let rough = stable_between(fam, line, located);
    let polish = |x: f64| -> (f64, f64) {
        if !x.is_finite() {
            return (x, f64::NAN);
        }
        located
            .iter()
            .find(|c| c.t == x)
            .map_or((x, f64::NAN), |&c| {
                let p = polished(fam, line, c);
                (p.t, p.theta)
            })
    };
    rough
        .into_iter()
        .map(|iv| {
            let ((lo, t_lo), (hi, t_hi)) = (polish(iv.lo), polish(iv.hi));
            (Interval { lo, hi }, [t_lo, t_hi])
        })
        .collect()
}
