//! `/api/export`: the current view as SVG (a standalone plot), CSV (every drawn vertex) or
//! JSON (the region answer plus the selected point and the view).

use std::fmt::Write as _;

use serde::Serialize;

use crate::api::{
    PointOut, RegionOut, RegionReq, WallAt, parse_region, point, region, region_names,
};
use crate::limits::{MAX_EXPORT_PX, MIN_EXPORT_PX};
use crate::query::{ApiError, Params, fmt};
use hapstab_plot::text::{eng, sig};

/// Query names of `/api/export`.
pub(crate) fn export_names() -> Vec<&'static str> {
    let mut v = region_names();
    v.extend(["format", "alpha", "beta", "view", "width", "height"]);
    v
}

/// Export formats.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Format {
    Svg,
    Csv,
    Json,
    /// The loop and the point's wall as a loop file (see [`crate::loop_io`]).
    Loop,
}

/// A parsed export request.
#[derive(Debug, Clone)]
pub(crate) struct ExportReq {
    pub region: RegionReq,
    pub format: Format,
    pub point: Option<(f64, f64)>,
    /// α0, α1, β0, β1 (normalized units).
    pub view: Option<[f64; 4]>,
    pub width: usize,
    pub height: usize,
}

/// Validates an export request.
pub(crate) fn parse_export(p: &Params) -> Result<ExportReq, ApiError> {
    let region = parse_region(p)?;
    let format = match p.choice("format", &["svg", "csv", "json", "loop"], "svg")? {
        "csv" => Format::Csv,
        "json" => Format::Json,
        "loop" => Format::Loop,
        _ => Format::Svg,
    };
    let point = match (p.has("alpha"), p.has("beta")) {
        (false, false) => None,
        _ => {
            let lim = crate::limits::MAX_WALL;
            Some((
                p.num_in("alpha", -lim, lim, "")?,
                p.num_in("beta", -lim, lim, "")?,
            ))
        }
    };
    let view = match p.raw("view") {
        None => None,
        Some(s) => {
            let bad = || {
                ApiError::param(
                    "view",
                    s,
                    format!(
                        "parameter 'view' must be four finite numbers α0,α1,β0,β1 with α0 < α1 and β0 < β1 (got '{}')",
                        crate::query::clip(s)
                    ),
                )
            };
            let v: Vec<f64> = s
                .split(',')
                .map(|x| x.trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|_| bad())?;
            if v.len() != 4 || v.iter().any(|x| !x.is_finite()) || v[0] >= v[1] || v[2] >= v[3] {
                return Err(bad());
            }
            Some([v[0], v[1], v[2], v[3]])
        }
    };
    let width = p
        .opt_count("width", MIN_EXPORT_PX, MAX_EXPORT_PX, " px")?
        .unwrap_or(900);
    let height = p
        .opt_count("height", MIN_EXPORT_PX, MAX_EXPORT_PX, " px")?
        .unwrap_or(650);
    Ok(ExportReq {
        region,
        format,
        point,
        view,
        width,
        height,
    })
}

/// The selected wall: the explorer's answer for it and its point in the plane's units.
struct Selected {
    answer: PointOut,
    at: (f64, f64),
}

#[derive(Serialize)]
struct JsonExport<'a> {
    region: &'a RegionOut,
    point: Option<&'a PointOut>,
    /// α0, α1, β0, β1 of the view.
    view: [f64; 4],
}

