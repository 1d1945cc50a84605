//! The models a recording is fitted with, their parameters, and the loop each parameter
//! vector makes: the plant kinds of [`crate::model::PlantModel`] with their physical
//! parameters, any of which can be held at a known value.
//!
//! | model | parameters (names as `sweep --param`) | plant |
//! |---|---|---|
//! | `mass-spring-damper` | mass, damping, stiffness | 1/(ms² + bs + k) (eq. 1) |
//! | `held-device` | device-mass, device-damping (usually held), arm-mass, arm-damping, arm-stiffness | eq. (1): m = m_L + m_H, b = b_L + b_H, k = k_H |
//! | `two-mass` | motor-mass, motor-damping, handle-mass, transmission-stiffness, transmission-damping | [`crate::model::TwoMass`] without an arm |
//! | `tf:N/D` | b0 … bN, a0 … a(D−1) | (b_N s^N + … + b0)/(s^D + a_{D−1}s^{D−1} + … + a0) |
//!
//! Physical parameters are positive and fitted as their logarithm; a transfer function's
//! numerator coefficients may have either sign and are fitted as they are, its
//! denominator's (positive for a stable plant, Stodola's condition) as logarithms.

use serde::Serialize;

use super::error::{IdResult, IdentifyError};
use crate::model::{Delay, Loop, Plant, PlantModel, TwoMass, VelocityEstimator};
use crate::params::{Arm, Device, Effective};
use crate::sweep::SweepParam;

/// Highest plant order a transfer-function model may have (the loop's own limit).
pub const MAX_TF_ORDER: usize = 12;

/// A model structure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ModelKind {
    /// One mass-spring-damper (device alone, or device and arm lumped).
    MassSpringDamper,
    /// A device (m_L, b_L) held by an arm (m_H, b_H, k_H), eq. (1).
    HeldDevice,
    /// A two-mass device without an arm.
    TwoMass,
    /// A strictly proper transfer function with a monic denominator.
    TransferFunction {
        /// Numerator order N.
        num_order: usize,
        /// Denominator order D > N.
        den_order: usize,
    },
}

/// How a parameter is moved by the optimiser.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Domain {
    /// Positive, fitted as its logarithm.
    Positive,
    /// Any sign, fitted as it is.
    Real,
}

/// One parameter of a model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParamInfo {
    /// Its name (`sweep --param`'s for physical parameters).
    pub name: String,
    /// Its SI unit.
    pub unit: String,
    /// Where it may lie.
    pub domain: Domain,
}

impl ModelKind {
    /// Parses `mass-spring-damper`, `held-device`, `two-mass` or `tf:N/D`.
    pub fn parse(text: &str) -> IdResult<Self> {
        let bad = |why: &str| IdentifyError::Parameter {
            name: "model".into(),
            reason: format!("'{text}': {why}"),
        };
        match text {
            "mass-spring-damper" | "msd" => return Ok(ModelKind::MassSpringDamper),
            "held-device" => return Ok(ModelKind::HeldDevice),
            "two-mass" => return Ok(ModelKind::TwoMass),
            _ => {}
        }
        let Some(orders) = text.strip_prefix("tf:") else {
            return Err(bad(
                "expected mass-spring-damper, held-device, two-mass or tf:N/D",
            ));
        };
        let (n, d) = orders
            .split_once('/')
            .ok_or_else(|| bad("expected tf:N/D, e.g. tf:0/3"))?;
        let (n, d) = match (n.trim().parse::<usize>(), d.trim().parse::<usize>()) {
            (Ok(n), Ok(d)) => (n, d),
            _ => return Err(bad("N and D must be whole numbers")),
        };
        if d == 0 || n >= d || d > MAX_TF_ORDER {
            return Err(bad("needs 0 ≤ N < D ≤ 12 (a strictly proper plant)"));
        }
        Ok(ModelKind::TransferFunction {
            num_order: n,
            den_order: d,
        })
    }

    /// The model's name as [`ModelKind::parse`] takes it.
    pub fn name(&self) -> String {
        match self {
            ModelKind::MassSpringDamper => "mass-spring-damper".into(),
            ModelKind::HeldDevice => "held-device".into(),
            ModelKind::TwoMass => "two-mass".into(),
            ModelKind::TransferFunction {
                num_order,
                den_order,
            } => format!("tf:{num_order}/{den_order}"),
        }
    }

