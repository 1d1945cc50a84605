//! `hapstab simulate` and `hapstab simboundary`: the sampled-data loop of Fig. 3 in the time
//! domain with the nonlinear effects the paper leaves to future work (Remark 1,
//! Section IX): unilateral wall, Coulomb/static friction, encoder quantization, actuator
//! saturation. All simulation lives in `hapstab::simulation`; this module parses flags,
//! writes the CSV trace and the plots, and formats the verdicts.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use clap::Args;
use hapstab::boundary::AlphaBeta;
use hapstab::params::Wall;
use hapstab::simulation::{
    BoundarySearch, Config, Contact, DEFAULT_MAX_SAMPLES, Effects, EmpiricalPoint, Friction,
    HumanForce, Initial, LoopModel, MAX_TRACE_ROWS, MIN_REL_TOLERANCE, Model, Outcome, RunResult,
    SimModel, StableWhen, Trace, empirical_boundary, samples_for_duration, simulate,
};
use hapstab::zoh::WallScale;
use hapstab::{AffineFamily, Normalized, PlantModel as LibPlantModel, Verdict};
use rayon::prelude::*;
use serde::Serialize;

use crate::model::{
    LoopArgs, LoopInput, NON_PAPER_PLANT_FLAGS, PlantModel, ResolvedLoop, WallArgs, describe_loop,
    resolve_loop_wall, resolve_point,
};
use crate::output::{eng, print_json, sig};
use crate::plot::{Figure, Grid, Legend, Marker, Saved, Series, palette};

/// Longest run and horizon accepted (samples): 10⁹ samples take 10–60 s per core.
const MAX_SAMPLES: f64 = hapstab::limits::MAX_SIMULATION_SAMPLES;
/// Default run length: 10 s at the physical period, 10 000 samples in normalized mode.
const DEFAULT_SAMPLES: usize = 10_000;
/// Default initial penetration x(0) in m.
const DEFAULT_X0: f64 = 1e-3;
/// Points per plotted curve (min-max decimated).
const PLOT_BUCKETS: usize = 2_000;

const UNITS_HELP: &str = "Units: with physical plant flags (or none: the default device and arm) \
forces are in N and time in s. In normalized mode (--alpha/--beta, --gamma/--delta without \
physical flags) m = 1 and T = 1: time counts samples, forces are normalized forces T²F/m \
(in m), and the run length is given with --duration-samples.";

/// Nonlinear effects, human force, initial state and run length, shared by both commands.
#[derive(Args, Debug, Clone, Default)]
pub struct RunArgs {
    /// Unilateral wall: force only while the sensed position penetrates it (Remark 1).
    #[arg(long)]
    pub unilateral: bool,
    /// With --unilateral: the wall never pulls (F_wall >= 0; the damper cannot hold the device).
    #[arg(long, requires = "unilateral")]
    pub no_pull: bool,
    /// Wall position x_w in m: the spring's rest position and the unilateral surface [default: 0].
    #[arg(long, allow_hyphen_values = true, value_name = "M")]
    pub wall_position: Option<f64>,
    /// Coulomb (sliding) friction F_c of the device in N.
    #[arg(long, allow_hyphen_values = true, value_name = "N")]
    pub coulomb: Option<f64>,
    /// Static (breakaway) friction F_s >= F_c in N [default: F_c].
    #[arg(long, allow_hyphen_values = true, value_name = "N")]
    pub stiction: Option<f64>,
    /// Position-encoder resolution q in m: the wall sees round(x/q)·q.
    #[arg(long, allow_hyphen_values = true, value_name = "M")]
    pub quantization: Option<f64>,
    /// Actuator force limit F_max in N: |F_wall| <= F_max.
    #[arg(long, allow_hyphen_values = true, value_name = "N")]
    pub saturation: Option<f64>,
    /// Constant human force F_H in N, positive into the wall [default: 0].
    #[arg(long, allow_hyphen_values = true, value_name = "N")]
    pub push: Option<f64>,
    /// Initial position x(0) in m, positive into the wall [default: 0.001].
    #[arg(long, allow_hyphen_values = true, value_name = "M")]
    pub initial_position: Option<f64>,
    /// Initial velocity ẋ(0) in m/s [default: 0].
    #[arg(long, allow_hyphen_values = true, value_name = "M/S")]
    pub initial_velocity: Option<f64>,
    /// Run length in seconds (physical mode) [default: 10 s].
    #[arg(
        long,
        allow_hyphen_values = true,
        value_name = "S",
        conflicts_with = "duration_samples"
    )]
    pub duration: Option<f64>,
    /// Run length in samples [default: 10000].
    #[arg(long, allow_hyphen_values = true, value_name = "N")]
    pub duration_samples: Option<f64>,
    /// Horizon in seconds: a run whose second half has not settled is extended (doubling)
    /// up to this length, then reported undecided [default: 10⁶ samples, or the run length
    /// if longer].
    #[arg(
        long,
        allow_hyphen_values = true,
        value_name = "S",
        conflicts_with = "max_duration_samples"
    )]
    pub max_duration: Option<f64>,
    /// Horizon in samples (see --max-duration) [default: 1000000].
    #[arg(long, allow_hyphen_values = true, value_name = "N")]
    pub max_duration_samples: Option<f64>,
}

/// The resolved run settings (everything but the wall).
#[derive(Debug, Clone, Copy, Serialize)]
struct RunSettings {
    effects: Effects,
    human_force: f64,
    initial: Initial,
    samples: usize,
    max_samples: usize,
}

/// A run length from a seconds flag or a samples flag (None if neither is given).
fn run_length(
    physical: bool,
    period: f64,
    seconds: (&str, Option<f64>),
    count: (&str, Option<f64>),
) -> Result<Option<usize>> {
    let ((sname, secs), (cname, n)) = (seconds, count);
    Ok(match (secs, n) {
        (Some(_), _) if !physical => {
            bail!("normalized mode counts time in samples (T = 1): use {cname} instead of {sname}")
        }
        (Some(s), _) => {
            if !s.is_finite() || s <= 0.0 {
                bail!("{sname} must be a positive number of seconds (got {s})");
            }
            if s / period > MAX_SAMPLES {
                bail!(
                    "{sname} {s} s is {} samples; at most {MAX_SAMPLES:e} are allowed",
                    sig(s / period, 6)
                );
            }
            Some(samples_for_duration(s, period)?)
        }
        (None, Some(n)) => {
            if !n.is_finite() || n < 2.0 || n.fract() != 0.0 {
                bail!("{cname} must be a whole number >= 2 (got {n})");
            }
            if n > MAX_SAMPLES {
                bail!("{cname} must be at most {MAX_SAMPLES:e} (got {n})");
            }
            Some(n as usize)
        }
        (None, None) => None,
    })
}

