//! `hapstab identify`: the plant from a recording of commanded force and measured position,
//! with standard errors and 95 % intervals, the fit and residual tests, the identified loop
//! as a loop file, and K_max at B = 0 and over the renderable damping band with its uncertainty. Every number is the library's
//! ([`hapstab::identify`]); this module parses, calls and renders.

mod plot;
mod text;

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::Args;
use hapstab::identify::bootstrap::{Bootstrap, bootstrap};
use hapstab::identify::frequency::FrequencyRecord;
use hapstab::identify::{
    Columns, Fixed, Identification, ModelKind, ModelSpec, Record, StiffnessLimit,
    identify_frequency, identify_runs, stiffness_limit,
};
use hapstab::model::{Loop, VelocityEstimator};
use serde::Serialize;

use crate::output::print_json;
use hapstab_plot::Saved;

/// Fit a plant model to a recording of force and position, then answer with K_max.
#[derive(Args, Debug, Clone)]
pub struct IdentifyArgs {
    /// CSV recording with a header line: time (s), commanded force (N), measured position (m),
    /// uniformly sampled at the loop's period (the mean time step is taken as T); repeat it
    /// for several runs of the same plant, fitted together
    #[arg(
        long,
        value_name = "FILE",
        required_unless_present = "frequency_data",
        conflicts_with = "frequency_data"
    )]
    pub data: Vec<PathBuf>,
    /// A measured frequency response instead: CSV with columns frequency (Hz) and
    /// magnitude_db, phase_deg, or real, imag (m/N), measured on a loop of period --period
    #[arg(long, value_name = "FILE")]
    pub frequency_data: Option<PathBuf>,
    /// Sampling period T in s of the loop a frequency response was measured on
    #[arg(long, default_value_t = 1e-3, requires = "frequency_data")]
    pub period: f64,
    /// Model: mass-spring-damper (m, b, k; device alone, or device + arm with
    /// --fix device-mass=… --fix device-damping=…), held-device, two-mass, or tf:N/D (a
    /// transfer function of numerator order N and denominator order D, monic denominator)
    #[arg(long, default_value = "mass-spring-damper")]
    pub model: String,
    /// The time, force and position column names in the header
    #[arg(long, value_name = "T,F,X", default_value = "time,force,position")]
    pub columns: String,
    /// Hold a parameter at a known value (repeatable), e.g. --fix device-mass=0.1
    #[arg(long = "fix", value_name = "NAME=VALUE")]
    pub fix: Vec<String>,
    /// Known delay of the force in whole samples
    #[arg(long, conflicts_with = "delay_time")]
    pub delay: Option<usize>,
    /// Known delay of the force in s (any fraction of a sample)
    #[arg(long)]
    pub delay_time: Option<f64>,
    /// Known actuator lag τ in s (a first-order lag between commanded and applied force)
    #[arg(long, default_value_t = 0.0)]
    pub force_lag: f64,
    /// Quantization step of the recorded position in m (0: none): the noise is taken as at
    /// least q²/12, and q is the position resolution of the renderable damping band
    #[arg(long, value_name = "Q", default_value_t = 0.0)]
    pub quantization: f64,
    /// Fit the delay too (any fraction of a sample), from --delay/--delay-time (at least a
    /// quarter sample)
    #[arg(long)]
    pub fit_delay: bool,
    /// Fit the actuator lag τ too, from --force-lag (half a sample when it is 0)
    #[arg(long)]
    pub fit_force_lag: bool,
    /// Velocity estimator of the wall rendered on the identified plant (for K_max and the
    /// loop file), as --velocity of the other commands
    #[arg(long, default_value = "backward")]
    pub velocity: VelocityEstimator,
    /// Loops drawn from the parameters' covariance for K_max's spread
    #[arg(long, default_value_t = hapstab::identify::consequence::DEFAULT_DRAWS)]
    pub draws: usize,
    /// Seed of the drawn loops and of the robust search
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Also give each parameter's 95 % interval by a residual bootstrap of N refits (0: none;
    /// a time recording only)
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub bootstrap: usize,
    /// Write the identified loop as a loop file for --loop
    #[arg(long, value_name = "FILE")]
    pub write_loop: Option<PathBuf>,
    /// Figure of measured and model position and the residuals (FILE.svg and FILE.png)
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
    /// One JSON object instead of text
    #[arg(long)]
    pub json: bool,
}

/// The command's settings as echoed under `input`.
#[derive(Serialize)]
struct Input<'a> {
    #[serde(skip_serializing_if = "<[PathBuf]>::is_empty")]
    data: &'a [PathBuf],
    #[serde(skip_serializing_if = "Option::is_none")]
    frequency_data: Option<&'a PathBuf>,
    columns: &'a str,
    fixed: &'a [Fixed],
    delay_time: f64,
    force_lag: f64,
    fit_delay: bool,
    fit_force_lag: bool,
    quantization: f64,
    velocity: &'a VelocityEstimator,
    draws: usize,
    seed: u64,
}

