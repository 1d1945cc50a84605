//! The linear stability condition (Section VI, eq. 16–23) and its validity against the exact
//! boundary (Section VII, eq. 24, Fig. 7).
//!
//! Approximating sample-and-hold by half a sample of delay and e^{−t_r s} ≈ 1/(1 + t_r s),
//! t_r = t_d + T/2, turns the loop into the cubic of eq. (17),
//!
//! ```text
//! m t_r s³ + (b t_r + m) s² + (k t_r + b + B) s + k + K = 0,
//! ```
//!
//! whose Routh–Hurwitz conditions are (18)–(20). Dropping the small term ε of eq. (21) gives
//! the linear condition (22) K < (b + B)/t_r, in normalized form (23) α < (β + δ)/(d + 1/2),
//! together with the lower bound (19) K > −k, α > −γ.

use serde::Serialize;

use crate::boundary::{WallLine, WallPoint, line_crossings, stable_stiffness_intervals};
use crate::error::{Error, Result, finite};
use crate::model::{Loop, PlantModel};
use crate::paper::NormalizedFamily;
use crate::paper::{Normalized, PlantParams};
use crate::param::Param;
use crate::params::{Physical, check_delay};
use crate::zoh::WallScale;

/// The cubic a3 s³ + a2 s² + a1 s + a0 of eq. (17).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Cubic {
    /// Coefficient of s³: m t_r.
    pub a3: f64,
    /// Coefficient of s²: b t_r + m.
    pub a2: f64,
    /// Coefficient of s: k t_r + b + B.
    pub a1: f64,
    /// Constant: k + K.
    pub a0: f64,
}

/// The cubic of eq. (17) in physical units (s in 1/s), from the approximation of eq. (16)
/// with t_r = t_d + T/2 and e^{−t_r s} ≈ 1/(1 + t_r s) (Section VI).
pub fn continuous_cubic(p: &Physical) -> Cubic {
    let (m, b, k) = (p.plant.mass, p.plant.damping, p.plant.stiffness);
    let (kw, bw) = (p.wall.stiffness, p.wall.damping);
    let tr = effective_delay(p);
    Cubic {
        a3: m * tr,
        a2: b * tr + m,
        a1: k * tr + b + bw,
        a0: k + kw,
    }
}

/// The cubic of eq. (17) in normalized units (time unit T, divided by m/T²): with
/// t_r/T = d + 1/2 it reads (d + ½) s³ + (δ(d + ½) + 1) s² + (γ(d + ½) + δ + β) s + γ + α
/// (Section VI with Table I).
pub fn continuous_cubic_normalized(n: &Normalized) -> Cubic {
    let tr = n.d as f64 + 0.5;
    Cubic {
        a3: tr,
        a2: n.delta * tr + 1.0,
        a1: n.gamma * tr + n.delta + n.beta,
        a0: n.gamma + n.alpha,
    }
}

/// The effective delay t_r = t_d + T/2 of eq. (16)–(17) in seconds.
pub fn effective_delay(p: &Physical) -> f64 {
    p.sampling.delay_time() + p.sampling.period / 2.0
}

/// One inequality `lhs > rhs`, reported with its margin lhs − rhs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Inequality {
    /// Left-hand side.
    pub lhs: f64,
    /// Right-hand side.
    pub rhs: f64,
    /// lhs − rhs.
    pub margin: f64,
    /// lhs > rhs.
    pub holds: bool,
}

impl Inequality {
    fn new(lhs: f64, rhs: f64) -> Self {
        Self {
            lhs,
            rhs,
            margin: lhs - rhs,
            holds: lhs > rhs,
        }
    }
}

/// The Routh–Hurwitz conditions (18)–(20) of the cubic (17) for positive m, T, t_d, b, k
/// (Section VI). The fourth condition of a cubic, a2 = b t_r + m > 0, holds for every
/// physical plant.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RouthHurwitz {
    /// Eq. (18): b + B > −k t_r (a1 > 0).
    pub eq18: Inequality,
    /// Eq. (19): K > −k (a0 > 0).
    pub eq19: Inequality,
    /// Eq. (20): b t_r (b + B + k t_r) + m (b + B − K t_r) > 0 (a2 a1 > a3 a0).
    pub eq20: Inequality,
    /// All three hold: the cubic (17) is Hurwitz.
    pub stable: bool,
}

