//! The steps of the module documentation of [`super`]: a blown-up run, a separated
//! unilateral wall, a linear window, a nonlinear one; the measured growth beside the verdict.

use super::facts::{LinearReference, LoopFacts};
use super::outcome::{ContactSummary, LimitCycle, Outcome, RunVerdict};
use super::run_log::{Block, RunLog};
use super::tail::{Fit, Tail, Trend, slope, spread, trend};
use super::{
    APPROACH_TOLERANCE, CYCLE_SPREAD, DECAY_FIT_TOP, DECAY_FLOOR, JUDGE_WINDOWS,
    MIN_CYCLES_PER_WINDOW, MIN_DECAY_POINTS, MONOTONE_TOLERANCE, PERIOD_SPREAD,
};
use crate::stability::Verdict as LinearVerdict;

/// An outcome with its reason, before the evidence is attached.
struct Decision {
    outcome: Outcome,
    reason: String,
    limit_cycle: Option<LimitCycle>,
}

fn settled(outcome: Outcome, reason: impl Into<String>) -> Decision {
    Decision {
        outcome,
        reason: reason.into(),
        limit_cycle: None,
    }
}

fn open(reason: impl Into<String>) -> Decision {
    settled(Outcome::Undecided, reason)
}

/// Contact loss or a force limit may still bound growth.
fn growth_may_be_bounded(facts: &LoopFacts) -> bool {
    facts.contact_can_be_lost || facts.force_limited
}

fn judge_separated(tail: &Tail, log: &RunLog) -> Decision {
    let p = &tail.whole.position;
    let tol = APPROACH_TOLERANCE * p.max.abs().max(p.min.abs());
    let approaching = tail
        .windows
        .windows(2)
        .any(|w| w[1].position.max > w[0].position.max + tol);
    if approaching {
        return open("out of contact, but the device is moving back toward the wall");
    }
    let reason = match log.separations {
        0 => "the device never touched the wall".to_string(),
        n => format!(
            "left the wall after {n} bounce{} and stayed out of contact over the whole judged window",
            if n == 1 { "" } else { "s" }
        ),
    };
    settled(Outcome::Separated, reason)
}

fn disagreement(trend: Trend, reference: &LinearReference) -> Decision {
    let what = if trend == Trend::Growing {
        "grows"
    } else {
        "decays"
    };
    open(format!(
        "the envelope {what} while the spectral radius is {}: the dominant mode has not emerged yet",
        short(reference.spectral_radius)
    ))
}

fn judge_linear(tail: &Tail, fit: Option<Fit>, facts: &LoopFacts, last_chance: bool) -> Decision {
    if tail.peak == 0.0 {
        return open(if tail.whole.position.range() == 0.0 {
            "the run never left its equilibrium: nothing excites the loop"
        } else {
            "the device moves at constant velocity: the loop is marginal"
        });
    }
    let t = trend(tail, fit);
    let expected = facts.linear.map(|r| r.verdict);
    match (t, expected) {
        (Trend::Decayed | Trend::Decaying, Some(LinearVerdict::Unstable))
        | (Trend::Growing, Some(LinearVerdict::Stable | LinearVerdict::Marginal)) => facts
            .linear
            .map_or_else(|| open(""), |r| disagreement(t, &r)),
        (Trend::Decayed, _) => settled(
            Outcome::Decaying,
            "the motion decayed below 1e-9 of its peak while the loop was linear",
        ),
        (Trend::Decaying, _) => settled(
            Outcome::Decaying,
            "the envelope decays steadily while the loop is linear",
        ),
        (Trend::Growing, _) if growth_may_be_bounded(facts) && !last_chance => {
            open("growing in linear contact; contact loss or the force limit will bound it")
        }
        (Trend::Growing, _) => settled(
            Outcome::Growing,
            "the envelope grows steadily while the loop is linear",
        ),
        (Trend::Steady, Some(LinearVerdict::Marginal)) => {
            open("marginal: the spectral radius is 1 within rounding and the envelope is steady")
        }
        (Trend::Steady, _) => open("the envelope changes too slowly to judge over this window"),
        (Trend::Unsettled(why), _) => open(why),
    }
}

