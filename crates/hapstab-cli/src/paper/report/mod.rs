//! The written report of `hapstab paper`: claims.json (machine-readable), report.md and a
//! self-contained report.html (figures embedded as base64 PNG, no network).
//!
//! Parts: [`tables`] the cells of the α_max and robust tables, [`markdown`] report.md,
//! [`html`] report.html.

mod html;
mod markdown;
mod tables;

use std::path::Path;

use anyhow::{Context, Result};
use serde::Serialize;

use super::claims::Claim;
use super::compute::{Key, Results, RobustKey};
use html::html_report;
use markdown::markdown;

/// One row of the α_max table.
#[derive(Debug, Clone, Serialize)]
pub struct AlphaRow {
    /// Figures that show the region.
    pub figures: String,
    /// γ.
    pub gamma: f64,
    /// δ.
    pub delta: f64,
    /// d.
    pub d: usize,
    /// α_max.
    pub alpha_max: f64,
    /// β at α_max.
    pub beta_at_alpha_max: f64,
    /// Area.
    pub area: f64,
    /// Outline vertices.
    pub vertices: usize,
}

/// One row of the robust-region table.
#[derive(Debug, Clone, Serialize)]
pub struct RobustRow {
    /// Figure.
    pub figure: &'static str,
    /// δ.
    pub delta: f64,
    /// d.
    pub d: usize,
    /// Upper end of the γ interval (lower end 0).
    pub gamma_hi: f64,
    /// No robustly stable interior point.
    pub empty: bool,
    /// Largest robust α.
    pub alpha_max: f64,
    /// β there.
    pub beta_at_alpha_max: f64,
    /// Area.
    pub area: f64,
}

/// A figure written.
#[derive(Debug, Clone, Serialize)]
pub struct FigureRow {
    /// File stem.
    pub name: &'static str,
    /// SVG file name.
    pub svg: String,
    /// PNG file name.
    pub png: String,
    /// Caption.
    pub caption: String,
}

/// Everything in the report.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    /// hapstab version.
    pub version: &'static str,
    /// Seconds spent computing and drawing (before writing the report).
    pub seconds: f64,
    /// Axis convention of the figures.
    pub axes: &'static str,
    /// Claims C1–C11.
    pub claims: Vec<Claim>,
    /// α_max for every (γ, δ, d) in the figures.
    pub alpha_max: Vec<AlphaRow>,
    /// Robust regions of Figs. 8–10.
    pub robust: Vec<RobustRow>,
    /// The figures.
    pub figures: Vec<FigureRow>,
    /// Notes on methods and on the library.
    pub notes: Vec<String>,
}

/// The axis convention.
pub const AXES: &str = "α (normalized virtual stiffness KT²/m) on the horizontal axis, β (normalized \
     virtual damping BT/m) on the vertical axis: the paper speaks of the \"left vertical \
     boundary α = −γ\", the \"bottom boundary\" and the \"left-half plane (α ≤ 0)\".";

/// Rows of the α_max table.
pub fn alpha_rows(r: &Results, shown: &[(Key, Vec<&'static str>)]) -> Result<Vec<AlphaRow>> {
    shown
        .iter()
        .map(|(k, figs)| {
            let reg = r.region(*k)?;
            Ok(AlphaRow {
                figures: figs.join(", "),
                gamma: k.gamma,
                delta: k.delta,
                d: k.d,
                alpha_max: reg.alpha_max,
                beta_at_alpha_max: reg.beta_at_alpha_max,
                area: reg.area,
                vertices: reg.vertices,
            })
        })
        .collect()
}

/// Rows of the robust table.
pub fn robust_rows(r: &Results) -> Result<Vec<RobustRow>> {
    let mut out = Vec::new();
    for (delta, d, figure) in [(0.0, 0, "8"), (1.0, 0, "9"), (0.0, 1, "10"), (1.0, 1, "10")] {
        for full in [false, true] {
            let k = RobustKey { delta, d, full };
            let rr = r.robust(k)?;
            out.push(RobustRow {
                figure,
                delta,
                d,
                gamma_hi: k.gamma_hi(),
                empty: rr.empty,
                alpha_max: rr.alpha_max,
                beta_at_alpha_max: rr.beta_at_alpha_max,
                area: rr.area,
            });
        }
    }
    Ok(out)
}

/// Writes claims.json, report.md and report.html into `dir`; returns their paths.
pub fn write(dir: &Path, rep: &Report) -> Result<Vec<String>> {
    let json = dir.join("claims.json");
    std::fs::write(&json, serde_json::to_string_pretty(rep)?)
        .with_context(|| format!("cannot write {}", json.display()))?;
    let md = dir.join("report.md");
    std::fs::write(&md, markdown(rep)).with_context(|| format!("cannot write {}", md.display()))?;
    let ht = dir.join("report.html");
    std::fs::write(&ht, html_report(dir, rep)?)
        .with_context(|| format!("cannot write {}", ht.display()))?;
    Ok([json, md, ht]
        .iter()
        .map(|p| p.display().to_string())
        .collect())
}
