//! K_max over a damping band without the region's polygon: the largest stable stiffness a
//! with b_lo ≤ b ≤ b_hi (Section V's D-decomposition, without tracing the region).
//!
//! The top of the stable region within the band is reached at the band's edges, at a
//! stationary point of a along the complex-pair curve (a smooth top), at a corner where the
//! curve crosses itself, meets the z = 1 or z = −1 line or ends on one, or where the two lines
//! meet. The search climbs from the bottom of that list:
//! 1. **Start**: the highest end of the exact stable stiffness intervals on the band's edges
//!    (at B = 0 in a band without edges), from [`crate::line_decomposition`].
//! 2. **Certificate**: the damping axis at a stiffness just above the answer holds no stable
//!    wall inside the band.
//! 3. **Caps**: where it holds one, that stable damping interval is a cap of the region
//!    above the answer; its ends lie on arcs of the curve or on the lines, and its top is one
//!    arc's smooth maximum (da/dθ = 0 between the ends), the corner where the two arcs meet
//!    (Newton's method on the two arcs), an arc meeting a line, or the lines meeting. A top
//!    that the exact stable intervals at its damping reach is the next answer; back to 2.
//! 4. **Separate components**: once the certificate holds, a component of the region above
//!    the answer that does not reach down to its level is bounded by arcs of the curve above
//!    that level (between the level's crossings) or has its top at a corner on a line; a
//!    sampled point of such an arc, or such a corner, that may lie on the region's boundary
//!    has the exact stable intervals at its damping tested. The curve's stationary points and
//!    corners are then sought only where the curve may lie above that level
//!    ([`windows::above_windows`]).
//!
//! Where a cap's top is not found, the curve's candidates are taken from the highest down:
//! on the curve a(u) = [P0, PB]/[PB, PK] and b(u) = −[P0, PK]/[PB, PK] in u = tan²(θ/2)
//! ([`crate::cayley`]), so the stationary points are the positive roots of
//! [P0, PB]′·[PB, PK] − [P0, PB]·[PB, PK]′ and the curve meets the line p0 + a·pk + b·pb = 0
//! at the roots of p0·[PB, PK] + pk·[P0, PB] − pb·[P0, PK]; a candidate above the top of the
//! exact intervals at its damping is a corner only touched by the region (a supremum) when
//! the intervals beside its damping close on it. What none of this settles is
//! [`BandMax::Undecided`], and the region decides it ([`crate::region::alpha_max_within`]).

use crate::boundary::{
    Interval, RootLine, WallLine, WallPoint, curve_end, curve_point, curve_point_at, da_dtheta,
    minus_one_line, plus_one_line,
};
use crate::cayley::CayleyFamily;
use crate::closed_loop::{AffineFamily, SHIFTED_THETA};
use crate::line_decomposition::{
    located_crossings_with_roots, stable_intervals, stable_intervals_located,
    stable_intervals_with_angles,
};
use crate::poly;
use crate::real_roots::positive_roots_within;
use crate::region::{ConfirmedMax, confirm_max};

mod cap;
mod windows;
use cap::{Level, cap_by_levels, cap_top_with_arcs};

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

/// K_max over b_lo ≤ b ≤ b_hi (wall units; either end may be infinite) from the
/// D-decomposition's candidates (module doc).
pub fn k_max_band(fam: &AffineFamily, b_lo: f64, b_hi: f64) -> BandMax {
    k_max_band_near(fam, b_lo, b_hi, None).0
}

/// A top of the stable region on the curve — a smooth top of one arc or a corner where two
/// arcs meet — with its stiffness and the arcs' angles θ: what [`k_max_band_near`] starts a
/// neighbouring loop's search from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveTop {
    /// The top's stiffness, wall units.
    pub a: f64,
    /// The angles of the two arcs that meet there; of a smooth top, its angle and NaN.
    pub arcs: [f64; 2],
}

