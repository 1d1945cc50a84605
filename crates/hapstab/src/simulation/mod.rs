//! Time-domain simulation of the sampled-data loop of Fig. 3 (Section II), including the
//! nonlinear effects that the paper leaves to future work (Remark 1 and Section IX): a
//! unilateral wall, Coulomb and static friction, position-sensor quantization and actuator
//! force saturation.
//!
//! # Model
//!
//! The continuous plant m ẍ + b ẋ + k x = F (eq. 1; the arm's spring k_H pulls toward the
//! origin, the hand's rest position) is stepped *exactly* from sample to sample with the
//! zero-order-hold matrices of [`DiscretePlant`] (Section III, eq. 2–6), in the normalized
//! state (x, T·ẋ):
//!
//! ```text
//! (x, Tẋ)[k+1] = Φ (x, Tẋ)[k] + Γ · u[k],      u[k] = (T²/m) · F[k]   (Table I),
//! F[k] = F_H[k] − F_wall[k] − F_friction,
//! F_wall[k] = K (y[k−d] − x_w) + B (y[k−d] − y[k−d−1]) / T,
//! ```
//!
//! where y is the sampled (optionally quantized) position, d the delay in samples and x_w
//! the wall position. In normalized units (T²/m)·F_wall = α (y[k−d] − x_w) + β (y[k−d] −
//! y[k−d−1]), so the linear bilateral loop has exactly the characteristic polynomial
//! p(z) = z^{d+1} D(z) + N(z)((α + β) z − β) of eq. (9) (see [`crate::closed_loop`]).
//! Positions are in metres, velocities in m/s and forces in newtons throughout the API;
//! internally all forces are scaled by T²/m.
//!
//! # Sign conventions
//!
//! Positive x points *into* the wall. The wall force F_wall is the force the wall exerts in
//! the −x direction (a positive F_wall pushes the device out of the wall); the human force
//! F_H is positive when pushing into the wall. A unilateral wall ([`Contact::Unilateral`])
//! acts only while the sensed, delayed position penetrates it, y[k−d] > x_w.
//!
//! # Human force
//!
//! F_H is held constant over each sample (zero-order hold, as the F* of eq. 7): a constant,
//! a per-sample profile (the last value is held after the profile ends) or a function of
//! time t = kT evaluated at the samples.
//!
//! # Friction (stick–slip within exact ZOH stepping)
//!
//! Coulomb friction F_c opposes the velocity, static friction F_s ≥ F_c holds the device at
//! rest. Friction is not held at its sampled value: within a sample the applied force is
//! constant, so the motion between velocity reversals is an exact ZOH step with the
//! constant input F − F_c·sgn(ẋ). When the velocity at the end of a (sub)step has changed
//! sign, the reversal instant τ* ∈ (0, 1) is located by bisection on the exact sub-step
//! solution (the plant over τT is the ZOH plant with γτ², δτ, see [`DiscretePlant`]). At
//! τ* the velocity is zero and the *stick rule* applies: the device sticks for the rest of
//! the sample if the non-friction force |F − k x| ≤ F_s (the damper force is zero at rest);
//! otherwise it slips on in the direction of that force with friction −F_c·sgn. A stuck
//! device stays exactly at rest over a sample iff |F − k x| ≤ F_s at the sample instant,
//! since F and x are then constant over the sample. Two reversals within one sample with
//! equal end signs are missed; that needs a plant half-period shorter than one sample
//! (γ > π², beyond the Nyquist frequency of Section VIII).
//!
//! # Verdict
//!
//! See [`simulate`] and [`verdict`]: the run is judged on its second half once that has
//! settled; until then it is extended (doubling its length) up to a horizon, where it is
//! reported undecided with the reason. While the wall acts linearly over the judged window
//! the verdict must agree with the spectral radius of the analysis (Section V).

use std::fmt;
use std::sync::Arc;

use serde::Serialize;

