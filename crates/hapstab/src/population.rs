//! Probabilistic stability over a population of operators: the probability that a wall is
//! stable when the human holding the device is drawn from a distribution, P(stable) as a
//! function of the wall's stiffness K at a damping B, and the K that keeps a given fraction
//! (0.99, 0.999) of the population stable. Every sample is an exact verdict (Section V),
//! not a simulation.
//!
//! The default population is the paper's Section IV: arm mass m_H uniform in
//! [[`DEFAULT_ARM_MASS`]] kg and the ratios of eq. (11) uniform below their bounds,
//! k_H/m_H ∈ [0, 710] s⁻², b_H/m_H ∈ [0, 12.6] s⁻¹ ([`crate::paper::ranges::RatioLimits::PAPER`]).
//! Any loop parameter (`sweep --param`'s names) can instead be given its own distribution
//! (uniform, normal or log-normal, independent).
//!
//! P(stable) at each K counts the samples whose exact stable K interval at B contains K; its
//! 95 % confidence interval is Wilson's score interval (Wilson, JASA 22, 1927), and the K at
//! which P(stable) falls below a level q is bracketed by the K where the interval's lower and
//! upper ends cross q.

use rayon::prelude::*;
use serde::Serialize;

use crate::error::{Error, Result};
use crate::kmax::{KmaxQuery, kmax};
use crate::model::Loop;
use crate::paper::ranges::RatioLimits;
use crate::param::Param;
use crate::splitmix::SplitMix;
use crate::sweep::SweepParam;
use crate::system::System;

/// The default range of the arm mass m_H in kg (the typical arm's 1 kg within it).
pub const DEFAULT_ARM_MASS: [f64; 2] = [0.5, 2.0];

/// z of the two-sided 95 % confidence interval.
pub const Z95: f64 = 1.959_963_984_540_054;

/// A distribution of one parameter.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Dist {
    /// Uniform in [lo, hi].
    Uniform {
        /// Lower end.
        lo: f64,
        /// Upper end.
        hi: f64,
    },
    /// Normal with mean and standard deviation (sd ≥ 0).
    Normal {
        /// Mean.
        mean: f64,
        /// Standard deviation.
        sd: f64,
    },
    /// Log-normal: exp of a normal with median `median` (> 0) and log-sd `sigma` (≥ 0).
    LogNormal {
        /// Median (e^μ).
        median: f64,
        /// Standard deviation of the logarithm.
        sigma: f64,
    },
}

impl Dist {
    /// Parses `uniform:LO:HI`, `normal:MEAN:SD` or `lognormal:MEDIAN:SIGMA`.
    pub fn parse(text: &str) -> Result<Dist> {
        let bad = |why: &str| Error::Invalid {
            param: Param::Distribution,
            reason: format!(
                "{why} (got '{text}'; uniform:LO:HI, normal:MEAN:SD or lognormal:MEDIAN:SIGMA)"
            ),
        };
        let parts: Vec<&str> = text.split(':').collect();
        let [kind, a, b] = parts[..] else {
            return Err(bad("needs KIND:A:B"));
        };
        let num = |t: &str| t.trim().parse::<f64>().ok().filter(|v| v.is_finite());
        let (Some(a), Some(b)) = (num(a), num(b)) else {
            return Err(bad("needs finite numbers"));
        };
        match kind {
            "uniform" if a <= b => Ok(Dist::Uniform { lo: a, hi: b }),
            "normal" if b >= 0.0 => Ok(Dist::Normal { mean: a, sd: b }),
            "lognormal" if a > 0.0 && b >= 0.0 => Ok(Dist::LogNormal {
                median: a,
                sigma: b,
            }),
            "uniform" | "normal" | "lognormal" => Err(bad("needs LO <= HI, SD >= 0, MEDIAN > 0")),
            _ => Err(bad("unknown kind")),
        }
    }

    /// The value at the uniform u1 (and u2 for the normal's Box–Muller pair).
    fn draw(self, u1: f64, u2: f64) -> f64 {
        let normal = || (-2.0 * (1.0 - u1).ln()).sqrt() * (std::f64::consts::TAU * u2).cos();
        match self {
            Dist::Uniform { lo, hi } => lo + u1 * (hi - lo),
            Dist::Normal { mean, sd } => mean + sd * normal(),
            Dist::LogNormal { median, sigma } => median * (sigma * normal()).exp(),
        }
    }
}

