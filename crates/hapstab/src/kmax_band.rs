//! K_max over a damping band without the region's polygon: the largest stable stiffness a
//! with b_lo ≤ b ≤ b_hi, from the finite candidate set of the D-decomposition (Section V).
//!
//! The top of the stable region within the band is reached at
//! 1. the band's edges: the highest stable interval's end at b_lo and at b_hi;
//! 2. a stationary point of a along the complex-pair curve (a smooth top);
//! 3. a corner where the curve meets the z = 1 or z = −1 line, where the two lines meet, or
//!    where the curve ends on a line (a double root at z = ±1).
//!
//! On the curve a(u) = [P0, PB]/[PB, PK] and b(u) = −[P0, PK]/[PB, PK] in u = tan²(θ/2)
//! ([`crate::cayley`]), so the stationary points are the positive roots of
//! [P0, PB]′·[PB, PK] − [P0, PB]·[PB, PK]′ and the curve meets the line
//! p0 + a·pk + b·pb = 0 at the roots of p0·[PB, PK] + pk·[P0, PB] − pb·[P0, PK]. Each candidate
//! inside the band is taken from the highest down: the exact stable intervals at its damping
//! ([`crate::line_decomposition`]) give the attained top there; a candidate above that top is
//! a corner only touched by the region (a supremum) when the intervals beside its damping
//! close on it. The answer is then certified: at a stiffness just above it the damping axis
//! has no stable wall inside the band. A certificate that fails — a top that the candidates
//! miss, such as a corner where the curve crosses itself — leaves the answer to the region
//! ([`crate::region::alpha_max_within`]).

use crate::boundary::{
    AlphaBeta, Interval, RootLine, WallLine, curve_end, curve_point, minus_one_line, plus_one_line,
};
use crate::cayley::CayleyFamily;
use crate::closed_loop::AffineFamily;
use crate::line_decomposition::{stable_intervals, stable_intervals_with_angles};
use crate::poly;
use crate::real_roots::positive_roots;
use crate::region::{ConfirmedMax, confirm_max};
use crate::verdict::inside_unit_circle;

/// Relative distance of the walls beside K_max that the point test must find inside (below)
/// and not inside (above): the region's confirmation distance.
const CONFIRM_REL: f64 = crate::region::CONFIRM_REL;

/// A candidate's damping is polished on its curve–line corner while the corner's line value
/// changes sign within this relative distance of its located angle.
const CORNER_REACH: f64 = 1e-6;

/// A candidate is attained where the stable intervals at its damping reach it to this
/// relative distance (the candidates' own precision, far below any margin that matters).
const ATTAINED_REL: f64 = 1e-9;

/// The stiffness of the certificate lies this far (relative) above K_max.
const CERTIFY_REL: f64 = 1e-9;

/// The answer of the fast search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BandMax {
    /// K_max over the band, confirmed and certified.
    Max(ConfirmedMax),
    /// No stiffness is stable anywhere in the band (certified on its edges and candidates).
    NoneStable,
    /// The candidates do not settle it (the certificate failed, or the loop is longer than
    /// the Cayley transform serves): the region decides.
    Undecided,
}

/// K_max over b_lo ≤ b ≤ b_hi (wall units; b_hi may be +∞) from the D-decomposition's
/// candidates (module doc).
pub fn k_max_band(fam: &AffineFamily, b_lo: f64, b_hi: f64) -> BandMax {
    let Some(cf) = CayleyFamily::new(fam) else {
        return BandMax::Undecided;
    };
    let inside = |b: f64| b >= b_lo && b <= b_hi;
    let mut edges: Vec<AlphaBeta> = Vec::new();
    for b in [b_lo, b_hi].into_iter().filter(|b| b.is_finite()) {
        if let Some(a) = top(fam, &cf, b) {
            edges.push(AlphaBeta { alpha: a, beta: b });
        }
    }
    let mut cands: Vec<AlphaBeta> = curve_candidates(fam, &cf)
        .into_iter()
        .filter(|p| inside(p.beta) && p.alpha.is_finite())
        .collect();
    cands.sort_by(|p, q| q.alpha.total_cmp(&p.alpha));
    let best = edges.into_iter().max_by(|p, q| p.alpha.total_cmp(&q.alpha));
    let Some(found) = highest_candidate(fam, &cf, &cands, best, (b_lo, b_hi)) else {
        return if cands.is_empty() {
            BandMax::NoneStable
        } else {
            BandMax::Undecided
        };
    };
    let mut found = found;
    for _ in 0..CAP_ROUNDS {
        match certificate(fam, &cf, found.alpha, (b_lo, b_hi)) {
            Certificate::Holds => {
                return confirmed(fam, found, (b_lo, b_hi))
                    .map_or(BandMax::Undecided, BandMax::Max);
            }
            Certificate::Other => return BandMax::Undecided,
            Certificate::Cap { alpha, ends } => {
                let Some(c) = cap_corner(fam, alpha, ends) else {
                    return BandMax::Undecided;
                };
                match top(fam, &cf, c.beta) {
                    Some(a) if a >= c.alpha - ATTAINED_REL * c.alpha.abs() => {
                        found = Found {
                            alpha: a,
                            beta: c.beta,
                            attained: true,
                        };
                    }
                    _ => return BandMax::Undecided,
                }
            }
        }
    }
    BandMax::Undecided
}