use crate::error::{Error, Result, finite, non_negative, positive};
use crate::params::{Normalized, Physical, PlantParams};
use crate::plant::DiscretePlant;
use crate::stability::Analysis;

mod boundary;
mod growth;
pub mod verdict;

pub use boundary::{
    BoundarySearch, EmpiricalPoint, InconclusiveRun, MAX_BISECTION_STEPS, MIN_REL_TOLERANCE,
    StableWhen, empirical_boundary, exact_alpha_limit,
};
pub use growth::{LinearGrowth, linear_growth};
pub use verdict::{
    ContactSummary, LimitCycle, LinearReference, LoopFacts, Outcome, RunLog, RunVerdict,
    SampleFacts,
};

/// A position or velocity beyond this magnitude (or a non-finite one) ends a run as
/// [`Outcome::Growing`]; it is far beyond any physical value and far below overflow.
pub const BLOW_UP: f64 = 1e100;

/// The linear part of the loop of Fig. 3: the normalized parameters of Table I plus the
/// effective mass m and period T that convert forces (u = T²F/m) and time.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Model {
    /// α, β, γ, δ and d (Table I).
    pub params: Normalized,
    /// Effective mass m in kg (eq. 1).
    pub mass: f64,
    /// Sampling period T in s.
    pub period: f64,
}

impl Model {
    /// Bundles normalized parameters with the mass m (kg) and period T (s) used to convert
    /// forces and time (Table I).
    pub fn new(params: Normalized, mass: f64, period: f64) -> Result<Self> {
        let params = params.validated()?;
        Ok(Self {
            params,
            mass: positive("mass m", mass)?,
            period: positive("sampling period T", period)?,
        })
    }

    /// The model of a physical description (eq. 1 and Table I).
    pub fn from_physical(physical: &Physical) -> Result<Self> {
        let physical = Physical::new(physical.plant, physical.wall, physical.sampling)?;
        Self::new(
            physical.normalized()?,
            physical.plant.mass,
            physical.sampling.period,
        )
    }

    /// Normalized units: m = 1 kg and T = 1 s, so forces are normalized forces T²F/m (in m)
    /// and time is counted in samples (Table I).
    pub fn unit(params: Normalized) -> Result<Self> {
        Self::new(params, 1.0, 1.0)
    }

    /// The same plant and sampling with another wall (α, β) (Table I).
    pub fn with_wall(&self, alpha: f64, beta: f64) -> Result<Self> {
        let mut params = self.params;
        params.alpha = finite("alpha", alpha)?;
        params.beta = finite("beta", beta)?;
        Self::new(params, self.mass, self.period)
    }

    /// The force scale T²/m (Table I): u = (T²/m)·F.
    pub fn force_scale(&self) -> f64 {
        self.period * self.period / self.mass
    }
}

/// How the virtual wall touches the device (Remark 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Contact {
    /// The paper's bilateral spring-damper: F_wall = K (y − x_w) + B ẏ everywhere.
    Bilateral,
    /// Force only while penetrating (y[k−d] > x_w); the damper may pull while the device
    /// is leaving the wall.
    Unilateral,
    /// As [`Contact::Unilateral`], and the wall never pulls: F_wall = max(0, ·).
    UnilateralNoPull,
}

/// Coulomb and static friction of the device (Section IX's "static friction").
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Friction {
    /// Coulomb (sliding) friction force F_c in N (>= 0).
    pub coulomb: f64,
    /// Static (breakaway) friction force F_s in N (>= F_c).
    pub stiction: f64,
}

/// The optional nonlinear effects of Section II's list ("static friction, or quantization
/// and saturation of sensors and actuators") and Remark 1's unilateral wall.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Effects {
    /// Bilateral or unilateral wall.
    pub contact: Contact,
    /// Wall position x_w in m (the spring's rest position; also the unilateral surface).
    pub wall_position: f64,
    /// Device friction, if any.
    pub friction: Option<Friction>,
    /// Encoder resolution q in m (> 0): the wall sees round(x/q)·q.
    pub quantization: Option<f64>,
    /// Actuator limit F_max in N (> 0): |F_wall| ≤ F_max.
    pub saturation: Option<f64>,
}

