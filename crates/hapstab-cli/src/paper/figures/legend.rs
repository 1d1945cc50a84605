//! Legend placement of the paper's figures: a corner where the legend covers nothing, else
//! the range widened to make room.

use hapstab_plot::{Figure, Kind, Legend};

pub(super) fn inside(poly: &[(f64, f64)], p: (f64, f64)) -> bool {
    let n = poly.len();
    let mut c = false;
    let mut j = n.wrapping_sub(1);
    for i in 0..n {
        let (a, b) = (poly[i], poly[j]);
        if (a.1 > p.1) != (b.1 > p.1) && p.0 < a.0 + (p.1 - a.1) / (b.1 - a.1) * (b.0 - a.0) {
            c = !c;
        }
        j = i;
    }
    c
}

/// Does anything drawn in `f` fall inside the box?
pub(super) fn occupied(f: &Figure, bx: [f64; 4]) -> bool {
    f.series.iter().any(|s| match s.kind {
        Kind::Line { .. } => s
            .points
            .windows(2)
            .any(|w| hapstab_plot::segment_meets_box(w[0], w[1], bx)),
        Kind::Polygon { .. } => {
            let n = s.points.len();
            (0..n).any(|i| hapstab_plot::segment_meets_box(s.points[i], s.points[(i + 1) % n], bx))
                || inside(&s.points, (0.5 * (bx[0] + bx[1]), 0.5 * (bx[2] + bx[3])))
        }
        Kind::Scatter { .. } => s
            .points
            .iter()
            .any(|p| p.0 >= bx[0] && p.0 <= bx[1] && p.1 >= bx[2] && p.1 <= bx[3]),
    }) || f
        .annotations
        .iter()
        .any(|a| a.at.0 >= bx[0] && a.at.0 <= bx[1] && a.at.1 >= bx[2] && a.at.1 <= bx[3])
}

/// Puts the legend in a corner where it covers nothing; when every corner is taken, widens
/// (if `may_widen`) the α range to the right or the β range upwards until a corner is free. `size` is the panel size
/// in px. The legend box is estimated from plot.rs's layout (fonts 21 px × scale, rows of
/// about 1.65 font heights, 46 px icons, 12 px margins; measured on the PNGs), with 2 % of
/// the plot to spare.
pub(super) fn place_legend(f: &mut Figure, size: (u32, u32), may_widen: bool) {
    let Some(lb) = legend_box(f, size) else {
        return;
    };
    let corners = [
        Legend::UpperRight,
        Legend::UpperLeft,
        Legend::LowerRight,
        Legend::LowerLeft,
    ];
    for pos in corners {
        if !occupied(f, lb.at(f.ranges(), pos)) {
            f.legend = pos;
            return;
        }
    }
    if may_widen {
        widen_for_legend(f, &lb);
    } else {
        f.legend = Legend::UpperRight;
    }
}

/// The legend box's estimated size and its offset from the plot's edge, as fractions of the
/// plotting area's width and height.
pub(super) struct LegendBox {
    pub(super) w: f64,
    pub(super) h: f64,
    pub(super) off: (f64, f64),
}

impl LegendBox {
    /// The box [x_lo, x_hi, y_lo, y_hi] in data units at the corner `pos` of the ranges.
    fn at(&self, ((x0, x1), (y0, y1)): ((f64, f64), (f64, f64)), pos: Legend) -> [f64; 4] {
        let (xs, ys) = (x1 - x0, y1 - y0);
        let (w, h, off) = (self.w, self.h, self.off);
        let right = matches!(
            pos,
            Legend::UpperRight | Legend::LowerRight | Legend::Hidden
        );
        let upper = matches!(pos, Legend::UpperRight | Legend::UpperLeft | Legend::Hidden);
        let (xa, xb) = if right {
            (x1 - (off.0 + w) * xs, x1 - off.0 * xs)
        } else {
            (x0 + off.0 * xs, x0 + (off.0 + w) * xs)
        };
        let (ya, yb) = if upper {
            (y1 - (off.1 + h) * ys, y1 - off.1 * ys)
        } else {
            (y0 + off.1 * ys, y0 + (off.1 + h) * ys)
        };
        [xa, xb, ya, yb]
    }
}

