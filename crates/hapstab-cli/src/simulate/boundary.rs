//! `hapstab simboundary`: the empirical stability boundary of a nonlinear setting, found by
//! bisection of simulated runs at each β, beside the exact linear region; its JSON and CSV.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use clap::Args;
use hapstab::Normalized;
use hapstab::params::Wall;
use hapstab::simulation::{
    BoundarySearch, Config, Effects, EmpiricalPoint, Initial, LoopModel, MIN_REL_TOLERANCE, Model,
    Outcome, SimModel, StableWhen, empirical_boundary,
};
use hapstab::zoh::WallScale;
use rayon::prelude::*;
use serde::Serialize;

use super::boundary_plot::{Plane, boundary_plot};
use super::boundary_text::print_simboundary;
use super::run_args::RunSettings;
use super::{
    RunArgs, UNITS_HELP, Units, check_output_path, check_run_budget, friction_defined, num,
};
use crate::model::{LoopArgs, LoopInput, PlantModel, ResolvedLoop};
use crate::output::print_json;
use hapstab_plot::Saved;

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
pub(super) struct BoundaryRow {
    #[serde(flatten)]
    pub(super) point: EmpiricalPoint,
    /// α_simulated / α_linear.
    pub(super) ratio: Option<f64>,
    /// Physical mode: B, K_linear and K_simulated in Ns/m and N/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) wall_damping: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) k_linear: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) k_simulated: Option<f64>,
}

/// γ, δ and d of the paper's loop (Table I).
#[derive(Serialize)]
pub(super) struct PaperPlant {
    gamma: f64,
    delta: f64,
    d: usize,
}

/// The inputs of `simboundary`: the loop, the runs' setting and the scan.
#[derive(Serialize)]
pub(super) struct SimboundaryInput {
    #[serde(flatten)]
    pub(super) lp: LoopInput,
    pub(super) effects: Effects,
    pub(super) human_force: f64,
    pub(super) initial: Initial,
    pub(super) samples: usize,
    pub(super) max_samples: usize,
    pub(super) stable_when: StableWhen,
    pub(super) grid: usize,
    pub(super) rel_tol: f64,
}

#[derive(Serialize)]
pub(super) struct SimboundaryOut {
    /// The paper's loop given in physical units: γ, δ, d (Table I).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) normalized: Option<PaperPlant>,
    pub(super) units: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) mass: Option<f64>,
    pub(super) period: f64,
    /// The loop and the runs' setting as given.
    pub(super) input: SimboundaryInput,
    /// Other loops: K = a·stiffness (N/m) and B = b·damping (Ns/m) for the a, b columns.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) wall_units: Option<WallScale>,
    /// α_max of the exact linear stable region (Section V) and the β where it is reached.
    pub(super) exact_alpha_max: f64,
    pub(super) exact_beta_at_alpha_max: f64,
    pub(super) points: Vec<BoundaryRow>,
    /// Why some of the answer is no evidence of stability (e.g. runs that left the wall).
    pub(super) warnings: Vec<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) csv: Option<PathBuf>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) plot: Option<Saved>,
}

fn model_of(pm: &PlantModel) -> Result<Model> {
    let n = Normalized::new(0.0, 0.0, pm.gamma, pm.delta, pm.d)?;
    Ok(match pm.physical {
        Some((eff, s)) => Model::new(n, eff.mass, s.period)?,
        None => Model::unit(n)?,
    })
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
    let bar = crate::progress::Bar::new(betas.len(), "dampings", !a.json);
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

/// The figure of the exact region and the simulated boundary at `--plot`'s stem, if asked for;
/// `per_unit` puts the axes in N/m and Ns/m.
fn save_boundary_plot(
    a: &SimboundaryArgs,
    (region, points): (&hapstab::region::StableRegion, &[EmpiricalPoint]),
    model: &SimModel,
    per_unit: Option<(f64, f64)>,
    settings: &RunSettings,
    units: Units,
    loop_line: &str,
) -> Result<Option<Saved>> {
    let Some(stem) = &a.plot else {
        return Ok(None);
    };
    let paper = match model {
        SimModel::Paper(m) => Some(m.params),
        SimModel::Loop(_) => None,
    };
    let fig = boundary_plot(
        region,
        points,
        paper.as_ref(),
        Plane { per_unit },
        settings,
        units,
    );
    let saved = fig
        .subtitle(loop_line)
        .save(stem)
        .with_context(|| format!("--plot {}", stem.display()))?;
    Ok(Some(saved))
}

/// Runs `hapstab simboundary`.
pub fn run_simboundary(a: &SimboundaryArgs) -> Result<()> {
    let stable_when = check_boundary_args(a)?;
    let rl = a.lp.resolve(false)?;
    friction_defined(&rl, &a.run)?;
    let units = Units {
        physical: !rl.normalized,
    };
    let sys = rl.system()?;
    let fam = sys.family();
    let (model, pm) = boundary_template(a, &rl)?;
    let (template, settings) = a.run.config(model.clone(), units.physical)?;
    let n = fam.degree();
    let region_cost = hapstab::limits::region_cost_of_degree(n, hapstab::limits::core_degree(fam));
    crate::budget::check_loop(&a.lp, &rl.lp, region_cost, "the exact region")?;
    let region = sys.region()?;
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
    let per_unit = scale.filter(|_| units.physical);
    let line = crate::wall_plot::loop_line(&rl);
    let saved = save_boundary_plot(
        a,
        (&region, &points),
        &model,
        per_unit,
        &settings,
        units,
        &line,
    )?;
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
            lp: rl.input(None),
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
            "at {separated} of {} dampings the device left the wall (separated); separation is not stability, so nothing beyond counts as stable: {advice}",
            points.len()
        ));
    }
    let undecided = count(Outcome::Undecided);
    if undecided > 0 {
        w.push(format!(
            "at {undecided} of {} dampings a run did not settle within the horizon (near the boundary the loop is nearly marginal), so nothing beyond counts as stable; --max-duration simulates longer",
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