impl Effects {
    /// The paper's linear bilateral wall at the origin, no nonlinear effect.
    pub const LINEAR: Effects = Effects {
        contact: Contact::Bilateral,
        wall_position: 0.0,
        friction: None,
        quantization: None,
        saturation: None,
    };

    /// True for the linear bilateral loop analysed in Sections III–V.
    pub fn is_linear(&self) -> bool {
        self.contact == Contact::Bilateral
            && self.friction.is_none()
            && self.quantization.is_none()
            && self.saturation.is_none()
    }

    /// Checks every value (finite wall position, q > 0, F_max > 0, 0 <= F_c <= F_s).
    pub fn validate(&self) -> Result<()> {
        finite("wall position x_w", self.wall_position)?;
        if let Some(q) = self.quantization {
            positive("quantization q", q)?;
        }
        if let Some(f) = self.saturation {
            positive("saturation F_max", f)?;
        }
        if let Some(fr) = self.friction {
            non_negative("Coulomb friction F_c", fr.coulomb)?;
            non_negative("static friction F_s", fr.stiction)?;
            if fr.stiction < fr.coulomb {
                return Err(Error::OutOfRange {
                    name: "static friction F_s",
                    value: fr.stiction,
                    range: "[F_c, inf)",
                });
            }
        }
        Ok(())
    }
}

impl Default for Effects {
    fn default() -> Self {
        Self::LINEAR
    }
}

/// The human operator's active force F_H in N, held over each sample (F* of eq. 7).
#[derive(Clone)]
pub enum HumanForce {
    /// A constant push (positive into the wall).
    Constant(f64),
    /// One value per sample; the last value is held after the profile ends (an empty
    /// profile means zero force).
    Samples(Vec<f64>),
    /// A function of time t = kT in seconds, evaluated at each sample.
    Function(Arc<dyn Fn(f64) -> f64 + Send + Sync>),
}

impl HumanForce {
    /// Wraps a closure of time (s) returning force (N).
    pub fn function(f: impl Fn(f64) -> f64 + Send + Sync + 'static) -> Self {
        HumanForce::Function(Arc::new(f))
    }

    fn validate(&self) -> Result<()> {
        match self {
            HumanForce::Constant(f) => finite("human force F_H", *f).map(|_| ()),
            HumanForce::Samples(v) => v
                .iter()
                .try_for_each(|&f| finite("human force profile F_H[k]", f).map(|_| ())),
            HumanForce::Function(_) => Ok(()),
        }
    }
}

impl Default for HumanForce {
    fn default() -> Self {
        HumanForce::Constant(0.0)
    }
}

impl fmt::Debug for HumanForce {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            HumanForce::Constant(v) => write!(f, "Constant({v})"),
            HumanForce::Samples(v) => write!(f, "Samples(len {})", v.len()),
            HumanForce::Function(_) => write!(f, "Function(..)"),
        }
    }
}

/// The initial state. The sensor history before t = 0 (the delay line) is filled with the
/// sensed initial position, as if the device had rested there.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Default)]
pub struct Initial {
    /// Position x(0) in m.
    pub position: f64,
    /// Velocity ẋ(0) in m/s.
    pub velocity: f64,
}

/// Everything one run needs.
#[derive(Debug, Clone)]
pub struct Config {
    /// Linear loop (eq. 1, Table I).
    pub model: Model,
    /// Nonlinear effects.
    pub effects: Effects,
    /// Human push F_H.
    pub human: HumanForce,
    /// Initial state.
    pub initial: Initial,
    /// Samples to simulate before the first judgement (>= 2).
    pub samples: usize,
    /// The horizon: while the verdict has not settled, the run is extended (doubling) up to
    /// this many samples (>= `samples`).
    pub max_samples: usize,
    /// Most trace rows to keep; 0 records nothing. Rows are every n-th sample; when a run is
    /// extended, every other row is dropped and n doubles, so the trace never exceeds this.
    pub trace_rows: usize,
}

