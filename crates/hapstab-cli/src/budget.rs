//! The command line's resource check: before a long analysis starts, its estimated cost
//! (`hapstab::limits`) is compared with [`Budget::COMMAND_LINE`], and a command beyond it
//! is refused with one line naming the flag that drives the cost and its value.

use anyhow::{Result, bail};
use hapstab::limits::{Budget, Cost};

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

/// Refuses `cost` beyond the command-line budget: "FLAG VALUE: WHAT would need ... (limit
/// ...)", blaming the driver that multiplies the cost most.
pub fn check(cost: Cost, what: &str, drivers: &[Driver]) -> Result<()> {
    let Err(e) = Budget::COMMAND_LINE.check(cost) else {
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
