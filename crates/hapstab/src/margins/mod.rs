//! Stability margins of a virtual wall on any loop: how far the wall is from the stability
//! boundary of Section V, measured as a factor on K, a factor on (K, B), a phase and an extra
//! delay, and the frequency at which the loop would oscillate.
//!
//! All margins are computed on the exact discrete loop ([`crate::zoh`]), so they hold for the
//! sampled system, not for a continuous approximation of it:
//!
//! - **gain margin** on K at the given B: the factor g with (gK, B) on the boundary, from the
//!   D-decomposition crossings of the stiffness axis ([`crate::boundary::line_crossings`]);
//! - **gain margin on (K, B)**: the factor on both, along the ray through the wall;
//! - **phase margin**: 180° + arg L at the gain crossover |L(e^{jθ})| = 1 of the open loop
//!   L = (K·PK + B·PB)/P0 (the loop's characteristic equation is 1 + L = 0, eq. 7–9);
//! - **delay margin**: the extra delay (fractional, in seconds) that makes the loop unstable,
//!   by a scan over the added delay with the exact fractional-delay discretization and the
//!   Schur–Cohn test (see [`delay_margin`] for the guarantee of the first crossing);
//! - **critical frequency**: the angle θ of the root pair e^{±jθ} on the unit circle at the
//!   gain-margin boundary, as f = θ/(2πT).
//!
//! Margins are defined for stable walls only; for a wall that is not stable every margin is
//! absent.

use num_complex::Complex64;
use serde::Serialize;

use crate::boundary::{AlphaBeta, WallLine, line_crossings, stable_between};
use crate::closed_loop::AffineFamily;
use crate::error::Result;
use crate::model::{Delay, Loop};
use crate::params::{MAX_DELAY, Wall};
use crate::stability::roots;
use crate::verdict::stable as verdict_stable;

/// A margin as a factor, and where the boundary is met.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GainMargin {
    /// The factor (> 1) that puts the wall on the boundary.
    pub factor: f64,
    /// Angle θ ∈ [0, π] of the root on the unit circle there.
    pub theta: f64,
    /// θ/(2πT) in Hz.
    pub frequency_hz: f64,
}

/// The phase margin at the most critical gain crossover.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PhaseMargin {
    /// 180° + arg L(e^{jθ}) in degrees, in (−180, 180].
    pub degrees: f64,
    /// The crossover angle θ.
    pub theta: f64,
    /// θ/(2πT) in Hz.
    pub frequency_hz: f64,
}

/// The delay margin and the oscillation that sets in there.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DelayMargin {
    /// The extra delay in seconds that brings the loop to the boundary.
    pub seconds: f64,
    /// The angle of the root pair on the unit circle at that delay.
    pub theta: f64,
    /// θ/(2πT) in Hz.
    pub frequency_hz: f64,
}

/// The margins of one wall. Each is None when the wall is not stable, or when no finite
/// margin exists (see `notes`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Margins {
    /// True iff the wall is stable (Schur–Cohn); otherwise no margin is given.
    pub stable: bool,
    /// Factor on K at the given B.
    pub gain: Option<GainMargin>,
    /// Factor on K and B together.
    pub gain_kb: Option<GainMargin>,
    /// Phase margin.
    pub phase: Option<PhaseMargin>,
    /// Delay margin.
    pub delay: Option<DelayMargin>,
    /// When the delay scan stopped at its work bound before a crossing: the added delay in
    /// seconds up to which the loop was shown stable (the margin is at least this).
    pub delay_at_least: Option<f64>,
    /// Frequency of the critical root pair at the gain-margin boundary, Hz.
    pub critical_frequency_hz: Option<f64>,
    /// Why a margin is absent, in words.
    pub notes: Vec<String>,
}

