//! Figures 4–10 of the paper from the computed regions: α on the horizontal axis, β on the
//! vertical axis (the paper's "left vertical boundary α = −γ" and "left-half plane α ≤ 0").

use anyhow::Result;
use hapstab::nyquist::passive_region;

use super::claims::{FIG5_ALPHA, FIG5_BETA};
use super::compute::{
    DELTA_ARM, DELTA_NYQUIST, FIG7_DELTAS, FULL_SWEEP, GAMMA_ARM, HALF_SWEEP, Key, Results,
    RobustKey, sweep_gamma,
};
use crate::output::sig;
use hapstab_plot::simplify::simplify_ring;
use hapstab_plot::{Figure, Grid, Kind, Legend, Marker, RGBColor, Saved, Series, palette};

/// x-axis label.
const XL: &str = "α = KT²/m";
/// y-axis label.
const YL: &str = "β = BT/m";
/// Chord tolerance of the drawn outlines, as a fraction of each axis range (a tenth of a
/// pixel in a 900 px panel).
const DRAW_TOL: f64 = 1e-4;
/// Panel size of the multi-panel figures.
const PANEL: (u32, u32) = (900, 700);
/// Font scale of the multi-panel figures (they print at half the width of a single one).
const GRID_FONT: f64 = 1.3;
/// Font scale of the single-panel figures.
const SINGLE_FONT: f64 = 1.15;

/// A figure to write: one panel or a grid.
pub enum Drawing {
    /// One panel.
    Single(Figure),
    /// Several panels.
    Grid(Grid),
}

/// A figure of the paper: file stem, caption and the drawing.
pub struct PaperFigure {
    /// File stem, e.g. "fig4".
    pub name: &'static str,
    /// Caption for the report.
    pub caption: String,
    /// The drawing.
    pub drawing: Drawing,
}

impl PaperFigure {
    /// Writes `<dir>/<name>.svg` and `.png`.
    pub fn save(&self, dir: &std::path::Path) -> Result<Saved> {
        let stem = dir.join(self.name);
        match &self.drawing {
            Drawing::Single(f) => Ok(f.save(stem)?),
            Drawing::Grid(g) => Ok(g.save(stem)?),
        }
    }
}

/// The outline of a region as polylines (one per component, NaN-separated in one series).
fn outline(r: &Results, k: Key, xr: (f64, f64), yr: (f64, f64)) -> Result<Vec<(f64, f64)>> {
    let reg = r.region(k)?;
    let mut out = Vec::new();
    for (i, ring) in reg.rings.iter().enumerate() {
        if i > 0 {
            out.push((f64::NAN, f64::NAN));
        }
        let scale = (1.0 / (xr.1 - xr.0), 1.0 / (yr.1 - yr.0));
        out.extend(simplify_ring(ring, scale, DRAW_TOL));
    }
    Ok(out)
}

/// Bounding box of the regions, padded by `pad` of the span on each side.
fn bbox(r: &Results, keys: &[Key], pad: f64) -> Result<((f64, f64), (f64, f64))> {
    let (mut x0, mut x1, mut y0, mut y1) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for &k in keys {
        let reg = r.region(k)?;
        x0 = x0.min(reg.alpha_min);
        x1 = x1.max(reg.alpha_max);
        y0 = y0.min(reg.beta_min);
        y1 = y1.max(reg.beta_max);
    }
    let (sx, sy) = (x1 - x0, y1 - y0);
    Ok((
        (x0 - pad * sx, x1 + pad * sx),
        (y0 - pad * sy, y1 + pad * sy),
    ))
}

fn inside(poly: &[(f64, f64)], p: (f64, f64)) -> bool {
    let n = poly.len();
    let mut c = false;
    let mut j = n.wrapping_sub(1);
    for i in 0..n {
        let (a, b) = (poly[i], poly[j]);
        if (a.1 > p.1) != (b.1 > p.1) && p.0 < a.0 + (p.1 - a.1) / (b.1 - a.1) * (b.0 - a.0) {
            c = !c;
        }
        j = i;
    }
    c
}

