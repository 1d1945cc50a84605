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
//! See [`simulate`]: in the linear bilateral case the growth per sample is measured on the
//! homogeneous loop by block power iteration through the simulator's own step (it equals
//! the spectral radius of p(z)); otherwise it is fitted to the envelope of the run.

use std::fmt;
use std::sync::Arc;

use nalgebra::{DMatrix, Schur};
use num_complex::Complex64;
use rayon::prelude::*;
use serde::Serialize;

use crate::closed_loop::PolyFamily;
use crate::error::{Error, Result, finite, non_negative, positive};
use crate::params::{Normalized, Physical, PlantParams};
use crate::plant::DiscretePlant;

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

/// How the envelope of a nonlinear run is judged (see [`simulate`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EnvelopeSettings {
    /// Number of windows the run is split into (>= 4); the envelope of a window is the
    /// half-range of the velocity in it.
    pub windows: usize,
    /// The fitted log-envelope must change by more than this over the second half of the
    /// run to count as growing (> 0) or decaying (< 0); otherwise the oscillation is
    /// sustained.
    pub min_log_change: f64,
}

impl Default for EnvelopeSettings {
    fn default() -> Self {
        Self {
            windows: 64,
            min_log_change: std::f64::consts::LN_2,
        }
    }
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
    /// Number of samples to simulate (>= 2).
    pub samples: usize,
    /// Record every n-th sample in the trace; 0 records nothing.
    pub record_every: usize,
    /// Envelope judgement of nonlinear runs.
    pub envelope: EnvelopeSettings,
}

/// Largest number of trace rows a run may record.
pub const MAX_TRACE_ROWS: usize = 50_000_000;

impl Config {
    /// A linear bilateral run of `samples` samples from rest at the origin with no human
    /// force and no trace.
    pub fn new(model: Model, samples: usize) -> Self {
        Self {
            model,
            effects: Effects::LINEAR,
            human: HumanForce::default(),
            initial: Initial::default(),
            samples,
            record_every: 0,
            envelope: EnvelopeSettings::default(),
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
        if self.record_every > 0 && self.samples / self.record_every > MAX_TRACE_ROWS {
            return Err(Error::OutOfRange {
                name: "recorded rows (samples / record_every)",
                value: (self.samples / self.record_every) as f64,
                range: "[0, 5e7]",
            });
        }
        if self.envelope.windows < 4 {
            return Err(Error::OutOfRange {
                name: "envelope windows",
                value: self.envelope.windows as f64,
                range: "[4, inf)",
            });
        }
        positive("envelope min_log_change", self.envelope.min_log_change)?;
        Ok(())
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

/// A run's verdict from its envelope (issue 6): `decaying`, `limit_cycle` or `growing`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// The oscillation dies out (linear: spectral radius < 1, Section V).
    Decaying,
    /// A sustained oscillation of roughly constant amplitude (a limit cycle).
    LimitCycle,
    /// The oscillation grows (linear: spectral radius > 1).
    Growing,
}

impl Outcome {
    /// The snake_case name used in JSON.
    pub fn as_str(&self) -> &'static str {
        match self {
            Outcome::Decaying => "decaying",
            Outcome::LimitCycle => "limit_cycle",
            Outcome::Growing => "growing",
        }
    }
}

/// How `growth_per_sample` was obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GrowthMethod {
    /// Block power iteration on the homogeneous linear loop ([`linear_growth`]).
    SubspaceIteration,
    /// Least-squares fit of the run's log-envelope.
    EnvelopeFit,
}

/// Growth of the homogeneous linear bilateral loop, measured by stepping the simulator.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LinearGrowth {
    /// Envelope factor per sample of the dominant mode: |λ| of the dominant Ritz value,
    /// which is the spectral radius of p(z) (eq. 9, Section V).
    pub growth_per_sample: f64,
    /// The dominant Ritz value λ (its argument is the oscillation angle per sample).
    pub dominant: Complex64,
    /// Relative residual ‖Av − λv‖/|λ| of the dominant Ritz pair.
    pub residual: f64,
    /// Block size of the power iteration.
    pub block: usize,
    /// Simulated steps per block vector.
    pub steps: usize,
    /// True when the residual fell below the target (1e-11).
    pub converged: bool,
}