/// Computes every margin of a physical wall on a loop (module doc).
pub fn margins(lp: &Loop, wall: Wall) -> Result<Margins> {
    let fam = AffineFamily::of_loop(lp)?;
    let (a, b) = fam.to_units(wall.stiffness, wall.damping);
    let p = AlphaBeta { alpha: a, beta: b };
    let mut out = Margins {
        stable: verdict_stable(&fam, a, b, &mut fam.coefficients(a, b)),
        gain: None,
        gain_kb: None,
        phase: None,
        delay: None,
        delay_at_least: None,
        critical_frequency_hz: None,
        notes: Vec::new(),
    };
    if !out.stable {
        out.notes
            .push("the wall is not stable: margins are defined for stable walls".into());
        return Ok(out);
    }
    let hz = |theta: f64| theta / (2.0 * std::f64::consts::PI * lp.period);
    out.gain = gain_margin(&fam, p, hz);
    if out.gain.is_none() {
        out.notes.push(if a == 0.0 {
            "K = 0: no factor on K changes the wall".into()
        } else {
            "no factor on K makes the wall unstable (gain margin unbounded)".into()
        });
    }
    out.critical_frequency_hz = out.gain.map(|g| g.frequency_hz);
    out.gain_kb = gain_margin_kb(&fam, p, hz);
    if out.gain_kb.is_none() {
        out.notes
            .push("no factor on (K, B) makes the wall unstable (unbounded)".into());
    }
    out.phase = phase_margin(&fam, p, hz);
    if out.phase.is_none() {
        out.notes
            .push("|L| never crosses 1: no gain crossover, phase margin unbounded".into());
    }
    match delay_margin(lp, wall)? {
        DelayScan::Crossing(d) => out.delay = Some(d),
        DelayScan::SmallGain(gain) => out.notes.push(format!(
            "stable for every added delay: |L| ≤ {gain:.4} < 1 at every frequency and every \
             fraction of a sample (small gain)"
        )),
        DelayScan::StableUpToMax => out.notes.push(format!(
            "stable for every added delay up to the largest modelled delay ({MAX_DELAY} samples)"
        )),
        DelayScan::AtLeast(seconds) => {
            out.delay_at_least = Some(seconds);
            out.notes.push(format!(
                "delay margin undecided beyond {seconds:.6e} s: the scan stopped at its work \
                 bound without a crossing (the margin is at least that)"
            ));
        }
    }
    Ok(out)
}

/// Why every margin is withheld beside a verdict that is not stable.
pub const NOT_STABLE_NOTE: &str = "the wall is not stable: margins are defined for stable walls";

/// Why every margin is withheld when the verdict says stable but the margins' own
/// Schur–Cohn test does not: the wall sits on the boundary to rounding.
pub const UNDECIDED_NOTE: &str = "undecided: the wall lies on the stability boundary to rounding";

/// The margins reported beside a stability verdict (what `check` and the Python package
/// print): none, with the reason in `notes`, when the verdict is not stable or when the
/// margins' own Schur–Cohn test disagrees with it (a wall on the boundary to rounding);
/// otherwise [`margins`]. `stable` is the verdict's.
pub fn margins_beside_verdict(lp: &Loop, wall: Wall, verdict_stable: bool) -> Result<Margins> {
    let withheld = |note: &str| Margins {
        stable: verdict_stable,
        gain: None,
        gain_kb: None,
        phase: None,
        delay: None,
        delay_at_least: None,
        critical_frequency_hz: None,
        notes: vec![note.to_string()],
    };
    if !verdict_stable {
        return Ok(withheld(NOT_STABLE_NOTE));
    }
    let m = margins(lp, wall)?;
    if !m.stable {
        return Ok(withheld(UNDECIDED_NOTE));
    }
    Ok(m)
}

/// The factor on the stiffness at fixed damping that reaches the stability boundary: the end
/// of the exact stable interval of K (Section V) on the side away from K = 0, divided by K.
/// None when K = 0 or when the interval is unbounded on that side.
pub fn gain_margin(
    fam: &AffineFamily,
    wall: AlphaBeta,
    hz: impl Fn(f64) -> f64,
) -> Option<GainMargin> {
    if wall.alpha == 0.0 {
        return None;
    }
    let line = WallLine::stiffness_axis(wall.beta);
    factor_to_boundary(fam, &line, wall.alpha, hz).map(|(end, theta, f)| GainMargin {
        factor: end / wall.alpha,
        theta,
        frequency_hz: f,
    })
}