/// Does anything drawn in `f` fall inside the box?
fn occupied(f: &Figure, bx: [f64; 4]) -> bool {
    f.series.iter().any(|s| match s.kind {
        Kind::Line { .. } => s
            .points
            .windows(2)
            .any(|w| hapstab_plot::segment_meets_box(w[0], w[1], bx)),
        Kind::Polygon { .. } => {
            let n = s.points.len();
            (0..n).any(|i| hapstab_plot::segment_meets_box(s.points[i], s.points[(i + 1) % n], bx))
                || inside(&s.points, (0.5 * (bx[0] + bx[1]), 0.5 * (bx[2] + bx[3])))
        }
        Kind::Scatter { .. } => s
            .points
            .iter()
            .any(|p| p.0 >= bx[0] && p.0 <= bx[1] && p.1 >= bx[2] && p.1 <= bx[3]),
    }) || f
        .annotations
        .iter()
        .any(|a| a.at.0 >= bx[0] && a.at.0 <= bx[1] && a.at.1 >= bx[2] && a.at.1 <= bx[3])
}

/// Puts the legend in a corner where it covers nothing; when every corner is taken, widens
/// (if `may_widen`) the α range to the right or the β range upwards until a corner is free. `size` is the panel size
/// in px. The legend box is estimated from plot.rs's layout (fonts 21 px × scale, rows of
/// about 1.65 font heights, 46 px icons, 12 px margins; measured on the PNGs), with 2 % of
/// the plot to spare.
fn place_legend(f: &mut Figure, size: (u32, u32), may_widen: bool) {
    let Some(lb) = legend_box(f, size) else {
        return;
    };
    let corners = [
        Legend::UpperRight,
        Legend::UpperLeft,
        Legend::LowerRight,
        Legend::LowerLeft,
    ];
    for pos in corners {
        if !occupied(f, lb.at(f.ranges(), pos)) {
            f.legend = pos;
            return;
        }
    }
    if may_widen {
        widen_for_legend(f, &lb);
    } else {
        f.legend = Legend::UpperRight;
    }
}

/// The legend box's estimated size and its offset from the plot's edge, as fractions of the
/// plotting area's width and height.
struct LegendBox {
    w: f64,
    h: f64,
    off: (f64, f64),
}

impl LegendBox {
    /// The box [x_lo, x_hi, y_lo, y_hi] in data units at the corner `pos` of the ranges.
    fn at(&self, ((x0, x1), (y0, y1)): ((f64, f64), (f64, f64)), pos: Legend) -> [f64; 4] {
        let (xs, ys) = (x1 - x0, y1 - y0);
        let (w, h, off) = (self.w, self.h, self.off);
        let right = matches!(
            pos,
            Legend::UpperRight | Legend::LowerRight | Legend::Hidden
        );
        let upper = matches!(pos, Legend::UpperRight | Legend::UpperLeft | Legend::Hidden);
        let (xa, xb) = if right {
            (x1 - (off.0 + w) * xs, x1 - off.0 * xs)
        } else {
            (x0 + off.0 * xs, x0 + (off.0 + w) * xs)
        };
        let (ya, yb) = if upper {
            (y1 - (off.1 + h) * ys, y1 - off.1 * ys)
        } else {
            (y0 + off.1 * ys, y0 + (off.1 + h) * ys)
        };
        [xa, xb, ya, yb]
    }
}