/// The export: content type, file name and body.
pub(crate) fn export(req: &ExportReq) -> Result<(&'static str, String, String), ApiError> {
    if req.format == Format::Loop {
        let body = crate::loop_io::saved_loop(&req.region.spec, req.point)?;
        return Ok(("application/json", "hapstab-loop.json".into(), body));
    }
    let out = region(&req.region)?;
    let pt = match req.point {
        Some((a, b)) => Some(Selected {
            answer: point(&req.region.spec, WallAt::of_units(&req.region.spec, a, b))?,
            at: (a, b),
        }),
        None => None,
    };
    let view = req.view.unwrap_or_else(|| auto_view(&out, pt.as_ref()));
    let spec = &req.region.spec;
    let lp = spec.sys.lp();
    // the file speaks the loop's units: (γ, δ, d) for normalized input, else T and t_d
    let stem = match spec.physical {
        None => {
            // normalized input is the paper's loop, whose (γ, δ, d) the region gives
            let (g, dl, d) = out
                .params
                .map_or((0.0, 0.0, 0), |p| (p.gamma, p.delta, p.d));
            format!("hapstab-region-gamma{}-delta{}-d{d}", fmt(g), fmt(dl))
        }
        Some(_) => format!(
            "hapstab-region-T{}-td{}",
            fmt(lp.period),
            fmt(lp.delay_time())
        ),
    };
    let title = format!(
        "Exact stable region: {}",
        hapstab_plot::wall::loop_line(lp, spec.physical.is_none())
    );
    Ok(match req.format {
        Format::Json => {
            let body = hapstab::json::pretty(&JsonExport {
                region: &out,
                point: pt.as_ref().map(|p| &p.answer),
                view,
            })
            .map_err(|e| ApiError::bad(format!("JSON encoding failed: {e}")))?;
            ("application/json", format!("{stem}.json"), body)
        }
        Format::Csv => (
            "text/csv; charset=utf-8",
            format!("{stem}.csv"),
            csv(&out, pt.as_ref(), view),
        ),
        Format::Loop | Format::Svg => (
            "image/svg+xml",
            format!("{stem}.svg"),
            svg(&out, pt.as_ref(), view, (req.width, req.height), &title),
        ),
    })
}

/// The view that shows everything drawn: the region, the overlays and the point, padded.
fn auto_view(out: &RegionOut, pt: Option<&Selected>) -> [f64; 4] {
    let mut b = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    let mut add = |a: f64, be: f64| {
        if a.is_finite() && be.is_finite() {
            b[0] = b[0].min(a);
            b[1] = b[1].max(a);
            b[2] = b[2].min(be);
            b[3] = b[3].max(be);
        }
    };
    for v in out.region.drawn.iter().flatten() {
        add(v[0], v[1]);
    }
    if let Some(r) = &out.robust {
        for v in &r.polygon {
            add(v[0], v[1]);
        }
    }
    for pa in out.passive.iter().chain(&out.passive_with_arm) {
        for v in &pa.drawn {
            add(v[0], v[1]);
        }
    }
    if let Some(p) = pt {
        add(p.at.0, p.at.1);
    }
    for v in robust_kmax_segment(out).iter().flatten() {
        add(v[0], v[1]);
    }
    if !b[0].is_finite() {
        let g = out.params.map_or(0.0, |p| p.gamma);
        return [-g - 0.1, 1.0, -0.5, 1.0];
    }
    let (w, h) = (b[1] - b[0], b[3] - b[2]);
    let (w, h) = (
        if w > 0.0 { w } else { b[1].abs().max(1e-6) },
        if h > 0.0 { h } else { b[3].abs().max(1e-6) },
    );
    [
        b[0] - 0.08 * w,
        b[1] + 0.08 * w,
        b[2] - 0.08 * h,
        b[3] + 0.08 * h,
    ]
}

/// The robust K_max over a box as a segment in the page's units: from (K_min, B) to
/// (K_max, B) as (α, β); None without a box or where no K is stable for every plant.
fn robust_kmax_segment(out: &RegionOut) -> Option<[[f64; 2]; 2]> {
    let r = &out.robust_kmax.as_ref()?.report;
    let ph = out.physical.as_ref()?;
    let b = r.wall_damping / ph.b_per_unit;
    Some([[r.k_min? / ph.k_per_unit, b], [r.k_max? / ph.k_per_unit, b]])
}