/// The factor on (K, B) together that reaches the stability boundary along the ray from the
/// origin through the wall. None when the ray never leaves the stable region.
pub fn gain_margin_kb(
    fam: &AffineFamily,
    wall: AlphaBeta,
    hz: impl Fn(f64) -> f64,
) -> Option<GainMargin> {
    if wall.alpha == 0.0 && wall.beta == 0.0 {
        return None;
    }
    let line = WallLine::ray(wall);
    factor_to_boundary(fam, &line, 1.0, hz).map(|(end, theta, f)| GainMargin {
        factor: end,
        theta,
        frequency_hz: f,
    })
}

/// The end of the stable interval containing t0 on the side away from t = 0, with the angle of
/// the root on the circle there.
fn factor_to_boundary(
    fam: &AffineFamily,
    line: &WallLine,
    t0: f64,
    hz: impl Fn(f64) -> f64,
) -> Option<(f64, f64, f64)> {
    let crossings = line_crossings(fam, line);
    let ivs = stable_between(fam, line, &crossings);
    let iv = ivs.iter().find(|iv| iv.lo < t0 && t0 < iv.hi)?;
    let end = if t0 > 0.0 { iv.hi } else { iv.lo };
    if !end.is_finite() {
        return None;
    }
    let theta = crossings.iter().find(|c| c.t == end)?.theta;
    Some((end, theta, hz(theta)))
}

/// θ samples per degree of p for the crossover scan, as for the boundary crossings: |L| − 1
/// changes sign at most a few times per turn of the phase of p.
const SAMPLES_PER_DEGREE: usize = 256;

/// The phase margin of the open loop L = (a·PK + b·PB)/P0: at every gain crossover
/// |L(e^{jθ})| = 1, θ ∈ (0, π), the angle 180° + arg L wrapped to (−180°, 180°]; the smallest
/// over the crossovers. Crossovers are bracketed on a θ grid and refined by bisection.
/// None when |L| never crosses 1.
pub fn phase_margin(
    fam: &AffineFamily,
    wall: AlphaBeta,
    hz: impl Fn(f64) -> f64,
) -> Option<PhaseMargin> {
    let g = |theta: f64| {
        let (p0, pk, pb) = fam.parts_on_circle(theta);
        let w = pk * wall.alpha + pb * wall.beta;
        (w.norm_sqr() - p0.norm_sqr(), w / p0)
    };
    let m = SAMPLES_PER_DEGREE * (fam.degree() + 1);
    let pi = std::f64::consts::PI;
    let at = |i: usize| pi * (i as f64 / m as f64).clamp(1e-12, 1.0 - 1e-12);
    let mut best: Option<PhaseMargin> = None;
    let mut prev = (at(0), g(at(0)).0);
    for i in 1..=m {
        let t = at(i);
        let v = g(t).0;
        if (v > 0.0) != (prev.1 > 0.0) {
            let tc = crate::boundary::bisect(prev.0, t, |x| g(x).0);
            let l = g(tc).1;
            let deg = wrap_degrees(180.0 + l.arg().to_degrees());
            if best.is_none_or(|b| deg < b.degrees) {
                best = Some(PhaseMargin {
                    degrees: deg,
                    theta: tc,
                    frequency_hz: hz(tc),
                });
            }
        }
        prev = (t, v);
    }
    best
}

fn wrap_degrees(d: f64) -> f64 {
    let w = d.rem_euclid(360.0);
    if w > 180.0 { w - 360.0 } else { w }
}

/// Safety factor κ of the delay scan's step: the step is 1/κ of the delay the Nyquist curve
/// needs to reach −1 at the pure-delay rate (see [`delay_margin`]); κ = 4 covers the
/// fractional hold's aliased terms, which can turn the phase faster than a pure delay near
/// the Nyquist frequency.
const DELAY_STEP_SAFETY: f64 = 4.0;

/// Smallest step of the delay scan, in samples: near the crossing the controlled step shrinks
/// geometrically, so a floor lets the scan step over the crossing; an instability window
/// narrower than this (1 ns at 1 kHz) could be missed.
const DELAY_MIN_STEP: f64 = 1e-6;

/// Bisection of the added delay stops at this relative width: far below the margins' 1e-6
/// acceptance.
const DELAY_BISECTION_REL: f64 = 1e-13;

