//! The loop a user runs (Section II, Fig. 3, generalized): a continuous plant from wall force
//! to measured position, sampled with period T behind a zero-order hold, a virtual wall
//! F_k = K·y_k + B·v_k whose force is delayed by t_d = (d + λ)·T, and a velocity estimator
//! v = V(z)·y.
//!
//! The paper's loop is one instance: the plant 1/(ms² + bs + k) of eq. (1), the backward
//! difference v_k = (y_k − y_{k−1})/T and a whole number d of samples of delay. Everything
//! the library answers (stability, regions, K_max, maps, margins, passivity, simulation) is a
//! question about one [`Loop`].

use serde::{Deserialize, Serialize};

pub use crate::delay::Delay;
use crate::error::{Error, Result, at_most, finite, non_negative, positive};
use crate::lowpass_design::{Family, NamedLowPass};
use crate::param::Param;
use crate::params::{Effective, MAX_DELAY};

/// A two-mass haptic device: the motor-side inertia (where the actuator pushes and the
/// encoder measures) coupled to the handle through a compliant transmission; the human arm,
/// if any, holds the handle (the paper's Section IX asks for "a model of the haptic device
/// including motor dynamics").
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TwoMass {
    /// Motor-side inertia J as an equivalent mass in kg (> 0).
    pub motor_mass: f64,
    /// Motor-side viscous damping b_m in Ns/m (>= 0).
    pub motor_damping: f64,
    /// Handle mass m_h in kg (>= 0; the arm's mass adds to it).
    pub handle_mass: f64,
    /// Transmission stiffness k_t in N/m (> 0).
    pub transmission_stiffness: f64,
    /// Transmission damping b_t in Ns/m (>= 0).
    pub transmission_damping: f64,
    /// Human arm on the handle: mass m_H, damping b_H, stiffness k_H (eq. 1's arm).
    pub arm: crate::params::Arm,
}

/// The plant from wall force (N) to measured position (m).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum PlantModel {
    /// The paper's device + arm as one mass-spring-damper 1/(ms² + bs + k) (eq. 1).
    MassSpringDamper(Effective),
    /// A two-mass device with a compliant transmission; see [`TwoMass`].
    TwoMass(TwoMass),
    /// Any strictly proper rational transfer function num(s)/den(s), coefficients in SI
    /// units, highest power of s first (as MATLAB's and python-control's `tf`).
    TransferFunction {
        /// Numerator coefficients, highest power first.
        num: Vec<f64>,
        /// Denominator coefficients, highest power first.
        den: Vec<f64>,
    },
}

/// A plant: a model and an optional first-order actuator lag 1/(τs + 1) between the commanded
/// and the applied force (the current loop of the motor driver).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Plant {
    /// The mechanical model.
    pub model: PlantModel,
    /// Actuator time constant τ in s (0 means no lag).
    pub force_lag: f64,
    /// The human arm that a mass-spring-damper's m, b and k include (eq. 1), when known: its
    /// damping is the operator's, not the device's own (see [`crate::passivity`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub operator: Option<crate::params::Arm>,
}

/// The velocity estimate v_k the wall's damper acts on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum VelocityEstimator {
    /// The paper's backward difference v_k = (y_k − y_{k−1})/T.
    Backward,
    /// First-order low-pass of the backward difference,
    /// v_k = a·v_{k−1} + (1 − a)(y_k − y_{k−1})/T with a = exp(−2π·f_c·T).
    LowPass {
        /// Cut-off frequency f_c in Hz (> 0).
        cutoff_hz: f64,
    },
    /// Difference over N samples, v_k = (y_k − y_{k−N})/(N·T).
    Average {
        /// Window N in samples (>= 1).
        samples: usize,
    },
    /// A digital Butterworth low-pass of the backward difference (MATLAB's and scipy's
    /// `butter(N, f_c, fs = 1/T)`, bilinear with pre-warping; see [`crate::lowpass_design`]),
    /// v = H(z)·(y_k − y_{k−1})/T.
    Butterworth {
        /// Order N, 1 ..= 8.
        order: usize,
        /// Cut-off f_c in Hz, 0 < f_c < 1/(2T).
        cutoff_hz: f64,
    },
    /// A digital Bessel low-pass of the backward difference (scipy's
    /// `bessel(N, f_c, fs = 1/T)`, norm='phase'; see [`crate::lowpass_design`]).
    Bessel {
        /// Order N, 1 ..= 8.
        order: usize,
        /// Cut-off f_c in Hz, 0 < f_c < 1/(2T).
        cutoff_hz: f64,
    },
    /// A digital critically damped low-pass of the backward difference: N equal real poles,
    /// −3 dB at f_c (see [`crate::lowpass_design`]).
    CriticallyDamped {
        /// Order N, 1 ..= 8.
        order: usize,
        /// Cut-off f_c in Hz, 0 < f_c < 1/(2T).
        cutoff_hz: f64,
    },
    /// Any proper discrete filter applied to the position,
    /// v = (b0 + b1 z⁻¹ + …)/(a0 + a1 z⁻¹ + …) · y, output in m/s.
    Iir {
        /// Numerator coefficients b0, b1, … in powers of z⁻¹.
        b: Vec<f64>,
        /// Denominator coefficients a0, a1, … in powers of z⁻¹ (a0 ≠ 0).
        a: Vec<f64>,
    },
}