/// Every drawn vertex: layer, polygon, vertex and K (N/m), B (Ns/m) in physical mode, α, β
/// for normalized input.
fn csv(out: &RegionOut, pt: Option<&Selected>, view: [f64; 4]) -> String {
    let mut s = String::from(match out.physical {
        Some(_) => "layer,polygon,vertex,K_N_per_m,B_Ns_per_m\n",
        None => "layer,polygon,vertex,alpha,beta\n",
    });
    let mut row = |layer: &str, poly: usize, i: usize, a: f64, b: f64| {
        let _ = match &out.physical {
            Some(ph) => writeln!(
                s,
                "{layer},{poly},{i},{},{}",
                a * ph.k_per_unit,
                b * ph.b_per_unit
            ),
            None => writeln!(s, "{layer},{poly},{i},{a},{b}"),
        };
    };
    for (j, poly) in out.region.drawn.iter().enumerate() {
        for (i, v) in poly.iter().enumerate() {
            row("region", j, i, v[0], v[1]);
        }
    }
    if out.region.max_drawn[0].is_finite() {
        row(
            if out.physical.is_some() {
                "k_max"
            } else {
                "alpha_max"
            },
            0,
            0,
            out.region.max_drawn[0],
            out.region.max_drawn[1],
        );
    }
    if let Some(l) = &out.linear {
        for (i, b) in [view[2], view[3]].into_iter().enumerate() {
            row("linear", 0, i, l.alpha_at_beta0 + l.slope * b, b);
        }
    }
    if let Some(pa) = &out.passive {
        for (i, v) in pa.drawn.iter().enumerate() {
            row("passive", 0, i, v[0], v[1]);
        }
    }
    if let Some(pa) = &out.passive_with_arm {
        for (i, v) in pa.drawn.iter().enumerate() {
            row("passive_with_arm", 0, i, v[0], v[1]);
        }
    }
    if let Some(r) = &out.robust {
        for (i, v) in r.polygon.iter().enumerate() {
            row("robust", 0, i, v[0], v[1]);
        }
    }
    for (i, v) in robust_kmax_segment(out).iter().flatten().enumerate() {
        row("robust_kmax", 0, i, v[0], v[1]);
    }
    if let Some(p) = pt {
        row("point", 0, 0, p.at.0, p.at.1);
    }
    s
}

/// "Nice" tick positions covering [lo, hi].
pub(crate) fn ticks(lo: f64, hi: f64, target: usize) -> Vec<f64> {
    let span = hi - lo;
    if span.is_nan() || span <= 0.0 || !span.is_finite() {
        return Vec::new();
    }
    let raw = span / target.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last.min(first + 50))
        .map(|i| {
            let v = i as f64 * step;
            if v.abs() < step * 1e-9 { 0.0 } else { v }
        })
        .collect()
}

fn verdict_color(v: &str) -> &'static str {
    match v {
        "stable" => "#1a7f1a",
        "unstable" => "#c00000",
        _ => "#b07000",
    }
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The plot's geometry in the SVG: margins, plot size, and the view in display coordinates
/// (α·sx, β·sy: K and B in physical mode).
struct Frame {
    ml: f64,
    mt: f64,
    pw: f64,
    ph: f64,
    sx: f64,
    sy: f64,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
}

impl Frame {
    /// The frame of a `w` × `h` image of `view`.
    fn new(out: &RegionOut, view: [f64; 4], w: usize, h: usize) -> Self {
        let (ml, mr, mt, mb) = (80.0, 20.0, 46.0, 56.0);
        let (wf, hf) = (w as f64, h as f64);
        let (sx, sy) = match &out.physical {
            Some(p) => (p.k_per_unit, p.b_per_unit),
            None => (1.0, 1.0),
        };
        Self {
            ml,
            mt,
            pw: wf - ml - mr,
            ph: hf - mt - mb,
            sx,
            sy,
            x0: view[0] * sx,
            x1: view[1] * sx,
            y0: view[2] * sy,
            y1: view[3] * sy,
        }
    }

    /// The x pixel of α.
    fn px(&self, a: f64) -> f64 {
        self.ml + (a * self.sx - self.x0) / (self.x1 - self.x0) * self.pw
    }

    /// The y pixel of β.
    fn py(&self, b: f64) -> f64 {
        self.mt + self.ph - (b * self.sy - self.y0) / (self.y1 - self.y0) * self.ph
    }

    /// The SVG points list of (α, β) vertices.
    fn points(&self, vertices: &[[f64; 2]]) -> String {
        let d: Vec<String> = vertices
            .iter()
            .map(|v| format!("{:.2},{:.2}", self.px(v[0]), self.py(v[1])))
            .collect();
        d.join(" ")
    }
}

