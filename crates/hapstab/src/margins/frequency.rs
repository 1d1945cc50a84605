//! The loop's frequency response on the unit circle and the frequencies where margins are
//! read: every gain crossover |L(e^{iθ})| = 1, the peak gain max |L| and the stability
//! (modulus) margin min |1 + L|, for the open loop L = (a·PK + b·PB)/P0 of eq. 7–9.
//!
//! **No crossing lost.** |L| is a ratio of trigonometric polynomials whose features live on
//! the scale of the distance of the roots of P0 and of W = a·PK + b·PB to the unit circle: a
//! lightly damped mode at r·e^{iφ} makes a peak of width ≈ 1 − r at θ = φ, a free mass or a
//! fast sampling (roots crowding z = 1) puts crossovers at θ ≪ 1/n. The grid is therefore
//! the union of
//! - a uniform grid of [`UNIFORM_PER_DEGREE`]·(n + 1) angles (n the delay-free degree: a
//!   whole-sample delay turns the phase of L but leaves |L| unchanged), the scale of the
//!   roots far from the circle (a trigonometric polynomial of degree n varies on 1/n),
//! - geometric runs toward θ = 0 and θ = π down to [`THETA_FLOOR`] of π, [`END_PER_DECADE`]
//!   per decade (there, below every root's scale, |L|² is a smooth function of θ², so a
//!   crossover is a sign change and an extremum a local extremum of the samples),
//! - geometric runs on both sides of the angle of every root of P0 and of W, from a tenth of
//!   its distance to the circle outward, [`PER_DECADE`] per decade, until their step is
//!   coarser than the uniform grid's (beyond, the root's feature is wider than that grid's
//!   step).
//!
//! Every sign change of ln|L| on the grid is a crossover (refined to rounding by Brent's
//! method, [`crate::bracket`]), and every local extremum of the samples is refined by golden
//! section, its bracket moved while the search lands on an end ([`crate::extremum`]): an
//! extremum that changes sign inside its cell is a pair of crossovers the samples straddled.

use num_complex::Complex64;
use serde::Serialize;

use crate::boundary::CircleTable;
use crate::closed_loop::AffineFamily;
use crate::extremum::{may_exceed, merge_grid, merge_sorted_grids, refine_max, sample_maxima};
use crate::poly::modulus;
use crate::stability::roots;

/// Uniform samples per degree: |L| − 1 changes sign at most twice per degree, and away from
/// the roots near the circle (which have their own runs) a trigonometric polynomial of degree
/// n varies on the scale π/n, which this resolves sixteen times.
pub const UNIFORM_PER_DEGREE: usize = 16;

/// The geometric runs toward θ = 0 and θ = π end at this fraction of π (a frequency of
/// 1e-12 of the Nyquist frequency).
pub const THETA_FLOOR: f64 = 1e-12;

/// Geometric samples per factor of 10 in the runs around roots (a step of 21 % of the
/// distance from the root's angle: its peak of width 1 − r is sampled about five times).
pub const PER_DECADE: usize = 12;

/// Geometric samples per factor of 10 in the runs toward θ = 0 and π, where no root's feature
/// lies (those have their own runs): |L|² is smooth in θ² there.
pub const END_PER_DECADE: usize = 6;

/// Local extrema of ln|L| within this of 0 (|L| within a factor of two of 1) are refined.
const REFINE_LOG: f64 = std::f64::consts::LN_2;

/// Refinement of a crossover, an extremum or a minimum stops at this relative width in θ.
const THETA_REL: f64 = 1e-13;

/// The open loop of one wall at θ: L(e^{iθ}) = (a·PK + b·PB)/P0.
pub fn loop_value(fam: &AffineFamily, a: f64, b: f64, theta: f64) -> Complex64 {
    let (p0, pk, pb) = fam.parts_on_circle(theta);
    (pk * a + pb * b) / p0
}

/// ln |L(e^{iθ})|, free of the delay's phase.
fn log_gain(fam: &AffineFamily, a: f64, b: f64, theta: f64) -> f64 {
    let (_, core, pk, pb) = fam.unturned_on_circle(theta);
    log_ratio(pk * a + pb * b, core)
}