/// The legend box of a figure on a panel of `size` px (see [`place_legend`]); None when no
/// series is labelled.
fn legend_box(f: &Figure, size: (u32, u32)) -> Option<LegendBox> {
    let labels: Vec<usize> = f
        .series
        .iter()
        .filter_map(|s| s.label.as_ref().map(|l| l.chars().count()))
        .collect();
    if labels.is_empty() {
        return None;
    }
    let s = f.font_scale;
    let font = 21.0 * s;
    let plot_w = size.0 as f64 - (105.0 + 42.0) * s;
    let plot_h = size.1 as f64 - (70.0 + 28.0 + if f.title.is_empty() { 0.0 } else { 45.0 }) * s;
    let chars = labels.iter().copied().max().unwrap_or(0) as f64;
    Some(LegendBox {
        w: (46.0 * s + 0.56 * font * chars + 30.0 * s) / plot_w + 0.01,
        h: (labels.len() as f64 * 1.65 * font + 14.0 * s) / plot_h + 0.02,
        off: (12.0 * s / plot_w, 12.0 * s / plot_h),
    })
}

/// Every corner covers data: widens the α range to the right or the β range upwards,
/// whichever needs the smaller widening, so that the legend box clears every drawn point in
/// its band, and puts the legend there.
fn widen_for_legend(f: &mut Figure, lb: &LegendBox) {
    let (w, h, off) = (lb.w, lb.h, lb.off);
    let ((x0, x1), (y0, y1)) = f.ranges();
    let (xs, ys) = (x1 - x0, y1 - y0);
    let fit = |need: f64, lo: f64, span: f64, box_frac: f64, off: f64| {
        let frac = (1.0 - box_frac - 2.0 * off).max(0.25);
        ((need - lo) / frac * 1.02).max(span)
    };
    let top = (y1 - (off.1 + h) * ys, y1);
    let bottom = (y0, y0 + (off.1 + h) * ys);
    let right = (x1 - (off.0 + w) * xs, x1);
    let left = (x0, x0 + (off.0 + w) * xs);
    let options = [
        (
            Legend::UpperRight,
            true,
            fit(max_in_band(f, false, top), x0, xs, w, off.0) / xs,
        ),
        (
            Legend::LowerRight,
            true,
            fit(max_in_band(f, false, bottom), x0, xs, w, off.0) / xs,
        ),
        (
            Legend::UpperRight,
            false,
            fit(max_in_band(f, true, right), y0, ys, h, off.1) / ys,
        ),
        (
            Legend::UpperLeft,
            false,
            fit(max_in_band(f, true, left), y0, ys, h, off.1) / ys,
        ),
    ];
    let (pos, along_x, factor) = options
        .iter()
        .copied()
        .min_by(|a, b| a.2.total_cmp(&b.2))
        .unwrap_or((Legend::UpperRight, true, 2.0));
    if along_x {
        f.x_range = Some((x0, x0 + factor * xs));
    } else {
        f.y_range = Some((y0, y0 + factor * ys));
    }
    f.legend = pos;
}

/// The largest α (`beta_band` false: points with β in the band) or β (`true`: points with α
/// in the band) of everything drawn in `f`; segments are clipped to the band first.
fn max_in_band(f: &Figure, alpha_band: bool, band: (f64, f64)) -> f64 {
    let key = |p: (f64, f64)| if alpha_band { p.0 } else { p.1 };
    let val = |p: (f64, f64)| if alpha_band { p.1 } else { p.0 };
    let mut best = f64::NEG_INFINITY;
    let mut seg = |a: (f64, f64), b: (f64, f64)| {
        if !(a.0.is_finite() && a.1.is_finite() && b.0.is_finite() && b.1.is_finite()) {
            return;
        }
        let (ka, kb) = (key(a), key(b));
        let (lo, hi) = (ka.min(kb), ka.max(kb));
        if hi < band.0 || lo > band.1 {
            return;
        }
        for k in [ka.clamp(band.0, band.1), kb.clamp(band.0, band.1)] {
            let t = if kb != ka { (k - ka) / (kb - ka) } else { 0.0 };
            best = best.max(val(a) + t.clamp(0.0, 1.0) * (val(b) - val(a)));
        }
    };
    for s in &f.series {
        match s.kind {
            Kind::Line { .. } => s.points.windows(2).for_each(|w| seg(w[0], w[1])),
            Kind::Polygon { .. } => {
                let n = s.points.len();
                (0..n).for_each(|i| seg(s.points[i], s.points[(i + 1) % n]));
            }
            Kind::Scatter { .. } => s.points.iter().for_each(|&p| seg(p, p)),
        }
    }
    for a in &f.annotations {
        seg(a.at, a.at);
    }
    best
}

