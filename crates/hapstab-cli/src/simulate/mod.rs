//! `hapstab simulate` and `hapstab simboundary`: the sampled-data loop of Fig. 3 in the time
//! domain with the nonlinear effects the paper leaves to future work (Remark 1,
//! Section IX): unilateral wall, Coulomb/static friction, encoder quantization, actuator
//! saturation. All simulation lives in `hapstab::simulation`; this module parses flags,
//! writes the CSV trace and the plots, and formats the verdicts.
//!
//! `run_args` holds the run's flags shared by both commands; `run`, `run_text` and `run_plot`
//! the `simulate` command, its text and its figure; `boundary`, `boundary_text` and
//! `boundary_plot` the `simboundary` command, its text and its figure. The pieces both use
//! (units, the effects in words, the output-path and budget checks) are here.

use std::path::Path;

use anyhow::{Result, bail};
use hapstab::PlantModel as LibPlantModel;
use hapstab::simulation::{Config, Contact};

use crate::model::{LoopArgs, ResolvedLoop};
use crate::output::sig;

mod boundary;
mod boundary_out;
mod boundary_plot;
mod boundary_scan;
mod boundary_text;
mod log;
mod run;
mod run_args;
mod run_plot;
mod run_plot_panels;
mod run_text;

pub use boundary::{SimboundaryArgs, run_simboundary};
pub use run::{SimulateArgs, run_simulate};
pub use run_args::RunArgs;

use run_args::{DEFAULT_SAMPLES, RunSettings};

const UNITS_HELP: &str = "Units: with physical plant flags (or none: the default device and arm) \
forces are in N and time in s. In normalized mode (--alpha/--beta, --gamma/--delta without \
physical flags) m = 1 and T = 1: time counts samples, forces are normalized forces T²F/m \
(in m), and the run length is given with --duration-samples.";

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

/// Shortest round-trip text of a number, in exponent form when very large or small.
fn num(v: f64) -> String {
    crate::output::csv_num(v)
}