impl LinearGrowth {
    /// Frequency of the dominant mode in Hz for period T: |arg λ| / (2πT).
    pub fn frequency_hz(&self, period: f64) -> f64 {
        self.dominant.arg().abs() / (2.0 * std::f64::consts::PI * period)
    }
}

/// The result of [`simulate`].
#[derive(Debug, Clone, Serialize)]
pub struct RunResult {
    /// Decaying, limit cycle or growing.
    pub verdict: Outcome,
    /// Envelope factor per sample (linear bilateral: the spectral radius of p(z)).
    pub growth_per_sample: f64,
    /// Where `growth_per_sample` comes from.
    pub growth_method: GrowthMethod,
    /// The log-envelope fit of this run itself (second half), if it had enough windows.
    pub run_envelope_growth: Option<f64>,
    /// Half peak-to-peak position amplitude in m over the last quarter (limit cycles only).
    pub amplitude: Option<f64>,
    /// Oscillation frequency in Hz (limit cycles only, when measurable).
    pub frequency_hz: Option<f64>,
    /// Samples actually simulated.
    pub samples: usize,
    /// True if the run stopped early because |x| or |ẋ|·T exceeded [`BLOW_UP`].
    pub blown_up: bool,
    /// Position at the end in m.
    pub final_position: f64,
    /// Velocity at the end in m/s.
    pub final_velocity: f64,
    /// Linear bilateral runs: the subspace-iteration measurement.
    pub linear: Option<LinearGrowth>,
    /// The recorded trace, if `record_every > 0` (not serialized).
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

#[derive(Debug, Clone, Copy)]
struct Window {
    xmin: f64,
    xmax: f64,
    vmin: f64,
    vmax: f64,
    start: usize,
    len: usize,
}

impl Window {
    fn empty(start: usize) -> Self {
        Self {
            xmin: f64::INFINITY,
            xmax: f64::NEG_INFINITY,
            vmin: f64::INFINITY,
            vmax: f64::NEG_INFINITY,
            start,
            len: 0,
        }
    }
    fn vrange(&self) -> f64 {
        0.5 * (self.vmax - self.vmin)
    }
    fn center(&self) -> f64 {
        self.start as f64 + 0.5 * self.len as f64
    }
}

/// Online envelope statistics: per-window extremes and hysteresis crossings of ẋ.
#[derive(Debug, Clone)]
struct Stats {
    window: usize,
    cur: Window,
    done: Vec<Window>,
    hyst: f64,
    below: bool,
    cross_from: usize,
    first_cross: usize,
    last_cross: usize,
    n_cross: usize,
}

impl Stats {
    fn new(planned: usize, windows: usize) -> Self {
        // At least 4 samples per window, so that a window's half-range means something.
        let window = planned.div_ceil(windows).max(4);
        Self {
            window,
            cur: Window::empty(0),
            done: Vec::with_capacity(planned / window + 2),
            hyst: 0.0,
            below: false,
            cross_from: planned / 2,
            first_cross: 0,
            last_cross: 0,
            n_cross: 0,
        }
    }

    #[inline(always)]
    fn push(&mut self, k: usize, x: f64, w: f64) {
        let c = &mut self.cur;
        c.xmin = c.xmin.min(x);
        c.xmax = c.xmax.max(x);
        c.vmin = c.vmin.min(w);
        c.vmax = c.vmax.max(w);
        c.len += 1;
        if w < -self.hyst {
            self.below = true;
        } else if w > self.hyst && self.below {
            self.below = false;
            if k >= self.cross_from {
                if self.n_cross == 0 {
                    self.first_cross = k;
                }
                self.last_cross = k;
                self.n_cross += 1;
            }
        }
        if c.len == self.window {
            self.hyst = 0.25 * c.vrange();
            self.done.push(*c);
            self.cur = Window::empty(k + 1);
        }
    }

