//! `hapstab simulate`: one run of the loop with its flags, the JSON it prints, and the CSV
//! trace and plot it writes on request.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use clap::Args;
use hapstab::answer::SimulationAnswer;
use hapstab::params::Wall;
use hapstab::simulation::{
    Config, LoopModel, MAX_TRACE_ROWS, Model, RunResult, SimModel, Trace, simulate,
};
use serde::Serialize;

use super::run_args::RunSettings;
use super::run_plot::trace_plot;
use super::run_text::print_simulate;
use super::{
    RunArgs, UNITS_HELP, Units, check_output_path, check_run_budget, friction_defined, num,
};
use crate::model::{
    LoopArgs, NON_PAPER_PLANT_FLAGS, ResolvedLoop, WallArgs, resolve_loop_wall, resolve_point,
};
use crate::output::{eng, print_json};

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
    #[command(flatten)]
    log: super::log::LogArgs,
    /// Write the trace as CSV with columns t, x, v, F (F: wall force, positive pushing out
    /// of the wall).
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
    /// Plot position and force over time, with the judged window (a decaying run: its
    /// transient, and the envelope of |x| over the whole run on a log scale): writes STEM.svg
    /// and STEM.png.
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
pub(super) struct Files {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) csv: Option<PathBuf>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) svg: Option<PathBuf>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) png: Option<PathBuf>,
    pub(super) rows: usize,
    pub(super) record_every: usize,
}

/// The JSON of `hapstab simulate`: the library's answer and the files written.
#[derive(Serialize)]
pub(super) struct SimulateOut {
    #[serde(flatten)]
    pub(super) answer: SimulationAnswer,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) files: Option<Files>,
}

impl std::ops::Deref for SimulateOut {
    type Target = SimulationAnswer;
    fn deref(&self) -> &SimulationAnswer {
        &self.answer
    }
}

/// Bytes per kept trace row in memory (five f64 columns).
const TRACE_ROW_BYTES: f64 = 40.0;

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
pub(super) struct SimLoop {
    pub(super) rl: ResolvedLoop,
    pub(super) wall: Wall,
    pub(super) model: SimModel,
}

impl SimLoop {
    fn resolve(lp: &LoopArgs, wall: &WallArgs, run: &RunArgs) -> Result<Self> {
        let rl = lp.resolve(wall.normalized())?;
        let sys = rl.system()?;
        let fam = sys.family();
        let w = resolve_loop_wall(&rl, fam, wall)?;
        friction_defined(&rl, run)?;
        let model = if rl.lp.paper_view().is_some() {
            let pm = resolve_point(&lp.plant, &wall.over_file(&rl))?;
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
}

/// Runs `hapstab simulate`.
pub fn run_simulate(a: &SimulateArgs) -> Result<()> {
    check_simulate_args(a)?;
    let sl = SimLoop::resolve(&a.lp, &a.wall, &a.run)?;
    if a.log.identification_log.is_some() {
        return super::log::run(&a.log, &sl.rl.lp, a.run.quantization, a.json);
    }
    let units = sl.units();
    let (mut cfg, settings) = a.run.config(sl.model.clone(), units.physical)?;
    let files_wanted = a.csv.is_some() || a.plot.is_some();
    cfg.trace_rows = if files_wanted { a.max_rows } else { 0 };
    check_run_budget(&a.lp, &sl.rl.lp, &cfg, 1.0, "the run")?;
    let mut result = simulate(&cfg)?;
    let trace = result.trace.take().unwrap_or_default();
    let files = if files_wanted {
        let line = crate::wall_plot::loop_line(&sl.rl);
        Some(write_files(
            a,
            (&trace, &result),
            &cfg,
            &settings,
            units,
            &line,
        )?)
    } else {
        None
    };
    let out = SimulateOut {
        answer: SimulationAnswer::new(result, &cfg, sl.rl.input(Some(sl.wall)), sl.rl.normalized),
        files,
    };
    if a.json {
        return print_json(&out);
    }
    print_simulate(&out, &sl, &settings, units);
    Ok(())
}

/// Writes the CSV and the plot that were asked for.
fn write_files(
    a: &SimulateArgs,
    (trace, result): (&Trace, &RunResult),
    cfg: &Config,
    settings: &RunSettings,
    units: Units,
    loop_line: &str,
) -> Result<Files> {
    if let Some(csv) = &a.csv {
        write_trace_csv(csv, trace)?;
    }
    let saved = match &a.plot {
        Some(stem) => {
            // a growing run is plotted up to where it leaves the scale of its start; the CSV
            // keeps every recorded row
            let clipped = hapstab::simulation::clip_growing_trace(cfg, result, trace)?;
            Some(
                trace_plot(trace, clipped.as_ref(), result, cfg, settings, units)
                    .subtitle(loop_line)
                    .save(stem)
                    .with_context(|| format!("--plot {}", stem.display()))?,
            )
        }
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