impl RunArgs {
    fn resolve(&self, physical: bool, period: f64) -> Result<RunSettings> {
        let finite = |name: &str, v: Option<f64>| -> Result<Option<f64>> {
            match v {
                Some(x) if !x.is_finite() => bail!("{name} must be a finite number (got {x})"),
                _ => Ok(v),
            }
        };
        let friction = match (
            finite("--coulomb", self.coulomb)?,
            finite("--stiction", self.stiction)?,
        ) {
            (None, None) => None,
            (c, s) => {
                let coulomb = c.unwrap_or(0.0);
                Some(Friction {
                    coulomb,
                    stiction: s.unwrap_or(coulomb),
                })
            }
        };
        let effects = Effects {
            contact: match (self.unilateral, self.no_pull) {
                (false, _) => Contact::Bilateral,
                (true, false) => Contact::Unilateral,
                (true, true) => Contact::UnilateralNoPull,
            },
            wall_position: finite("--wall-position", self.wall_position)?.unwrap_or(0.0),
            friction,
            quantization: finite("--quantization", self.quantization)?,
            saturation: finite("--saturation", self.saturation)?,
        };
        effects.validate()?;
        let samples = run_length(
            physical,
            period,
            ("--duration", self.duration),
            ("--duration-samples", self.duration_samples),
        )?
        .unwrap_or(DEFAULT_SAMPLES);
        let max_samples = match run_length(
            physical,
            period,
            ("--max-duration", self.max_duration),
            ("--max-duration-samples", self.max_duration_samples),
        )? {
            Some(m) if m < samples => bail!(
                "the horizon (--max-duration/--max-duration-samples) must be at least the run length of {samples} samples (got {m} samples)"
            ),
            Some(m) => m,
            None => samples.max(DEFAULT_MAX_SAMPLES),
        };
        Ok(RunSettings {
            effects,
            human_force: finite("--push", self.push)?.unwrap_or(0.0),
            initial: Initial {
                position: finite("--initial-position", self.initial_position)?
                    .unwrap_or(DEFAULT_X0),
                velocity: finite("--initial-velocity", self.initial_velocity)?.unwrap_or(0.0),
            },
            samples,
            max_samples,
        })
    }

    fn config(&self, model: SimModel, physical: bool) -> Result<(Config, RunSettings)> {
        let s = self.resolve(physical, model.period())?;
        let mut cfg = Config::new(model, s.samples);
        cfg.max_samples = s.max_samples;
        cfg.effects = s.effects;
        cfg.human = HumanForce::Constant(s.human_force);
        cfg.initial = s.initial;
        cfg.validate()?;
        Ok((cfg, s))
    }
}

/// A one-line caption of the simulated loop: (α, β, γ, δ, d) for the paper's loop, the wall
/// and the delay otherwise.
fn model_caption(m: &SimModel) -> String {
    match m {
        SimModel::Paper(m) => {
            let p = m.params;
            format!(
                "α = {}, β = {}, γ = {}, δ = {}, d = {}",
                sig(p.alpha, 6),
                sig(p.beta, 6),
                sig(p.gamma, 6),
                sig(p.delta, 6),
                p.d
            )
        }
        SimModel::Loop(l) => format!(
            "K = {}, B = {}, t_d = {}",
            eng(l.wall.stiffness, "N/m", 6),
            eng(l.wall.damping, "Ns/m", 6),
            eng(l.lp.delay_time(), "s", 6)
        ),
    }
}

/// Human-readable list of the active nonlinear effects.
fn describe_effects(s: &RunSettings, force_unit: &str) -> String {
    let e = &s.effects;
    let mut parts = Vec::new();
    match e.contact {
        Contact::Bilateral => {}
        Contact::Unilateral => parts.push("unilateral wall".to_string()),
        Contact::UnilateralNoPull => parts.push("unilateral wall that never pulls".to_string()),
    }
    if e.wall_position != 0.0 {
        parts.push(format!("wall at x_w = {} m", sig(e.wall_position, 6)));
    }
    if let Some(f) = e.friction {
        parts.push(format!(
            "friction F_c = {} {force_unit}, F_s = {} {force_unit}",
            sig(f.coulomb, 6),
            sig(f.stiction, 6)
        ));
    }
    if let Some(q) = e.quantization {
        parts.push(format!("quantization q = {} m", sig(q, 6)));
    }
    if let Some(f) = e.saturation {
        parts.push(format!("saturation F_max = {} {force_unit}", sig(f, 6)));
    }
    if s.human_force != 0.0 {
        parts.push(format!(
            "human push F_H = {} {force_unit}",
            sig(s.human_force, 6)
        ));
    }
    if parts.is_empty() {
        "none: the linear bilateral loop".to_string()
    } else {
        parts.join(", ")
    }
}

/// Units of a run: physical (s, N) or normalized (samples, T²F/m).
#[derive(Debug, Clone, Copy)]
struct Units {
    physical: bool,
}

impl Units {
    fn name(&self) -> &'static str {
        if self.physical {
            "physical"
        } else {
            "normalized"
        }
    }
    fn time(&self) -> &'static str {
        if self.physical { "s" } else { "samples" }
    }
    fn force(&self) -> &'static str {
        if self.physical { "N" } else { "T²F/m (m)" }
    }
    fn velocity(&self) -> &'static str {
        if self.physical { "m/s" } else { "m/sample" }
    }
}

// ---------------------------------------------------------------------------------------
// hapstab simulate
// ---------------------------------------------------------------------------------------

/// Arguments of `hapstab simulate`.
#[derive(Args, Debug)]
#[command(after_help = UNITS_HELP)]
#[command(mut_arg("alpha", |a| a.conflicts_with_all(NON_PAPER_PLANT_FLAGS)))]
#[command(mut_arg("beta", |a| a.conflicts_with_all(NON_PAPER_PLANT_FLAGS)))]
pub struct SimulateArgs {
    #[command(flatten)]
    lp: LoopArgs,
    #[command(flatten)]
    wall: WallArgs,
    #[command(flatten)]
    run: RunArgs,
    /// Write the trace as CSV with columns t, x, v, F (F: wall force, positive pushing out
    /// of the wall).
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
    /// Plot position and force over time, with the judged window: writes STEM.svg and
    /// STEM.png.
    #[arg(long, value_name = "STEM")]
    plot: Option<PathBuf>,
    /// Most trace rows (at most 2000000); longer runs record every n-th sample.
    #[arg(long, value_name = "N", default_value_t = 100_000)]
    max_rows: usize,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct Files {
    #[serde(skip_serializing_if = "Option::is_none")]
    csv: Option<PathBuf>,
    #[serde(skip_serializing_if = "Option::is_none")]
    svg: Option<PathBuf>,
    #[serde(skip_serializing_if = "Option::is_none")]
    png: Option<PathBuf>,
    rows: usize,
    record_every: usize,
}

#[derive(Serialize)]
struct SimulateOut<'a> {
    /// The library's result: outcome, reason, evidence, run length.
    #[serde(flatten)]
    run: &'a RunResult,
    /// Simulated time (s, or samples in normalized mode).
    duration: f64,
    /// The judged window in time units.
    judged_from: f64,
    judged_to: f64,
    units: &'static str,
    /// The paper's loop: its mass m in kg and normalized point (Table I).
    #[serde(skip_serializing_if = "Option::is_none")]
    mass: Option<f64>,
    period: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    normalized: Option<Normalized>,
    /// The loop, its wall and the run's setting as given.
    input: SimInput,
    #[serde(skip_serializing_if = "Option::is_none")]
    files: Option<Files>,
}

/// The inputs of a simulation: the loop and its wall, the nonlinear effects, the human's
/// force and the initial state.
#[derive(Serialize)]
struct SimInput {
    #[serde(flatten)]
    lp: LoopInput,
    effects: Effects,
    human_force: f64,
    initial: Initial,
}

/// Bytes per kept trace row in memory (five f64 columns).
const TRACE_ROW_BYTES: f64 = 40.0;

/// Refuses an output path whose folder does not exist (nothing is created).
fn check_output_path(flag: &str, path: &Path) -> Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty())
        && !dir.is_dir()
    {
        bail!(
            "{flag} {}: the folder {} does not exist",
            path.display(),
            dir.display()
        );
    }
    Ok(())
}

