//! Loop files in the explorer: "Save loop" writes the page's loop and wall in the form every
//! JSON report echoes under `input` ([`hapstab::loop_spec`], what `--loop FILE` and Python's
//! `Loop.load` read), and "Open loop" turns such a file into the page's own query
//! (`/api/open`), so that the page, the command line and Python share one file form.

use hapstab::loop_spec::{LoopInput, parse};
use hapstab::{Loop, PlantModel};
use serde::Serialize;

use crate::api::wall_analyses::wall_of;
use crate::query::{ApiError, PlantSpec};

/// The loop file of a request and its optional wall (a, b) in the page's units.
pub fn saved_loop(spec: &PlantSpec, point: Option<(f64, f64)>) -> Result<String, ApiError> {
    let wall = point.map(|(a, b)| wall_of(spec, a, b));
    let normalized = spec.physical.is_none();
    Ok(LoopInput::new(spec.sys.lp(), normalized, wall).to_json() + "\n")
}

/// The answer of `/api/open`: the page's query for the file's loop and wall (K and B in N/m
/// and Ns/m for a physical loop, α and β for a normalized one).
#[derive(Debug, Clone, Serialize)]
pub struct Opened {
    /// The query string (mode, plant, period, delay, estimator, lag, and the wall).
    pub query: String,
}

/// The page's query for the text of a loop file.
pub fn open(text: &str) -> Result<Opened, ApiError> {
    let f = parse(text).map_err(|e| ApiError::param("file", "", e.to_string()))?;
    let mut q: Vec<(&str, String)> = Vec::new();
    let num = |x: f64| format!("{x:?}");
    if f.normalized {
        let pp =
            f.lp.paper_view()
                .ok_or_else(|| ApiError::bad("not a normalized loop".into()))?;
        q.push(("mode", "normalized".into()));
        q.extend([("gamma", num(pp.gamma)), ("delta", num(pp.delta))]);
        q.push(("d", f.lp.delay.samples.to_string()));
        if let Some(w) = f.wall {
            q.extend([("alpha", num(w.stiffness)), ("beta", num(w.damping))]);
        }
        return Ok(Opened { query: encode(&q) });
    }
    q.push(("mode", "physical".into()));
    plant_params(&f.lp, &mut q);
    q.push(("period", num(f.lp.period)));
    if f.lp.delay.fraction == 0.0 {
        q.push(("d", f.lp.delay.samples.to_string()));
    } else {
        q.push(("delay_time", num(f.lp.delay_time())));
    }
    if f.lp.plant.force_lag > 0.0 {
        q.push(("force_lag", num(f.lp.plant.force_lag)));
    }
    if f.lp.velocity != hapstab::VelocityEstimator::Backward {
        q.push(("estimator", f.lp.velocity.to_string()));
    }
    if let Some(w) = f.wall {
        q.extend([
            ("wall_stiffness", num(w.stiffness)),
            ("wall_damping", num(w.damping)),
        ]);
    }
    Ok(Opened { query: encode(&q) })
}

/// The page's plant fields of a loop: device and arm (a mass-spring-damper; without a named
/// arm its m, b as the device and k as the arm's stiffness, which is how the page forms m, b
/// and k), two-mass device, or transfer function.
fn plant_params(lp: &Loop, q: &mut Vec<(&str, String)>) {
    let num = |x: f64| format!("{x:?}");
    let list = |c: &[f64]| c.iter().map(|x| num(*x)).collect::<Vec<_>>().join(",");
    match &lp.plant.model {
        PlantModel::MassSpringDamper(e) => {
            let arm = lp.plant.operator.unwrap_or(hapstab::Arm {
                mass: 0.0,
                damping: 0.0,
                stiffness: e.stiffness,
            });
            q.extend([
                ("device_mass", num(remainder(e.mass, arm.mass))),
                ("device_damping", num(remainder(e.damping, arm.damping))),
                ("arm_mass", num(arm.mass)),
                ("arm_damping", num(arm.damping)),
                ("arm_stiffness", num(arm.stiffness)),
            ]);
        }
        PlantModel::TwoMass(t) => q.extend([
            ("motor_mass", num(t.motor_mass)),
            ("motor_damping", num(t.motor_damping)),
            ("handle_mass", num(t.handle_mass)),
            ("transmission_stiffness", num(t.transmission_stiffness)),
            ("transmission_damping", num(t.transmission_damping)),
            ("arm_mass", num(t.arm.mass)),
            ("arm_damping", num(t.arm.damping)),
            ("arm_stiffness", num(t.arm.stiffness)),
        ]),
        PlantModel::TransferFunction { num: n, den } => {
            q.extend([("plant_num", list(n)), ("plant_den", list(den))]);
        }
    }
}

/// A query string, every value percent-encoded.
fn encode(q: &[(&str, String)]) -> String {
    let enc = |s: &str| {
        s.bytes()
            .map(|b| match b {
                b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'-' | b'.' | b'_' | b'~' => {
                    (b as char).to_string()
                }
                _ => format!("%{b:02X}"),
            })
            .collect::<String>()
    };
    q.iter()
        .map(|(k, v)| format!("{k}={}", enc(v)))
        .collect::<Vec<_>>()
        .join("&")
}

/// The device's part x of a sum s = x + arm (eq. 1's m = m_L + m_H, b = b_L + b_H), as the
/// explorer's "Open loop" and the command line's `--loop FILE` split a loop file's lumped
/// plant back into device and arm: the shortest decimal that the arm completes to s exactly
/// (the number the user typed, where s − arm would carry the sum's rounding:
/// 1.1 − 1.0 = 0.10000000000000009), else s − arm.
pub fn remainder(sum: f64, arm: f64) -> f64 {
    let diff = (sum - arm).max(0.0);
    (1..=17)
        .filter_map(|digits| format!("{diff:.*e}", digits - 1).parse::<f64>().ok())
        .find(|x| *x + arm == sum)
        .unwrap_or(diff)
}
