//! Robust K_max of any loop over a box of its parameters: the largest stiffness K that is
//! stable, at a given damping B, for every loop whose parameters (the arm's mass, damping and
//! stiffness, the device's, the transmission, the filter's cut-off, the delay, the period —
//! the names of [`SweepParam`]) lie in the box.
//!
//! K_max is not monotone in the parameters in general (a heavier arm can raise or lower it,
//! a resonance moves through the loop's crossover), so the box's corners are not enough. The
//! search is:
//! 1. **sample**: the corners (up to [`MAX_CORNER_PARAMS`] parameters), the centre and
//!    `samples` points drawn uniformly from the box (seeded), each with its exact stable K
//!    interval at B (Section V);
//! 2. **refine**: a compass search (Kolda, Lewis & Torczon, SIAM Review 45, 2003) in the box
//!    from the [`REFINE_STARTS`] worst samples, minimizing the interval's upper end;
//! 3. **verify**: `verify` more plants drawn from the box are checked by the exact verdict at
//!    K_max·(1 − 1e-6); a plant found not stable there is folded in as a sample and refined
//!    from, and the verification repeats (at most [`VERIFY_ROUNDS`] times).
//!
//! What is guaranteed: the reported K_max is the exact K_max of the reported worst plant (a
//! plant in the box, unstable just above it), and every plant sampled, refined or verified
//! is stable at K_max·(1 − 1e-6). It is not a proof over the continuum of the box: a worse
//! plant may hide in a region narrower than the samples and refinement reach.

use rayon::prelude::*;
use serde::Serialize;

use crate::closed_loop::AffineFamily;
use crate::error::{Error, Result};
use crate::kmax::{KmaxQuery, kmax};
use crate::model::Loop;
use crate::param::Param;
use crate::params::Wall;
use crate::splitmix::SplitMix;
use crate::sweep::SweepParam;
use crate::system::System;
use crate::verdict::Verdict;

/// Box parameters beyond which only the centre and the random samples are taken (2^8 = 256
/// corners at most).
pub const MAX_CORNER_PARAMS: usize = 8;

/// Worst samples the compass search starts from.
pub const REFINE_STARTS: usize = 3;

/// Loop evaluations one compass search may spend.
pub const REFINE_BUDGET: usize = 120;

/// Smallest compass step, as a fraction of each parameter's range.
pub const REFINE_STEP: f64 = 1e-4;

/// Verification rounds: a round that finds a plant not stable folds it in and runs again.
pub const VERIFY_ROUNDS: usize = 4;

/// Relative distance below K_max at which every plant must be stable.
pub const VERIFY_MARGIN: f64 = 1e-6;

/// One side of the box: a loop parameter and its range.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BoxSide {
    /// The parameter (`sweep --param`'s names).
    pub param: SweepParam,
    /// Lower end, in the parameter's unit.
    pub lo: f64,
    /// Upper end (≥ lo).
    pub hi: f64,
}

/// How many plants each stage of the search takes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RobustOptions {
    /// Uniform samples of the box (besides its corners and centre).
    pub samples: usize,
    /// Plants drawn for the verification.
    pub verify: usize,
    /// Seed of the samples and of the verification plants.
    pub seed: u64,
}

impl Default for RobustOptions {
    fn default() -> Self {
        RobustOptions {
            samples: 256,
            verify: 10_000,
            seed: 1,
        }
    }
}

/// A parameter's value at the worst plant.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParamValue {
    /// The parameter's name (`sweep --param`'s).
    pub param: &'static str,
    /// Its value in its unit.
    pub value: f64,
    /// The unit.
    pub unit: &'static str,
}

/// Robust K_max over a box: the numbers of `hapstab kmax --robust --box … --json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RobustKmax {
    /// The damping B in Ns/m.
    pub wall_damping: f64,
    /// The largest K (N/m) stable for every plant checked: the worst plant's K_max; None
    /// when some plant of the box has no stable K at B.
    pub k_max: Option<f64>,
    /// The smallest K (N/m) stable for every plant checked (the largest lower end).
    pub k_min: Option<f64>,
    /// K_max of the given loop itself (the box's parameters as the loop has them), N/m.
    pub k_max_nominal: Option<f64>,
    /// The plant that sets `k_max` (or one with no stable K at B).
    pub worst_plant: Vec<ParamValue>,
    /// Plants whose exact stable interval was computed (samples and refinement).
    pub plants_evaluated: usize,
    /// Plants verified stable at K_max·(1 − 1e-6) by the verdict alone (0 where some plant of
    /// the box has no stable K at B: there is no K_max to verify).
    pub plants_verified: usize,
    /// Plants the verification found not stable there and folded into the search.
    pub verification_found: usize,
}

/// A point of the box in unit coordinates and its stable K interval at B (N/m); `None`
/// where no K is stable.
#[derive(Debug, Clone)]
struct Eval {
    u: Vec<f64>,
    interval: Option<[f64; 2]>,
}

