//! Query-string parsing and validation for the JSON API: every failure is an [`ApiError`]
//! (HTTP 400 with `{"error": ..., "parameter": ..., "value": ...}`) naming the parameter and
//! the offending value. Nothing here panics.

use std::collections::BTreeMap;

use axum::Json;
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use hapstab::loop_spec::{LoopSpec, VelocitySpec};
use hapstab::paper::PlantParams;
use hapstab::params::{Arm, Device, Effective};
use hapstab::{Delay, Param, Plant, PlantModel, System, TwoMass, VelocityEstimator};
use serde::Serialize;

use crate::limits::{
    MAX_D, MAX_DELTA, MAX_GAMMA, MAX_MASS, MAX_PERIOD, MAX_PHYS_DAMPING, MAX_PHYS_STIFFNESS,
    MIN_PERIOD,
};

/// An API error: status code and a JSON body `{"error": message, "parameter"?, "value"?}`.
#[derive(Debug, Clone)]
pub struct ApiError {
    pub status: StatusCode,
    pub message: String,
    pub parameter: Option<String>,
    pub value: Option<String>,
}

#[derive(Serialize)]
struct ErrorBody<'a> {
    error: &'a str,
    #[serde(skip_serializing_if = "Option::is_none")]
    parameter: Option<&'a str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    value: Option<&'a str>,
}

impl ApiError {
    /// A 400 about one parameter and its value.
    pub fn param(name: &str, value: &str, message: String) -> Self {
        Self {
            status: StatusCode::BAD_REQUEST,
            message,
            parameter: Some(name.to_string()),
            value: Some(clip(value)),
        }
    }

    /// A 400 not tied to one parameter.
    pub fn bad(message: String) -> Self {
        Self {
            status: StatusCode::BAD_REQUEST,
            message,
            parameter: None,
            value: None,
        }
    }

    /// Any other status.
    pub fn status(status: StatusCode, message: String) -> Self {
        Self {
            status,
            message,
            parameter: None,
            value: None,
        }
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let body = ErrorBody {
            error: &self.message,
            parameter: self.parameter.as_deref(),
            value: self.value.as_deref(),
        };
        (self.status, Json(body)).into_response()
    }
}

/// Error from the library (its messages already name the parameter and the value), with the
/// query parameter that carries it when there is one.
pub(crate) fn lib_error(e: hapstab::Error) -> ApiError {
    let parameter = e.param().and_then(Param::query).map(str::to_string);
    ApiError {
        status: StatusCode::BAD_REQUEST,
        message: e.to_string(),
        value: parameter.as_ref().and(e.value()).map(fmt),
        parameter,
    }
}

/// At most 40 characters of a user-supplied value, for messages.
pub(crate) fn clip(s: &str) -> String {
    if s.chars().count() > 40 {
        let mut t: String = s.chars().take(40).collect();
        t.push('…');
        t
    } else {
        s.to_string()
    }
}

/// Formats a number for a message (shortest round-trip form).
pub(crate) fn fmt(x: f64) -> String {
    format!("{x}")
}

/// The parsed query string of one request: each name at most once, only allowed names.
pub(crate) struct Params {
    map: BTreeMap<String, String>,
}

impl Params {
    /// Checks for duplicates and unknown names.
    pub(crate) fn new(pairs: Vec<(String, String)>, allowed: &[&str]) -> Result<Self, ApiError> {
        let mut map: BTreeMap<String, String> = BTreeMap::new();
        for (k, v) in pairs {
            if !allowed.contains(&k.as_str()) {
                return Err(ApiError::param(
                    &k,
                    &v,
                    format!(
                        "unknown parameter '{}' (value '{}'; allowed: {})",
                        clip(&k),
                        clip(&v),
                        allowed.join(", ")
                    ),
                ));
            }
            if let Some(first) = map.get(&k) {
                return Err(ApiError::param(
                    &k,
                    &v,
                    format!(
                        "parameter '{}' given more than once (values '{}' and '{}')",
                        clip(&k),
                        clip(first),
                        clip(&v)
                    ),
                ));
            }
            map.insert(k, v);
        }
        Ok(Self { map })
    }

    /// The raw value, if present.
    pub(crate) fn raw(&self, name: &str) -> Option<&str> {
        self.map.get(name).map(String::as_str)
    }