/// ln(|x|/|y|) with one logarithm, ½·ln(|x|²/|y|²), where the squares and their ratio are
/// normal numbers; else from the moduli ([`modulus`]).
fn log_ratio(x: Complex64, y: Complex64) -> f64 {
    let (nx, ny) = (x.norm_sqr(), y.norm_sqr());
    let q = nx / ny;
    if nx.is_normal() && ny.is_normal() && q.is_normal() {
        0.5 * q.ln()
    } else {
        modulus(x).ln() - modulus(y).ln()
    }
}

/// The angles θ ∈ (0, π) on which |L| of the wall (a, b) is sampled (module doc), sorted.
pub fn frequency_grid(fam: &AffineFamily, a: f64, b: f64) -> Vec<f64> {
    let pi = std::f64::consts::PI;
    let core = fam.p0_core.len().max(fam.pk.len()).max(fam.pb.len());
    let m = UNIFORM_PER_DEGREE * (core + 1);
    let mut ts: Vec<f64> = (1..m).map(|i| pi * i as f64 / m as f64).collect();
    let decades = (-THETA_FLOOR.log10()) as usize * END_PER_DECADE;
    for j in 1..=decades {
        let t = pi * 10f64.powf(-(j as f64) / END_PER_DECADE as f64);
        ts.push(t);
        ts.push(pi - t);
    }
    // the roots from the shifted form where there is one: roots crowding z = 1 (fast
    // sampling) are placed there to their distance from 1, in z only to ε^{1/m}
    let (core, pk, pb, shift) = match &fam.shifted {
        Some(sh) => (&sh.p0_core, &sh.pk, &sh.pb, 1.0),
        None => (&fam.p0_core, &fam.pk, &fam.pb, 0.0),
    };
    let w = wall_poly(pk, pb, a, b);
    push_root_runs(
        &mut ts,
        &[core.as_slice(), trimmed(&w)],
        shift,
        pi / m as f64,
    );
    merge_grid(&mut ts);
    ts
}

/// The geometric runs of [`frequency_grid`] around the roots of the given polynomials alone
/// (ascending coefficients in x = z − `shift`: 0 for z, 1 for w = z − 1), each run ending where its step exceeds `step` (the uniform
/// grid's), sorted: what a second wall part on the same P0 (the loop at
/// another fraction of a sample, [`super::fraction`]) adds to the grid of the first.
pub fn root_grid(polys: &[&[f64]], shift: f64, step: f64) -> Vec<f64> {
    let mut ts = Vec::new();
    push_root_runs(&mut ts, polys, shift, step);
    merge_grid(&mut ts);
    ts
}

/// W = a·PK + b·PB (ascending).
fn wall_poly(pk: &[f64], pb: &[f64], a: f64, b: f64) -> Vec<f64> {
    crate::poly::add_scaled(&crate::poly::add_scaled(&[], a, pk), b, pb)
}

/// Geometric runs on both sides of the angle of every root of the polynomials (module doc),
/// from a tenth of the root's distance to the circle outward until the run's step exceeds
/// `step`, and the angle itself; the polynomials are in x = z − `shift`.
fn push_root_runs(ts: &mut Vec<f64>, polys: &[&[f64]], shift: f64, step: f64) {
    let pi = std::f64::consts::PI;
    let ratio = 10f64.powf(1.0 / PER_DECADE as f64);
    for (phi, dist) in root_angles(polys, shift) {
        let mut h = 0.1 * dist.max(THETA_FLOOR * pi);
        while h < pi && h * (ratio - 1.0) < step {
            for t in [phi - h, phi + h] {
                if t > 0.0 && t < pi {
                    ts.push(t);
                }
            }
            h *= ratio;
        }
        if phi > 0.0 && phi < pi {
            ts.push(phi);
        }
    }
}

/// (|arg z|, ||z| − 1|) of every root z = x + shift of the polynomials (ascending
/// coefficients in x).
fn root_angles(polys: &[&[f64]], shift: f64) -> Vec<(f64, f64)> {
    polys
        .iter()
        .filter(|c| c.len() > 1)
        .filter_map(|c| roots(c).ok())
        .flatten()
        .map(|x| x + shift)
        .filter(|z| z.is_finite())
        .map(|z| (z.arg().abs(), (z.norm() - 1.0).abs()))
        .collect()
}