    /// Completed windows plus the current one if at least half full.
    fn windows(&self) -> Vec<Window> {
        let mut v = self.done.clone();
        if self.cur.len * 2 >= self.window && self.cur.len > 0 {
            v.push(self.cur);
        }
        v
    }
}

/// The time-domain simulator of Fig. 3 (see the module documentation). Stepping is
/// allocation-free: the delay line is a ring buffer of sensed positions and the envelope
/// statistics are preallocated for `Config::samples` (advancing beyond that only appends
/// more envelope windows); a trace, if requested, is preallocated too.
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
    stats: Stats,
    trace: Option<Trace>,
    record_every: usize,
    countdown: usize,
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
        let trace = (config.record_every > 0).then(|| {
            let rows = config.samples / config.record_every + 1;
            Trace {
                time: Vec::with_capacity(rows),
                position: Vec::with_capacity(rows),
                velocity: Vec::with_capacity(rows),
                wall_force: Vec::with_capacity(rows),
                human_force: Vec::with_capacity(rows),
            }
        });
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
            stats: Stats::new(config.samples, config.envelope.windows),
            trace,
            record_every: config.record_every,
            countdown: 0,
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
        self.trace.as_ref()
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
        if self.countdown == 0 {
            self.countdown = self.record_every;
            let (t, period, scale, k) = (self.period, self.period, self.scale, self.k);
            if let Some(tr) = self.trace.as_mut() {
                tr.time.push(k as f64 * t);
                tr.position.push(x);
                tr.velocity.push(w / period);
                tr.wall_force.push(uw / scale);
                tr.human_force.push(uh / scale);
            }
        }
        self.countdown -= 1;
    }

    fn run_loop<const LINEAR: bool>(&mut self, n: usize) -> Result<usize> {
        if self.blown_up {
            return Ok(0);
        }
        let recording = self.trace.is_some();
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
            let uw = if LINEAR {
                wall_linear(alpha, beta, xw, yd, yd1)
            } else {
                self.wall(yd, yd1)
            };
            let uh = self.human_at(k)?;
            if recording {
                self.record(x, w, uw, uh);
            }
            self.stats.push(k, x, w);
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

    #[inline(always)]
    fn wall(&self, yd: f64, yd1: f64) -> f64 {
        let u = match self.contact {
            Contact::Bilateral => wall_linear(self.alpha, self.beta, self.xw, yd, yd1),
            Contact::Unilateral => {
                if yd > self.xw {
                    wall_linear(self.alpha, self.beta, self.xw, yd, yd1)
                } else {
                    0.0
                }
            }
            Contact::UnilateralNoPull => {
                if yd > self.xw {
                    wall_linear(self.alpha, self.beta, self.xw, yd, yd1).max(0.0)
                } else {
                    0.0
                }
            }
        };
        u.clamp(-self.u_max, self.u_max)
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

/// Least-squares slope of ln(range) against window centre, over windows with range > floor.
fn log_slope(ws: &[Window], floor: f64) -> Option<(f64, f64)> {
    let pts: Vec<(f64, f64)> = ws
        .iter()
        .filter(|w| w.vrange() > floor && w.vrange().is_finite())
        .map(|w| (w.center(), w.vrange().ln()))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx <= 0.0 {
        return None;
    }
    let span = pts[pts.len() - 1].0 - pts[0].0;
    Some((sxy / sxx, span))
}

struct EnvelopeFit {
    outcome: Outcome,
    growth: Option<f64>,
    amplitude: f64,
    frequency: Option<f64>,
}

fn envelope_fit(
    stats: &Stats,
    settings: &EnvelopeSettings,
    blown_up: bool,
    period: f64,
) -> EnvelopeFit {
    let ws = stats.windows();
    let peak = ws
        .iter()
        .map(|w| w.vrange())
        .filter(|r| r.is_finite())
        .fold(0.0, f64::max);
    let floor = 1e-9 * peak;
    let half = &ws[ws.len() / 2..];
    let half = if half.len() < 2 { &ws[..] } else { half };
    let fit = log_slope(half, floor);
    let growth = fit.map(|(s, _)| s.exp());
    let quarter = &ws[(3 * ws.len()) / 4..];
    let (xmin, xmax) = quarter
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), w| {
            (a.min(w.xmin), b.max(w.xmax))
        });
    let amplitude = if xmax >= xmin {
        0.5 * (xmax - xmin)
    } else {
        0.0
    };
    let frequency = (stats.n_cross >= 2 && stats.last_cross > stats.first_cross).then(|| {
        (stats.n_cross - 1) as f64 / ((stats.last_cross - stats.first_cross) as f64 * period)
    });
    let last = half.last().map_or(0.0, |w| w.vrange());
    let outcome = if blown_up {
        Outcome::Growing
    } else if last.is_nan() || last <= floor {
        Outcome::Decaying
    } else {
        match fit {
            Some((s, span)) if s * span > settings.min_log_change => Outcome::Growing,
            Some((s, span)) if s * span < -settings.min_log_change => Outcome::Decaying,
            _ => Outcome::LimitCycle,
        }
    };
    EnvelopeFit {
        outcome,
        growth,
        amplitude,
        frequency,
    }
}

