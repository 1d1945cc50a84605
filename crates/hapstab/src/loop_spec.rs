//! A loop as a user writes it down, saves it and loads it again: the `input` object that
//! every JSON report echoes (`{"loop": {...}, "delay_time": ..., "wall": {...}}`), or the
//! `loop` object alone, or a whole report; every part of the loop optional, with the
//! defaults in one place ([`LoopSpec::resolve`]).
//!
//! ```json
//! {"loop": {"plant": {"model": {"kind": "transfer_function", "num": [10], "den": [1, 3, 10]},
//!                     "force_lag": 0.0005},
//!           "period": 0.001, "delay_time": 0.0003, "velocity": "lowpass:100"},
//!  "wall": {"stiffness": 2000, "damping": 5}}
//! ```
//!
//! The velocity estimator is its object form (`{"kind": "low_pass", "cutoff_hz": 100}`, as
//! reports write it) or its text form (`"lowpass:100"`, as `--velocity` takes it; see
//! [`crate::spec`]). The paper's loop in normalized units is `{"gamma": γ, "delta": δ,
//! "d": d}` with an optional wall `"alpha"`, `"beta"` (Table I), as reports echo it.
//! Every value goes through [`Loop::new`]'s checks; a field of the wrong kind or an unknown
//! field is named by its path ("loop.plant.model.mass: invalid type: …"); beside the loop of a
//! report's `input` stand its analysis's own settings (a sweep's parameter, ...), which are
//! not read: the command's flags give them.

use std::path::Path;

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};

use crate::error::{Error, Result};
use crate::model::{Delay, Loop, Plant, PlantModel, VelocityEstimator};
use crate::paper::PlantParams;
use crate::param::Param;
use crate::params::{Arm, Device, Effective, Wall};

/// Default sampling period T: 1 ms, the paper's upper limit (Section IV).
pub const DEFAULT_PERIOD: f64 = 1e-3;

/// Default virtual wall: K = 10 kN/m, B = 10 Ns/m.
pub const DEFAULT_WALL: Wall = Wall {
    stiffness: 10_000.0,
    damping: 10.0,
};

/// The default plant: the PHANToM-like device ([`Device::PHANTOM_LIKE`]) held by the typical
/// arm ([`Arm::TYPICAL`]) as one mass-spring-damper (eq. 1), the arm named as its operator.
pub fn default_plant() -> Result<Plant> {
    Plant::mass_spring_damper(Effective::combine(Device::PHANTOM_LIKE, Arm::TYPICAL)?)?
        .with_operator(Arm::TYPICAL)
}

/// A plant as written in a loop file: the model, the actuator lag τ in s (0 when left out)
/// and the arm a mass-spring-damper includes (eq. 1), as [`Plant`] serializes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlantSpec {
    /// The mechanical model.
    pub model: PlantModel,
    /// Actuator time constant τ in s.
    #[serde(default)]
    pub force_lag: f64,
    /// The arm inside a mass-spring-damper's m, b and k.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub operator: Option<Arm>,
}

/// A velocity estimator in a loop file: the object form reports write or the text form of
/// `--velocity`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum VelocitySpec {
    /// `"lowpass:100"`, parsed by [`crate::spec`].
    Text(String),
    /// `{"kind": "low_pass", "cutoff_hz": 100}`.
    Estimator(VelocityEstimator),
}

/// The loop object of a loop file, every part optional (see the module doc for the defaults).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoopSpec {
    /// The plant [default: [`default_plant`]].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plant: Option<PlantSpec>,
    /// Sampling period T in s [default: [`DEFAULT_PERIOD`]].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub period: Option<f64>,
    /// The delay in whole samples and a fraction [default: none].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub delay: Option<Delay>,
    /// The delay t_d in s (instead of `delay`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub delay_time: Option<f64>,
    /// The velocity estimator [default: backward difference].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<VelocitySpec>,
}

/// A loop read from a file: the loop, whether it is the paper's normalized loop (m = T = 1,
/// so K is α and B is β) and the wall the file names, if any.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadedLoop {
    /// The validated loop.
    pub lp: Loop,
    /// True for a normalized loop (`{"gamma", "delta", "d"}`).
    pub normalized: bool,
    /// The file's wall (K in N/m, B in Ns/m; α, β for a normalized loop).
    pub wall: Option<Wall>,
}

/// The paper's loop in normalized units as written in a file (Table I).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct NormalizedSpec {
    #[serde(default)]
    gamma: f64,
    #[serde(default)]
    delta: f64,
    #[serde(default)]
    d: usize,
    alpha: Option<f64>,
    beta: Option<f64>,
}

