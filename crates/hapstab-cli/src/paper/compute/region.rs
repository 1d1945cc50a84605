//! One stable region of the paper's loop, ready for drawing and tabulating.

use anyhow::{Context, Result};
use hapstab::paper::NormalizedFamily;
use hapstab::region::stable_region;
use serde::Serialize;

use super::Key;

/// A stable region ready for drawing and tabulating.
#[derive(Debug, Clone, Serialize)]
pub struct Region {
    /// (γ, δ, d).
    pub key: Key,
    /// Closed outlines (first vertex not repeated), α horizontal, β vertical.
    #[serde(skip)]
    pub rings: Vec<Vec<(f64, f64)>>,
    /// Number of outline vertices.
    pub vertices: usize,
    /// Largest stable α.
    pub alpha_max: f64,
    /// β at α_max.
    pub beta_at_alpha_max: f64,
    /// Area in the (α, β)-plane.
    pub area: f64,
    /// Smallest α of the outline.
    pub alpha_min: f64,
    /// Smallest β of the outline.
    pub beta_min: f64,
    /// Largest β of the outline.
    pub beta_max: f64,
}

/// (α_min, β_min, β_max) of the outline (infinite when it is empty).
pub(super) fn extent(rings: &[Vec<(f64, f64)>]) -> (f64, f64, f64) {
    hapstab::extent::Extent::of(rings.iter().flatten().copied())
        .map_or((f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY), |e| {
            (e.x_min, e.y_min, e.y_max)
        })
}

/// The exact stable region of one key ([`stable_region`]'s polygons).
pub fn region(key: Key) -> Result<Region> {
    let fam = NormalizedFamily::new(key.plant()?, key.d)?;
    let r = stable_region(&fam).with_context(|| format!("stable region of {key:?}"))?;
    let rings: Vec<Vec<(f64, f64)>> = r
        .polygons
        .iter()
        .map(|p| p.vertices.iter().map(|v| (v.a, v.b)).collect())
        .collect();
    let (alpha_min, beta_min, beta_max) = extent(&rings);
    Ok(Region {
        key,
        vertices: rings.iter().map(Vec::len).sum(),
        rings,
        alpha_max: r.a_max,
        beta_at_alpha_max: r.b_at_a_max,
        area: r.area,
        alpha_min,
        beta_min,
        beta_max,
    })
}