/// The coefficients without trailing (leading-power) zeros.
pub(crate) fn trimmed(c: &[f64]) -> &[f64] {
    let n = c.iter().rposition(|&x| x != 0.0).map_or(0, |i| i + 1);
    &c[..n]
}

/// A gain crossover: |L(e^{iθ})| = 1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GainCrossover {
    /// The angle θ ∈ (0, π).
    pub theta: f64,
    /// 180° + arg L there, wrapped to (−180°, 180°]: the phase margin read at it.
    pub phase_margin_deg: f64,
}

/// Samples of ln|L| on the grid and what they show.
pub struct GainScan {
    /// Every gain crossover, in increasing θ.
    pub crossovers: Vec<GainCrossover>,
    /// max |L| over θ ∈ (0, π) and where.
    pub peak: (f64, f64),
}

/// Every gain crossover and the peak gain of the wall (a, b) (module doc).
pub fn gain_scan(fam: &AffineFamily, a: f64, b: f64) -> GainScan {
    let table = CircleTable::on(fam, frequency_grid(fam, a, b));
    gain_scan_tabulated(fam, a, b, &table)
}

/// The margins' shared grid: the family's [`frequency_grid`] `modes` joined by a uniform grid
/// of [`UNIFORM_PER_DEGREE`]·(n + 2) angles for p's degree n (a delay turns the phase of L
/// once per 2π/d, so the phase crossings and min |1 + L| need it), inside (0, π).
pub fn margin_grid(fam: &AffineFamily, modes: &[f64]) -> Vec<f64> {
    let m = UNIFORM_PER_DEGREE * (fam.degree() + 2);
    let pi = std::f64::consts::PI;
    let uniform: Vec<f64> = (1..m).map(|i| pi * i as f64 / m as f64).collect();
    merge_sorted_grids(modes, &uniform)
}

/// [`gain_scan`] with the samples taken from a table on a grid that contains the family's
/// [`frequency_grid`] (the margins' shared [`margin_grid`]).
pub fn gain_scan_tabulated(fam: &AffineFamily, a: f64, b: f64, table: &CircleTable) -> GainScan {
    let ts = table.thetas();
    let g = |t: f64| log_gain(fam, a, b, t);
    let vs: Vec<f64> = table
        .parts()
        .iter()
        .map(|&(p0, pk, pb)| log_ratio(pk * a + pb * b, p0))
        .collect();
    let mut thetas = Vec::new();
    let mut peak = (f64::NEG_INFINITY, f64::NAN);
    for i in 0..ts.len() {
        if vs[i] > peak.0 {
            peak = (vs[i], ts[i]);
        }
        if i > 0 && (vs[i] > 0.0) != (vs[i - 1] > 0.0) && vs[i].is_finite() && vs[i - 1].is_finite()
        {
            thetas.push(crate::bracket::sign_change(ts[i - 1], ts[i], g));
        }
    }
    // Extrema within a factor of two of |L| = 1 are refined (the grid samples every mode's
    // peak within a tenth of its width, so a farther one cannot reach 1): a maximum below 1
    // that rises above it, or a minimum above 1 that dips below, is a pair of crossovers the
    // samples straddled.
    let neg: Vec<f64> = vs.iter().map(|v| -v).collect();
    for i in sample_maxima(&vs) {
        if vs[i] > -REFINE_LOG {
            let (t, v) = refine_max(g, ts, i, THETA_REL);
            if v > peak.0 {
                peak = (v, t);
            }
            if vs[i] <= 0.0 && v > 0.0 {
                thetas.extend(pair_around(ts, t, |x| g(x) <= 0.0, g));
            }
        }
    }
    for i in sample_maxima(&neg) {
        if vs[i] > 0.0 && vs[i] < REFINE_LOG {
            let (t, v) = refine_max(|x| -g(x), ts, i, THETA_REL);
            if -v <= 0.0 {
                thetas.extend(pair_around(ts, t, |x| g(x) > 0.0, g));
            }
        }
    }
    if let Some(i) = (0..ts.len()).max_by(|&i, &j| vs[i].total_cmp(&vs[j])) {
        let (t, v) = refine_max(g, ts, i, THETA_REL);
        if v > peak.0 {
            peak = (v, t);
        }
    }
    thetas.sort_by(f64::total_cmp);
    thetas.dedup_by(|x, y| (*x - *y).abs() <= 1e-9 * y.abs());
    let crossovers = thetas
        .into_iter()
        .map(|theta| GainCrossover {
            theta,
            phase_margin_deg: wrap_degrees(180.0 + loop_value(fam, a, b, theta).arg().to_degrees()),
        })
        .collect();
    GainScan {
        crossovers,
        peak: (peak.0.exp(), peak.1),
    }
}

