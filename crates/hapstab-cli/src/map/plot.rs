//! The `--plot` heatmap of `hapstab map`: stable cells, or the spectral radius in classes.

use hapstab::map::AxisRange;
use hapstab_plot::{Figure, Legend, RGBColor, Series, palette};

use super::Values;
use super::axes::{Grid, axis_title};

/// Colour classes of a radius heatmap: (upper bound of ρ, colour, legend entry).
pub(super) fn radius_classes() -> [(f64, RGBColor, &'static str); 4] {
    [
        (0.99, palette::BLUE, "ρ < 0.99"),
        (1.0, palette::SKY, "0.99 ≤ ρ < 1"),
        (1.01, palette::ORANGE, "1 ≤ ρ < 1.01"),
        (f64::INFINITY, palette::VERMILLION, "ρ ≥ 1.01"),
    ]
}

/// The points of class `c` (by `class_of`, a function of the point's index) as rectangles
/// merged into runs along each row: a few rectangles per row instead of one per point.
pub(super) fn runs(
    x: &AxisRange,
    y: &AxisRange,
    class_of: &dyn Fn(usize) -> Option<usize>,
    c: usize,
) -> Vec<((f64, f64), (f64, f64))> {
    let (hx, hy) = (x.step() / 2.0, y.step() / 2.0);
    let mut out = Vec::new();
    for iy in 0..y.n {
        let yv = y.value(iy);
        let mut ix = 0;
        while ix < x.n {
            if class_of(iy * x.n + ix) != Some(c) {
                ix += 1;
                continue;
            }
            let start = ix;
            while ix < x.n && class_of(iy * x.n + ix) == Some(c) {
                ix += 1;
            }
            out.push((
                (x.value(start) - hx, yv - hy),
                (x.value(ix - 1) + hx, yv + hy),
            ));
        }
    }
    out
}

/// The heatmap of a map: stable points (or the spectral radius in classes) as filled cells.
pub(super) fn heatmap(x: Grid, y: Grid, v: &Values) -> Figure {
    let (xr, yr) = (&x.range, &y.range);
    let (hx, hy) = (xr.step() / 2.0, yr.step() / 2.0);
    let mut fig = Figure::new("Stability map")
        .subtitle(&v.loop_line)
        .x_label(axis_title(x.name))
        .y_label(axis_title(y.name))
        .x_range(xr.lo - hx, xr.hi + hx)
        .y_range(yr.lo - hy, yr.hi + hy)
        .legend(Legend::Below);
    match &v.radius {
        None => {
            let stable = |k: usize| v.stable[k].then_some(0);
            let cells = runs(xr, yr, &stable, 0);
            add_cells(&mut fig, cells, palette::BLUE, "stable (Schur–Cohn)");
        }
        Some(r) => {
            let classes = radius_classes();
            let class_of = |k: usize| classes.iter().position(|(hi, _, _)| r[k] < *hi);
            for (c, (_, color, label)) in classes.iter().enumerate() {
                add_cells(&mut fig, runs(xr, yr, &class_of, c), *color, label);
            }
        }
    }
    fig
}

/// Adds rectangles as opaque, unoutlined polygons of one colour, the first one labelled.
pub(super) fn add_cells(
    fig: &mut Figure,
    rects: Vec<((f64, f64), (f64, f64))>,
    color: RGBColor,
    label: &str,
) {
    for (i, ((x0, y0), (x1, y1))) in rects.into_iter().enumerate() {
        let cell = Series::polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
            .color(color)
            .alpha(1.0)
            .no_outline();
        fig.add(if i == 0 { cell.label(label) } else { cell });
    }
}
