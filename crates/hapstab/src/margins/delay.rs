//! The delay margin: the smallest added delay h ≥ 0 (any fraction of a sample) at which a root
//! of p(z) reaches the unit circle, exact at any delay.
//!
//! A root reaches e^{iθ} at total delay s (samples) iff L_s(e^{iθ}) = −1 (p = P0·(1 + L),
//! eq. 7–9). A whole sample more
//! multiplies L by e^{−iθ}, so L_s = L_λ·e^{−iwθ} with w = ⌊s⌋ and L_λ the loop at the
//! fraction λ = s − w alone: the condition is |L_λ(θ)| = 1 (θ a gain crossover of the
//! fraction's loop) and arg L_λ(θ) − wθ ≡ −π. Every fraction's loop comes from one table
//! ([`super::fraction`]), which also bounds |L_λ| over every fraction: below 1 at every
//! frequency, no added delay destabilizes the wall (small gain). Otherwise the seeds are the
//! pure-delay estimates λ + (PM + 2πk)/θ at the crossovers of [`super::fraction::FRACTIONS`] fractions; the
//! seeds of one crossing cluster, so each cluster is solved once, exactly, by Newton's method
//! in (s, θ) on L_λ(θ)e^{−iwθ} + 1 = 0. The smallest solution is confirmed by the verdict
//! (on p at that delay from the same parts): not stable at h·(1 + [`CONFIRM_REL`]), not
//! unstable just before, at the nearest wall the Schur–Cohn recursion decides surely — and
//! reported. Where no seed converges
//! and confirms, the certified scan of [`delay_scan`] decides.

use num_complex::Complex64;

use super::fraction::{FractionCrossover, FractionLoop, FractionTable};
use super::frequency::{GainScan, frequency_grid, gain_scan};
use super::{DelayMargin, SAMPLES_PER_DEGREE};
use crate::closed_loop::AffineFamily;
use crate::error::Result;
use crate::model::{Delay, Loop};
use crate::params::{MAX_DELAY, Wall};
use crate::stability::roots;
use crate::verdict::{Verdict, decide, decide_fast, stable as verdict_stable};

/// The confirmed delay margin puts the wall stable at h·(1 − CONFIRM_REL) and not stable at
/// h·(1 + CONFIRM_REL).
pub const CONFIRM_REL: f64 = 1e-6;

/// The stable side of the confirmation moves back by a factor of 10 at most this many times
/// (to 1e-3 of the added delay) to a wall the Schur–Cohn step decides surely.
const CONFIRM_WIDENINGS: i32 = 3;

/// Seeds this many samples beyond the largest modelled delay are not solved: the loop is
/// stable up to that delay.
const BEYOND_MAX: f64 = 2.0;

/// Seeds further than this many samples above the best solution so far are not solved.
const SEED_REACH: f64 = 1.0;

/// A seed within this many samples (and [`CLUSTER_THETA_REL`] in θ) of a seed already solved
/// to a solution belongs to the same crossing.
const CLUSTER_SAMPLES: f64 = 0.25;

/// Relative width in θ of a cluster of seeds.
const CLUSTER_THETA_REL: f64 = 0.1;

/// Newton steps of the exact solve.
const NEWTON_STEPS: usize = 60;

/// Relative step of the θ-derivative's central difference in the exact solve.
const THETA_DIFF_REL: f64 = 1e-7;

/// At most this many seeds are solved.
const MAX_SOLVES: usize = 64;

/// The loop gain may not exceed this for the small-gain shortcut: the bound of max |L| over
/// every frequency and fraction ([`super::fraction`]).
const SMALL_GAIN_LIMIT: f64 = 0.999;

/// What the delay margin's search found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DelayScan {
    /// The first crossing: the margin.
    Crossing(DelayMargin),
    /// A bound of max |L| over every frequency and fraction of a sample, below 1: stable for
    /// every added delay.
    SmallGain(f64),
    /// No crossing up to the largest modelled delay.
    StableUpToMax,
    /// The scan's work bound was reached after this added delay in seconds, stable so far.
    AtLeast(f64),
}

