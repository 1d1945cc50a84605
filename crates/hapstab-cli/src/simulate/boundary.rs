//! `hapstab simboundary`: the empirical stability boundary of a nonlinear setting, found by
//! bisection of simulated runs at each β, beside the exact linear region; its JSON and CSV.
//!
//! Parts: [`super::boundary_scan`] scans the β values and bisects the runs,
//! [`super::boundary_out`] holds the answer's rows and writes the CSV,
//! [`super::boundary_text`] prints it and [`super::boundary_plot`] draws it.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;
use hapstab::simulation::{EmpiricalPoint, SimModel};
use hapstab_plot::Saved;

use super::boundary_out::{
    BoundaryRow, ExactOut, PaperPlant, SimboundaryInput, SimboundaryOut, boundary_row,
    write_boundary_csv,
};
use super::boundary_plot::{Plane, boundary_plot};
use super::boundary_scan::{
    ScanRange, beta_values, boundary_points, boundary_template, boundary_warnings,
    check_boundary_args,
};
use super::boundary_text::print_simboundary;
use super::run_args::RunSettings;
use super::{RunArgs, UNITS_HELP, Units, check_run_budget, friction_defined};
use crate::model::LoopArgs;
use crate::output::print_json;

/// Arguments of `hapstab simboundary`.
#[derive(Args, Debug)]
#[command(after_help = UNITS_HELP)]
pub struct SimboundaryArgs {
    #[command(flatten)]
    pub(super) lp: LoopArgs,
    #[command(flatten)]
    pub(super) run: RunArgs,
    /// Smallest wall damping B in Ns/m (a loop in physical units) [default: 10 % of the exact
    /// region's top].
    #[arg(long, value_name = "NS_PER_M", allow_hyphen_values = true)]
    pub(super) wall_damping_min: Option<f64>,
    /// Largest wall damping B in Ns/m [default: 90 % of the exact region's top].
    #[arg(long, value_name = "NS_PER_M", allow_hyphen_values = true)]
    pub(super) wall_damping_max: Option<f64>,
    /// Upper end of the stiffness scan in N/m [default: 3× the exact linear boundary at each
    /// damping].
    #[arg(long, value_name = "N_PER_M", allow_hyphen_values = true)]
    pub(super) wall_stiffness_max: Option<f64>,
    /// Smallest normalized damping β = BT/m, in place of --wall-damping-min (for other
    /// plants the wall unit b = B·T/m with m the plant's reference mass).
    #[arg(long, allow_hyphen_values = true, conflicts_with = "wall_damping_min")]
    pub(super) beta_min: Option<f64>,
    /// Largest β, in place of --wall-damping-max.
    #[arg(long, allow_hyphen_values = true, conflicts_with = "wall_damping_max")]
    pub(super) beta_max: Option<f64>,
    /// Number of dampings (B or β values), evenly spaced.
    #[arg(long, value_name = "N", default_value_t = 8)]
    pub(super) beta_count: usize,
    /// Upper end of the α scan (wall unit a = K·T²/m for other plants), in place of
    /// --wall-stiffness-max.
    #[arg(
        long,
        allow_hyphen_values = true,
        conflicts_with = "wall_stiffness_max"
    )]
    pub(super) alpha_max: Option<f64>,
    /// Coarse α scan points before bisection.
    #[arg(long, value_name = "N", default_value_t = 12)]
    pub(super) grid: usize,
    /// Bisection stops when the bracket is below this fraction of α (at least 1e-6).
    #[arg(
        long,
        value_name = "REL",
        default_value_t = 1e-3,
        allow_hyphen_values = true
    )]
    pub(super) rel_tol: f64,
    /// Count limit cycles of peak-to-peak amplitude below M metres as stable [default: only
    /// decaying runs].
    #[arg(long, value_name = "M", allow_hyphen_values = true)]
    pub(super) stable_amplitude: Option<f64>,
    /// Write the table as CSV: wall_damping (Ns/m), k_linear, k_simulated, k_unstable (N/m),
    /// ratio, censored, k_max, runs, inconclusive_k, inconclusive_outcome (beta, alpha_… for
    /// normalized input).
    #[arg(long, value_name = "FILE")]
    pub(super) csv: Option<PathBuf>,
    /// Plot the exact linear region and the simulated boundary: writes STEM.svg and STEM.png.
    #[arg(long, value_name = "STEM")]
    pub(super) plot: Option<PathBuf>,
    /// Print one JSON object instead of text (no progress bar).
    #[arg(long)]
    pub(super) json: bool,
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
    let scale = match (&pm, units.physical) {
        (Some(pm), _) => pm
            .physical
            .map(|(eff, s)| (eff.mass / (s.period * s.period), eff.mass / s.period)),
        (None, _) => Some((fam.scale.stiffness, fam.scale.damping)),
    };
    let range = ScanRange::of(a, scale.filter(|_| units.physical))?;
    let betas = beta_values(a, &range, &region)?;
    // every β: the α grid's runs and a bisection of about log2(1/rel-tol) more
    let runs = betas.len() as f64 * (a.grid as f64 + (1.0 / a.rel_tol).log2().max(1.0));
    check_run_budget(&a.lp, &rl.lp, &template, runs, "the boundary's runs")?;
    let points = boundary_points(a, range.a_max, &template, &betas, stable_when)?;
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
        exact: (region.a_max, region.b_at_a_max),
        exact_out: ExactOut::new(region.a_max, region.b_at_a_max, per_unit),
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