/// Eq. (18)–(20) for a physical parameter set (Section VI).
pub fn routh_hurwitz(p: &Physical) -> RouthHurwitz {
    let (m, b, k) = (p.plant.mass, p.plant.damping, p.plant.stiffness);
    let (kw, bw) = (p.wall.stiffness, p.wall.damping);
    let tr = effective_delay(p);
    rh_from(m, b, k, kw, bw, tr)
}

/// Eq. (18)–(20) in normalized units (m = T = 1, t_r = d + ½, K → α, B → β, k → γ, b → δ)
/// (Section VI with Table I).
pub fn routh_hurwitz_normalized(n: &Normalized) -> RouthHurwitz {
    rh_from(1.0, n.delta, n.gamma, n.alpha, n.beta, n.d as f64 + 0.5)
}

fn rh_from(m: f64, b: f64, k: f64, kw: f64, bw: f64, tr: f64) -> RouthHurwitz {
    let eq18 = Inequality::new(b + bw, -k * tr);
    let eq19 = Inequality::new(kw, -k);
    let eq20 = Inequality::new(b * tr * (b + bw + k * tr) + m * (b + bw - kw * tr), 0.0);
    RouthHurwitz {
        eq18,
        eq19,
        eq20,
        stable: eq18.holds && eq19.holds && eq20.holds,
    }
}

/// The term ε = b t_r (b + B + k t_r)/m of eq. (21) that the linear condition (22) neglects.
pub fn epsilon(p: &Physical) -> f64 {
    let (m, b, k) = (p.plant.mass, p.plant.damping, p.plant.stiffness);
    let tr = effective_delay(p);
    b * tr * (b + p.wall.damping + k * tr) / m
}

/// The linear condition (22): the largest virtual stiffness K = (b + B)/(t_d + T/2) in N/m.
pub fn linear_stiffness_limit(p: &Physical) -> f64 {
    (p.plant.damping + p.wall.damping) / effective_delay(p)
}

/// The lower bound (19): K > −k, in N/m.
pub fn lower_stiffness_limit(p: &Physical) -> f64 {
    -p.plant.stiffness
}

/// The normalized linear condition (23): α_lin = (β + δ)/(d + 1/2), the upper end.
pub fn linear_alpha_limit(beta: f64, delta: f64, d: usize) -> f64 {
    (beta + delta) / (d as f64 + 0.5)
}

/// The normalized lower bound (19): α > −γ.
pub fn lower_alpha_limit(gamma: f64) -> f64 {
    -gamma
}

/// The linear conditions (19) and (22)/(23) for one parameter set.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LinearCheck {
    /// Lower bound of α from (19): −γ.
    pub alpha_lower: f64,
    /// Upper bound of α from (23): (β + δ)/(d + ½).
    pub alpha_upper: f64,
    /// −γ < α < (β + δ)/(d + ½).
    pub satisfied: bool,
}

/// Checks (19) and (23) for normalized parameters (Sections VI–VII).
pub fn linear_check(n: &Normalized) -> LinearCheck {
    let alpha_lower = lower_alpha_limit(n.gamma);
    let alpha_upper = linear_alpha_limit(n.beta, n.delta, n.d);
    LinearCheck {
        alpha_lower,
        alpha_upper,
        satisfied: alpha_lower < n.alpha && n.alpha < alpha_upper,
    }
}

/// The upper end of the exact stable α-interval at β (Section V, Fig. 5), from the
/// D-decomposition of [`crate::boundary::stable_stiffness_intervals`]: the interval that starts
/// on the left boundary α = −γ, or, for long delays where instability sets in before the
/// net stiffness γ + α reaches zero, the one that contains α = 0. None when neither exists.
pub fn exact_upper_alpha(fam: &NormalizedFamily, beta: f64) -> Option<f64> {
    let g = fam.gamma();
    let tol = 1e-12 * g.max(1e-300) + 1e-300;
    let ivs = stable_stiffness_intervals(fam, beta);
    ivs.iter()
        .find(|iv| iv.lo <= -g + tol && iv.hi > -g)
        .or_else(|| ivs.iter().find(|iv| iv.lo < 0.0 && iv.hi > 0.0))
        .map(|iv| iv.hi)
}

