//! `margins`: how far a stable wall is from the stability boundary of Section V, through the
//! library calls of the command line's `hapstab check` (the same verdict, then
//! `hapstab::margins::margins_beside_verdict`): no margin for a wall that is not stable.

use hapstab::margins::report::MarginsReport;
use hapstab::margins::{CrossingKind, margins_beside_verdict};
use pyo3::prelude::*;

use crate::errors::Context;
use crate::loops::PyLoop;
use crate::text::num;
use crate::wall::WallArgs;

/// The result of `margins`, named as python-control's `stability_margins` and MATLAB's
/// `allmargin` name them. Every margin is None when the wall is not stable or the margin is
/// unbounded; `notes` says which and why.
#[pyclass(frozen, get_all, module = "hapstab", name = "Margins")]
pub struct PyMargins {
    /// The wall's stability verdict (as `check`).
    pub stable: bool,
    /// Factor g > 1 on K and B together with (gK, gB) on the stability boundary: the loop's
    /// gain margin (python-control's `gm`; L = (K·PK + B·PB)/P0 scales with the wall).
    pub gain_margin: Option<f64>,
    /// Factor g < 1 on K and B together that reaches the boundary downward.
    pub gain_margin_lower: Option<f64>,
    /// Phase crossover (L real and negative) where the gain margin is read, Hz.
    pub phase_crossover_hz: Option<f64>,
    /// Factor > 1 on K alone at the given B (the end of the exact stable K interval).
    pub stiffness_margin: Option<f64>,
    /// Factor < 1 on K alone at the given B.
    pub stiffness_margin_lower: Option<f64>,
    /// Frequency of the root pair on the unit circle at K × stiffness_margin, Hz.
    pub stiffness_crossover_hz: Option<f64>,
    /// Phase margin in degrees, 180° + arg L at a gain crossover |L| = 1: the smallest in
    /// magnitude over the crossovers (all are in `crossings`).
    pub phase_margin_deg: Option<f64>,
    /// Gain crossover (|L| = 1) where the phase margin is read, Hz.
    pub gain_crossover_hz: Option<f64>,
    /// The exact extra delay in s (any fraction of a sample) at which a root reaches the unit
    /// circle.
    pub delay_margin: Option<f64>,
    /// Frequency of the oscillation at the delay margin, Hz.
    pub delay_margin_frequency_hz: Option<f64>,
    /// min PM/ω_c over the gain crossovers, s (MATLAB's figure for a pure delay).
    pub delay_margin_pm_over_wc: Option<f64>,
    /// When the delay scan stopped at its work bound without a crossing: the extra delay in s
    /// up to which the loop was shown stable (the delay margin is at least this).
    pub delay_margin_at_least: Option<f64>,
    /// min |1 + L| over frequency (python-control's `sm`).
    pub stability_margin: Option<f64>,
    /// Where min |1 + L| is reached, Hz.
    pub stability_margin_hz: Option<f64>,
    /// max |L| over frequency.
    pub peak_gain: Option<f64>,
    /// Where max |L| is reached, Hz.
    pub peak_gain_hz: Option<f64>,
    /// Every crossing as (kind, frequency in Hz, value): kind "gain" (|L| = 1, value the phase
    /// margin in degrees) or "phase" (L real, value the factor on (K, B) that puts a root on
    /// the unit circle there).
    pub crossings: Vec<(String, f64, f64)>,
    /// Why a margin is None, in words.
    pub notes: Vec<String>,
}

#[pymethods]
impl PyMargins {
    fn __repr__(&self) -> String {
        let opt = |x: Option<f64>| x.map_or("None".into(), num);
        format!(
            "Margins(stable={}, gain_margin={}, gain_margin_lower={}, stiffness_margin={}, phase_margin_deg={}, delay_margin={}, stability_margin={})",
            if self.stable { "True" } else { "False" },
            opt(self.gain_margin),
            opt(self.gain_margin_lower),
            opt(self.stiffness_margin),
            opt(self.phase_margin_deg),
            opt(self.delay_margin),
            opt(self.stability_margin)
        )
    }
}

/// The Python object of the margins: the report every front end gives
/// ([`MarginsReport`], `hapstab check --json`'s keys) beside the wall's verdict, crossings
/// as (kind, Hz, value).
pub(crate) fn margins_object(stable: bool, r: MarginsReport) -> PyMargins {
    PyMargins {
        stable,
        gain_margin: r.gain_margin,
        gain_margin_lower: r.gain_margin_lower,
        phase_crossover_hz: r.phase_crossover_hz,
        stiffness_margin: r.stiffness_margin,
        stiffness_margin_lower: r.stiffness_margin_lower,
        stiffness_crossover_hz: r.stiffness_crossover_hz,
        phase_margin_deg: r.phase_margin_deg,
        gain_crossover_hz: r.gain_crossover_hz,
        delay_margin: r.delay_margin,
        delay_margin_frequency_hz: r.delay_margin_frequency_hz,
        delay_margin_pm_over_wc: r.delay_margin_pm_over_wc,
        delay_margin_at_least: r.delay_margin_at_least,
        stability_margin: r.stability_margin,
        stability_margin_hz: r.stability_margin_hz,
        peak_gain: r.peak_gain,
        peak_gain_hz: r.peak_gain_hz,
        crossings: r
            .crossings
            .iter()
            .map(|c| {
                let kind = match c.kind {
                    CrossingKind::Gain => "gain",
                    CrossingKind::Phase => "phase",
                };
                (kind.to_string(), c.frequency_hz, c.value)
            })
            .collect(),
        notes: r.margin_notes,
    }
}

#[pyfunction]
#[pyo3(signature = (r#loop, wall_stiffness = None, wall_damping = None, *, alpha = None,
                    beta = None))]
pub fn margins(
    r#loop: &PyLoop,
    wall_stiffness: Option<f64>,
    wall_damping: Option<f64>,
    alpha: Option<f64>,
    beta: Option<f64>,
    py: Python<'_>,
) -> PyResult<PyMargins> {
    let lp = &r#loop.lp;
    let (sys, w) = WallArgs::system_and_wall(r#loop, wall_stiffness, wall_damping, alpha, beta)?;
    let fam = sys.family();
    let core = hapstab::limits::core_degree(fam);
    let cost = hapstab::limits::margins_cost(fam.degree(), core);
    crate::budget::check_loop(cost, lp, fam, "the margins")?;
    let verdict_stable = sys.decide(sys.wall_units(w).py()?).verdict == hapstab::Verdict::Stable;
    let m = py
        .detach(|| margins_beside_verdict(lp, w, verdict_stable))
        .py()?;
    Ok(margins_object(m.stable, MarginsReport::from(&m)))
}