/// A standalone SVG of the view.
fn svg(
    out: &RegionOut,
    pt: Option<&Selected>,
    view: [f64; 4],
    (w, h): (usize, usize),
    title: &str,
) -> String {
    let f = Frame::new(out, view, w, h);
    let (ml, mt, pw, ph) = (f.ml, f.mt, f.pw, f.ph);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<defs><clipPath id="plot"><rect x="{ml}" y="{mt}" width="{pw}" height="{ph}"/></clipPath></defs>"#
    );
    svg_grid(&mut s, &f);
    svg_axis_labels(&mut s, out, &f, h as f64);
    let _ = writeln!(
        s,
        r#"<text x="{ml}" y="20" font-size="14" font-weight="bold">{}</text>"#,
        esc(title)
    );
    let _ = writeln!(s, r#"<g clip-path="url(#plot)">"#);
    svg_areas(&mut s, out, &f);
    svg_lines(&mut s, out, &f, view);
    if let Some(p) = pt {
        svg_point(&mut s, p, &f);
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(
        s,
        r##"<rect x="{ml}" y="{mt}" width="{pw}" height="{ph}" fill="none" stroke="#333"/>"##
    );
    svg_legend(&mut s, &legend_items(out, pt), &f);
    s.push_str("</svg>\n");
    s
}

/// Tick labels of one axis as the page writes them: with a k or M prefix once the ticks reach
/// 10⁴ (250k for 250 000 N/m).
fn tick_labels(ts: &[f64]) -> Vec<String> {
    let big = ts.iter().fold(0.0f64, |m, t| m.max(t.abs()));
    let (div, unit) = if big >= 1e7 {
        (1e6, "M")
    } else if big >= 1e4 {
        (1e3, "k")
    } else {
        (1.0, "")
    };
    ts.iter()
        .map(|&t| {
            if t == 0.0 {
                "0".to_string()
            } else {
                format!("{}{unit}", sig(t / div, 4))
            }
        })
        .collect()
}

/// The grid lines and tick labels of both axes.
fn svg_grid(s: &mut String, f: &Frame) {
    let (ml, mt, pw, ph) = (f.ml, f.mt, f.pw, f.ph);
    let (x0, x1, y0, y1) = (f.x0, f.x1, f.y0, f.y1);
    let xt = ticks(x0, x1, 8);
    for (t, label) in xt.iter().copied().zip(tick_labels(&xt)) {
        let x = ml + (t - x0) / (x1 - x0) * pw;
        let _ = writeln!(
            s,
            "<line x1=\"{x:.2}\" y1=\"{mt}\" x2=\"{x:.2}\" y2=\"{}\" stroke=\"{}\"/><text x=\"{x:.2}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
            mt + ph,
            if t == 0.0 { "#888" } else { "#eee" },
            mt + ph + 16.0,
            esc(&label)
        );
    }
    let yt = ticks(y0, y1, 8);
    for (t, label) in yt.iter().copied().zip(tick_labels(&yt)) {
        let y = mt + ph - (t - y0) / (y1 - y0) * ph;
        let _ = writeln!(
            s,
            "<line x1=\"{ml}\" y1=\"{y:.2}\" x2=\"{}\" y2=\"{y:.2}\" stroke=\"{}\"/><text x=\"{}\" y=\"{:.2}\" text-anchor=\"end\">{}</text>",
            ml + pw,
            if t == 0.0 { "#888" } else { "#eee" },
            ml - 6.0,
            y + 4.0,
            esc(&label)
        );
    }
}

/// The x and y axis labels: K and B in physical mode, α and β otherwise.
fn svg_axis_labels(s: &mut String, out: &RegionOut, f: &Frame, hf: f64) {
    let (xl, yl) = if out.physical.is_some() {
        ("virtual stiffness K (N/m)", "virtual damping B (Ns/m)")
    } else {
        ("α = KT²/m", "β = BT/m")
    };
    let _ = writeln!(
        s,
        r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{xl}</text>"#,
        f.ml + f.pw / 2.0,
        hf - 14.0
    );
    let _ = writeln!(
        s,
        r#"<text transform="translate(18,{:.1}) rotate(-90)" text-anchor="middle">{yl}</text>"#,
        f.mt + f.ph / 2.0
    );
}

/// The filled areas: the exact region, the robust region and the passive regions.
fn svg_areas(s: &mut String, out: &RegionOut, f: &Frame) {
    for poly in &out.region.drawn {
        let _ = writeln!(
            s,
            "<polygon class=\"region\" points=\"{}\" fill=\"#4c8fd6\" fill-opacity=\"0.35\" stroke=\"#1d4f91\" stroke-width=\"1.5\"/>",
            f.points(poly)
        );
    }
    if let Some(r) = out.robust.as_ref().filter(|r| !r.polygon.is_empty()) {
        let _ = writeln!(
            s,
            "<polygon class=\"robust\" points=\"{}\" fill=\"#f0b400\" fill-opacity=\"0.25\" stroke=\"#a87b00\" stroke-width=\"1.5\" stroke-dasharray=\"6 3\"/>",
            f.points(&r.polygon)
        );
    }
    if let Some(pa) = &out.passive {
        let _ = writeln!(
            s,
            "<polygon class=\"passive\" points=\"{}\" fill=\"#2ca02c\" fill-opacity=\"0.35\" stroke=\"#1a6e1a\" stroke-width=\"1.5\"/>",
            f.points(&pa.drawn)
        );
    }
    if let Some(pa) = &out.passive_with_arm {
        let _ = writeln!(
            s,
            "<polygon class=\"passive-with-arm\" points=\"{}\" fill=\"none\" stroke=\"#1a6e1a\" stroke-width=\"1.5\" stroke-dasharray=\"4 3\"/>",
            f.points(&pa.drawn)
        );
    }
}

/// The lines: the linear condition with its α > −γ bound, and α_max with its vertex.
fn svg_lines(s: &mut String, out: &RegionOut, f: &Frame, view: [f64; 4]) {
    let (mt, ph) = (f.mt, f.ph);
    if let Some(l) = &out.linear {
        let (b0, b1) = (view[2], view[3]);
        let _ = writeln!(
            s,
            "<line class=\"linear\" x1=\"{:.2}\" y1=\"{:.2}\" x2=\"{:.2}\" y2=\"{:.2}\" stroke=\"#d62728\" stroke-width=\"1.5\" stroke-dasharray=\"8 4\"/>",
            f.px(l.alpha_at_beta0 + l.slope * b0),
            f.py(b0),
            f.px(l.alpha_at_beta0 + l.slope * b1),
            f.py(b1)
        );
        let _ = writeln!(
            s,
            "<line x1=\"{:.2}\" y1=\"{mt}\" x2=\"{:.2}\" y2=\"{}\" stroke=\"#d62728\" stroke-width=\"1\" stroke-dasharray=\"2 3\"/>",
            f.px(l.alpha_lower),
            f.px(l.alpha_lower),
            mt + ph
        );
    }
    if let Some([lo, hi]) = robust_kmax_segment(out) {
        let (x0, x1, y) = (f.px(lo[0]), f.px(hi[0]), f.py(hi[1]));
        let _ = writeln!(
            s,
            "<g class=\"robust-kmax\" stroke=\"#a87b00\" stroke-width=\"3\"><line x1=\"{x0:.2}\" y1=\"{y:.2}\" x2=\"{x1:.2}\" y2=\"{y:.2}\"/><path d=\"M{x1:.2},{:.2}L{:.2},{y:.2}L{x1:.2},{:.2}L{:.2},{y:.2}Z\" fill=\"#f0b400\" stroke-width=\"1.5\"/></g>",
            y - 7.0,
            x1 + 7.0,
            y + 7.0,
            x1 - 7.0
        );
    }
    let am = out.region.max_drawn[0];
    if am.is_finite() {
        let (x, y) = (f.px(am), f.py(out.region.max_drawn[1]));
        let _ = writeln!(
            s,
            "<line x1=\"{x:.2}\" y1=\"{mt}\" x2=\"{x:.2}\" y2=\"{}\" stroke=\"#444\" stroke-dasharray=\"3 3\"/><circle class=\"alpha-max\" cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"5\" fill=\"#111\"/>",
            mt + ph
        );
    }
}

/// The selected point: a cross in its verdict's color.
fn svg_point(s: &mut String, p: &Selected, f: &Frame) {
    let color = verdict_color(p.answer.verdict);
    let (x, y) = (f.px(p.at.0), f.py(p.at.1));
    let _ = writeln!(
        s,
        "<g class=\"point\" stroke=\"{color}\" stroke-width=\"2.5\"><line x1=\"{:.2}\" y1=\"{:.2}\" x2=\"{:.2}\" y2=\"{:.2}\"/><line x1=\"{:.2}\" y1=\"{:.2}\" x2=\"{:.2}\" y2=\"{:.2}\"/></g>",
        x - 6.0,
        y - 6.0,
        x + 6.0,
        y + 6.0,
        x - 6.0,
        y + 6.0,
        x + 6.0,
        y - 6.0
    );
}

/// The legend's entries (text, color) of everything drawn.
fn legend_items(out: &RegionOut, pt: Option<&Selected>) -> Vec<(String, &'static str)> {
    let mut items: Vec<(String, &str)> = vec![("exact stable region".into(), "#4c8fd6")];
    if out.linear.is_some() {
        items.push(("linear condition (23), α > −γ (19)".into(), "#d62728"));
    }
    let am = out.region.max_drawn[0];
    if am.is_finite() {
        let v = match &out.physical {
            Some(ph) => format!("K_max = {}", eng(am * ph.k_per_unit, "N/m", 6)),
            None => format!("α_max = {}", sig(am, 6)),
        };
        items.push((v, "#111"));
    }
    if out.passive.is_some() {
        let what = if out.physical.is_some() {
            "passive, device's own b_L (any operator)"
        } else {
            "Colgate's passive region (28)"
        };
        items.push((what.into(), "#2ca02c"));
    }
    if out.passive_with_arm.is_some() {
        items.push((
            "eq. (28) with the arm's b_H (this operator)".into(),
            "#1a6e1a",
        ));
    }
    if let Some(r) = &out.robust {
        let range = match (r.arm_stiffness_lo, r.arm_stiffness_hi) {
            (Some(lo), Some(hi)) => format!("k_H ∈ [{}, {}]", eng(lo, "N/m", 4), eng(hi, "N/m", 4)),
            _ => format!("γ ∈ [{}, {}]", sig(r.gamma_lo, 4), sig(r.gamma_hi, 4)),
        };
        items.push((format!("robust region, {range}"), "#f0b400"));
    }
    if let Some(r) = out.robust_kmax.as_ref().map(|r| &r.report) {
        let text = match r.k_max {
            Some(k) => format!(
                "robust K_max = {} at B = {} over the box",
                eng(k, "N/m", 6),
                eng(r.wall_damping, "Ns/m", 4)
            ),
            None => format!(
                "no K stable for the whole box at B = {}",
                eng(r.wall_damping, "Ns/m", 4)
            ),
        };
        items.push((text, "#a87b00"));
    }
    if let Some(p) = pt {
        items.push((
            format!(
                "point: {} (ρ = {})",
                p.answer.verdict,
                sig(p.answer.spectral_radius, 6)
            ),
            verdict_color(p.answer.verdict),
        ));
    }
    items
}

/// The legend: a color swatch and a text per entry, top right of the plot.
fn svg_legend(s: &mut String, items: &[(String, &str)], f: &Frame) {
    let lx = f.ml + f.pw - 290.0;
    for (i, (text, color)) in items.iter().enumerate() {
        let y = f.mt + 16.0 + 18.0 * i as f64;
        let _ = writeln!(
            s,
            r#"<rect x="{lx:.1}" y="{:.1}" width="12" height="12" fill="{color}" fill-opacity="0.7"/><text x="{:.1}" y="{:.1}">{}</text>"#,
            y - 10.0,
            lx + 18.0,
            y,
            esc(text)
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_nice() {
        let t = ticks(0.0, 1.0, 5);
        assert_eq!(t.len(), 6);
        for (i, v) in t.iter().enumerate() {
            assert!((v - 0.2 * i as f64).abs() < 1e-12, "{t:?}");
        }
        assert!(ticks(1.0, 1.0, 5).is_empty());
        assert_eq!(ticks(-0.015, 0.015, 3), vec![-0.01, 0.0, 0.01]);
    }

    #[test]
    fn tick_labels_take_a_prefix_from_ten_thousand() {
        assert_eq!(tick_labels(&[0.0, 5000.0, 9000.0]), ["0", "5000", "9000"]);
        assert_eq!(tick_labels(&[-2e4, 0.0, 2.5e5]), ["-20k", "0", "250k"]);
        assert_eq!(tick_labels(&[1e7, 1.5e7]), ["10M", "15M"]);
    }
}
