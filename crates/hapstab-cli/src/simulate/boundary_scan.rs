//! The scan of `hapstab simboundary`: the β values, the template model of the runs, the
//! bisection at each β in parallel and the warnings about inconclusive runs.

use anyhow::{Result, bail};
use hapstab::Normalized;
use hapstab::params::Wall;
use hapstab::simulation::{
    BoundarySearch, Config, EmpiricalPoint, LoopModel, MIN_REL_TOLERANCE, Model, Outcome, SimModel,
    StableWhen, empirical_boundary,
};
use rayon::prelude::*;

use super::boundary::SimboundaryArgs;
use super::check_output_path;
use super::run_args::RunSettings;
use crate::model::{PlantModel, ResolvedLoop};

pub(super) fn model_of(pm: &PlantModel) -> Result<Model> {
    let n = Normalized::new(0.0, 0.0, pm.gamma, pm.delta, pm.d)?;
    Ok(match pm.physical {
        Some((eff, s)) => Model::new(n, eff.mass, s.period)?,
        None => Model::unit(n)?,
    })
}

/// The template model of a boundary search: the paper's loop in its normalized view, or any
/// loop (its wall is replaced by every run).
pub(super) fn boundary_template(
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

pub(super) fn check_boundary_args(a: &SimboundaryArgs) -> Result<StableWhen> {
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
    if let Some(m) = a.wall_stiffness_max
        && !(m.is_finite() && m > 0.0)
    {
        bail!("--wall-stiffness-max must be a positive number of N/m (got {m})");
    }
    Ok(match a.stable_amplitude {
        None => StableWhen::Decaying,
        Some(m) if m.is_finite() && m > 0.0 => StableWhen::AmplitudeBelow(m),
        Some(m) => bail!("--stable-amplitude must be a positive number of metres (got {m})"),
    })
}

/// The scan's range in the loop's wall units: the dampings' ends and the top of the stiffness
/// scan, from the physical flags (K in N/m, B in Ns/m) or the normalized ones (α, β).
pub(super) struct ScanRange {
    /// Smallest damping b.
    pub b_min: Option<f64>,
    /// Largest damping b.
    pub b_max: Option<f64>,
    /// Top of the stiffness scan a.
    pub a_max: Option<f64>,
    /// Ns/m per unit of b when the dampings were given in Ns/m.
    pub b_unit: Option<f64>,
}

impl ScanRange {
    /// The range of the flags; `per_unit` = (N/m, Ns/m) per wall unit for a loop in physical
    /// units, None for normalized input, which takes only α and β.
    pub(super) fn of(a: &SimboundaryArgs, per_unit: Option<(f64, f64)>) -> Result<Self> {
        let physical = [
            ("--wall-damping-min", a.wall_damping_min),
            ("--wall-damping-max", a.wall_damping_max),
            ("--wall-stiffness-max", a.wall_stiffness_max),
        ];
        let Some((k_unit, b_unit)) = per_unit else {
            if let Some((flag, _)) = physical.iter().find(|(_, v)| v.is_some()) {
                bail!(
                    "{flag} needs a loop in physical units (normalized input takes --beta-min, --beta-max and --alpha-max)"
                );
            }
            return Ok(Self {
                b_min: a.beta_min,
                b_max: a.beta_max,
                a_max: a.alpha_max,
                b_unit: None,
            });
        };
        if let Some((flag, Some(v))) = physical
            .iter()
            .find(|(_, v)| v.is_some_and(|x| !x.is_finite()))
        {
            bail!("{flag} must be a finite number (got {v})");
        }
        Ok(Self {
            b_min: a.wall_damping_min.map(|b| b / b_unit).or(a.beta_min),
            b_max: a.wall_damping_max.map(|b| b / b_unit).or(a.beta_max),
            a_max: a.wall_stiffness_max.map(|k| k / k_unit).or(a.alpha_max),
            b_unit: (a.wall_damping_min.is_some() || a.wall_damping_max.is_some())
                .then_some(b_unit),
        })
    }
}

/// The simulated boundary at each β, in parallel, with a progress bar on a terminal; the
/// stiffness scan of each reaches `a_max` (wall units) where given.
pub(super) fn boundary_points(
    a: &SimboundaryArgs,
    a_max: Option<f64>,
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
                dampings: vec![beta],
                a_max,
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

/// Warnings about inconclusive runs: a separation or an undecided run is no evidence of
/// stability.
pub(super) fn boundary_warnings(points: &[EmpiricalPoint], s: &RunSettings) -> Vec<String> {
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

/// The dampings b (wall units): the range's, or 10 %–90 % of the exact region's extent in b
/// above 0.
pub(super) fn beta_values(
    a: &SimboundaryArgs,
    range: &ScanRange,
    region: &hapstab::region::StableRegion,
) -> Result<Vec<f64>> {
    let top = region
        .extent()
        .map(|e| e.y_max)
        .filter(|t| t.is_finite() && *t > 0.0)
        .unwrap_or(1.0);
    let lo = range.b_min.unwrap_or(0.1 * top);
    let hi = range.b_max.unwrap_or(0.9 * top);
    // the ends in the flags' units: B in Ns/m, or β
    let (lo_flag, hi_flag, unit, shown) = match range.b_unit {
        Some(u) => ("--wall-damping-min", "--wall-damping-max", " Ns/m", u),
        None => ("--beta-min", "--beta-max", "", 1.0),
    };
    if !(lo.is_finite() && hi.is_finite()) {
        bail!("{lo_flag}/{hi_flag} must be finite (got {lo}, {hi})");
    }
    if hi < lo {
        bail!(
            "{hi_flag} ({}{unit}) must be >= {lo_flag} ({}{unit})",
            hi * shown,
            lo * shown
        );
    }
    let n = a.beta_count;
    Ok(hapstab::grid::evenly_spaced(lo, hi, n))
}