/// The delay margin: the smallest extra delay Δ (seconds, any fraction of a sample) at which
/// the loop loses stability, with the frequency of the root pair that crosses.
///
/// Method: scan the total delay s (in samples) upward from the loop's own, testing every step
/// with the Schur–Cohn test on the exact fractional-delay discretization, then bisect the
/// first stable/unstable pair. **First crossing**: a root can reach the unit circle at e^{jθ}
/// only where the Nyquist curve 1 + L reaches 0. An added delay h turns L by e^{−jθh}, which
/// moves 1 + L by at most θh·|L|; so no root reaches the circle while
/// h < min_θ |1 + L|/(θ|L|) = min_θ |p(e^{jθ})|/(θ·|a·PK + b·PB|) (P0 cancels). Each step is
/// that bound divided by [`DELAY_STEP_SAFETY`] (the fractional hold's deviation from a pure
/// phase), at least [`DELAY_MIN_STEP`]; the minimum over θ is taken on the boundary scan's
/// grid. None when the loop stays stable up to the largest modelled delay ([`MAX_DELAY`]
/// samples).
pub fn delay_margin(lp: &Loop, wall: Wall) -> Result<DelayScan> {
    let s0 = lp.delay.in_samples();
    let family_at = |s: f64| -> Result<AffineFamily> {
        AffineFamily::of_loop(&lp.with_delay(delay_in_samples(s))?)
    };
    let base = family_at(s0)?;
    let (a, b) = base.to_units(wall.stiffness, wall.damping);
    let gain = max_loop_gain(lp, a, b)?;
    if gain < SMALL_GAIN_LIMIT {
        return Ok(DelayScan::SmallGain(gain));
    }
    let stable = |f: &AffineFamily| verdict_stable(f, a, b, &mut f.coefficients(a, b));
    let mut s = s0;
    let mut fam = base;
    let mut work = 0.0;
    loop {
        work += scan_step_work(&fam);
        if work > DELAY_SCAN_WORK {
            return Ok(DelayScan::AtLeast((s - s0) * lp.period));
        }
        let h = (robustness(&fam, a, b) / DELAY_STEP_SAFETY).max(DELAY_MIN_STEP);
        let next = s + h;
        if next > MAX_DELAY as f64 {
            return Ok(DelayScan::StableUpToMax);
        }
        let fam_next = family_at(next)?;
        if !stable(&fam_next) {
            let (lo, hi) = bisect_delay(s, next, |x| Ok(stable(&family_at(x)?)))?;
            let theta = critical_angle(&family_at(hi)?, a, b)?;
            let seconds = (0.5 * (lo + hi) - s0) * lp.period;
            return Ok(DelayScan::Crossing(DelayMargin {
                seconds,
                theta,
                frequency_hz: theta / (2.0 * std::f64::consts::PI * lp.period),
            }));
        }
        s = next;
        fam = fam_next;
    }
}

/// What the delay scan found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DelayScan {
    /// The first crossing: the margin.
    Crossing(DelayMargin),
    /// max |L| over every frequency and fraction of a sample, below 1: stable for every
    /// added delay.
    SmallGain(f64),
    /// No crossing up to the largest modelled delay.
    StableUpToMax,
    /// The scan's work bound was reached after this added delay in seconds, stable so far.
    AtLeast(f64),
}

/// The loop gain may not exceed this for the small-gain shortcut. Each λ's maximum over θ
/// is refined to 1e-9 rad (so the value is exact to rounding); between the 64 fractions of a
/// sample |L| moves by far less than the 0.1 % left (a fraction of a sample turns L's phase,
/// its magnitude only through the hold's aliased terms).
const SMALL_GAIN_LIMIT: f64 = 0.999;

/// Fractions of a sample on which the loop gain is evaluated for the small-gain shortcut.
const GAIN_FRACTIONS: usize = 64;

/// Local maxima of |L| on the θ grid above this are refined (lower ones cannot reach
/// [`SMALL_GAIN_LIMIT`] between two grid points).
const GAIN_REFINE_FLOOR: f64 = 0.5;