/// [`k_max_band`] warm-started from a neighbouring loop's top on the curve (a sweep's previous
/// point): the two arcs of a corner followed from its angles to where they meet in this loop
/// (the cap corner's Newton iteration), or the stationary point of a(θ) nearest a smooth
/// top's angle (Brent's method on da/dθ), taken as the start where the exact stable intervals
/// at its damping reach it and the certificate above it holds — two line decompositions where
/// the climb from B = 0 takes four; else the cold start. Returns the answer with its own top
/// on the curve, where it is one.
pub fn k_max_band_near(
    fam: &AffineFamily,
    b_lo: f64,
    b_hi: f64,
    near: Option<CurveTop>,
) -> (BandMax, Option<CurveTop>) {
    let Some(cf) = CayleyFamily::new(fam) else {
        return (BandMax::Undecided, None);
    };
    let band = (b_lo, b_hi);
    if let Some(warm) = near.and_then(|c| warm_start(fam, &cf, c, band)) {
        return warm;
    }
    match start(fam, &cf, band) {
        Start::Found(found) => ascend(fam, &cf, found, band, None),
        Start::NoneStable => (BandMax::NoneStable, None),
        Start::Undecided => (BandMax::Undecided, None),
    }
}

/// The search from a neighbouring loop's top on the curve (see [`k_max_band_near`]), taken only
/// where the certificate above its top holds: the band's edges, which the cold start
/// climbs from, then lie below it.
fn warm_start(
    fam: &AffineFamily,
    cf: &CayleyFamily,
    near: CurveTop,
    band: (f64, f64),
) -> Option<(BandMax, Option<CurveTop>)> {
    let (p, arcs) = if near.arcs[1].is_finite() {
        cap::cap_corner(fam, near.a, near.arcs)?
    } else {
        cap::smooth_from(fam, near.arcs[0])?
    };
    if !(p.b >= band.0 && p.b <= band.1) {
        return None;
    }
    let alpha = exact_top(fam, cf, p.a, p.b)?;
    let found = Found {
        a: alpha,
        b: p.b,
        exact: true,
        arcs,
    };
    match certificate(fam, cf, found.a, band) {
        c @ Certificate::Holds { .. } => Some(ascend(fam, cf, found, band, Some(c))),
        _ => None,
    }
}

/// Where the ascent starts.
enum Start {
    Found(Found),
    NoneStable,
    Undecided,
}

/// The highest top on the band's edges (or at B = 0 in a band without edges), else the
/// highest candidate of the curve that the region reaches.
fn start(fam: &AffineFamily, cf: &CayleyFamily, (b_lo, b_hi): (f64, f64)) -> Start {
    let mut dampings: Vec<f64> = [b_lo, b_hi].into_iter().filter(|b| b.is_finite()).collect();
    if dampings.is_empty() {
        dampings.push(0.0);
    }
    let edge = dampings
        .into_iter()
        .filter_map(|b| top_interval(fam, cf, b).map(|iv| (iv, b)))
        .max_by(|p, q| p.0.hi.total_cmp(&q.0.hi));
    if let Some((iv, b)) = edge {
        return Start::Found(Found {
            a: iv.hi,
            b,
            exact: iv.lo < iv.hi - CONFIRM_REL * iv.hi.abs(),
            arcs: NO_ARCS,
        });
    }
    let cands = sorted_candidates(fam, cf, (b_lo, b_hi), f64::NEG_INFINITY, &WHOLE_AXIS);
    match highest_candidate(fam, cf, &cands, None, (b_lo, b_hi)) {
        Some(f) => Start::Found(f),
        None if cands.is_empty() => Start::NoneStable,
        None => Start::Undecided,
    }
}

