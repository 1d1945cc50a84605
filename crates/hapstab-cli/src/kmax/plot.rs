//! `hapstab kmax --plot`: the stable region with K_max marked, the damping band (or the given
//! B) dashed, K_max at B = 0 and the renderable band.

use anyhow::Result;
use hapstab::System;
use hapstab::kmax::RenderableBand;
use hapstab_plot::{Marker, palette};

use super::{DampingRange, KmaxOut, band_text};
use crate::model::ResolvedLoop;
use crate::output::eng;
use crate::wall_plot::{self, Plane};

/// The stable region with K_max marked at its B, the damping band or the given B dashed,
/// and K_max at B = 0.
pub(super) fn figure(
    rl: &ResolvedLoop,
    sys: &System,
    out: &KmaxOut,
    band: DampingRange,
) -> Result<hapstab_plot::Figure> {
    let r = sys.region()?;
    let plane = wall_plot::plane(rl, sys.family());
    let mut fig = wall_plot::region_figure(&plane, &r, "Largest stable stiffness K_max")
        .subtitle(wall_plot::loop_line(rl));
    let mut lines: Vec<f64> = match out.wall_damping {
        Some(b) => vec![b],
        None => [band.lo, band.hi]
            .into_iter()
            .filter(|b| b.is_finite())
            .collect(),
    };
    if let Some(rb) = &out.answer.report.renderable {
        lines.push(rb.b_max);
    }
    let band_lines = lines.len() - usize::from(out.answer.report.renderable.is_some());
    for (i, b) in lines[..band_lines].iter().enumerate() {
        let label = match out.wall_damping {
            Some(_) => "the given B".to_string(),
            None => format!("damping range {}", band_text(band)),
        };
        wall_plot::damping_line(&mut fig, *b, (i == 0).then_some(label.as_str()));
    }
    // the renderable band's top after the band's lines (each spans the ranges drawn so far)
    if let Some(rb) = &out.answer.report.renderable {
        mark_renderable(&mut fig, rb, &plane);
    }
    // a tag on a damping line is lifted off it (the marker stays at its point)
    let on_line = |b: f64| {
        lines
            .iter()
            .any(|l| (l - b).abs() <= 1e-9 * l.abs().max(1.0))
    };
    let tag = |fig: &mut hapstab_plot::Figure, at: (f64, f64), style, legend: &str, text| {
        if on_line(at.1) {
            wall_plot::mark_above(fig, at, style, legend, text)
        } else {
            wall_plot::mark(fig, at, style.0, style.1, legend, text)
        }
    };
    if let Some(k) = out.answer.report.k_max_at_zero_damping {
        tag(
            &mut fig,
            (k, 0.0),
            (Marker::Triangle, palette::GREEN),
            &format!("K_max at B = 0: {}", eng(k, "N/m", 6)),
            "B = 0",
        );
    }
    let b_best = out.answer.report.b_at_k_max.or(out.wall_damping);
    if let (Some(k), Some(b)) = (out.answer.report.k_max, b_best) {
        tag(
            &mut fig,
            (k, b),
            (Marker::Circle, palette::VERMILLION),
            &format!("K_max: {}", plane.describe((k, b))),
            "K_max",
        );
    }
    Ok(fig)
}

/// The renderable band's top B_r dashed, and K_max over the band marked above it.
fn mark_renderable(fig: &mut hapstab_plot::Figure, rb: &RenderableBand, plane: &Plane) {
    let label = format!("renderable band 0 ≤ B ≤ {}", eng(rb.b_max, "Ns/m", 6));
    wall_plot::damping_line(fig, rb.b_max, Some(label.as_str()));
    if let (Some(k), Some(b)) = (rb.k_max, rb.b_at_k_max) {
        wall_plot::mark_above(
            fig,
            (k, b),
            (Marker::Square, palette::PURPLE),
            &format!("K_max over the renderable band: {}", plane.describe((k, b))),
            "",
        );
    }
}