/// Default horizon of a run in samples (1000 s at T = 1 ms); a linear run takes about 10 ms
/// for it, and it lets a loop whose spectral radius is 1 ± 1e-5 change its envelope by e^5.
pub const DEFAULT_MAX_SAMPLES: usize = 1_000_000;

/// Largest number of trace rows a run may keep: 5 columns of 8 bytes, 80 MB.
pub const MAX_TRACE_ROWS: usize = 2_000_000;

impl Config {
    /// A linear bilateral run of `samples` samples from rest at the origin with no human
    /// force and no trace, extended up to [`DEFAULT_MAX_SAMPLES`] (or `samples`, if more)
    /// until its verdict settles.
    pub fn new(model: Model, samples: usize) -> Self {
        Self {
            model,
            effects: Effects::LINEAR,
            human: HumanForce::default(),
            initial: Initial::default(),
            samples,
            max_samples: samples.max(DEFAULT_MAX_SAMPLES),
            trace_rows: 0,
        }
    }

    /// Validates every field.
    pub fn validate(&self) -> Result<()> {
        Model::new(self.model.params, self.model.mass, self.model.period)?;
        self.effects.validate()?;
        self.human.validate()?;
        finite("initial position", self.initial.position)?;
        finite("initial velocity", self.initial.velocity)?;
        if self.samples < 2 {
            return Err(Error::OutOfRange {
                name: "samples",
                value: self.samples as f64,
                range: "[2, inf)",
            });
        }
        if self.max_samples < self.samples {
            return Err(Error::OutOfRange {
                name: "max_samples (the horizon)",
                value: self.max_samples as f64,
                range: "[samples, inf)",
            });
        }
        if self.trace_rows == 1 || self.trace_rows > MAX_TRACE_ROWS {
            return Err(Error::OutOfRange {
                name: "trace rows",
                value: self.trace_rows as f64,
                range: "0 or [2, 2e6]",
            });
        }
        Ok(())
    }

    /// What the verdict needs to know about this loop (see [`verdict`]), with the analysis of
    /// the bilateral loop (Section V) as the reference for linear windows.
    pub fn loop_facts(&self) -> LoopFacts {
        let e = &self.effects;
        let linear = Analysis::new(self.model.params)
            .ok()
            .map(|a| LinearReference {
                spectral_radius: a.spectral_radius,
                verdict: a.verdict,
            });
        LoopFacts {
            contact_can_be_lost: e.contact != Contact::Bilateral,
            force_limited: e.saturation.is_some(),
            static_nonlinearity: e.friction.is_some() || e.quantization.is_some(),
            quantum: e.quantization,
            period: self.model.period,
            linear,
        }
    }
}

/// The number of samples covering `seconds` at period T (rounded up), for `--duration`.
pub fn samples_for_duration(seconds: f64, period: f64) -> Result<usize> {
    positive("duration", seconds)?;
    positive("sampling period T", period)?;
    let n = (seconds / period).ceil();
    if n > 1e12 {
        return Err(Error::OutOfRange {
            name: "duration / T",
            value: n,
            range: "[1, 1e12]",
        });
    }
    Ok(n.max(2.0) as usize)
}

/// A recorded trajectory: one row per recorded sample k, values at t = kT; the forces are
/// those held over [kT, (k+1)T).
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct Trace {
    /// Time t = kT in s.
    pub time: Vec<f64>,
    /// Position x in m.
    pub position: Vec<f64>,
    /// Velocity ẋ in m/s.
    pub velocity: Vec<f64>,
    /// Wall force F_wall in N (positive pushes out of the wall).
    pub wall_force: Vec<f64>,
    /// Human force F_H in N.
    pub human_force: Vec<f64>,
}