impl LoopSpec {
    /// The spec of a plant model with its actuator lag τ in s and operator, sampled with
    /// period T in s and read by `velocity`, without a delay (set `delay` or `delay_time`):
    /// the form every front end builds from its own arguments before [`LoopSpec::resolve`]
    /// applies the defaults, rules and limits.
    pub fn of_plant(
        model: PlantModel,
        force_lag: f64,
        operator: Option<Arm>,
        period: f64,
        velocity: VelocitySpec,
    ) -> Self {
        Self {
            plant: Some(PlantSpec {
                model,
                force_lag,
                operator,
            }),
            period: Some(period),
            delay: None,
            delay_time: None,
            velocity: Some(velocity),
        }
    }

    /// The loop this spec describes, its missing parts from the defaults (module doc), every
    /// value checked by [`Plant::validated`] and [`Loop::new`].
    pub fn resolve(&self) -> Result<Loop> {
        let plant = match &self.plant {
            None => default_plant()?,
            Some(p) => {
                let plant = Plant {
                    model: p.model.clone(),
                    force_lag: p.force_lag,
                    operator: p.operator,
                }
                .validated()?;
                if let PlantModel::MassSpringDamper(e) = &plant.model {
                    // γ = kT²/m and δ = bT/m must be finite (Table I)
                    PlantParams::from_physical(e, self.period.unwrap_or(DEFAULT_PERIOD))?;
                }
                plant
            }
        };
        let period = self.period.unwrap_or(DEFAULT_PERIOD);
        let delay = match (self.delay, self.delay_time) {
            (Some(_), Some(_)) => {
                return Err(Error::Invalid {
                    param: Param::LoopFileDelay,
                    reason:
                        "is given twice: give either delay (samples, fraction) or delay_time (s)"
                            .into(),
                });
            }
            (Some(d), None) => d,
            (None, Some(t)) => Delay::from_time(t, period)?,
            (None, None) => Delay::NONE,
        };
        Loop::new(plant, period, delay, self.velocity()?)
    }

    /// The velocity estimator, parsed from its text form where it is one.
    fn velocity(&self) -> Result<VelocityEstimator> {
        match &self.velocity {
            None => Ok(VelocityEstimator::Backward),
            Some(VelocitySpec::Text(t)) => t.parse(),
            Some(VelocitySpec::Estimator(v)) => Ok(v.clone()),
        }
    }

    /// The spec of a loop: every part written out, as reports echo it.
    pub fn of(lp: &Loop) -> Self {
        Self {
            plant: Some(PlantSpec {
                model: lp.plant.model.clone(),
                force_lag: lp.plant.force_lag,
                operator: lp.plant.operator,
            }),
            period: Some(lp.period),
            delay: Some(lp.delay),
            delay_time: None,
            velocity: Some(VelocitySpec::Estimator(lp.velocity.clone())),
        }
    }
}

/// Largest loop file read, in bytes: a loop is a few hundred bytes, a whole report with its
/// region polygons a few megabytes; anything longer (a device such as /dev/zero) is refused
/// before it fills the memory.
pub const MAX_FILE_BYTES: u64 = 64 << 20;

/// Reads a loop file (module doc). Errors name the file and the field.
pub fn load(path: &Path) -> Result<LoadedLoop> {
    use std::io::Read;
    let cannot = |e: std::io::Error| Error::Invalid {
        param: Param::LoopFile,
        reason: format!("'{}' cannot be read: {e}", path.display()),
    };
    let mut text = String::new();
    std::fs::File::open(path)
        .map_err(cannot)?
        .take(MAX_FILE_BYTES + 1)
        .read_to_string(&mut text)
        .map_err(cannot)?;
    if text.len() as u64 > MAX_FILE_BYTES {
        return Err(Error::Invalid {
            param: Param::LoopFile,
            reason: format!(
                "'{}' is longer than {} MB: not a loop file",
                path.display(),
                MAX_FILE_BYTES >> 20
            ),
        });
    }
    parse(&text).map_err(|e| {
        let why = match e {
            Error::Invalid {
                param: Param::LoopFile,
                reason,
            } => reason,
            other => other.to_string(),
        };
        Error::Invalid {
            param: Param::LoopFile,
            reason: format!("'{}': {why}", path.display()),
        }
    })
}

