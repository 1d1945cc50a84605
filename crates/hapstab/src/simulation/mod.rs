//! Time-domain simulation of the sampled-data loop of Fig. 3 (Section II) for any loop
//! ([`crate::Loop`]: plant, actuator lag, fractional delay, velocity estimator), including the
//! nonlinear effects that the paper leaves to future work (Remark 1 and Section IX): a
//! unilateral wall, Coulomb and static friction, position-sensor quantization and actuator
//! force saturation.
//!
//! # Model
//!
//! The simulator steps the exact discrete loop of [`crate::DiscreteLoop`], the same matrices
//! the analysis closes into p(z) ([`crate::closed_loop`]), in normalized time (one unit per
//! sample) and wall units (forces divided by k_u = m/T², Table I, m the plant's reference
//! mass):
//!
//! ```text
//! x[k+1] = Φ x[k] + Γ0 u_w[k−d] + Γ1 u_w[k−d−1] + Ψ b_h u_H[k] + Ψ b_f u_f,
//! y[k] = C x[k] (sensed: optionally quantized),   v = V(z)·y (the loop's estimator),
//! u_w[j] = −F_wall[j]/k_u,   F_wall[j] = K (y[j] − x_w) + B v[j],
//! ```
//!
//! with t_d = (d + λ)T: the wall force computed at sample j acts from jT + t_d, so over one
//! sample the force of k − d − 1 acts on [0, λT) and that of k − d on [λT, T) (Γ1 = 0 for
//! a whole number of samples). The human force u_H and friction u_f act on the plant
//! directly, not through the actuator lag (see [`crate::zoh::PlantPorts`]). The linear
//! bilateral loop therefore has exactly the characteristic polynomial
//! p(z) = P0 + a·PK + b·PB of [`crate::AffineFamily`]; for the paper's loop, stepped in the
//! state (x, T·ẋ) with (a, b) = (α, β), that is eq. (9). Positions are in metres, velocities
//! in m/s and forces in newtons throughout the API.
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
//! Coulomb friction F_c opposes the velocity of the point where it acts, static friction
//! F_s ≥ F_c holds that point at rest: the device of the paper's plant, the motor side of a
//! two-mass device. A transfer function names no mass, so friction is refused for it.
//! Friction is not held at its sampled value: between events the motion is an exact ZOH
//! (sub)step with constant inputs, and events inside a sample (velocity reversals, breakaway
//! of a stuck point) are located on the exact sub-step solution, with the stick rule at each
//! reversal (stick if the rest of the plant pushes the point with at most F_s, otherwise
//! slip in that direction). While stuck, the point is held and the rest of the plant moves
//! on (a two-mass device's handle, an actuator lag). See `stepper.rs` for the method and
//! its limits (two reversals within one sample need dynamics faster than the sampling).
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

use crate::closed_loop::AffineFamily;
use crate::error::{Error, Result, finite, non_negative, positive};
use crate::model::{Loop, PlantModel};
use crate::paper::Normalized;
use crate::param::Param;
use crate::params::{Physical, Wall};
use crate::stability::Analysis;

mod boundary;
mod clip;
mod filter;
mod growth;
mod settling;
mod simulator;
mod stepper;
pub mod verdict;

pub use boundary::{
    BoundarySearch, EmpiricalPoint, InconclusiveRun, MAX_BISECTION_STEPS, MIN_REL_TOLERANCE,
    StableWhen, empirical_boundary, exact_alpha_limit,
};
pub use clip::{
    CLIP_FACTOR, ClippedTrace, TraceClip, clip_growing_trace, simulate_clipped, start_scale,
};
pub use growth::{LinearGrowth, linear_growth, linear_growth_of};
pub use settling::SETTLING_BAND;
pub use simulator::Simulator;
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
            mass: positive(Param::Mass, mass)?,
            period: positive(Param::Period, period)?,
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
        params.alpha = finite(Param::Alpha, alpha)?;
        params.beta = finite(Param::Beta, beta)?;
        Self::new(params, self.mass, self.period)
    }

    /// The force scale T²/m (Table I): u = (T²/m)·F.
    pub fn force_scale(&self) -> f64 {
        self.period * self.period / self.mass
    }
}

/// Any loop ([`Loop`]: plant, period, delay, velocity estimator) with its wall, in
/// physical units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LoopModel {
    /// The loop.
    pub lp: Loop,
    /// The wall's stiffness K (N/m) and damping B (Ns/m).
    pub wall: Wall,
}

impl LoopModel {
    /// Bundles a loop and its wall; the wall must be finite.
    pub fn new(lp: Loop, wall: Wall) -> Result<Self> {
        finite(Param::WallStiffness, wall.stiffness)?;
        finite(Param::WallDamping, wall.damping)?;
        Ok(Self { lp, wall })
    }
}