fn check_simulate_args(a: &SimulateArgs) -> Result<()> {
    if a.max_rows < 2 {
        bail!("--max-rows must be at least 2 (got {})", a.max_rows);
    }
    if a.max_rows > MAX_TRACE_ROWS {
        bail!(
            "--max-rows {} would keep {} of trace in memory; at most {MAX_TRACE_ROWS} rows ({}) are allowed",
            a.max_rows,
            eng(a.max_rows as f64 * TRACE_ROW_BYTES, "B", 3),
            eng(MAX_TRACE_ROWS as f64 * TRACE_ROW_BYTES, "B", 3)
        );
    }
    if let Some(p) = &a.csv {
        check_output_path("--csv", p)?;
    }
    if let Some(p) = &a.plot {
        check_output_path("--plot", p)?;
    }
    Ok(())
}

/// The simulated loop: the paper's loop in its normalized view (the (α, β) every command
/// reports), or any other loop with its physical wall.
struct SimLoop {
    rl: ResolvedLoop,
    wall: Wall,
    model: SimModel,
}

impl SimLoop {
    fn resolve(lp: &LoopArgs, wall: &WallArgs, run: &RunArgs) -> Result<Self> {
        let rl = lp.resolve(wall.normalized())?;
        let fam = AffineFamily::of_loop(&rl.lp)?;
        let w = resolve_loop_wall(&rl, &fam, wall)?;
        friction_defined(&rl, run)?;
        let model = if rl.lp.paper_view().is_some() {
            let pm = resolve_point(&lp.plant, wall)?;
            SimModel::Paper(match &pm.physical {
                Some(p) => Model::from_physical(p)?,
                None => Model::unit(pm.normalized)?,
            })
        } else {
            SimModel::Loop(LoopModel::new(rl.lp.clone(), w)?)
        };
        Ok(Self { rl, wall: w, model })
    }

    fn units(&self) -> Units {
        Units {
            physical: !self.rl.normalized,
        }
    }

    fn paper(&self) -> Option<&Model> {
        match &self.model {
            SimModel::Paper(m) => Some(m),
            SimModel::Loop(_) => None,
        }
    }
}

/// Runs `hapstab simulate`.
pub fn run_simulate(a: &SimulateArgs) -> Result<()> {
    check_simulate_args(a)?;
    let sl = SimLoop::resolve(&a.lp, &a.wall, &a.run)?;
    let units = sl.units();
    let (mut cfg, settings) = a.run.config(sl.model.clone(), units.physical)?;
    let files_wanted = a.csv.is_some() || a.plot.is_some();
    cfg.trace_rows = if files_wanted { a.max_rows } else { 0 };
    check_run_budget(&a.lp, &sl.rl.lp, &cfg, 1.0, "the run")?;
    let mut result = simulate(&cfg)?;
    let trace = result.trace.take().unwrap_or_default();
    let files = if files_wanted {
        Some(write_files(a, &trace, &result, &cfg, &settings, units)?)
    } else {
        None
    };
    let period = sl.model.period();
    let out = SimulateOut {
        run: &result,
        duration: result.samples as f64 * period,
        judged_from: result.verdict.judged_from_sample as f64 * period,
        judged_to: result.verdict.judged_to_sample as f64 * period,
        units: units.name(),
        mass: sl.paper().map(|m| m.mass),
        period,
        normalized: sl.paper().filter(|_| !sl.rl.normalized).map(|m| m.params),
        input: SimInput {
            lp: LoopInput::new(&sl.rl, Some(sl.wall)),
            effects: settings.effects,
            human_force: settings.human_force,
            initial: settings.initial,
        },
        files,
    };
    if a.json {
        return print_json(&out);
    }
    print_simulate(&out, &sl, &settings, units);
    Ok(())
}

/// Refuses `runs` simulations of `cfg` beyond the command-line budget: each costs its run
/// length times the loop's states ([`hapstab::limits::simulation_cost`]); a run that may
/// extend to its horizon is refused when the horizon alone is beyond the budget. Blames the
/// run length's flag, or the flag that sets most of the loop's degree.
fn check_run_budget(
    args: &LoopArgs,
    lp: &hapstab::model::Loop,
    cfg: &Config,
    runs: f64,
    what: &str,
) -> Result<()> {
    let n = crate::budget::loop_degree(lp);
    let states = n.saturating_sub(3);
    let rows = cfg.trace_rows as f64;
    let one = hapstab::limits::simulation_cost(cfg.samples as f64, states, rows)
        .then(hapstab::limits::roots_cost(n));
    let cost = hapstab::limits::Cost {
        seconds: one.seconds * runs,
        memory: one.memory,
    };
    let mut drivers = crate::budget::degree_drivers(args, lp);
    let length = cfg.samples as f64 / DEFAULT_SAMPLES as f64;
    drivers.push(crate::budget::Driver {
        flag: "--duration",
        value: format!("{} samples", cfg.samples),
        factor: length,
    });
    crate::budget::check(cost, what, &drivers)?;
    let horizon = hapstab::limits::simulation_cost(cfg.max_samples as f64, states, rows);
    let horizon = hapstab::limits::Cost {
        seconds: horizon.seconds * runs,
        memory: horizon.memory,
    };
    if hapstab::limits::Budget::COMMAND_LINE
        .check(horizon)
        .is_err()
    {
        crate::budget::check(
            horizon,
            &format!("{what} up to the horizon"),
            &[crate::budget::Driver {
                flag: "--max-duration",
                value: format!("{} samples", cfg.max_samples),
                factor: 1.0,
            }],
        )?;
    }
    Ok(())
}

/// Writes the CSV and the plot that were asked for.
fn write_files(
    a: &SimulateArgs,
    trace: &Trace,
    result: &RunResult,
    cfg: &Config,
    settings: &RunSettings,
    units: Units,
) -> Result<Files> {
    if let Some(csv) = &a.csv {
        write_trace_csv(csv, trace)?;
    }
    let saved = match &a.plot {
        Some(stem) => Some(
            trace_plot(trace, result, cfg, settings, units)
                .save(stem)
                .with_context(|| format!("--plot {}", stem.display()))?,
        ),
        None => None,
    };
    Ok(Files {
        csv: a.csv.clone(),
        svg: saved.as_ref().map(|s| s.svg.clone()),
        png: saved.map(|s| s.png),
        rows: trace.time.len(),
        record_every: result.trace_stride,
    })
}

fn write_trace_csv(path: &Path, tr: &Trace) -> Result<usize> {
    let mut w = csv::Writer::from_path(path)
        .with_context(|| format!("cannot write CSV {}", path.display()))?;
    w.write_record(["t", "x", "v", "F"])?;
    for i in 0..tr.time.len() {
        w.write_record([
            num(tr.time[i]),
            num(tr.position[i]),
            num(tr.velocity[i]),
            num(tr.wall_force[i]),
        ])?;
    }
    w.flush()
        .with_context(|| format!("cannot write CSV {}", path.display()))?;
    Ok(tr.time.len())
}

/// A unit prefix for values up to `max_abs` in base unit `unit`: (factor, label).
fn scaled_unit(max_abs: f64, unit: &str) -> (f64, String) {
    if unit != "m" && unit != "N" {
        return (1.0, unit.to_string());
    }
    let (f, p) = if !(max_abs.is_finite() && max_abs > 0.0) || max_abs >= 1.0 {
        (1.0, "")
    } else if max_abs >= 1e-3 {
        (1e3, "m")
    } else if max_abs >= 1e-6 {
        (1e6, "µ")
    } else {
        (1e9, "n")
    };
    (f, format!("{p}{unit}"))
}

