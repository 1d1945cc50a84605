//! Steady-state verdicts of a simulated run: `decaying`, `limit_cycle`, `growing`,
//! `separated` (the device left a unilateral wall for good) or `undecided`.
//!
//! # What is judged
//!
//! A verdict is a claim about the steady state, so it is drawn from the *judged window*, the
//! second half of the run, and only once that window has settled; until then the driver
//! ([`super::simulate`]) extends the run, and at its horizon it reports `undecided` with the
//! reason. Nothing here knows the plant: the simulator feeds one [`SampleFacts`] per sample
//! into a [`RunLog`], and the loop is described by [`LoopFacts`] (which nonlinear effects are
//! configured, and the spectral radius of the loop while the wall acts linearly, Section V).
//!
//! The log keeps blocks of consecutive samples (at most [`MAX_BLOCKS`]; neighbours merge as
//! the run grows, so memory is bounded): extremes of position and velocity, upward velocity
//! crossings, contact events and how many samples obeyed the linear bilateral wall law. The
//! judged window is split into [`JUDGE_WINDOWS`] windows; the *envelope* of a window is the
//! half-range of the velocity in it (insensitive to an offset such as the equilibrium under a
//! push), and a least-squares fit of the log-envelope gives the growth rate over the whole
//! judged window and over each half.
//!
//! # Steps
//!
//! 1. A run that blew up is `growing`.
//! 2. A unilateral wall that the device did not touch during the whole judged window:
//!    `separated`, unless its closest approach to the wall is still increasing.
//! 3. A *linear window* (no friction or quantization, every judged sample under the linear
//!    bilateral wall law, e.g. a unilateral wall that stays in contact): a steady trend that
//!    changes the envelope by at least [`TREND_LOG_CHANGE`] decides `growing` or `decaying`,
//!    but only if it agrees with the spectral radius of the analysis (Section V); otherwise the
//!    dominant mode has not emerged yet and the window is not settled. Growth that contact loss
//!    or a force limit will bound later is not a steady state either.
//! 4. Otherwise (nonlinear): `decaying` only once the envelope has fallen below
//!    [`DECAY_FLOOR`] of its peak (until then quantization, friction or contact may still
//!    sustain a small oscillation); `limit_cycle` when envelope, amplitude, offset and period are
//!    steady over the windows; `growing` when steady growth cannot be bounded, or when the device
//!    moves on without oscillating and without slowing down.

use std::f64::consts::LN_2;

use serde::Serialize;

use crate::stability::Verdict as LinearVerdict;

/// Windows the judged window is split into: enough for a trend and its consistency over
/// the two halves (4 points each), few enough that each window spans several cycles.
pub const JUDGE_WINDOWS: usize = 8;
/// Blocks the requested run is first divided into: 64 per judging window of the first check.
const INITIAL_BLOCKS: usize = 512;
/// Shortest block in samples, so that a block's velocity range means something.
const MIN_BLOCK_LEN: usize = 4;
/// Blocks merged to measure the run's peak envelope (the reference of [`DECAY_FLOOR`]):
/// a group spans 1/64 of the first check, long enough to hold a swing of the motion.
const PEAK_GROUP: usize = 8;
/// Most blocks a log keeps; when full, neighbours merge (the block length doubles), so a log
/// takes about 100 kB whatever the run length.
pub const MAX_BLOCKS: usize = 1024;
/// A trend is decisive when the fitted envelope changes by at least this (a factor 4) over the
/// judged window: far beyond the few per cent that the phase of a window adds.
pub const TREND_LOG_CHANGE: f64 = 2.0 * LN_2;
/// The envelope of a limit cycle changes by less than this (about 5 %) over the judged window.
pub const CYCLE_LOG_CHANGE: f64 = 0.05;
/// Envelope, peak-to-peak amplitude and offset of a limit cycle vary by less than this
/// fraction between the judging windows (each window spans at least two cycles, so a settled
/// cycle repeats its extremes in every window).
pub const CYCLE_SPREAD: f64 = 0.1;
/// The cycle period measured in each judging window varies by less than this fraction.
pub const PERIOD_SPREAD: f64 = 0.1;
/// Each judging window must span at least this many cycles for a limit cycle to be judged.
pub const MIN_CYCLES_PER_WINDOW: usize = 2;
/// A trend is steady when the growth rates fitted on the two halves of the judged window
/// differ by less than this fraction of the overall rate (plus [`RATE_NOISE`]).
pub const RATE_AGREEMENT: f64 = 0.5;
/// Log-envelope noise (nepers) allowed between the two halves' predictions: the envelope of a
/// window depends on where the extremes fall in it by up to about 20 %.
pub const RATE_NOISE: f64 = 0.25;
/// Motion below this fraction of its peak envelope has decayed: nine orders of magnitude
/// below the peak, far below any encoder step or friction-limited motion of the same run.
pub const DECAY_FLOOR: f64 = 1e-9;
/// A decayed run's growth is fitted below this fraction of its peak envelope: the first two
/// decades after the peak hold the transient of the faster modes.
const DECAY_FIT_TOP: f64 = 1e-2;
/// Fewest blocks for that fit (two halves of two points).
const MIN_DECAY_POINTS: usize = 4;
/// The contact state before the first sample.
const NO_SAMPLE: u8 = 2;
/// Hysteresis of the velocity crossings, as a fraction of the recent envelope: ignores
/// ripple on a slow swing while counting every cycle of a settled oscillation.
const HYSTERESIS: f64 = 0.1;
/// Closed blocks whose envelope sets the hysteresis.
const HYSTERESIS_BLOCKS: usize = 8;
/// Relative tolerance on "not approaching the wall": rounding of the position, not motion.
const APPROACH_TOLERANCE: f64 = 1e-9;
/// A window is monotonic when its net displacement equals its range to this fraction.
const MONOTONE_TOLERANCE: f64 = 1e-9;