/// Every window moves monotonically in the same direction, without velocity crossings.
fn drifting(tail: &Tail) -> bool {
    let dir = |w: &Block| {
        let net = w.last_position - w.first_position;
        let monotone = w.position.range() > 0.0
            && net.abs() >= (1.0 - MONOTONE_TOLERANCE) * w.position.range();
        if monotone { net.signum() } else { 0.0 }
    };
    let d0 = dir(&tail.windows[0]);
    d0 != 0.0 && tail.whole.crossings.count == 0 && tail.windows.iter().all(|w| dir(w) == d0)
}

fn judge_nonlinear(
    tail: &Tail,
    fit: Option<Fit>,
    facts: &LoopFacts,
    last_chance: bool,
) -> Decision {
    match trend(tail, fit) {
        Trend::Decayed if tail.windows[JUDGE_WINDOWS - 1].velocity.range() == 0.0 => {
            settled(Outcome::Decaying, "the device came to rest")
        }
        Trend::Decayed => settled(
            Outcome::Decaying,
            "the motion decayed below 1e-9 of its peak",
        ),
        Trend::Decaying => open(
            "decaying, but still above 1e-9 of its peak: a nonlinear effect may yet sustain a small oscillation",
        ),
        Trend::Growing if growth_may_be_bounded(facts) && !last_chance => {
            open("growing; contact loss or the force limit may still bound it")
        }
        Trend::Growing => settled(Outcome::Growing, "the envelope grows steadily"),
        Trend::Steady | Trend::Unsettled(_) if drifting(tail) => settled(
            Outcome::Growing,
            "the device moves on without bound: no oscillation, and its speed does not decay",
        ),
        Trend::Steady => match limit_cycle(tail, facts) {
            Ok(lc) => Decision {
                outcome: Outcome::LimitCycle,
                reason: cycle_reason(&lc),
                limit_cycle: Some(lc),
            },
            Err(why) => open(why),
        },
        Trend::Unsettled(why) => open(why),
    }
}

fn cycle_reason(lc: &LimitCycle) -> String {
    let base = format!(
        "amplitude and period steady over the judged window ({} cycles)",
        lc.cycles.floor()
    );
    if lc.bouncing {
        base + "; contact is lost and regained every cycle"
    } else {
        base
    }
}

/// Amplitude, offset and period of a steady oscillation, or why they have not settled.
fn limit_cycle(tail: &Tail, facts: &LoopFacts) -> Result<LimitCycle, &'static str> {
    let bouncing = tail.whole.separations > 0;
    let events = |w: &Block| if bouncing { w.contacts } else { w.crossings };
    if tail
        .windows
        .iter()
        .any(|w| events(w).count < MIN_CYCLES_PER_WINDOW + 1)
    {
        return Err(
            "fewer than 2 cycles per judging window: the oscillation is too slow or irregular",
        );
    }
    let periods = tail.windows.iter().filter_map(|w| events(w).period());
    if spread(periods) > PERIOD_SPREAD {
        return Err("bounded oscillation whose period has not settled");
    }
    let pp = tail.whole.position.range();
    let ranges = tail.windows.iter().map(|w| w.position.range());
    let mids = tail.windows.iter().map(|w| w.position.middle());
    let (lo, hi) = mids.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), m| {
        (a.min(m), b.max(m))
    });
    if spread(ranges) > CYCLE_SPREAD || hi - lo > CYCLE_SPREAD * pp {
        return Err("bounded oscillation whose amplitude or offset has not settled");
    }
    let all = events(&tail.whole);
    let period = all.period().ok_or("no period could be measured")?;
    Ok(LimitCycle {
        peak_to_peak: pp,
        counts: facts.quantum.map(|q| pp / q),
        period_samples: period,
        frequency_hz: 1.0 / (period * facts.period),
        cycles: tail.span() / period,
        bouncing,
    })
}

/// Growth per sample of a run that blew up: from its quietest block to its last one.
fn blow_up_growth(blocks: &[Block]) -> Option<f64> {
    let (last, rest) = blocks.split_last()?;
    let quiet = rest
        .iter()
        .filter(|b| b.envelope() > 0.0)
        .min_by(|a, b| a.envelope().total_cmp(&b.envelope()))?;
    let dk = last.centre() - quiet.centre();
    let g = (last.envelope() / quiet.envelope()).powf(1.0 / dk);
    (dk > 0.0 && g.is_finite() && g > 1.0).then_some(g)
}