impl Eval {
    /// The upper end, −∞ without a stable K (the worst possible).
    fn hi(&self) -> f64 {
        self.interval.map_or(f64::NEG_INFINITY, |i| i[1])
    }
}

/// The box, checked against the loop: finite ends, lo ≤ hi, one side per parameter, and
/// each end a valid loop.
fn check_box(lp: &Loop, sides: &[BoxSide]) -> Result<()> {
    if sides.is_empty() {
        return Err(Error::Invalid {
            param: Param::Box,
            reason: "needs at least one parameter range NAME:LO:HI".into(),
        });
    }
    for (i, s) in sides.iter().enumerate() {
        if !(s.lo.is_finite() && s.hi.is_finite() && s.lo <= s.hi) {
            return Err(Error::Invalid {
                param: Param::Box,
                reason: format!(
                    "{}: needs finite LO <= HI (got {}:{})",
                    s.param.name(),
                    s.lo,
                    s.hi
                ),
            });
        }
        if sides[..i].iter().any(|o| o.param == s.param) {
            return Err(Error::Invalid {
                param: Param::Box,
                reason: format!("{} is given twice", s.param.name()),
            });
        }
        s.param.apply(lp, s.lo)?;
        s.param.apply(lp, s.hi)?;
    }
    Ok(())
}

/// The largest degree of p(z) over the box, for pricing a robust search
/// ([`crate::limits::robust_box_cost`]) before it runs: the loop's own degree plus, for each
/// side, the most its ends add to it, with the delay time and the period taken together at
/// their four corners (the delay in samples is t_d/T). The degree is a sum of the plant's
/// order (with an actuator lag), the velocity filter's length and the delay, so adding each
/// side's increase bounds it from above. Fails, naming the parameter, where an end is not a
/// valid loop.
pub fn box_degree(lp: &Loop, sides: &[BoxSide]) -> Result<usize> {
    let degree = |l: &Loop| -> Result<usize> { Ok(AffineFamily::of_loop(l)?.degree()) };
    let nominal = degree(lp)?;
    let is_delay = |s: &&BoxSide| matches!(s.param, SweepParam::DelayTime | SweepParam::Period);
    let mut delay_loops = vec![lp.clone()];
    for s in sides.iter().filter(is_delay) {
        delay_loops = delay_loops
            .iter()
            .flat_map(|l| [s.lo, s.hi].map(|v| s.param.apply(l, v)))
            .collect::<Result<_>>()?;
    }
    let mut most = nominal;
    for l in &delay_loops {
        most = most.max(degree(l)?);
    }
    for s in sides.iter().filter(|s| !is_delay(s)) {
        let ends = [
            degree(&s.param.apply(lp, s.lo)?)?,
            degree(&s.param.apply(lp, s.hi)?)?,
        ];
        most += ends[0].max(ends[1]).saturating_sub(nominal);
    }
    Ok(most)
}

/// The loop at unit coordinates u of the box.
fn loop_at(lp: &Loop, sides: &[BoxSide], u: &[f64]) -> Result<Loop> {
    sides.iter().zip(u).try_fold(lp.clone(), |l, (s, &x)| {
        s.param.apply(&l, s.lo + x.clamp(0.0, 1.0) * (s.hi - s.lo))
    })
}

/// The exact stable K interval at damping B (N/m) reaching furthest, of the loop at u.
fn evaluate(lp: &Loop, sides: &[BoxSide], b: f64, u: Vec<f64>) -> Result<Eval> {
    let l = loop_at(lp, sides, &u)?;
    let r = kmax(&System::new(l)?, KmaxQuery::AtDamping(b))?;
    Ok(Eval {
        u,
        interval: r.k_interval,
    })
}

/// Stage 1: corners, centre and seeded uniform samples, evaluated in parallel.
fn sample(lp: &Loop, sides: &[BoxSide], b: f64, opts: &RobustOptions) -> Result<Vec<Eval>> {
    let n = sides.len();
    let mut points: Vec<Vec<f64>> = vec![vec![0.5; n]];
    if n <= MAX_CORNER_PARAMS {
        points.extend((0..1usize << n).map(|c| (0..n).map(|j| ((c >> j) & 1) as f64).collect()));
    }
    let mut rng = SplitMix(opts.seed);
    points.extend((0..opts.samples).map(|_| rng.point(n)));
    points
        .into_par_iter()
        .map(|u| evaluate(lp, sides, b, u))
        .collect()
}