/// The relative error of eq. (24), |(α_lin − α)/(α + γ)|, at β: α on the exact upper
/// boundary ([`exact_upper_alpha`]) and α_lin from (23) (Section VII). None where no stable
/// interval starts at α = −γ.
pub fn relative_error(fam: &NormalizedFamily, beta: f64) -> Option<f64> {
    let a = exact_upper_alpha(fam, beta)?;
    let lin = linear_alpha_limit(beta, fam.delta(), fam.d);
    Some(((lin - a) / (a + fam.gamma())).abs())
}

/// A point of the exact boundary where the error (24) first reaches a level (Fig. 7).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ValidityPoint {
    /// The error level, e.g. 0.02.
    pub level: f64,
    /// α on the exact upper boundary at `beta`.
    pub alpha: f64,
    /// The smallest β > 0 at which the error (24) reaches `level`.
    pub beta: f64,
    /// α_lin of (23) at `beta`.
    pub alpha_linear: f64,
    /// The error (24) at `beta` (equals `level` up to the tolerance).
    pub error: f64,
    /// True when the error is at or above `level` already at the first sample β₀ > 0
    /// ([`VALIDITY_BETA_START`]): the linear condition never holds to this level.
    pub at_start: bool,
}

/// The linear condition of a loop with the paper's normalized view and where it stops
/// holding: the half-planes of (23) and (19) and the validity points of every error level
/// (Sections VI–VII, Fig. 7), with the wall's units to read them in N/m and Ns/m.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LinearCondition {
    /// γ of Table I.
    pub gamma: f64,
    /// δ of Table I.
    pub delta: f64,
    /// The delay d in samples.
    pub d: usize,
    /// 1/(d + 1/2): (23) is α < slope·β + intercept.
    pub slope: f64,
    /// δ/(d + 1/2).
    pub intercept: f64,
    /// (19): α > −γ.
    pub alpha_lower: f64,
    /// The validity point of each level, in the order given.
    pub points: Vec<ValidityPoint>,
    /// N/m per unit of α and Ns/m per unit of β: m/T² and m/T of the loop's plant (1 and 1
    /// for [`Loop::normalized`]).
    pub units: WallScale,
}

/// The linear condition in N/m and Ns/m (the wall of a loop given in physical units): with
/// α = KT²/m, β = BT/m, δ = bT/m, condition (23) α < (β + δ)/(d + 1/2) reads
/// K < (B + b)/(T(d + 1/2)) = `k_slope`·B + `k_intercept`, and (19) α > −γ reads
/// K > −k = `k_lower`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PhysicalLinear {
    /// 1/(T(d + 1/2)) in 1/s: N/m of K per Ns/m of B on the line (23).
    pub k_linear_slope: f64,
    /// b/(T(d + 1/2)) in N/m: the line (23) at B = 0.
    pub k_linear_intercept: f64,
    /// −k in N/m: the bound (19).
    pub k_lower: f64,
}

impl LinearCondition {
    /// The half-planes (23) and (19) in N/m and Ns/m ([`PhysicalLinear`]), read through
    /// `units`.
    pub fn physical(&self) -> PhysicalLinear {
        let (ku, bu) = (self.units.stiffness, self.units.damping);
        PhysicalLinear {
            k_linear_slope: self.slope * ku / bu,
            k_linear_intercept: self.intercept * ku,
            k_lower: self.alpha_lower * ku,
        }
    }

    /// K_lin of (23) in N/m at a validity point (its α_lin through `units`).
    pub fn k_linear(&self, p: &ValidityPoint) -> f64 {
        p.alpha_linear * self.units.stiffness
    }
}