/// Who holds the device: the paper's Section IV population, or independent distributions
/// of named loop parameters.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Population {
    /// m_H uniform in [`DEFAULT_ARM_MASS`], k_H/m_H and b_H/m_H uniform below eq. (11)'s
    /// bounds.
    SectionIv,
    /// Each parameter drawn from its own distribution, independently.
    Independent {
        /// The parameters and their distributions.
        params: Vec<(SweepParam, Dist)>,
    },
}

/// P(stable) against K at a damping B, with the levels' stiffnesses: the numbers of
/// `hapstab population --json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StabilityProbability {
    /// The damping B in Ns/m.
    pub wall_damping: f64,
    /// Operators drawn.
    pub samples: usize,
    /// The seed of the draw.
    pub seed: u64,
    /// Stiffnesses K in N/m of the curve.
    pub k: Vec<f64>,
    /// P(stable) at each K (the fraction of the samples whose stable interval holds K).
    pub probability: Vec<f64>,
    /// Wilson's 95 % interval at each K: lower ends.
    pub probability_lo: Vec<f64>,
    /// Upper ends.
    pub probability_hi: Vec<f64>,
    /// For each level q: the largest K with P(stable) ≥ q, and its bracket.
    pub levels: Vec<LevelStiffness>,
    /// Each sample's stable K interval at B, [lo, hi] in N/m (NaN where none is stable).
    #[serde(skip)]
    pub intervals: Vec<[f64; 2]>,
    /// Each sample's drawn parameters, in the order of `param_names`.
    #[serde(skip)]
    pub draws: Vec<Vec<f64>>,
    /// The names of the drawn parameters.
    pub param_names: Vec<&'static str>,
}

/// The stiffness at which P(stable) reaches a level.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LevelStiffness {
    /// The level q.
    pub level: f64,
    /// The largest K (N/m) at which P(stable) ≥ q; None if no K reaches q.
    pub k: Option<f64>,
    /// The K where Wilson's lower end reaches q (a K surely good to q at 95 %).
    pub k_lo: Option<f64>,
    /// The K where Wilson's upper end reaches q.
    pub k_hi: Option<f64>,
}

/// P(stable) at one wall over a population, each operator by the exact verdict alone.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WallProbability {
    /// The wall stiffness K in N/m.
    pub wall_stiffness: f64,
    /// The damping B in Ns/m.
    pub wall_damping: f64,
    /// Operators drawn.
    pub samples: usize,
    /// The seed of the draw.
    pub seed: u64,
    /// Operators for whom the wall is stable.
    pub stable: usize,
    /// P(stable) = stable/samples.
    pub probability: f64,
    /// Wilson's 95 % interval.
    pub interval: [f64; 2],
    /// The names of the drawn parameters.
    pub param_names: Vec<&'static str>,
    /// Each operator's drawn parameters, in the order of `param_names`.
    #[serde(skip)]
    pub draws: Vec<Vec<f64>>,
    /// Each operator's verdict: stable or not.
    #[serde(skip)]
    pub verdicts: Vec<bool>,
}

/// P(stable) of the wall (K, B) in N/m, Ns/m over `samples` operators of the population
/// (seeded), each by the exact verdict ([`crate::verdict::decide`]) at that wall.
pub fn wall_probability(
    lp: &Loop,
    pop: &Population,
    wall: crate::params::Wall,
    samples: usize,
    seed: u64,
) -> Result<WallProbability> {
    check(pop, wall.damping, samples, &[])?;
    if !wall.stiffness.is_finite() {
        return Err(Error::NotFinite {
            param: Param::WallStiffness,
            value: wall.stiffness,
        });
    }
    let params = param_list(pop);
    applies(lp, pop, &params, seed)?;
    let draws: Vec<Vec<f64>> = (0..samples).map(|i| draw(pop, seed, i)).collect();
    let verdicts: Vec<bool> = draws
        .par_iter()
        .map(|v| -> Result<bool> {
            let l = loop_of(lp, &params, v)?;
            let d = System::decide_wall(&l, wall)?;
            Ok(d.verdict == crate::verdict::Verdict::Stable)
        })
        .collect::<Result<_>>()?;
    let stable = verdicts.iter().filter(|&&s| s).count();
    Ok(WallProbability {
        wall_stiffness: wall.stiffness,
        wall_damping: wall.damping,
        samples,
        seed,
        stable,
        probability: stable as f64 / samples as f64,
        interval: wilson(stable, samples, Z95),
        param_names: params.iter().map(|p| p.name()).collect(),
        draws,
        verdicts,
    })
}

