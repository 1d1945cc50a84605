//! Figures of the wall plane for `boundary`, `kmax` and `check` (`--plot FILE`): the exact
//! stable region (Section V, Figs. 4–6) in K (N/m) and B (Ns/m) for a loop given in physical
//! units, in (α, β) for the paper's normalized loop, with marked walls; and the roots of p(z)
//! in the z-plane with the unit circle (Section III). Drawn with the shared [`crate::plot`].

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use hapstab::AffineFamily;
use hapstab::region::StableRegion;
use num_complex::Complex64;

use crate::model::ResolvedLoop;
use crate::output::{eng, sig};
use crate::plot::{Figure, Grid, Legend, Marker, RGBColor, Series, palette};

/// The wall plane of a loop: physical (K, B) or the paper's normalized (α, β).
pub struct Plane<'a> {
    fam: &'a AffineFamily,
    physical: bool,
}

impl<'a> Plane<'a> {
    /// The plane of a resolved loop (physical unless given in normalized parameters).
    pub fn of(rl: &ResolvedLoop, fam: &'a AffineFamily) -> Self {
        Self {
            fam,
            physical: !rl.normalized,
        }
    }

    /// A point in wall units (a, b) as plotted.
    pub fn point(&self, a: f64, b: f64) -> (f64, f64) {
        if self.physical {
            self.fam.to_physical(a, b)
        } else {
            (a, b)
        }
    }

    /// A wall as plotted, named as the axes are: (K, B) or (α, β).
    pub fn describe(&self, (x, y): (f64, f64)) -> String {
        if self.physical {
            format!("K = {}, B = {}", eng(x, "N/m", 6), eng(y, "Ns/m", 6))
        } else {
            format!("α = {}, β = {}", sig(x, 6), sig(y, 6))
        }
    }

    fn labels(&self) -> (&'static str, &'static str) {
        if self.physical {
            ("virtual stiffness K (N/m)", "virtual damping B (Ns/m)")
        } else {
            ("virtual stiffness α = KT²/m", "virtual damping β = BT/m")
        }
    }
}

/// The stable region as filled polygons on labelled axes; empty regions give an empty
/// panel around the origin.
pub fn region_figure(plane: &Plane, r: &StableRegion, title: &str) -> Figure {
    let (xl, yl) = plane.labels();
    let mut fig = Figure::new(title)
        .x_label(xl)
        .y_label(yl)
        .legend(Legend::UpperRight);
    for (i, p) in r.polygons.iter().enumerate() {
        let pts = p.vertices.iter().map(|v| plane.point(v.alpha, v.beta));
        let s = Series::polygon(pts).color(palette::BLUE);
        fig.add(if i == 0 { s.label("stable (exact)") } else { s });
    }
    if r.polygons.is_empty() {
        fig = fig.x_range(-1.0, 1.0).y_range(-1.0, 1.0);
    }
    fig
}

/// Marks a point with a marker (in the legend as `legend`) and the text `tag` written from
/// the point itself, so that the text's anchor is the point.
pub fn mark(
    fig: &mut Figure,
    at: (f64, f64),
    marker: Marker,
    color: RGBColor,
    legend: &str,
    tag: &str,
) {
    fig.add(
        Series::scatter([at], marker)
            .color(color)
            .size(9)
            .label(legend),
    );
    fig.annotations.push(crate::plot::Annotation {
        at,
        text: format!("   {tag}"),
        color,
    });
}

/// A horizontal dashed line at damping `y` across the figure's data (a band edge).
pub fn damping_line(fig: &mut Figure, y: f64, label: Option<&str>) {
    let ((x0, x1), _) = fig.ranges();
    let s = Series::dashed([(x0, y), (x1, y)])
        .color(palette::GREY)
        .width(2);
    fig.add(match label {
        Some(l) => s.label(l),
        None => s,
    });
}

/// The roots of p(z) and the unit circle, on the same range for Re z and Im z (square panels
/// keep the circle round to a few per cent) that holds every root.
pub fn roots_figure(roots: &[Complex64], title: &str) -> Figure {
    let reach = roots
        .iter()
        .map(|z| z.norm())
        .filter(|r| r.is_finite())
        .fold(1.0_f64, f64::max)
        * 1.15;
    let circle = (0..=360).map(|i| {
        let t = (i as f64).to_radians();
        (t.cos(), t.sin())
    });
    Figure::new(title)
        .x_label("Re z")
        .y_label("Im z")
        .x_range(-reach, reach)
        .y_range(-reach, reach)
        .legend(Legend::UpperRight)
        .with(
            Series::line(circle)
                .color(palette::BLACK)
                .width(2)
                .label("unit circle |z| = 1"),
        )
        .with(
            Series::scatter(roots.iter().map(|z| (z.re, z.im)), Marker::Cross)
                .color(palette::VERMILLION)
                .label(format!("roots of p(z) ({})", roots.len())),
        )
}

/// Share of the x span added on the right when the figure has tags, so that a tag written
/// from a point near the right edge stays readable.
const TAG_ROOM: f64 = 0.12;

/// Fixes the x range with [`TAG_ROOM`] added on the right when the figure has tags.
fn room_for_tags(fig: Figure) -> Figure {
    if fig.annotations.is_empty() || fig.x_range.is_some() {
        return fig;
    }
    let ((x0, x1), _) = fig.ranges();
    fig.x_range(x0, x1 + TAG_ROOM * (x1 - x0))
}

/// Side length of each square panel of a two-panel figure (px).
const PANEL: u32 = 800;

/// Writes `fig` (or `fig` beside `second` as two square panels) to the file(s) that `path`
/// names (SVG or PNG by its extension), naming the path on failure.
pub fn save(fig: Figure, second: Option<Figure>, path: &Path) -> Result<Vec<PathBuf>> {
    let fig = room_for_tags(fig);
    let written = match second {
        None => fig.save_as(path),
        Some(s) => {
            let mut g = Grid::new("", 2).panel_size(PANEL, PANEL);
            g.push(fig).push(s);
            g.save_as(path)
        }
    };
    written.with_context(|| format!("--plot {}", path.display()))
}

/// The written files, for the text output.
pub fn files_text(files: &[PathBuf]) -> String {
    files
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(" and ")
}

/// A figure title: `what`, then the sampling and delay (physical) or γ, δ, d (normalized).
pub fn title(rl: &ResolvedLoop, what: &str) -> String {
    let lp = &rl.lp;
    match (rl.normalized, lp.paper_view()) {
        (true, Some(pp)) => format!(
            "{what}: γ = {}, δ = {}, d = {}",
            sig(pp.gamma, 6),
            sig(pp.delta, 6),
            lp.delay.samples
        ),
        _ => format!(
            "{what}: T = {} ms, t_d = {} ms",
            sig(lp.period * 1e3, 6),
            sig(lp.delay_time() * 1e3, 6)
        ),
    }
}
