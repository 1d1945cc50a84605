//! `/api/simulate`: one time-domain run of the wall with the library's verdict and a
//! decimated trace.

use std::time::Instant;

use hapstab::answer::SimulationAnswer;
use hapstab::limits::{point_cost, simulation_cost};
use hapstab::loop_spec::LoopInput;
use hapstab::params::Wall;
use hapstab::simulation::{Config, Contact, Effects, HumanForce, Initial, LoopModel, Model};
use hapstab::simulation::{SimModel, TraceClip, simulate_clipped};
use serde::Serialize;

use super::point::{point_names, point_params, wall_at};
use super::within_budget;
use crate::limits::*;
use crate::query::{ApiError, Params, PlantSpec, lib_error, plant_spec};

/// Query names of `/api/simulate`.
pub(crate) fn simulate_names() -> Vec<&'static str> {
    let mut v = point_names();
    v.extend(["samples", "push", "velocity", "contact"]);
    v
}

/// A parsed simulation request.
#[derive(Debug, Clone)]
pub(crate) struct SimReq {
    pub spec: PlantSpec,
    pub alpha: f64,
    pub beta: f64,
    /// The wall in the loop's units (K and B as given, see [`super::point::wall_at`]).
    pub wall: Wall,
    pub samples: usize,
    pub push: f64,
    pub velocity: f64,
    pub contact: Contact,
}

/// The explorer's simulated contact by default: the operator pushes with 1 N (into the wall)...
const DEFAULT_PUSH: f64 = 1.0;
/// ... and the device reaches the wall surface x = 0 at 10 mm/s ...
const DEFAULT_VELOCITY: f64 = 0.01;
/// ... of a unilateral wall (force only in contact). `hapstab simulate` starts instead from
/// x(0) = 1 mm at rest with no push against the bilateral wall of the paper's analysis; the
/// answer's `simulate_flags` give its flags for the explorer's run.
const DEFAULT_CONTACT: &str = "unilateral";

/// Validates a simulation request.
pub(crate) fn parse_simulate(p: &Params) -> Result<SimReq, ApiError> {
    let spec = plant_spec(p)?;
    let at = wall_at(p, &spec)?;
    let (alpha, beta) = at.units;
    let samples = match p.opt_count(
        "samples",
        MIN_SIM_SAMPLES,
        MAX_SIM_SAMPLES,
        " (simulated samples)",
    )? {
        Some(n) => n,
        None => {
            // about six periods of the wall's oscillation, ω ≈ √(α + γ) per sample
            let w = (alpha + spec.view().plant.gamma).max(1e-8).sqrt();
            ((6.0 * 2.0 * std::f64::consts::PI / w).ceil() as usize).clamp(300, 4000)
        }
    };
    // a run may be extended up to the horizon until its verdict settles: budget for that
    let (name, value) = spec.delay_param();
    within_budget(
        simulation_cost(
            samples.max(SIM_HORIZON) as f64,
            spec.cost_d(),
            samples.min(MAX_TRACE_POINTS) as f64,
        )
        .then(point_cost(spec.cost_d())),
        "the simulation (extended up to its horizon)",
        name,
        &value,
    )?;
    let push = p.num_or(
        "push",
        DEFAULT_PUSH,
        -MAX_PUSH,
        MAX_PUSH,
        " N (human push into the wall)",
    )?;
    let velocity = p.num_or(
        "velocity",
        DEFAULT_VELOCITY,
        -MAX_VELOCITY,
        MAX_VELOCITY,
        " m/s (approach velocity at the wall surface)",
    )?;
    let contact = match p.choice(
        "contact",
        &["unilateral", "unilateral_no_pull", "bilateral"],
        DEFAULT_CONTACT,
    )? {
        "bilateral" => Contact::Bilateral,
        "unilateral_no_pull" => Contact::UnilateralNoPull,
        _ => Contact::Unilateral,
    };
    Ok(SimReq {
        spec,
        alpha,
        beta,
        wall: at.wall,
        samples,
        push,
        velocity,
        contact,
    })
}

/// A recorded trace, decimated.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct TraceOut {
    /// Time in s.
    pub time: Vec<f64>,
    /// Position in m (positive into the wall).
    pub position: Vec<f64>,
    /// Wall force in N (positive pushes out).
    pub wall_force: Vec<f64>,
}

