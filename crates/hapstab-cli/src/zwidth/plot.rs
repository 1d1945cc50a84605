//! The figure of `hapstab zwidth`: stable and passive regions of every loop, then zoomed
//! onto the passive ones.

use hapstab::answer::ZwidthLoop as LoopOut;
use hapstab::params::Wall;
use hapstab_plot::{Figure, Grid, Legend, Marker, Series, palette};

pub(super) fn points(v: &[Wall]) -> Vec<(f64, f64)> {
    v.iter().map(|w| (w.stiffness, w.damping)).collect()
}

/// The extent (K0, K1, B0, B1) of a set of polygons.
pub(super) type Extent = (f64, f64, f64, f64);

pub(super) fn extent<'a>(polys: impl IntoIterator<Item = &'a Vec<Wall>>) -> Option<Extent> {
    let walls = polys.into_iter().flatten();
    hapstab::extent::Extent::of(walls.map(|w| (w.stiffness, w.damping)))
        .map(|e| (e.x_min, e.x_max, e.y_min, e.y_max))
}

/// Two panels: every loop's stable region (light) and passive region (dark) with K_max marked
/// and the linear condition (22) of the first loop dashed; then the same zoomed onto the
/// passive regions, which are small beside the stable ones.
pub(super) fn figure(out: &[LoopOut], subtitle: &str) -> Grid {
    let stable = extent(out.iter().flat_map(|o| o.zwidth.stable.iter()));
    let passive = extent(
        out.iter()
            .filter_map(|o| o.zwidth.passive.as_ref())
            .map(|p| &p.vertices)
            .filter(|v| !v.is_empty()),
    );
    let mut g = Grid::new("Z-width: stable (light) and passive (dark) walls", 2).subtitle(subtitle);
    let whole = stable.or(passive).unwrap_or((0.0, 1.0, -1.0, 1.0));
    g.push(panel(out, "all stable walls", pad(whole), Legend::Below));
    if let Some(p) = passive {
        let (k0, k1, b0, b1) = p;
        let (w, h) = (k1 - k0, b1 - b0);
        let zoom = (k0 - 0.1 * w, k1 + 0.6 * w, b0 - 0.3 * h, b1 + 0.3 * h);
        g.push(panel(
            out,
            "zoom: the passive regions",
            zoom,
            Legend::Hidden,
        ));
    }
    g
}

pub(super) fn pad((k0, k1, b0, b1): Extent) -> Extent {
    let (w, h) = ((k1 - k0).max(1e-9), (b1 - b0).max(1e-9));
    (k0 - 0.03 * w, k1 + 0.06 * w, b0 - 0.05 * h, b1 + 0.05 * h)
}

pub(super) fn panel(
    out: &[LoopOut],
    title: &str,
    (k0, k1, b0, b1): Extent,
    legend: Legend,
) -> Figure {
    let mut f = Figure::new(title)
        .x_label("virtual stiffness K (N/m)")
        .y_label("virtual damping B (Ns/m)")
        .legend(legend)
        .x_range(k0, k1)
        .y_range(b0, b1);
    let mut rings = Vec::new();
    // the zoom shows the passive regions: the stable fills behind them are fainter
    let stable_alpha = if legend == Legend::Hidden { 0.05 } else { 0.12 };
    for (i, o) in out.iter().enumerate() {
        let c = palette::CYCLE[i % palette::CYCLE.len()];
        for (j, poly) in o.zwidth.stable.iter().enumerate() {
            let s = Series::polygon(points(poly))
                .color(c)
                .alpha(stable_alpha)
                .width(2);
            f.add(if j == 0 {
                s.label(format!("stable: {}", o.label))
            } else {
                s
            });
        }
        if let Some(p) = o.zwidth.passive.as_ref().filter(|p| !p.vertices.is_empty()) {
            f.add(
                Series::polygon(points(&p.vertices))
                    .color(c)
                    .alpha(0.22)
                    .width(3)
                    .label(format!("passive: {}", o.label)),
            );
            let mut ring = points(&p.vertices);
            ring.extend(ring.first().copied());
            rings.push(Series::line(ring).color(c).width(3));
        }
        if let Some(k) = o.zwidth.k_max {
            f.add(Series::scatter([(k.stiffness, k.damping)], Marker::Circle).color(c));
        }
    }
    // each passive region's outline over every fill, so that overlapping ones stay apart
    for r in rings {
        f.add(r);
    }
    if let Some(l) = out.first().and_then(|o| o.zwidth.linear) {
        let line = [b0, b1].map(|b| (l.k_at(b), b));
        f.add(
            Series::dashed(line)
                .color(palette::BLACK)
                .width(2)
                .label("linear condition (22)"),
        );
    }
    f
}