/// Runs one simulation of Fig. 3 and judges it.
///
/// * Linear bilateral settings: `growth_per_sample` is [`linear_growth`] (the envelope
///   factor of the homogeneous loop, i.e. the spectral radius of p(z), Section V); the
///   verdict is `decaying` below 1 − 1e-9, `growing` above 1 + 1e-9, else `limit_cycle` with
///   the dominant mode's frequency.
/// * Otherwise the run is split into windows ([`EnvelopeSettings`]); the envelope of a
///   window is the half-range of ẋ (insensitive to offsets and to free drift), and a
///   least-squares fit of its logarithm over the second half gives `growth_per_sample`
///   (per-sample factor) and the verdict: `decaying` if the envelope falls below 1e-9 of
///   its peak or its log falls by more than `min_log_change`, `growing` if it rises by more
///   or the run blew up, otherwise `limit_cycle`, with amplitude (half peak-to-peak of x
///   over the last quarter) and frequency (hysteresis crossings of ẋ over the second half).
pub fn simulate(config: &Config) -> Result<RunResult> {
    let mut sim = Simulator::new(config)?;
    let samples = sim.advance(config.samples)?;
    let fit = envelope_fit(
        &sim.stats,
        &config.envelope,
        sim.blown_up,
        config.model.period,
    );
    let period = config.model.period;
    let (verdict, growth, method, linear, frequency) = if config.effects.is_linear() {
        let lg = linear_growth(&config.model.params)?;
        let rho = lg.growth_per_sample;
        let verdict = if rho < 1.0 - 1e-9 {
            Outcome::Decaying
        } else if rho > 1.0 + 1e-9 {
            Outcome::Growing
        } else {
            Outcome::LimitCycle
        };
        let f = lg.frequency_hz(period);
        (
            verdict,
            rho,
            GrowthMethod::SubspaceIteration,
            Some(lg),
            Some(f),
        )
    } else {
        let growth = fit.growth.unwrap_or(if fit.outcome == Outcome::Decaying {
            0.0
        } else {
            1.0
        });
        let growth = if sim.blown_up && fit.growth.is_none_or(|g| g <= 1.0) {
            // Too few windows before the blow-up: average factor from the start.
            let start = config
                .initial
                .position
                .abs()
                .max((config.initial.velocity * period).abs())
                .max(1e-300);
            (BLOW_UP / start).powf(1.0 / samples.max(1) as f64)
        } else {
            growth
        };
        (
            fit.outcome,
            growth,
            GrowthMethod::EnvelopeFit,
            None,
            fit.frequency,
        )
    };
    let limit = verdict == Outcome::LimitCycle;
    Ok(RunResult {
        verdict,
        growth_per_sample: growth,
        growth_method: method,
        run_envelope_growth: fit.growth,
        amplitude: limit.then_some(fit.amplitude),
        frequency_hz: if limit { frequency } else { None },
        samples,
        blown_up: sim.blown_up,
        final_position: sim.position(),
        final_velocity: sim.velocity(),
        linear,
        trace: sim.trace.take(),
    })
}

/// Largest block of the power iteration.
const BLOCK: usize = 6;

/// One homogeneous step of the linear bilateral loop on the state (x, Tẋ, y[k−1], …,
/// y[k−d−1]) with the simulator's kernel and wall law.
fn homogeneous_step(k: &Kernel, alpha: f64, beta: f64, d: usize, src: &[f64], dst: &mut [f64]) {
    let (x, w) = (src[0], src[1]);
    let h = &src[2..];
    let yd = if d == 0 { x } else { h[d - 1] };
    let yd1 = h[d];
    let u = -wall_linear(alpha, beta, 0.0, yd, yd1);
    let (x1, w1) = k.step(x, w, u);
    dst[0] = x1;
    dst[1] = w1;
    dst[2] = x;
    dst[3..].copy_from_slice(&h[..d]);
}