/// Decay per sample of a run that decayed below the floor: the slope of the log-envelope of
/// the blocks after the peak, between [`DECAY_FIT_TOP`] and [`DECAY_FLOOR`] of it.
fn decay_growth(blocks: &[Block], peak: f64) -> Option<f64> {
    let start = blocks
        .iter()
        .position(|b| b.envelope() >= DECAY_FIT_TOP * peak)?;
    let pts: Vec<(f64, f64)> = blocks[start..]
        .iter()
        .skip_while(|b| b.envelope() > DECAY_FIT_TOP * peak)
        .take_while(|b| b.envelope() > DECAY_FLOOR * peak)
        .map(|b| (b.centre(), b.envelope().ln()))
        .collect();
    if pts.len() < MIN_DECAY_POINTS {
        return None;
    }
    slope(&pts).map(f64::exp).filter(|g| *g < 1.0)
}

fn measured_growth(
    outcome: Outcome,
    tail: Option<&Tail>,
    fit: Option<Fit>,
    blocks: &[Block],
    blown_up: bool,
) -> Option<f64> {
    let decayed = tail.is_some_and(|t| t.windows[JUDGE_WINDOWS - 1].envelope() <= t.floor());
    match outcome {
        Outcome::LimitCycle | Outcome::Separated => None,
        _ if blown_up => blow_up_growth(blocks),
        _ if decayed => tail.and_then(|t| decay_growth(blocks, t.peak)),
        _ => fit.map(|f| f.rate.exp()),
    }
}

/// A number with 6 significant digits for a reason text.
fn short(v: f64) -> String {
    let s = format!("{v:.6e}");
    s.parse::<f64>().map_or(s, |x| format!("{x}"))
}

/// Judges a run from its log (see the module documentation for the steps). `blown_up` says
/// that the run stopped because its state exceeded the simulator's bound; `last_chance`
/// that the run will not be extended (its horizon is reached), so growth that contact loss
/// or a force limit could still bound is reported as growing. The outcome is
/// [`Outcome::Undecided`] exactly when the judged window has not settled.
pub fn judge(log: &RunLog, facts: &LoopFacts, blown_up: bool, last_chance: bool) -> RunVerdict {
    let blocks = log.all_blocks();
    let tail = Tail::of(&blocks, log.samples);
    let fit = tail.as_ref().and_then(Fit::of);
    let mut decision = match &tail {
        _ if blown_up => settled(
            Outcome::Growing,
            "the state blew up (exceeded the simulator's bound)",
        ),
        None => open("the run is too short to judge"),
        Some(t) if facts.contact_can_be_lost && t.whole.contact_samples == 0 => {
            judge_separated(t, log)
        }
        Some(t) if t.linear(facts) => judge_linear(t, fit, facts, last_chance),
        Some(t) => judge_nonlinear(t, fit, facts, last_chance),
    };
    if decision.outcome == Outcome::Undecided && last_chance {
        decision.reason = format!(
            "not settled after {} samples (the horizon): {}",
            log.samples, decision.reason
        );
    }
    let measured = measured_growth(decision.outcome, tail.as_ref(), fit, &blocks, blown_up);
    let (from, judged) = match &tail {
        Some(t) => (t.from, t.whole),
        None => (0, Block::merge_all(&blocks)),
    };
    RunVerdict {
        outcome: decision.outcome,
        reason: decision.reason,
        judged_from_sample: from,
        judged_to_sample: log.samples,
        linear_window: tail.as_ref().is_some_and(|t| t.linear(facts)),
        measured_growth_per_sample: measured,
        spectral_radius: facts.linear.map(|r| r.spectral_radius),
        linear_verdict: facts.linear.map(|r| r.verdict),
        limit_cycle: decision.limit_cycle,
        contact: ContactSummary {
            contacts: log.contacts,
            separations: log.separations,
            in_contact_at_end: log.previous_contact == 1,
            last_separation_sample: log.last_separation,
            judged_contact_fraction: judged.contact_samples as f64 / judged.len.max(1) as f64,
            judged_separations: judged.separations,
        },
    }
}
