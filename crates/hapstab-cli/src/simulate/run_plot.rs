//! The figure of one run: position and wall force over time with the judged window, and a
//! zoom on the last periods of a limit cycle. A decaying run's position and force show its
//! transient (until it has settled), and a third panel its distance from rest on a log
//! scale over the whole run, with the judged window.

use hapstab::simulation::{ClippedTrace, Config, Contact, Outcome, RunResult, SimModel, Trace};

use super::run_args::RunSettings;
use super::run_text::outcome_summary;
use super::{Units, describe_effects};
use crate::output::{eng, sig};
use hapstab_plot::{Figure, Grid, Legend, Series, palette};

/// Points per plotted curve (min-max decimated).
const PLOT_BUCKETS: usize = 2_000;

/// A one-line caption of the simulated loop: (α, β, γ, δ, d) for the paper's loop, the wall
/// and the delay otherwise.
fn model_caption(m: &SimModel, units: Units) -> String {
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
fn scaled_unit(max_abs: f64, unit: &str) -> (f64, String) {
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

/// What every panel of a run's figure shares: the trace, its end time, the end of the
/// shown transient and the time axis label.
struct Panels<'a> {
    tr: &'a Trace,
    cfg: &'a Config,
    t_end: f64,
    t_show: f64,
    tlabel: String,
}

/// The position the run settles at: 0, or the last position when that is not within 10⁻⁶
/// of the peak of 0 (a push against the wall).
fn rest(x: &[f64]) -> f64 {
    let last = x.last().copied().unwrap_or(0.0);
    if last.abs() <= 1e-6 * max_abs(x) {
        0.0
    } else {
        last
    }
}

/// The end of a decaying run's transient: 1.3 times the last time its distance from rest
/// exceeds 2 % of the largest, at least 50 samples, at most the run.
fn transient_end(tr: &Trace, period: f64, t_end: f64) -> f64 {
    let x0 = rest(&tr.position);
    let peak = tr
        .position
        .iter()
        .fold(0.0f64, |m, x| m.max((x - x0).abs()));
    let last = tr
        .time
        .iter()
        .zip(&tr.position)
        .filter(|(_, x)| (**x - x0).abs() > 0.02 * peak)
        .map(|(t, _)| *t)
        .fold(0.0, f64::max);
    (1.3 * last).max(50.0 * period).min(t_end)
}

/// The largest magnitude in `v` (0 for none).
fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// (min, max) of the values.
fn extent<'a>(v: impl IntoIterator<Item = &'a f64>) -> (f64, f64) {
    v.into_iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        })
}