/// The legend box of a figure on a panel of `size` px (see [`place_legend`]); None when no
/// series is labelled.
pub(super) fn legend_box(f: &Figure, size: (u32, u32)) -> Option<LegendBox> {
    let labels: Vec<usize> = f
        .series
        .iter()
        .filter_map(|s| s.label.as_ref().map(|l| l.chars().count()))
        .collect();
    if labels.is_empty() {
        return None;
    }
    let s = f.font_scale;
    let font = 21.0 * s;
    let plot_w = size.0 as f64 - (105.0 + 42.0) * s;
    let plot_h = size.1 as f64 - (70.0 + 28.0 + if f.title.is_empty() { 0.0 } else { 45.0 }) * s;
    let chars = labels.iter().copied().max().unwrap_or(0) as f64;
    Some(LegendBox {
        w: (46.0 * s + 0.56 * font * chars + 30.0 * s) / plot_w + 0.01,
        h: (labels.len() as f64 * 1.65 * font + 14.0 * s) / plot_h + 0.02,
        off: (12.0 * s / plot_w, 12.0 * s / plot_h),
    })
}

/// Every corner covers data: widens the α range to the right or the β range upwards,
/// whichever needs the smaller widening, so that the legend box clears every drawn point in
/// its band, and puts the legend there.
pub(super) fn widen_for_legend(f: &mut Figure, lb: &LegendBox) {
    let (w, h, off) = (lb.w, lb.h, lb.off);
    let ((x0, x1), (y0, y1)) = f.ranges();
    let (xs, ys) = (x1 - x0, y1 - y0);
    let fit = |need: f64, lo: f64, span: f64, box_frac: f64, off: f64| {
        let frac = (1.0 - box_frac - 2.0 * off).max(0.25);
        ((need - lo) / frac * 1.02).max(span)
    };
    let top = (y1 - (off.1 + h) * ys, y1);
    let bottom = (y0, y0 + (off.1 + h) * ys);
    let right = (x1 - (off.0 + w) * xs, x1);
    let left = (x0, x0 + (off.0 + w) * xs);
    let options = [
        (
            Legend::UpperRight,
            true,
            fit(max_in_band(f, false, top), x0, xs, w, off.0) / xs,
        ),
        (
            Legend::LowerRight,
            true,
            fit(max_in_band(f, false, bottom), x0, xs, w, off.0) / xs,
        ),
        (
            Legend::UpperRight,
            false,
            fit(max_in_band(f, true, right), y0, ys, h, off.1) / ys,
        ),
        (
            Legend::UpperLeft,
            false,
            fit(max_in_band(f, true, left), y0, ys, h, off.1) / ys,
        ),
    ];
    let (pos, along_x, factor) = options
        .iter()
        .copied()
        .min_by(|a, b| a.2.total_cmp(&b.2))
        .unwrap_or((Legend::UpperRight, true, 2.0));
    if along_x {
        f.x_range = Some((x0, x0 + factor * xs));
    } else {
        f.y_range = Some((y0, y0 + factor * ys));
    }
    f.legend = pos;
}

/// The largest α (`beta_band` false: points with β in the band) or β (`true`: points with α
/// in the band) of everything drawn in `f`; segments are clipped to the band first.
pub(super) fn max_in_band(f: &Figure, alpha_band: bool, band: (f64, f64)) -> f64 {
    let key = |p: (f64, f64)| if alpha_band { p.0 } else { p.1 };
    let val = |p: (f64, f64)| if alpha_band { p.1 } else { p.0 };
    let mut best = f64::NEG_INFINITY;
    let mut seg = |a: (f64, f64), b: (f64, f64)| {
        if !(a.0.is_finite() && a.1.is_finite() && b.0.is_finite() && b.1.is_finite()) {
            return;
        }
        let (ka, kb) = (key(a), key(b));
        let (lo, hi) = (ka.min(kb), ka.max(kb));
        if hi < band.0 || lo > band.1 {
            return;
        }
        for k in [ka.clamp(band.0, band.1), kb.clamp(band.0, band.1)] {
            let t = if kb != ka { (k - ka) / (kb - ka) } else { 0.0 };
            best = best.max(val(a) + t.clamp(0.0, 1.0) * (val(b) - val(a)));
        }
    };
    for s in &f.series {
        match s.kind {
            Kind::Line { .. } => s.points.windows(2).for_each(|w| seg(w[0], w[1])),
            Kind::Polygon { .. } => {
                let n = s.points.len();
                (0..n).for_each(|i| seg(s.points[i], s.points[(i + 1) % n]));
            }
            Kind::Scatter { .. } => s.points.iter().for_each(|&p| seg(p, p)),
        }
    }
    for a in &f.annotations {
        seg(a.at, a.at);
    }
    best
}
