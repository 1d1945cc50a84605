//! The part of a growing run worth plotting: its trace up to where the position first leaves
//! the scale of the run's start by [`CLIP_FACTOR`].
//!
//! A run judged [`Outcome::Growing`] may grow until the simulator's bound ([`super::BLOW_UP`],
//! 1e100): plotted whole, its first part is a flat line under an axis that reaches 1e100. The
//! trace of such a run is therefore cut at the first recorded sample where
//! |x| > [`CLIP_FACTOR`] · [`start_scale`], after recording it again at full resolution up to
//! there. Runs of any other outcome (decaying, limit cycle, separated, undecided) are never
//! cut: the whole trace is what their verdict describes.

use serde::Serialize;

use super::{Config, HumanForce, Outcome, RunResult, Simulator, Trace, simulate};
use crate::error::Result;

/// A growing run's trace is cut where |x| first exceeds this multiple of the scale of its start
/// ([`start_scale`]): 10³ ≈ e^6.9, about seven e-foldings of growth.
pub const CLIP_FACTOR: f64 = 1e3;

/// Where the trace of a growing run was cut (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TraceClip {
    /// The first recorded sample k with |x| above `threshold`; the kept trace ends before it.
    pub sample: usize,
    /// Its time kT in s.
    pub time: f64,
    /// Its position x in m.
    pub position: f64,
    /// The threshold [`CLIP_FACTOR`] · `start_scale` in m.
    pub threshold: f64,
    /// The scale of the run's start in m ([`start_scale`]).
    pub start_scale: f64,
    /// [`CLIP_FACTOR`].
    pub factor: f64,
}

/// The displacement scale of a run's start in m: the largest of |x(0)|, the wall position
/// |x_w|, the distance |ẋ(0)|·T the initial velocity covers in one sample, and the distance
/// |F_H(0)|·T²/m the initial human push moves the reference mass m in one sample (Table I's
/// force unit k_u = m/T²). Zero when the run starts at rest at x = 0 with no push.
pub fn start_scale(config: &Config) -> f64 {
    let push = match &config.human {
        HumanForce::Constant(f) => *f,
        HumanForce::Samples(v) => v.first().copied().unwrap_or(0.0),
        HumanForce::Function(f) => f(0.0),
    };
    let period = config.model.period();
    [
        config.initial.position,
        config.effects.wall_position,
        config.initial.velocity * period,
        push * config.model.force_scale(),
    ]
    .into_iter()
    .map(f64::abs)
    .filter(|v| v.is_finite())
    .fold(0.0, f64::max)
}

/// The first row whose |x| is above `threshold` (a non-finite position counts as above).
fn first_beyond(position: &[f64], threshold: f64) -> Option<usize> {
    position
        .iter()
        .position(|x| !x.is_finite() || x.abs() > threshold)
}

/// The trace of the same run recorded again over its first `samples` samples, with
/// `config.trace_rows` rows at most, and its stride.
fn record_again(config: &Config, samples: usize) -> Result<(Trace, usize)> {
    let mut again = config.clone();
    again.samples = samples.max(2);
    again.max_samples = again.samples;
    let mut sim = Simulator::new(&again)?;
    sim.advance(again.samples)?;
    let stride = sim.trace_stride();
    Ok((sim.take_trace().unwrap_or_default(), stride))
}

/// Keeps the first `rows` rows of every column.
fn truncate(trace: &mut Trace, rows: usize) {
    for col in [
        &mut trace.time,
        &mut trace.position,
        &mut trace.velocity,
        &mut trace.wall_force,
        &mut trace.human_force,
    ] {
        col.truncate(rows);
    }
}

/// The kept part of a growing run's trace ([`clip_growing_trace`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ClippedTrace {
    /// The trace before the cut.
    pub trace: Trace,
    /// Its rows are every `stride`-th sample.
    pub stride: usize,
    /// Where it was cut.
    pub clip: TraceClip,
}

/// The trace `trace` of `run` (a run of `config`; rows every `run.trace_stride` samples) cut before the first sample where |x| exceeds
/// [`CLIP_FACTOR`] · [`start_scale`], if the run is [`Outcome::Growing`] (module
/// documentation): the run is recorded again up to there with `config.trace_rows` rows, so
/// the kept part is as finely sampled as a whole run of that length. None for a run that is
/// not growing, starts at scale 0 or never exceeds the threshold.
pub fn clip_growing_trace(
    config: &Config,
    run: &RunResult,
    coarse: &Trace,
) -> Result<Option<ClippedTrace>> {
    let scale = start_scale(config);
    let threshold = CLIP_FACTOR * scale;
    if run.verdict.outcome != Outcome::Growing || scale <= 0.0 {
        return Ok(None);
    }
    let Some(row) = first_beyond(&coarse.position, threshold) else {
        return Ok(None);
    };
    let mut stride = run.trace_stride.max(1);
    let mut trace = coarse.clone();
    if stride > 1 {
        let (fine, fine_stride) = record_again(config, row * stride + 1)?;
        if first_beyond(&fine.position, threshold).is_some() {
            (trace, stride) = (fine, fine_stride.max(1));
        }
    }
    let Some(row) = first_beyond(&trace.position, threshold) else {
        return Ok(None);
    };
    let clip = TraceClip {
        sample: row * stride,
        time: trace.time[row],
        position: trace.position[row],
        threshold,
        start_scale: scale,
        factor: CLIP_FACTOR,
    };
    truncate(&mut trace, row);
    Ok(Some(ClippedTrace {
        trace,
        stride,
        clip,
    }))
}

/// Runs [`simulate`] and replaces the trace of a growing run by its part before the first
/// sample where |x| exceeds [`CLIP_FACTOR`] · [`start_scale`] ([`clip_growing_trace`]), with
/// `trace_stride` that recording's. The verdict and every other field are those of the whole
/// run. Returns where the trace was cut, or None if it was kept whole.
pub fn simulate_clipped(config: &Config) -> Result<(RunResult, Option<TraceClip>)> {
    let mut run = simulate(config)?;
    let clipped = match &run.trace {
        Some(t) => clip_growing_trace(config, &run, t)?,
        None => None,
    };
    Ok(match clipped {
        Some(c) => {
            run.trace = Some(c.trace);
            run.trace_stride = c.stride;
            (run, Some(c.clip))
        }
        None => (run, None),
    })
}