fn num(x: f64) -> String {
    sig(x, 4)
}

/// The four corners of the range (15): (γ, δ, colour, dashed).
fn corners() -> [(f64, f64, RGBColor, bool); 4] {
    // δ = 0.015 first so that the δ = 0 lines stay visible where both run along α = 0.
    [
        (0.0, DELTA_ARM, palette::VERMILLION, false),
        (GAMMA_ARM, DELTA_ARM, palette::ORANGE, true),
        (0.0, 0.0, palette::BLUE, false),
        (GAMMA_ARM, 0.0, palette::SKY, true),
    ]
}

/// A panel with the four boundaries of the range (15) at delay d.
fn corner_panel(
    r: &Results,
    d: usize,
    title: String,
    window: Option<((f64, f64), (f64, f64))>,
    font: f64,
) -> Result<Figure> {
    let keys: Vec<Key> = corners().iter().map(|c| Key::new(c.0, c.1, d)).collect();
    let (xr, yr) = match window {
        Some(w) => w,
        None => bbox(r, &keys, 0.04)?,
    };
    let mut f = Figure::new(title)
        .x_label(XL)
        .y_label(YL)
        .x_range(xr.0, xr.1)
        .y_range(yr.0, yr.1)
        .font_scale(font);
    for (g, dl, c, dashed) in corners() {
        let pts = outline(r, Key::new(g, dl, d), xr, yr)?;
        let s = if dashed {
            Series::dashed(pts)
        } else {
            Series::line(pts)
        };
        f.add(
            s.color(c)
                .width(3)
                .label(format!("γ = {}, δ = {}", num(g), num(dl))),
        );
    }
    Ok(f)
}

fn fig4(r: &Results) -> Result<PaperFigure> {
    let mut f = corner_panel(
        r,
        0,
        "Fig. 4: exact stability boundary, d = 0".into(),
        None,
        SINGLE_FONT,
    )?;
    let size = f.size;
    place_legend(&mut f, size, true);
    Ok(PaperFigure {
        name: "fig4",
        caption: "Fig. 4. Exact stability boundary in the (α, β)-plane for d = 0 and the limits \
                  of the parameter range γ ∈ {0, 0.001}, δ ∈ {0, 0.015} (solid: γ = 0, dashed: \
                  γ = 0.001). The effect of γ is not visible at this scale."
            .into(),
        drawing: Drawing::Single(f),
    })
}

fn fig5(r: &Results) -> Result<PaperFigure> {
    let mut f = corner_panel(
        r,
        0,
        "Fig. 5: close-up of Fig. 4 around the origin".into(),
        Some((FIG5_ALPHA, FIG5_BETA)),
        SINGLE_FONT,
    )?;
    f.add(
        Series::dashed([(-GAMMA_ARM, FIG5_BETA.0), (-GAMMA_ARM, FIG5_BETA.1)])
            .color(palette::GREY)
            .width(1),
    );
    f.annotate(
        -GAMMA_ARM + 0.00012,
        FIG5_BETA.0 + 0.045 * (FIG5_BETA.1 - FIG5_BETA.0),
        "α = −γ = −0.001",
    );
    let size = f.size;
    place_legend(&mut f, size, false);
    Ok(PaperFigure {
        name: "fig5",
        caption: "Fig. 5. Close-up of Fig. 4 around the origin: physical stiffness γ = 0.001 \
                  shifts the left boundary to α = −γ and does not visibly move the bottom \
                  boundary."
            .into(),
        drawing: Drawing::Single(f),
    })
}