/// The JSON report.
#[derive(Serialize)]
struct Report<'a> {
    input: Input<'a>,
    #[serde(flatten)]
    identification: &'a Identification,
    stiffness_limit: &'a StiffnessLimit,
    #[serde(skip_serializing_if = "Option::is_none")]
    bootstrap: Option<&'a Bootstrap>,
    #[serde(rename = "loop")]
    lp: &'a Loop,
    loop_file: Option<&'a PathBuf>,
    plot: Option<Saved>,
}

/// The data a fit reads: a time recording or a frequency response.
enum Data {
    Time(Vec<Record>),
    Frequency(FrequencyRecord),
}

impl Data {
    fn period(&self) -> f64 {
        match self {
            Data::Time(r) => r[0].period,
            Data::Frequency(r) => r.period,
        }
    }
}

/// The recording or the frequency response, checked.
fn load(args: &IdentifyArgs) -> Result<Data> {
    let read = |flag: &str, path: &PathBuf| {
        std::fs::read_to_string(path)
            .with_context(|| format!("{flag} '{}': cannot read", path.display()))
    };
    if let Some(path) = &args.frequency_data {
        let text = read("--frequency-data", path)?;
        let rec = FrequencyRecord::from_csv(&text, args.period)
            .with_context(|| format!("--frequency-data '{}'", path.display()))?;
        return Ok(Data::Frequency(rec));
    }
    if args.data.is_empty() {
        bail!("--data: give a recording (or --frequency-data)");
    }
    let columns = Columns::parse(&args.columns)?;
    let runs = args
        .data
        .iter()
        .map(|path| {
            let text = read("--data", path)?;
            Record::from_csv(&text, &columns)
                .with_context(|| format!("--data '{}'", path.display()))
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(Data::Time(runs))
}

/// The model spec from the flags (the delay in s at the recording's period).
fn spec(args: &IdentifyArgs, period: f64) -> Result<ModelSpec> {
    let kind = ModelKind::parse(&args.model)?;
    let fixed = args
        .fix
        .iter()
        .map(|f| Fixed::parse(f))
        .collect::<Result<Vec<_>, _>>()?;
    let delay_time = match (args.delay, args.delay_time) {
        (Some(d), _) => d as f64 * period,
        (None, Some(t)) => t,
        (None, None) => 0.0,
    };
    Ok(ModelSpec::new(kind, fixed, delay_time, args.force_lag)?
        .fitting_timing(args.fit_delay, args.fit_force_lag)
        .with_quantization(args.quantization)?)
}

/// Writes the identified loop as a loop file (`{"loop": …}`, as `--loop` reads it).
fn write_loop(path: &PathBuf, lp: &Loop) -> Result<()> {
    #[derive(Serialize)]
    struct File<'a> {
        #[serde(rename = "loop")]
        lp: &'a Loop,
    }
    let text = crate::output::json_text(&File { lp })?;
    std::fs::write(path, text + "\n")
        .with_context(|| format!("--write-loop '{}': cannot write", path.display()))
}

/// Runs `hapstab identify`.
pub fn run(args: &IdentifyArgs) -> Result<()> {
    if args.draws == 0 {
        bail!("--draws: must be at least 1");
    }
    let data = load(args)?;
    let spec = spec(args, data.period())?;
    let id = match &data {
        Data::Time(r) => identify_runs(r, &spec)?,
        Data::Frequency(r) => identify_frequency(r, &spec)?,
    };
    let lp = id.to_loop(args.velocity.clone())?;
    let boot = match (&data, args.bootstrap) {
        (_, 0) => None,
        (Data::Time(r), n) => Some(bootstrap(r, &id, n, args.seed)?),
        (Data::Frequency(_), _) => bail!("--bootstrap: resamples a time recording (--data)"),
    };
    let limit = stiffness_limit(&id, &args.velocity, args.draws, args.seed)?;
    if let Some(path) = &args.write_loop {
        write_loop(path, &lp)?;
    }
    let saved = match &args.plot {
        Some(path) => Some(match &data {
            Data::Time(r) => plot::figure(&r[0], &id, &lp).save(path)?,
            Data::Frequency(r) => plot::bode(r, &id, &lp).save(path)?,
        }),
        None => None,
    };
    if args.json {
        return print_json(&Report {
            input: Input {
                data: &args.data,
                frequency_data: args.frequency_data.as_ref(),
                columns: &args.columns,
                fixed: &spec.fixed,
                delay_time: spec.delay_time,
                force_lag: spec.force_lag,
                fit_delay: spec.fit_delay,
                fit_force_lag: spec.fit_force_lag,
                quantization: spec.quantization,
                velocity: &args.velocity,
                draws: args.draws,
                seed: args.seed,
            },
            identification: &id,
            stiffness_limit: &limit,
            bootstrap: boot.as_ref(),
            lp: &lp,
            loop_file: args.write_loop.as_ref(),
            plot: saved,
        });
    }
    text::print(&id, &limit, &lp, args, saved.as_ref());
    if let Some(b) = &boot {
        text::print_bootstrap(&id, b);
    }
    Ok(())
}