/// The loop of Fig. 3, generalized: plant, sampling period, delay and velocity estimator.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Loop {
    /// Plant from wall force to measured position.
    pub plant: Plant,
    /// Sampling period T in s.
    pub period: f64,
    /// Delay of the wall force.
    pub delay: Delay,
    /// Velocity estimator of the wall's damper.
    pub velocity: VelocityEstimator,
}

/// Longest actuator lag τ in s: no actuator is slower, and near 1e300 s 1 − e^(−T/τ) underflows.
pub const MAX_FORCE_LAG: f64 = 1e3;

impl Plant {
    /// The paper's plant 1/(ms² + bs + k) (eq. 1).
    pub fn mass_spring_damper(plant: Effective) -> Result<Self> {
        Self::new(PlantModel::MassSpringDamper(plant), 0.0)
    }

    /// Validates the model's parameters and the lag 0 <= τ <= [`MAX_FORCE_LAG`].
    pub fn new(model: PlantModel, force_lag: f64) -> Result<Self> {
        at_most(Param::ForceLag, force_lag, MAX_FORCE_LAG, "[0, 1e3] s")?;
        validate_model(&model)?;
        Ok(Self {
            model,
            force_lag,
            operator: None,
        })
    }

    /// The same plant with an actuator lag τ in seconds.
    pub fn with_force_lag(self, tau: f64) -> Result<Self> {
        Self {
            force_lag: tau,
            ..self
        }
        .validated()
    }

    /// The mass that normalizes the wall (Table I: α = KT²/m, β = BT/m): m of eq. (1) for the
    /// paper's plant; the total mass (motor, handle, arm) of a two-mass device, which is what
    /// it weighs at low frequency; for a transfer function, 1/(ω²|P(jω)|) at ω = 1/T, which is
    /// m for a mass.
    pub fn reference_mass(&self, period: f64) -> f64 {
        match &self.model {
            PlantModel::MassSpringDamper(e) => e.mass,
            PlantModel::TwoMass(t) => t.motor_mass + t.handle_mass + t.arm.mass,
            PlantModel::TransferFunction { num, den } => {
                let w = 1.0 / period;
                let s = num_complex::Complex64::new(0.0, w);
                let p = eval_desc(num, s) / eval_desc(den, s);
                let m = 1.0 / (w * w * p.norm());
                if m.is_finite() && m > 0.0 { m } else { 1.0 }
            }
        }
    }

    /// The static stiffness 1/P(0) in N/m: k for the paper's plant (eq. 1); for a two-mass
    /// device the transmission k_t in series with the arm's k_H, k_t·k_H/(k_t + k_H) (a
    /// constant force on the motor stretches both springs; the encoder is on the motor side);
    /// den(0)/num(0) for a transfer function; 0 for a free mass. None when P(0) = 0 (a plant
    /// that does not move under a constant force). The actuator lag does not change it.
    pub fn dc_stiffness(&self) -> Option<f64> {
        let k = match &self.model {
            PlantModel::MassSpringDamper(e) => e.stiffness,
            PlantModel::TwoMass(t) => series_stiffness(t.transmission_stiffness, t.arm.stiffness),
            PlantModel::TransferFunction { num, den } => {
                den.last().copied().unwrap_or(0.0) / num.last().copied().unwrap_or(0.0)
            }
        };
        k.is_finite().then_some(k)
    }
}