/// The linear part of a simulated loop: the paper's loop in Table I's coordinates, or any
/// loop. Both are stepped through the same engine, the exact discrete loop of
/// [`crate::DiscreteLoop`]; the paper's loop as its normalized loop ([`Loop::normalized`],
/// m = T = 1, so that its wall units are (α, β) and its analysis is the paper's, eq. 9).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum SimModel {
    /// The paper's loop (eq. 1, Table I) with the mass and period that give it units.
    Paper(Model),
    /// Any loop with a physical wall.
    Loop(LoopModel),
}

impl From<Model> for SimModel {
    fn from(m: Model) -> Self {
        SimModel::Paper(m)
    }
}

impl From<LoopModel> for SimModel {
    fn from(m: LoopModel) -> Self {
        SimModel::Loop(m)
    }
}

impl SimModel {
    /// The loop that is stepped (see the type's doc), in normalized time and wall units.
    pub fn stepped_loop(&self) -> Result<Loop> {
        match self {
            SimModel::Paper(m) => Loop::normalized(m.params.plant(), m.params.d),
            SimModel::Loop(m) => Ok(m.lp.clone()),
        }
    }

    /// The wall in the stepped loop's wall units (a, b) = (K/k_u, B/(k_u·T)): (α, β) of
    /// Table I for the paper's loop.
    pub fn wall_units(&self) -> (f64, f64) {
        match self {
            SimModel::Paper(m) => (m.params.alpha, m.params.beta),
            SimModel::Loop(m) => {
                let s = m.lp.wall_scale();
                (m.wall.stiffness / s.stiffness, m.wall.damping / s.damping)
            }
        }
    }

    /// The same loop with another wall in wall units (a, b).
    pub fn with_wall_units(&self, a: f64, b: f64) -> Result<Self> {
        Ok(match self {
            SimModel::Paper(m) => SimModel::Paper(m.with_wall(a, b)?),
            SimModel::Loop(m) => {
                let s = m.lp.wall_scale();
                let wall = Wall {
                    stiffness: finite(Param::WallUnitStiffness, a)? * s.stiffness,
                    damping: finite(Param::WallUnitDamping, b)? * s.damping,
                };
                SimModel::Loop(LoopModel::new(m.lp.clone(), wall)?)
            }
        })
    }

    /// Sampling period T in s.
    pub fn period(&self) -> f64 {
        match self {
            SimModel::Paper(m) => m.period,
            SimModel::Loop(m) => m.lp.period,
        }
    }

    /// Wall units per newton, 1/k_u = T²/m (Table I; m the plant's reference mass).
    pub fn force_scale(&self) -> f64 {
        match self {
            SimModel::Paper(m) => m.force_scale(),
            SimModel::Loop(m) => 1.0 / m.lp.wall_scale().stiffness,
        }
    }

    /// The affine family p(z) = P0 + a·PK + b·PB of the stepped loop ([`AffineFamily`]).
    pub fn family(&self) -> Result<AffineFamily> {
        AffineFamily::of_loop(&self.stepped_loop()?)
    }

    /// The analysis of the linear bilateral loop (Section V): verdict, spectral radius, roots
    /// of p(z) at this wall.
    pub fn analysis(&self) -> Result<Analysis> {
        match self {
            SimModel::Paper(m) => Analysis::new(m.params),
            SimModel::Loop(_) => {
                let (a, b) = self.wall_units();
                Analysis::of_family(&self.family()?, a, b)
            }
        }
    }

    /// The exact linear boundary along a at damping b (wall units): the upper end of the
    /// stable a-interval that starts at the z = 1 line (Section V: α = −γ for the paper's
    /// loop) and reaches a > 0. None if there is none; `f64::INFINITY` if it is unbounded.
    pub fn exact_upper_a(&self, b: f64) -> Result<Option<f64>> {
        finite(Param::WallUnitDamping, b)?;
        match self {
            SimModel::Paper(m) => exact_alpha_limit(m.params.plant(), m.params.d, b),
            SimModel::Loop(_) => {
                let fam = self.family()?;
                Ok(crate::boundary::stable_stiffness_intervals(&fam, b)
                    .into_iter()
                    .find(|iv| iv.lo <= UPPER_A_START * iv.hi.abs().min(1.0) && iv.hi > 0.0)
                    .map(|iv| iv.hi))
            }
        }
    }

    /// Friction acts on a mass of the plant: the paper's device, a two-mass device's motor
    /// side. A transfer function names no mass, so friction is not defined for it.
    pub fn friction_defined(&self) -> bool {
        match self {
            SimModel::Paper(_) => true,
            SimModel::Loop(m) => !matches!(m.lp.plant.model, PlantModel::TransferFunction { .. }),
        }
    }