/// A frequency in Hz (physical) or cycles per sample (normalized).
fn frequency(hz: f64, units: Units) -> String {
    if units.physical {
        eng(hz, "Hz", 6)
    } else {
        format!("{} cycles/sample", sig(hz, 6))
    }
}

/// A time in s (physical) or a sample count (normalized).
fn time_text(seconds: f64, units: Units) -> String {
    if units.physical {
        eng(seconds, "s", 6)
    } else {
        format!("{} samples", sig(seconds, 6))
    }
}

/// The outcome with its key numbers, e.g. "limit cycle, bouncing: 1.383 mm peak-to-peak, 8.88 Hz".
fn outcome_summary(r: &RunResult, units: Units) -> String {
    let v = &r.verdict;
    match (v.outcome, v.limit_cycle) {
        (Outcome::LimitCycle, Some(lc)) => {
            let counts = lc
                .counts
                .map(|c| format!(" ({} counts)", sig(c, 3)))
                .unwrap_or_default();
            format!(
                "limit cycle{}: {} peak-to-peak{counts}, {}",
                if lc.bouncing { ", bouncing" } else { "" },
                eng(lc.peak_to_peak, "m", 6),
                frequency(lc.frequency_hz, units)
            )
        }
        (Outcome::Separated, _) => match v.contact.separations {
            0 => "separated: never touched the wall".to_string(),
            1 => "separated: left the wall after 1 bounce".to_string(),
            n => format!("separated: left the wall after {n} bounces"),
        },
        (o, _) => o.as_str().replace('_', " "),
    }
}

fn trace_plot(tr: &Trace, r: &RunResult, cfg: &Config, s: &RunSettings, units: Units) -> Grid {
    let verdict = outcome_summary(r, units);
    let params = model_caption(&cfg.model);
    let max_abs = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let xw = cfg.effects.wall_position;
    let (xs, xunit) = scaled_unit(max_abs(&tr.position).max(xw.abs()), "m");
    let fu = if units.physical { "N" } else { "" };
    let (fs, funit) = scaled_unit(max_abs(&tr.wall_force), fu);
    let series = |v: &[f64], scale: f64, from: f64| -> Vec<(f64, f64)> {
        let pts: Vec<(f64, f64)> = tr
            .time
            .iter()
            .zip(v)
            .filter(|(t, _)| **t >= from)
            .map(|(&t, &y)| (t, y * scale))
            .collect();
        crate::plot::decimate_minmax(&pts, PLOT_BUCKETS)
    };
    let t_end = tr
        .time
        .last()
        .copied()
        .unwrap_or(1.0)
        .max(cfg.model.period());
    let tlabel = format!("time t ({})", units.time());
    let mut pos = Figure::new(params)
        .x_label(&tlabel)
        .y_label(format!("position x ({xunit})"))
        .x_range(0.0, t_end)
        .legend(Legend::UpperRight);
    let (lo, hi) = tr
        .position
        .iter()
        .chain([&xw])
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let (j0, j1) = (
        r.verdict.judged_from_sample as f64 * cfg.model.period(),
        r.verdict.judged_to_sample as f64 * cfg.model.period(),
    );
    if hi > lo {
        let (lo, hi) = (lo * xs, hi * xs);
        pos.add(
            Series::polygon([(j0, lo), (j1, lo), (j1, hi), (j0, hi)])
                .color(palette::GREY)
                .alpha(0.15)
                .no_outline()
                .label("judged window"),
        );
    }
    pos.add(
        Series::line(series(&tr.position, xs, 0.0))
            .color(palette::BLUE)
            .width(2)
            .label("position x"),
    );
    let wall_line = cfg.effects.contact != Contact::Bilateral || xw != 0.0;
    if wall_line {
        pos.add(
            Series::dashed([(0.0, xw * xs), (t_end, xw * xs)])
                .color(palette::GREY)
                .width(2)
                .label("wall surface x_w"),
        );
    }
    let flabel = if units.physical {
        format!("wall force F ({funit})")
    } else {
        "wall force T²F/m".to_string()
    };
    let effects = describe_effects(s, units.force());
    let effects = effects
        .strip_prefix("none: ")
        .unwrap_or(&effects)
        .to_string();
    let mut force = Figure::new(effects)
        .x_label(&tlabel)
        .y_label(flabel)
        .x_range(0.0, t_end)
        .legend(Legend::UpperRight);
    force.add(
        Series::line(series(&tr.wall_force, fs, 0.0))
            .color(palette::VERMILLION)
            .width(2)
            .label("wall force F"),
    );
    if let Some(fmax) = cfg.effects.saturation {
        let (hi, lo) = (fmax * fs, -fmax * fs);
        force.add(
            Series::dashed([
                (0.0, hi),
                (t_end, hi),
                (f64::NAN, 0.0),
                (0.0, lo),
                (t_end, lo),
            ])
            .color(palette::GREY)
            .width(2)
            .label("saturation ±F_max"),
        );
    }
    if s.human_force != 0.0 {
        let fh = s.human_force * fs;
        force.add(
            Series::dashed([(0.0, fh), (t_end, fh)])
                .color(palette::GREEN)
                .width(2)
                .label("human push F_H"),
        );
    }
    let mut g = Grid::new(format!("Simulation: {verdict}"), 1).panel_size(1000, 520);
    g.push(pos);
    g.push(force);
    // A limit cycle: zoom on its last periods.
    if r.verdict.outcome == Outcome::LimitCycle && tr.time.len() > 16 {
        let span = r
            .verdict
            .limit_cycle
            .map(|c| c.frequency_hz)
            .filter(|f| *f > 0.0)
            .map_or(t_end / 8.0, |f| 8.0 / f)
            .min(t_end / 4.0);
        let from = t_end - span;
        let tail: Vec<f64> = tr
            .time
            .iter()
            .zip(&tr.position)
            .filter(|(t, _)| **t >= from)
            .map(|(_, x)| *x)
            .collect();
        let (zs, zunit) = scaled_unit(max_abs(&tail).max(xw.abs()), "m");
        let mut zoom = Figure::new("Limit cycle: the last periods")
            .x_label(&tlabel)
            .y_label(format!("position x ({zunit})"))
            .x_range(from, t_end)
            .legend(Legend::UpperRight);
        zoom.add(
            Series::line(series(&tr.position, zs, from))
                .color(palette::BLUE)
                .width(3)
                .label("position x"),
        );
        if let Some(q) = cfg.effects.quantization {
            // The encoder levels around the cycle.
            let (lo, hi) = tail
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                });
            // Thresholds (k + 1/2)·q from just below the cycle to just above it.
            let (k0, k1) = ((lo / q - 0.5).floor() as i64, (hi / q - 0.5).ceil() as i64);
            if k1 - k0 <= 40 {
                let mut levels = Vec::new();
                for k in k0..=k1 {
                    let y = (k as f64 + 0.5) * q * zs;
                    levels.extend([(from, y), (t_end, y), (f64::NAN, 0.0)]);
                }
                zoom.add(
                    Series::dashed(levels)
                        .color(palette::GREY)
                        .width(1)
                        .label("encoder thresholds"),
                );
            }
        }
        g.push(zoom);
    }
    g
}

