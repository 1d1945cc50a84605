//! The figures of `hapstab bode` (magnitude and phase panels over a log frequency axis in Hz,
//! the Nyquist frequency as a vertical line, the crossovers marked with their margins) and
//! `hapstab nyquist-plot` (L in the complex plane with −1, the unit circle and the circle of
//! radius min |1 + L| around −1).

use hapstab::freqresp::{FrequencyResponse, Mark};
use hapstab::margins::CrossingKind;

use crate::text::sig;
use crate::{Annotation, Figure, Grid, Legend, Marker, RGBColor, Series, palette};

/// Size of each Bode panel (px).
const BODE_PANEL: (u32, u32) = (1100, 600);

/// Magnitudes more than this many dB below the top of the panel are clipped (the zero of a
/// ZOH at the Nyquist frequency sends |L| to 0).
const DB_SPAN: f64 = 120.0;

/// Size of the Nyquist plot (px): a square plotting area.
const NYQUIST_SIZE: (u32, u32) = (978, 950);

/// The Bode plot: magnitude above phase, margins marked (module doc).
pub fn bode(fr: &FrequencyResponse, title: &str, subtitle: &str) -> Grid {
    let lx: Vec<f64> = fr.frequency_hz.iter().map(|f| f.log10()).collect();
    let x_lo = lx.first().copied().unwrap_or(0.0);
    let x_hi = fr.nyquist_hz.log10();
    let xr = (x_lo, x_hi + 0.04 * (x_hi - x_lo).max(1.0));
    let mut grid = Grid::new(format!("Bode plot of L(e^(jωT)), {title}"), 1)
        .subtitle(subtitle)
        .panel_size(BODE_PANEL.0, BODE_PANEL.1);
    grid.push(magnitude_panel(fr, &lx, xr));
    grid.push(phase_panel(fr, &lx, xr));
    grid
}

/// Plotting-area width of a Bode panel (px), for placing text.
const BODE_PLOT_PX: f64 = 950.0;

/// The x from which `text` is written so that it ends at `x` when `x` lies in the right
/// half of the range `xr` (else `x` itself): text stays inside the panel.
fn left_of(x: f64, text: &str, xr: (f64, f64)) -> f64 {
    if x < 0.5 * (xr.0 + xr.1) {
        return x;
    }
    x - text.chars().count() as f64 * 12.0 / BODE_PLOT_PX * (xr.1 - xr.0)
}

fn x_of(f: f64) -> f64 {
    f.log10()
}

fn note(fig: &mut Figure, at: (f64, f64), text: String, color: RGBColor) {
    fig.annotations.push(Annotation {
        at,
        text,
        color,
        lift: false,
    });
}

/// The vertical Nyquist-frequency line over the y range.
fn nyquist_line(fig: &mut Figure, fr: &FrequencyResponse, (y0, y1): (f64, f64), label: bool) {
    let x = x_of(fr.nyquist_hz);
    let s = Series::dashed([(x, y0), (x, y1)])
        .color(palette::BLACK)
        .width(2);
    fig.add(if label {
        s.label(format!("Nyquist frequency {} Hz", sig(fr.nyquist_hz, 4)))
    } else {
        s
    });
}

fn magnitude_panel(fr: &FrequencyResponse, lx: &[f64], xr: (f64, f64)) -> Figure {
    let finite = fr.magnitude_db.iter().copied().filter(|v| v.is_finite());
    let top = finite.clone().fold(0.0_f64, f64::max) + 10.0;
    let low = finite.fold(f64::INFINITY, f64::min).max(top - DB_SPAN);
    let marks_low = fr.marks.iter().map(|m| m.magnitude_db - 10.0);
    let bottom = marks_low.fold(low, f64::min).max(top - 2.0 * DB_SPAN) - 5.0;
    let mut fig = Figure::new("")
        .x_label("frequency (Hz)")
        .y_label("|L| (dB)")
        .x_log10()
        .x_range(xr.0, xr.1)
        .y_range(bottom, top)
        .legend(Legend::Below);
    fig.add(
        Series::line(lx.iter().copied().zip(fr.magnitude_db.iter().copied()))
            .color(palette::BLUE)
            .label("|L|"),
    );
    fig.add(
        Series::dashed([(xr.0, 0.0), (xr.1, 0.0)])
            .color(palette::GREY)
            .width(2),
    );
    nyquist_line(&mut fig, fr, (bottom, top), true);
    for m in &fr.marks {
        magnitude_mark(&mut fig, m, xr, top - bottom);
    }
    fig
}

