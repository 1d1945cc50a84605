//! The judged window (the second half of the run) split into windows, the least-squares fit
//! of its log-envelope, and the trend that fit shows.

use super::facts::LoopFacts;
use super::run_log::Block;
use super::{
    CYCLE_LOG_CHANGE, CYCLE_SPREAD, DECAY_FLOOR, JUDGE_WINDOWS, PEAK_GROUP, RATE_AGREEMENT,
    RATE_NOISE, TREND_LOG_CHANGE,
};

/// The judged window split into windows.
pub(super) struct Tail {
    pub(super) from: usize,
    pub(super) to: usize,
    pub(super) windows: Vec<Block>,
    pub(super) whole: Block,
    /// Largest block envelope of the whole run.
    pub(super) peak: f64,
}

impl Tail {
    pub(super) fn of(blocks: &[Block], to: usize) -> Option<Tail> {
        let tail: Vec<Block> = blocks
            .iter()
            .copied()
            .filter(|b| b.start >= to / 2)
            .collect();
        let n = tail.len();
        if n < JUDGE_WINDOWS {
            return None;
        }
        let windows = (0..JUDGE_WINDOWS)
            .map(|i| Block::merge_all(&tail[i * n / JUDGE_WINDOWS..(i + 1) * n / JUDGE_WINDOWS]))
            .collect();
        Some(Tail {
            from: tail[0].start,
            to,
            windows,
            whole: Block::merge_all(&tail),
            peak: blocks
                .chunks(PEAK_GROUP)
                .map(|g| Block::merge_all(g).envelope())
                .fold(0.0, f64::max),
        })
    }

    pub(super) fn span(&self) -> f64 {
        (self.to - self.from) as f64
    }

    pub(super) fn floor(&self) -> f64 {
        DECAY_FLOOR * self.peak
    }

    pub(super) fn linear(&self, facts: &LoopFacts) -> bool {
        !facts.static_nonlinearity && self.whole.linear_samples == self.whole.len
    }
}

/// Least-squares slope of y against x.
pub(super) fn slope(points: &[(f64, f64)]) -> Option<f64> {
    let n = points.len() as f64;
    if points.len() < 2 {
        return None;
    }
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// Log-envelope growth rates (per sample) over the judged window and its two halves.
#[derive(Debug, Clone, Copy)]
pub(super) struct Fit {
    pub(super) rate: f64,
    pub(super) first: f64,
    pub(super) second: f64,
}

impl Fit {
    /// Fits every window; None if the envelope of some window is zero (the motion stopped
    /// there) or not finite.
    pub(super) fn of(tail: &Tail) -> Option<Fit> {
        if tail
            .windows
            .iter()
            .any(|w| !(w.envelope() > 0.0 && w.envelope().is_finite()))
        {
            return None;
        }
        let pts: Vec<(f64, f64)> = tail
            .windows
            .iter()
            .map(|w| (w.centre(), w.envelope().ln()))
            .collect();
        let h = pts.len() / 2;
        Some(Fit {
            rate: slope(&pts)?,
            first: slope(&pts[..h])?,
            second: slope(&pts[h..])?,
        })
    }

    /// The two halves agree on the rate (see [`RATE_AGREEMENT`], [`RATE_NOISE`]).
    pub(super) fn steady(&self, span: f64) -> bool {
        (self.first - self.second).abs()
            <= RATE_AGREEMENT * self.rate.abs() + RATE_NOISE / (0.5 * span)
    }
}

/// Largest over smallest, minus one (0 for equal values; infinite if one is zero).
pub(super) fn spread(values: impl Iterator<Item = f64>) -> f64 {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0_f64), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if hi == 0.0 { 0.0 } else { hi / lo - 1.0 }
}

/// The envelope's behaviour over the judged window.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Trend {
    /// The last window is below [`DECAY_FLOOR`] of the peak (or at rest).
    Decayed,
    /// Steady, decisive decay.
    Decaying,
    /// Steady, decisive growth.
    Growing,
    /// Nearly constant envelope.
    Steady,
    /// None of these yet.
    Unsettled(&'static str),
}

pub(super) fn trend(tail: &Tail, fit: Option<Fit>) -> Trend {
    let last = tail.windows[JUDGE_WINDOWS - 1].envelope();
    if last <= tail.floor() {
        return Trend::Decayed;
    }
    let Some(fit) = fit else {
        return Trend::Unsettled("the motion stopped and started again within the judged window");
    };
    let change = fit.rate * tail.span();
    let steady = fit.steady(tail.span());
    if steady && change >= TREND_LOG_CHANGE {
        Trend::Growing
    } else if steady && change <= -TREND_LOG_CHANGE {
        Trend::Decaying
    } else if change.abs() <= CYCLE_LOG_CHANGE
        && spread(tail.windows.iter().map(Block::envelope)) <= CYCLE_SPREAD
    {
        Trend::Steady
    } else if steady {
        Trend::Unsettled("the envelope changes too slowly to judge over this window")
    } else {
        Trend::Unsettled(
            "the envelope's growth rate differs between the halves of the judged window",
        )
    }
}