/// The simulated loop in words: the paper's normalized point, or the loop and its wall.
fn print_model(o: &SimulateOut, sl: &SimLoop, units: Units) {
    let Some(n) = &o.normalized else {
        for line in describe_loop(&sl.rl.lp) {
            println!("{line}");
        }
        println!(
            "wall      K = {} N/m, B = {} Ns/m",
            sig(sl.wall.stiffness, 6),
            sig(sl.wall.damping, 6)
        );
        return;
    };
    println!(
        "model       α = {}, β = {}, γ = {}, δ = {}, d = {}{}",
        sig(n.alpha, 6),
        sig(n.beta, 6),
        sig(n.gamma, 6),
        sig(n.delta, 6),
        n.d,
        match o.mass {
            Some(m) if units.physical => {
                format!(" (m = {} kg, T = {})", sig(m, 6), eng(o.period, "s", 6))
            }
            _ => " (normalized: time in samples, forces as T²F/m)".to_string(),
        }
    );
}

fn print_simulate(o: &SimulateOut, sl: &SimLoop, s: &RunSettings, units: Units) {
    let r = o.run;
    let v = &r.verdict;
    print_model(o, sl, units);
    println!("effects     {}", describe_effects(s, units.force()));
    println!("run         {}", run_text(o, units));
    let outcome = outcome_summary(r, units);
    match outcome.split_once(':') {
        Some((head, tail)) => println!("verdict     {}:{tail}", head.to_uppercase()),
        None => println!("verdict     {}", outcome.to_uppercase()),
    }
    println!("why         {}", v.reason);
    println!(
        "judged      t = {} … {} (the second half of the run)",
        time_text(o.judged_from, units),
        time_text(o.judged_to, units)
    );
    if let Some(line) = analysis_text(r, s) {
        println!("{line}");
    }
    if s.effects.contact != Contact::Bilateral {
        println!("contact     {}", contact_text(r));
    }
    if let Some(hint) = hint_text(r, s, units, o.period) {
        println!("hint        {hint}");
    }
    if let Some(f) = &o.files {
        let mut names: Vec<String> = Vec::new();
        if let Some(c) = &f.csv {
            names.push(format!("{} ({} rows: t, x, v, F)", c.display(), f.rows));
        }
        names.extend(f.svg.iter().chain(&f.png).map(|p| p.display().to_string()));
        println!("files       {}", names.join(", "));
    }
}

fn run_text(o: &SimulateOut, units: Units) -> String {
    let r = o.run;
    let mut t = format!(
        "{} samples ({}) from x(0) = {}, ẋ(0) = {} {}",
        r.samples,
        time_text(o.duration, units),
        eng(o.input.initial.position, "m", 6),
        sig(o.input.initial.velocity, 6),
        units.velocity()
    );
    if r.blown_up {
        t += " (stopped: the state blew up)";
    } else if r.verdict.outcome == Outcome::Undecided && r.samples > r.requested_samples {
        t += &format!(
            "; extended from {} samples to the horizon without settling",
            r.requested_samples
        );
    } else if r.samples > r.requested_samples {
        t += &format!(
            "; extended from {} samples until it settled (horizon {} samples)",
            r.requested_samples, r.max_samples
        );
    }
    t
}

/// The measured growth beside the spectral radius, or what the analysis says about a
/// cycle or a separation.
fn analysis_text(r: &RunResult, s: &RunSettings) -> Option<String> {
    let v = &r.verdict;
    let rho = v.spectral_radius?;
    let lin = v.linear_verdict.map_or("", |x| x.as_str());
    let analysis = format!(
        "spectral radius {} ({lin})",
        crate::output::radius_text(rho)
    );
    let in_contact = if v.linear_window {
        ""
    } else {
        " for the loop in linear contact"
    };
    let measured = v.measured_growth_per_sample.filter(|g| match v.outcome {
        Outcome::Growing => *g > 1.0,
        Outcome::Decaying => *g < 1.0,
        _ => true,
    });
    Some(match (v.outcome, measured) {
        (Outcome::Growing | Outcome::Decaying | Outcome::Undecided, Some(g)) => format!(
            "growth      measured {} per sample{}; analysis: {analysis}{in_contact}",
            crate::output::radius_text(g),
            if v.outcome == Outcome::Undecided {
                " (not settled)"
            } else {
                ""
            }
        ),
        (Outcome::LimitCycle, _) => format!(
            "analysis    {analysis}{in_contact}; {}",
            cycle_explanation(r, s)
        ),
        (Outcome::Separated, _) => format!(
            "analysis    {analysis} while in contact; the run ended out of contact, so it does not test the wall"
        ),
        _ => format!("analysis    {analysis}{in_contact}"),
    })
}

fn cycle_explanation(r: &RunResult, s: &RunSettings) -> String {
    let v = &r.verdict;
    let unstable = v.linear_verdict == Some(Verdict::Unstable);
    let bouncing = v.limit_cycle.is_some_and(|c| c.bouncing);
    let e = &s.effects;
    let mut limits: Vec<&str> = Vec::new();
    if e.quantization.is_some() {
        limits.push("quantization");
    }
    if e.friction.is_some() {
        limits.push("friction");
    }
    if e.saturation.is_some() {
        limits.push("saturation");
    }
    match (bouncing, unstable) {
        (true, true) => "in contact the oscillation grows until the device leaves the wall".into(),
        (true, false) => {
            "the contact itself is stable; the device bounces off the wall and returns".into()
        }
        (false, true) => format!(
            "the growth of the unstable loop is limited by {}",
            limits.join(" and ")
        ),
        (false, false) => format!(
            "the linear loop is stable; {} sustains the cycle",
            limits.join(" and ")
        ),
    }
}

fn contact_text(r: &RunResult) -> String {
    let c = &r.verdict.contact;
    format!(
        "contacts {}, separations {} ({} in the judged window, in contact {} % of it); {} at the end",
        c.contacts,
        c.separations,
        c.judged_separations,
        sig(100.0 * c.judged_contact_fraction, 3),
        if c.in_contact_at_end {
            "in contact"
        } else {
            "out of contact"
        }
    )
}

fn hint_text(r: &RunResult, s: &RunSettings, units: Units, period: f64) -> Option<String> {
    let v = &r.verdict;
    match v.outcome {
        Outcome::Separated if s.human_force <= 0.0 => Some(
            "nothing pushes the device into the wall: give --push F to keep it in contact".into(),
        ),
        Outcome::Separated => Some(
            "the push does not hold the device on the wall; a larger --push keeps it in contact"
                .into(),
        ),
        Outcome::Undecided if v.linear_window && v.linear_verdict == Some(Verdict::Marginal) => {
            Some("the loop is marginal (spectral radius 1): a longer run will not settle it".into())
        }
        Outcome::Undecided if r.samples >= r.max_samples => Some(format!(
            "simulate longer with --max-duration{} (the horizon is now {})",
            if units.physical { "" } else { "-samples" },
            time_text(r.max_samples as f64 * period, units)
        )),
        _ => None,
    }
}

// ---------------------------------------------------------------------------------------
// hapstab simboundary
// ---------------------------------------------------------------------------------------