/// The verdict of a run on its steady state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// The motion dies out (linear: spectral radius < 1, Section V).
    Decaying,
    /// A sustained oscillation whose amplitude and period have settled.
    LimitCycle,
    /// The motion grows without bound (linear: spectral radius > 1).
    Growing,
    /// The device left a unilateral wall for good: the run says nothing about the wall.
    Separated,
    /// The run has not settled within its horizon; the reason says why.
    Undecided,
}

impl Outcome {
    /// The snake_case name used in JSON.
    pub fn as_str(&self) -> &'static str {
        match self {
            Outcome::Decaying => "decaying",
            Outcome::LimitCycle => "limit_cycle",
            Outcome::Growing => "growing",
            Outcome::Separated => "separated",
            Outcome::Undecided => "undecided",
        }
    }
}

/// The analysis of the loop while the wall acts linearly (Section V), as a reference for
/// linear windows.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LinearReference {
    /// Spectral radius of the closed loop.
    pub spectral_radius: f64,
    /// Stable, marginal or unstable.
    pub verdict: LinearVerdict,
}

/// What the classifier needs to know about the loop, independent of its plant model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LoopFacts {
    /// The wall acts only in contact (unilateral): contact may be lost.
    pub contact_can_be_lost: bool,
    /// The wall force is limited (saturation).
    pub force_limited: bool,
    /// Friction or quantization is configured: the loop is never linear.
    pub static_nonlinearity: bool,
    /// Encoder step q in m, to give amplitudes in counts.
    pub quantum: Option<f64>,
    /// Sampling period T in s, for frequencies.
    pub period: f64,
    /// The analysis of the loop in linear contact, if available.
    pub linear: Option<LinearReference>,
}

/// One sample as the classifier sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampleFacts {
    /// Position in m (positive into the wall).
    pub position: f64,
    /// Velocity in any fixed unit (only ratios and signs are used).
    pub velocity: f64,
    /// The wall acts on this sample (always true for a bilateral wall).
    pub in_contact: bool,
    /// The wall force equals the linear bilateral law on this sample (in contact, not clamped,
    /// not saturated).
    pub linear: bool,
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct Extremes {
    min: f64,
    max: f64,
}

impl Extremes {
    const EMPTY: Self = Self {
        min: f64::INFINITY,
        max: f64::NEG_INFINITY,
    };

    #[inline(always)]
    fn include(&mut self, v: f64) {
        self.min = self.min.min(v);
        self.max = self.max.max(v);
    }

    fn merge(self, o: Self) -> Self {
        Self {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    fn range(&self) -> f64 {
        if self.max >= self.min {
            self.max - self.min
        } else {
            0.0
        }
    }

    fn middle(&self) -> f64 {
        0.5 * (self.min + self.max)
    }
}

/// Count and first/last sample index of a kind of event.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Events {
    count: usize,
    first: usize,
    last: usize,
}

impl Events {
    #[inline(always)]
    fn add(&mut self, k: usize) {
        if self.count == 0 {
            self.first = k;
        }
        self.last = k;
        self.count += 1;
    }

    fn merge(self, o: Self) -> Self {
        match (self.count, o.count) {
            (0, _) => o,
            (_, 0) => self,
            _ => Self {
                count: self.count + o.count,
                first: self.first,
                last: o.last,
            },
        }
    }

