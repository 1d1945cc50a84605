//! The Python package's resource check, the command line's budget
//! ([`hapstab::limits::Budget::COMMAND_LINE`]): every entry point with a command-line
//! counterpart estimates its cost from its inputs' sizes before it copies or computes
//! anything, and refuses a call beyond the budget with a `ValueError` whose message starts
//! with the keyword argument that drives the cost.

use hapstab::AffineFamily;
use hapstab::limits::{Budget, Cost};
use hapstab::model::{Loop, VelocityEstimator};
use pyo3::prelude::*;

use crate::errors::bad;

/// Refuses `cost` beyond the budget: "KEYWORD: WHAT would need … (limit …); VALUE".
pub fn check(cost: Cost, keyword: &str, what: &str, why: &str) -> PyResult<()> {
    match Budget::COMMAND_LINE.check(cost) {
        Ok(()) => Ok(()),
        Err(e) => Err(bad(keyword, format!("{what} {e}; {why}"))),
    }
}

/// What sets most of the degree of a loop's p(z), in words for a refusal.
pub fn degree_reason(lp: &Loop, fam: &AffineFamily) -> String {
    let taps = match &lp.velocity {
        VelocityEstimator::Average { samples } => *samples,
        VelocityEstimator::Butterworth { order, .. }
        | VelocityEstimator::Bessel { order, .. }
        | VelocityEstimator::CriticallyDamped { order, .. } => order + 1,
        VelocityEstimator::Iir { b, a } => b.len().max(a.len()).saturating_sub(1),
        _ => 1,
    };
    let part = if taps > lp.delay.samples {
        format!("its velocity estimator of {taps} samples")
    } else {
        format!("its delay of {} samples", lp.delay.samples)
    };
    format!(
        "p(z) has degree {} from {part}; use a shorter one",
        fam.degree()
    )
}

/// Refuses an analysis of `lp` beyond the budget, blaming the keyword `loop` and what sets
/// its degree.
pub fn check_loop(cost: Cost, lp: &Loop, fam: &AffineFamily, what: &str) -> PyResult<()> {
    check(cost, "loop", what, &degree_reason(lp, fam))
}

/// The shape of an array-like argument without copying it: a numpy array's `shape`, else
/// numpy's shape of the object (a list is already in memory as Python objects).
pub fn shape_of(x: &Bound<'_, PyAny>) -> PyResult<Vec<usize>> {
    if let Ok(shape) = x.getattr("shape").and_then(|s| s.extract::<Vec<usize>>()) {
        return Ok(shape);
    }
    let np = x.py().import("numpy")?;
    np.getattr("shape")?.call1((x,))?.extract()
}