/// [`LinearCondition`] of a loop: its (γ, δ, d) from [`Loop::paper_view`] and the
/// [`validity_points`] of the levels. A loop without the paper's normalized view (another
/// plant or estimator, an actuator lag, a fractional delay) is refused naming the loop.
pub fn linear_condition(lp: &Loop, levels: &[f64]) -> Result<LinearCondition> {
    let (Some(pp), PlantModel::MassSpringDamper(e)) = (lp.paper_view(), &lp.plant.model) else {
        return Err(Error::Invalid {
            param: Param::Loop,
            reason: "has no normalized view (the paper's loop: a mass-spring-damper, the \
                     backward difference, a whole-sample delay, no actuator lag): the linear \
                     condition (22) belongs to it"
                .into(),
        });
    };
    let d = lp.delay.samples;
    let tr = d as f64 + 0.5;
    let t = lp.period;
    Ok(LinearCondition {
        gamma: pp.gamma,
        delta: pp.delta,
        d,
        slope: 1.0 / tr,
        intercept: pp.delta / tr,
        alpha_lower: -pp.gamma,
        points: validity_points(pp, d, levels)?,
        units: WallScale {
            stiffness: e.mass / (t * t),
            damping: e.mass / t,
        },
    })
}

/// First β of the scan for the validity points: the scan starts at β₀ = 1e-7 (β = 0⁺).
pub const VALIDITY_BETA_START: f64 = 1e-7;
/// Ratio of the geometric β scan that brackets a level before bisection (the fallback).
const SCAN_RATIO: f64 = 1.01;
/// Ratio of the coarse geometric β check below an exact crossing: the error (24) must stay
/// below the level there, else the upper boundary jumps and the scan decides (a quarter step
/// resolves the slow, roughly linear growth of the error many times over).
const CHECK_RATIO: f64 = 1.25;
/// Relative tolerance on β of the bisection (well below the required 1e-9).
const BETA_TOL: f64 = 1e-13;
/// Relative agreement of the error (24) with the level at a validity point: a crossing of
/// the level line is on the upper boundary when its error meets the level to this (the
/// crossings are exact to rounding; a crossing with another branch misses by far more).
const LEVEL_MATCH: f64 = 1e-6;

/// The β and α at which the relative error (24) first reaches each level, going up from
/// β = 0⁺ (Section VII, Fig. 7 circles and squares).
///
/// Exact: with α + γ > 0 the error equals the level L on the two lines
/// α = (α_lin(β) ∓ Lγ)/(1 ± L) of the (α, β)-plane (α below or above α_lin of (23)), so the
/// points are the D-decomposition crossings of these lines ([`line_crossings`]): the first
/// one with β > β₀ = [`VALIDITY_BETA_START`] whose α is the exact upper boundary
/// ([`exact_upper_alpha`]). A coarse geometric check below it confirms that the error stays
/// under the level (no jump of the upper boundary); otherwise, or without such a crossing,
/// the error is scanned on the grid β₀·1.01ᵏ and bisected to 1e-13 relative. Where the
/// stable interval at −γ ends the error counts as infinite. Levels must be finite and > 0.
pub fn validity_points(pp: PlantParams, d: usize, levels: &[f64]) -> Result<Vec<ValidityPoint>> {
    check_delay(d)?;
    for &l in levels {
        finite(Param::Level, l)?;
        if l <= 0.0 {
            return Err(Error::NotPositive {
                param: Param::Level,
                value: l,
            });
        }
    }
    let fam = NormalizedFamily::new(pp, d)?;
    // The region ends where the closed-form z = −1 bound and the Schur bound |β| < 1/|n0|
    // make it; stop the scan well beyond (no stable region at β ≥ 1/|n0|: |p(0)| = |n0 β|).
    let beta_cap = if fam.numerator_constant().abs() > 0.0 {
        1.0 / fam.numerator_constant().abs()
    } else {
        f64::INFINITY
    };
    let mut out = Vec::with_capacity(levels.len());
    for &level in levels {
        let b0 = VALIDITY_BETA_START;
        if error_at(&fam, b0) >= level {
            out.push(point(&fam, level, b0, true));
            continue;
        }
        let p = match exact_crossing(&fam, level, beta_cap) {
            Some(p) => p,
            None => scanned_point(&fam, level, beta_cap)?,
        };
        out.push(p);
    }
    Ok(out)
}