/// One crossing on the magnitude panel: a gain crossover on 0 dB, a phase crossover with
/// its gain margin as a segment up to 0 dB (a negative factor, L real and positive, as a
/// hollow marker); the reported margins with their values.
fn magnitude_mark(fig: &mut Figure, m: &Mark, xr: (f64, f64), span: f64) {
    let x = x_of(m.frequency_hz);
    match m.kind {
        CrossingKind::Gain => {
            fig.add(Series::scatter([(x, 0.0)], Marker::Circle).color(palette::VERMILLION));
            if m.primary {
                let text = format!("  ω_c: {} Hz", sig(m.frequency_hz, 4));
                note(fig, (x, 0.06 * span), text, palette::VERMILLION);
            }
        }
        CrossingKind::Phase if m.value < 0.0 => {
            fig.add(
                Series::scatter([(x, m.magnitude_db)], Marker::Square)
                    .color(palette::GREEN)
                    .hollow(),
            );
        }
        CrossingKind::Phase => {
            let w = if m.primary { 3 } else { 1 };
            fig.add(
                Series::line([(x, m.magnitude_db), (x, 0.0)])
                    .color(palette::GREEN)
                    .width(w),
            );
            fig.add(Series::scatter([(x, m.magnitude_db)], Marker::Square).color(palette::GREEN));
            if m.primary {
                let text = gm_text(m);
                let at = (left_of(x, &text, xr), m.magnitude_db - 0.05 * span);
                note(fig, at, text, palette::GREEN);
            }
        }
    }
}

/// "GM ×2.31 (7.27 dB), 85.2 Hz" (a negative factor has no dB).
fn gm_text(m: &Mark) -> String {
    let db = if m.value > 0.0 {
        format!(" ({} dB)", sig(20.0 * m.value.log10(), 3))
    } else {
        String::new()
    };
    format!(
        "  GM ×{}{db}, {} Hz",
        sig(m.value, 3),
        sig(m.frequency_hz, 4)
    )
}

/// The −180° + k·360° line nearest `phase`.
fn minus_180_near(phase: f64) -> f64 {
    -180.0 + 360.0 * ((phase + 180.0) / 360.0).round()
}

fn phase_panel(fr: &FrequencyResponse, lx: &[f64], xr: (f64, f64)) -> Figure {
    let finite = || fr.phase_deg.iter().copied().filter(|v| v.is_finite());
    let lo = finite().fold(f64::INFINITY, f64::min).min(-180.0);
    let hi = finite().fold(f64::NEG_INFINITY, f64::max).max(-180.0);
    let pad = 0.12 * (hi - lo).max(90.0);
    let (y0, y1) = (lo - pad, hi + pad);
    let mut fig = Figure::new("")
        .x_label("frequency (Hz)")
        .y_label("arg L (deg)")
        .x_log10()
        .x_range(xr.0, xr.1)
        .y_range(y0, y1)
        .legend(Legend::Below);
    fig.add(
        Series::line(lx.iter().copied().zip(fr.phase_deg.iter().copied()))
            .color(palette::BLUE)
            .label("arg L"),
    );
    let mut k = minus_180_near(y0);
    while k <= y1 {
        fig.add(
            Series::dashed([(xr.0, k), (xr.1, k)])
                .color(palette::GREY)
                .width(2),
        );
        k += 360.0;
    }
    nyquist_line(&mut fig, fr, (y0, y1), false);
    for m in &fr.marks {
        phase_mark(&mut fig, m, xr, y1 - y0);
    }
    fig
}