    /// Mean interval between the events in samples (needs two).
    fn period(&self) -> Option<f64> {
        (self.count >= 2 && self.last > self.first)
            .then(|| (self.last - self.first) as f64 / (self.count - 1) as f64)
    }
}

/// Statistics of consecutive samples.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Block {
    start: usize,
    len: usize,
    position: Extremes,
    velocity: Extremes,
    first_position: f64,
    last_position: f64,
    contact_samples: usize,
    linear_samples: usize,
    crossings: Events,
    contacts: Events,
    separations: usize,
}

impl Block {
    fn empty(start: usize) -> Self {
        Self {
            start,
            len: 0,
            position: Extremes::EMPTY,
            velocity: Extremes::EMPTY,
            first_position: 0.0,
            last_position: 0.0,
            contact_samples: 0,
            linear_samples: 0,
            crossings: Events::default(),
            contacts: Events::default(),
            separations: 0,
        }
    }

    fn merge(self, o: Self) -> Self {
        Self {
            start: self.start,
            len: self.len + o.len,
            position: self.position.merge(o.position),
            velocity: self.velocity.merge(o.velocity),
            first_position: self.first_position,
            last_position: o.last_position,
            contact_samples: self.contact_samples + o.contact_samples,
            linear_samples: self.linear_samples + o.linear_samples,
            crossings: self.crossings.merge(o.crossings),
            contacts: self.contacts.merge(o.contacts),
            separations: self.separations + o.separations,
        }
    }

    fn merge_all(blocks: &[Block]) -> Block {
        match blocks.split_first() {
            Some((first, rest)) => rest.iter().fold(*first, |a, b| a.merge(*b)),
            None => Block::empty(0),
        }
    }

    /// Half-range of the velocity.
    fn envelope(&self) -> f64 {
        0.5 * self.velocity.range()
    }

    fn centre(&self) -> f64 {
        self.start as f64 + 0.5 * self.len as f64
    }
}

/// The running statistics of a run (see the module documentation): fed one sample at a
/// time, allocation-free except when a block closes.
#[derive(Debug, Clone)]
pub struct RunLog {
    block_len: usize,
    blocks: Vec<Block>,
    current: Block,
    samples: usize,
    /// Contact on the previous sample: 0 or 1, [`NO_SAMPLE`] before the first sample.
    previous_contact: u8,
    below: bool,
    hysteresis: f64,
    contacts: usize,
    separations: usize,
    last_separation: Option<usize>,
}

impl RunLog {
    /// An empty log for a run planned to last `planned` samples (it may run longer).
    pub fn new(planned: usize) -> Self {
        Self {
            block_len: planned.div_ceil(INITIAL_BLOCKS).max(MIN_BLOCK_LEN),
            blocks: Vec::with_capacity(MAX_BLOCKS),
            current: Block::empty(0),
            samples: 0,
            previous_contact: NO_SAMPLE,
            below: false,
            hysteresis: 0.0,
            contacts: 0,
            separations: 0,
            last_separation: None,
        }
    }

    /// Samples logged so far.
    pub fn samples(&self) -> usize {
        self.samples
    }

    /// Logs the next sample.
    #[inline(always)]
    pub fn push(&mut self, s: SampleFacts) {
        let k = self.samples;
        self.samples += 1;
        let crossing = if s.velocity < -self.hysteresis {
            self.below = true;
            false
        } else if s.velocity > self.hysteresis && self.below {
            self.below = false;
            true
        } else {
            false
        };
        let contact = u8::from(s.in_contact);
        let event = contact != self.previous_contact && self.previous_contact != NO_SAMPLE;
        self.previous_contact = contact;
        let b = &mut self.current;
        if b.len == 0 {
            b.first_position = s.position;
        }
        b.len += 1;
        b.position.include(s.position);
        b.velocity.include(s.velocity);
        b.last_position = s.position;
        b.contact_samples += usize::from(s.in_contact);
        b.linear_samples += usize::from(s.linear);
        if crossing {
            b.crossings.add(k);
        }
        let full = b.len == self.block_len;
        if event {
            self.contact_event(k, s.in_contact);
        }
        if full {
            self.close_block();
        }
    }

    #[cold]
    #[inline(never)]
    fn contact_event(&mut self, k: usize, in_contact: bool) {
        let b = &mut self.current;
        if in_contact {
            self.contacts += 1;
            b.contacts.add(k);
        } else {
            self.separations += 1;
            b.separations += 1;
            self.last_separation = Some(k);
        }
    }