/// The delay margin of a wall on a loop (module doc), with the MATLAB-style figure
/// min PM/ω_c over the gain crossovers of the loop as it is (seconds; None without a
/// crossover).
pub fn delay_margin(lp: &Loop, wall: Wall) -> Result<(DelayScan, Option<f64>)> {
    let dl = lp.discretize()?;
    let base = AffineFamily::new(&dl);
    let (a, b) = base.to_units(wall.stiffness, wall.damping);
    let modes = frequency_grid(&base, a, b);
    let pm = pm_over_wc(&gain_scan(&base, a, b), lp.period);
    let fl = FractionLoop::new(lp, &dl, a, b, &modes)?;
    Ok((delay_margin_with(lp, wall, &fl)?, pm))
}

/// The MATLAB-style figure min PM/ω_c over the gain crossovers of a gain scan, in seconds
/// for the period T (None without a crossover): the added delay that would bring L to −1 if
/// a delay only turned its phase.
pub fn pm_over_wc(own: &GainScan, period: f64) -> Option<f64> {
    own.crossovers
        .iter()
        .map(|c| positive_phase(c.phase_margin_deg.to_radians()) / c.theta)
        .reduce(f64::min)
        .map(|h| h * period)
}

/// [`delay_margin`] on the wall's [`FractionLoop`] `fl` (its grid joined with the loop's
/// [`frequency_grid`]), as the margins build it beside their own grid.
pub fn delay_margin_with(lp: &Loop, wall: Wall, fl: &FractionLoop) -> Result<DelayScan> {
    let s0 = lp.delay.in_samples();
    let table = FractionTable::new(fl);
    let peak = table.peak_bound();
    if peak < SMALL_GAIN_LIMIT {
        return Ok(DelayScan::SmallGain(peak));
    }
    let seeds = seeds(s0, &table.crossovers());
    // A root can reach the circle only at a gain crossover of some fraction's loop; when
    // there is none, or the nearest phase alignment lies samples beyond the largest modelled
    // delay (the fraction moves a seed by well under a sample), no modelled delay is unstable.
    if seeds
        .first()
        .is_none_or(|s| s.0 > MAX_DELAY as f64 + BEYOND_MAX)
    {
        return Ok(DelayScan::StableUpToMax);
    }
    if let Some((s, theta)) = smallest_solution(fl, s0, seeds)
        && confirmed(fl, s0, s)
    {
        return Ok(DelayScan::Crossing(DelayMargin {
            seconds: (s - s0) * lp.period,
            theta,
            frequency_hz: theta / (2.0 * std::f64::consts::PI * lp.period),
        }));
    }
    delay_scan(lp, wall)
}

/// The smallest solution s > s0 of the exact solve over the seeds (in increasing delay):
/// each seed's solution lies within a sample of it (the fraction changes L far less than a
/// whole turn), so seeds beyond the best solution by more than SEED_REACH samples cannot
/// improve it; a seed in the cluster of one already solved is skipped.
fn smallest_solution(fl: &FractionLoop, s0: f64, seeds: Vec<(f64, f64)>) -> Option<(f64, f64)> {
    let mut best: Option<(f64, f64)> = None;
    let mut solved: Vec<(f64, f64)> = Vec::new();
    let mut tries = 0;
    for seed in seeds
        .into_iter()
        .filter(|s| s.0 <= MAX_DELAY as f64 + BEYOND_MAX)
    {
        if best.is_some_and(|b| seed.0 > b.0 + SEED_REACH) || tries == MAX_SOLVES {
            break;
        }
        let clustered = solved.iter().any(|&(s, t)| {
            (seed.0 - s).abs() < CLUSTER_SAMPLES && (seed.1 - t).abs() < CLUSTER_THETA_REL * t
        });
        if clustered {
            continue;
        }
        tries += 1;
        if let Some(sol) = solve(fl, seed) {
            solved.push(seed);
            if sol.0 > s0 && best.is_none_or(|b| sol.0 < b.0) {
                best = Some(sol);
            }
        }
    }
    best
}

