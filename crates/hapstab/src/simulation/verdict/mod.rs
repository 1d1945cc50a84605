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
//!
//! # Where the code is
//!
//! The thresholds are here; the classifier's inputs in `facts`, the running statistics of a
//! run in `run_log`, the verdict and its evidence in `outcome`, the judged window and the trend of
//! its envelope in `tail`, and the steps above in `judge`.

use std::f64::consts::LN_2;

mod facts;
mod judge;
mod outcome;
mod run_log;
mod tail;

pub use facts::{LinearReference, LoopFacts, SampleFacts};
pub use judge::judge;
pub use outcome::{ContactSummary, LimitCycle, Outcome, RunVerdict};
pub use run_log::RunLog;

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
