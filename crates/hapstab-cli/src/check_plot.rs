//! The figure of `hapstab check --plot`: four panels, the stable region with the wall marked
//! and the roots of p(z) with the unit circle (Sections III, V), each beside a zoom — onto
//! the wall and the boundary nearest to it, and onto z = 1, where the dominant roots of a
//! haptic loop sit close to the unit circle.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use hapstab::System;
use hapstab::region::StableRegion;
use num_complex::Complex64;

use crate::model::ResolvedLoop;
use crate::output::sig;
use crate::wall_plot::{self, Plane};
use hapstab_plot::{Figure, Grid, Legend, Marker, Series, palette, segment_distance};

/// Side length of each square panel (px).
const PANEL: u32 = 800;

/// The wall zoom spans this many times the wall's distance to the boundary on each side.
const WALL_REACH: f64 = 3.0;

/// The z = 1 zoom holds the roots within this distance of z = 1.
const NEAR_ONE: f64 = 0.5;

/// What the figure shows: the wall in wall units, its verdict, the roots and the radius.
pub struct CheckFigure<'a> {
    /// The wall (a, b) in the family's wall units.
    pub wall: (f64, f64),
    /// "stable", "marginal" or "unstable".
    pub verdict: &'a str,
    /// The roots of p(z).
    pub roots: &'a [Complex64],
    /// Their largest modulus.
    pub spectral_radius: f64,
}

/// Writes the four panels (module doc) to the file(s) that `path` names.
pub fn save(rl: &ResolvedLoop, sys: &System, c: &CheckFigure, path: &Path) -> Result<Vec<PathBuf>> {
    let r = sys.region()?;
    let plane = wall_plot::plane(rl, sys.family());
    let at = plane.point(c.wall.0, c.wall.1);
    let title = format!("Check of the wall {}: {}", plane.describe(at), c.verdict);
    let mut g = Grid::new(title, 2)
        .subtitle(wall_plot::loop_line(rl))
        .panel_size(PANEL, PANEL);
    let mut region = wall_plot::region_figure(&plane, &r, "Stable region");
    wall_plot::mark(
        &mut region,
        at,
        Marker::Square,
        palette::BLACK,
        &format!("wall ({})", c.verdict),
        "wall",
    );
    let roots = wall_plot::roots_figure(
        c.roots,
        &format!(
            "Roots of p(z): spectral radius {}",
            sig(c.spectral_radius, 6)
        ),
    );
    let region = wall_plot::room_for_tags(region);
    g.push(region.clone());
    g.push(roots);
    g.push(wall_zoom(region, &plane, &r, at));
    g.push(one_zoom(c.roots));
    g.save_as(path)
        .with_context(|| format!("--plot {}", path.display()))
}

/// The region zoomed onto the wall: a window around it of [`WALL_REACH`] times its
/// distance to the boundary (measured in shares of the whole region's extent; a wall far
/// outside the region gets a window just reaching the boundary), so that the nearest stretch
/// of boundary shows; the wall keeps its marker, without its tag.
fn wall_zoom(mut fig: Figure, plane: &Plane, r: &StableRegion, at: (f64, f64)) -> Figure {
    let ((x0, x1), (y0, y1)) = fig.ranges();
    let span = (x1 - x0, y1 - y0);
    let edges: Vec<((f64, f64), (f64, f64))> = r
        .polygons
        .iter()
        .flat_map(|p| {
            let pts: Vec<(f64, f64)> = p.vertices.iter().map(|v| plane.point(v.a, v.b)).collect();
            let n = pts.len();
            (0..n).map(move |i| (pts[i], pts[(i + 1) % n]))
        })
        .collect();
    let share = |p: (f64, f64)| ((p.0 - at.0) / span.0, (p.1 - at.1) / span.1);
    let d = edges
        .iter()
        .map(|&(a, b)| segment_distance((0.0, 0.0), share(a), share(b)))
        .fold(f64::INFINITY, f64::min);
    // far from the region, just wide enough to reach the boundary
    let half = match WALL_REACH * d {
        h if h <= 0.5 => h.max(0.01),
        _ => (1.15 * d).min(2.0),
    };
    fig.annotations.clear();
    fig.title = "zoom: the wall and the nearest boundary".to_string();
    fig.legend = Legend::Hidden;
    fig.x_range(at.0 - half * span.0, at.0 + half * span.0)
        .y_range(at.1 - half * span.1, at.1 + half * span.1)
}

/// The z-plane zoomed onto z = 1 (or, with no root within [`NEAR_ONE`] of it, onto the
/// point of the unit circle nearest the dominant root of the upper half plane): a square window that holds the roots
/// within [`NEAR_ONE`] of that point (at least ±0.002), with the stretch of the unit circle
/// through it drawn finely and each root's |z| written beside it (upper half plane).
fn one_zoom(roots: &[Complex64]) -> Figure {
    let one = Complex64::new(1.0, 0.0);
    let near_one = roots.iter().any(|z| (z - one).norm() < NEAR_ONE);
    let dominant = roots
        .iter()
        .filter(|z| z.norm() > 0.0 && z.im >= 0.0)
        .max_by(|a, b| a.norm().total_cmp(&b.norm()));
    let c = match (near_one, dominant) {
        (false, Some(z)) => z / z.norm(),
        _ => one,
    };
    let near: Vec<&Complex64> = roots
        .iter()
        .filter(|z| (*z - c).norm() < NEAR_ONE)
        .collect();
    let reach = near.iter().map(|z| (*z - c).norm()).fold(0.0, f64::max);
    let h = (1.5 * reach).clamp(0.002, NEAR_ONE);
    let at = c.arg();
    let arc = (0..=600).map(|i| {
        let t = at + (i as f64 / 300.0 - 1.0) * 2.0 * h;
        (t.cos(), t.sin())
    });
    let title = match (near_one, near.len()) {
        (true, n) => format!("zoom: the {n} roots near z = 1 (±{})", sig(h, 2)),
        (false, _) => "zoom: the dominant roots and the unit circle".to_string(),
    };
    let mut fig = Figure::new(title)
        .x_label("Re z")
        .y_label("Im z")
        .x_range(c.re - h, c.re + h)
        .y_range(c.im - h, c.im + h)
        .legend(Legend::Hidden)
        .with(Series::line(arc).color(palette::BLACK).width(2))
        .with(
            Series::scatter(near.iter().map(|z| (z.re, z.im)), Marker::Cross)
                .color(palette::VERMILLION),
        );
    for z in near.iter().filter(|z| z.im >= 0.0) {
        let text = format!("|z| = {}", sig(z.norm(), 6));
        fig.annotate(z.re, z.im, format!("   {text}"));
    }
    fig
}