/// From a stable top upward, cap by cap: the certificate's stable damping interval above the
/// current answer is a cap of the region, whose top ([`cap_top`]) is the next answer once the
/// point test confirms it; where a cap's top is not found or not confirmed, the curve's
/// candidates above the current answer ([`highest_candidate`]) give the next, and failing
/// them the cap's levels ([`cap_by_levels`]). `first`: the certificate at `found`, where
/// it is known. The answer with its top on the curve, where it is one.
fn ascend(
    fam: &AffineFamily,
    cf: &CayleyFamily,
    mut found: Found,
    band: (f64, f64),
    mut first: Option<Certificate>,
) -> (BandMax, Option<CurveTop>) {
    let mut cands: Option<Vec<WallPoint>> = None;
    for _ in 0..CAP_ROUNDS {
        let cert = first
            .take()
            .unwrap_or_else(|| certificate(fam, cf, found.a, band));
        let cap = match cert {
            Certificate::Holds { thetas, roots } => {
                match separate_component(fam, cf, found, (thetas, &roots), band) {
                    Some(f) => {
                        found = f;
                        continue;
                    }
                    None => {
                        let answer =
                            confirmed(fam, found, band).map_or(BandMax::Undecided, BandMax::Max);
                        let top = found.arcs[0].is_finite().then_some(CurveTop {
                            a: found.a,
                            arcs: found.arcs,
                        });
                        return (answer, top);
                    }
                }
            }
            Certificate::Other => None,
            Certificate::Cap { alpha, ends } => Some(Level { a: alpha, ends }),
        };
        match next_top(fam, cf, found, cap, &mut cands, band) {
            Some(f) => found = f,
            None => return (BandMax::Undecided, None),
        }
    }
    (BandMax::Undecided, None)
}

/// The next top above `found`: the cap's top where [`cap_top`] finds it and the exact stable
/// intervals at its damping reach it, else the highest of the curve's candidates above
/// `found` (listed once per search in `cands`), else the cap's top by its levels.
fn next_top(
    fam: &AffineFamily,
    cf: &CayleyFamily,
    found: Found,
    cap: Option<Level>,
    cands: &mut Option<Vec<WallPoint>>,
    band: (f64, f64),
) -> Option<Found> {
    let exact = |(alpha, beta): (f64, f64)| Found {
        a: alpha,
        b: beta,
        exact: true,
        arcs: NO_ARCS,
    };
    let inside = |b: f64| b >= band.0 && b <= band.1;
    let top = cap.and_then(|c| cap_top_with_arcs(fam, c.a, c.ends));
    top.filter(|(c, _)| c.a > found.a && inside(c.b))
        .and_then(|(c, arcs)| {
            exact_top(fam, cf, c.a, c.b).map(|a| Found {
                arcs,
                ..exact((a, c.b))
            })
        })
        .or_else(|| {
            let list =
                cands.get_or_insert_with(|| sorted_candidates(fam, cf, band, found.a, &WHOLE_AXIS));
            highest_candidate(fam, cf, list, Some(found), band).filter(|f| f.a > found.a)
        })
        .or_else(|| {
            let guess = top.map_or(f64::NAN, |(c, _)| c.a);
            cap_by_levels(fam, cf, cap?, guess).map(exact)
        })
}

/// The whole positive u axis, as windows of [`positive_roots_within`].
const WHOLE_AXIS: [(f64, f64); 1] = [(0.0, f64::INFINITY)];

/// The curve's candidates inside the band above `floor`, highest first (items 2 and 3 of the
/// module doc: the curve's stationary points in stiffness and its corners on the z = ±1
/// lines), sought in the windows of u outside which the curve lies below the floor
/// ([`WHOLE_AXIS`] or [`windows::above_windows`]).
fn sorted_candidates(
    fam: &AffineFamily,
    cf: &CayleyFamily,
    (b_lo, b_hi): (f64, f64),
    floor: f64,
    windows: &[(f64, f64)],
) -> Vec<WallPoint> {
    // located candidates far below the floor or outside the band are not polished
    let keep = |p: WallPoint| {
        let slack = CORNER_REACH * p.a.abs().max(p.b.abs());
        p.a > floor - slack && p.b >= b_lo - slack && p.b <= b_hi + slack
    };
    let (a1, a2) = (&cf.p0_pb, &cf.pb_pk);
    let stationary = poly::mul_diff_trimmed(&derivative(a1), a2, a1, &derivative(a2));
    let mut cands: Vec<WallPoint> = positive_roots_within(&stationary, windows)
        .into_iter()
        .filter_map(|u| curve_point(fam, angle(u)))
        .chain(line_corners(fam, cf, &keep, floor, (b_lo, b_hi), windows))
        .filter(|p| p.b >= b_lo && p.b <= b_hi && p.a.is_finite())
        .collect();
    cands.sort_by(|p, q| q.a.total_cmp(&p.a));
    cands
}

