//! `simulate`: the sampled-data loop of Fig. 3 in the time domain, with the nonlinear effects
//! of Remark 1 and Section IX, its trace as numpy arrays and the run's verdict.

use hapstab::Param;
use hapstab::answer::SimulationAnswer;
use hapstab::loop_spec::LoopInput;
use hapstab::model::{Loop, PlantModel};
use hapstab::params::{Physical, Sampling, Wall};
use hapstab::simulation::{
    Config, Contact, DEFAULT_MAX_SAMPLES, Effects, Friction, HumanForce, Initial, LoopModel, Model,
    SimModel, samples_for_duration, simulate as run,
};
use numpy::{AllowTypeChange, PyArray1, PyArrayLike1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::dicts::dict_of;
use crate::errors::{Context, bad};
use crate::loops::PyLoop;
use crate::text::num;
use crate::wall::WallArgs;

/// Default run length in samples (10 s at T = 1 ms), as the command line's.
const DEFAULT_SAMPLES: usize = 10_000;
/// Default number of trace rows: every sample of runs up to 200 000 samples, 8 MB.
const DEFAULT_TRACE_ROWS: usize = 200_000;

/// The result of `simulate`.
#[pyclass(frozen, get_all, module = "hapstab", name = "Simulation")]
pub struct PySimulation {
    /// Time t = kT in s of each recorded sample (float64 array).
    pub time: Py<PyArray1<f64>>,
    /// Position x in m, positive into the wall.
    pub position: Py<PyArray1<f64>>,
    /// Velocity ẋ in m/s.
    pub velocity: Py<PyArray1<f64>>,
    /// Wall force F_wall in N held over [kT, (k+1)T) (positive pushes out of the wall).
    pub wall_force: Py<PyArray1<f64>>,
    /// Human force F_H in N held over [kT, (k+1)T) (positive into the wall).
    pub human_force: Py<PyArray1<f64>>,
    /// "decaying", "limit_cycle", "growing", "separated" or "undecided".
    pub outcome: String,
    /// Why: what settled, or why the run could not decide.
    pub reason: String,
    /// The wall acted linearly over the judged window, so the outcome must agree with the
    /// analysis (decaying iff spectral radius < 1, Section V).
    pub linear_window: bool,
    /// Envelope growth per sample fitted on the run, if any.
    pub measured_growth_per_sample: Option<f64>,
    /// Spectral radius of the loop in linear contact (Section V).
    pub spectral_radius: Option<f64>,
    /// The analysis' verdict in linear contact: "stable", "marginal" or "unstable".
    pub linear_verdict: Option<String>,
    /// A settled limit cycle: peak_to_peak (m), counts, period_samples, frequency_hz, cycles,
    /// bouncing; else None.
    pub limit_cycle: Option<Py<PyDict>>,
    /// Contact events: contacts, separations, in_contact_at_end, last_separation_sample,
    /// judged_contact_fraction, judged_separations.
    pub contact: Py<PyDict>,
    /// First sample of the judged window and one past its last.
    pub judged_samples: (usize, usize),
    /// Samples simulated (the run doubles up to max_samples until its verdict settles).
    pub samples: usize,
    /// Trace rows are every trace_stride-th sample.
    pub trace_stride: usize,
    /// The run stopped early because the state exceeded 1e100.
    pub blown_up: bool,
    /// Position at the end in m.
    pub final_position: f64,
    /// Velocity at the end in m/s.
    pub final_velocity: f64,
    /// Samples asked for before any extension.
    pub requested_samples: usize,
    /// The horizon: the most samples the run may be extended to.
    pub max_samples: usize,
    /// Simulated time: s, or samples for a loop given in normalized units.
    pub duration: f64,
    /// Start of the judged window, in the time unit of `duration`.
    pub judged_from: f64,
    /// End of the judged window, in the time unit of `duration`.
    pub judged_to: f64,
    /// "physical" (s, m, N) or "normalized" (samples and the units of Table I).
    pub units: String,
    /// The loop, its wall, the effects, the constant human force (None for a profile) and
    /// the initial state, as `hapstab simulate --json` echoes them under `input`.
    pub input: Py<PyDict>,
}

#[pymethods]
impl PySimulation {
    fn __repr__(&self) -> String {
        format!(
            "Simulation(outcome='{}', samples={}, spectral_radius={})",
            self.outcome,
            self.samples,
            self.spectral_radius.map_or("None".into(), num)
        )
    }
}

/// The simulated model of a loop and its wall: the paper's model (eq. 1, Table I) for a loop
/// with the paper's view, else the loop's exact discrete loop.
fn sim_model(lp: &Loop, w: Wall) -> PyResult<SimModel> {
    if let (PlantModel::MassSpringDamper(e), Some(_)) = (&lp.plant.model, lp.paper_view()) {
        let sampling = Sampling::new(lp.period, lp.delay.samples).py()?;
        return Ok(SimModel::Paper(
            Model::from_physical(&Physical::new(*e, w, sampling).py()?).py()?,
        ));
    }
    Ok(SimModel::Loop(LoopModel::new(lp.clone(), w).py()?))
}

/// The run's nonlinear effects from the keyword arguments.
fn effects(
    contact: &str,
    wall_position: f64,
    coulomb_friction: Option<f64>,
    static_friction: Option<f64>,
    quantization: Option<f64>,
    saturation: Option<f64>,
) -> PyResult<Effects> {
    let contact = match contact {
        "bilateral" => Contact::Bilateral,
        "unilateral" => Contact::Unilateral,
        "unilateral_no_pull" => Contact::UnilateralNoPull,
        other => {
            return Err(bad(
                "contact",
                format!(
                    "must be 'bilateral', 'unilateral' or 'unilateral_no_pull' (got '{other}')"
                ),
            ));
        }
    };
    let friction = Friction::from_parts(coulomb_friction, static_friction);
    let e = Effects {
        contact,
        wall_position,
        friction,
        quantization,
        saturation,
    };
    e.validate().py()?;
    Ok(e)
}

/// A run length from seconds or samples (not both).
fn length(
    period: f64,
    seconds: (&str, Option<f64>),
    count: (&str, Option<usize>),
) -> PyResult<Option<usize>> {
    match (seconds.1, count.1) {
        (Some(_), Some(_)) => Err(bad(
            &format!("{}, {}", seconds.0, count.0),
            "give the length either in seconds or in samples",
        )),
        (Some(s), None) => Ok(Some(samples_for_duration(s, period).py_with(&[
            (Param::Duration, seconds.0),
            (Param::DurationPeriods, seconds.0),
        ])?)),
        (None, n) => Ok(n),
    }
}

fn human(force: &Bound<'_, PyAny>) -> PyResult<HumanForce> {
    if let Ok(f) = force.extract::<f64>() {
        return Ok(HumanForce::Constant(f));
    }
    let v: PyArrayLike1<'_, f64, AllowTypeChange> = force.extract().map_err(|_| {
        bad(
            "human_force",
            "must be a force in N or a 1-D array of forces per sample",
        )
    })?;
    Ok(HumanForce::Samples(v.as_array().to_vec()))
}

