//! The answer of one simulated run, as `hapstab simulate --json` and the explorer's
//! `/api/simulate` give it: the run's verdict ([`RunResult`]) in time units, the loop and its
//! wall, and the run's setting (effects, human push, initial state) under `input`. The
//! command line adds the files it wrote, the explorer the decimated trace.

use serde::Serialize;

use crate::loop_spec::LoopInput;
use crate::paper::Normalized;
use crate::simulation::{Config, Effects, HumanForce, Initial, RunResult, SimModel};

/// The inputs of a simulated run: the loop and its wall, the nonlinear effects, the human's
/// push and the initial state.
#[derive(Debug, Clone, Serialize)]
pub struct SimulationInput {
    /// The loop and its wall (the form a loop file takes).
    #[serde(flatten)]
    pub lp: LoopInput,
    /// Contact mode, wall position, friction, quantization, saturation.
    pub effects: Effects,
    /// The constant human push F_H in N (positive into the wall); None for a force profile.
    pub human_force: Option<f64>,
    /// Position x(0) in m and velocity ẋ(0) in m/s.
    pub initial: Initial,
}

/// One simulated run with its inputs.
#[derive(Debug, Clone, Serialize)]
pub struct SimulationAnswer {
    /// The library's result: outcome, reason, evidence, run length (samples).
    #[serde(flatten)]
    pub run: RunResult,
    /// Simulated time: s, or samples for normalized input.
    pub duration: f64,
    /// Start of the judged window, in the time unit of `duration`.
    pub judged_from: f64,
    /// End of the judged window, in the time unit of `duration`.
    pub judged_to: f64,
    /// `physical` (s, m, N) or `normalized` (samples and the units of Table I).
    pub units: &'static str,
    /// The paper's loop: its effective mass m in kg (1 for normalized input).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
    /// Sampling period T in s (1 for normalized input).
    pub period: f64,
    /// The paper's loop given in physical units: its point in Table I (α, β, γ, δ, d).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub normalized: Option<Normalized>,
    /// The loop, its wall and the run's setting as given.
    pub input: SimulationInput,
}

impl SimulationAnswer {
    /// The answer of `run`, simulated with `cfg`, for the loop and wall `lp`; `normalized`
    /// when the user gave the paper's normalized input (then time is in samples).
    pub fn new(run: RunResult, cfg: &Config, lp: LoopInput, normalized: bool) -> Self {
        let period = cfg.model.period();
        let paper = match &cfg.model {
            SimModel::Paper(m) => Some(m),
            SimModel::Loop(_) => None,
        };
        let time = |k: usize| k as f64 * period;
        Self {
            duration: time(run.samples),
            judged_from: time(run.verdict.judged_from_sample),
            judged_to: time(run.verdict.judged_to_sample),
            units: if normalized { "normalized" } else { "physical" },
            mass: paper.map(|m| m.mass),
            period,
            normalized: paper.filter(|_| !normalized).map(|m| m.params),
            input: SimulationInput {
                lp,
                effects: cfg.effects,
                human_force: match cfg.human {
                    HumanForce::Constant(f) => Some(f),
                    _ => None,
                },
                initial: cfg.initial,
            },
            run,
        }
    }
}
