//! `margins`: how far a stable wall is from the stability boundary of Section V, through the
//! library calls of the command line's `hapstab check` (the same verdict, then
//! `hapstab::margins::margins_beside_verdict`): no margin for a wall that is not stable.

use hapstab::loop_analysis::{analysis, wall_units};
use hapstab::margins::{CrossingKind, Margins, margins_beside_verdict};
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

/// The library's margins as the Python object.
pub(crate) fn margins_object(m: Margins) -> PyMargins {
    PyMargins {
        stable: m.stable,
        gain_margin: m.gain.map(|g| g.factor),
        gain_margin_lower: m.gain_lower.map(|g| g.factor),
        phase_crossover_hz: m.gain.map(|g| g.frequency_hz),
        stiffness_margin: m.stiffness.map(|g| g.factor),
        stiffness_margin_lower: m.stiffness_lower.map(|g| g.factor),
        stiffness_crossover_hz: m.stiffness.map(|g| g.frequency_hz),
        phase_margin_deg: m.phase.map(|p| p.degrees),
        gain_crossover_hz: m.phase.map(|p| p.frequency_hz),
        delay_margin: m.delay.map(|d| d.seconds),
        delay_margin_frequency_hz: m.delay.map(|d| d.frequency_hz),
        delay_margin_pm_over_wc: m.delay_pm_over_wc,
        delay_margin_at_least: m.delay_at_least,
        stability_margin: m.stability_margin.map(|s| s.value),
        stability_margin_hz: m.stability_margin.map(|s| s.frequency_hz),
        peak_gain: m.peak_gain.map(|p| p.0),
        peak_gain_hz: m.peak_gain.map(|p| p.1),
        crossings: m
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
        notes: m.notes,
    }
}

/// Stability margins of the virtual wall on this loop, all on the exact discrete loop
/// (Section V), so they hold for the sampled system, named as python-control's
/// `stability_margins` and MATLAB's `allmargin` name them (the open loop is
/// L = (K·PK + B·PB)/P0, the characteristic equation p(z) = 0 of eq. 9 being 1 + L = 0):
///
/// - gain_margin / gain_margin_lower: the factors on (K, B) together that reach the boundary
///   upward and downward (python-control's `gm` is the first), read at phase_crossover_hz;
/// - stiffness_margin / stiffness_margin_lower: the same on K alone at the given B;
/// - phase_margin_deg at gain_crossover_hz (|L| = 1), the smallest in magnitude over every
///   crossover (no crossover is lost: the frequency grid resolves every mode);
/// - delay_margin: the exact extra delay in s (any fraction of a sample, discretized exactly)
///   at which a root reaches the unit circle, and delay_margin_pm_over_wc, MATLAB's PM/ω_c;
/// - stability_margin: min |1 + L| (python-control's `sm`); peak_gain: max |L|;
/// - crossings: every gain and phase crossover.
///
/// Margins are defined for stable walls: when the wall is not stable (the verdict of `check`)
/// every margin is None and `notes` says so; an unbounded margin is None with a note too.
/// The wall is K in N/m and B in Ns/m, or α = KT²/m, β = BT/m (as in `check`). The GIL is
/// released while the margins are computed.
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
    let fam = r#loop.family()?;
    let args = WallArgs {
        stiffness: wall_stiffness,
        damping: wall_damping,
        alpha,
        beta,
    };
    let w = args.resolve(r#loop, &fam)?;
    let core = hapstab::limits::core_degree(&fam);
    let cost = hapstab::limits::margins_cost(fam.degree(), core);
    crate::budget::check_loop(cost, lp, &fam, "the margins")?;
    let units = wall_units(lp, &fam, w).py()?;
    let verdict_stable = analysis(lp, &fam, units).py()?.stable();
    let m = py
        .detach(|| margins_beside_verdict(lp, w, verdict_stable))
        .py()?;
    Ok(margins_object(m))
}