/// Arguments of `hapstab simboundary`.
#[derive(Args, Debug)]
#[command(after_help = UNITS_HELP)]
pub struct SimboundaryArgs {
    #[command(flatten)]
    lp: LoopArgs,
    #[command(flatten)]
    run: RunArgs,
    /// Smallest normalized damping β = BT/m (for other plants the wall unit b = B·T/m with m
    /// the plant's reference mass) [default: 10 % of the exact region's top].
    #[arg(long, allow_hyphen_values = true)]
    beta_min: Option<f64>,
    /// Largest β [default: 90 % of the exact region's top].
    #[arg(long, allow_hyphen_values = true)]
    beta_max: Option<f64>,
    /// Number of β values, evenly spaced.
    #[arg(long, value_name = "N", default_value_t = 8)]
    beta_count: usize,
    /// Upper end of the α scan (wall unit a = K·T²/m for other plants) [default: 3× the
    /// exact linear boundary at each β].
    #[arg(long, allow_hyphen_values = true)]
    alpha_max: Option<f64>,
    /// Coarse α scan points before bisection.
    #[arg(long, value_name = "N", default_value_t = 12)]
    grid: usize,
    /// Bisection stops when the bracket is below this fraction of α (at least 1e-6).
    #[arg(
        long,
        value_name = "REL",
        default_value_t = 1e-3,
        allow_hyphen_values = true
    )]
    rel_tol: f64,
    /// Count limit cycles of peak-to-peak amplitude below M metres as stable [default: only
    /// decaying runs].
    #[arg(long, value_name = "M", allow_hyphen_values = true)]
    stable_amplitude: Option<f64>,
    /// Write the table as CSV.
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
    /// Plot the exact linear region and the simulated boundary: writes STEM.svg and STEM.png.
    #[arg(long, value_name = "STEM")]
    plot: Option<PathBuf>,
    /// Print one JSON object instead of text (no progress bar).
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct BoundaryRow {
    #[serde(flatten)]
    point: EmpiricalPoint,
    /// α_simulated / α_linear.
    ratio: Option<f64>,
    /// Physical mode: B, K_linear and K_simulated in Ns/m and N/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    wall_damping: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    k_linear: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    k_simulated: Option<f64>,
}

/// γ, δ and d of the paper's loop (Table I).
#[derive(Serialize)]
struct PaperPlant {
    gamma: f64,
    delta: f64,
    d: usize,
}

/// The inputs of `simboundary`: the loop, the runs' setting and the scan.
#[derive(Serialize)]
struct SimboundaryInput {
    #[serde(flatten)]
    lp: LoopInput,
    effects: Effects,
    human_force: f64,
    initial: Initial,
    samples: usize,
    max_samples: usize,
    stable_when: StableWhen,
    grid: usize,
    rel_tol: f64,
}

#[derive(Serialize)]
struct SimboundaryOut {
    /// The paper's loop given in physical units: γ, δ, d (Table I).
    #[serde(skip_serializing_if = "Option::is_none")]
    normalized: Option<PaperPlant>,
    units: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    mass: Option<f64>,
    period: f64,
    /// The loop and the runs' setting as given.
    input: SimboundaryInput,
    /// Other loops: K = a·stiffness (N/m) and B = b·damping (Ns/m) for the a, b columns.
    #[serde(skip_serializing_if = "Option::is_none")]
    wall_units: Option<WallScale>,
    /// α_max of the exact linear stable region (Section V) and the β where it is reached.
    exact_alpha_max: f64,
    exact_beta_at_alpha_max: f64,
    points: Vec<BoundaryRow>,
    /// Why some of the answer is no evidence of stability (e.g. runs that left the wall).
    warnings: Vec<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    csv: Option<PathBuf>,
    #[serde(skip_serializing_if = "Option::is_none")]
    plot: Option<Saved>,
}

fn model_of(pm: &PlantModel) -> Result<Model> {
    let n = Normalized::new(0.0, 0.0, pm.gamma, pm.delta, pm.d)?;
    Ok(match pm.physical {
        Some((eff, s)) => Model::new(n, eff.mass, s.period)?,
        None => Model::unit(n)?,
    })
}

/// Refuses friction on a plant that names no mass.
fn friction_defined(rl: &ResolvedLoop, run: &RunArgs) -> Result<()> {
    let friction = run.coulomb.is_some() || run.stiction.is_some();
    if friction && matches!(rl.lp.plant.model, LibPlantModel::TransferFunction { .. }) {
        bail!(
            "--coulomb/--stiction: friction is not defined for a transfer-function plant (--plant-num/--plant-den), which names no mass for it to act on; describe the device as a mass-spring-damper or a two-mass device instead"
        );
    }
    Ok(())
}

/// The template model of a boundary search: the paper's loop in its normalized view, or any
/// loop (its wall is replaced by every run).
fn boundary_template(
    a: &SimboundaryArgs,
    rl: &ResolvedLoop,
) -> Result<(SimModel, Option<PlantModel>)> {
    if rl.lp.paper_view().is_some() {
        let pm = a.lp.plant.resolve()?;
        return Ok((SimModel::Paper(model_of(&pm)?), Some(pm)));
    }
    let wall = Wall {
        stiffness: 0.0,
        damping: 0.0,
    };
    Ok((SimModel::Loop(LoopModel::new(rl.lp.clone(), wall)?), None))
}

fn check_boundary_args(a: &SimboundaryArgs) -> Result<StableWhen> {
    if let Some(p) = &a.csv {
        check_output_path("--csv", p)?;
    }
    if let Some(p) = &a.plot {
        check_output_path("--plot", p)?;
    }
    if a.beta_count == 0 || a.beta_count > 10_000 {
        bail!("--beta-count must be in [1, 10000] (got {})", a.beta_count);
    }
    if a.grid < 2 || a.grid > 10_000 {
        bail!("--grid must be in [2, 10000] (got {})", a.grid);
    }
    if !(a.rel_tol.is_finite() && a.rel_tol < 1.0) {
        bail!("--rel-tol must be in [1e-6, 1) (got {})", a.rel_tol);
    }
    if a.rel_tol < MIN_REL_TOLERANCE {
        bail!(
            "--rel-tol {} is below the minimum 1e-6: the bisection would resolve α more finely than the simulated verdicts can",
            a.rel_tol
        );
    }
    if let Some(m) = a.alpha_max
        && !(m.is_finite() && m > 0.0)
    {
        bail!("--alpha-max must be a positive number (got {m})");
    }
    Ok(match a.stable_amplitude {
        None => StableWhen::Decaying,
        Some(m) if m.is_finite() && m > 0.0 => StableWhen::AmplitudeBelow(m),
        Some(m) => bail!("--stable-amplitude must be a positive number of metres (got {m})"),
    })
}

/// The simulated boundary at each β, in parallel, with a progress bar on a terminal.
fn boundary_points(
    a: &SimboundaryArgs,
    template: &Config,
    betas: &[f64],
    stable_when: StableWhen,
) -> Result<Vec<EmpiricalPoint>> {
    let bar = crate::progress::Bar::new(betas.len(), "β values", !a.json);
    let points: Vec<EmpiricalPoint> = betas
        .par_iter()
        .map(|&beta| {
            let search = BoundarySearch {
                template: template.clone(),
                betas: vec![beta],
                alpha_max: a.alpha_max,
                grid: a.grid,
                rel_tolerance: a.rel_tol,
                stable_when,
            };
            let r = empirical_boundary(&search).map(|v| v[0]);
            bar.inc();
            r
        })
        .collect::<hapstab::Result<_>>()?;
    bar.finish();
    Ok(points)
}

/// A row with its physical columns: K = a·k, B = b·kb (None in normalized mode).
fn boundary_row(p: &EmpiricalPoint, scale: Option<(f64, f64)>) -> BoundaryRow {
    let ratio = match (p.alpha_simulated, p.alpha_linear) {
        (Some(s), Some(l)) if l.is_finite() && l > 0.0 => Some(s / l),
        _ => None,
    };
    BoundaryRow {
        point: *p,
        ratio,
        wall_damping: scale.map(|(_, kb)| p.beta * kb),
        k_linear: scale.and_then(|(k, _)| p.alpha_linear.map(|x| x * k)),
        k_simulated: scale.and_then(|(k, _)| p.alpha_simulated.map(|x| x * k)),
    }
}

