//! The verdict of a run on its steady state and the evidence behind it: the outcome, a
//! settled limit cycle, the contact events.

use serde::Serialize;

use crate::stability::Verdict as LinearVerdict;

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