/// Caps closed before the search gives up (each a corner where the curve crosses itself
/// above the previous answer; one is the rule, a second is rare).
const CAP_ROUNDS: usize = 4;

/// The highest end of the stable stiffness intervals at damping b (None when none is stable
/// or the highest is unbounded).
fn top(fam: &AffineFamily, cf: &CayleyFamily, b: f64) -> Option<f64> {
    top_interval(fam, cf, b).map(|iv| iv.hi)
}

/// The stable stiffness interval at damping b with the highest finite end.
fn top_interval(fam: &AffineFamily, cf: &CayleyFamily, b: f64) -> Option<Interval> {
    stable_intervals(fam, cf, &WallLine::stiffness_axis(b))
        .into_iter()
        .filter(|iv| iv.hi.is_finite())
        .max_by(|x, y| x.hi.total_cmp(&y.hi))
}

/// A top at damping b that the exact stable intervals there reach: their highest end within
/// [`ATTAINED_REL`] of a, in an interval holding a·(1 − [`CONFIRM_REL`]) (the wall the
/// answer reports stable). The exact end, or None — at once where the wall at
/// a·(1 − [`CONFIRM_REL`]/2), which such an interval holds, has a root surely outside the
/// circle ([`surely_outside`]: a stationary point or corner that is not the region's top, for
/// one Schur–Cohn recursion instead of a line decomposition).
fn exact_top(fam: &AffineFamily, cf: &CayleyFamily, a: f64, b: f64) -> Option<f64> {
    let mut coeffs = vec![0.0; fam.degree() + 1];
    let below = WallPoint {
        a: a - 0.5 * CONFIRM_REL * a.abs(),
        b,
    };
    if surely_outside(fam, below, &mut coeffs) {
        return None;
    }
    let iv = top_interval(fam, cf, b)?;
    let reach = (iv.hi - a).abs() <= ATTAINED_REL * a.abs();
    (reach && iv.lo < iv.hi - CONFIRM_REL * iv.hi.abs()).then_some(iv.hi)
}

/// A found top of the region.
#[derive(Debug, Clone, Copy)]
struct Found {
    a: f64,
    b: f64,
    /// The top of the exact stable interval at `b` (see [`exact_top`]); false for a
    /// corner that the region only closes on (a supremum).
    exact: bool,
    /// Where it is a top on the curve: the angles of the two arcs that meet there, or of a
    /// smooth top and NaN ([`NO_ARCS`] else).
    arcs: [f64; 2],
}

/// [`Found::arcs`] of a top that is not on the curve, or whose arcs are not known.
const NO_ARCS: [f64; 2] = [f64::NAN; 2];

/// The highest of a floor (a top found already) and the candidates that the region reaches
/// (attained) or closes on (a supremum), taking candidates from the highest down.
fn highest_candidate(
    fam: &AffineFamily,
    cf: &CayleyFamily,
    cands: &[WallPoint],
    floor: Option<Found>,
    band: (f64, f64),
) -> Option<Found> {
    let mut best = floor;
    let mut coeffs = vec![0.0; fam.degree() + 1];
    for c in cands {
        if best.is_some_and(|b| c.a <= b.a) {
            break;
        }
        if surely_outside(fam, *c, &mut coeffs) {
            continue;
        }
        let iv = top_interval(fam, cf, c.b);
        let at = iv.map(|iv| iv.hi);
        if let Some(iv) = iv.filter(|iv| best.is_none_or(|b| iv.hi > b.a)) {
            best = Some(Found {
                a: iv.hi,
                b: c.b,
                exact: iv.lo < iv.hi - CONFIRM_REL * iv.hi.abs(),
                arcs: NO_ARCS,
            });
        }
        if at.is_some_and(|a| a >= c.a - ATTAINED_REL * c.a.abs()) {
            break;
        }
        if closes_on(fam, cf, *c, band) {
            return Some(Found {
                a: c.a,
                b: c.b,
                exact: false,
                arcs: NO_ARCS,
            });
        }
    }
    best
}

