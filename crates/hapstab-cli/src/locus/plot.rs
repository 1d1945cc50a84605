//! The figure of `hapstab locus`: the roots of p(z) in the z-plane with the unit circle, the
//! crossing at K_max marked, and a zoom onto the crossing.

use hapstab::locus::RootLocus;
use hapstab_plot::{Annotation, Figure, Grid, Legend, Marker, Series, palette};
use num_complex::Complex64;

use crate::output::sig;

/// Largest |z| shown: the locus beyond it is clipped.
pub(super) const REACH_CAP: f64 = 3.0;

/// Side of each square panel (px; a little wider than tall for the y-axis labels).
pub(super) const PANEL: (u32, u32) = (840, 800);

/// The zoom panel holds the moving roots within this distance of the crossing.
pub(super) const ZOOM_RADIUS: f64 = 0.5;

/// The z-plane with every branch, and beside it a zoom on the crossing at K_max.
pub(super) fn figure(l: &RootLocus, title: &str, subtitle: &str) -> Grid {
    let reach = l
        .spectral_radius
        .iter()
        .copied()
        .filter(|r| r.is_finite())
        .fold(1.0_f64, f64::max)
        .min(REACH_CAP)
        * 1.12;
    let full = [-reach, reach, -reach, reach];
    let zoom = zoom_box(l);
    let mut g = Grid::new(title, if zoom.is_some() { 2 } else { 1 })
        .subtitle(subtitle)
        .panel_size(PANEL.0, PANEL.1);
    g.push(panel(l, full, "z-plane", true));
    if let Some(b) = zoom {
        g.push(panel(l, b, "near the crossing at K_max", false));
    }
    g
}

/// A square window around the crossing holding the branches that move within
/// [`ZOOM_RADIUS`] of it (None without a crossing).
pub(super) fn zoom_box(l: &RootLocus) -> Option<[f64; 4]> {
    let c = l.crossing?;
    let c = Complex64::new(c.re, c.im.abs());
    let branches = l.roots.first().map_or(0, Vec::len);
    let (mut x0, mut x1, mut y0, mut y1) = (c.re, c.re, -c.im, c.im);
    for j in 0..branches {
        let path: Vec<Complex64> = l.roots.iter().filter_map(|r| r.get(j).copied()).collect();
        let moves = path.iter().any(|z| (z - path[0]).norm() > 1e-6);
        for z in path
            .iter()
            .filter(|z| moves && (*z - c).norm().min((z.conj() - c).norm()) < ZOOM_RADIUS)
        {
            (x0, x1, y0, y1) = (x0.min(z.re), x1.max(z.re), y0.min(z.im), y1.max(z.im));
        }
    }
    let half = 0.5 * (x1 - x0).max(y1 - y0).max(1e-3) * 1.15;
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    Some([cx - half, cx + half, cy - half, cy + half])
}

/// One panel: the unit circle, each branch as a line, the roots at K = 0 and the roots on
/// the circle at K_max, in the window [x0, x1, y0, y1].
pub(super) fn panel(l: &RootLocus, w: [f64; 4], title: &str, legend: bool) -> Figure {
    let mut fig = Figure::new(title)
        .x_label("Re z")
        .y_label("Im z")
        .x_range(w[0], w[1])
        .y_range(w[2], w[3])
        .legend(if legend {
            Legend::Below
        } else {
            Legend::Hidden
        });
    let circle = (0..=3600).map(|i| {
        let t = (i as f64 / 10.0).to_radians();
        (t.cos(), t.sin())
    });
    fig.add(
        Series::dashed(circle)
            .color(palette::GREY)
            .width(2)
            .label("unit circle |z| = 1"),
    );
    let branches = l.roots.first().map_or(0, Vec::len);
    for j in 0..branches {
        let pts = l
            .roots
            .iter()
            .filter_map(|r| r.get(j))
            .map(|z| (z.re, z.im));
        let s = Series::line(pts).color(palette::BLUE).width(2);
        fig.add(if j == 0 {
            s.label(format!(
                "roots of p(z), K = 0 … {} N/m",
                sig(l.stiffness.last().copied().unwrap_or(f64::NAN), 4)
            ))
        } else {
            s
        });
    }
    if let Some(r0) = l.roots.first() {
        fig.add(
            Series::scatter(r0.iter().map(|z| (z.re, z.im)), Marker::Cross)
                .color(palette::BLACK)
                .label("K = 0"),
        );
    }
    mark_crossing(&mut fig, l, w);
    fig
}

/// The roots on the unit circle at K_max, with the value written beside the upper one.
pub(super) fn mark_crossing(fig: &mut Figure, l: &RootLocus, w: [f64; 4]) {
    let (Some(i), Some(k)) = (l.k_max_index, l.k_max) else {
        return;
    };
    let on: Vec<(f64, f64)> = l.roots[i]
        .iter()
        .filter(|z| (z.norm() - 1.0).abs() < 1e-6)
        .map(|z| (z.re, z.im))
        .collect();
    let f = l.crossing_frequency_hz.unwrap_or(f64::NAN);
    fig.add(
        Series::scatter(on.clone(), Marker::Circle)
            .color(palette::VERMILLION)
            .size(9)
            .label(format!("K_max = {} N/m ({} Hz)", sig(k, 6), sig(f, 4))),
    );
    if let Some(&at) = on.iter().max_by(|x, y| x.1.total_cmp(&y.1)) {
        let text = format!("K_max = {} N/m   ", sig(k, 6));
        // written to the left of the point when it lies in the right half
        let span = w[1] - w[0];
        let x = if at.0 > 0.5 * (w[0] + w[1]) {
            at.0 - text.chars().count() as f64 * 12.0 / 640.0 * span
        } else {
            at.0
        };
        fig.annotations.push(Annotation {
            at: (x, at.1 + 0.04 * span),
            text,
            color: palette::VERMILLION,
            lift: false,
        });
    }
}
