//! The margins as every front end reports them (`hapstab check --json`, the explorer's
//! `/api/point`, the Python package's `Margins`): one flat record named as MATLAB's
//! `allmargin` and python-control's `stability_margins` name them.

use serde::Serialize;

use super::{CrossingKind, Margins};

/// The wall's stability margins in the conventions of MATLAB's `allmargin` and
/// python-control's `stability_margins` (null when the wall is not stable or a margin is
/// unbounded; `margin_notes` says which).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MarginsReport {
    /// Factor > 1 on K and B together (the loop's gain margin, python-control's `gm`).
    pub gain_margin: Option<f64>,
    /// Factor < 1 on K and B together that reaches the boundary.
    pub gain_margin_lower: Option<f64>,
    /// Phase crossover (L real, negative) where the gain margin is read, Hz.
    pub phase_crossover_hz: Option<f64>,
    /// Factor > 1 on K alone at the given B.
    pub stiffness_margin: Option<f64>,
    /// Factor < 1 on K alone at the given B.
    pub stiffness_margin_lower: Option<f64>,
    /// Frequency of the root pair on the unit circle at K × stiffness margin, Hz.
    pub stiffness_crossover_hz: Option<f64>,
    /// Phase margin in degrees (the smallest in magnitude over the gain crossovers).
    pub phase_margin_deg: Option<f64>,
    /// Gain crossover (|L| = 1) where the phase margin is read, Hz.
    pub gain_crossover_hz: Option<f64>,
    /// Exact extra delay that the loop tolerates, s.
    pub delay_margin: Option<f64>,
    /// Frequency of the oscillation at the delay margin, Hz.
    pub delay_margin_frequency_hz: Option<f64>,
    /// min PM/ω_c over the gain crossovers, s (MATLAB's figure for a pure delay).
    pub delay_margin_pm_over_wc: Option<f64>,
    /// When the delay scan stopped at its work bound: the extra delay, s, up to which the loop
    /// was shown stable (the delay margin is at least this).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub delay_margin_at_least: Option<f64>,
    /// min |1 + L| (python-control's `sm`).
    pub stability_margin: Option<f64>,
    /// Where min |1 + L| is reached, Hz.
    pub stability_margin_hz: Option<f64>,
    /// max |L| over frequency.
    pub peak_gain: Option<f64>,
    /// Where max |L| is reached, Hz.
    pub peak_gain_hz: Option<f64>,
    /// Every gain and phase crossover (kind, frequency, value).
    pub crossings: Vec<CrossingReport>,
    /// Why a margin is null.
    pub margin_notes: Vec<String>,
}

/// One crossing of the open loop.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CrossingReport {
    /// "gain" (|L| = 1; value: phase margin in degrees) or "phase" (L real; value: the factor
    /// on (K, B) that puts a root on the unit circle there).
    pub kind: CrossingKind,
    /// Where, Hz.
    pub frequency_hz: f64,
    /// The phase margin in degrees (gain crossover) or the factor on (K, B) (phase crossover).
    pub value: f64,
}

impl From<&Margins> for MarginsReport {
    /// The report of the margins (see [`super::margins`]).
    fn from(m: &Margins) -> Self {
        MarginsReport {
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
                .map(|c| CrossingReport {
                    kind: c.kind,
                    frequency_hz: c.frequency_hz,
                    value: c.value,
                })
                .collect(),
            margin_notes: m.notes.clone(),
        }
    }
}
