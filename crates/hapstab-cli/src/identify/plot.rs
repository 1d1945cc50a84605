//! The figure of `hapstab identify`: measured and model position over time, and the
//! residuals below them.

use hapstab::identify::frequency::FrequencyRecord;
use hapstab::identify::{Identification, Record};
use hapstab::model::Loop;

use crate::output::sig;
use hapstab_plot::{Figure, Grid, Legend, Series, palette};

/// Buckets of the min-max decimation of each curve: two points per bucket keep the envelope
/// of a dense noisy trace. The curves are one pixel wide: a wider polyline's mitred joins
/// spike far past the data at the sharp turns of a noisy trace.
const PLOT_BUCKETS: usize = 1_500;

/// The (time, value × scale) pairs, min-max decimated to [`PLOT_BUCKETS`] buckets.
fn thinned(t: &[f64], v: &[f64], scale: f64) -> Vec<(f64, f64)> {
    let pts: Vec<(f64, f64)> = t.iter().zip(v).map(|(t, v)| (*t, v * scale)).collect();
    hapstab_plot::decimate_minmax(&pts, PLOT_BUCKETS)
}

/// The figure (module doc), positions in mm.
pub fn figure(record: &Record, id: &Identification, lp: &Loop) -> Grid {
    let residual: Vec<f64> = record
        .position
        .iter()
        .zip(&id.predicted)
        .map(|(m, p)| m - p)
        .collect();
    let span = |v: &[f64], scale: f64| {
        let (lo, hi) = v
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        let pad = 0.05 * (hi - lo).max(f64::MIN_POSITIVE);
        ((lo - pad) * scale, (hi + pad) * scale)
    };
    let (plo, phi) = span(&record.position, 1e3);
    let (rlo, rhi) = span(&residual, 1e6);
    let mut pos = Figure::new(format!(
        "Position: measured and {} model (fit {} %)",
        id.model,
        sig(id.fit.fit_percent, 4)
    ))
    .x_label("time t (s)")
    .y_label("position (mm)")
    .y_range(plo, phi)
    .legend(Legend::Below);
    pos.add(
        Series::line(thinned(&record.time, &record.position, 1e3))
            .color(palette::GREY)
            .width(1)
            .label("measured"),
    );
    pos.add(
        Series::line(thinned(&record.time, &id.predicted, 1e3))
            .color(palette::VERMILLION)
            .width(1)
            .label("model (exact sampled response from rest)"),
    );
    let mut res = Figure::new("Residual: measured − model")
        .x_label("time t (s)")
        .y_label("residual (µm)")
        .y_range(rlo, rhi)
        .legend(Legend::Below);
    res.add(
        Series::line(thinned(&record.time, &residual, 1e6))
            .color(palette::BLUE)
            .width(1)
            .label(format!(
                "residual (whiteness test {})",
                if id.whiteness.passes {
                    "passed"
                } else {
                    "failed"
                }
            )),
    );
    let mut g = Grid::new(format!("Identification: {}", id.model), 1)
        .panel_size(1000, 460)
        .subtitle(caption(lp));
    g.push(pos);
    g.push(res);
    g
}

/// The identified loop in one line: T and t_d.
fn caption(lp: &Loop) -> String {
    format!(
        "T = {} s, t_d = {} s",
        sig(lp.period, 4),
        sig(lp.delay_time(), 4)
    )
}

/// The Bode figure of a frequency-response fit: measured and model magnitude (dB) and phase
/// (degrees, unwrapped) against frequency on a log axis.
pub fn bode(rec: &FrequencyRecord, id: &Identification, lp: &Loop) -> Grid {
    let f: Vec<f64> = rec.frequency_hz.iter().map(|f| f.log10()).collect();
    let db = |h: &[num_complex::Complex64]| -> Vec<f64> {
        h.iter().map(|z| 20.0 * z.norm().log10()).collect()
    };
    let phase = |h: &[num_complex::Complex64]| -> Vec<f64> {
        let mut out: Vec<f64> = Vec::with_capacity(h.len());
        for z in h {
            let mut p = z.arg().to_degrees();
            if let Some(prev) = out.last() {
                p += 360.0 * ((prev - p) / 360.0).round();
            }
            out.push(p);
        }
        out
    };
    let panel = |title: &str, y: &str, meas: Vec<f64>, model: Vec<f64>| {
        let mut fig = Figure::new(title)
            .x_label("frequency (Hz)")
            .y_label(y)
            .x_log10()
            .legend(Legend::Below);
        fig.add(
            Series::scatter(f.iter().copied().zip(meas), hapstab_plot::Marker::Circle)
                .color(palette::GREY)
                .label("measured"),
        );
        fig.add(
            Series::line(f.iter().copied().zip(model))
                .color(palette::VERMILLION)
                .label("model (exact sampled response)"),
        );
        fig
    };
    let mut g = Grid::new(
        format!(
            "Identification: {} (fit {} %)",
            id.model,
            sig(id.fit.fit_percent, 4)
        ),
        1,
    )
    .panel_size(1000, 460)
    .subtitle(caption(lp));
    g.push(panel(
        "Magnitude",
        "magnitude (dB re 1 m/N)",
        db(&rec.response),
        db(&id.predicted_response),
    ));
    g.push(panel(
        "Phase",
        "phase (°)",
        phase(&rec.response),
        phase(&id.predicted_response),
    ));
    g
}
