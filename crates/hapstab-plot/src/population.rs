//! The figure of `hapstab population --plot`: P(stable) against K with Wilson's 95 % band,
//! and the fraction of operators for whom the wall is not stable on a log scale, where the
//! 1 % and 0.1 % levels and their stiffnesses are read.

use hapstab::population::StabilityProbability;

use crate::text::eng;
use crate::{Figure, Grid, Legend, Marker, Series, palette};

/// Both panels, titled with the damping and subtitled with the loop.
pub fn figure(r: &StabilityProbability, subtitle: &str) -> Grid {
    let title = format!(
        "P(stable) over {} operators at B = {}",
        r.samples,
        eng(r.wall_damping, "Ns/m", 6)
    );
    let mut g = Grid::new(title, 1).panel_size(1000, 520).subtitle(subtitle);
    g.push(probability_panel(r));
    g.push(failure_panel(r));
    g
}

fn curve(k: &[f64], p: &[f64], f: impl Fn(f64) -> f64) -> Vec<(f64, f64)> {
    k.iter().zip(p).map(|(&k, &p)| (k, f(p))).collect()
}

fn probability_panel(r: &StabilityProbability) -> Figure {
    let mut f = Figure::new("P(stable) against the wall stiffness")
        .x_label("virtual stiffness K (N/m)")
        .y_label("P(stable)")
        .y_range(0.0, 1.02)
        .legend(Legend::Below);
    f.add(
        Series::dashed(curve(&r.k, &r.probability_lo, |p| p))
            .color(palette::SKY)
            .label("95 % interval (Wilson)"),
    );
    f.add(Series::dashed(curve(&r.k, &r.probability_hi, |p| p)).color(palette::SKY));
    f.add(
        Series::line(curve(&r.k, &r.probability, |p| p))
            .color(palette::BLUE)
            .width(2)
            .label("P(stable): operators whose stable K interval holds K"),
    );
    f
}

/// 1 − P(stable) on a log scale, with each level's K marked; a zero (no operator drawn
/// unstable) is drawn at a tenth of one operator's share, which the legend says.
fn failure_panel(r: &StabilityProbability) -> Figure {
    let floor = 0.1 / r.samples as f64;
    let log = |p: f64| (1.0 - p).max(floor).log10();
    let mut f = Figure::new("operators for whom the wall is not stable (log scale)")
        .x_label("virtual stiffness K (N/m)")
        .y_label("1 − P(stable)")
        .y_log10()
        .legend(Legend::Below);
    f.add(
        Series::dashed(curve(&r.k, &r.probability_hi, log))
            .color(palette::ORANGE)
            .label("95 % interval (Wilson)"),
    );
    f.add(Series::dashed(curve(&r.k, &r.probability_lo, log)).color(palette::ORANGE));
    f.add(
        Series::line(curve(&r.k, &r.probability, log))
            .color(palette::VERMILLION)
            .width(2)
            .label(format!("1 − P(stable) (zero drawn at {floor:.0e})")),
    );
    let markers = [Marker::Circle, Marker::Square, Marker::Triangle];
    for (i, l) in r.levels.iter().enumerate() {
        let Some(k) = l.k else { continue };
        let at = (k, (1.0 - l.level).log10());
        f.add(
            Series::scatter([at], markers[i % markers.len()])
                .color(palette::BLACK)
                .size(6)
                .label(format!(
                    "P(stable) ≥ {} up to K = {}",
                    l.level,
                    eng(k, "N/m", 6)
                )),
        );
    }
    f
}