/// A root of p at the candidate lies surely outside |z| < 1 + [`CONFIRM_REL`]: the candidate
/// is not on the stable region's boundary (its pair on the circle aside, every root of a
/// boundary wall is inside or on the circle).
fn surely_outside(fam: &AffineFamily, c: WallPoint, coeffs: &mut [f64]) -> bool {
    fam.coefficients_into(c.a, c.b, coeffs);
    if product_outside(coeffs) {
        return true;
    }
    let sc = crate::schur_cohn::schur_cohn(coeffs, 1.0 + CONFIRM_REL, 0.0);
    !sc.stable && sc.sure
}

/// The product of p's root moduli |c_0/c_n| exceeds (1 + [`CONFIRM_REL`])^n by more than its
/// rounding: one root at least lies surely outside that circle (Vieta), without the
/// Schur–Cohn recursion.
fn product_outside(c: &[f64]) -> bool {
    let (Some(&c0), Some(&cn)) = (c.first(), c.last()) else {
        return false;
    };
    let n = (c.len() - 1) as i32;
    c0.abs() > cn.abs() * (1.0 + CONFIRM_REL).powi(n) * (1.0 + 1e-12)
}

/// Whether the stable intervals at dampings beside a corner's close on it: a stable interval
/// at b ± δ (δ = 1e-6 of the corner's size) reaching within 1e-4 of its stiffness.
fn closes_on(fam: &AffineFamily, cf: &CayleyFamily, c: WallPoint, band: (f64, f64)) -> bool {
    let size = c.a.abs().max(c.b.abs()).max(f64::MIN_POSITIVE);
    let delta = CONFIRM_REL * size;
    [c.b - delta, c.b + delta]
        .into_iter()
        .filter(|&b| b >= band.0 && b <= band.1)
        .filter_map(|b| top(fam, cf, b))
        .any(|a| (a - c.a).abs() <= 1e-4 * size)
}

/// What the damping axis at a stiffness just above K_max holds inside the band.
enum Certificate {
    /// No stable wall: K_max is certified on the level, whose crossings' angles θ and the
    /// positive roots u of its crossing polynomial are kept for [`separate_component`].
    Holds { thetas: Vec<f64>, roots: Vec<f64> },
    /// One stable damping interval inside the band (its ends' dampings and angles θ, 0 or π
    /// on the z = ±1 lines): a cap of the region above, closing at its top.
    Cap { alpha: f64, ends: [(f64, f64); 2] },
    /// Several stable intervals, or one reaching past the band's edges: not settled here.
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
    let axis = damping_axis(above);
    let known = |t: f64| (0.0..=std::f64::consts::PI).contains(&t);
    let (located, roots) = located_crossings_with_roots(fam, cf, &axis);
    let hits: Vec<(Interval, [f64; 2])> = stable_intervals_located(fam, &axis, &located)
        .into_iter()
        .filter(|(iv, _)| iv.lo < hi && iv.hi > lo)
        .collect();
    match hits.as_slice() {
        [] => Certificate::Holds {
            thetas: located.iter().map(|c| c.theta).collect(),
            roots,
        },
        [(iv, [t0, t1])] if iv.lo >= lo && iv.hi <= hi && known(*t0) && known(*t1) => {
            Certificate::Cap {
                alpha: above,
                ends: [(iv.lo, *t0), (iv.hi, *t1)],
            }
        }
        _ => Certificate::Other,
    }
}

/// Samples of a(θ) on each arc of the curve between consecutive crossings of the
/// certificate's level.
const HUMP_SAMPLES: usize = 12;

