//! The empirical stability boundary of a nonlinear setting (compare Fig. 4–6 and Remark 1):
//! for each β the largest α whose simulated run is stable.

use rayon::prelude::*;
use serde::Serialize;

use super::{Config, Outcome, simulate};
use crate::error::{Error, Result, finite, positive};
use crate::paper::NormalizedFamily;
use crate::paper::PlantParams;
use crate::param::Param;

/// When a simulated run counts as stable for [`empirical_boundary`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StableWhen {
    /// Only a decaying run is stable.
    Decaying,
    /// Decaying runs and limit cycles with a peak-to-peak amplitude below this many metres
    /// are stable.
    AmplitudeBelow(f64),
}

/// Smallest relative bisection tolerance: 20 bisection steps below a grid bracket; a
/// simulated boundary is not sharper than the steady-state verdicts it bisects on.
pub const MIN_REL_TOLERANCE: f64 = 1e-6;

/// Most bisection steps per β: more than [`MIN_REL_TOLERANCE`] needs from any bracket.
pub const MAX_BISECTION_STEPS: usize = 64;

/// An empirical stability-boundary search: for each damping b the largest stiffness a whose
/// simulated run is stable, in the loop's wall units (α and β for the paper's loop), with
/// everything else taken from a template run.
#[derive(Debug, Clone)]
pub struct BoundarySearch {
    /// Template run (plant, delay, effects, human force, initial state, duration); its wall
    /// is replaced.
    pub template: Config,
    /// Virtual damping values b in wall units (β of Table I for the paper's loop).
    pub dampings: Vec<f64>,
    /// Upper end of the stiffness scan; default 3× the linear boundary at that b (or 2 if
    /// the linear loop is unstable there).
    pub a_max: Option<f64>,
    /// Coarse scan points in (0, a_max] before bisection (>= 2).
    pub grid: usize,
    /// Bisection stops when the bracket is below this fraction of a
    /// (>= [`MIN_REL_TOLERANCE`]).
    pub rel_tolerance: f64,
    /// Stability criterion.
    pub stable_when: StableWhen,
}

/// A run that neither counts as stable nor as unstable: the device left a unilateral wall
/// (`separated`), or the run did not settle (`undecided`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct InconclusiveRun {
    /// Stiffness of the run in wall units (α for the paper's loop).
    #[serde(rename = "alpha")]
    pub a: f64,
    /// `separated` or `undecided`.
    pub outcome: Outcome,
}

/// One damping of an empirical boundary, in wall units (written with the paper's names α
/// and β, which they are for the paper's loop).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EmpiricalPoint {
    /// Virtual damping b.
    #[serde(rename = "beta")]
    pub b: f64,
    /// The exact linear boundary a at this b (Section V), if the linear loop is stable for
    /// small a > 0.
    #[serde(rename = "alpha_linear")]
    pub a_linear: Option<f64>,
    /// The simulated boundary: the largest a found stable below every a that was not
    /// (None if the first grid point is not stable).
    #[serde(rename = "alpha_simulated")]
    pub a_simulated: Option<f64>,
    /// Smallest a found unstable (None if no run was unstable).
    #[serde(rename = "alpha_unstable")]
    pub a_unstable: Option<f64>,
    /// Smallest a whose run was inconclusive (separated or undecided), if any: no evidence
    /// of stability, so the scan does not go beyond the first one.
    pub inconclusive: Option<InconclusiveRun>,
    /// True if every a up to the scan end was stable (the boundary lies beyond).
    pub censored: bool,
    /// Upper end of the stiffness scan.
    #[serde(rename = "alpha_max")]
    pub a_max: f64,
    /// Number of simulated runs.
    pub runs: usize,
}

/// The exact linear boundary along α at fixed β (Section V): the upper end of the stable
/// α-interval that starts at α = −γ, by D-decomposition ([`crate::paper::linear::exact_upper_alpha`]).
/// None if no such interval exists; `f64::INFINITY` if it is unbounded.
pub fn exact_alpha_limit(plant: PlantParams, d: usize, beta: f64) -> Result<Option<f64>> {
    finite(Param::Beta, beta)?;
    let plant = PlantParams::new(plant.gamma, plant.delta)?;
    let fam = NormalizedFamily::new(plant, d)?;
    Ok(crate::paper::linear::exact_upper_alpha(&fam, beta))
}

/// How one run counts for the boundary.
#[derive(Debug, Clone, Copy, PartialEq)]
enum RunClass {
    Stable,
    Unstable,
    Inconclusive(Outcome),
}

fn classify_run(template: &Config, alpha: f64, beta: f64, when: StableWhen) -> Result<RunClass> {
    let mut cfg = template.clone();
    cfg.model = template.model.with_wall_units(alpha, beta)?;
    cfg.trace_rows = 0;
    let v = simulate(&cfg)?.verdict;
    let small = |a: f64| v.limit_cycle.is_some_and(|c| c.peak_to_peak < a);
    Ok(match (v.outcome, when) {
        (Outcome::Decaying, _) => RunClass::Stable,
        (Outcome::LimitCycle, StableWhen::AmplitudeBelow(a)) if small(a) => RunClass::Stable,
        (Outcome::LimitCycle | Outcome::Growing, _) => RunClass::Unstable,
        (o @ (Outcome::Separated | Outcome::Undecided), _) => RunClass::Inconclusive(o),
    })
}