/// Caps closed before the search gives up (each a corner where the curve crosses itself
/// above the previous answer; one is the rule, a second is rare).
const CAP_ROUNDS: usize = 4;

/// A Newton step below this relative size has settled (a few ulps of a(θ)'s rounding).
const SETTLED: f64 = 1e-14;

/// A Newton step that no longer halves has settled at the rounding of the function when it is
/// below this relative size.
const NEAR: f64 = 1e-10;

/// Newton steps at most on the meeting of two arcs, and on a point of an arc at a stiffness.
const CAP_STEPS: usize = 60;

/// The corner where a cap closes: the two arcs through its ends (angles θ1, θ2 at stiffness
/// a0) meet at the stiffness a where b(θ2(a)) − b(θ1(a)) = 0, by Newton's method in a (each
/// arc followed by Newton's method in θ on a(θ) = a). None where an arc turns back (a smooth
/// top that the stationary points should have held) or the iteration does not settle.
fn cap_corner(fam: &AffineFamily, a0: f64, ends: [(f64, f64); 2]) -> Option<AlphaBeta> {
    let mut a = a0;
    let mut arcs = (arc_at(fam, ends[0].1, a)?, arc_at(fam, ends[1].1, a)?);
    let mut last = f64::INFINITY;
    for _ in 0..CAP_STEPS {
        let ((t1, b1, s1), (t2, b2, s2)) = arcs;
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
            return Some(AlphaBeta {
                alpha: a,
                beta: arcs.0.1,
            });
        }
        last = step.abs();
    }
    None
}

/// Halvings of a Newton step in a that leaves an arc before the corner search gives up.
const DAMPING_HALVINGS: usize = 40;

/// The point of the curve's arc through θ at stiffness a: (θ, b, db/da there), by Newton's
/// method on a(θ) = a with slopes from central differences.
fn arc_at(fam: &AffineFamily, theta: f64, a: f64) -> Option<(f64, f64, f64)> {
    use std::f64::consts::PI;
    let slopes = |t: f64| -> Option<(f64, f64)> {
        let h = 1e-6 * t.min(PI - t);
        let (p, q) = (curve_point(fam, t - h)?, curve_point(fam, t + h)?);
        Some((
            (q.alpha - p.alpha) / (2.0 * h),
            (q.beta - p.beta) / (2.0 * h),
        ))
    };
    let mut th = theta;
    let mut last = f64::INFINITY;
    for _ in 0..CAP_STEPS {
        let p = curve_point(fam, th)?;
        let (da, db) = slopes(th)?;
        let step = (p.alpha - a) / da;
        let next = th - step;
        if !(next > 0.0 && next < PI) {
            return None;
        }
        // settled: a step at the rounding of a(θ), or one that no longer shrinks near it
        if step.abs() <= SETTLED * th || (step.abs() >= 0.5 * last && step.abs() <= NEAR * th) {
            let p = curve_point(fam, next)?;
            return Some((next, p.beta, db / da));
        }
        th = next;
        last = step.abs();
    }
    None
}

/// The highest end of the stable stiffness intervals at damping b (None when none is stable
/// or the highest is unbounded).
fn top(fam: &AffineFamily, cf: &CayleyFamily, b: f64) -> Option<f64> {
    highest(&stable_intervals(fam, cf, &WallLine::stiffness_axis(b)))
}

fn highest(ivs: &[Interval]) -> Option<f64> {
    ivs.iter()
        .map(|iv| iv.hi)
        .filter(|h| h.is_finite())
        .reduce(f64::max)
}