    /// True if present.
    pub(crate) fn has(&self, name: &str) -> bool {
        self.map.contains_key(name)
    }

    /// An optional finite number.
    pub(crate) fn opt_num(&self, name: &str) -> Result<Option<f64>, ApiError> {
        let Some(s) = self.raw(name) else {
            return Ok(None);
        };
        let t = s.trim();
        let x: f64 = t.parse().map_err(|_| {
            ApiError::param(
                name,
                s,
                format!("parameter '{name}' must be a number (got '{}')", clip(s)),
            )
        })?;
        if !x.is_finite() {
            return Err(ApiError::param(
                name,
                s,
                format!(
                    "parameter '{name}' must be a finite number (got '{}')",
                    clip(s)
                ),
            ));
        }
        Ok(Some(x))
    }

    /// A required finite number.
    pub(crate) fn num(&self, name: &str) -> Result<f64, ApiError> {
        self.opt_num(name)?.ok_or_else(|| missing(name))
    }

    /// A required number in [lo, hi].
    pub(crate) fn num_in(&self, name: &str, lo: f64, hi: f64, why: &str) -> Result<f64, ApiError> {
        let x = self.num(name)?;
        self.check_range(name, x, lo, hi, why)
    }

    /// lo <= x <= hi, with the value shown as the client wrote it.
    fn check_range(
        &self,
        name: &str,
        x: f64,
        lo: f64,
        hi: f64,
        why: &str,
    ) -> Result<f64, ApiError> {
        if x < lo || x > hi {
            let raw = self.raw(name).map_or_else(|| fmt(x), |s| clip(s.trim()));
            return Err(ApiError::param(
                name,
                &raw,
                format!(
                    "parameter '{name}' must be in [{}, {}]{why} (got {raw})",
                    fmt(lo),
                    fmt(hi),
                ),
            ));
        }
        Ok(x)
    }

    /// An optional number in [lo, hi] with a default.
    pub(crate) fn num_or(
        &self,
        name: &str,
        default: f64,
        lo: f64,
        hi: f64,
        why: &str,
    ) -> Result<f64, ApiError> {
        match self.opt_num(name)? {
            Some(x) => self.check_range(name, x, lo, hi, why),
            None => Ok(default),
        }
    }

    /// An optional whole number in [lo, hi].
    pub(crate) fn opt_count(
        &self,
        name: &str,
        lo: usize,
        hi: usize,
        why: &str,
    ) -> Result<Option<usize>, ApiError> {
        let Some(x) = self.opt_num(name)? else {
            return Ok(None);
        };
        if x.fract() != 0.0 || x < lo as f64 || x > hi as f64 {
            let raw = self.raw(name).map_or_else(|| fmt(x), |s| clip(s.trim()));
            return Err(ApiError::param(
                name,
                &raw,
                format!(
                    "parameter '{name}' must be a whole number in [{lo}, {hi}]{why} (got {raw})"
                ),
            ));
        }
        Ok(Some(x as usize))
    }

    /// A required whole number in [lo, hi].
    pub(crate) fn count(
        &self,
        name: &str,
        lo: usize,
        hi: usize,
        why: &str,
    ) -> Result<usize, ApiError> {
        self.opt_count(name, lo, hi, why)?
            .ok_or_else(|| missing(name))
    }

    /// An optional choice among fixed words.
    pub(crate) fn choice<'a>(
        &self,
        name: &str,
        options: &[&'a str],
        default: &'a str,
    ) -> Result<&'a str, ApiError> {
        match self.raw(name) {
            None => Ok(default),
            Some(s) => options.iter().find(|o| **o == s).copied().ok_or_else(|| {
                ApiError::param(
                    name,
                    s,
                    format!(
                        "parameter '{name}' must be one of {} (got '{}')",
                        options.join(", "),
                        clip(s)
                    ),
                )
            }),
        }
    }

    /// An optional boolean: 1/0/true/false/yes/no/on/off.
    pub(crate) fn flag(&self, name: &str) -> Result<bool, ApiError> {
        match self.raw(name) {
            None => Ok(false),
            Some(s) => match s {
                "1" | "true" | "yes" | "on" => Ok(true),
                "0" | "false" | "no" | "off" | "" => Ok(false),
                _ => Err(ApiError::param(
                    name,
                    s,
                    format!("parameter '{name}' must be 1 or 0 (got '{}')", clip(s)),
                )),
            },
        }
    }
}