/// A part of the stable region above the answer that does not reach down to it (a separate
/// component): the curve rises above the answer's level a* only on arcs between consecutive
/// angles at which it crosses that level (the damping axis's crossings at a*), and such a
/// component is bounded by them; on each such hump (outside the windows of u certified below
/// the level, [`windows::above_windows`]) the first sampled point that may lie on
/// the region's boundary (no root surely outside) has its exact stable intervals tested at
/// its damping; then the curve's stationary points and corners above a* (an island's
/// extremes), as [`highest_candidate`] takes them. The first top found above a*, or None.
fn separate_component(
    fam: &AffineFamily,
    cf: &CayleyFamily,
    found: Found,
    (level_thetas, level_roots): (Vec<f64>, &[f64]),
    (lo, hi): (f64, f64),
) -> Option<Found> {
    use std::f64::consts::PI;
    let level = found.a + CERTIFY_REL * found.a.abs().max(f64::MIN_POSITIVE);
    let mut thetas: Vec<f64> = level_thetas
        .into_iter()
        .filter(|&t| t > 0.0 && t < PI)
        .collect();
    thetas.push(0.0);
    thetas.push(PI);
    thetas.sort_by(f64::total_cmp);
    // the windows of u where the curve may rise above the level: a hump outside them (beyond
    // a relative slack for the crossings' rounding) lies below it throughout
    let windows = windows::above_windows(cf, level, level_roots);
    let u_of = |t: f64| (0.5 * t).tan().powi(2);
    let may_rise = |t0: f64, t1: f64| {
        let (u0, u1) = (u_of(t0), u_of(t1));
        windows
            .iter()
            .any(|&(l, r)| l < u1 * (1.0 - WINDOW_SLACK) && r > u0 * (1.0 + WINDOW_SLACK))
    };
    let mut coeffs = vec![0.0; fam.degree() + 1];
    for w in thetas.windows(2).filter(|w| may_rise(w[0], w[1])) {
        let step = (w[1] - w[0]) / (HUMP_SAMPLES + 1) as f64;
        // the first sample above the level that may lie on the boundary, inside the band
        let on_hump = hump_samples(fam, w[0], step).find(|p| {
            p.a > level
                && p.a.is_finite()
                && p.b >= lo
                && p.b <= hi
                && !surely_outside(fam, *p, &mut coeffs)
        });
        let Some(p) = on_hump else { continue };
        if let Some(iv) = top_interval(fam, cf, p.b).filter(|iv| iv.hi > level) {
            return Some(Found {
                a: iv.hi,
                b: p.b,
                exact: iv.lo < iv.hi - CONFIRM_REL * iv.hi.abs(),
                arcs: NO_ARCS,
            });
        }
    }
    // an island whose boundary the samples miss: its top, bottom or sides are among the
    // curve's stationary points and corners
    let cands = sorted_candidates(fam, cf, (lo, hi), level, &windows);
    highest_candidate(fam, cf, &cands, Some(found), (lo, hi)).filter(|f| f.a > level)
}

/// Relative slack by which a hump's ends in u (u = tan²(θ/2)) must reach into a window of
/// [`windows::above_windows`] for its samples to be taken: the crossings' angles and the
/// roots u of their polynomial are the same points rounded apart.
const WINDOW_SLACK: f64 = 1e-9;

/// The curve's points at θ0 + j·step, j = 1 … [`HUMP_SAMPLES`]: z stepped along the circle by
/// one rotation (no sine per point) where θ ≥ [`SHIFTED_THETA`], from the shifted form below.
fn hump_samples(fam: &AffineFamily, theta0: f64, step: f64) -> impl Iterator<Item = WallPoint> {
    let rotation = crate::circle::unit(step);
    let mut z = crate::circle::unit(theta0);
    (1..=HUMP_SAMPLES).filter_map(move |j| {
        z *= rotation;
        let theta = theta0 + step * j as f64;
        if theta < SHIFTED_THETA {
            curve_point(fam, theta)
        } else {
            curve_point_at(fam, z)
        }
    })
}

/// The damping axis at stiffness a.
fn damping_axis(alpha: f64) -> WallLine {
    WallLine {
        from: WallPoint { a: alpha, b: 0.0 },
        dir: WallPoint { a: 0.0, b: 1.0 },
    }
}

