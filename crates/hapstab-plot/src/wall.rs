//! Figures of the wall plane (the command line's `boundary`, `kmax` and `check --plot FILE`):
//! the exact stable region (Section V, Figs. 4–6) in K (N/m) and B (Ns/m) for a loop given in
//! physical units, in (α, β) for the paper's normalized loop, with marked walls; the roots of
//! p(z) in the z-plane with the unit circle (Section III); and the loop a figure shows, in one
//! line for its subtitle.

use hapstab::AffineFamily;
use hapstab::model::Loop;
use hapstab::region::StableRegion;
use num_complex::Complex64;

use crate::text::{eng, sig};
use crate::{Annotation, Figure, Legend, Marker, RGBColor, Series, palette};

/// The wall plane of a loop: physical (K, B) or the paper's normalized (α, β).
pub struct Plane<'a> {
    fam: &'a AffineFamily,
    physical: bool,
}

impl<'a> Plane<'a> {
    /// The plane of a loop's family: physical (K, B), or the paper's normalized (α, β) for
    /// a loop given in normalized parameters.
    pub fn new(fam: &'a AffineFamily, physical: bool) -> Self {
        Self { fam, physical }
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
        .legend(Legend::Below);
    for (i, p) in r.polygons.iter().enumerate() {
        let pts = p.vertices.iter().map(|v| plane.point(v.a, v.b));
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
    fig.annotations.push(Annotation {
        at,
        text: format!("   {tag}"),
        color,
        lift: false,
    });
}

/// [`mark`] with the tag written just above the point (the marker stays on it), off a line
/// drawn through the point.
pub fn mark_above(
    fig: &mut Figure,
    at: (f64, f64),
    (marker, color): (Marker, RGBColor),
    legend: &str,
    tag: &str,
) {
    mark(fig, at, marker, color, legend, tag);
    if let Some(a) = fig.annotations.last_mut() {
        a.lift = true;
    }
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
        .legend(Legend::Below)
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

/// Fixes the x range with `TAG_ROOM` (12 % of the x span) added on the right when the figure
/// has tags.
pub fn room_for_tags(fig: Figure) -> Figure {
    if fig.annotations.is_empty() || fig.x_range.is_some() {
        return fig;
    }
    let ((x0, x1), _) = fig.ranges();
    fig.x_range(x0, x1 + TAG_ROOM * (x1 - x0))
}

/// A part of the loop that [`loop_line_without`] can leave out (a figure whose axis varies
/// it, or that compares it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// The plant (device, arm, or the effective m, b, k).
    Plant,
    /// The actuator lag τ.
    Lag,
    /// The velocity estimator.
    Estimator,
    /// The sampling period T.
    Period,
    /// The delay t_d (or d).
    Delay,
}

/// The loop a figure shows, in one short line for its subtitle: the plant (the device's mass
/// and the arm, or m, b, k of eq. (1), or γ, δ of the paper's normalized loop), the actuator
/// lag, the velocity estimator, the sampling period T and the delay t_d (d when normalized),
/// e.g. "device 0.1 kg + arm, backward difference, T = 1 ms, t_d = 0".
/// `normalized`: the loop was given in the paper's normalized parameters.
pub fn loop_line(lp: &Loop, normalized: bool) -> String {
    loop_line_without(lp, normalized, &[])
}

/// [`loop_line`] without the parts in `omit`.
pub fn loop_line_without(lp: &Loop, normalized: bool, omit: &[Part]) -> String {
    let keep = |p: Part| !omit.contains(&p);
    let paper = lp.paper_view().filter(|_| normalized);
    let mut parts = Vec::new();
    if keep(Part::Plant) {
        parts.push(match paper {
            Some(pp) => format!("γ = {}, δ = {}", sig(pp.gamma, 4), sig(pp.delta, 4)),
            None => plant_words(&lp.plant),
        });
    }
    if keep(Part::Lag) && lp.plant.force_lag > 0.0 {
        parts.push(format!("lag τ = {}", eng(lp.plant.force_lag, "s", 4)));
    }
    if keep(Part::Estimator) {
        parts.push(estimator_words(&lp.velocity));
    }
    if paper.is_some() {
        if keep(Part::Delay) {
            parts.push(format!("d = {}", lp.delay.samples));
        }
    } else {
        if keep(Part::Period) {
            parts.push(format!("T = {}", eng(lp.period, "s", 4)));
        }
        if keep(Part::Delay) {
            let td = lp.delay_time();
            parts.push(match td {
                0.0 => "t_d = 0".to_string(),
                _ => format!("t_d = {}", eng(td, "s", 4)),
            });
        }
    }
    parts.join(", ")
}

/// The plant in a few words: "device 0.1 kg + arm" (the typical arm) or "+ arm 2 kg", the
/// effective "m = 1.1 kg, b = 7.5 Ns/m" (k when not 0), "two-mass device", or "plant P(s)".
fn plant_words(p: &hapstab::model::Plant) -> String {
    use hapstab::model::PlantModel as M;
    match (&p.model, p.operator) {
        (M::MassSpringDamper(e), Some(arm)) => {
            let device = format!("{} kg", sig(e.mass - arm.mass, 4));
            if arm == hapstab::params::Arm::TYPICAL {
                format!("device {device} + arm")
            } else {
                format!("device {device} + arm {} kg", sig(arm.mass, 4))
            }
        }
        (M::MassSpringDamper(e), None) => {
            let mut s = format!(
                "m = {} kg, b = {}",
                sig(e.mass, 4),
                eng(e.damping, "Ns/m", 4)
            );
            if e.stiffness != 0.0 {
                s += &format!(", k = {}", eng(e.stiffness, "N/m", 4));
            }
            s
        }
        (M::TwoMass(t), _) if t.arm.mass > 0.0 => "two-mass device + arm".to_string(),
        (M::TwoMass(_), _) => "two-mass device".to_string(),
        (M::TransferFunction { .. }, _) => "plant P(s)".to_string(),
    }
}

/// The velocity estimator in words: "backward difference", "low-pass 100 Hz", "average of
/// 15 samples", "Butterworth order 2, 50 Hz" (Bessel, critically damped alike), "IIR filter".
fn estimator_words(v: &hapstab::model::VelocityEstimator) -> String {
    use hapstab::model::VelocityEstimator as V;
    match v {
        V::Backward => "backward difference".to_string(),
        V::LowPass { cutoff_hz } => format!("low-pass {} Hz", sig(*cutoff_hz, 4)),
        V::Average { samples } => format!("average of {samples} samples"),
        V::Butterworth { order, cutoff_hz } => {
            format!("Butterworth order {order}, {} Hz", sig(*cutoff_hz, 4))
        }
        V::Bessel { order, cutoff_hz } => {
            format!("Bessel order {order}, {} Hz", sig(*cutoff_hz, 4))
        }
        V::CriticallyDamped { order, cutoff_hz } => {
            format!("critically damped order {order}, {} Hz", sig(*cutoff_hz, 4))
        }
        V::Iir { .. } => "IIR velocity filter".to_string(),
    }
}