/// The error (24) at β, infinite where no stable interval starts at α = −γ.
fn error_at(fam: &NormalizedFamily, beta: f64) -> f64 {
    relative_error(fam, beta).unwrap_or(f64::INFINITY)
}

/// The lines of the (α, β)-plane on which the error (24) equals `level` (with α + γ > 0),
/// parameterized by β: α − α_lin = ∓L(α + γ) gives α = (α_lin(β) ∓ Lγ)/(1 ± L).
fn level_lines(fam: &NormalizedFamily, level: f64) -> Vec<WallLine> {
    let c = fam.d as f64 + 0.5;
    let (g, delta) = (fam.gamma(), fam.delta());
    [1.0, -1.0]
        .into_iter()
        .filter(|s| 1.0 + s * level > 0.0)
        .map(|s| {
            let q = 1.0 + s * level;
            WallLine {
                from: WallPoint {
                    a: (delta / c - s * level * g) / q,
                    b: 0.0,
                },
                dir: WallPoint {
                    a: 1.0 / (c * q),
                    b: 1.0,
                },
            }
        })
        .collect()
}

/// The validity point from the exact crossings of the level lines, if the first one on the
/// upper boundary is confirmed by the coarse check below it.
fn exact_crossing(fam: &NormalizedFamily, level: f64, beta_cap: f64) -> Option<ValidityPoint> {
    let b0 = VALIDITY_BETA_START;
    let mut betas: Vec<f64> = level_lines(fam, level)
        .iter()
        .flat_map(|l| line_crossings(fam, l))
        .map(|c| c.t)
        .filter(|&t| t > b0 && t < beta_cap * 1.01)
        .collect();
    betas.sort_by(f64::total_cmp);
    let p = betas
        .into_iter()
        .map(|b| point(fam, level, b, false))
        .find(|p| (p.error - level).abs() <= LEVEL_MATCH * level)?;
    let mut b = b0;
    while b < p.beta {
        if error_at(fam, b) >= level {
            return None;
        }
        b *= CHECK_RATIO;
    }
    Some(p)
}

/// The validity point by the geometric scan and bisection (see [`validity_points`]).
fn scanned_point(fam: &NormalizedFamily, level: f64, beta_cap: f64) -> Result<ValidityPoint> {
    let err = |b: f64| error_at(fam, b);
    let mut lo = VALIDITY_BETA_START;
    let mut hi = lo;
    let mut found = false;
    while hi < beta_cap * 1.01 {
        hi = lo * SCAN_RATIO;
        if err(hi) >= level {
            found = true;
            break;
        }
        lo = hi;
    }
    if !found {
        return Err(Error::Numerical(format!(
            "relative error (24) never reaches {level} below beta = {beta_cap}"
        )));
    }
    while hi - lo > BETA_TOL * hi {
        let m = 0.5 * (lo + hi);
        if m <= lo || m >= hi {
            break;
        }
        if err(m) >= level {
            hi = m;
        } else {
            lo = m;
        }
    }
    // The last point below the level, where α is finite and on the boundary; at the
    // tolerance both ends agree to 1e-13 relative.
    let p = point(fam, level, lo, false);
    let miss = (p.error - level).abs();
    if miss.is_nan() || miss > LEVEL_MATCH * level {
        return Err(Error::Numerical(format!(
            "relative error (24) jumps across {level} at beta = {lo} (the stable interval at -gamma ends there)"
        )));
    }
    Ok(p)
}

fn point(fam: &NormalizedFamily, level: f64, beta: f64, at_start: bool) -> ValidityPoint {
    let alpha = exact_upper_alpha(fam, beta).unwrap_or(f64::NAN);
    let alpha_linear = linear_alpha_limit(beta, fam.delta(), fam.d);
    ValidityPoint {
        level,
        alpha,
        beta,
        alpha_linear,
        error: ((alpha_linear - alpha) / (alpha + fam.gamma())).abs(),
        at_start,
    }
}