/// Wilson's score interval of a proportion k/n at z (Wilson 1927).
pub fn wilson(k: usize, n: usize, z: f64) -> [f64; 2] {
    if n == 0 {
        return [0.0, 1.0];
    }
    let (nf, p) = (n as f64, k as f64 / n as f64);
    let z2 = z * z;
    let centre = (p + z2 / (2.0 * nf)) / (1.0 + z2 / nf);
    let half = z / (1.0 + z2 / nf) * (p * (1.0 - p) / nf + z2 / (4.0 * nf * nf)).sqrt();
    [(centre - half).max(0.0), (centre + half).min(1.0)]
}

/// Sample i's uniforms: its own SplitMix stream, so a draw does not depend on the threads.
fn uniforms(seed: u64, i: usize, count: usize) -> Vec<f64> {
    SplitMix::stream(seed, i).point(count)
}

/// The names and values of sample i.
fn draw(pop: &Population, seed: u64, i: usize) -> Vec<f64> {
    match pop {
        Population::SectionIv => {
            let u = uniforms(seed, i, 3);
            let r = RatioLimits::PAPER;
            let m = DEFAULT_ARM_MASS[0] + u[0] * (DEFAULT_ARM_MASS[1] - DEFAULT_ARM_MASS[0]);
            vec![
                m,
                u[1] * r.arm_damping_per_mass * m,
                u[2] * r.arm_stiffness_per_mass * m,
            ]
        }
        Population::Independent { params } => {
            let u = uniforms(seed, i, 2 * params.len());
            params
                .iter()
                .enumerate()
                .map(|(j, (_, d))| d.draw(u[2 * j], u[2 * j + 1]))
                .collect()
        }
    }
}

fn param_list(pop: &Population) -> Vec<SweepParam> {
    match pop {
        Population::SectionIv => vec![
            SweepParam::ArmMass,
            SweepParam::ArmDamping,
            SweepParam::ArmStiffness,
        ],
        Population::Independent { params } => params.iter().map(|(p, _)| *p).collect(),
    }
}

/// The loop of one operator.
fn loop_of(lp: &Loop, params: &[SweepParam], values: &[f64]) -> Result<Loop> {
    params
        .iter()
        .zip(values)
        .try_fold(lp.clone(), |l, (p, &v)| p.apply(&l, v))
}

/// Every drawn parameter must apply to this loop before the draw; the default population
/// needs a loop with an arm.
fn applies(lp: &Loop, pop: &Population, params: &[SweepParam], seed: u64) -> Result<()> {
    match (loop_of(lp, params, &draw(pop, seed, 0)), pop) {
        (Ok(_), _) => Ok(()),
        (Err(e), Population::SectionIv) => Err(Error::Invalid {
            param: Param::Population,
            reason: format!(
                "of Section IV draws the arm's m_H, b_H and k_H, which this loop cannot take \
                 ({e}); give the distributions of its own parameters instead"
            ),
        }),
        (Err(e), _) => Err(e),
    }
}

/// One operator's stable K interval at B in N/m (NaN, NaN where none is).
fn interval(lp: &Loop, params: &[SweepParam], values: &[f64], b: f64) -> Result<[f64; 2]> {
    let l = loop_of(lp, params, values)?;
    let r = kmax(&System::new(l)?, KmaxQuery::AtDamping(b))?;
    Ok(r.k_interval.unwrap_or([f64::NAN, f64::NAN]))
}

/// The number of stable K intervals (open) that hold K.
pub fn count_at(intervals: &[[f64; 2]], k: f64) -> usize {
    intervals.iter().filter(|i| i[0] < k && k < i[1]).count()
}

