//! The command line's resource check: before a long analysis starts, its estimated cost
//! (`hapstab::limits`) is compared with [`Budget::COMMAND_LINE`], and a command beyond it
//! is refused with one line naming the flag that drives the cost and its value.
//!
//! Two environment variables serve scripts and tests: `HAPSTAB_MAX_SECONDS` sets another
//! time budget in core-seconds (e.g. a lower one for a batch job), and `HAPSTAB_ESTIMATE=1`
//! prints each estimate on standard error (`estimate: 1.23 core-seconds, 4.5 MB: WHAT`),
//! which is how `benches/budget_ratios.sh` compares estimates with measured times.

use anyhow::{Result, bail};
use hapstab::limits::{Budget, Cost};
use hapstab::model::{Loop, PlantModel, VelocityEstimator};

use crate::model::LoopArgs;

/// A flag that drives a cost: its name, the value as typed and its size relative to the
/// default (how much it multiplies the cost).
pub struct Driver<'a> {
    /// Flag name with dashes, e.g. "--box-samples".
    pub flag: &'a str,
    /// The value as the user wrote it (or as parsed).
    pub value: String,
    /// value / default, or (d + 4)/4 for a delay.
    pub factor: f64,
}

impl<'a> Driver<'a> {
    /// A sample count against its default.
    pub fn count(flag: &'a str, value: usize, default: usize) -> Self {
        Self {
            flag,
            value: value.to_string(),
            factor: value as f64 / default.max(1) as f64,
        }
    }

    /// The delay d: the cost grows with d + 4.
    pub fn delay(value: usize) -> Self {
        Self {
            flag: "--delay",
            value: value.to_string(),
            factor: (value as f64 + 4.0) / 4.0,
        }
    }
}

/// The flags that set the degree of a loop's p(z), each with its share of the degree (the
/// delay in samples, the velocity filter's length, the plant's order) as its factor: the
/// one with the largest share is blamed for a cost that grows with the degree.
pub fn degree_drivers(args: &LoopArgs, lp: &Loop) -> Vec<Driver<'static>> {
    let mut out = Vec::new();
    let d = lp.delay.samples as f64 + lp.delay.fraction.ceil();
    let (flag, value) = match (args.plant.delay_time, args.plant.delay) {
        (Some(t), _) => ("--delay-time", t.to_string()),
        (None, Some(d)) => ("--delay", d.to_string()),
        (None, None) => ("--delay", "0".to_string()),
    };
    out.push(Driver {
        flag,
        value,
        factor: d,
    });
    let taps = match &lp.velocity {
        VelocityEstimator::Backward | VelocityEstimator::LowPass { .. } => 1.0,
        VelocityEstimator::Average { samples } => *samples as f64,
        VelocityEstimator::Butterworth { order, .. }
        | VelocityEstimator::Bessel { order, .. }
        | VelocityEstimator::CriticallyDamped { order, .. } => *order as f64 + 1.0,
        VelocityEstimator::Iir { b, a } => b.len().max(a.len()) as f64 - 1.0,
    };
    out.push(Driver {
        flag: "--velocity",
        value: hapstab::spec::excerpt(&lp.velocity.to_string()),
        factor: taps,
    });
    if let PlantModel::TransferFunction { den, .. } = &lp.plant.model {
        out.push(Driver {
            flag: "--plant-den",
            value: hapstab::spec::excerpt_list(den),
            factor: den.len() as f64,
        });
    }
    out
}

/// The command-line budget: [`Budget::COMMAND_LINE`], its time replaced by
/// `HAPSTAB_MAX_SECONDS` when that is set to a positive number.
pub fn command_budget() -> Budget {
    let mut b = Budget::COMMAND_LINE;
    if let Some(s) = std::env::var("HAPSTAB_MAX_SECONDS")
        .ok()
        .and_then(|v| v.trim().parse::<f64>().ok())
        .filter(|s| s.is_finite() && *s > 0.0)
    {
        b.seconds = s;
    }
    b
}

/// Refuses `cost` beyond the command-line budget: "FLAG VALUE: WHAT would need ... (limit
/// ...)", blaming the driver that multiplies the cost most.
pub fn check(cost: Cost, what: &str, drivers: &[Driver]) -> Result<()> {
    if std::env::var_os("HAPSTAB_ESTIMATE").is_some_and(|v| v == "1") {
        eprintln!(
            "estimate: {:.6} core-seconds, {:.0} bytes: {what}",
            cost.seconds, cost.memory
        );
    }
    let Err(e) = command_budget().check(cost) else {
        return Ok(());
    };
    let blame = drivers.iter().max_by(|a, b| a.factor.total_cmp(&b.factor));
    match blame {
        Some(d) => bail!(
            "{} {}: {what} {e}; use a smaller {} (see the Limits section of the README)",
            d.flag,
            d.value,
            d.flag
        ),
        None => bail!("{what} {e}"),
    }
}

/// Refuses an analysis of one loop beyond the budget, blaming the flag that sets most of the
/// degree of its p(z).
pub fn check_loop(args: &LoopArgs, lp: &Loop, cost: Cost, what: &str) -> Result<()> {
    check(cost, what, &degree_drivers(args, lp))
}

pub use hapstab::limits::loop_degree;
