//! The figure of a boundary search: the exact linear stable region and the simulated boundary,
//! with the points the scan could not decide; in K and B for physical input, in α and β (or a
//! loop's wall units a, b) for normalized input.

use hapstab::Normalized;
use hapstab::boundary::WallPoint;
use hapstab::simulation::EmpiricalPoint;

use super::run_args::RunSettings;
use super::{Units, describe_effects};
use hapstab_plot::{Figure, Legend, Marker, Series, palette};

/// The plane of the figure: N/m per unit of α (or a) and Ns/m per unit of β (or b) for a
/// physical figure, none for a normalized one.
#[derive(Debug, Clone, Copy)]
pub(super) struct Plane {
    pub(super) per_unit: Option<(f64, f64)>,
}

impl Plane {
    fn at(&self, a: f64, b: f64) -> (f64, f64) {
        self.per_unit.map_or((a, b), |(k, d)| (a * k, b * d))
    }
}

/// Title (with the simulated effects) and axis labels.
fn labels(
    paper: Option<&Normalized>,
    plane: Plane,
    effects: &str,
) -> (String, &'static str, &'static str) {
    let title = match effects.strip_prefix("none") {
        Some(_) => "Simulated vs exact linear boundary".to_string(),
        None => format!("Simulated ({effects}) vs exact linear boundary"),
    };
    match (paper, plane.per_unit) {
        (_, Some(_)) => (
            title,
            "virtual stiffness K (N/m)",
            "virtual damping B (Ns/m)",
        ),
        (Some(_), None) => (
            title,
            "virtual stiffness α = KT²/m",
            "virtual damping β = BT/m",
        ),
        (None, None) => (
            title,
            "wall stiffness a = K/k_u",
            "wall damping b = B/(k_u·T)",
        ),
    }
}

/// The figure of the search (module doc).
pub(super) fn boundary_plot(
    region: &hapstab::region::StableRegion,
    points: &[EmpiricalPoint],
    paper: Option<&Normalized>,
    plane: Plane,
    s: &RunSettings,
    units: Units,
) -> Figure {
    let (title, xl, yl) = labels(paper, plane, &describe_effects(s, units.force()));
    let mut f = Figure::new(title)
        .x_label(xl)
        .y_label(yl)
        .legend(Legend::Below);
    for (i, poly) in region.polygons.iter().enumerate() {
        let pts = poly.vertices.iter().map(|v: &WallPoint| plane.at(v.a, v.b));
        let mut s = Series::polygon(pts).color(palette::BLUE).alpha(0.18);
        if i == 0 {
            s = s.label("exact linear stable region");
        }
        f.add(s);
    }
    add_simulated(&mut f, points, plane, s, units);
    f
}

/// The simulated boundary and the points it could not settle.
fn add_simulated(
    f: &mut Figure,
    points: &[EmpiricalPoint],
    plane: Plane,
    s: &RunSettings,
    units: Units,
) {
    let pick = |keep: &dyn Fn(&EmpiricalPoint) -> Option<f64>| -> Vec<(f64, f64)> {
        points
            .iter()
            .filter_map(|p| keep(p).map(|a| plane.at(a, p.b)))
            .collect()
    };
    let found = pick(&|p| p.a_simulated.filter(|_| !p.censored));
    let censored = pick(&|p| p.a_simulated.filter(|_| p.censored));
    let none = pick(&|p| p.a_unstable.filter(|_| p.a_simulated.is_none()));
    let inconclusive = pick(&|p| p.inconclusive.map(|i| i.a));
    let mut curve: Vec<(f64, f64)> = points
        .iter()
        .map(|p| match (p.a_simulated, p.censored) {
            (Some(a), false) => plane.at(a, p.b),
            _ => (f64::NAN, plane.at(0.0, p.b).1),
        })
        .collect();
    curve.sort_by(|a, b| a.1.total_cmp(&b.1));
    f.add(Series::line(curve).color(palette::VERMILLION).width(2));
    let label = if describe_effects(s, units.force()).starts_with("none") {
        "simulated (linear)"
    } else {
        "simulated boundary"
    };
    f.add(
        Series::scatter(found, Marker::Circle)
            .color(palette::VERMILLION)
            .label(label),
    );
    let first = if plane.per_unit.is_some() {
        "unstable at the first scanned K"
    } else {
        "unstable at first scan α"
    };
    for (pts, marker, color, hollow, text) in [
        (
            censored,
            Marker::Triangle,
            palette::ORANGE,
            false,
            "stable up to scan end",
        ),
        (none, Marker::Cross, palette::BLACK, false, first),
        (
            inconclusive,
            Marker::Triangle,
            palette::GREY,
            true,
            "left the wall or undecided: no verdict",
        ),
    ] {
        if pts.is_empty() {
            continue;
        }
        let mut series = Series::scatter(pts, marker).color(color).label(text);
        if hollow {
            series = series.hollow();
        }
        f.add(series);
    }
}