/// The verdict confirms a crossing at total delay s: after it, at s + ε (ε = CONFIRM_REL of
/// the added delay), not stable; before it not unstable — at the nearest of s − 10^j·ε,
/// j = 0 … [`CONFIRM_WIDENINGS`], that the verdict's Schur–Cohn step decides surely
/// ([`decide_fast`]: a stable root 1e-8 inside the circle is often beyond the recursion's
/// rounding bound, and the argument principle costs a hundred times more), else by the whole
/// verdict at s − ε. Both sides are marginal only where the whole path lies within the
/// verdict's band of the circle. p at each delay comes from the fraction loop's parts
/// ([`FractionLoop::family_at`]), the exact model at that delay.
fn confirmed(fl: &FractionLoop, s0: f64, s: f64) -> bool {
    let family = |s: f64| {
        let whole = s.floor();
        fl.family_at(whole as usize, &fl.hold(s - whole).g)
    };
    let verdict_at = |s: f64| -> Verdict {
        let f = family(s);
        decide(&f, 1.0, 0.0, &mut f.coefficients(1.0, 0.0)).verdict
    };
    let eps = CONFIRM_REL * (s - s0);
    if s + eps > MAX_DELAY as f64 || verdict_at(s + eps) == Verdict::Stable {
        return false;
    }
    let before = (0..=CONFIRM_WIDENINGS)
        .map(|j| s - eps * 10f64.powi(j))
        .filter(|&x| x > s0)
        .find_map(|x| {
            let f = family(x);
            decide_fast(&f, 1.0, 0.0, &mut f.coefficients(1.0, 0.0))
        });
    before.unwrap_or_else(|| verdict_at(s - eps)) != Verdict::Unstable
}

/// A phase in (−π, π] moved to (0, 2π]: the extra lag that brings L to −1.
fn positive_phase(p: f64) -> f64 {
    if p > 0.0 {
        p
    } else {
        p + 2.0 * std::f64::consts::PI
    }
}

/// Seeds (total delay in samples, θ) of the exact solve, in increasing delay: at every
/// crossover θ of every fraction λ's loop, the smallest s ≥ s0 with s ≡ λ + (PM + 2πk)/θ —
/// the whole samples that a pure delay would need.
fn seeds(s0: f64, crossovers: &[FractionCrossover]) -> Vec<(f64, f64)> {
    let two_pi = 2.0 * std::f64::consts::PI;
    let mut out: Vec<(f64, f64)> = crossovers
        .iter()
        .map(|c| {
            let period = two_pi / c.theta;
            let pm = (c.value.arg() + std::f64::consts::PI).rem_euclid(two_pi);
            let mut d = c.lambda + positive_phase(pm) / c.theta;
            if d < s0 {
                d += ((s0 - d) / period).ceil() * period;
            }
            (d, c.theta)
        })
        .collect();
    out.sort_by(|x, y| x.0.total_cmp(&y.0));
    out
}