/// The Python object of a run: the library's [`SimulationAnswer`] (the keys of `hapstab
/// simulate --json`) with the recorded trace as arrays.
fn result_object(py: Python<'_>, mut answer: SimulationAnswer) -> PyResult<PySimulation> {
    let t = answer.run.trace.take().unwrap_or_default();
    let r = &answer.run;
    let v = &r.verdict;
    let arr = |x: Vec<f64>| PyArray1::from_vec(py, x).unbind();
    Ok(PySimulation {
        time: arr(t.time),
        position: arr(t.position),
        velocity: arr(t.velocity),
        wall_force: arr(t.wall_force),
        human_force: arr(t.human_force),
        outcome: v.outcome.as_str().into(),
        reason: v.reason.clone(),
        linear_window: v.linear_window,
        measured_growth_per_sample: v.measured_growth_per_sample,
        spectral_radius: v.spectral_radius,
        linear_verdict: v.linear_verdict.map(|x| x.as_str().into()),
        limit_cycle: v.limit_cycle.as_ref().map(|c| dict_of(py, c)).transpose()?,
        contact: dict_of(py, &v.contact)?,
        judged_samples: (v.judged_from_sample, v.judged_to_sample),
        samples: r.samples,
        trace_stride: r.trace_stride,
        blown_up: r.blown_up,
        final_position: r.final_position,
        final_velocity: r.final_velocity,
        requested_samples: r.requested_samples,
        max_samples: r.max_samples,
        duration: answer.duration,
        judged_from: answer.judged_from,
        judged_to: answer.judged_to,
        units: answer.units.into(),
        input: dict_of(py, &answer.input)?,
    })
}