/// Modified Gram–Schmidt on p columns of length n (column-major); returns false if the
/// block lost rank.
fn orthonormalize(q: &mut [f64], n: usize, p: usize) -> bool {
    for j in 0..p {
        for i in 0..j {
            let (a, b) = q.split_at_mut(j * n);
            let qi = &a[i * n..(i + 1) * n];
            let qj = &mut b[..n];
            let r: f64 = qi.iter().zip(qj.iter()).map(|(u, v)| u * v).sum();
            qj.iter_mut().zip(qi).for_each(|(v, u)| *v -= r * u);
        }
        let col = &mut q[j * n..(j + 1) * n];
        let norm = col.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !(norm > 0.0 && norm.is_finite()) {
            return false;
        }
        col.iter_mut().for_each(|v| *v /= norm);
    }
    true
}

/// Solves the small complex system a·x = b in place by Gaussian elimination with partial
/// pivoting; zero pivots are replaced by a tiny value (inverse iteration).
fn complex_solve(a: &mut [Complex64], b: &mut [Complex64], p: usize) {
    let scale = a
        .iter()
        .map(|z| z.norm())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    for c in 0..p {
        let piv = (c..p)
            .max_by(|&i, &j| a[i * p + c].norm().total_cmp(&a[j * p + c].norm()))
            .unwrap_or(c);
        if piv != c {
            for j in 0..p {
                a.swap(c * p + j, piv * p + j);
            }
            b.swap(c, piv);
        }
        if a[c * p + c].norm() < 1e-14 * scale {
            a[c * p + c] = Complex64::new(1e-14 * scale, 0.0);
        }
        for i in c + 1..p {
            let f = a[i * p + c] / a[c * p + c];
            for j in c..p {
                let v = a[c * p + j];
                a[i * p + j] -= f * v;
            }
            let v = b[c];
            b[i] -= f * v;
        }
    }
    for c in (0..p).rev() {
        let mut s = b[c];
        for j in c + 1..p {
            s -= a[c * p + j] * b[j];
        }
        b[c] = s / a[c * p + c];
    }
}

/// Ritz values of the p×p matrix t (row-major) and the dominant one with its residual.
fn dominant_ritz(t: &[f64], p: usize, q: &[f64], aq: &[f64], n: usize) -> Option<(Complex64, f64)> {
    let m = DMatrix::from_row_slice(p, p, t);
    let schur = Schur::try_new(m, f64::EPSILON, 10_000)?;
    let eig = schur.complex_eigenvalues();
    let lam = eig
        .iter()
        .map(|z| Complex64::new(z.re, z.im))
        .max_by(|a, b| a.norm().total_cmp(&b.norm()))?;
    // Ritz vector by inverse iteration on t − λI.
    let mut y = vec![Complex64::new(1.0, 0.0); p];
    for (i, yi) in y.iter_mut().enumerate() {
        *yi = Complex64::new(1.0 + 0.1 * i as f64, 0.3 - 0.05 * i as f64);
    }
    for _ in 0..3 {
        let mut a: Vec<Complex64> = t.iter().map(|&v| Complex64::new(v, 0.0)).collect();
        for i in 0..p {
            a[i * p + i] -= lam;
        }
        complex_solve(&mut a, &mut y, p);
        let nrm = y.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
        if !(nrm > 0.0 && nrm.is_finite()) {
            return Some((lam, f64::INFINITY));
        }
        y.iter_mut().for_each(|z| *z /= nrm);
    }
    // Residual ‖(AQ) y − λ Q y‖ / |λ|, with ‖Q y‖ = 1.
    let mut res = 0.0;
    for r in 0..n {
        let mut s = Complex64::new(0.0, 0.0);
        for j in 0..p {
            s += y[j] * (aq[j * n + r]) - lam * y[j] * q[j * n + r];
        }
        res += s.norm_sqr();
    }
    Some((lam, res.sqrt() / lam.norm().max(f64::MIN_POSITIVE)))
}