impl Panels<'_> {
    /// The samples of `v` from time `from` on, scaled, min-max decimated for plotting.
    fn series(&self, v: &[f64], scale: f64, from: f64) -> Vec<(f64, f64)> {
        let pts: Vec<(f64, f64)> = self
            .tr
            .time
            .iter()
            .zip(v)
            .filter(|(t, _)| **t >= from)
            .map(|(&t, &y)| (t, y * scale))
            .collect();
        hapstab_plot::decimate_minmax(&pts, PLOT_BUCKETS)
    }

    /// Position over time with the judged window shaded and the wall surface where it is not
    /// the bilateral contact at 0; a clipped trace ends at a dashed line labelled `clip_note`.
    fn position(&self, r: &RunResult, params: String, clip_note: Option<String>) -> Figure {
        let (tr, cfg) = (self.tr, self.cfg);
        let xw = cfg.effects.wall_position;
        let (xs, xunit) = scaled_unit(max_abs(&tr.position).max(xw.abs()), "m");
        let mut pos = Figure::new(params)
            .x_label(&self.tlabel)
            .y_label(format!("position x ({xunit})"))
            .x_range(0.0, self.t_show)
            .legend(Legend::Below);
        let (lo, hi) = extent(tr.position.iter().chain([&xw]));
        if let Some(note) = clip_note {
            let (lo, hi) = (lo * xs, hi * xs);
            pos.add(
                Series::dashed([(self.t_end, lo), (self.t_end, hi)])
                    .color(palette::VERMILLION)
                    .width(2)
                    .label(note),
            );
        }
        // within the plotted time (a clipped trace may end before the judged window)
        let (j0, j1) = (
            (r.verdict.judged_from_sample as f64 * cfg.model.period()).min(self.t_end),
            (r.verdict.judged_to_sample as f64 * cfg.model.period()).min(self.t_end),
        );
        if hi > lo {
            let (lo, hi) = (lo * xs, hi * xs);
            pos.add(
                Series::polygon([(j0, lo), (j1, lo), (j1, hi), (j0, hi)])
                    .color(palette::GREY)
                    .alpha(0.15)
                    .no_outline()
                    .label("judged window"),
            );
        }
        pos.add(
            Series::line(self.series(&tr.position, xs, 0.0))
                .color(palette::BLUE)
                .width(2)
                .label("position x"),
        );
        if cfg.effects.contact != Contact::Bilateral || xw != 0.0 {
            pos.add(
                Series::dashed([(0.0, xw * xs), (self.t_end, xw * xs)])
                    .color(palette::GREY)
                    .width(2)
                    .label("wall surface x_w"),
            );
        }
        pos
    }

    /// The wall force over time, with the saturation limits and the human's push.
    fn force(&self, s: &RunSettings, units: Units) -> Figure {
        let (tr, t_end) = (self.tr, self.t_end);
        let fu = if units.physical { "N" } else { "" };
        let (fs, funit) = scaled_unit(max_abs(&tr.wall_force), fu);
        let flabel = if units.physical {
            format!("wall force F ({funit})")
        } else {
            "wall force T²F/m".to_string()
        };
        let effects = describe_effects(s, units.force());
        let effects = effects
            .strip_prefix("none: ")
            .unwrap_or(&effects)
            .to_string();
        let mut force = Figure::new(effects)
            .x_label(&self.tlabel)
            .y_label(flabel)
            .x_range(0.0, self.t_show)
            .legend(Legend::Below);
        force.add(
            Series::line(self.series(&tr.wall_force, fs, 0.0))
                .color(palette::VERMILLION)
                .width(2)
                .label("wall force F"),
        );
        if let Some(fmax) = self.cfg.effects.saturation {
            let (hi, lo) = (fmax * fs, -fmax * fs);
            force.add(
                Series::dashed([
                    (0.0, hi),
                    (t_end, hi),
                    (f64::NAN, 0.0),
                    (0.0, lo),
                    (t_end, lo),
                ])
                .color(palette::GREY)
                .width(2)
                .label("saturation ±F_max"),
            );
        }
        if s.human_force != 0.0 {
            let fh = s.human_force * fs;
            force.add(
                Series::dashed([(0.0, fh), (t_end, fh)])
                    .color(palette::GREEN)
                    .width(2)
                    .label("human push F_H"),
            );
        }
        force
    }

    /// The distance from rest |x − x_rest| over the whole run on a log scale, with the judged
    /// window: how the transient decays and where the verdict was judged.
    fn envelope(&self, r: &RunResult, units: Units) -> Figure {
        let (tr, t_end) = (self.tr, self.t_end);
        let x0 = rest(&tr.position);
        let (xs, xunit) = scaled_unit(max_abs(&tr.position), "m");
        // the largest distance in each of about 500 stretches: the envelope, without the dips
        // of every zero crossing
        let n = tr.position.len();
        let per = n.div_ceil(500).max(1);
        let logs: Vec<(f64, f64)> = (0..n)
            .step_by(per)
            .map(|i| {
                let j = (i + per).min(n);
                let d = tr.position[i..j]
                    .iter()
                    .fold(0.0f64, |m, x| m.max((x - x0).abs()))
                    * xs;
                (tr.time[i], if d > 0.0 { d.log10() } else { f64::NAN })
            })
            .collect();
        let what = if x0 == 0.0 { "|x|" } else { "|x − x_end|" };
        let mut f = Figure::new(format!("Envelope of {what} over the whole run (log scale)"))
            .x_label(format!("time t ({})", units.time()))
            .y_label(format!("{what} ({xunit})"))
            .x_range(0.0, t_end)
            .y_log10()
            .legend(Legend::Below);
        let (lo, hi) = extent(logs.iter().map(|p| &p.1).filter(|v| v.is_finite()));
        let period = self.cfg.model.period();
        let (j0, j1) = (
            r.verdict.judged_from_sample as f64 * period,
            r.verdict.judged_to_sample as f64 * period,
        );
        if hi > lo {
            let unit = units.time();
            let t = |v: f64| sig(v, 4);
            f.add(
                Series::polygon([(j0, lo), (j1, lo), (j1, hi), (j0, hi)])
                    .color(palette::GREY)
                    .alpha(0.15)
                    .no_outline()
                    .label(format!("judged window t = {} … {} {unit}", t(j0), t(j1))),
            );
        }
        f.add(
            Series::line(logs)
                .color(palette::BLUE)
                .width(2)
                .label(format!("largest {what} per stretch of the run")),
        );
        f
    }

    /// A zoom on the last periods of a limit cycle (eight periods, at most a quarter of the
    /// run), with the encoder's thresholds around it under quantization.
    fn limit_cycle(&self, r: &RunResult) -> Figure {
        let (tr, t_end) = (self.tr, self.t_end);
        let xw = self.cfg.effects.wall_position;
        let span = r
            .verdict
            .limit_cycle
            .map(|c| c.frequency_hz)
            .filter(|f| *f > 0.0)
            .map_or(t_end / 8.0, |f| 8.0 / f)
            .min(t_end / 4.0);
        let from = t_end - span;
        let tail: Vec<f64> = tr
            .time
            .iter()
            .zip(&tr.position)
            .filter(|(t, _)| **t >= from)
            .map(|(_, x)| *x)
            .collect();
        let (zs, zunit) = scaled_unit(max_abs(&tail).max(xw.abs()), "m");
        let mut zoom = Figure::new("Limit cycle: the last periods")
            .x_label(&self.tlabel)
            .y_label(format!("position x ({zunit})"))
            .x_range(from, t_end)
            .legend(Legend::Below);
        zoom.add(
            Series::line(self.series(&tr.position, zs, from))
                .color(palette::BLUE)
                .width(3)
                .label("position x"),
        );
        if let Some(q) = self.cfg.effects.quantization {
            let (lo, hi) = extent(&tail);
            // Thresholds (k + 1/2)·q from just below the cycle to just above it.
            let (k0, k1) = ((lo / q - 0.5).floor() as i64, (hi / q - 0.5).ceil() as i64);
            if k1 - k0 <= 40 {
                let mut levels = Vec::new();
                for k in k0..=k1 {
                    let y = (k as f64 + 0.5) * q * zs;
                    levels.extend([(from, y), (t_end, y), (f64::NAN, 0.0)]);
                }
                zoom.add(
                    Series::dashed(levels)
                        .color(palette::GREY)
                        .width(1)
                        .label("encoder thresholds"),
                );
            }
        }
        zoom
    }
}

/// The title's note on a clipped trace: where it was cut and why.
fn clip_note(c: &ClippedTrace, units: Units, period: f64) -> String {
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