/// The delay scan's work bound in evaluations of p's coefficients (estimated at about 0.3 s
/// on one core): past it the scan reports a lower bound instead of running on with p's
/// growing degree.
const DELAY_SCAN_WORK: f64 = 3e8;

/// Work of one scan step: the robustness bound's θ grid times p's degree.
fn scan_step_work(fam: &AffineFamily) -> f64 {
    let n = (fam.degree() + 1) as f64;
    SAMPLES_PER_DEGREE as f64 * n * n
}

/// max over θ ∈ (0, π] and over fractions λ ∈ [0, 1] of a sample of |L(e^{jθ})| with
/// L = (a·PK + b·PB)/P0 of the loop with delay λ: a whole sample more of delay multiplies L
/// by e^{−jθ}, so this is the loop gain at every added delay.
fn max_loop_gain(lp: &Loop, a: f64, b: f64) -> Result<f64> {
    let mut gain: f64 = 0.0;
    for j in 0..=GAIN_FRACTIONS {
        let fraction = (j as f64 / GAIN_FRACTIONS as f64).min(1.0 - 1e-12);
        let fam = AffineFamily::of_loop(&lp.with_delay(Delay {
            samples: 0,
            fraction,
        })?)?;
        let l = |t: f64| {
            let (p0, pk, pb) = fam.parts_on_circle(t);
            (pk * a + pb * b).norm() / p0.norm()
        };
        let m = SAMPLES_PER_DEGREE * (fam.degree() + 1);
        let ts: Vec<f64> = (0..=m)
            .map(|i| std::f64::consts::PI * (i as f64 / m as f64).clamp(1e-12, 1.0))
            .collect();
        let ls: Vec<f64> = ts.iter().map(|&t| l(t)).collect();
        for i in 0..=m {
            let left = if i > 0 { ls[i - 1] } else { f64::NEG_INFINITY };
            let right = ls.get(i + 1).copied().unwrap_or(f64::NEG_INFINITY);
            gain = gain.max(ls[i]);
            if ls[i] >= left && ls[i] >= right && ls[i] > GAIN_REFINE_FLOOR {
                let (lo, hi) = (ts[i.saturating_sub(1)], ts[(i + 1).min(m)]);
                let (_, v) = crate::passivity::golden_max(l, lo, hi, crate::passivity::THETA_TOL);
                gain = gain.max(v);
            }
        }
    }
    Ok(gain)
}

/// A total delay of s samples as whole samples and a fraction.
fn delay_in_samples(s: f64) -> Delay {
    let d = s.floor();
    Delay {
        samples: d as usize,
        fraction: s - d,
    }
}

/// min over θ ∈ (0, π] of |p(e^{jθ})|/(θ·|a·PK + b·PB|): the added delay (in samples) that
/// the pure-delay bound guarantees safe.
fn robustness(fam: &AffineFamily, a: f64, b: f64) -> f64 {
    let m = SAMPLES_PER_DEGREE * (fam.degree() + 1);
    let pi = std::f64::consts::PI;
    (1..=m)
        .map(|i| {
            let t = pi * i as f64 / m as f64;
            let (p0, pk, pb) = fam.parts_on_circle(t);
            let w = pk * a + pb * b;
            (p0 + w).norm() / (t * w.norm())
        })
        .fold(f64::INFINITY, f64::min)
}

/// Bisects [lo, hi] (stable at lo, not at hi) down to [`DELAY_BISECTION_REL`].
fn bisect_delay(
    mut lo: f64,
    mut hi: f64,
    stable: impl Fn(f64) -> Result<bool>,
) -> Result<(f64, f64)> {
    while hi - lo > DELAY_BISECTION_REL * hi.max(1.0) {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if stable(mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok((lo, hi))
}

/// The angle of the root closest to the unit circle (the pair that just crossed).
fn critical_angle(fam: &AffineFamily, a: f64, b: f64) -> Result<f64> {
    let rs = roots(&fam.coefficients(a, b))?;
    let z = rs
        .iter()
        .min_by(|x, y| (x.norm() - 1.0).abs().total_cmp(&(y.norm() - 1.0).abs()))
        .copied()
        .unwrap_or(Complex64::new(1.0, 0.0));
    Ok(z.arg().abs())
}