/// Stage 2: compass search from `start`, minimizing the interval's upper end; every point
/// it evaluates is returned.
fn refine(lp: &Loop, sides: &[BoxSide], b: f64, start: Eval) -> Result<Vec<Eval>> {
    let n = start.u.len();
    let (mut best, mut step, mut spent) = (start, 0.25, 0);
    let mut seen = Vec::new();
    while step >= REFINE_STEP && spent < REFINE_BUDGET {
        let polls: Vec<Vec<f64>> = (0..2 * n)
            .map(|k| {
                let mut u = best.u.clone();
                let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
                u[k / 2] = (u[k / 2] + sign * step).clamp(0.0, 1.0);
                u
            })
            .filter(|u| *u != best.u)
            .collect();
        spent += polls.len();
        let evals: Vec<Eval> = polls
            .into_par_iter()
            .map(|u| evaluate(lp, sides, b, u))
            .collect::<Result<_>>()?;
        let better = evals
            .iter()
            .filter(|e| e.hi() < best.hi())
            .min_by(|x, y| x.hi().total_cmp(&y.hi()))
            .cloned();
        seen.extend(evals);
        match better {
            Some(e) => best = e,
            None => step /= 2.0,
        }
    }
    seen.push(best);
    Ok(seen)
}

/// The `count` evaluations with the lowest upper ends.
fn worst(evals: &[Eval], count: usize) -> Vec<Eval> {
    let mut sorted: Vec<&Eval> = evals.iter().collect();
    sorted.sort_by(|x, y| x.hi().total_cmp(&y.hi()));
    sorted.into_iter().take(count).cloned().collect()
}

/// Stage 3: the verification plants not stable at K (N/m), B, as evaluations.
fn verify(
    lp: &Loop,
    sides: &[BoxSide],
    wall: Wall,
    plants: &[Vec<f64>],
    k_max: f64,
) -> Result<Vec<Eval>> {
    let failures: Vec<Option<Eval>> = plants
        .par_iter()
        .map(|u| -> Result<Option<Eval>> {
            let l = loop_at(lp, sides, u)?;
            let v = System::decide_wall(&l, wall)?.verdict;
            if v == Verdict::Stable {
                return Ok(None);
            }
            let e = evaluate(lp, sides, wall.damping, u.clone())?;
            // a marginal verdict within rounding of a plant whose K_max is no lower is no
            // counter-example
            Ok((v == Verdict::Unstable || e.hi() < k_max).then_some(e))
        })
        .collect::<Result<_>>()?;
    Ok(failures.into_iter().flatten().collect())
}

/// Robust K_max at damping B (Ns/m) over the box `sides` around the loop `lp` (see the
/// module's doc for the search and what it guarantees).
pub fn robust_kmax(
    lp: &Loop,
    sides: &[BoxSide],
    b: f64,
    opts: &RobustOptions,
) -> Result<RobustKmax> {
    check_box(lp, sides)?;
    let nominal = kmax(&System::of(lp)?, KmaxQuery::AtDamping(b))?;
    let mut evals = sample(lp, sides, b, opts)?;
    for start in worst(&evals, REFINE_STARTS) {
        evals.extend(refine(lp, sides, b, start)?);
    }
    let mut rng = SplitMix(opts.seed ^ 0x005E_ED0F_7E57);
    let plants: Vec<Vec<f64>> = (0..opts.verify).map(|_| rng.point(sides.len())).collect();
    let (mut found, mut verified) = (0, 0);
    for _ in 0..VERIFY_ROUNDS {
        let k = worst(&evals, 1)[0].hi();
        if !k.is_finite() {
            break;
        }
        // no plant is verified where some plant has no stable K at all
        verified = opts.verify;
        let wall = Wall {
            stiffness: k - VERIFY_MARGIN * k.abs(),
            damping: b,
        };
        let bad = verify(lp, sides, wall, &plants, k)?;
        if bad.is_empty() {
            break;
        }
        found += bad.len();
        for start in worst(&bad, 1) {
            evals.extend(refine(lp, sides, b, start)?);
        }
        evals.extend(bad);
    }
    Ok(report(sides, b, nominal.k_max, &evals, verified, found))
}

/// The worst plant and the robust interval from every evaluation.
fn report(
    sides: &[BoxSide],
    b: f64,
    nominal: Option<f64>,
    evals: &[Eval],
    verified: usize,
    found: usize,
) -> RobustKmax {
    let w = &worst(evals, 1)[0];
    let k_min = evals
        .iter()
        .filter_map(|e| e.interval.map(|i| i[0]))
        .fold(f64::NEG_INFINITY, f64::max);
    // no K is stable for every plant when one has none or the intervals do not meet
    let common = evals.iter().all(|e| e.interval.is_some()) && k_min < w.hi();
    RobustKmax {
        wall_damping: b,
        k_max: common.then(|| w.hi()),
        k_min: common.then_some(k_min),
        k_max_nominal: nominal,
        worst_plant: sides
            .iter()
            .zip(&w.u)
            .map(|(s, &x)| ParamValue {
                param: s.param.name(),
                value: s.lo + x * (s.hi - s.lo),
                unit: s.param.unit(),
            })
            .collect(),
        plants_evaluated: evals.len(),
        plants_verified: verified,
        verification_found: found,
    }
}