    /// Every parameter of the model, in its order (module doc's table).
    pub fn params(&self) -> Vec<ParamInfo> {
        let p = |name: &str, unit: &str, domain| ParamInfo {
            name: name.into(),
            unit: unit.into(),
            domain,
        };
        use Domain::{Positive, Real};
        match self {
            ModelKind::MassSpringDamper => vec![
                p("mass", "kg", Positive),
                p("damping", "Ns/m", Positive),
                p("stiffness", "N/m", Positive),
            ],
            ModelKind::HeldDevice => vec![
                p("device-mass", "kg", Positive),
                p("device-damping", "Ns/m", Positive),
                p("arm-mass", "kg", Positive),
                p("arm-damping", "Ns/m", Positive),
                p("arm-stiffness", "N/m", Positive),
            ],
            ModelKind::TwoMass => vec![
                p("motor-mass", "kg", Positive),
                p("motor-damping", "Ns/m", Positive),
                p("handle-mass", "kg", Positive),
                p("transmission-stiffness", "N/m", Positive),
                p("transmission-damping", "Ns/m", Positive),
            ],
            ModelKind::TransferFunction {
                num_order,
                den_order,
            } => {
                // P in m/N: b_j·s^j and a_i·s^i weigh as s^D, so b_j is in m/N·s^{j−D}
                // and a_i in s^{i−D}
                let d = *den_order as i64;
                let mut v: Vec<ParamInfo> = (0..=*num_order)
                    .map(|j| p(&format!("b{j}"), &format!("m/N·s^{}", j as i64 - d), Real))
                    .collect();
                v.extend((0..*den_order).map(|i| {
                    p(
                        &format!("a{i}"),
                        &format!("s^{}", i as i64 - *den_order as i64),
                        Positive,
                    )
                }));
                v
            }
        }
    }

    /// The plant of a full parameter vector (in [`ModelKind::params`]' order) with an
    /// actuator lag τ, validated as every loop's plant.
    pub fn plant(&self, v: &[f64], force_lag: f64) -> crate::Result<Plant> {
        let plant = match self {
            ModelKind::MassSpringDamper => {
                Plant::mass_spring_damper(Effective::new(v[0], v[1], v[2])?)?
            }
            ModelKind::HeldDevice => Plant::held_device(
                Device {
                    mass: v[0],
                    damping: v[1],
                },
                Arm {
                    mass: v[2],
                    damping: v[3],
                    stiffness: v[4],
                },
            )?,
            ModelKind::TwoMass => Plant::new(
                PlantModel::TwoMass(TwoMass {
                    motor_mass: v[0],
                    motor_damping: v[1],
                    handle_mass: v[2],
                    transmission_stiffness: v[3],
                    transmission_damping: v[4],
                    arm: Arm::NONE,
                }),
                0.0,
            )?,
            ModelKind::TransferFunction { num_order, .. } => {
                let num: Vec<f64> = v[..=*num_order].iter().rev().copied().collect();
                let mut den = vec![1.0];
                den.extend(v[num_order + 1..].iter().rev());
                Plant::new(PlantModel::TransferFunction { num, den }, 0.0)?
            }
        };
        plant.with_force_lag(force_lag)
    }

    /// The loop parameter of [`crate::robust`]'s box that a model parameter is, if any.
    pub fn sweep_param(&self, name: &str) -> Option<SweepParam> {
        SweepParam::ALL.into_iter().find(|p| p.name() == name)
    }
}

/// A parameter held at a known value.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fixed {
    /// The parameter's name.
    pub name: String,
    /// Its value in its SI unit.
    pub value: f64,
}

impl Fixed {
    /// Parses `NAME=VALUE`.
    pub fn parse(text: &str) -> IdResult<Self> {
        let (name, value) = text
            .split_once('=')
            .ok_or_else(|| IdentifyError::Parameter {
                name: text.into(),
                reason: "expected NAME=VALUE".into(),
            })?;
        let value = value
            .trim()
            .parse::<f64>()
            .map_err(|_| IdentifyError::Parameter {
                name: name.trim().into(),
                reason: format!("'{}' is not a number", value.trim()),
            })?;
        Ok(Fixed {
            name: name.trim().into(),
            value,
        })
    }
}

/// What is fitted: the model, the parameters held fixed, and the known parts of the loop
/// (the delay and the actuator lag).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModelSpec {
    /// The model structure.
    pub kind: ModelKind,
    /// Parameters held at known values.
    pub fixed: Vec<Fixed>,
    /// The force's delay t_d in s (whole samples and a fraction of one, exactly as the loop).
    pub delay_time: f64,
    /// The actuator lag τ in s (0 for none).
    pub force_lag: f64,
    /// True when the delay is fitted (`delay-time`, after the model's parameters), the
    /// given `delay_time` its start.
    pub fit_delay: bool,
    /// True when the actuator lag is fitted (`force-lag`, last), the given `force_lag` its
    /// start.
    pub fit_force_lag: bool,
    /// The position's quantization step q in m (0 for none): the measurement noise is at
    /// least the rounding's q²/12 ([`super::uncertainty::covariance`]), and q is the position
    /// resolution of the renderable band ([`super::consequence`]).
    pub quantization: f64,
}