/// One sample of the error curve (24) as a function of β (Section VII).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ErrorSample {
    /// β.
    pub beta: f64,
    /// Exact upper α (None outside the stable region).
    pub alpha: Option<f64>,
    /// α_lin of (23).
    pub alpha_linear: f64,
    /// The error (24) (None outside the stable region).
    pub error: Option<f64>,
}

/// The error (24) sampled at the given β values (Section VII).
pub fn error_curve(pp: PlantParams, d: usize, betas: &[f64]) -> Result<Vec<ErrorSample>> {
    let fam = NormalizedFamily::new(pp, d)?;
    betas
        .iter()
        .map(|&b| {
            finite(Param::Beta, b)?;
            let alpha = exact_upper_alpha(&fam, b);
            let alpha_linear = linear_alpha_limit(b, pp.delta, d);
            Ok(ErrorSample {
                beta: b,
                alpha,
                alpha_linear,
                error: alpha.map(|a| ((alpha_linear - a) / (a + pp.gamma)).abs()),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::{Effective, Sampling, Wall};

    /// The exact crossings of the level lines and the 1 %-scan with bisection are
    /// independent ways to the same validity points.
    #[test]
    fn validity_crossings_agree_with_the_scan() {
        for (gamma, delta, d) in [
            (0.0, 0.0, 0),
            (0.001, 0.01, 0),
            (0.0, 0.015, 1),
            (0.001, 0.005, 2),
        ] {
            let fam = NormalizedFamily::new(PlantParams::new(gamma, delta).unwrap(), d).unwrap();
            let cap = 1.0 / fam.numerator_constant().abs();
            for level in [0.02, 0.05, 0.2] {
                let exact = exact_crossing(&fam, level, cap).expect("a crossing");
                let scan = scanned_point(&fam, level, cap).unwrap();
                let rel = (exact.beta - scan.beta).abs() / scan.beta;
                assert!(
                    rel < 1e-10,
                    "γ={gamma} δ={delta} d={d} L={level}: {exact:?} {scan:?}"
                );
                assert!((exact.alpha - scan.alpha).abs() < 1e-10 * scan.alpha);
            }
        }
    }

    #[test]
    fn cubic_scales_to_normalized() {
        let (m, t) = (1.3, 1e-3);
        let n = Normalized::new(0.02, 0.3, 1e-3, 0.01, 2).unwrap();
        let p = n.to_physical(m, t).unwrap();
        let c = continuous_cubic(&p);
        let cn = continuous_cubic_normalized(&n);
        // s = s'/T, multiplied by T²/m
        let k = t * t / m;
        let rel = |a: f64, b: f64| ((a - b) / b).abs();
        assert!(rel(c.a3 * k / t.powi(3), cn.a3) < 1e-12);
        assert!(rel(c.a2 * k / t.powi(2), cn.a2) < 1e-12);
        assert!(rel(c.a1 * k / t, cn.a1) < 1e-12);
        assert!(rel(c.a0 * k, cn.a0) < 1e-12);
    }

    #[test]
    fn rh_eq20_is_hurwitz_determinant() {
        let p = Physical::new(
            Effective::new(1.1, 7.5, 350.0).unwrap(),
            Wall {
                stiffness: 2e4,
                damping: 10.0,
            },
            Sampling::new(1e-3, 1).unwrap(),
        )
        .unwrap();
        let c = continuous_cubic(&p);
        let rh = routh_hurwitz(&p);
        let det = c.a2 * c.a1 - c.a3 * c.a0;
        assert!((rh.eq20.margin - det).abs() < 1e-9 * det.abs());
        assert!((rh.eq18.margin - c.a1).abs() < 1e-12 * c.a1);
        assert!((rh.eq19.margin - c.a0).abs() < 1e-9);
        // ε of (21) closes the gap between (20)/m and (22)
        let lhs = p.plant.damping + p.wall.damping + epsilon(&p);
        assert!((lhs - p.wall.stiffness * effective_delay(&p) - rh.eq20.margin / 1.1).abs() < 1e-9);
    }
}