/// Newton's method in (s, θ) from a seed on F = L_λ(θ)·e^{−iwθ} + 1 = 0 (w = ⌊s⌋,
/// λ = s − w): ∂F/∂s from the hold input's λ-derivative, ∂F/∂θ by a central difference.
/// (s, θ) when it converges.
fn solve(fl: &FractionLoop, (mut s, mut theta): (f64, f64)) -> Option<(f64, f64)> {
    let pi = std::f64::consts::PI;
    for _ in 0..NEWTON_STEPS {
        if !((0.0..=MAX_DELAY as f64).contains(&s) && theta > 0.0 && theta < pi) {
            return None;
        }
        let whole = s.floor();
        let hold = fl.hold(s - whole);
        let f_at =
            |t: f64| fl.parts(t).view().loop_at(&hold.g) * crate::circle::unit(-whole * t) + 1.0;
        let at = fl.parts(theta);
        let parts = at.view();
        let turn = crate::circle::unit(-whole * theta);
        let f = parts.loop_at(&hold.g) * turn + 1.0;
        let ds = parts.slope_at(&hold.dg) * turn;
        let h = THETA_DIFF_REL * theta;
        let dt = (f_at(theta + h) - f_at(theta - h)) / (2.0 * h);
        let det = ds.re * dt.im - ds.im * dt.re;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let step_s = -(f.re * dt.im - f.im * dt.re) / det;
        let step_t = -(ds.re * f.im - ds.im * f.re) / det;
        let step_s = step_s.clamp(-0.5, 0.5);
        let step_t = step_t.clamp(-0.5 * theta, 0.5 * theta);
        s += step_s;
        theta += step_t;
        if step_s.abs() <= 1e-14 * s.max(1.0) && step_t.abs() <= 1e-12 * theta {
            return Some((s, theta));
        }
    }
    None
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

/// The delay margin by a certified scan, where the exact solve of [`delay_margin`] did not
/// converge and confirm: the smallest extra delay Δ (seconds, any fraction of a sample) at
/// which the loop loses stability, with the frequency of the root pair that crosses.
///
/// Method: scan the total delay s (in samples) upward from the loop's own, testing every step
/// with the Schur–Cohn test on the exact fractional-delay discretization, then bisect the
/// first stable/unstable pair. **First crossing**: a root can reach the unit circle at e^{jθ}
/// only where the Nyquist curve 1 + L reaches 0. An added delay h turns L by e^{−jθh}, which
/// moves 1 + L by at most θh·|L|; so no root reaches the circle while
/// h < min_θ |1 + L|/(θ|L|) = min_θ |p(e^{jθ})|/(θ·|a·PK + b·PB|) (P0 cancels). Each step is
/// that bound divided by [`DELAY_STEP_SAFETY`] (the fractional hold's deviation from a pure
/// phase), at least [`DELAY_MIN_STEP`]; the minimum over θ is taken on the boundary scan's
/// grid and on the loop's mode grid ([`robustness`]). None when the loop stays stable up to the largest modelled delay ([`MAX_DELAY`]
/// samples).
pub fn delay_scan(lp: &Loop, wall: Wall) -> Result<DelayScan> {
    let s0 = lp.delay.in_samples();
    let family_at = |s: f64| -> Result<AffineFamily> {
        AffineFamily::of_loop(&lp.with_delay(delay_in_samples(s))?)
    };
    let base = family_at(s0)?;
    let (a, b) = base.to_units(wall.stiffness, wall.damping);
    let stable = |f: &AffineFamily| verdict_stable(f, a, b, &mut f.coefficients(a, b));
    let modes = frequency_grid(&base, a, b);
    let mut s = s0;
    let mut fam = base;
    let mut work = 0.0;
    loop {
        work += scan_step_work(&fam);
        if work > DELAY_SCAN_WORK {
            return Ok(DelayScan::AtLeast((s - s0) * lp.period));
        }
        let h = (robustness(&fam, a, b, &modes) / DELAY_STEP_SAFETY).max(DELAY_MIN_STEP);
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

/// The delay scan's work bound in evaluations of p's coefficients (estimated at about 0.3 s
/// on one core): past it the scan reports a lower bound instead of running on with p's
/// growing degree.
const DELAY_SCAN_WORK: f64 = 3e8;

/// Work of one scan step: the robustness bound's θ grid times p's degree.
fn scan_step_work(fam: &AffineFamily) -> f64 {
    let n = (fam.degree() + 1) as f64;
    SAMPLES_PER_DEGREE as f64 * n * n
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
/// the pure-delay bound guarantees safe. Taken on a uniform grid of p's degree (the delay
/// turns L round −1 once per 2π/d) and on `modes`, the frequency grid of the loop's own
/// modes ([`frequency_grid`]: a fast-sampled loop's crossover lies far below the uniform
/// grid's first angle).
fn robustness(fam: &AffineFamily, a: f64, b: f64, modes: &[f64]) -> f64 {
    let m = SAMPLES_PER_DEGREE * (fam.degree() + 1);
    let pi = std::f64::consts::PI;
    (1..=m)
        .map(|i| pi * i as f64 / m as f64)
        .chain(modes.iter().copied())
        .map(|t| {
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

/// The angle of the root closest to the unit circle (the pair that just crossed), from the
/// coefficients in w = z − 1 where they are finite (a slow root among many crowding z = 1 is
/// resolved there, [`AffineFamily::coefficients_shifted`]), else from those in z.
fn critical_angle(fam: &AffineFamily, a: f64, b: f64) -> Result<f64> {
    let shifted = fam
        .coefficients_shifted(a, b)
        .filter(|c| c.iter().all(|x| x.is_finite()));
    let rs: Vec<Complex64> = match shifted {
        Some(c) => roots(&c)?.into_iter().map(|w| w + 1.0).collect(),
        None => roots(&fam.coefficients(a, b))?,
    };
    let z = rs
        .iter()
        .min_by(|x, y| (x.norm() - 1.0).abs().total_cmp(&(y.norm() - 1.0).abs()))
        .copied()
        .unwrap_or(Complex64::new(1.0, 0.0));
    Ok(z.arg().abs())
}