/// What a scan along α found so far.
#[derive(Debug, Clone, Copy)]
struct Scan {
    stable: Option<f64>,
    unstable: Option<f64>,
    inconclusive: Option<InconclusiveRun>,
}

impl Scan {
    fn note(&mut self, alpha: f64, class: RunClass) {
        match class {
            RunClass::Stable => self.stable = Some(self.stable.map_or(alpha, |s| s.max(alpha))),
            RunClass::Unstable => {
                self.unstable = Some(self.unstable.map_or(alpha, |u| u.min(alpha)))
            }
            RunClass::Inconclusive(outcome) => {
                if self.inconclusive.is_none_or(|i| alpha < i.a) {
                    self.inconclusive = Some(InconclusiveRun { a: alpha, outcome });
                }
            }
        }
    }
}

/// Bisects between a stable `lo` and a non-stable `hi` down to the relative tolerance
/// (at most [`MAX_BISECTION_STEPS`] steps); returns the final stable end and the runs made.
fn bisect(
    search: &BoundarySearch,
    beta: f64,
    mut lo: f64,
    mut hi: f64,
    scan: &mut Scan,
) -> Result<(f64, usize)> {
    let mut runs = 0;
    while hi - lo > search.rel_tolerance * hi && runs < MAX_BISECTION_STEPS {
        let mid = 0.5 * (lo + hi);
        if !(mid > lo && mid < hi) {
            break;
        }
        runs += 1;
        let class = classify_run(&search.template, mid, beta, search.stable_when)?;
        scan.note(mid, class);
        if class == RunClass::Stable {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok((lo, runs))
}

fn boundary_at(search: &BoundarySearch, beta: f64) -> Result<EmpiricalPoint> {
    let alpha_linear = search.template.model.exact_upper_a(beta)?;
    let alpha_max = match search.a_max {
        Some(a) => positive(Param::AlphaMax, a)?,
        None => match alpha_linear {
            Some(a) if a.is_finite() => 3.0 * a,
            _ => 2.0,
        },
    };
    let g = search.grid;
    let grid: Vec<f64> = (1..=g).map(|i| alpha_max * i as f64 / g as f64).collect();
    let classes: Vec<RunClass> = grid
        .par_iter()
        .map(|&a| classify_run(&search.template, a, beta, search.stable_when))
        .collect::<Result<_>>()?;
    let mut scan = Scan {
        stable: None,
        unstable: None,
        inconclusive: None,
    };
    let first_bad = classes.iter().position(|c| *c != RunClass::Stable);
    let mut runs = g;
    for (&a, &c) in grid
        .iter()
        .zip(&classes)
        .take(first_bad.map_or(g, |i| i + 1))
    {
        scan.note(a, c);
    }
    let alpha_simulated = match first_bad {
        None => Some(alpha_max),
        Some(0) => None,
        Some(i) => {
            let (lo, n) = bisect(search, beta, grid[i - 1], grid[i], &mut scan)?;
            runs += n;
            Some(lo)
        }
    };
    Ok(EmpiricalPoint {
        b: beta,
        a_linear: alpha_linear,
        a_simulated: alpha_simulated,
        a_unstable: scan.unstable,
        inconclusive: scan.inconclusive,
        censored: first_bad.is_none(),
        a_max: alpha_max,
        runs,
    })
}

/// The empirical stability boundary of a nonlinear setting (compare Fig. 4–6 and
/// Remark 1): for each β a coarse scan of α over (0, alpha_max] finds the first run that is
/// not stable, and bisection between it and the last stable grid point finds the transition.
/// A run that is not stable is unstable (a growing run or a limit cycle not accepted by
/// `stable_when`) or inconclusive (separated from a unilateral wall, or undecided): no
/// evidence either way, so nothing beyond it counts as stable, and the point reports it. β
/// values and grid runs are simulated in parallel (rayon). Assumes the stable set along α
/// starts near 0; the point reports the first transition.
pub fn empirical_boundary(search: &BoundarySearch) -> Result<Vec<EmpiricalPoint>> {
    search.template.validate()?;
    if search.grid < 2 {
        return Err(Error::OutOfRange {
            param: Param::Grid,
            value: search.grid as f64,
            range: "[2, inf)",
        });
    }
    if !(search.rel_tolerance >= MIN_REL_TOLERANCE && search.rel_tolerance < 1.0) {
        return Err(Error::OutOfRange {
            param: Param::RelTolerance,
            value: search.rel_tolerance,
            range: "[1e-6, 1)",
        });
    }
    if let StableWhen::AmplitudeBelow(a) = search.stable_when {
        positive(Param::AmplitudeThreshold, a)?;
    }
    for &b in &search.dampings {
        finite(Param::Beta, b)?;
    }
    search
        .dampings
        .par_iter()
        .map(|&b| boundary_at(search, b))
        .collect()
}