impl ModelSpec {
    /// A model with held parameters, checked: every held name is a parameter of the model
    /// and its value finite (and ≥ 0 for a positive parameter); `mass-spring-damper` with a
    /// held `device-mass` or `device-damping` is the `held-device` model.
    pub fn new(
        kind: ModelKind,
        fixed: Vec<Fixed>,
        delay_time: f64,
        force_lag: f64,
    ) -> IdResult<Self> {
        let holds_device = fixed.iter().any(|f| f.name.starts_with("device-"));
        let kind = if kind == ModelKind::MassSpringDamper && holds_device {
            ModelKind::HeldDevice
        } else {
            kind
        };
        let params = kind.params();
        for f in &fixed {
            let Some(p) = params.iter().find(|p| p.name == f.name) else {
                let names: Vec<&str> = params.iter().map(|p| p.name.as_str()).collect();
                return Err(IdentifyError::Parameter {
                    name: f.name.clone(),
                    reason: format!(
                        "not a parameter of {} (it has: {})",
                        kind.name(),
                        names.join(", ")
                    ),
                });
            };
            if !f.value.is_finite() || (p.domain == Domain::Positive && f.value < 0.0) {
                return Err(IdentifyError::Parameter {
                    name: f.name.clone(),
                    reason: format!("= {} must be a finite number ≥ 0", f.value),
                });
            }
        }
        if kind == ModelKind::HeldDevice {
            for name in ["device-mass", "device-damping"] {
                if !fixed.iter().any(|f| f.name == name) {
                    return Err(IdentifyError::Parameter {
                        name: name.into(),
                        reason: format!(
                            "a held device needs it known (--fix {name}=VALUE): the recording \
                             shows only the device's and the arm's sum (eq. 1)"
                        ),
                    });
                }
            }
        }
        for (name, v) in [("delay-time", delay_time), ("force-lag", force_lag)] {
            if !v.is_finite() || v < 0.0 {
                return Err(IdentifyError::Parameter {
                    name: name.into(),
                    reason: format!("= {v} must be a finite number ≥ 0"),
                });
            }
        }
        Ok(ModelSpec {
            kind,
            fixed,
            delay_time,
            force_lag,
            fit_delay: false,
            fit_force_lag: false,
            quantization: 0.0,
        })
    }

    /// The same spec with the position quantized in steps of `q` m (module doc of
    /// [`super::uncertainty`]); refused naming `quantization` unless q is finite and ≥ 0.
    pub fn with_quantization(self, q: f64) -> IdResult<Self> {
        if !q.is_finite() || q < 0.0 {
            return Err(IdentifyError::Parameter {
                name: "quantization".into(),
                reason: format!("= {q} must be a finite number ≥ 0 (m)"),
            });
        }
        Ok(ModelSpec {
            quantization: q,
            ..self
        })
    }

    /// The same spec with the delay and/or the actuator lag fitted too (both positive, as
    /// their logarithms; the exact sampled model is smooth in a fractional delay).
    pub fn fitting_timing(self, delay: bool, force_lag: bool) -> Self {
        ModelSpec {
            fit_delay: delay,
            fit_force_lag: force_lag,
            ..self
        }
    }

    /// Every parameter fitted or held: the model's, then `delay-time` and `force-lag` when
    /// they are fitted.
    pub fn params(&self) -> Vec<ParamInfo> {
        let mut p = self.kind.params();
        let timing = |name: &str| ParamInfo {
            name: name.into(),
            unit: "s".into(),
            domain: Domain::Positive,
        };
        if self.fit_delay {
            p.push(timing("delay-time"));
        }
        if self.fit_force_lag {
            p.push(timing("force-lag"));
        }
        p
    }

    /// The starting values of the fitted timing parameters at period T: the given delay
    /// (at least a quarter sample) and lag (half a sample when none is given).
    pub fn timing_start(&self, period: f64) -> Vec<f64> {
        let mut v = Vec::new();
        if self.fit_delay {
            v.push(self.delay_time.max(0.25 * period));
        }
        if self.fit_force_lag {
            v.push(if self.force_lag > 0.0 {
                self.force_lag
            } else {
                0.5 * period
            });
        }
        v
    }

    /// The held value of parameter `i`, if it is held.
    pub fn held(&self, i: usize) -> Option<f64> {
        let name = &self.params()[i].name;
        self.fixed.iter().find(|f| &f.name == name).map(|f| f.value)
    }

    /// Indices of the parameters that are fitted.
    pub fn free(&self) -> Vec<usize> {
        (0..self.params().len())
            .filter(|&i| self.held(i).is_none())
            .collect()
    }

    /// The loop of a full parameter vector at the recording's period, with the spec's delay
    /// and lag and the given velocity estimator.
    pub fn to_loop(
        &self,
        v: &[f64],
        period: f64,
        velocity: VelocityEstimator,
    ) -> crate::Result<Loop> {
        let mut at = self.kind.params().len();
        let mut next = |fitted: bool, given: f64| {
            if fitted {
                at += 1;
                v[at - 1]
            } else {
                given
            }
        };
        let delay = next(self.fit_delay, self.delay_time);
        let lag = next(self.fit_force_lag, self.force_lag);
        Loop::new(
            self.kind.plant(v, lag)?,
            period,
            Delay::from_time(delay, period)?,
            velocity,
        )
    }
}