/// The found top as the region reports it: an exact top (the exact stable interval at its
/// damping reaches it, holding K_max·(1 − 1e-6)) is attained; a corner the region only closes
/// on gets its supremum's stable neighbour from [`confirm_max`].
fn confirmed(fam: &AffineFamily, f: Found, band: (f64, f64)) -> Option<ConfirmedMax> {
    if f.exact {
        return Some(ConfirmedMax {
            a: f.a,
            b: f.b,
            attained: true,
            b_stable: f.b,
            a_stable: f.a - CONFIRM_REL * f.a.abs(),
        });
    }
    let cand = WallPoint { a: f.a, b: f.b };
    confirm_max(fam, cand, band, f.a.abs().max(f.b.abs()))
}

/// The corners on the z = ±1 lines (item 3 of the module doc): where the curve meets each
/// line (not sought on a line that stays below `floor` over the band, [`line_below`], nor
/// outside `windows`), where the lines meet, and the curve's ends.
fn line_corners(
    fam: &AffineFamily,
    cf: &CayleyFamily,
    keep: &dyn Fn(WallPoint) -> bool,
    floor: f64,
    band: (f64, f64),
    windows: &[(f64, f64)],
) -> Vec<WallPoint> {
    let (a1, a2, b1) = (&cf.p0_pb, &cf.pb_pk, &poly_neg(&cf.p0_pk));
    let mut out: Vec<WallPoint> = Vec::new();
    let lines: Vec<RootLine> = [plus_one_line(fam), minus_one_line(fam)]
        .into_iter()
        .flatten()
        .collect();
    for l in lines.iter().filter(|l| !line_below(l, floor, band)) {
        let meet = poly::weighted_sum_trimmed(&[(l.p0, a2), (l.pk, a1), (l.pb, b1)]);
        out.extend(
            positive_roots_within(&meet, windows)
                .into_iter()
                .filter_map(|u| corner_on_line(fam, l, angle(u), keep)),
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

/// A line's corners with the curve lie on it, so where its stiffness a stays below the floor
/// over the band by more than this (relative) their candidates fall below it too: the
/// candidates' own slack ([`CORNER_REACH`]) a thousand times over.
const LINE_BELOW_REL: f64 = 1e-3;

/// The line's stiffness a = −(p0 + b·pb)/pk stays below `floor` (by [`LINE_BELOW_REL`]) for
/// every damping b of the band: none of its corners can be a candidate above the floor (the
/// search takes candidates above the current answer only), and the roots of its meeting
/// polynomial are not sought. For the z = 1 line of a loop whose velocity estimate vanishes at
/// DC (pb = 0, a = −p0/pk below every stable stiffness) this holds over any band.
fn line_below(l: &RootLine, floor: f64, (b_lo, b_hi): (f64, f64)) -> bool {
    if l.pk == 0.0 || !floor.is_finite() {
        return false;
    }
    let at = |b: f64| -(l.p0 + b * l.pb) / l.pk;
    let top = if l.pb == 0.0 {
        at(0.0)
    } else {
        at(b_lo).max(at(b_hi))
    };
    top.is_finite() && top < floor - LINE_BELOW_REL * floor.abs().max(top.abs())
}

/// θ = 2·atan(√u).
fn angle(u: f64) -> f64 {
    2.0 * u.sqrt().atan()
}

/// The curve's point where it meets the line, polished in θ where the line's value changes
/// sign within [`CORNER_REACH`] of the located angle; None for a located point that `keep`
/// rejects.
fn corner_on_line(
    fam: &AffineFamily,
    l: &RootLine,
    theta: f64,
    keep: &dyn Fn(WallPoint) -> bool,
) -> Option<WallPoint> {
    if !keep(curve_point(fam, theta)?) {
        return None;
    }
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
fn lines_meet(l1: &RootLine, l2: &RootLine) -> Option<WallPoint> {
    let det = l1.pk * l2.pb - l1.pb * l2.pk;
    let p = WallPoint {
        a: (-l1.p0 * l2.pb + l1.pb * l2.p0) / det,
        b: (-l1.pk * l2.p0 + l1.p0 * l2.pk) / det,
    };
    (p.a.is_finite() && p.b.is_finite()).then_some(p)
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