/// The crossings of g = 0 on both sides of an extremum at t that lies across zero from the
/// samples of its grid cell: refined between t and each neighbouring sample on the other
/// side (`other_side`); a neighbour on t's side leaves that crossing to the sign-change scan.
fn pair_around(
    ts: &[f64],
    t: f64,
    other_side: impl Fn(f64) -> bool,
    g: impl Fn(f64) -> f64,
) -> Vec<f64> {
    let j = ts.partition_point(|&x| x < t);
    let lo = ts[j.saturating_sub(1)];
    let hi = ts[j.min(ts.len() - 1)];
    [(lo, t), (t, hi)]
        .into_iter()
        .filter(|&(x, y)| x < y && other_side(if x == t { y } else { x }))
        .map(|(x, y)| crate::bracket::sign_change(x, y, &g))
        .collect()
}

/// min over θ ∈ [0, π] of |1 + L(e^{iθ})| = |p(e^{iθ})|/|P0(e^{iθ})|, the distance of the
/// Nyquist curve to −1 (python-control's `sm`), and the θ where it is reached. The grid is the
/// frequency grid of the delay-free magnitude refined by the uniform grid of the full degree
/// (a delay turns L round −1 once per 2π/d).
pub fn stability_margin(fam: &AffineFamily, a: f64, b: f64) -> (f64, f64) {
    let table = CircleTable::on(fam, margin_grid(fam, &frequency_grid(fam, a, b)));
    stability_margin_tabulated(fam, a, b, &table)
}

/// [`stability_margin`] with the samples taken from a table on the [`margin_grid`], and at
/// θ = 0 and π.
pub fn stability_margin_tabulated(
    fam: &AffineFamily,
    a: f64,
    b: f64,
    table: &CircleTable,
) -> (f64, f64) {
    let pi = std::f64::consts::PI;
    let f = |t: f64| {
        let (p0, pk, pb) = fam.parts_on_circle(t);
        modulus(p0 + pk * a + pb * b) / modulus(p0)
    };
    let mut ts = Vec::with_capacity(table.thetas().len() + 2);
    ts.push(0.0);
    ts.extend_from_slice(table.thetas());
    ts.push(pi);
    let mut neg = Vec::with_capacity(ts.len());
    neg.push(-f(0.0));
    neg.extend(
        table
            .parts()
            .iter()
            .map(|&(p0, pk, pb)| -(modulus(p0 + pk * a + pb * b) / modulus(p0))),
    );
    neg.push(-f(pi));
    let mut best = (f64::INFINITY, f64::NAN);
    for (i, &v) in neg.iter().enumerate() {
        if -v < best.0 {
            best = (-v, ts[i]);
        }
    }
    // the deepest sampled minima first, so that the best so far rules out the rest early
    let mut minima: Vec<usize> = sample_maxima(&neg).collect();
    minima.sort_by(|&i, &j| neg[j].total_cmp(&neg[i]));
    for i in minima {
        if may_exceed(&ts, &neg, i, -best.0) {
            let (t, v) = refine_max(|x| -f(x), &ts, i, THETA_REL);
            if -v < best.0 {
                best = (-v, t);
            }
        }
    }
    best
}

/// An angle in degrees wrapped to (−180°, 180°].
pub fn wrap_degrees(d: f64) -> f64 {
    let w = d.rem_euclid(360.0);
    if w > 180.0 { w - 360.0 } else { w }
}