/// Measures the growth per sample of the homogeneous linear bilateral loop (eq. 9,
/// Section V) by stepping the simulator's own one-sample map: block power iteration with a
/// block of min(d + 3, 6) generic state vectors (position, velocity *and* the delay line),
/// re-orthonormalized every step, and Rayleigh–Ritz on the block. The modulus of the
/// dominant Ritz value is the envelope factor of the dominant mode, so a complex dominant
/// pair is tracked as the growth of a rotating plane rather than by the oscillating norm of
/// one trajectory. Stops when the dominant Ritz pair's relative residual is below 1e-11 or
/// after a work budget.
pub fn linear_growth(params: &Normalized) -> Result<LinearGrowth> {
    let params = params.validated()?;
    let kernel = Kernel::new(&DiscretePlant::from_params(params.plant()));
    let (alpha, beta, d) = (params.alpha, params.beta, params.d);
    let n = d + 3;
    let p = n.min(BLOCK);
    let mut seed = 0x9E37_79B9_7F4A_7C15_u64;
    let mut q: Vec<f64> = (0..n * p)
        .map(|_| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect();
    if !orthonormalize(&mut q, n, p) {
        return Err(Error::Numerical("initial block is rank deficient".into()));
    }
    let mut aq = vec![0.0; n * p];
    let mut t = vec![0.0; p * p];
    let max_steps = (4e9 / (n * p * p) as f64).clamp(2_000.0, 1_000_000.0) as usize;
    let mut best: Option<(Complex64, f64)> = None;
    let mut steps = 0;
    let mut next_check = 1;
    loop {
        for j in 0..p {
            let (src, dst) = (&q[j * n..(j + 1) * n], &mut aq[j * n..(j + 1) * n]);
            homogeneous_step(&kernel, alpha, beta, d, src, dst);
        }
        steps += 1;
        if steps >= next_check || steps >= max_steps {
            next_check = steps + if steps < 64 { 1 } else { 16 };
            for i in 0..p {
                for j in 0..p {
                    t[i * p + j] = (0..n).map(|r| q[i * n + r] * aq[j * n + r]).sum();
                }
            }
            if let Some((lam, res)) = dominant_ritz(&t, p, &q, &aq, n) {
                best = Some((lam, res));
                if res < 1e-11 || steps >= max_steps {
                    break;
                }
            } else if steps >= max_steps {
                break;
            }
        }
        std::mem::swap(&mut q, &mut aq);
        if !orthonormalize(&mut q, n, p) {
            // The map annihilated the block (all roots zero): nothing grows.
            return Ok(LinearGrowth {
                growth_per_sample: 0.0,
                dominant: Complex64::new(0.0, 0.0),
                residual: 0.0,
                block: p,
                steps,
                converged: true,
            });
        }
    }
    let (lam, res) = best.ok_or_else(|| Error::Numerical("Ritz values did not converge".into()))?;
    Ok(LinearGrowth {
        growth_per_sample: lam.norm(),
        dominant: lam,
        residual: res,
        block: p,
        steps,
        converged: res < 1e-11,
    })
}

/// When a simulated run counts as stable for [`empirical_boundary`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StableWhen {
    /// Only a decaying run is stable.
    Decaying,
    /// Decaying runs and limit cycles with amplitude below this many metres are stable.
    AmplitudeBelow(f64),
}

/// An empirical stability-boundary search (issue 6, item 4): for each β the largest α whose
/// simulated run is stable, with everything else taken from a template run.
#[derive(Debug, Clone)]
pub struct BoundarySearch {
    /// Template run (plant, delay, effects, human force, initial state, duration); its α
    /// and β are replaced.
    pub template: Config,
    /// Normalized virtual damping values β (Table I).
    pub betas: Vec<f64>,
    /// Upper end of the α scan; default 3× the linear boundary at that β (or 2 if the
    /// linear loop is unstable there).
    pub alpha_max: Option<f64>,
    /// Coarse scan points in (0, alpha_max] before bisection (>= 2).
    pub grid: usize,
    /// Bisection stops when the bracket is below this fraction of α (> 0).
    pub rel_tolerance: f64,
    /// Stability criterion.
    pub stable_when: StableWhen,
}