/// Shortest sampling period accepted, in seconds (10 MHz).
pub const MIN_PERIOD: f64 = 1e-7;

/// Longest sampling period accepted, in seconds (1 Hz).
pub const MAX_PERIOD: f64 = 1.0;

/// Largest rate of an oscillating plant mode times the sampling period: beyond it a mode
/// turns by more than 10⁷ rad per sample, and the sampled plant's phase, known to about that
/// many times the rounding unit, is no longer exact to nine digits.
pub const MAX_RATE_PER_SAMPLE: f64 = 1e7;

/// Largest rate of a decaying plant mode (a damper's b/m, the actuator lag's 1/τ) times the
/// sampling period: such a mode is gone within the sample (e^{−rate·T} is exactly 0), but past
/// about 10¹⁵⁰ the wall's scale overflows; 10⁵⁰ keeps far from that.
pub const MAX_DECAY_PER_SAMPLE: f64 = 1e50;

impl Plant {
    /// The plant's fastest rates in 1/s with the parameter that sets each: √(k/m) and b/m for
    /// the paper's plant; the transmission, arm and damping rates of a two-mass device; a
    /// bound on the poles (Fujiwara's, within a factor 2 of the largest) for a transfer
    /// function; 1/τ for the actuator lag.
    fn rates(&self) -> Vec<Rate> {
        let mut r = match &self.model {
            PlantModel::MassSpringDamper(e) => vec![
                (
                    Param::Stiffness,
                    e.stiffness,
                    "N/m",
                    e.stiffness.sqrt() / e.mass.sqrt(),
                    MAX_RATE_PER_SAMPLE,
                ),
                (
                    Param::Damping,
                    e.damping,
                    "Ns/m",
                    e.damping / e.mass,
                    MAX_DECAY_PER_SAMPLE,
                ),
            ],
            PlantModel::TwoMass(t) => {
                let (j, mh) = (t.motor_mass, t.handle_mass + t.arm.mass);
                let (kt, bt) = (t.transmission_stiffness, t.transmission_damping);
                vec![
                    (
                        Param::TransmissionStiffness,
                        kt,
                        "N/m",
                        kt.sqrt() / j.sqrt() + kt.sqrt() / mh.sqrt(),
                        MAX_RATE_PER_SAMPLE,
                    ),
                    (
                        Param::ArmStiffness,
                        t.arm.stiffness,
                        "N/m",
                        t.arm.stiffness.sqrt() / mh.sqrt(),
                        MAX_RATE_PER_SAMPLE,
                    ),
                    (
                        Param::MotorDamping,
                        t.motor_damping,
                        "Ns/m",
                        t.motor_damping / j,
                        MAX_DECAY_PER_SAMPLE,
                    ),
                    (
                        Param::TransmissionDamping,
                        bt,
                        "Ns/m",
                        bt / j + bt / mh,
                        MAX_DECAY_PER_SAMPLE,
                    ),
                    (
                        Param::ArmDamping,
                        t.arm.damping,
                        "Ns/m",
                        t.arm.damping / mh,
                        MAX_DECAY_PER_SAMPLE,
                    ),
                ]
            }
            PlantModel::TransferFunction { den, .. } => {
                vec![(
                    Param::PlantDen,
                    f64::NAN,
                    "",
                    pole_bound(strip_leading_zeros(den)),
                    MAX_RATE_PER_SAMPLE,
                )]
            }
        };
        if self.force_lag > 0.0 {
            r.push((
                Param::ForceLag,
                self.force_lag,
                "s",
                1.0 / self.force_lag,
                MAX_DECAY_PER_SAMPLE,
            ));
        }
        r
    }

    /// Refuses a plant with a mode too fast for the sampling period (see
    /// [`MAX_RATE_PER_SAMPLE`] and [`MAX_DECAY_PER_SAMPLE`]), naming the parameter that makes it so.
    fn check_time_scale(&self, period: f64) -> Result<()> {
        for (param, value, unit, rate, limit) in self.rates() {
            let per_sample = rate * period;
            if per_sample.is_nan() || per_sample <= limit {
                continue;
            }
            let what = if value.is_nan() {
                String::new()
            } else {
                format!("= {value:e} {unit} ")
            };
            return Err(Error::Invalid {
                param,
                reason: format!(
                    "{what}makes a plant mode as fast as {rate:.3e} rad/s, {per_sample:.3e} per sampling \
                     period T = {period:e} s: beyond the exact discretization's range \
                     (rate × T ≤ {limit:e})"
                ),
            });
        }
        Ok(())
    }
}