/// One crossing on the phase panel: a gain crossover with its phase margin as a segment
/// from the −180° line (the reported one with its value), a phase crossover on the line.
fn phase_mark(fig: &mut Figure, m: &Mark, xr: (f64, f64), span: f64) {
    let x = x_of(m.frequency_hz);
    match m.kind {
        CrossingKind::Gain => {
            let base = minus_180_near(m.phase_deg);
            fig.add(
                Series::line([(x, base), (x, m.phase_deg)])
                    .color(palette::VERMILLION)
                    .width(if m.primary { 3 } else { 1 }),
            );
            fig.add(Series::scatter([(x, m.phase_deg)], Marker::Circle).color(palette::VERMILLION));
            if m.primary {
                let text = format!("  PM {}°, {} Hz", sig(m.value, 3), sig(m.frequency_hz, 4));
                // below the −180° line, where the curve of a stable loop is not
                let at = (left_of(x, &text, xr), m.phase_deg.min(base) - 0.07 * span);
                note(fig, at, text, palette::VERMILLION);
            }
        }
        CrossingKind::Phase => {
            let s = Series::scatter([(x, m.phase_deg)], Marker::Square).color(palette::GREEN);
            fig.add(if m.value < 0.0 { s.hollow() } else { s });
        }
    }
}

/// The Nyquist plot (module doc).
pub fn nyquist(fr: &FrequencyResponse, title: &str, subtitle: &str) -> Figure {
    let reach = fr
        .marks
        .iter()
        .map(|m| m.re.hypot(m.im))
        .chain(fr.closest.map(|c| 1.0 + c.distance))
        .fold(1.0_f64, f64::max);
    let r = (1.6 * reach).max(2.0);
    let mut fig = Figure::new(format!("Nyquist plot of L(e^(jωT)), {title}"))
        .subtitle(subtitle)
        .x_label("Re L")
        .y_label("Im L")
        .x_range(-r, r)
        .y_range(-r, r)
        .size(NYQUIST_SIZE.0, NYQUIST_SIZE.1)
        .legend(Legend::Below);
    let curve = || fr.re.iter().copied().zip(fr.im.iter().copied());
    fig.add(
        Series::line(curve())
            .color(palette::BLUE)
            .label("L, 0 < f ≤ f_N"),
    );
    fig.add(
        Series::dashed(curve().map(|(x, y)| (x, -y)))
            .color(palette::SKY)
            .width(2)
            .label("L, −f_N ≤ f < 0"),
    );
    fig.add(
        Series::dashed(circle((0.0, 0.0), 1.0))
            .color(palette::GREY)
            .width(2)
            .label("unit circle |L| = 1"),
    );
    if let Some(c) = fr.closest {
        fig.add(
            Series::line(circle((-1.0, 0.0), c.distance))
                .color(palette::VERMILLION)
                .width(2)
                .label(format!(
                    "min |1 + L| = {} at {} Hz",
                    sig(c.distance, 4),
                    sig(c.frequency_hz, 4)
                )),
        );
        fig.add(
            Series::line([(-1.0, 0.0), (c.re, c.im)])
                .color(palette::VERMILLION)
                .width(2),
        );
        fig.add(Series::scatter([(c.re, c.im)], Marker::Circle).color(palette::VERMILLION));
    }
    fig.add(
        Series::scatter([(-1.0, 0.0)], Marker::Cross)
            .color(palette::BLACK)
            .label("critical point −1"),
    );
    nyquist_marks(&mut fig, fr, r);
    fig
}

/// The crossovers on the Nyquist plot: gain crossovers on the unit circle with their phase
/// margin, phase crossovers on the real axis with their gain factor.
fn nyquist_marks(fig: &mut Figure, fr: &FrequencyResponse, r: f64) {
    for m in &fr.marks {
        let at = (m.re, m.im);
        let (marker, color, text) = match m.kind {
            CrossingKind::Gain => (
                Marker::Circle,
                palette::PURPLE,
                format!("  PM {}°", sig(m.value, 3)),
            ),
            CrossingKind::Phase => (Marker::Square, palette::GREEN, gm_text(m)),
        };
        fig.add(Series::scatter([at], marker).color(color).size(8));
        if m.primary {
            // the phase margin above its point, the gain margin below: apart when both are
            // near −1
            let dy = if m.kind == CrossingKind::Gain {
                0.06
            } else {
                -0.06
            };
            note(fig, (at.0, at.1 + dy * r), text, color);
        }
    }
}

/// A circle of 361 points.
fn circle((cx, cy): (f64, f64), radius: f64) -> Vec<(f64, f64)> {
    (0..=360)
        .map(|i| {
            let t = (i as f64).to_radians();
            (cx + radius * t.cos(), cy + radius * t.sin())
        })
        .collect()
}
