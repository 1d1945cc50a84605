//! The figure of a boundary search: the exact linear stable region and the simulated boundary,
//! with the points the scan could not decide.

use hapstab::Normalized;
use hapstab::boundary::AlphaBeta;
use hapstab::simulation::EmpiricalPoint;

use super::run_args::RunSettings;
use super::{Units, describe_effects};
use crate::output::sig;
use crate::plot::{Figure, Legend, Marker, Series, palette};

pub(super) fn boundary_plot(
    region: &hapstab::region::StableRegion,
    points: &[EmpiricalPoint],
    paper: Option<&Normalized>,
    s: &RunSettings,
    units: Units,
) -> Figure {
    let (title, xl, yl) = match paper {
        Some(p) => (
            format!(
                "Simulated vs exact linear boundary (γ = {}, δ = {}, d = {})",
                sig(p.gamma, 3),
                sig(p.delta, 3),
                p.d
            ),
            "virtual stiffness α = KT²/m",
            "virtual damping β = BT/m",
        ),
        None => (
            "Simulated vs exact linear boundary".to_string(),
            "wall stiffness a = K/k_u",
            "wall damping b = B/(k_u·T)",
        ),
    };
    let mut f = Figure::new(title)
        .x_label(xl)
        .y_label(yl)
        .legend(Legend::UpperRight);
    for (i, poly) in region.polygons.iter().enumerate() {
        let pts = poly.vertices.iter().map(|v: &AlphaBeta| (v.alpha, v.beta));
        let mut s = Series::polygon(pts).color(palette::BLUE).alpha(0.18);
        if i == 0 {
            s = s.label("exact linear stable region");
        }
        f.add(s);
    }
    let found: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| !p.censored)
        .filter_map(|p| p.alpha_simulated.map(|a| (a, p.beta)))
        .collect();
    let censored: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.censored)
        .filter_map(|p| p.alpha_simulated.map(|a| (a, p.beta)))
        .collect();
    let none: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.alpha_simulated.is_none())
        .filter_map(|p| p.alpha_unstable.map(|a| (a, p.beta)))
        .collect();
    let mut curve: Vec<(f64, f64)> = points
        .iter()
        .map(|p| match (p.alpha_simulated, p.censored) {
            (Some(a), false) => (a, p.beta),
            _ => (f64::NAN, p.beta),
        })
        .collect();
    curve.sort_by(|a, b| a.1.total_cmp(&b.1));
    f.add(Series::line(curve).color(palette::VERMILLION).width(2));
    let effects = describe_effects(s, units.force());
    let label = if effects.starts_with("none") {
        "simulated (linear)".to_string()
    } else {
        "simulated boundary".to_string()
    };
    f.add(
        Series::scatter(found, Marker::Circle)
            .color(palette::VERMILLION)
            .label(label),
    );
    if !censored.is_empty() {
        f.add(
            Series::scatter(censored, Marker::Triangle)
                .color(palette::ORANGE)
                .label("stable up to scan end"),
        );
    }
    if !none.is_empty() {
        f.add(
            Series::scatter(none, Marker::Cross)
                .color(palette::BLACK)
                .label("unstable at first scan α"),
        );
    }
    let inconclusive: Vec<(f64, f64)> = points
        .iter()
        .filter_map(|p| p.inconclusive.map(|i| (i.alpha, p.beta)))
        .collect();
    if !inconclusive.is_empty() {
        f.add(
            Series::scatter(inconclusive, Marker::Triangle)
                .color(palette::GREY)
                .hollow()
                .label("left the wall or undecided: no verdict"),
        );
    }
    f
}