fn fig6(r: &Results) -> Result<PaperFigure> {
    let mut g = Grid::new(
        "Fig. 6: stability boundary for d = 1 (left) and d = 2 (right)",
        2,
    )
    .panel_size(PANEL.0, PANEL.1);
    for d in [1, 2] {
        let mut f = corner_panel(r, d, format!("d = {d}"), None, GRID_FONT)?;
        place_legend(&mut f, PANEL, true);
        g.push(f);
    }
    Ok(PaperFigure {
        name: "fig6",
        caption: "Fig. 6. Stability boundary in the (α, β)-plane for d = 1 (left) and d = 2 \
                  (right) for the limits of the parameter range γ ∈ {0, 0.001}, δ ∈ {0, 0.015} \
                  (solid: γ = 0, dashed: γ = 0.001)."
            .into(),
        drawing: Drawing::Grid(g),
    })
}

fn delta_color(i: usize) -> RGBColor {
    [
        palette::BLUE,
        palette::GREEN,
        palette::PURPLE,
        palette::VERMILLION,
    ][i % 4]
}

fn fig7(r: &Results) -> Result<PaperFigure> {
    let mut g = Grid::new(
        "Fig. 7: exact boundary (solid), linear condition (23) (dashed), error (24) of 2 % (○) and 5 % (□)",
        2,
    )
    .panel_size(PANEL.0, PANEL.1);
    for d in 0..=1 {
        // The same window for both γ: the 5 % points of the largest δ set the scale.
        let mut a5: f64 = 0.0;
        let mut b5: f64 = 0.0;
        for gamma in [0.0, GAMMA_ARM] {
            for delta in FIG7_DELTAS {
                for p in r.validity(Key::new(gamma, delta, d))? {
                    a5 = a5.max(p.alpha);
                    b5 = b5.max(p.beta);
                }
            }
        }
        let xr = (-0.1 * a5, 1.2 * a5);
        let yr = (-0.021, 1.25 * b5);
        for gamma in [0.0, GAMMA_ARM] {
            let mut f = Figure::new(format!("d = {d}, γ = {}", num(gamma)))
                .x_label(XL)
                .y_label(YL)
                .x_range(xr.0, xr.1)
                .y_range(yr.0, yr.1)
                .font_scale(GRID_FONT);
            let mut two = Vec::new();
            let mut five = Vec::new();
            for (i, delta) in FIG7_DELTAS.iter().copied().enumerate() {
                let k = Key::new(gamma, delta, d);
                f.add(
                    Series::line(outline(r, k, xr, yr)?)
                        .color(delta_color(i))
                        .width(3)
                        .label(format!("δ = {}", num(delta))),
                );
                // (23): α = (β + δ)/(d + 1/2) for α ≥ −γ.
                let s = d as f64 + 0.5;
                let lin = [
                    (-gamma, -gamma * s - delta),
                    (xr.1 * 1.5, xr.1 * 1.5 * s - delta),
                ];
                f.add(Series::dashed(lin).color(delta_color(i)).width(2));
                for p in r.validity(k)? {
                    if p.level < 0.03 {
                        two.push((p.alpha, p.beta));
                    } else {
                        five.push((p.alpha, p.beta));
                    }
                }
            }
            f.add(
                Series::scatter(two, Marker::Circle)
                    .color(palette::BLACK)
                    .hollow()
                    .size(8),
            );
            f.add(
                Series::scatter(five, Marker::Square)
                    .color(palette::BLACK)
                    .hollow()
                    .size(7),
            );
            place_legend(&mut f, PANEL, true);
            g.push(f);
        }
    }
    Ok(PaperFigure {
        name: "fig7",
        caption: "Fig. 7. Validity of the linear stability condition: exact stability boundaries \
                  (solid) with the points where the relative error (24) of the linear condition \
                  (23) (dashed) equals 2 % (circles) and 5 % (squares), for δ ∈ {0, 0.005, 0.01, \
                  0.015} and γ = 0 (left) resp. γ = 0.001 (right); top d = 0, bottom d = 1."
            .into(),
        drawing: Drawing::Grid(g),
    })
}