fn missing(name: &str) -> ApiError {
    ApiError {
        status: StatusCode::BAD_REQUEST,
        message: format!("missing parameter '{name}'"),
        parameter: Some(name.to_string()),
        value: None,
    }
}

/// The physical description of the physical-units mode.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct PhysicalSpec {
    pub device_mass: f64,
    pub device_damping: f64,
    pub arm_mass: f64,
    pub arm_damping: f64,
    pub arm_stiffness: f64,
    /// Sampling period T in s.
    pub period: f64,
    /// Delay t_d = dT in s.
    pub delay_time: f64,
    /// Effective mass m = m_L + m_H (eq. 1).
    pub mass: f64,
    /// Effective damping b = b_L + b_H.
    pub damping: f64,
    /// Effective stiffness k = k_H.
    pub stiffness: f64,
    /// N/m of one wall unit a = K/k_per_unit (m/T² for the paper's loop: per unit α).
    pub k_per_unit: f64,
    /// Ns/m of one wall unit b = B/b_per_unit (m/T for the paper's loop: per unit β).
    pub b_per_unit: f64,
}

/// The loop of a request, built once for every mode: its analysis object, the paper's
/// plant (γ, δ, d) when the loop is the paper's, and its physical description.
#[derive(Debug, Clone)]
pub struct PlantSpec {
    /// The loop with its family ([`System`]); the normalized mode's loop has m = T = 1
    /// ([`hapstab::Loop::normalized`]), so that its wall units are (α, β).
    pub sys: System,
    /// The paper's plant and delay ([`hapstab::Loop::paper_view`]): None beyond the paper's
    /// loop (another plant, an actuator lag, a velocity filter, a fractional delay).
    pub paper: Option<PaperPlant>,
    /// The physical description; None in the normalized mode.
    pub physical: Option<PhysicalSpec>,
}

/// The paper's plant (γ, δ) of Table I and its delay d in samples.
#[derive(Debug, Clone, Copy)]
pub struct PaperPlant {
    /// Normalized stiffness γ and damping δ.
    pub plant: PlantParams,
    /// Delay d in samples.
    pub d: usize,
}

impl PlantSpec {
    /// The delay that prices a computation: the d of a paper loop of the same degree of p(z)
    /// (degree d + 3; for the paper's loop its own d).
    pub fn cost_d(&self) -> usize {
        self.sys.family().degree().saturating_sub(3)
    }

    /// The (γ, δ) and d the page is drawn with: the paper's plant, or beyond the paper's loop
    /// its static stiffness in wall units as γ (the z = 1 edge lies at a = −γ), δ = 0 and the
    /// delay's whole samples.
    pub fn view(&self) -> PaperPlant {
        self.paper.unwrap_or_else(|| {
            let fam = self.sys.family();
            let lp = self.sys.lp();
            let static_k = lp.plant.dc_stiffness().unwrap_or(0.0);
            PaperPlant {
                plant: PlantParams {
                    gamma: (static_k / fam.scale.stiffness).max(0.0),
                    delta: 0.0,
                },
                d: lp.delay.samples,
            }
        })
    }

    /// The query parameter that sets the degree of p(z), with its value: `delay_time` for a
    /// fractional delay, else `d`.
    pub fn delay_param(&self) -> (&'static str, String) {
        let lp = self.sys.lp();
        if lp.delay.fraction > 0.0 {
            ("delay_time", fmt(lp.delay_time()))
        } else {
            ("d", lp.delay.samples.to_string())
        }
    }
}

/// Parameter names of the plant (both modes).
pub(crate) const PLANT_PARAMS: &[&str] = &[
    "mode",
    "gamma",
    "delta",
    "d",
    "device_mass",
    "device_damping",
    "arm_mass",
    "arm_damping",
    "arm_stiffness",
    "period",
    "delay_time",
    "estimator",
    "force_lag",
    "motor_mass",
    "motor_damping",
    "handle_mass",
    "transmission_stiffness",
    "transmission_damping",
    "plant_num",
    "plant_den",
];