/// A found top: the wall and whether the stable intervals at its damping reach it.
#[derive(Debug, Clone, Copy)]
struct Found {
    alpha: f64,
    beta: f64,
    attained: bool,
}

/// The highest of the edges' tops and the candidates that the region reaches (attained) or
/// closes on (a supremum), taking candidates from the highest down.
fn highest_candidate(
    fam: &AffineFamily,
    cf: &CayleyFamily,
    cands: &[AlphaBeta],
    edge: Option<AlphaBeta>,
    band: (f64, f64),
) -> Option<Found> {
    let mut best = edge.map(|p| Found {
        alpha: p.alpha,
        beta: p.beta,
        attained: true,
    });
    let mut coeffs = vec![0.0; fam.degree() + 1];
    for c in cands {
        if best.is_some_and(|b| c.alpha <= b.alpha) {
            break;
        }
        if surely_outside(fam, *c, &mut coeffs) {
            continue;
        }
        let at = top(fam, cf, c.beta);
        if let Some(a) = at.filter(|&a| best.is_none_or(|b| a > b.alpha)) {
            best = Some(Found {
                alpha: a,
                beta: c.beta,
                attained: true,
            });
        }
        if at.is_some_and(|a| a >= c.alpha - ATTAINED_REL * c.alpha.abs()) {
            break;
        }
        if closes_on(fam, cf, *c, band) {
            return Some(Found {
                alpha: c.alpha,
                beta: c.beta,
                attained: false,
            });
        }
    }
    best
}

/// A root of p at the candidate lies surely outside |z| < 1 + [`CONFIRM_REL`]: the candidate
/// is not on the stable region's boundary (its pair on the circle aside, every root of a
/// boundary wall is inside or on the circle).
fn surely_outside(fam: &AffineFamily, c: AlphaBeta, coeffs: &mut [f64]) -> bool {
    fam.coefficients_into(c.alpha, c.beta, coeffs);
    let sc = crate::schur_cohn::schur_cohn(coeffs, 1.0 + CONFIRM_REL, 0.0);
    !sc.stable && sc.sure
}

/// Whether the stable intervals at dampings beside a corner's close on it: a stable interval
/// at b ± δ (δ = 1e-6 of the corner's size) reaching within 1e-4 of its stiffness.
fn closes_on(fam: &AffineFamily, cf: &CayleyFamily, c: AlphaBeta, band: (f64, f64)) -> bool {
    let size = c.alpha.abs().max(c.beta.abs()).max(f64::MIN_POSITIVE);
    let delta = CONFIRM_REL * size;
    [c.beta - delta, c.beta + delta]
        .into_iter()
        .filter(|&b| b >= band.0 && b <= band.1)
        .filter_map(|b| top(fam, cf, b))
        .any(|a| (a - c.alpha).abs() <= 1e-4 * size)
}

/// What the damping axis at a stiffness just above K_max holds inside the band.
enum Certificate {
    /// No stable wall: K_max is certified.
    Holds,
    /// A stable damping interval whose ends lie on the complex-pair curve (angles θ at its
    /// ends): a cap of the region above, closing where its two arcs meet.
    Cap { alpha: f64, ends: [(f64, f64); 2] },
    /// A stable interval reaching the band's edge or a z = ±1 line: not settled here.
    Other,
}

/// The damping axis at a stiffness just above K_max (module doc).
fn certificate(
    fam: &AffineFamily,
    cf: &CayleyFamily,
    alpha: f64,
    (lo, hi): (f64, f64),
) -> Certificate {
    let above = alpha + CERTIFY_REL * alpha.abs().max(f64::MIN_POSITIVE);
    let axis = WallLine {
        from: AlphaBeta {
            alpha: above,
            beta: 0.0,
        },
        dir: AlphaBeta {
            alpha: 0.0,
            beta: 1.0,
        },
    };
    let on_curve = |t: f64| t > 0.0 && t < std::f64::consts::PI;
    let hits: Vec<(Interval, [f64; 2])> = stable_intervals_with_angles(fam, cf, &axis)
        .into_iter()
        .filter(|(iv, _)| iv.lo < hi && iv.hi > lo)
        .collect();
    match hits.as_slice() {
        [] => Certificate::Holds,
        [(iv, [t0, t1])] if iv.lo >= lo && iv.hi <= hi && on_curve(*t0) && on_curve(*t1) => {
            Certificate::Cap {
                alpha: above,
                ends: [(iv.lo, *t0), (iv.hi, *t1)],
            }
        }
        _ => Certificate::Other,
    }
}