    /// Checks the loop and the wall.
    pub fn validate(&self) -> Result<()> {
        match self {
            SimModel::Paper(m) => Model::new(m.params, m.mass, m.period).map(|_| ()),
            SimModel::Loop(m) => {
                let lp = &m.lp;
                Loop::new(lp.plant.clone(), lp.period, lp.delay, lp.velocity.clone())?;
                LoopModel::new(lp.clone(), m.wall).map(|_| ())
            }
        }
    }
}

/// A stable a-interval "starts at the z = 1 line" when its lower end is at most this fraction
/// of its upper end above 0 (the line a = −s lies at a ≤ 0 for every plant with a
/// non-negative static stiffness s; rounding of the crossing may put it a few ulps above).
const UPPER_A_START: f64 = 1e-12;

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

impl Friction {
    /// The friction a user's optional forces describe: none when neither is given; a missing
    /// Coulomb force is 0 and a missing static force equals the Coulomb force (no breakaway
    /// peak). Validated with the other effects ([`Effects::validate`]).
    pub fn from_parts(coulomb: Option<f64>, stiction: Option<f64>) -> Option<Self> {
        match (coulomb, stiction) {
            (None, None) => None,
            (c, s) => {
                let coulomb = c.unwrap_or(0.0);
                Some(Self {
                    coulomb,
                    stiction: s.unwrap_or(coulomb),
                })
            }
        }
    }
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
        finite(Param::WallPosition, self.wall_position)?;
        if let Some(q) = self.quantization {
            positive(Param::Quantization, q)?;
        }
        if let Some(f) = self.saturation {
            positive(Param::Saturation, f)?;
        }
        if let Some(fr) = self.friction {
            non_negative(Param::CoulombFriction, fr.coulomb)?;
            non_negative(Param::StaticFriction, fr.stiction)?;
            if fr.stiction < fr.coulomb {
                return Err(Error::OutOfRange {
                    param: Param::StaticFriction,
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
            HumanForce::Constant(f) => finite(Param::HumanForce, *f).map(|_| ()),
            HumanForce::Samples(v) => v
                .iter()
                .try_for_each(|&f| finite(Param::HumanForceProfile, f).map(|_| ())),
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
    /// The linear loop: the paper's (eq. 1, Table I) or any loop with its wall.
    pub model: SimModel,
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
    pub fn new(model: impl Into<SimModel>, samples: usize) -> Self {
        Self {
            model: model.into(),
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
        self.model.validate()?;
        self.effects.validate()?;
        if self.effects.friction.is_some() && !self.model.friction_defined() {
            return Err(Error::Invalid {
                param: Param::Friction,
                reason: "is not defined for a transfer-function plant: it acts on a mass, which \
                         a transfer function does not name (use the mass-spring-damper or the \
                         two-mass plant)"
                    .into(),
            });
        }
        self.human.validate()?;
        finite(Param::InitialPosition, self.initial.position)?;
        finite(Param::InitialVelocity, self.initial.velocity)?;
        if self.samples < 2 {
            return Err(Error::OutOfRange {
                param: Param::DurationSamples,
                value: self.samples as f64,
                range: "[2, inf)",
            });
        }
        if self.max_samples < self.samples {
            return Err(Error::OutOfRange {
                param: Param::MaxSamples,
                value: self.max_samples as f64,
                range: "[samples, inf)",
            });
        }
        if self.trace_rows == 1 || self.trace_rows > MAX_TRACE_ROWS {
            return Err(Error::OutOfRange {
                param: Param::TraceRows,
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
        let linear = self.model.analysis().ok().map(|a| LinearReference {
            spectral_radius: a.spectral_radius,
            verdict: a.verdict,
        });
        LoopFacts {
            contact_can_be_lost: e.contact != Contact::Bilateral,
            force_limited: e.saturation.is_some(),
            static_nonlinearity: e.friction.is_some() || e.quantization.is_some(),
            quantum: e.quantization,
            period: self.model.period(),
            linear,
        }
    }
}

/// The number of samples covering `seconds` at period T (rounded up), for `--duration`.
pub fn samples_for_duration(seconds: f64, period: f64) -> Result<usize> {
    positive(Param::Duration, seconds)?;
    positive(Param::Period, period)?;
    let n = (seconds / period).ceil();
    if n > 1e12 {
        return Err(Error::OutOfRange {
            param: Param::DurationPeriods,
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
        let last_chance = target >= config.max_samples || sim.blown_up();
        let v = sim.verdict(&facts, last_chance);
        if v.outcome != Outcome::Undecided || last_chance {
            break v;
        }
        target = target.saturating_mul(2).min(config.max_samples);
    };
    Ok(RunResult {
        verdict,
        samples: sim.sample_index(),
        requested_samples: config.samples,
        max_samples: config.max_samples,
        blown_up: sim.blown_up(),
        final_position: sim.position(),
        final_velocity: sim.velocity(),
        trace_stride: sim.trace_stride(),
        trace: sim.take_trace(),
    })
}
