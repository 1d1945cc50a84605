//! The figure of one run: position and wall force over time with the judged window, and a
//! zoom on the last periods of a limit cycle. A decaying run's position and force show its
//! transient (until it has settled), and a third panel its distance from rest on a log
//! scale over the whole run, with the judged window.
//!
//! The panels themselves are drawn in [`super::run_plot_panels`].

use hapstab::simulation::{
    ClippedTrace, Config, Outcome, RunResult, SETTLING_BAND, SimModel, Trace,
};
use hapstab_plot::Grid;

use super::Units;
use super::run_args::RunSettings;
use super::run_plot_panels::Panels;
use super::run_text::outcome_summary;
use crate::output::{eng, sig};

/// Points per plotted curve (min-max decimated).
pub(super) const PLOT_BUCKETS: usize = 2_000;

/// A one-line caption of the simulated loop: (α, β, γ, δ, d) for the paper's loop, the wall
/// and the delay otherwise.
pub(super) fn model_caption(m: &SimModel, units: Units) -> String {
    match m {
        SimModel::Paper(m) if units.physical => {
            let (k, b, mass) = (m.params.alpha, m.params.beta, m.mass);
            let t = m.period;
            format!(
                "K = {}, B = {}, m = {}, d = {}",
                eng(k * mass / (t * t), "N/m", 6),
                eng(b * mass / t, "Ns/m", 6),
                eng(mass, "kg", 6),
                m.params.d
            )
        }
        SimModel::Paper(m) => {
            let p = m.params;
            format!(
                "α = {}, β = {}, γ = {}, δ = {}, d = {}",
                sig(p.alpha, 6),
                sig(p.beta, 6),
                sig(p.gamma, 6),
                sig(p.delta, 6),
                p.d
            )
        }
        SimModel::Loop(l) => format!(
            "K = {}, B = {}, t_d = {}",
            eng(l.wall.stiffness, "N/m", 6),
            eng(l.wall.damping, "Ns/m", 6),
            eng(l.lp.delay_time(), "s", 6)
        ),
    }
}

/// A unit prefix for values up to `max_abs` in base unit `unit`: (factor, label).
pub(super) fn scaled_unit(max_abs: f64, unit: &str) -> (f64, String) {
    if unit != "m" && unit != "N" {
        return (1.0, unit.to_string());
    }
    let (f, p) = if !(max_abs.is_finite() && max_abs > 0.0) || max_abs >= 1.0 {
        (1.0, "")
    } else if max_abs >= 1e-3 {
        (1e3, "m")
    } else if max_abs >= 1e-6 {
        (1e6, "µ")
    } else {
        (1e9, "n")
    };
    (f, format!("{p}{unit}"))
}

/// The end of a decaying run's transient as the zoomed panel shows it: 1.3 times the 2 %
/// settling time ([`Trace::settling_time`]), at least 50 samples, at most the run.
pub(super) fn transient_end(tr: &Trace, period: f64, t_end: f64) -> f64 {
    (1.3 * tr.settling_time(SETTLING_BAND))
        .max(50.0 * period)
        .min(t_end)
}

/// The largest magnitude in `v` (0 for none).
pub(super) fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// (min, max) of the values.
pub(super) fn extent<'a>(v: impl IntoIterator<Item = &'a f64>) -> (f64, f64) {
    v.into_iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        })
}

/// The title's note on a clipped trace: where it was cut and why.
pub(super) fn clip_note(c: &ClippedTrace, units: Units, period: f64) -> String {
    let at = if units.physical {
        eng(c.clip.time, "s", 4)
    } else {
        format!("{} samples", sig(c.clip.time / period, 6))
    };
    format!(
        "unstable: clipped at t = {at}, |x| > {}",
        eng(c.clip.threshold, "m", 4)
    )
}

/// The figure of one run: position (with the judged window) and wall force over time, and
/// for a limit cycle a zoom on its last periods. A growing run's trace `clipped` before it
/// leaves the scale of its start ([`hapstab::simulation::clip_growing_trace`]) is plotted
/// instead of the whole `tr`, and the title says where it was cut.
pub(super) fn trace_plot(
    tr: &Trace,
    clipped: Option<&ClippedTrace>,
    r: &RunResult,
    cfg: &Config,
    s: &RunSettings,
    units: Units,
) -> Grid {
    let mut verdict = outcome_summary(r, units);
    let tr = clipped.map_or(tr, |c| &c.trace);
    let t_end = clipped
        .map(|c| c.clip.time)
        .or_else(|| tr.time.last().copied())
        .unwrap_or(1.0)
        .max(cfg.model.period());
    let note = clipped.map(|c| clip_note(c, units, cfg.model.period()));
    if clipped.is_some() {
        verdict.push_str(", trace clipped");
    }
    let decaying = r.verdict.outcome == Outcome::Decaying;
    let t_show = match decaying {
        true => transient_end(tr, cfg.model.period(), t_end),
        false => t_end,
    };
    let unit = units.time();
    let tlabel = match t_show < t_end {
        true => format!(
            "time t ({unit}): the transient, first {} {unit} of the {} {unit} run",
            sig(t_show, 3),
            sig(t_end, 3)
        ),
        false => format!("time t ({unit})"),
    };
    let panels = Panels {
        tr,
        cfg,
        t_end,
        t_show,
        tlabel,
    };
    let mut g = Grid::new(format!("Simulation: {verdict}"), 1).panel_size(1000, 520);
    g.push(panels.position(r, model_caption(&cfg.model, units), note));
    g.push(panels.force(s, units));
    if t_show < t_end {
        g.push(panels.envelope(r, units));
    }
    if r.verdict.outcome == Outcome::LimitCycle && tr.time.len() > 16 {
        g.push(panels.limit_cycle(r));
    }
    g
}
