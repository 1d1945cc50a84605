//! The run's flags shared by `simulate` and `simboundary` (nonlinear effects, human force,
//! initial state, run length and horizon) and the settings they resolve to.

use anyhow::{Result, bail};
use clap::Args;
use hapstab::simulation::{
    Config, Contact, DEFAULT_MAX_SAMPLES, Effects, Friction, HumanForce, Initial, SimModel,
    samples_for_duration,
};
use serde::Serialize;

use crate::output::sig;

/// Longest run and horizon accepted (samples): 10⁹ samples take 10–60 s per core.
const MAX_SAMPLES: f64 = hapstab::limits::MAX_SIMULATION_SAMPLES;
/// Default run length: 10 s at the physical period, 10 000 samples in normalized mode.
pub(super) const DEFAULT_SAMPLES: usize = 10_000;
/// Default initial penetration x(0) in m.
const DEFAULT_X0: f64 = 1e-3;

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
pub(super) struct RunSettings {
    pub(super) effects: Effects,
    pub(super) human_force: f64,
    pub(super) initial: Initial,
    pub(super) samples: usize,
    pub(super) max_samples: usize,
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
    pub(super) fn resolve(&self, physical: bool, period: f64) -> Result<RunSettings> {
        let finite = |name: &str, v: Option<f64>| -> Result<Option<f64>> {
            match v {
                Some(x) if !x.is_finite() => bail!("{name} must be a finite number (got {x})"),
                _ => Ok(v),
            }
        };
        let friction = Friction::from_parts(
            finite("--coulomb", self.coulomb)?,
            finite("--stiction", self.stiction)?,
        );
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

    pub(super) fn config(&self, model: SimModel, physical: bool) -> Result<(Config, RunSettings)> {
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
