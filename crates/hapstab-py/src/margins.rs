//! `margins`: how far a stable wall is from the stability boundary of Section V, through the
//! library calls of the command line's `hapstab check` (the same verdict, then
//! `hapstab::margins::margins_beside_verdict`): no margin for a wall that is not stable.

use hapstab::loop_analysis::{analysis, wall_units};
use hapstab::margins::{Margins, margins_beside_verdict};
use pyo3::prelude::*;

use crate::errors::Context;
use crate::loops::PyLoop;
use crate::text::num;
use crate::wall::WallArgs;

/// The result of `margins`. Every margin is None when the wall is not stable or the margin
/// is unbounded; `notes` says which and why.
#[pyclass(frozen, get_all, module = "hapstab", name = "Margins")]
pub struct PyMargins {
    /// The wall's stability verdict (Schur–Cohn, as `check`).
    pub stable: bool,
    /// The factor g on K at the given B that puts (gK, B) on the stability boundary: the end
    /// of the exact stable K interval away from K = 0, divided by K.
    pub gain_margin: Option<f64>,
    /// The factor on K and B together (along the ray through the wall).
    pub gain_margin_kb: Option<f64>,
    /// Phase margin in degrees: 180° + arg L(e^{jωT}) at the gain crossover |L| = 1 of the
    /// open loop L = (K·PK + B·PB)/P0 (characteristic equation 1 + L = 0, eq. 7–9).
    pub phase_margin_deg: Option<f64>,
    /// The gain-crossover frequency of the phase margin, Hz.
    pub phase_crossover_hz: Option<f64>,
    /// The extra delay in s (fractional, discretized exactly) that brings the loop to the
    /// boundary.
    pub delay_margin: Option<f64>,
    /// Frequency of the oscillation at the delay margin, Hz.
    pub delay_margin_frequency_hz: Option<f64>,
    /// When the delay scan stopped at its work bound without a crossing: the extra delay in s
    /// up to which the loop was shown stable (the delay margin is at least this).
    pub delay_margin_at_least: Option<f64>,
    /// Frequency θ/(2πT) of the critical root pair e^{±jθ} on the unit circle at K × gain
    /// margin, Hz.
    pub critical_frequency_hz: Option<f64>,
    /// Why a margin is None, in words.
    pub notes: Vec<String>,
}

#[pymethods]
impl PyMargins {
    fn __repr__(&self) -> String {
        let opt = |x: Option<f64>| x.map_or("None".into(), num);
        format!(
            "Margins(stable={}, gain_margin={}, gain_margin_kb={}, phase_margin_deg={}, delay_margin={}, critical_frequency_hz={})",
            if self.stable { "True" } else { "False" },
            opt(self.gain_margin),
            opt(self.gain_margin_kb),
            opt(self.phase_margin_deg),
            opt(self.delay_margin),
            opt(self.critical_frequency_hz)
        )
    }
}

fn margins_object(m: Margins) -> PyMargins {
    PyMargins {
        stable: m.stable,
        gain_margin: m.gain.map(|g| g.factor),
        gain_margin_kb: m.gain_kb.map(|g| g.factor),
        phase_margin_deg: m.phase.map(|p| p.degrees),
        phase_crossover_hz: m.phase.map(|p| p.frequency_hz),
        delay_margin: m.delay.map(|d| d.seconds),
        delay_margin_frequency_hz: m.delay.map(|d| d.frequency_hz),
        delay_margin_at_least: m.delay_at_least,
        critical_frequency_hz: m.critical_frequency_hz,
        notes: m.notes,
    }
}

/// Stability margins of the virtual wall on this loop, all on the exact discrete loop
/// (Section V), so they hold for the sampled system:
///
/// - gain_margin: the factor g on K at the given B with (gK, B) on the stability boundary,
///   from the D-decomposition crossings of the stiffness axis; gain_margin_kb: the factor on
///   (K, B) together;
/// - phase_margin_deg: 180° + arg L at the gain crossover |L(e^{jωT})| = 1 of the open loop
///   L = (K·PK + B·PB)/P0, the loop's characteristic equation p(z) = 0 (eq. 9) being 1 + L = 0;
/// - delay_margin: the extra delay in s (fractional: discretized exactly with the modified
///   z-transform) at which the loop first becomes unstable, by a scan over the added delay
///   with the Schur–Cohn test;
/// - critical_frequency_hz: the angle θ of the root pair e^{±jθ} on the unit circle at the
///   gain-margin boundary, f = θ/(2πT).
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
