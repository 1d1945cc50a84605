//! The panels of a run's figure ([`super::run_plot::trace_plot`]): position, wall force,
//! distance from rest on a log scale and the zoom on a limit cycle.

use hapstab::simulation::{Config, Contact, RunResult, Trace};
use hapstab_plot::{Figure, Legend, Series, palette};

use super::run_args::RunSettings;
use super::run_plot::{PLOT_BUCKETS, extent, max_abs, scaled_unit};
use super::{Units, describe_effects};
use crate::output::sig;

/// What every panel of a run's figure shares: the trace, its end time, the end of the
/// shown transient and the time axis label.
pub(super) struct Panels<'a> {
    pub(super) tr: &'a Trace,
    pub(super) cfg: &'a Config,
    pub(super) t_end: f64,
    pub(super) t_show: f64,
    pub(super) tlabel: String,
}

impl Panels<'_> {
    /// The samples of `v` from time `from` on, scaled, min-max decimated for plotting.
    pub(super) fn series(&self, v: &[f64], scale: f64, from: f64) -> Vec<(f64, f64)> {
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
    pub(super) fn position(
        &self,
        r: &RunResult,
        params: String,
        clip_note: Option<String>,
    ) -> Figure {
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
    pub(super) fn force(&self, s: &RunSettings, units: Units) -> Figure {
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
    pub(super) fn envelope(&self, r: &RunResult, units: Units) -> Figure {
        let (tr, t_end) = (self.tr, self.t_end);
        let x0 = tr.rest_position();
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
    pub(super) fn limit_cycle(&self, r: &RunResult) -> Figure {
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