fn sweep_color(i: usize) -> RGBColor {
    [
        palette::BLACK,
        palette::BLUE,
        palette::GREEN,
        palette::ORANGE,
        palette::VERMILLION,
    ][i % 5]
}

fn frac_label(f: (u32, u32)) -> String {
    match f {
        (1, 1) => "π".into(),
        (1, den) => format!("π/{den}"),
        (num, den) => format!("{num}π/{den}"),
    }
}

fn gamma_label(f: (u32, u32), delta: f64) -> String {
    if f.0 == 0 {
        return "γ = 0".into();
    }
    let core = if f == (1, 1) {
        "π²".to_string()
    } else {
        format!("({})²", frac_label(f))
    };
    if delta == 0.0 {
        if f == (1, 1) {
            "γ → π² (limit)".into()
        } else {
            format!("γ = {core}")
        }
    } else {
        let q = delta * delta / 4.0;
        let q = if q == 0.25 { "¼".to_string() } else { num(q) };
        format!("γ = {core} + {q}")
    }
}

/// One panel of Figs. 8–10.
fn nyquist_panel(r: &Results, delta: f64, d: usize, full: bool, passive: bool) -> Result<Figure> {
    let sweep: &[(u32, u32)] = if full { &FULL_SWEEP } else { &HALF_SWEEP };
    let keys: Vec<Key> = sweep
        .iter()
        .map(|&f| Key::new(sweep_gamma(f, delta), delta, d))
        .collect();
    let (xr, yr) = bbox(r, &keys, 0.05)?;
    let top = if full { "π²" } else { "(π/2)²" };
    let title = if delta == 0.0 {
        format!("δ = 0, d = {d}, 0 ≤ γ ≤ {top}")
    } else {
        format!("δ = {}, d = {d}, 0 ≤ γ ≤ {top} + δ²/4", num(delta))
    };
    let mut f = Figure::new(title)
        .x_label(XL)
        .y_label(YL)
        .x_range(xr.0, xr.1)
        .y_range(yr.0, yr.1)
        .font_scale(GRID_FONT);
    let rob = r.robust(RobustKey { delta, d, full })?;
    if rob.empty {
        // Explained in the title: the robust region is the origin only.
        f.add(
            Series::scatter([(0.0, 0.0)], Marker::Cross)
                .color(palette::BLACK)
                .size(9),
        );
    } else {
        f.add(
            Series::polygon(rob.polygon.iter().map(|p| (p.alpha, p.beta)))
                .color(palette::GREY)
                .alpha(0.35)
                .no_outline()
                .label("robustly stable"),
        );
    }
    if passive {
        let p = passive_region(delta)?;
        f.add(
            Series::polygon(p.vertices.iter().map(|v| (v.alpha, v.beta)))
                .color(palette::GREEN)
                .alpha(0.55)
                .label("passive (28)"),
        );
    }
    for (i, (&fr, &k)) in sweep.iter().zip(&keys).enumerate() {
        f.add(
            Series::line(outline(r, k, xr, yr)?)
                .color(sweep_color(i))
                .width(3)
                .label(gamma_label(fr, delta)),
        );
    }
    place_legend(&mut f, PANEL, true);
    Ok(f)
}

fn fig8(r: &Results) -> Result<PaperFigure> {
    let mut g = Grid::new(
        "Fig. 8: δ = 0, d = 0, up to half (left) and full (right) Nyquist frequency; robust region: × (origin)",
        2,
    )
    .panel_size(PANEL.0, PANEL.1);
    for full in [false, true] {
        g.push(nyquist_panel(r, 0.0, 0, full, false)?);
    }
    Ok(PaperFigure {
        name: "fig8",
        caption: "Fig. 8. Stability boundaries for δ = 0, d = 0 and γ such that the plant \
                  oscillates up to half (left; 0 ≤ γ ≤ (π/2)²) or the full (right; 0 ≤ γ ≤ π²) \
                  Nyquist frequency. At γ = π² every point is limit stable (pole at z = −1); the \
                  limit γ → π² is drawn. The robustly stable region is the origin."
            .into(),
        drawing: Drawing::Grid(g),
    })
}

