//! The answer of a check of one wall, as `hapstab check --json` writes it and the Python
//! package's `check` reads it: the verdict with the spectral radius and the roots of p(z)
//! (Section V), the stable stiffness interval at the wall's damping, the paper's normalized
//! view with the linear condition (eq. 22–23) for the paper's loop, and the margins beside
//! the verdict (none for a wall that is not stable, with the reason).

use num_complex::Complex64;
use serde::Serialize;

use crate::boundary::Interval;
use crate::error::Result;
use crate::loop_spec::LoopInput;
use crate::margins::margins_beside_verdict;
use crate::margins::report::MarginsReport;
use crate::paper::Normalized;
use crate::params::Wall;
use crate::system::{System, pick_interval};

/// The paper's normalized view of a checked wall (Table I) with the linear condition.
#[derive(Debug, Clone, Serialize)]
pub struct CheckPaperView {
    /// The point in normalized units (in both modes; not serialized: see `normalized`).
    #[serde(skip)]
    pub point: Normalized,
    /// The same point in the output, for a loop given in physical units only (in normalized
    /// mode it is the input).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub normalized: Option<Normalized>,
    /// Stable α interval at the given β that contains α, or the one reaching furthest.
    pub alpha_interval: Option<[f64; 2]>,
    /// Linear condition (23): α < (β + δ)/(d + 1/2).
    pub alpha_linear: f64,
    /// Linear condition (22) in N/m: K < (b + B)/(t_d + T/2) (physical loops).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub k_linear: Option<f64>,
}

/// The check of one wall on a loop, its inputs echoed.
#[derive(Debug, Clone, Serialize)]
pub struct CheckAnswer {
    /// The loop and the wall (the form a loop file takes).
    pub input: LoopInput,
    /// True iff the verdict is stable.
    pub stable: bool,
    /// "stable", "marginal" or "unstable" ([`crate::verdict::decide`]).
    pub verdict: &'static str,
    /// Largest root modulus of p(z).
    pub spectral_radius: f64,
    /// The roots of p(z), largest modulus first.
    pub roots: Vec<Complex64>,
    /// Stable K interval in N/m at the given B (physical loops): the one containing K, or
    /// the one reaching furthest; null when no K is stable at that B.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub k_interval: Option<Option<[f64; 2]>>,
    /// The paper's loop: its normalized view.
    #[serde(flatten)]
    pub paper: Option<CheckPaperView>,
    /// The margins beside the verdict.
    #[serde(flatten)]
    pub margins: MarginsReport,
}

/// The check of the wall `w` (in the loop's units: N/m and Ns/m, α and β for a normalized
/// loop) on a loop: [`System::analysis`] for the verdict and the roots, the stable interval
/// at the wall's damping ([`System::stable_intervals`], the one holding K or else the one
/// reaching furthest), the paper's view and the margins ([`margins_beside_verdict`]);
/// `normalized` says whether the loop is the paper's normalized one (m = T = 1).
pub fn check_answer(sys: &System, normalized: bool, w: Wall) -> Result<CheckAnswer> {
    let units = sys.wall_units(w)?;
    let analysis = sys.analysis(units)?;
    let interval = pick_interval(&sys.stable_intervals(units.1), units.0);
    let fam = sys.family();
    let k_interval = (!normalized)
        .then(|| interval.map(|iv| [fam.to_physical(iv.lo, 0.0).0, fam.to_physical(iv.hi, 0.0).0]));
    let margins = margins_beside_verdict(sys.lp(), w, analysis.stable())?;
    Ok(CheckAnswer {
        input: LoopInput::new(sys.lp(), normalized, Some(w)),
        stable: analysis.stable(),
        verdict: analysis.verdict.as_str(),
        spectral_radius: analysis.spectral_radius,
        paper: paper_view(sys, normalized, w, units, interval)?,
        roots: analysis.roots,
        k_interval,
        margins: MarginsReport::from(&margins),
    })
}

/// The paper's normalized view of the wall at `(alpha, beta)` (its wall units) with the
/// stable α interval there; None beyond the paper's loop.
fn paper_view(
    sys: &System,
    normalized: bool,
    w: Wall,
    (alpha, beta): (f64, f64),
    interval: Option<Interval>,
) -> Result<Option<CheckPaperView>> {
    let lp = sys.lp();
    let Some(pp) = lp.paper_view() else {
        return Ok(None);
    };
    let d = lp.delay.samples;
    let point = Normalized::new(alpha, beta, pp.gamma, pp.delta, d)?;
    Ok(Some(CheckPaperView {
        point,
        normalized: (!normalized).then_some(point),
        alpha_interval: interval.map(|iv| [iv.lo, iv.hi]),
        alpha_linear: crate::paper::linear::linear_alpha_limit(beta, pp.delta, d),
        k_linear: if normalized {
            None
        } else {
            sys.linear_k(w.damping)
        },
    }))
}
