//! The jobs of `hapstab paper` (regions, validity points, robust regions, the passivity
//! check) and their parallel run.

use anyhow::{Context, Result};
use hapstab::paper::linear::{ValidityPoint, validity_points};
use hapstab::paper::nyquist::{
    GammaRange, PassiveCheck, RobustOptions, RobustRegion, passive_inside_robust, robust_region,
};
use rayon::prelude::*;

use super::region::{Region, region};
use super::{
    DELTA_ARM, DELTA_NYQUIST, FIG7_DELTAS, FULL_SWEEP, GAMMA_ARM, HALF_SWEEP, Key, LEVELS,
    ROBUST_DRAW, Results, RobustKey, sweep_gamma,
};

/// One unit of work.
#[derive(Debug, Clone, Copy)]
pub enum Job {
    /// A stable region.
    Region(Key),
    /// The 2 % and 5 % points of Fig. 7.
    Validity(Key),
    /// A robust region of Figs. 8–10.
    Robust(RobustKey),
    /// Claim C8: passive triangle inside the robust region (δ = 1, d = 0, full range).
    Passive,
}

impl Job {
    /// Rough cost rank (higher first) so the slow jobs start first.
    fn cost(&self) -> u32 {
        match self {
            Job::Passive => 4,
            Job::Robust(r) if r.delta > 0.0 => 3,
            Job::Validity(_) => 2,
            Job::Robust(_) => 1,
            Job::Region(_) => 0,
        }
    }
}

pub(super) enum Out {
    Region(Region),
    Validity(Key, Vec<ValidityPoint>),
    Robust(RobustKey, Box<RobustRegion>),
    Passive(PassiveCheck),
}

/// The jobs of every figure plus `extra` region keys (claims), deduplicated.
pub fn jobs(extra: &[Key]) -> Vec<Job> {
    let mut keys: Vec<Key> = Vec::new();
    // Figs. 4–6: the corners of the range (15) for d = 0, 1, 2.
    for d in 0..=2 {
        for gamma in [0.0, GAMMA_ARM] {
            for delta in [0.0, DELTA_ARM] {
                keys.push(Key::new(gamma, delta, d));
            }
        }
    }
    // Fig. 7.
    let mut validity = Vec::new();
    for d in 0..=1 {
        for gamma in [0.0, GAMMA_ARM] {
            for delta in FIG7_DELTAS {
                keys.push(Key::new(gamma, delta, d));
                validity.push(Key::new(gamma, delta, d));
            }
        }
    }
    // Figs. 8–10.
    let mut robust = Vec::new();
    for (delta, d) in [(0.0, 0), (DELTA_NYQUIST, 0), (0.0, 1), (DELTA_NYQUIST, 1)] {
        for f in HALF_SWEEP.iter().chain(FULL_SWEEP.iter()) {
            keys.push(Key::new(sweep_gamma(*f, delta), delta, d));
        }
        for full in [false, true] {
            robust.push(RobustKey { delta, d, full });
        }
    }
    keys.extend_from_slice(extra);
    let mut seen = std::collections::HashSet::new();
    keys.retain(|k| seen.insert(k.id()));
    let mut jobs: Vec<Job> = keys.into_iter().map(Job::Region).collect();
    jobs.extend(validity.into_iter().map(Job::Validity));
    jobs.extend(robust.into_iter().map(Job::Robust));
    jobs.push(Job::Passive);
    jobs.sort_by_key(|j| std::cmp::Reverse(j.cost()));
    jobs
}

/// Options of the passivity check of claim C8 (the library defaults: refined in γ).
pub fn passive_options() -> RobustOptions {
    RobustOptions::default()
}

/// The γ range of claim C8: up to the Nyquist frequency for δ = 1.
pub fn passive_gamma_hi() -> f64 {
    RobustKey {
        delta: DELTA_NYQUIST,
        d: 0,
        full: true,
    }
    .gamma_hi()
}

pub(super) fn run_job(j: Job) -> Result<Out> {
    Ok(match j {
        Job::Region(k) => Out::Region(region(k)?),
        Job::Validity(k) => Out::Validity(
            k,
            validity_points(k.plant()?, k.d, &LEVELS)
                .with_context(|| format!("validity points of {k:?}"))?,
        ),
        Job::Robust(r) => Out::Robust(
            r,
            Box::new(robust_region(
                GammaRange {
                    delta: r.delta,
                    d: r.d,
                    gamma_lo: 0.0,
                    gamma_hi: r.gamma_hi(),
                },
                ROBUST_DRAW,
            )?),
        ),
        Job::Passive => Out::Passive(passive_inside_robust(
            GammaRange {
                delta: DELTA_NYQUIST,
                d: 0,
                gamma_lo: 0.0,
                gamma_hi: passive_gamma_hi(),
            },
            41,
            passive_options(),
        )?),
    })
}

/// Runs every job in parallel; `tick` is called after each.
pub fn run(jobs: &[Job], tick: &(dyn Fn() + Sync)) -> Result<Results> {
    let outs: Vec<Out> = jobs
        .par_iter()
        .with_max_len(1)
        .map(|&j| {
            let o = run_job(j);
            tick();
            o
        })
        .collect::<Result<_>>()?;
    let mut res = Results::default();
    for o in outs {
        match o {
            Out::Region(r) => {
                res.regions.insert(r.key.id(), r);
            }
            Out::Validity(k, v) => {
                res.validity.insert(k.id(), v);
            }
            Out::Robust(k, r) => {
                res.robust.insert(k.id(), *r);
            }
            Out::Passive(p) => res.passive = Some(p),
        }
    }
    Ok(res)
}