/// One β of an empirical boundary.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EmpiricalPoint {
    /// Normalized virtual damping β.
    pub beta: f64,
    /// The exact linear boundary α at this β (Section V), if the linear loop is stable for
    /// small α > 0.
    pub alpha_linear: Option<f64>,
    /// The simulated boundary: the largest α found stable (None if the first grid point
    /// is already unstable).
    pub alpha_simulated: Option<f64>,
    /// Smallest α found unstable (None if every α up to the scan end was stable).
    pub alpha_unstable: Option<f64>,
    /// True if no instability was found up to the scan end (the boundary lies beyond).
    pub censored: bool,
    /// Upper end of the α scan.
    pub alpha_max: f64,
    /// Number of simulated runs.
    pub runs: usize,
}

/// The exact linear boundary along α at fixed β (Section V): the upper end of the stable
/// α-interval that starts at α = −γ, by D-decomposition ([`crate::linear::exact_upper_alpha`]).
/// None if no such interval exists; `f64::INFINITY` if it is unbounded.
pub fn exact_alpha_limit(plant: PlantParams, d: usize, beta: f64) -> Result<Option<f64>> {
    finite("beta", beta)?;
    let plant = PlantParams::new(plant.gamma, plant.delta)?;
    let fam = PolyFamily::new(plant, d)?;
    Ok(crate::linear::exact_upper_alpha(&fam, beta))
}

fn run_is_stable(template: &Config, alpha: f64, beta: f64, when: StableWhen) -> Result<bool> {
    let mut cfg = template.clone();
    cfg.model = template.model.with_wall(alpha, beta)?;
    cfg.record_every = 0;
    let r = simulate(&cfg)?;
    Ok(match (r.verdict, when) {
        (Outcome::Decaying, _) => true,
        (Outcome::LimitCycle, StableWhen::AmplitudeBelow(a)) => r.amplitude.is_some_and(|x| x < a),
        _ => false,
    })
}

fn boundary_at(search: &BoundarySearch, beta: f64) -> Result<EmpiricalPoint> {
    let p = search.template.model.params;
    let alpha_linear = exact_alpha_limit(p.plant(), p.d, beta)?;
    let alpha_max = match search.alpha_max {
        Some(a) => positive("alpha_max", a)?,
        None => match alpha_linear {
            Some(a) if a.is_finite() => 3.0 * a,
            _ => 2.0,
        },
    };
    let g = search.grid;
    let grid: Vec<f64> = (1..=g).map(|i| alpha_max * i as f64 / g as f64).collect();
    let verdicts: Vec<bool> = grid
        .par_iter()
        .map(|&a| run_is_stable(&search.template, a, beta, search.stable_when))
        .collect::<Result<_>>()?;
    let mut runs = g;
    let first_bad = verdicts.iter().position(|s| !s);
    let (alpha_simulated, alpha_unstable) = match first_bad {
        None => (Some(alpha_max), None),
        Some(0) => (None, Some(grid[0])),
        Some(i) => {
            let (mut lo, mut hi) = (grid[i - 1], grid[i]);
            while hi - lo > search.rel_tolerance * hi {
                let mid = 0.5 * (lo + hi);
                runs += 1;
                if run_is_stable(&search.template, mid, beta, search.stable_when)? {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            (Some(lo), Some(hi))
        }
    };
    Ok(EmpiricalPoint {
        beta,
        alpha_linear,
        alpha_simulated,
        alpha_unstable,
        censored: first_bad.is_none(),
        alpha_max,
        runs,
    })
}

/// The empirical stability boundary of a nonlinear setting (issue 6, item 4; compare
/// Fig. 4–6 and Remark 1): for each β a coarse scan of α over (0, alpha_max] finds the
/// first unstable run, then bisection between the last stable and the first unstable grid
/// point. β values and grid runs are simulated in parallel (rayon). Assumes the stable set
/// along α starts near 0; the point reports the first transition.
pub fn empirical_boundary(search: &BoundarySearch) -> Result<Vec<EmpiricalPoint>> {
    search.template.validate()?;
    if search.grid < 2 {
        return Err(Error::OutOfRange {
            name: "grid",
            value: search.grid as f64,
            range: "[2, inf)",
        });
    }
    positive("rel_tolerance", search.rel_tolerance)?;
    if let StableWhen::AmplitudeBelow(a) = search.stable_when {
        positive("amplitude threshold", a)?;
    }
    for &b in &search.betas {
        finite("beta", b)?;
    }
    search
        .betas
        .par_iter()
        .map(|&b| boundary_at(search, b))
        .collect()
}