/// The found top as the region confirms it: the point test just below (inside) and above
/// (not inside) an attained top, the supremum's stable neighbour found by
/// [`confirm_max`].
fn confirmed(fam: &AffineFamily, f: Found, band: (f64, f64)) -> Option<ConfirmedMax> {
    let cand = AlphaBeta {
        alpha: f.alpha,
        beta: f.beta,
    };
    let scale = f.alpha.abs().max(f.beta.abs());
    if f.attained {
        let delta = CONFIRM_REL * f.alpha.abs();
        let mut coeffs = vec![0.0; fam.degree() + 1];
        let mut inside = |a: f64| inside_unit_circle(fam, a, f.beta, &mut coeffs) == Some(true);
        if delta > 0.0 && inside(f.alpha - delta) && !inside(f.alpha + delta) {
            return Some(ConfirmedMax {
                alpha: f.alpha,
                beta: f.beta,
                attained: true,
                beta_stable: f.beta,
                alpha_stable: f.alpha - delta,
            });
        }
    }
    confirm_max(fam, cand, band, scale)
}

/// The curve's candidates (items 2 and 3 of the module doc) in wall units, unfiltered.
fn curve_candidates(fam: &AffineFamily, cf: &CayleyFamily) -> Vec<AlphaBeta> {
    let (a1, a2, b1) = (&cf.p0_pb, &cf.pb_pk, &poly_neg(&cf.p0_pk));
    let mut out: Vec<AlphaBeta> = Vec::new();
    let stationary = poly::add_scaled(
        &poly::mul(&derivative(a1), a2),
        -1.0,
        &poly::mul(a1, &derivative(a2)),
    );
    out.extend(
        positive_roots(&stationary)
            .into_iter()
            .filter_map(|u| curve_point(fam, angle(u))),
    );
    let lines: Vec<RootLine> = [plus_one_line(fam), minus_one_line(fam)]
        .into_iter()
        .flatten()
        .collect();
    for l in &lines {
        let meet = poly::add_scaled(&poly::add_scaled(&scaled(a2, l.p0), l.pk, a1), l.pb, b1);
        out.extend(
            positive_roots(&meet)
                .into_iter()
                .filter_map(|u| corner_on_line(fam, l, angle(u))),
        );
    }
    if let [l1, l2] = lines.as_slice() {
        out.extend(lines_meet(l1, l2));
    }
    out.extend(
        [true, false]
            .into_iter()
            .filter_map(|one| curve_end(fam, one)),
    );
    out
}

/// θ = 2·atan(√u).
fn angle(u: f64) -> f64 {
    2.0 * u.sqrt().atan()
}

/// The curve's point where it meets the line, polished in θ where the line's value changes
/// sign within [`CORNER_REACH`] of the located angle.
fn corner_on_line(fam: &AffineFamily, l: &RootLine, theta: f64) -> Option<AlphaBeta> {
    let value = |t: f64| curve_point(fam, t).map_or(f64::NAN, |p| l.value(p));
    let (t0, t1) = (
        theta * (1.0 - CORNER_REACH),
        (theta * (1.0 + CORNER_REACH)).min(std::f64::consts::PI),
    );
    let (v0, v1) = (value(t0), value(t1));
    let t = if v0.is_finite() && v1.is_finite() && (v0 > 0.0) != (v1 > 0.0) {
        crate::bracket::sign_change(t0, t1, value)
    } else {
        theta
    };
    curve_point(fam, t)
}

/// Where the z = 1 and z = −1 lines meet (None when parallel).
fn lines_meet(l1: &RootLine, l2: &RootLine) -> Option<AlphaBeta> {
    let det = l1.pk * l2.pb - l1.pb * l2.pk;
    let p = AlphaBeta {
        alpha: (-l1.p0 * l2.pb + l1.pb * l2.p0) / det,
        beta: (-l1.pk * l2.p0 + l1.p0 * l2.pk) / det,
    };
    (p.alpha.is_finite() && p.beta.is_finite()).then_some(p)
}

fn poly_neg(c: &[f64]) -> Vec<f64> {
    scaled(c, -1.0)
}

fn scaled(c: &[f64], x: f64) -> Vec<f64> {
    c.iter().map(|v| v * x).collect()
}

/// c′ (ascending coefficients).
fn derivative(c: &[f64]) -> Vec<f64> {
    c.iter()
        .enumerate()
        .skip(1)
        .map(|(j, &v)| v * j as f64)
        .collect()
}