/// Runs `hapstab simboundary`.
pub fn run_simboundary(a: &SimboundaryArgs) -> Result<()> {
    let stable_when = check_boundary_args(a)?;
    let rl = a.lp.resolve(false)?;
    friction_defined(&rl, &a.run)?;
    let units = Units {
        physical: !rl.normalized,
    };
    let fam = AffineFamily::of_loop(&rl.lp)?;
    let (model, pm) = boundary_template(a, &rl)?;
    let (template, settings) = a.run.config(model.clone(), units.physical)?;
    let n = fam.degree();
    let region_cost = hapstab::limits::region_cost_of_degree(n, hapstab::limits::core_degree(&fam));
    crate::budget::check_loop(&a.lp, &rl.lp, region_cost, "the exact region")?;
    let region = hapstab::loop_analysis::region(&rl.lp, &fam)?;
    let betas = beta_values(a, &region)?;
    // every β: the α grid's runs and a bisection of about log2(1/rel-tol) more
    let runs = betas.len() as f64 * (a.grid as f64 + (1.0 / a.rel_tol).log2().max(1.0));
    check_run_budget(&a.lp, &rl.lp, &template, runs, "the boundary's runs")?;
    let points = boundary_points(a, &template, &betas, stable_when)?;
    let scale = match (&pm, units.physical) {
        (Some(pm), _) => pm
            .physical
            .map(|(eff, s)| (eff.mass / (s.period * s.period), eff.mass / s.period)),
        (None, _) => Some((fam.scale.stiffness, fam.scale.damping)),
    };
    let rows: Vec<BoundaryRow> = points.iter().map(|p| boundary_row(p, scale)).collect();
    if let Some(path) = &a.csv {
        write_boundary_csv(path, &rows)?;
    }
    let paper = match &model {
        SimModel::Paper(m) => Some(m.params),
        SimModel::Loop(_) => None,
    };
    let saved = match &a.plot {
        Some(stem) => Some(
            boundary_plot(&region, &points, paper.as_ref(), &settings, units)
                .save(stem)
                .with_context(|| format!("--plot {}", stem.display()))?,
        ),
        None => None,
    };
    let out = SimboundaryOut {
        normalized: pm.filter(|_| !rl.normalized).map(|p| PaperPlant {
            gamma: p.gamma,
            delta: p.delta,
            d: p.d,
        }),
        units: units.name(),
        mass: match &model {
            SimModel::Paper(m) => Some(m.mass),
            SimModel::Loop(_) => None,
        },
        period: model.period(),
        input: SimboundaryInput {
            lp: LoopInput::new(&rl, None),
            effects: settings.effects,
            human_force: settings.human_force,
            initial: settings.initial,
            samples: settings.samples,
            max_samples: settings.max_samples,
            stable_when,
            grid: a.grid,
            rel_tol: a.rel_tol,
        },
        wall_units: pm.is_none().then_some(fam.scale),
        exact_alpha_max: region.alpha_max,
        exact_beta_at_alpha_max: region.beta_at_alpha_max,
        warnings: boundary_warnings(&points, &settings),
        points: rows,
        csv: a.csv.clone(),
        plot: saved,
    };
    if a.json {
        return print_json(&out);
    }
    print_simboundary(&out, &rl, &settings, units);
    Ok(())
}

/// Warnings about inconclusive runs: a separation or an undecided run is no evidence of
/// stability.
fn boundary_warnings(points: &[EmpiricalPoint], s: &RunSettings) -> Vec<String> {
    let count = |o: Outcome| {
        points
            .iter()
            .filter(|p| p.inconclusive.is_some_and(|i| i.outcome == o))
            .count()
    };
    let mut w = Vec::new();
    let separated = count(Outcome::Separated);
    if separated > 0 {
        let advice = if s.human_force <= 0.0 {
            "nothing pushes the device into the wall: give --push F to keep it in contact"
        } else {
            "the push does not hold the device on the wall: a larger --push keeps it in contact"
        };
        w.push(format!(
            "at {separated} of {} β values the device left the wall (separated); separation is not stability, so nothing beyond counts as stable: {advice}",
            points.len()
        ));
    }
    let undecided = count(Outcome::Undecided);
    if undecided > 0 {
        w.push(format!(
            "at {undecided} of {} β values a run did not settle within the horizon (near the boundary the loop is nearly marginal), so nothing beyond counts as stable; --max-duration simulates longer",
            points.len()
        ));
    }
    w
}

/// The β values: the flags, or 10 %–90 % of the exact region's β extent above 0.
fn beta_values(a: &SimboundaryArgs, region: &hapstab::region::StableRegion) -> Result<Vec<f64>> {
    let top = region
        .polygons
        .iter()
        .flat_map(|p| p.vertices.iter().map(|v| v.beta))
        .filter(|b| b.is_finite())
        .fold(f64::NEG_INFINITY, f64::max);
    let top = if top.is_finite() && top > 0.0 {
        top
    } else {
        1.0
    };
    let lo = a.beta_min.unwrap_or(0.1 * top);
    let hi = a.beta_max.unwrap_or(0.9 * top);
    if !(lo.is_finite() && hi.is_finite()) {
        bail!("--beta-min/--beta-max must be finite (got {lo}, {hi})");
    }
    if hi < lo {
        bail!("--beta-max ({hi}) must be >= --beta-min ({lo})");
    }
    let n = a.beta_count;
    Ok(if n == 1 {
        vec![lo]
    } else {
        (0..n)
            .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
            .collect()
    })
}

/// Shortest round-trip text of a number, in exponent form when very large or small.
fn num(v: f64) -> String {
    crate::output::csv_num(v)
}

fn opt(v: Option<f64>) -> String {
    v.map_or_else(String::new, num)
}

fn write_boundary_csv(path: &Path, rows: &[BoundaryRow]) -> Result<()> {
    let mut w = csv::Writer::from_path(path)
        .with_context(|| format!("cannot write CSV {}", path.display()))?;
    w.write_record([
        "beta",
        "alpha_linear",
        "alpha_simulated",
        "alpha_unstable",
        "ratio",
        "censored",
        "alpha_max",
        "runs",
        "inconclusive_alpha",
        "inconclusive_outcome",
    ])?;
    for r in rows {
        let p = &r.point;
        w.write_record([
            num(p.beta),
            opt(p.alpha_linear),
            opt(p.alpha_simulated),
            opt(p.alpha_unstable),
            opt(r.ratio),
            p.censored.to_string(),
            num(p.alpha_max),
            p.runs.to_string(),
            opt(p.inconclusive.map(|i| i.alpha)),
            p.inconclusive
                .map_or("", |i| i.outcome.as_str())
                .to_string(),
        ])?;
    }
    w.flush()
        .with_context(|| format!("cannot write CSV {}", path.display()))?;
    Ok(())
}