/// The result of [`simulate`].
#[derive(Debug, Clone, Serialize)]
pub struct RunResult {
    /// The verdict with its evidence.
    #[serde(flatten)]
    pub verdict: RunVerdict,
    /// Samples actually simulated.
    pub samples: usize,
    /// Samples asked for before the first judgement.
    pub requested_samples: usize,
    /// The horizon the run could have been extended to.
    pub max_samples: usize,
    /// True if the run stopped early because |x| or |ẋ|·T exceeded [`BLOW_UP`].
    pub blown_up: bool,
    /// Position at the end in m.
    pub final_position: f64,
    /// Velocity at the end in m/s.
    pub final_velocity: f64,
    /// Trace rows are every n-th sample (0 without a trace).
    pub trace_stride: usize,
    /// The recorded trace, if `trace_rows > 0` (not serialized).
    #[serde(skip)]
    pub trace: Option<Trace>,
}

/// One-sample ZOH step of the normalized plant (Section III).
#[derive(Debug, Clone, Copy)]
struct Kernel {
    p00: f64,
    p01: f64,
    p10: f64,
    p11: f64,
    g0: f64,
    g1: f64,
}

impl Kernel {
    fn new(p: &DiscretePlant) -> Self {
        Self {
            p00: p.phi[0][0],
            p01: p.phi[0][1],
            p10: p.phi[1][0],
            p11: p.phi[1][1],
            g0: p.input[0],
            g1: p.input[1],
        }
    }

    #[inline(always)]
    fn step(&self, x: f64, w: f64, u: f64) -> (f64, f64) {
        (
            self.p00 * x + self.p01 * w + self.g0 * u,
            self.p10 * x + self.p11 * w + self.g1 * u,
        )
    }
}

/// Exact ZOH step over a fraction τ ∈ (0, 1] of a sample with constant normalized input u:
/// the plant over τT is the ZOH plant with (γτ², δτ) in the state (x, τTẋ).
fn sub_step(gamma: f64, delta: f64, x: f64, w: f64, u: f64, tau: f64) -> (f64, f64) {
    if tau <= 0.0 {
        return (x, w);
    }
    let p = DiscretePlant::from_params(PlantParams {
        gamma: gamma * tau * tau,
        delta: delta * tau,
    });
    let ws = tau * w;
    let us = tau * tau * u;
    let x1 = p.phi[0][0] * x + p.phi[0][1] * ws + p.input[0] * us;
    let w1 = p.phi[1][0] * x + p.phi[1][1] * ws + p.input[1] * us;
    (x1, w1 / tau)
}

/// The linear wall law in normalized units: α (y_d − x_w) + β (y_d − y_{d+1}).
#[inline(always)]
fn wall_linear(alpha: f64, beta: f64, xw: f64, yd: f64, yd1: f64) -> f64 {
    alpha * (yd - xw) + beta * (yd - yd1)
}

/// The wall's normalized force on one sample and how it relates to the linear law.
#[derive(Debug, Clone, Copy)]
struct WallSample {
    force: f64,
    in_contact: bool,
    linear: bool,
}

/// A trace that keeps at most `cap` rows: every `stride`-th sample from k = 0, thinned by
/// half (stride doubled) whenever it fills up, so an extended run never exceeds `cap`.
#[derive(Debug, Clone)]
struct Recorder {
    trace: Trace,
    cap: usize,
    stride: usize,
    next: usize,
}

impl Recorder {
    fn new(cap: usize, planned: usize) -> Self {
        let stride = planned.div_ceil(cap - 1).max(1);
        let rows = (planned / stride + 1).min(cap);
        Self {
            trace: Trace {
                time: Vec::with_capacity(rows),
                position: Vec::with_capacity(rows),
                velocity: Vec::with_capacity(rows),
                wall_force: Vec::with_capacity(rows),
                human_force: Vec::with_capacity(rows),
            },
            cap,
            stride,
            next: 0,
        }
    }