/// Answer of `/api/simulate`: the library's [`SimulationAnswer`] (the same keys and the same
/// verdict as `hapstab simulate --json` for the same setting; the loop, wall, effects, push and
/// initial state under `input`) with a decimated trace of the whole run.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct SimOut {
    #[serde(flatten)]
    pub answer: SimulationAnswer,
    /// The units of the run in words (normalized mode: shown for m = 1 kg, T = 1 ms).
    pub units_note: &'static str,
    /// The flags of `hapstab simulate` for this run (besides the loop and the wall): its own
    /// defaults are a bilateral wall from x(0) = 1 mm at rest, no push.
    pub simulate_flags: String,
    /// The trace of the run, cut for a growing run before it leaves the scale of its start
    /// (see `trace_clipped`).
    pub trace: TraceOut,
    /// For a growing run, where the trace was cut: the first sample whose |x| exceeds
    /// `factor` (10³) times `start_scale` (the largest of |x(0)|, |ẋ(0)|·T and F_H·T²/m, in m),
    /// with its time (s), position (m) and the `threshold` (m); null when the whole run is
    /// returned (see `hapstab::simulation::simulate_clipped`).
    pub trace_clipped: Option<TraceClip>,
    pub server_ms: f64,
}

/// The flags of `hapstab simulate` that give the run of `req` (besides the loop and the wall).
fn simulate_flags(req: &SimReq) -> String {
    let contact = match req.contact {
        Contact::Bilateral => "",
        Contact::Unilateral => "--unilateral ",
        Contact::UnilateralNoPull => "--unilateral --no-pull ",
    };
    format!(
        "{contact}--push {} --initial-position 0 --initial-velocity {} --duration-samples {}",
        req.push, req.velocity, req.samples
    )
}

/// Runs `/api/simulate`: the device starts at the wall surface x = 0 moving in with
/// `velocity`, the operator pushes with a constant `push`; unilateral wall by default. The
/// run is `samples` long, extended like `hapstab simulate` until its verdict settles; a
/// growing run's trace ends where |x| first exceeds 10³ times the scale of its start
/// (`hapstab::simulation::simulate_clipped`).
pub(crate) fn simulate(req: &SimReq) -> Result<SimOut, ApiError> {
    let t0 = Instant::now();
    let spec = &req.spec;
    let n = point_params(spec, req.alpha, req.beta)?;
    let (mass, period, units_note) = match spec.physical {
        Some(ph) => (ph.mass, ph.period, "physical units of the request"),
        None => (
            1.0,
            1e-3,
            "normalized mode: shown for m = 1 kg and T = 1 ms (only the shape depends on α, β, γ, δ, d)",
        ),
    };
    let model = match n {
        Some(n) => SimModel::Paper(Model::new(n, mass, period).map_err(lib_error)?),
        None => SimModel::Loop(LoopModel::new(spec.sys.lp().clone(), req.wall).map_err(lib_error)?),
    };
    let mut cfg = Config::new(model, req.samples);
    cfg.effects = Effects {
        contact: req.contact,
        ..Effects::LINEAR
    };
    cfg.human = HumanForce::Constant(req.push);
    cfg.initial = Initial {
        position: 0.0,
        velocity: req.velocity,
    };
    cfg.trace_rows = MAX_TRACE_POINTS;
    let (mut run, trace_clipped) = simulate_clipped(&cfg).map_err(lib_error)?;
    let trace = run.trace.take().unwrap_or_default();
    let normalized = spec.physical.is_none();
    let input = LoopInput::new(spec.sys.lp(), normalized, Some(req.wall));
    Ok(SimOut {
        // the explorer runs a normalized loop at m = 1 kg, T = 1 ms: in physical units
        answer: SimulationAnswer::new(run, &cfg, input, false),
        units_note,
        simulate_flags: simulate_flags(req),
        trace: TraceOut {
            time: trace.time,
            position: trace.position,
            wall_force: trace.wall_force,
        },
        trace_clipped,
        server_ms: t0.elapsed().as_secs_f64() * 1e3,
    })
}