/// Parses the text of a loop file (module doc).
pub fn parse(text: &str) -> Result<LoadedLoop> {
    let value: Value = serde_json::from_str(text).map_err(|e| Error::Invalid {
        param: Param::LoopFile,
        reason: format!("is not JSON: {e}"),
    })?;
    let Value::Object(mut doc) = value else {
        return Err(invalid(
            "",
            "must be a JSON object (a loop, a report's input or a report)",
        ));
    };
    let mut prefix = "";
    if let Some(Value::Object(input)) = doc.remove("input") {
        (doc, prefix) = (input, "input.");
    }
    if ["gamma", "delta", "d"].iter().any(|k| doc.contains_key(*k)) {
        return normalized(doc, prefix);
    }
    let wall = match doc.remove("wall") {
        Some(w) => Some(field::<Wall>(w, &format!("{prefix}wall"))?),
        None => None,
    };
    let spec = match doc.remove("loop") {
        Some(inner) => {
            // the report's delay_time beside the loop repeats the loop's delay
            let echoed = doc.remove("delay_time");
            // beside a report's loop stand its analysis's own settings (a sweep's parameter
            // and damping constraint, ...), which the command's flags give anew; a loop file
            // holds nothing else
            if let Some((k, _)) = doc.iter().next().filter(|_| prefix.is_empty()) {
                return Err(invalid(
                    &format!("{prefix}{k}"),
                    "is not a part of a loop file",
                ));
            }
            let mut spec: LoopSpec = field(inner, &format!("{prefix}loop"))?;
            if spec.delay.is_none() && spec.delay_time.is_none() {
                spec.delay_time = echoed
                    .map(|v| field(v, &format!("{prefix}delay_time")))
                    .transpose()?;
            }
            spec
        }
        None => field(Value::Object(doc), prefix.trim_end_matches('.'))?,
    };
    Ok(LoadedLoop {
        lp: spec.resolve()?,
        normalized: false,
        wall,
    })
}

/// The normalized paper loop of a file.
fn normalized(doc: Map<String, Value>, prefix: &str) -> Result<LoadedLoop> {
    let n: NormalizedSpec = field(Value::Object(doc), prefix.trim_end_matches('.'))?;
    let lp = Loop::normalized(PlantParams::new(n.gamma, n.delta)?, n.d)?;
    let wall = match (n.alpha, n.beta) {
        (None, None) => None,
        (Some(alpha), Some(beta)) => Some(Wall {
            stiffness: alpha,
            damping: beta,
        }),
        _ => {
            return Err(invalid(
                prefix,
                "a normalized wall needs both alpha and beta",
            ));
        }
    };
    Ok(LoadedLoop {
        lp,
        normalized: true,
        wall,
    })
}

/// One part of the file, its errors named by their path in the file.
fn field<T: DeserializeOwned>(value: Value, at: &str) -> Result<T> {
    serde_path_to_error::deserialize(value).map_err(|e| {
        let inner = e.path().to_string();
        let path = match (at.is_empty(), inner == ".") {
            (true, _) => inner,
            (false, true) => at.to_string(),
            (false, false) => format!("{at}.{inner}"),
        };
        invalid(&path, &e.into_inner().to_string())
    })
}

fn invalid(path: &str, why: &str) -> Error {
    Error::Invalid {
        param: Param::LoopFile,
        reason: if path.is_empty() || path == "." {
            why.to_string()
        } else {
            format!("{path}: {why}")
        },
    }
}

/// The inputs of a command on one loop, as every report echoes them under `input`: the form
/// a loop file takes and [`parse`] reads back to the same loop.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum LoopInput {
    /// A physical loop in SI units and, for analyses at one point, its wall.
    Physical {
        /// The loop.
        #[serde(rename = "loop")]
        lp: Loop,
        /// t_d in s.
        delay_time: f64,
        /// The wall (K in N/m, B in Ns/m).
        #[serde(skip_serializing_if = "Option::is_none")]
        wall: Option<Wall>,
    },
    /// The paper's loop in normalized units (Table I).
    Normalized {
        /// γ.
        gamma: f64,
        /// δ.
        delta: f64,
        /// d.
        d: usize,
        /// α.
        #[serde(skip_serializing_if = "Option::is_none")]
        alpha: Option<f64>,
        /// β.
        #[serde(skip_serializing_if = "Option::is_none")]
        beta: Option<f64>,
    },
}

impl LoopInput {
    /// The input record of a loop (normalized: built by [`Loop::normalized`], its wall then
    /// α, β) and an optional wall in the loop's units.
    pub fn new(lp: &Loop, normalized: bool, wall: Option<Wall>) -> Self {
        match (normalized, lp.paper_view()) {
            (true, Some(pp)) => LoopInput::Normalized {
                gamma: pp.gamma,
                delta: pp.delta,
                d: lp.delay.samples,
                alpha: wall.map(|w| w.stiffness),
                beta: wall.map(|w| w.damping),
            },
            _ => LoopInput::Physical {
                lp: lp.clone(),
                delay_time: lp.delay_time(),
                wall,
            },
        }
    }

    /// The record as JSON text, for a loop file.
    pub fn to_json(&self) -> String {
        crate::json::pretty(self).unwrap_or_default()
    }
}