    fn push(&mut self, row: [f64; 5]) {
        let t = &mut self.trace;
        let cols = [
            &mut t.time,
            &mut t.position,
            &mut t.velocity,
            &mut t.wall_force,
            &mut t.human_force,
        ];
        for (col, v) in cols.into_iter().zip(row) {
            col.push(v);
        }
        self.next += self.stride;
        if self.trace.time.len() == self.cap {
            self.thin();
        }
    }

    /// Keeps every other row (those at multiples of the doubled stride).
    fn thin(&mut self) {
        let t = &mut self.trace;
        for col in [
            &mut t.time,
            &mut t.position,
            &mut t.velocity,
            &mut t.wall_force,
            &mut t.human_force,
        ] {
            let kept: Vec<f64> = col.iter().step_by(2).copied().collect();
            *col = kept;
        }
        self.stride *= 2;
        self.next = self.next.div_ceil(self.stride) * self.stride;
    }
}

/// The time-domain simulator of Fig. 3 (see the module documentation). Stepping is
/// allocation-free except when a block of the run's log closes: the delay line is a ring
/// buffer of sensed positions, the log ([`RunLog`]) and the trace have bounded size
/// whatever the run length.
#[derive(Debug, Clone)]
pub struct Simulator {
    kernel: Kernel,
    alpha: f64,
    beta: f64,
    gamma: f64,
    delta: f64,
    d: usize,
    scale: f64,
    period: f64,
    xw: f64,
    contact: Contact,
    quant: Option<f64>,
    u_max: f64,
    friction: Option<(f64, f64)>,
    linear: bool,
    human: HumanForce,
    k: usize,
    x: f64,
    w: f64,
    ring: Vec<f64>,
    mask: usize,
    log: RunLog,
    recorder: Option<Recorder>,
    blown_up: bool,
    friction_events: usize,
}

/// Most velocity reversals handled within one sample.
const MAX_EVENTS: usize = 16;

impl Simulator {
    /// Builds a simulator from a validated configuration (Fig. 3, Section III).
    pub fn new(config: &Config) -> Result<Self> {
        config.validate()?;
        let model = config.model;
        let p = model.params;
        let plant = DiscretePlant::from_params(p.plant());
        let scale = model.force_scale();
        let cap = (p.d + 2).next_power_of_two();
        let quant = config.effects.quantization;
        let x0 = config.initial.position;
        let y0 = match quant {
            Some(q) => (x0 / q).round() * q,
            None => x0,
        };
        Ok(Self {
            kernel: Kernel::new(&plant),
            alpha: p.alpha,
            beta: p.beta,
            gamma: p.gamma,
            delta: p.delta,
            d: p.d,
            scale,
            period: model.period,
            xw: config.effects.wall_position,
            contact: config.effects.contact,
            quant,
            u_max: config
                .effects
                .saturation
                .map_or(f64::INFINITY, |f| f * scale),
            friction: config
                .effects
                .friction
                .map(|f| (f.coulomb * scale, f.stiction * scale)),
            linear: config.effects.is_linear(),
            human: config.human.clone(),
            k: 0,
            x: x0,
            w: config.initial.velocity * model.period,
            ring: vec![y0; cap],
            mask: cap - 1,
            log: RunLog::new(config.samples),
            recorder: (config.trace_rows > 0)
                .then(|| Recorder::new(config.trace_rows, config.samples)),
            blown_up: false,
            friction_events: 0,
        })
    }

    /// Index k of the next sample.
    pub fn sample_index(&self) -> usize {
        self.k
    }

    /// Current time kT in s.
    pub fn time(&self) -> f64 {
        self.k as f64 * self.period
    }

    /// Current position x in m.
    pub fn position(&self) -> f64 {
        self.x
    }

    /// Current velocity ẋ in m/s.
    pub fn velocity(&self) -> f64 {
        self.w / self.period
    }