    #[cold]
    #[inline(never)]
    fn close_block(&mut self) {
        self.blocks.push(self.current);
        self.current = Block::empty(self.samples);
        let recent = &self.blocks[self.blocks.len().saturating_sub(HYSTERESIS_BLOCKS)..];
        self.hysteresis = HYSTERESIS * recent.iter().map(Block::envelope).fold(0.0, f64::max);
        if self.blocks.len() == MAX_BLOCKS {
            self.blocks = self.blocks.chunks(2).map(Block::merge_all).collect();
            self.block_len *= 2;
        }
    }

    /// The closed blocks and the current one (if not empty).
    fn all_blocks(&self) -> Vec<Block> {
        let mut v = self.blocks.clone();
        if self.current.len > 0 {
            v.push(self.current);
        }
        v
    }
}

/// Contact events of a run (a bilateral wall is always in contact).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactSummary {
    /// Times the wall started acting again after a separation.
    pub contacts: usize,
    /// Times the device left the wall.
    pub separations: usize,
    /// The wall acts on the last sample.
    pub in_contact_at_end: bool,
    /// Sample index of the last separation.
    pub last_separation_sample: Option<usize>,
    /// Share of the judged window in contact (0 to 1).
    pub judged_contact_fraction: f64,
    /// Separations within the judged window.
    pub judged_separations: usize,
}

/// A settled limit cycle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LimitCycle {
    /// Peak-to-peak position amplitude over the judged window in m.
    pub peak_to_peak: f64,
    /// The same in encoder counts (peak-to-peak / q), when quantized.
    pub counts: Option<f64>,
    /// Period in samples.
    pub period_samples: f64,
    /// Frequency in Hz (1 / (period · T)).
    pub frequency_hz: f64,
    /// Cycles in the judged window.
    pub cycles: f64,
    /// The device loses and regains contact with a unilateral wall every cycle.
    pub bouncing: bool,
}

/// The verdict of a run with the evidence behind it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunVerdict {
    /// decaying | limit_cycle | growing | separated | undecided.
    pub outcome: Outcome,
    /// Why: what settled, or why the run could not decide.
    pub reason: String,
    /// First sample of the judged window.
    pub judged_from_sample: usize,
    /// One past the last sample of the judged window.
    pub judged_to_sample: usize,
    /// The wall law was linear (and no friction or quantization configured) over the
    /// judged window, so the verdict must agree with the analysis (Section V).
    pub linear_window: bool,
    /// Envelope growth factor per sample fitted on the run (null for limit cycles and
    /// separations, and when nothing could be fitted).
    pub measured_growth_per_sample: Option<f64>,
    /// Spectral radius of the loop in linear contact (Section V), beside the measurement.
    pub spectral_radius: Option<f64>,
    /// The analysis' verdict for the loop in linear contact.
    pub linear_verdict: Option<LinearVerdict>,
    /// Amplitude and frequency of a settled limit cycle.
    pub limit_cycle: Option<LimitCycle>,
    /// Contact events.
    pub contact: ContactSummary,
}

/// The judged window split into windows.
struct Tail {
    from: usize,
    to: usize,
    windows: Vec<Block>,
    whole: Block,
    /// Largest block envelope of the whole run.
    peak: f64,
}

impl Tail {
    fn of(blocks: &[Block], to: usize) -> Option<Tail> {
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

    fn span(&self) -> f64 {
        (self.to - self.from) as f64
    }

    fn floor(&self) -> f64 {
        DECAY_FLOOR * self.peak
    }

    fn linear(&self, facts: &LoopFacts) -> bool {
        !facts.static_nonlinearity && self.whole.linear_samples == self.whole.len
    }
}

/// Least-squares slope of y against x.
fn slope(points: &[(f64, f64)]) -> Option<f64> {
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
struct Fit {
    rate: f64,
    first: f64,
    second: f64,
}

impl Fit {
    /// Fits every window; None if the envelope of some window is zero (the motion stopped
    /// there) or not finite.
    fn of(tail: &Tail) -> Option<Fit> {
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
    fn steady(&self, span: f64) -> bool {
        (self.first - self.second).abs()
            <= RATE_AGREEMENT * self.rate.abs() + RATE_NOISE / (0.5 * span)
    }
}

/// Largest over smallest, minus one (0 for equal values; infinite if one is zero).
fn spread(values: impl Iterator<Item = f64>) -> f64 {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0_f64), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if hi == 0.0 { 0.0 } else { hi / lo - 1.0 }
}

/// The envelope's behaviour over the judged window.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Trend {
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

fn trend(tail: &Tail, fit: Option<Fit>) -> Trend {
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
