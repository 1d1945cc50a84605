//! The answer about one wall of the explorer's plane (`/api/point`): the verdict with the
//! spectral radius and the roots of p(z) (Section V), the paper's linear condition (eq. 19,
//! 23) for the paper's loop, and the margins beside the verdict and the passivity of the wall
//! (Colgate–Schenkel; eq. 28), the same numbers as `hapstab check --json` and
//! `hapstab passivity --json` give for the same loop and wall.

use serde::Serialize;

use crate::error::Result;
use crate::margins::margins_beside_verdict;
use crate::margins::report::MarginsReport;
use crate::model::Loop;
use crate::paper::Normalized;
use crate::paper::linear::{LinearCheck, linear_check};
use crate::params::Wall;
use crate::passivity::{Passivity, passivity};
use crate::system::System;

/// One wall of a loop, judged and measured.
#[derive(Debug, Clone, Serialize)]
pub struct WallAnswer {
    /// The point in Table I (α, β, γ, δ, d) for a loop with the paper's normalized view; None
    /// for a loop beyond the paper's (it is under `loop`, its wall under `wall`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub params: Option<Normalized>,
    /// A loop beyond the paper's (None for the paper's loop, whose `params` say it all).
    #[serde(rename = "loop", skip_serializing_if = "Option::is_none")]
    pub lp: Option<Loop>,
    /// The wall in N/m and Ns/m (None for a loop given in normalized units).
    pub wall: Option<Wall>,
    /// "stable", "marginal" or "unstable" ([`crate::verdict::decide`]).
    pub verdict: &'static str,
    /// True iff the verdict is stable.
    pub stable: bool,
    /// Largest root modulus of p(z).
    pub spectral_radius: f64,
    /// Roots of p(z) as [re, im], largest modulus first.
    pub roots: Vec<[f64; 2]>,
    /// The linear conditions (19) and (23) of the paper's loop (None for other loops).
    pub linear: Option<LinearCheck>,
    /// Passive for the device's own damping (towards any passive operator); None where the
    /// condition does not apply (see `passivity`).
    pub passive: Option<bool>,
    /// Passive by eq. (28) with the arm's damping counted (towards this operator only); None
    /// without an arm.
    pub passive_with_arm: Option<bool>,
    /// Every margin of the wall, as `hapstab check --json` gives them (withheld with a note
    /// beside a verdict that is not stable).
    pub margins: MarginsReport,
    /// The passivity of the wall, as `hapstab passivity --json` gives it.
    pub passivity: Passivity,
}

/// The answer for the wall at `units` (the family's wall units, [`System::wall_units`]) and
/// `wall` (the same wall in the loop's units: N/m and Ns/m, α and β for a normalized loop):
/// [`System::analysis`] for the verdict and the roots, [`linear_check`] at `params` (the
/// point in Table I, given for a loop with the paper's view, [`Loop::paper_view`]),
/// [`margins_beside_verdict`] and [`passivity`]. `normalized` says whether the loop was
/// given in normalized units (then `wall` is not echoed).
pub fn wall_answer(
    sys: &System,
    params: Option<Normalized>,
    normalized: bool,
    units: (f64, f64),
    wall: Wall,
) -> Result<WallAnswer> {
    let a = sys.analysis(units)?;
    let lp = sys.lp();
    let paper = lp.paper_view().is_some();
    let params = params.filter(|_| paper);
    let margins = margins_beside_verdict(lp, wall, a.stable())?;
    let passivity = passivity(lp, wall)?;
    Ok(WallAnswer {
        params,
        lp: (!paper).then(|| lp.clone()),
        wall: (!normalized).then_some(wall),
        verdict: a.verdict.as_str(),
        stable: a.stable(),
        spectral_radius: a.spectral_radius,
        roots: a.roots.iter().map(|z| [z.re, z.im]).collect(),
        linear: params.as_ref().map(linear_check),
        passive: passivity.verdict.meets(),
        passive_with_arm: passivity.with_arm.and_then(|w| w.verdict.meets()),
        margins: MarginsReport::from(&margins),
        passivity,
    })
}