fn fig9(r: &Results) -> Result<PaperFigure> {
    let mut g = Grid::new(
        "Fig. 9: δ = 1, d = 0, robust region (grey) and Colgate's passive region (green)",
        2,
    )
    .panel_size(PANEL.0, PANEL.1);
    for full in [false, true] {
        g.push(nyquist_panel(r, DELTA_NYQUIST, 0, full, true)?);
    }
    Ok(PaperFigure {
        name: "fig9",
        caption: "Fig. 9. Same as Fig. 8 for δ = 1 (Nyquist frequency at γ = π² + 1/4). The \
                  robustly stable region over the panel's γ range is shaded grey, Colgate's \
                  passive region (28) green."
            .into(),
        drawing: Drawing::Grid(g),
    })
}

fn fig10(r: &Results) -> Result<PaperFigure> {
    let mut g = Grid::new(
        "Fig. 10: d = 1; δ = 0 (top, robust: × origin) and δ = 1 (bottom), up to half (left) and full (right) Nyquist",
        2,
    )
    .panel_size(PANEL.0, PANEL.1);
    for delta in [0.0, DELTA_NYQUIST] {
        for full in [false, true] {
            g.push(nyquist_panel(r, delta, 1, full, false)?);
        }
    }
    Ok(PaperFigure {
        name: "fig10",
        caption: "Fig. 10. Same as Fig. 8 for d = 1: δ = 0 (top) and δ = 1 (bottom), γ up to half \
                  (left) and full (right) Nyquist frequency; robustly stable region shaded grey."
            .into(),
        drawing: Drawing::Grid(g),
    })
}

/// Builds Figs. 4–10.
pub fn build(r: &Results) -> Result<Vec<PaperFigure>> {
    Ok(vec![
        fig4(r)?,
        fig5(r)?,
        fig6(r)?,
        fig7(r)?,
        fig8(r)?,
        fig9(r)?,
        fig10(r)?,
    ])
}

/// The (γ, δ, d) of every region drawn, with the figures that show it.
pub fn shown() -> Vec<(Key, Vec<&'static str>)> {
    let mut out: Vec<(Key, Vec<&'static str>)> = Vec::new();
    let mut add = |k: Key, fig: &'static str| match out.iter_mut().find(|(x, _)| {
        x.gamma.to_bits() == k.gamma.to_bits()
            && x.delta.to_bits() == k.delta.to_bits()
            && x.d == k.d
    }) {
        Some((_, figs)) => {
            if !figs.contains(&fig) {
                figs.push(fig);
            }
        }
        None => out.push((k, vec![fig])),
    };
    for d in 0..=2 {
        for (g, dl, _, _) in corners() {
            let k = Key::new(g, dl, d);
            match d {
                0 => {
                    add(k, "4");
                    add(k, "5");
                }
                _ => add(k, "6"),
            }
        }
    }
    for d in 0..=1 {
        for gamma in [0.0, GAMMA_ARM] {
            for delta in FIG7_DELTAS {
                add(Key::new(gamma, delta, d), "7");
            }
        }
    }
    for (delta, d, fig) in [
        (0.0, 0, "8"),
        (DELTA_NYQUIST, 0, "9"),
        (0.0, 1, "10"),
        (DELTA_NYQUIST, 1, "10"),
    ] {
        for f in HALF_SWEEP.iter().chain(FULL_SWEEP.iter()) {
            add(Key::new(sweep_gamma(*f, delta), delta, d), fig);
        }
    }
    out
}