/// The plant parameters that only the physical mode accepts (the tail of [`PLANT_PARAMS`]).
const PHYSICAL_ONLY: &[&str] = PLANT_PARAMS.split_at(4).1;

fn delay(p: &Params) -> Result<usize, ApiError> {
    p.count(
        "d",
        0,
        MAX_D,
        " (delay in whole samples; bounded for interactive use)",
    )
}

/// Reads `mode` (normalized | physical) and the loop of that mode: (γ, δ, d) of the paper's
/// loop in normalized units, or a physical loop through [`LoopSpec`] (the paper's device held
/// by an arm, or any plant, actuator lag, velocity estimator and fractional delay).
pub(crate) fn plant_spec(p: &Params) -> Result<PlantSpec, ApiError> {
    let mode = p.choice("mode", &["normalized", "physical"], "normalized")?;
    if mode == "normalized" {
        return normalized_spec(p);
    }
    refuse(p, &["gamma", "delta"], "belongs to mode=normalized")?;
    physical_spec(p)
}

/// The normalized mode: (γ, δ, d) of the paper's loop, no physical parameter.
fn normalized_spec(p: &Params) -> Result<PlantSpec, ApiError> {
    refuse(p, PHYSICAL_ONLY, "belongs to mode=physical")?;
    let gamma = p.num_in("gamma", 0.0, MAX_GAMMA, " (normalized stiffness γ = kT²/m)")?;
    let delta = p.num_in("delta", 0.0, MAX_DELTA, " (normalized damping δ = bT/m)")?;
    let d = delay(p)?;
    let plant = PlantParams::new(gamma, delta).map_err(lib_error)?;
    let lp = hapstab::Loop::normalized(plant, d).map_err(lib_error)?;
    Ok(PlantSpec {
        sys: System::new(lp).map_err(lib_error)?,
        paper: Some(PaperPlant { plant, d }),
        physical: None,
    })
}

/// The (γ, δ) that physical parameters give are within the explorer's bounds.
fn check_explorer_range(plant: &PlantParams) -> Result<(), ApiError> {
    if plant.gamma > MAX_GAMMA || plant.delta > MAX_DELTA {
        return Err(ApiError::bad(format!(
            "the physical parameters give γ = kT²/m = {} and δ = bT/m = {}; the explorer accepts γ <= {} and δ <= {}",
            fmt(plant.gamma),
            fmt(plant.delta),
            fmt(MAX_GAMMA),
            fmt(MAX_DELTA)
        )));
    }
    Ok(())
}

/// No one-mass device (a two-mass device or a transfer function describes the plant).
const NO_DEVICE: Device = Device {
    mass: 0.0,
    damping: 0.0,
};

/// Longest actuator time constant accepted: a current loop is far faster than 1 s.
const MAX_FORCE_LAG: f64 = 1.0;

/// None of `names` may be given: the first one present is refused with `why`.
fn refuse(p: &Params, names: &[&str], why: &str) -> Result<(), ApiError> {
    for &name in names {
        if let Some(v) = p.raw(name) {
            return Err(ApiError::param(
                name,
                v,
                format!("parameter '{name}' (got '{}') {why}", clip(v)),
            ));
        }
    }
    Ok(())
}

/// The one-mass device: `device_mass`, `device_damping`.
fn device(p: &Params) -> Result<Device, ApiError> {
    Ok(Device {
        mass: p.num_in("device_mass", 0.0, MAX_MASS, " kg")?,
        damping: p.num_in("device_damping", 0.0, MAX_PHYS_DAMPING, " Ns/m")?,
    })
}

/// The operator's arm: `arm_mass`, `arm_damping`, `arm_stiffness`.
fn arm(p: &Params) -> Result<Arm, ApiError> {
    Ok(Arm {
        mass: p.num_in("arm_mass", 0.0, MAX_MASS, " kg")?,
        damping: p.num_in("arm_damping", 0.0, MAX_PHYS_DAMPING, " Ns/m")?,
        stiffness: p.num_in("arm_stiffness", 0.0, MAX_PHYS_STIFFNESS, " N/m")?,
    })
}