/// A plant rate: the parameter that sets it, its value and unit, the rate in 1/s, and the
/// largest rate × T accepted.
type Rate = (Param, f64, &'static str, f64, f64);

/// Fujiwara's bound on the roots of a polynomial with descending coefficients:
/// 2·max |a_i/a_0|^{1/i} (the last term halved).
fn pole_bound(den: &[f64]) -> f64 {
    let n = den.len().saturating_sub(1);
    (1..=n)
        .map(|i| {
            let c = (den[i] / den[0]).abs();
            let c = if i == n { 0.5 * c } else { c };
            2.0 * c.powf(1.0 / i as f64)
        })
        .fold(0.0, f64::max)
}

/// Two springs in series, k1·k2/(k1 + k2) (0 when either is 0).
fn series_stiffness(k1: f64, k2: f64) -> f64 {
    if k1 == 0.0 || k2 == 0.0 {
        0.0
    } else {
        k1 * k2 / (k1 + k2)
    }
}

/// Evaluates a polynomial with descending coefficients at a complex point.
pub(crate) fn eval_desc(c: &[f64], s: num_complex::Complex64) -> num_complex::Complex64 {
    c.iter()
        .fold(num_complex::Complex64::new(0.0, 0.0), |acc, &x| acc * s + x)
}

/// Smallest mass accepted, in kg (1 mg): with the largest, [`MAX_MASS`], the masses of a loop
/// stay within 10¹² of each other and of the arm, so that no plant mode is slower or faster
/// than double precision can tell from z = 1 next to the others (a motor a 10¹⁸ times
/// heavier than its handle has a mode within 10⁻¹⁸ of the circle).
pub const MIN_MASS: f64 = 1e-6;

/// Largest mass accepted, in kg (1000 t); see [`MIN_MASS`].
pub const MAX_MASS: f64 = 1e6;

/// The range of [`MIN_MASS`] and [`MAX_MASS`] for messages.
const MASS_RANGE: &str = "[1e-6, 1e6] kg";

/// Refuses a mass outside [[`MIN_MASS`], [`MAX_MASS`]], naming it.
fn check_mass(param: Param, m: f64) -> Result<()> {
    if (MIN_MASS..=MAX_MASS).contains(&m) {
        return Ok(());
    }
    Err(Error::OutOfRange {
        param,
        value: m,
        range: MASS_RANGE,
    })
}

/// The masses of a two-mass device in range: the motor's, and the handle's with the arm's
/// (blaming the larger of the two when the sum is too heavy, the sum when too light).
fn check_two_mass(t: &TwoMass) -> Result<()> {
    check_mass(Param::MotorMass, t.motor_mass)?;
    let sum = t.handle_mass + t.arm.mass;
    if sum > MAX_MASS {
        return if t.handle_mass >= t.arm.mass {
            check_mass(Param::HandleMass, t.handle_mass.max(sum))
        } else {
            check_mass(Param::ArmMass, t.arm.mass.max(sum))
        };
    }
    check_mass(Param::HandleAndArmMass, sum)
}

fn validate_model(model: &PlantModel) -> Result<()> {
    match model {
        PlantModel::MassSpringDamper(e) => {
            Effective::new(e.mass, e.damping, e.stiffness)?;
            check_mass(Param::Mass, e.mass)?;
        }
        PlantModel::TwoMass(t) => {
            positive(Param::MotorMass, t.motor_mass)?;
            non_negative(Param::MotorDamping, t.motor_damping)?;
            non_negative(Param::HandleMass, t.handle_mass)?;
            positive(Param::TransmissionStiffness, t.transmission_stiffness)?;
            non_negative(Param::TransmissionDamping, t.transmission_damping)?;
            non_negative(Param::ArmMass, t.arm.mass)?;
            non_negative(Param::ArmDamping, t.arm.damping)?;
            non_negative(Param::ArmStiffness, t.arm.stiffness)?;
            if t.handle_mass + t.arm.mass == 0.0 {
                return Err(Error::NotPositive {
                    param: Param::HandleAndArmMass,
                    value: 0.0,
                });
            }
            check_two_mass(t)?;
        }
        PlantModel::TransferFunction { num, den } => validate_tf(num, den)?,
    }
    Ok(())
}

/// Largest plant order accepted: haptic plants are of order 2 to 6; the bound keeps the
/// dense matrix exponential and characteristic polynomials small and accurate.
pub const MAX_PLANT_ORDER: usize = 12;

fn validate_tf(num: &[f64], den: &[f64]) -> Result<()> {
    for &c in num {
        finite(Param::PlantNumCoefficient, c)?;
    }
    for &c in den {
        finite(Param::PlantDenCoefficient, c)?;
    }
    let den = strip_leading_zeros(den);
    let num = strip_leading_zeros(num);
    if den.is_empty() {
        return Err(Error::Invalid {
            param: Param::PlantDen,
            reason: "is zero".into(),
        });
    }
    if num.is_empty() {
        return Err(Error::Invalid {
            param: Param::PlantNum,
            reason: "is zero (the wall would act on nothing)".into(),
        });
    }
    if num.len() >= den.len() {
        return Err(Error::Invalid {
            param: Param::PlantTransferFunction,
            reason: format!(
                "must be strictly proper: numerator degree < denominator degree (got numerator degree {}, denominator degree {})",
                num.len() - 1,
                den.len() - 1
            ),
        });
    }
    if den.len() - 1 > MAX_PLANT_ORDER {
        return Err(Error::OutOfRange {
            param: Param::PlantOrder,
            value: (den.len() - 1) as f64,
            range: "1..=12",
        });
    }
    Ok(())
}

/// Drops leading (highest-power) zeros of a descending coefficient list.
pub(crate) fn strip_leading_zeros(c: &[f64]) -> &[f64] {
    let first = c.iter().position(|&x| x != 0.0).unwrap_or(c.len());
    &c[first..]
}

impl VelocityEstimator {
    /// Checks the estimator's parameters (f_c > 0, N >= 1, a0 ≠ 0, finite coefficients).
    pub fn validated(self) -> Result<Self> {
        match &self {
            VelocityEstimator::Backward => {}
            VelocityEstimator::LowPass { cutoff_hz } => {
                positive(Param::VelocityCutoff, *cutoff_hz)?;
            }
            VelocityEstimator::Butterworth { .. }
            | VelocityEstimator::Bessel { .. }
            | VelocityEstimator::CriticallyDamped { .. } => {
                if let Some(f) = self.named_lowpass() {
                    f.validated()?;
                }
            }
            VelocityEstimator::Average { samples } => {
                if *samples == 0 || *samples > MAX_DELAY {
                    return Err(Error::OutOfRange {
                        param: Param::VelocityWindow,
                        value: *samples as f64,
                        range: "1..=2000",
                    });
                }
            }
            VelocityEstimator::Iir { b, a } => {
                for &c in b.iter().chain(a) {
                    finite(Param::VelocityFilterCoefficient, c)?;
                }
                if a.first().copied().unwrap_or(0.0) == 0.0 {
                    return Err(Error::Invalid {
                        param: Param::VelocityFilterA0,
                        reason: "must be nonzero (the filter must be causal)".into(),
                    });
                }
                check_filter_range(b, a)?;
                if b.is_empty() || b.iter().all(|&x| x == 0.0) {
                    return Err(Error::Invalid {
                        param: Param::VelocityFilterNumerator,
                        reason: "is zero (the wall's damper would act on nothing)".into(),
                    });
                }
                if b.len().max(a.len()) > MAX_DELAY + 1 {
                    return Err(Error::OutOfRange {
                        param: Param::VelocityFilterLength,
                        value: b.len().max(a.len()) as f64,
                        range: "1..=2001",
                    });
                }
            }
        }
        Ok(self)
    }

    /// The estimator as a discrete transfer function from position to T·velocity (the
    /// velocity in metres per sample), V(z) = num(z)/den(z) in ascending powers of z with a
    /// monic denominator.
    pub fn per_sample_filter(&self, period: f64) -> (Vec<f64>, Vec<f64>) {
        match self {
            VelocityEstimator::Backward => (vec![-1.0, 1.0], vec![0.0, 1.0]),
            VelocityEstimator::LowPass { cutoff_hz } => {
                let a = (-2.0 * std::f64::consts::PI * cutoff_hz * period).exp();
                (vec![-(1.0 - a), 1.0 - a], vec![-a, 1.0])
            }
            VelocityEstimator::Average { samples } => {
                let n = *samples;
                let mut num = vec![0.0; n + 1];
                num[0] = -1.0 / n as f64;
                num[n] = 1.0 / n as f64;
                let mut den = vec![0.0; n + 1];
                den[n] = 1.0;
                (num, den)
            }
            VelocityEstimator::Butterworth { order, cutoff_hz } => {
                NamedLowPass::new(Family::Butterworth, *order, *cutoff_hz).per_sample_filter(period)
            }
            VelocityEstimator::Bessel { order, cutoff_hz } => {
                NamedLowPass::new(Family::Bessel, *order, *cutoff_hz).per_sample_filter(period)
            }
            VelocityEstimator::CriticallyDamped { order, cutoff_hz } => {
                NamedLowPass::new(Family::CriticallyDamped, *order, *cutoff_hz)
                    .per_sample_filter(period)
            }
            VelocityEstimator::Iir { b, a } => {
                let len = b.len().max(a.len());
                let a0 = a[0];
                // Σ b_i z^{−i} = z^{−(len−1)} Σ b_i z^{len−1−i}: ascending index len−1−i.
                let mut num = vec![0.0; len];
                let mut den = vec![0.0; len];
                for (i, &bi) in b.iter().enumerate() {
                    num[len - 1 - i] = period * bi / a0;
                }
                for (i, &ai) in a.iter().enumerate() {
                    den[len - 1 - i] = ai / a0;
                }
                (num, den)
            }
        }
    }
}

impl VelocityEstimator {
    /// Refuses a named low-pass (Butterworth, Bessel, critically damped) whose cut-off is at
    /// or beyond the Nyquist frequency 1/(2T) of the period.
    pub fn within_nyquist(self, period: f64) -> Result<Self> {
        if let Some(f) = self.named_lowpass() {
            f.within_nyquist(period)?;
        }
        Ok(self)
    }

    /// The DC gain of [`VelocityEstimator::per_sample_filter`], T·V(1), formed from the
    /// estimator's own parameters: exactly 0 for every differentiator (backward difference,
    /// low-pass, average, and an IIR filter whose numerator sums to zero as typed), where the
    /// scaled coefficients would leave a rounding residue of 1e-17. T·Σb/Σa for an IIR filter.
    pub fn per_sample_dc_gain(&self, period: f64) -> f64 {
        match self {
            VelocityEstimator::Backward
            | VelocityEstimator::LowPass { .. }
            | VelocityEstimator::Butterworth { .. }
            | VelocityEstimator::Bessel { .. }
            | VelocityEstimator::CriticallyDamped { .. }
            | VelocityEstimator::Average { .. } => 0.0,
            VelocityEstimator::Iir { b, a } => {
                let (sb, sa) = (exact_sum(b), exact_sum(a));
                if sb == 0.0 { 0.0 } else { period * sb / sa }
            }
        }
    }
}

/// A sum of doubles with compensated (Neumaier) summation: exactly zero when the terms cancel
/// exactly, as a differentiator's numerator 600, −500, −100 does.
fn exact_sum(x: &[f64]) -> f64 {
    let (mut s, mut c) = (0.0_f64, 0.0_f64);
    for &v in x {
        let t = s + v;
        c += if s.abs() >= v.abs() {
            (s - t) + v
        } else {
            (v - t) + s
        };
        s = t;
    }
    s + c
}

/// Largest magnitude of a velocity filter's coefficient relative to a0, |b_i/a0| and
/// |a_i/a0|: far beyond any estimator (a differentiator's taps are about 1/T ≤ 10⁷), and far
/// enough below the overflow of double precision (10³⁰⁸) that p(z), its wall terms and their
/// squares stay finite.
pub const MAX_FILTER_RATIO: f64 = 1e50;

/// Refuses a filter whose coefficients relative to a0 exceed [`MAX_FILTER_RATIO`] (or
/// overflow), blaming the coefficient when it is itself beyond that range and a0 when it is
/// a0's smallness that makes the ratio.
fn check_filter_range(b: &[f64], a: &[f64]) -> Result<()> {
    let a0 = a[0];
    let parts = [
        (Param::VelocityFilterNumerator, b),
        (Param::VelocityFilterDenominator, a),
    ];
    for (name, part) in parts {
        for (i, &c) in part.iter().enumerate() {
            let ratio = (c / a0).abs();
            if ratio <= MAX_FILTER_RATIO {
                continue;
            }
            let letter = if name == Param::VelocityFilterNumerator {
                'b'
            } else {
                'a'
            };
            let (name, value) = if c.abs() > MAX_FILTER_RATIO {
                (name, c)
            } else {
                (Param::VelocityFilterA0, a0)
            };
            return Err(Error::Invalid {
                param: name,
                reason: format!(
                    "= {value:e} makes {letter}{i}/a0 = {ratio:e}: beyond the representable range \
                     (|b_i/a0|, |a_i/a0| ≤ {MAX_FILTER_RATIO:e})"
                ),
            });
        }
    }
    Ok(())
}

/// Largest ratio of a wall's term of p(z) = P0 + a·PK + b·PB to the loop's own part P0
/// (largest coefficients, P0 monic): beyond about 10¹⁵⁰ the roots' evaluations square
/// past the overflow of double precision; 10¹⁰⁰ keeps far from that.
pub const MAX_WALL_TERM: f64 = 1e100;

/// Refuses a wall whose stiffness or damping term of p(z) exceeds the loop's own part by
/// more than [`MAX_WALL_TERM`], naming the wall's parameter and its value (`units` is the
/// wall in the family's units; `normalized` names it α, β instead of K, B).
pub fn check_wall_range(
    fam: &crate::closed_loop::AffineFamily,
    wall: crate::params::Wall,
    units: (f64, f64),
    normalized: bool,
) -> Result<()> {
    let largest = |c: &[f64]| c.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let own = largest(&fam.p0_core).max(1.0);
    let terms = [
        (
            Param::WallStiffness,
            Param::Alpha,
            "N/m",
            wall.stiffness,
            units.0,
            &fam.pk,
        ),
        (
            Param::WallDamping,
            Param::Beta,
            "Ns/m",
            wall.damping,
            units.1,
            &fam.pb,
        ),
    ];
    for (name, normalized_name, unit, value, t, part) in terms {
        let ratio = t.abs() * largest(part) / own;
        if ratio <= MAX_WALL_TERM {
            continue;
        }
        let (name, unit, value) = if normalized {
            (normalized_name, "", t)
        } else {
            (name, unit, value)
        };
        return Err(Error::Invalid {
            param: name,
            reason: format!(
                "= {value:e}{}{unit} makes its term of p(z) {ratio:.1e} times the loop's own: \
                 beyond the representable range (at most {MAX_WALL_TERM:e})",
                if unit.is_empty() { "" } else { " " }
            ),
        });
    }
    Ok(())
}

impl Loop {
    /// Validates and bundles the parts of a loop.
    pub fn new(
        plant: Plant,
        period: f64,
        delay: Delay,
        velocity: VelocityEstimator,
    ) -> Result<Self> {
        positive(Param::Period, period)?;
        if !(MIN_PERIOD..=MAX_PERIOD).contains(&period) {
            return Err(Error::OutOfRange {
                param: Param::Period,
                value: period,
                range: "[1e-7, 1] s",
            });
        }
        let plant = plant.validated()?;
        plant.check_time_scale(period)?;
        Ok(Self {
            plant,
            period,
            delay: delay.validated()?,
            velocity: velocity.validated()?.within_nyquist(period)?,
        })
    }

    /// The paper's loop in physical units: plant 1/(ms² + bs + k) (eq. 1), period T, d whole
    /// samples of delay, backward-difference velocity.
    pub fn paper(plant: Effective, period: f64, d: usize) -> Result<Self> {
        Self::new(
            Plant::mass_spring_damper(plant)?,
            period,
            Delay::samples(d)?,
            VelocityEstimator::Backward,
        )
    }

    /// The delay time t_d in seconds.
    pub fn delay_time(&self) -> f64 {
        self.delay.in_samples() * self.period
    }

    /// The same loop with another delay.
    pub fn with_delay(&self, delay: Delay) -> Result<Self> {
        Self::new(
            self.plant.clone(),
            self.period,
            delay,
            self.velocity.clone(),
        )
    }
}