/// P(stable) against K at damping B over `samples` operators of the population (each
/// operator's exact stable K interval at B), and the K of each level.
pub fn stability_probability(
    lp: &Loop,
    pop: &Population,
    b: f64,
    samples: usize,
    seed: u64,
    levels: &[f64],
) -> Result<StabilityProbability> {
    check(pop, b, samples, levels)?;
    let params = param_list(pop);
    // every parameter must apply to this loop before the draw
    applies(lp, pop, &params, seed)?;
    let draws: Vec<Vec<f64>> = (0..samples).map(|i| draw(pop, seed, i)).collect();
    let intervals: Vec<[f64; 2]> = draws
        .par_iter()
        .map(|v| interval(lp, &params, v, b))
        .collect::<Result<_>>()?;
    let k = curve_grid(&intervals);
    let counts: Vec<usize> = k.iter().map(|&x| count_at(&intervals, x)).collect();
    let ci: Vec<[f64; 2]> = counts.iter().map(|&c| wilson(c, samples, Z95)).collect();
    Ok(StabilityProbability {
        wall_damping: b,
        samples,
        seed,
        probability: counts.iter().map(|&c| c as f64 / samples as f64).collect(),
        probability_lo: ci.iter().map(|c| c[0]).collect(),
        probability_hi: ci.iter().map(|c| c[1]).collect(),
        levels: {
            let runs = stretches(&intervals);
            levels
                .iter()
                .map(|&q| level_stiffness(&runs, samples, q))
                .collect()
        },
        k,
        intervals,
        draws,
        param_names: params.iter().map(|p| p.name()).collect(),
    })
}

fn check(pop: &Population, b: f64, samples: usize, levels: &[f64]) -> Result<()> {
    if !b.is_finite() {
        return Err(Error::NotFinite {
            param: Param::WallDamping,
            value: b,
        });
    }
    if samples == 0 {
        return Err(Error::Invalid {
            param: Param::Samples,
            reason: "must be at least 1".into(),
        });
    }
    if let Some(q) = levels.iter().find(|q| !(**q > 0.0 && **q < 1.0)) {
        return Err(Error::OutOfRange {
            param: Param::Level,
            value: *q,
            range: "(0, 1)",
        });
    }
    if let Population::Independent { params } = pop
        && params.is_empty()
    {
        return Err(Error::Invalid {
            param: Param::Population,
            reason: "needs at least one parameter distribution".into(),
        });
    }
    Ok(())
}

/// The curve's stiffnesses: 0 … 1.2 × the largest upper end, 401 points.
fn curve_grid(intervals: &[[f64; 2]]) -> Vec<f64> {
    let top = intervals
        .iter()
        .map(|i| i[1])
        .filter(|x| x.is_finite())
        .fold(0.0, f64::max);
    let mut k: Vec<f64> = (0..=400).map(|i| 1.2 * top * i as f64 / 400.0).collect();
    k.sort_by(f64::total_cmp);
    k.dedup();
    k
}

/// The stable count on each open stretch between consecutive interval ends: (right end of
/// the stretch, count), ascending (a sweep over the ends, +1 at a lower end, −1 at an upper).
fn stretches(intervals: &[[f64; 2]]) -> Vec<(f64, usize)> {
    let mut ev: Vec<(f64, i64)> = intervals
        .iter()
        .filter(|i| i[0].is_finite() && i[1].is_finite())
        .flat_map(|i| [(i[0], 1), (i[1], -1)])
        .collect();
    ev.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out = Vec::new();
    let mut count = 0i64;
    let mut j = 0;
    while j < ev.len() {
        let x = ev[j].0;
        while j < ev.len() && ev[j].0 == x {
            count += ev[j].1;
            j += 1;
        }
        if j < ev.len() {
            out.push((ev[j].0, count.max(0) as usize));
        }
    }
    out
}

/// The largest K with P(stable) ≥ q, and the K where Wilson's lower and upper ends reach q:
/// P(K) is constant between interval ends, so each is the right end of the highest stretch
/// whose count passes.
fn level_stiffness(runs: &[(f64, usize)], n: usize, q: f64) -> LevelStiffness {
    let sup_where =
        |ok: &dyn Fn(usize) -> bool| runs.iter().rev().find(|(_, c)| ok(*c)).map(|(x, _)| *x);
    LevelStiffness {
        level: q,
        k: sup_where(&|c| c as f64 >= q * n as f64),
        k_lo: sup_where(&|c| wilson(c, n, Z95)[0] >= q),
        k_hi: sup_where(&|c| wilson(c, n, Z95)[1] >= q),
    }
}
