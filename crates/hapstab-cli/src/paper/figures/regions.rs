//! Figs. 4–7 of the paper: the stable regions at the corners of the range (15), at the
//! paper's wall, and over δ.

use anyhow::Result;
use hapstab_plot::{Figure, Grid, Marker, RGBColor, Series, palette};

use super::legend::place_legend;
use super::{Drawing, GRID_FONT, PANEL, PaperFigure, SINGLE_FONT, XL, YL, bbox, num, outline};
use crate::paper::claims::{FIG5_ALPHA, FIG5_BETA};
use crate::paper::compute::{DELTA_ARM, FIG7_DELTAS, GAMMA_ARM, Key, Results};

/// The four corners of the range (15): (γ, δ, colour, dashed).
pub(super) fn corners() -> [(f64, f64, RGBColor, bool); 4] {
    // δ = 0.015 first so that the δ = 0 lines stay visible where both run along α = 0.
    [
        (0.0, DELTA_ARM, palette::VERMILLION, false),
        (GAMMA_ARM, DELTA_ARM, palette::ORANGE, true),
        (0.0, 0.0, palette::BLUE, false),
        (GAMMA_ARM, 0.0, palette::SKY, true),
    ]
}

/// A panel with the four boundaries of the range (15) at delay d.
pub(super) fn corner_panel(
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

pub(super) fn fig4(r: &Results) -> Result<PaperFigure> {
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

pub(super) fn fig5(r: &Results) -> Result<PaperFigure> {
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

pub(super) fn fig6(r: &Results) -> Result<PaperFigure> {
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

pub(super) fn delta_color(i: usize) -> RGBColor {
    [
        palette::BLUE,
        palette::GREEN,
        palette::PURPLE,
        palette::VERMILLION,
    ][i % 4]
}

pub(super) fn fig7(r: &Results) -> Result<PaperFigure> {
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
