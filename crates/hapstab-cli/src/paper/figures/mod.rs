//! Figures 4–10 of the paper from the computed regions: α on the horizontal axis, β on the
//! vertical axis (the paper's "left vertical boundary α = −γ" and "left-half plane α ≤ 0").
//!
//! Parts: [`regions`] draws Figs. 4–7 (the stable regions over the range (15) and the δ's),
//! [`nyquist`] Figs. 8–10 (the regions up to the Nyquist frequency), [`legend`] places the
//! legends where they cover nothing.

mod legend;
mod nyquist;
mod regions;

use anyhow::Result;
use hapstab_plot::simplify::simplify_ring;
use hapstab_plot::{Figure, Grid, Saved};

use super::compute::{
    DELTA_NYQUIST, FIG7_DELTAS, FULL_SWEEP, GAMMA_ARM, HALF_SWEEP, Key, Results, sweep_gamma,
};
use crate::output::sig;
use nyquist::{fig8, fig9, fig10};
use regions::{corners, fig4, fig5, fig6, fig7};

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

fn num(x: f64) -> String {
    sig(x, 4)
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