/// The coefficient list of `param` (its key is the query parameter: plant_num, plant_den).
fn coefficients(p: &Params, param: Param) -> Result<Vec<f64>, ApiError> {
    let name = param.key();
    let v = p.raw(name).ok_or_else(|| missing(name))?;
    hapstab::spec::parse_coefficients(param, v)
        .map_err(|e| ApiError::param(name, v, format!("parameter '{name}': {e}")))
}

/// The plant model of a general loop: a transfer function (plant_num, plant_den), a two-mass
/// device (motor_mass, transmission_stiffness, …, the arm on the handle) or the paper's
/// device + arm.
fn plant_model(p: &Params) -> Result<PlantModel, ApiError> {
    const DEVICE: &[&str] = &["device_mass", "device_damping"];
    const ARM: &[&str] = &["arm_mass", "arm_damping", "arm_stiffness"];
    const TWO_MASS: &[&str] = &[
        "motor_mass",
        "motor_damping",
        "handle_mass",
        "transmission_stiffness",
        "transmission_damping",
    ];
    if p.has("plant_num") || p.has("plant_den") {
        let why = "does not combine with a transfer-function plant (plant_num/plant_den)";
        refuse(p, DEVICE, why)?;
        refuse(p, ARM, why)?;
        refuse(p, TWO_MASS, why)?;
        let num = coefficients(p, Param::PlantNum)?;
        let den = coefficients(p, Param::PlantDen)?;
        return Ok(PlantModel::TransferFunction { num, den });
    }
    if TWO_MASS.iter().any(|n| p.has(n)) {
        refuse(
            p,
            DEVICE,
            "does not combine with a two-mass device (motor_mass, …)",
        )?;
        return Ok(PlantModel::TwoMass(TwoMass {
            motor_mass: p.num_in("motor_mass", 0.0, MAX_MASS, " kg")?,
            motor_damping: p.num_or("motor_damping", 0.0, 0.0, MAX_PHYS_DAMPING, " Ns/m")?,
            handle_mass: p.num_or("handle_mass", 0.0, 0.0, MAX_MASS, " kg")?,
            transmission_stiffness: p.num_in(
                "transmission_stiffness",
                0.0,
                MAX_PHYS_STIFFNESS,
                " N/m",
            )?,
            transmission_damping: p.num_or(
                "transmission_damping",
                0.0,
                0.0,
                MAX_PHYS_DAMPING,
                " Ns/m",
            )?,
            arm: arm(p)?,
        }));
    }
    let (device, arm) = (device(p)?, arm(p)?);
    if device.mass + arm.mass <= 0.0 {
        return Err(ApiError::param(
            "device_mass",
            &fmt(device.mass),
            format!(
                "the effective mass m = device_mass + arm_mass must be > 0 (got {} + {})",
                fmt(device.mass),
                fmt(arm.mass)
            ),
        ));
    }
    let eff = Effective::combine(device, arm).map_err(lib_error)?;
    Ok(PlantModel::MassSpringDamper(eff))
}

/// The delay of a general loop: d whole samples or t_d = (d + λ)T in seconds.
fn general_delay(p: &Params, period: f64) -> Result<Delay, ApiError> {
    let delay = match (p.raw("d"), p.opt_num("delay_time")?) {
        (Some(v), Some(_)) => {
            return Err(ApiError::param(
                "d",
                v,
                "give either 'd' (samples) or 'delay_time' (s), not both".into(),
            ));
        }
        (Some(_), None) => Delay::samples(delay(p)?).map_err(lib_error)?,
        (None, Some(td)) => Delay::from_time(td, period).map_err(|e| {
            ApiError::param(
                "delay_time",
                &fmt(td),
                format!("parameter 'delay_time': {e}"),
            )
        })?,
        (None, None) => return Err(missing("delay_time")),
    };
    if delay.samples > MAX_D {
        let v = p.raw("delay_time").unwrap_or("");
        return Err(ApiError::param(
            "delay_time",
            v,
            format!(
                "parameter 'delay_time' must be at most {MAX_D} sampling periods for interactive use (got {} s = {} periods)",
                clip(v),
                fmt(delay.in_samples())
            ),
        ));
    }
    Ok(delay)
}