    /// True once the state exceeded [`BLOW_UP`] (the run has stopped).
    pub fn blown_up(&self) -> bool {
        self.blown_up
    }

    /// Number of friction velocity reversals located so far.
    pub fn friction_events(&self) -> usize {
        self.friction_events
    }

    /// The recorded trace so far, if recording.
    pub fn trace(&self) -> Option<&Trace> {
        self.recorder.as_ref().map(|r| &r.trace)
    }

    /// The run's log so far.
    pub fn log(&self) -> &RunLog {
        &self.log
    }

    /// Judges the run so far ([`verdict::judge`]); `last_chance` reports growth that contact
    /// loss or a force limit could still bound as growing.
    pub fn verdict(&self, facts: &LoopFacts, last_chance: bool) -> RunVerdict {
        verdict::judge(&self.log, facts, self.blown_up, last_chance)
    }

    /// Normalized human force at sample k (T²/m · F_H).
    #[inline(always)]
    fn human_at(&self, k: usize) -> Result<f64> {
        Ok(match &self.human {
            HumanForce::Constant(f) => *f * self.scale,
            HumanForce::Samples(v) => v.get(k).or(v.last()).copied().unwrap_or(0.0) * self.scale,
            HumanForce::Function(f) => {
                let v = f(k as f64 * self.period);
                finite("human force F_H(t)", v)? * self.scale
            }
        })
    }

    /// Simulates up to `n` more samples and returns how many were simulated (fewer only if
    /// the state blew up). Errors only if a human force function returns a non-finite value.
    pub fn advance(&mut self, n: usize) -> Result<usize> {
        if self.linear {
            self.run_loop::<true>(n)
        } else {
            self.run_loop::<false>(n)
        }
    }

    #[inline(always)]
    fn record(&mut self, x: f64, w: f64, uw: f64, uh: f64) {
        let (k, period, scale) = (self.k, self.period, self.scale);
        if let Some(r) = self.recorder.as_mut()
            && r.next == k
        {
            r.push([k as f64 * period, x, w / period, uw / scale, uh / scale]);
        }
    }

    fn run_loop<const LINEAR: bool>(&mut self, n: usize) -> Result<usize> {
        if self.blown_up {
            return Ok(0);
        }
        let recording = self.recorder.is_some();
        let (d, mask) = (self.d, self.mask);
        let (alpha, beta, xw) = (self.alpha, self.beta, self.xw);
        let kernel = self.kernel;
        let (mut x, mut w) = (self.x, self.w);
        let mut done = 0;
        while done < n {
            let k = self.k;
            // Sample and delay line: y[k] at (k + d + 1) & mask, y[k−d] at (k + 1) & mask.
            let y = if LINEAR { x } else { self.sense(x) };
            self.ring[(k + d + 1) & mask] = y;
            let yd = self.ring[(k + 1) & mask];
            let yd1 = self.ring[k & mask];
            let wall = if LINEAR {
                WallSample {
                    force: wall_linear(alpha, beta, xw, yd, yd1),
                    in_contact: true,
                    linear: true,
                }
            } else {
                self.wall(yd, yd1)
            };
            let uw = wall.force;
            let uh = self.human_at(k)?;
            if recording {
                self.record(x, w, uw, uh);
            }
            self.log.push(SampleFacts {
                position: x,
                velocity: w,
                in_contact: wall.in_contact,
                linear: wall.linear,
            });
            let ua = uh - uw;
            (x, w) = if LINEAR || self.friction.is_none() {
                kernel.step(x, w, ua)
            } else {
                self.friction_step(x, w, ua)
            };
            self.k += 1;
            done += 1;
            if !(x.abs() < BLOW_UP && w.abs() < BLOW_UP) {
                self.blown_up = true;
                break;
            }
        }
        self.x = x;
        self.w = w;
        Ok(done)
    }