fn boundary_plot(
    region: &hapstab::region::StableRegion,
    points: &[EmpiricalPoint],
    paper: Option<&Normalized>,
    s: &RunSettings,
    units: Units,
) -> Figure {
    let (title, xl, yl) = match paper {
        Some(p) => (
            format!(
                "Simulated vs exact linear boundary (γ = {}, δ = {}, d = {})",
                sig(p.gamma, 3),
                sig(p.delta, 3),
                p.d
            ),
            "virtual stiffness α = KT²/m",
            "virtual damping β = BT/m",
        ),
        None => (
            "Simulated vs exact linear boundary".to_string(),
            "wall stiffness a = K/k_u",
            "wall damping b = B/(k_u·T)",
        ),
    };
    let mut f = Figure::new(title)
        .x_label(xl)
        .y_label(yl)
        .legend(Legend::UpperRight);
    for (i, poly) in region.polygons.iter().enumerate() {
        let pts = poly.vertices.iter().map(|v: &AlphaBeta| (v.alpha, v.beta));
        let mut s = Series::polygon(pts).color(palette::BLUE).alpha(0.18);
        if i == 0 {
            s = s.label("exact linear stable region");
        }
        f.add(s);
    }
    let found: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| !p.censored)
        .filter_map(|p| p.alpha_simulated.map(|a| (a, p.beta)))
        .collect();
    let censored: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.censored)
        .filter_map(|p| p.alpha_simulated.map(|a| (a, p.beta)))
        .collect();
    let none: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.alpha_simulated.is_none())
        .filter_map(|p| p.alpha_unstable.map(|a| (a, p.beta)))
        .collect();
    let mut curve: Vec<(f64, f64)> = points
        .iter()
        .map(|p| match (p.alpha_simulated, p.censored) {
            (Some(a), false) => (a, p.beta),
            _ => (f64::NAN, p.beta),
        })
        .collect();
    curve.sort_by(|a, b| a.1.total_cmp(&b.1));
    f.add(Series::line(curve).color(palette::VERMILLION).width(2));
    let effects = describe_effects(s, units.force());
    let label = if effects.starts_with("none") {
        "simulated (linear)".to_string()
    } else {
        "simulated boundary".to_string()
    };
    f.add(
        Series::scatter(found, Marker::Circle)
            .color(palette::VERMILLION)
            .label(label),
    );
    if !censored.is_empty() {
        f.add(
            Series::scatter(censored, Marker::Triangle)
                .color(palette::ORANGE)
                .label("stable up to scan end"),
        );
    }
    if !none.is_empty() {
        f.add(
            Series::scatter(none, Marker::Cross)
                .color(palette::BLACK)
                .label("unstable at first scan α"),
        );
    }
    let inconclusive: Vec<(f64, f64)> = points
        .iter()
        .filter_map(|p| p.inconclusive.map(|i| (i.alpha, p.beta)))
        .collect();
    if !inconclusive.is_empty() {
        f.add(
            Series::scatter(inconclusive, Marker::Triangle)
                .color(palette::GREY)
                .hollow()
                .label("left the wall or undecided: no verdict"),
        );
    }
    f
}

/// The loop of a boundary search: the paper's (γ, δ, d), or the loop in words with its wall
/// units.
fn print_boundary_loop(o: &SimboundaryOut, rl: &ResolvedLoop, units: Units) {
    let Some((gamma, delta, d)) = rl
        .lp
        .paper_view()
        .map(|pp| (pp.gamma, pp.delta, rl.lp.delay.samples))
    else {
        for line in describe_loop(&rl.lp) {
            println!("{line}");
        }
        if let Some(w) = o.wall_units {
            println!(
                "units     a = K/k_u, b = B/(k_u·T) with k_u = {} N/m, k_u·T = {} Ns/m (the α and β columns and flags)",
                sig(w.stiffness, 6),
                sig(w.damping, 6)
            );
        }
        return;
    };
    println!(
        "plant       γ = {}, δ = {}, d = {}{}",
        sig(gamma, 6),
        sig(delta, 6),
        d,
        match o.mass {
            Some(m) if units.physical => {
                format!(" (m = {} kg, T = {} ms)", sig(m, 6), sig(o.period * 1e3, 6))
            }
            _ => String::new(),
        }
    );
}

fn print_simboundary(o: &SimboundaryOut, rl: &ResolvedLoop, s: &RunSettings, units: Units) {
    print_boundary_loop(o, rl, units);
    println!("effects     {}", describe_effects(s, units.force()));
    println!(
        "runs        {} samples each (extended up to {} until settled) from x(0) = {}; stable = {}",
        o.input.samples,
        o.input.max_samples,
        eng(o.input.initial.position, "m", 6),
        match o.input.stable_when {
            StableWhen::Decaying => "decaying".to_string(),
            StableWhen::AmplitudeBelow(m) => format!(
                "decaying or limit cycle below {} peak-to-peak",
                eng(m, "m", 4)
            ),
        }
    );
    match o.wall_units {
        None => println!(
            "exact       α_max = {} at β = {} (linear stable region, Section V)",
            sig(o.exact_alpha_max, 6),
            sig(o.exact_beta_at_alpha_max, 6)
        ),
        Some(w) => println!(
            "exact       K_max = {} N/m at B = {} Ns/m (a = {}, b = {}; linear stable region)",
            sig(o.exact_alpha_max * w.stiffness, 6),
            sig(o.exact_beta_at_alpha_max * w.damping, 6),
            sig(o.exact_alpha_max, 6),
            sig(o.exact_beta_at_alpha_max, 6)
        ),
    }
    println!();
    let phys = units.physical;
    let (sa, sb) = if o.wall_units.is_some() {
        ("a", "b")
    } else {
        ("α", "β")
    };
    if phys {
        println!(
            "{:>10} {:>10} {:>14} {:>14} {:>8} {:>12} {:>12}  note",
            sb,
            "B (Ns/m)",
            format!("{sa} linear"),
            format!("{sa} simulated"),
            "ratio",
            "K lin (N/m)",
            "K sim (N/m)"
        );
    } else {
        println!(
            "{:>10} {:>14} {:>14} {:>8}  note",
            "β", "α linear", "α simulated", "ratio"
        );
    }
    let f = |v: Option<f64>, n| v.map_or_else(|| "-".to_string(), |x| sig(x, n));
    for r in &o.points {
        let p = &r.point;
        let note = if let Some(i) = p.inconclusive.filter(|i| {
            p.alpha_unstable.is_none_or(|u| i.alpha < u)
                && p.alpha_simulated.is_none_or(|s| i.alpha > s)
        }) {
            let what = match i.outcome {
                Outcome::Separated => "left the wall",
                _ => "undecided",
            };
            format!("{what} at α = {}: no verdict beyond", sig(i.alpha, 6))
        } else if p.alpha_simulated.is_none() {
            format!("unstable already at α = {}", f(p.alpha_unstable, 4))
        } else if p.censored {
            format!("stable up to scan end α = {}", sig(p.alpha_max, 4))
        } else {
            String::new()
        };
        if phys {
            println!(
                "{:>10} {:>10} {:>14} {:>14} {:>8} {:>12} {:>12}  {note}",
                sig(p.beta, 6),
                f(r.wall_damping, 5),
                f(p.alpha_linear, 8),
                f(p.alpha_simulated, 8),
                f(r.ratio, 4),
                f(r.k_linear, 6),
                f(r.k_simulated, 6)
            );
        } else {
            println!(
                "{:>10} {:>14} {:>14} {:>8}  {note}",
                sig(p.beta, 6),
                f(p.alpha_linear, 8),
                f(p.alpha_simulated, 8),
                f(r.ratio, 4)
            );
        }
    }
    println!();
    if s.effects.quantization.is_some()
        && o.input.stable_when == StableWhen::Decaying
        && o.points.iter().any(|r| {
            r.point.alpha_simulated.is_none()
                && r.point.alpha_unstable.is_some()
                && r.point.inconclusive.is_none()
        })
    {
        println!(
            "note        quantized runs often settle into small limit cycles instead of decaying;\n            --stable-amplitude M counts cycles below M metres as stable"
        );
    }
    for w in &o.warnings {
        println!("warning     {w}");
    }
    if let Some(c) = &o.csv {
        println!("csv         {}", c.display());
    }
    if let Some(p) = &o.plot {
        println!("plot        {}, {}", p.svg.display(), p.png.display());
    }
}