/// A physical loop: its plant model, actuator lag, velocity estimator and (possibly
/// fractional) delay, validated through [`LoopSpec`], with its family.
fn physical_spec(p: &Params) -> Result<PlantSpec, ApiError> {
    let model = plant_model(p)?;
    let period = p.num_in("period", MIN_PERIOD, MAX_PERIOD, " s (sampling period T)")?;
    let lag = p.num_or(
        "force_lag",
        0.0,
        0.0,
        MAX_FORCE_LAG,
        " s (actuator time constant τ)",
    )?;
    let velocity = match p.raw("estimator") {
        Some(v) => v
            .parse::<VelocityEstimator>()
            .map_err(|e| ApiError::param("estimator", v, format!("parameter 'estimator': {e}")))?,
        None => VelocityEstimator::Backward,
    };
    let fallback = match &model {
        PlantModel::TransferFunction { .. } => "plant_den",
        PlantModel::TwoMass(_) => "motor_mass",
        PlantModel::MassSpringDamper(_) => "device_mass",
    };
    // the device held by an arm names its operator: passivity counts the device's own damping
    let operator = match &model {
        PlantModel::MassSpringDamper(_) if arm(p)? != Arm::NONE => Some(arm(p)?),
        _ => None,
    };
    // the plant's own errors name the query parameter the user typed
    Plant::new(model.clone(), lag).map_err(|e| {
        let given = e.param().and_then(Param::query).filter(|n| p.has(n));
        let name = given.unwrap_or(fallback);
        let v = p.raw(name).unwrap_or("");
        ApiError::param(
            name,
            v,
            format!("parameter '{name}' (got '{}'): {e}", clip(v)),
        )
    })?;
    // the loop file's form: one set of defaults and checks for every front end
    let spec = LoopSpec {
        delay: Some(general_delay(p, period)?),
        ..LoopSpec::of_plant(
            model,
            lag,
            operator,
            period,
            VelocitySpec::Estimator(velocity),
        )
    };
    let lp = spec.resolve().map_err(lib_error)?;
    let sys = System::new(lp).map_err(lib_error)?;
    physical_plant_spec(sys)
}

/// The [`PlantSpec`] of a physical loop: its units for the page (K = a·k_per_unit, B =
/// b·b_per_unit), its static stiffness and, for the paper's loop, its (γ, δ, d) within the
/// explorer's bounds.
fn physical_plant_spec(sys: System) -> Result<PlantSpec, ApiError> {
    let lp = sys.lp();
    let (dev, arm_, eff) = match &lp.plant.model {
        PlantModel::MassSpringDamper(e) => {
            let arm = lp.plant.operator.unwrap_or(Arm::NONE);
            let device = Device {
                mass: e.mass - arm.mass,
                damping: e.damping - arm.damping,
            };
            (device, arm, Some(*e))
        }
        PlantModel::TwoMass(t) => (NO_DEVICE, t.arm, None),
        PlantModel::TransferFunction { .. } => (NO_DEVICE, Arm::NONE, None),
    };
    let s = sys.family().scale;
    let static_k = lp.plant.dc_stiffness().unwrap_or(0.0);
    let physical = PhysicalSpec {
        device_mass: dev.mass,
        device_damping: dev.damping,
        arm_mass: arm_.mass,
        arm_damping: arm_.damping,
        arm_stiffness: arm_.stiffness,
        period: lp.period,
        delay_time: lp.delay_time(),
        mass: lp.plant.reference_mass(lp.period),
        damping: eff.map_or(0.0, |e| e.damping),
        stiffness: static_k,
        k_per_unit: s.stiffness,
        b_per_unit: s.damping,
    };
    let paper = lp
        .paper_view()
        .map(|plant| {
            check_explorer_range(&plant)?;
            Ok::<_, ApiError>(PaperPlant {
                plant,
                d: lp.delay.samples,
            })
        })
        .transpose()?;
    Ok(PlantSpec {
        sys,
        paper,
        physical: Some(physical),
    })
}

#[cfg(test)]
mod tests {
    /// Every query parameter a library error can name is one the API accepts.
    #[test]
    fn parameters_name_real_query_parameters() {
        let mut names = super::super::export::export_names();
        names.extend(super::super::api::simulate_names());
        names.push("file");
        for p in hapstab::Param::ALL {
            if let Some(q) = p.query() {
                assert!(names.contains(&q), "{p:?}: the API has no parameter {q}");
            }
        }
    }
}