    #[inline(always)]
    fn sense(&self, x: f64) -> f64 {
        match self.quant {
            Some(q) => (x / q).round() * q,
            None => x,
        }
    }

    /// The wall force on one sample: the linear law while the sensed, delayed position
    /// penetrates a unilateral wall (never pulling if so configured), limited to ±F_max.
    #[inline(always)]
    fn wall(&self, yd: f64, yd1: f64) -> WallSample {
        let law = wall_linear(self.alpha, self.beta, self.xw, yd, yd1);
        let in_contact = self.contact == Contact::Bilateral || yd > self.xw;
        let acting = match self.contact {
            _ if !in_contact => 0.0,
            Contact::UnilateralNoPull => law.max(0.0),
            _ => law,
        };
        let force = acting.clamp(-self.u_max, self.u_max);
        WallSample {
            force,
            in_contact,
            linear: force == law,
        }
    }

    /// One sample with Coulomb/static friction and exact location of velocity reversals
    /// (module documentation, "Friction").
    fn friction_step(&mut self, mut x: f64, mut w: f64, ua: f64) -> (f64, f64) {
        let (uc, us) = self.friction.unwrap_or((0.0, 0.0));
        let (g, dl) = (self.gamma, self.delta);
        let mut remaining = 1.0_f64;
        for event in 0..=MAX_EVENTS {
            let sign = if w == 0.0 {
                let net = ua - g * x;
                if net.abs() <= us {
                    return (x, 0.0); // stuck for the rest of the sample
                }
                net.signum()
            } else {
                w.signum()
            };
            let u = ua - uc * sign;
            let (x1, w1) = if remaining == 1.0 {
                self.kernel.step(x, w, u)
            } else {
                sub_step(g, dl, x, w, u, remaining)
            };
            if w1 * sign > 0.0 || event == MAX_EVENTS {
                return (x1, w1);
            }
            if w1 == 0.0 {
                self.friction_events += 1;
                return (x1, 0.0);
            }
            // Velocity reversal inside (0, remaining]: bisect on the exact solution.
            let (mut lo, mut hi) = (0.0_f64, remaining);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi || hi - lo <= 1e-15 {
                    break;
                }
                let (_, wm) = sub_step(g, dl, x, w, u, mid);
                if wm * sign > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let tau = 0.5 * (lo + hi);
            let (xs, _) = sub_step(g, dl, x, w, u, tau);
            self.friction_events += 1;
            x = xs;
            w = 0.0;
            remaining -= tau;
            if remaining <= 1e-15 {
                return (x, 0.0);
            }
        }
        (x, w)
    }
}

/// Runs one simulation of Fig. 3 and judges its steady state ([`verdict`]).
///
/// The run lasts `config.samples` samples; if its second half has not settled (see
/// [`verdict::judge`]), it is extended, doubling its length, up to `config.max_samples`,
/// where an unsettled run is reported [`Outcome::Undecided`] with the reason. The loop's
/// analysis (spectral radius of the bilateral loop, Section V) is the reference for windows in
/// which the wall acts linearly: a verdict there always agrees with it.
pub fn simulate(config: &Config) -> Result<RunResult> {
    let facts = config.loop_facts();
    let mut sim = Simulator::new(config)?;
    let mut target = config.samples;
    let verdict = loop {
        sim.advance(target - sim.sample_index())?;
        let last_chance = target >= config.max_samples || sim.blown_up;
        let v = sim.verdict(&facts, last_chance);
        if v.outcome != Outcome::Undecided || last_chance {
            break v;
        }
        target = target.saturating_mul(2).min(config.max_samples);
    };
    Ok(RunResult {
        verdict,
        samples: sim.k,
        requested_samples: config.samples,
        max_samples: config.max_samples,
        blown_up: sim.blown_up,
        final_position: sim.position(),
        final_velocity: sim.velocity(),
        trace_stride: sim.recorder.as_ref().map_or(0, |r| r.stride),
        trace: sim.recorder.take().map(|r| r.trace),
    })
}
