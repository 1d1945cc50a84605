//! Figs. 8–10 of the paper: the regions up to the Nyquist frequency over γ, with the
//! passive and robust regions.

use anyhow::Result;
use hapstab::paper::nyquist::passive_region;
use hapstab_plot::{Figure, Grid, Marker, RGBColor, Series, palette};

use super::legend::place_legend;
use super::{Drawing, GRID_FONT, PANEL, PaperFigure, XL, YL, bbox, num, outline};
use crate::paper::compute::{
    DELTA_NYQUIST, FULL_SWEEP, HALF_SWEEP, Key, Results, RobustKey, sweep_gamma,
};

pub(super) fn sweep_color(i: usize) -> RGBColor {
    [
        palette::BLACK,
        palette::BLUE,
        palette::GREEN,
        palette::ORANGE,
        palette::VERMILLION,
    ][i % 5]
}

pub(super) fn frac_label(f: (u32, u32)) -> String {
    match f {
        (1, 1) => "π".into(),
        (1, den) => format!("π/{den}"),
        (num, den) => format!("{num}π/{den}"),
    }
}

pub(super) fn gamma_label(f: (u32, u32), delta: f64) -> String {
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
pub(super) fn nyquist_panel(
    r: &Results,
    delta: f64,
    d: usize,
    full: bool,
    passive: bool,
) -> Result<Figure> {
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
            Series::polygon(rob.polygon.iter().map(|p| (p.a, p.b)))
                .color(palette::GREY)
                .alpha(0.35)
                .no_outline()
                .label("robustly stable"),
        );
    }
    if passive {
        let p = passive_region(delta)?;
        f.add(
            Series::polygon(p.vertices.iter().map(|v| (v.a, v.b)))
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

pub(super) fn fig8(r: &Results) -> Result<PaperFigure> {
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

pub(super) fn fig9(r: &Results) -> Result<PaperFigure> {
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

pub(super) fn fig10(r: &Results) -> Result<PaperFigure> {
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