/// Runs the loop of Fig. 3 in the time domain: the plant m ẍ + b ẋ + k x = F stepped exactly
/// from sample to sample (the zero-order-hold matrices of eq. 2–6), the wall
/// F_wall[k] = K (y[k−d] − x_w) + B (y[k−d] − y[k−d−1])/T, and the nonlinear effects: a
/// unilateral wall (Remark 1), Coulomb and static friction, encoder quantization q (m) and
/// actuator saturation F_max (N). The run (duration in s or samples; default 10 000 samples)
/// is judged on its second half once that has settled, else doubled up to the horizon
/// (max_duration in s or max_samples; default 10⁶ samples), then reported undecided. While the
/// wall acts linearly the outcome agrees with the spectral radius of Section V. The GIL is
/// released while it runs.
///
/// human_force: F_H in N (positive into the wall), constant or one value per sample (the
/// last is held). The trace keeps at most trace_rows rows (every trace_stride-th sample).
/// Refuses a run beyond the command line's budget before it starts, naming the keyword that
/// sets its length: the run of `n` samples ([`hapstab::limits::simulation_cost`] with the
/// roots of the linear verdict), and the horizon it may extend to.
fn check_budget(
    fam: &hapstab::AffineFamily,
    (n, horizon): (usize, usize),
    trace_rows: usize,
    by_duration: bool,
    horizon_by_duration: bool,
) -> PyResult<()> {
    use hapstab::limits::{MAX_SIMULATION_SAMPLES, roots_cost, simulation_cost};
    for (kw, len) in [
        (if by_duration { "duration" } else { "samples" }, n),
        (
            if horizon_by_duration {
                "max_duration"
            } else {
                "max_samples"
            },
            horizon,
        ),
    ] {
        if len as f64 > MAX_SIMULATION_SAMPLES {
            return Err(crate::errors::bad(
                kw,
                format!(
                    "the run of {len} samples is longer than the {MAX_SIMULATION_SAMPLES:e} samples allowed"
                ),
            ));
        }
    }
    let d = fam.degree().saturating_sub(3);
    let rows = (trace_rows as f64).min(horizon as f64);
    let run = simulation_cost(n as f64, d, rows).then(roots_cost(fam.degree()));
    let kw = if by_duration { "duration" } else { "samples" };
    crate::budget::check(
        run,
        kw,
        &format!("the run of {n} samples"),
        &format!("use a shorter {kw}"),
    )?;
    let kw = if horizon_by_duration {
        "max_duration"
    } else {
        "max_samples"
    };
    crate::budget::check(
        simulation_cost(horizon as f64, d, rows),
        kw,
        &format!("the run's horizon of {horizon} samples"),
        &format!("use a shorter {kw}"),
    )
}

#[pyfunction]
#[pyo3(signature = (r#loop, wall_stiffness = None, wall_damping = None, *, alpha = None,
                    beta = None, duration = None, samples = None, max_duration = None,
                    max_samples = None, human_force = None, initial_position = 1e-3,
                    initial_velocity = 0.0, contact = "bilateral", wall_position = 0.0,
                    coulomb_friction = None, static_friction = None, quantization = None,
                    saturation = None, trace_rows = DEFAULT_TRACE_ROWS))]
#[allow(clippy::too_many_arguments)]
pub fn simulate(
    py: Python<'_>,
    r#loop: &PyLoop,
    wall_stiffness: Option<f64>,
    wall_damping: Option<f64>,
    alpha: Option<f64>,
    beta: Option<f64>,
    duration: Option<f64>,
    samples: Option<usize>,
    max_duration: Option<f64>,
    max_samples: Option<usize>,
    human_force: Option<&Bound<'_, PyAny>>,
    initial_position: f64,
    initial_velocity: f64,
    contact: &str,
    wall_position: f64,
    coulomb_friction: Option<f64>,
    static_friction: Option<f64>,
    quantization: Option<f64>,
    saturation: Option<f64>,
    trace_rows: usize,
) -> PyResult<PySimulation> {
    let (sys, w) = WallArgs::system_and_wall(r#loop, wall_stiffness, wall_damping, alpha, beta)?;
    let fam = sys.family();
    let model = sim_model(&r#loop.lp, w)?;
    let period = r#loop.lp.period;
    let n =
        length(period, ("duration", duration), ("samples", samples))?.unwrap_or(DEFAULT_SAMPLES);
    let horizon = length(
        period,
        ("max_duration", max_duration),
        ("max_samples", max_samples),
    )?
    .unwrap_or(n.max(DEFAULT_MAX_SAMPLES));
    check_budget(
        fam,
        (n, horizon),
        trace_rows,
        duration.is_some(),
        max_duration.is_some(),
    )?;
    let config = Config {
        model,
        effects: effects(
            contact,
            wall_position,
            coulomb_friction,
            static_friction,
            quantization,
            saturation,
        )?,
        human: human_force.map(human).transpose()?.unwrap_or_default(),
        initial: Initial {
            position: initial_position,
            velocity: initial_velocity,
        },
        samples: n,
        max_samples: horizon,
        trace_rows,
    };
    config.validate().py()?;
    let r = py.detach(|| run(&config)).py()?;
    let input = LoopInput::new(&r#loop.lp, r#loop.normalized, Some(w));
    result_object(
        py,
        SimulationAnswer::new(r, &config, input, r#loop.normalized),
    )
}
