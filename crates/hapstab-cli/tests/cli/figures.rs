//! Figures in physical units (`--plot` of boundary, map, kmax, check), a growing simulation's
//! clipped figure, kmax's damping range, and quiet standard error when it is not a terminal.
//! Expected values come from the library or from closed forms, never from the program's own
//! output.

use crate::common;

use common::hapstab;
use hapstab::Effective;
use hapstab::model::Loop;
use serde_json::Value;

/// Runs the binary, asserts success and an empty standard error (not a terminal: no
/// progress bar), and returns standard output.
fn run_quiet(args: &[&str]) -> String {
    let out = hapstab().args(args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {err}");
    assert!(err.is_empty(), "{args:?} wrote to stderr: {err}");
    String::from_utf8(out.stdout).unwrap()
}

fn json(args: &[&str]) -> Value {
    let mut a = args.to_vec();
    a.push("--json");
    serde_json::from_str(&run_quiet(&a)).unwrap()
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The CLI's default physical loop: m = m_L + m_H = 0.1 + 1.0 kg, b = 1.5 + 6 Ns/m,
/// k = 350 N/m, T = 1 ms.
fn default_loop(d: usize) -> Loop {
    Loop::paper(Effective::new(1.1, 7.5, 350.0).unwrap(), 1e-3, d).unwrap()
}

// ---- kmax --damping-range ------------------------------------------------------------

#[test]
fn kmax_by_default_keeps_the_damping_non_negative() {
    let lp = default_loop(200);
    let sys = hapstab::System::of(&lp).unwrap();
    let fam = sys.family();
    let best = sys.k_max_within(0.0, f64::INFINITY).unwrap().unwrap();
    let (k, b) = fam.to_physical(best.a, best.b);
    let v = json(&["kmax", "--delay", "200"]);
    let (k_cli, b_cli) = (f(&v["k_max"]), f(&v["b_at_k_max"]));
    assert!(b_cli >= 0.0, "B = {b_cli}");
    assert!((k_cli - k).abs() <= 1e-12 * k, "{k_cli} vs {k}");
    assert!(
        (b_cli - b).abs() <= 1e-12 * b.abs().max(1.0),
        "{b_cli} vs {b}"
    );
    // without a band the region's maximum lies at a negative B for this delay: the band
    // changes the answer
    let free = sys
        .k_max_within(f64::NEG_INFINITY, f64::INFINITY)
        .unwrap()
        .unwrap();
    assert!(free.b < 0.0 && free.a > best.a);
    // K_max at B = 0 (the plant's own damping only)
    let at0 = sys.k_max_at_damping(0.0).unwrap();
    let k0 = fam.to_physical(at0.hi, 0.0).0;
    assert!((f(&v["k_max_at_zero_damping"]) - k0).abs() <= 1e-12 * k0);
}

#[test]
fn kmax_damping_range_bounds_the_damping() {
    let lp = default_loop(0);
    let sys = hapstab::System::of(&lp).unwrap();
    let fam = sys.family();
    let hi = sys.damping_units(50.0).unwrap();
    let best = sys.k_max_within(0.0, hi).unwrap().unwrap();
    let (k, b) = fam.to_physical(best.a, best.b);
    let v = json(&["kmax", "--damping-range", "0:50"]);
    assert!((f(&v["k_max"]) - k).abs() <= 1e-12 * k);
    assert!((f(&v["b_at_k_max"]) - b).abs() <= 1e-9 * 50.0);
    assert!(f(&v["b_at_k_max"]) <= 50.0 + 1e-9);
    assert_eq!(v["input"]["damping_range"], serde_json::json!([0.0, 50.0]));
}

#[test]
fn kmax_damping_range_rejects_bad_bands() {
    for bad in ["5", "3:1", "a:2", "nan:1", "0:-inf"] {
        let out = hapstab()
            .args(["kmax", "--damping-range", bad])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{bad}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("--damping-range"), "{bad}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{bad}: {err}");
    }
}

// ---- --plot ------------------------------------------------------------------------------

/// The `<text>` elements of an SVG: (x, y, text-anchor, content).
fn svg_texts(svg: &str) -> Vec<(f64, f64, String, String)> {
    let attr = |tag: &str, name: &str| -> Option<String> {
        let key = format!(" {name}=\"");
        let i = tag.find(&key)? + key.len();
        Some(tag[i..].split('"').next()?.to_string())
    };
    svg.split("<text")
        .skip(1)
        .filter_map(|chunk| {
            let (tag, rest) = chunk.split_once('>')?;
            let content = rest.split("</text>").next()?.trim().to_string();
            let x = attr(tag, "x")?.parse().ok()?;
            let y = attr(tag, "y")?.parse().ok()?;
            Some((x, y, attr(tag, "text-anchor").unwrap_or_default(), content))
        })
        .collect()
}

/// The value of a tick label: a number with an optional engineering prefix (150k, 1.2M).
fn tick_value(label: &str) -> Option<f64> {
    let (body, scale) = match label.chars().last()? {
        'k' => (&label[..label.len() - 1], 1e3),
        'M' => (&label[..label.len() - 1], 1e6),
        'G' => (&label[..label.len() - 1], 1e9),
        'T' => (&label[..label.len() - 1], 1e12),
        _ => (label, 1.0),
    };
    body.parse::<f64>().ok().map(|v| v * scale)
}

/// Least-squares line px = c0 + c1·value through the tick labels, inverted: value at px.
fn axis_map(ticks: &[(f64, f64)]) -> impl Fn(f64) -> f64 {
    assert!(ticks.len() >= 3, "too few ticks: {ticks:?}");
    let n = ticks.len() as f64;
    let (mv, mp) = ticks
        .iter()
        .fold((0.0, 0.0), |(a, b), (v, p)| (a + v / n, b + p / n));
    let (sxy, sxx) = ticks.iter().fold((0.0, 0.0), |(a, b), (v, p)| {
        (a + (v - mv) * (p - mp), b + (v - mv) * (v - mv))
    });
    let c1 = sxy / sxx;
    let c0 = mp - c1 * mv;
    move |px| (px - c0) / c1
}

/// A panel's box in px: [x0, x1, y0, y1].
type PanelBox = [f64; 4];

/// The whole image.
const WHOLE: PanelBox = [
    f64::NEG_INFINITY,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::INFINITY,
];

fn inside(b: PanelBox, (x, y): (f64, f64)) -> bool {
    x >= b[0] && x < b[1] && y >= b[2] && y < b[3]
}

/// A panel's axes read from its tick labels: px → data maps along x and y, and the lowest
/// x tick label's y in px (the plotting area and its markers lie above it, the legend below).
struct Axes {
    x_ticks: Vec<(f64, f64)>,
    y_ticks: Vec<(f64, f64)>,
    bottom: f64,
}

fn axes(svg: &str, panel: PanelBox) -> Axes {
    let texts = svg_texts(svg);
    let ticks = |anchor: &'static str| -> Vec<(f64, f64, f64)> {
        texts
            .iter()
            .filter(|t| t.2 == anchor && inside(panel, (t.0, t.1)))
            .filter_map(|t| tick_value(&t.3).map(|v| (v, t.0, t.1)))
            .collect()
    };
    Axes {
        x_ticks: ticks("middle").iter().map(|&(v, x, _)| (v, x)).collect(),
        y_ticks: ticks("end").iter().map(|&(v, _, y)| (v, y)).collect(),
        bottom: ticks("middle")
            .iter()
            .map(|t| t.2)
            .fold(f64::NEG_INFINITY, f64::max),
    }
}

impl Axes {
    /// Data coordinates of the pixel (x, y), and the data size of one pixel on each axis.
    fn data(&self, (x, y): (f64, f64)) -> ((f64, f64), (f64, f64)) {
        let (fx, fy) = (axis_map(&self.x_ticks), axis_map(&self.y_ticks));
        let px = ((fx(x + 1.0) - fx(x)).abs(), (fy(y + 1.0) - fy(y)).abs());
        ((fx(x), fy(y)), px)
    }
}

/// Data coordinates of the anchor of the text `tag` in `panel`, and the data size of one
/// pixel along each axis.
fn tag_position(svg: &str, tag: &str, panel: PanelBox) -> ((f64, f64), (f64, f64)) {
    let texts = svg_texts(svg);
    let hits: Vec<_> = texts
        .iter()
        .filter(|t| t.3 == tag && inside(panel, (t.0, t.1)))
        .collect();
    assert_eq!(hits.len(), 1, "text '{tag}' in {texts:?}");
    axes(svg, panel).data((hits[0].0, hits[0].1))
}

/// Asserts that a tag lies at `want` to within 1.5 px on each axis.
fn assert_at(svg: &str, tag: &str, panel: PanelBox, want: (f64, f64)) {
    let ((x, y), (px, py)) = tag_position(svg, tag, panel);
    assert!(
        (x - want.0).abs() <= 1.5 * px && (y - want.1).abs() <= 1.5 * py,
        "{tag} at ({x}, {y}), expected {want:?} (pixel {px}, {py})"
    );
}

/// The centre in px of every marker filled with `fill` (a circle's centre, a polygon's
/// vertex mean): (x, y).
fn markers(svg: &str, fill: &str) -> Vec<(f64, f64)> {
    let attr = |tag: &str, name: &str| -> Option<String> {
        let key = format!(" {name}=\"");
        let i = tag.find(&key)? + key.len();
        Some(tag[i..].split('"').next()?.to_string())
    };
    let num = |tag: &str, name: &str| attr(tag, name).and_then(|v| v.parse::<f64>().ok());
    let mut out = Vec::new();
    for (open, kind) in [("<circle", 0), ("<polygon", 1)] {
        for chunk in svg.split(open).skip(1) {
            let tag = chunk.split('>').next().unwrap_or("");
            if attr(tag, "fill").as_deref() != Some(fill) {
                continue;
            }
            if kind == 0 {
                out.extend(num(tag, "cx").zip(num(tag, "cy")));
            } else if let Some(pts) = attr(tag, "points") {
                let v: Vec<(f64, f64)> = pts
                    .split_whitespace()
                    .filter_map(|p| p.split_once(','))
                    .filter_map(|(x, y)| Some((x.parse().ok()?, y.parse().ok()?)))
                    .collect();
                let n = v.len() as f64;
                let (sx, sy) = v.iter().fold((0.0, 0.0), |(a, b), p| (a + p.0, b + p.1));
                out.push((sx / n, sy / n));
            }
        }
    }
    out
}

/// Asserts that the one marker filled with `fill` inside the plotting area of `panel` (not
/// its legend swatch below the axes) lies at `want` to within 1.5 px on each axis.
fn assert_marker_at(svg: &str, fill: &str, panel: PanelBox, want: (f64, f64)) {
    let ax = axes(svg, panel);
    let hits: Vec<(f64, f64)> = markers(svg, fill)
        .into_iter()
        .filter(|&p| inside(panel, p) && p.1 < ax.bottom)
        .collect();
    assert_eq!(hits.len(), 1, "markers filled {fill}: {hits:?}");
    let ((x, y), (px, py)) = ax.data(hits[0]);
    assert!(
        (x - want.0).abs() <= 1.5 * px && (y - want.1).abs() <= 1.5 * py,
        "marker {fill} at ({x}, {y}), expected {want:?} (pixel {px}, {py})"
    );
}

/// The y in px of the text `t` (exactly one).
fn text_y(svg: &str, t: &str) -> f64 {
    let hits: Vec<f64> = svg_texts(svg)
        .into_iter()
        .filter(|x| x.3 == t)
        .map(|x| x.1)
        .collect();
    assert_eq!(hits.len(), 1, "text '{t}': {hits:?}");
    hits[0]
}

/// Okabe–Ito vermillion and bluish green, the fills of the K_max and B = 0 markers.
const VERMILLION: &str = "#D55E00";
const GREEN: &str = "#009E73";

/// The width and height of an SVG.
fn svg_size(svg: &str) -> (f64, f64) {
    let head = svg.split('>').next().unwrap();
    let get = |name: &str| -> f64 {
        let key = format!(" {name}=\"");
        let i = head.find(&key).unwrap() + key.len();
        head[i..].split('"').next().unwrap().parse().unwrap()
    };
    (get("width"), get("height"))
}

fn is_png(path: &std::path::Path) -> bool {
    let bytes = std::fs::read(path).unwrap();
    bytes.len() > 1000 && bytes.starts_with(b"\x89PNG\r\n\x1a\n")
}

#[test]
fn boundary_plot_is_in_k_and_b_with_k_max_marked() {
    let dir = tempfile::tempdir().unwrap();
    let svg_path = dir.path().join("region.svg");
    let v = json(&[
        "boundary",
        "--delay",
        "1",
        "--plot",
        svg_path.to_str().unwrap(),
    ]);
    assert_eq!(v["plot"], serde_json::json!([svg_path.to_str().unwrap()]));
    assert!(
        !dir.path().join("region.png").exists(),
        "only the SVG was asked for"
    );
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    assert!(svg.contains("virtual stiffness K (N/m)"));
    assert!(svg.contains("virtual damping B (Ns/m)"));
    let lp = default_loop(1);
    let sys = hapstab::System::of(&lp).unwrap();
    let fam = sys.family();
    let r = sys.region().unwrap();
    let want = fam.to_physical(r.a_max, r.b_at_a_max);
    assert_at(&svg, "K_max", WHOLE, want);
    // PNG by the extension
    let png = dir.path().join("region.png");
    run_quiet(&["boundary", "--plot", png.to_str().unwrap()]);
    assert!(is_png(&png));
    assert!(!dir.path().join("region.png.svg").exists());
}

#[test]
fn boundary_plot_of_the_normalized_loop_is_in_alpha_and_beta() {
    let dir = tempfile::tempdir().unwrap();
    let stem = dir.path().join("fig");
    let args = ["--gamma", "0.001", "--delta", "0.015", "--delay", "1"];
    run_quiet(
        &[
            &["boundary"][..],
            &args,
            &["--plot", stem.to_str().unwrap()],
        ]
        .concat(),
    );
    // a name without .svg/.png gets both files
    assert!(is_png(&dir.path().join("fig.png")));
    let svg = std::fs::read_to_string(dir.path().join("fig.svg")).unwrap();
    assert!(svg.contains("virtual stiffness α = KT²/m"));
    assert!(svg.contains("virtual damping β = BT/m"));
    assert!(!svg.contains("N/m)"));
    let lp = Loop::normalized(
        hapstab::PlantParams {
            gamma: 0.001,
            delta: 0.015,
        },
        1,
    )
    .unwrap();
    let sys = hapstab::System::of(&lp).unwrap();
    let r = sys.region().unwrap();
    assert_at(&svg, "α_max", WHOLE, (r.a_max, r.b_at_a_max));
}

#[test]
fn check_plot_marks_the_wall_and_draws_the_roots() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("check.svg");
    let (k, b) = (300_000.0, 400.0);
    run_quiet(&[
        "check",
        "--wall-stiffness",
        "300000",
        "--wall-damping",
        "400",
        "--plot",
        path.to_str().unwrap(),
    ]);
    let svg = std::fs::read_to_string(&path).unwrap();
    for label in [
        "virtual stiffness K (N/m)",
        "virtual damping B (Ns/m)",
        "Re z",
        "Im z",
    ] {
        assert!(svg.contains(label), "{label}");
    }
    assert!(svg.contains("unit circle"));
    // four panels, two by two: the region's ticks lie in the upper left quarter
    let size = svg_size(&svg);
    let region = [0.0, 0.5 * size.0, 0.0, 0.5 * size.1];
    assert_at(&svg, "wall", region, (k, b));
    let png = dir.path().join("check.png");
    run_quiet(&[
        "check",
        "--wall-stiffness",
        "3000",
        "--plot",
        png.to_str().unwrap(),
    ]);
    assert!(is_png(&png));
}

#[test]
fn kmax_plot_marks_k_max_within_the_damping_range() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("kmax.svg");
    run_quiet(&[
        "kmax",
        "--delay",
        "2",
        "--damping-range",
        "0:300",
        "--plot",
        path.to_str().unwrap(),
    ]);
    let svg = std::fs::read_to_string(&path).unwrap();
    assert!(svg.contains("virtual stiffness K (N/m)"));
    assert!(svg.contains("virtual damping B (Ns/m)"));
    let lp = default_loop(2);
    let sys = hapstab::System::of(&lp).unwrap();
    let fam = sys.family();
    let hi = sys.damping_units(300.0).unwrap();
    let best = sys.k_max_within(0.0, hi).unwrap().unwrap();
    // the markers sit at their points (K_max's circle, B = 0's triangle); tags on a damping
    // line are lifted off it
    let k_max_at = fam.to_physical(best.a, best.b);
    assert_marker_at(&svg, VERMILLION, WHOLE, k_max_at);
    let at0 = sys.k_max_at_damping(0.0).unwrap();
    let b0_at = (fam.to_physical(at0.hi, 0.0).0, 0.0);
    assert_marker_at(&svg, GREEN, WHOLE, b0_at);
    // the B = 0 tag is written above its point, clear of the dashed line at B = 0: its text
    // (20 px high, drawn from its baseline up) ends above the line by at least 4 px
    let ((_, tag_b), (_, per_px)) = tag_position(&svg, "B = 0", WHOLE);
    assert!(
        tag_b >= 4.0 * per_px,
        "B = 0 tag at B = {tag_b}, pixel {per_px}"
    );
    // K_max at B = 300 lies on the band's upper line: lifted too
    let ((_, k_tag_b), _) = tag_position(&svg, "K_max", WHOLE);
    if (k_max_at.1 - 300.0).abs() < 1e-6 {
        assert!(
            k_tag_b >= 300.0 + 4.0 * per_px,
            "K_max tag at B = {k_tag_b}"
        );
    }
}

#[test]
fn map_plot_of_a_physical_loop_has_k_and_b_axes() {
    let dir = tempfile::tempdir().unwrap();
    let stem = dir.path().join("map");
    run_quiet(&[
        "map",
        "--x",
        "K:0:100000:40",
        "--y",
        "B:0:200:30",
        "--period",
        "0.002",
        "--plot",
        stem.to_str().unwrap(),
    ]);
    let svg = std::fs::read_to_string(dir.path().join("map.svg")).unwrap();
    assert!(svg.contains("K (N/m)") && svg.contains("B (Ns/m)"));
    assert!(is_png(&dir.path().join("map.png")));
    // by the extension: only the PNG
    let png = dir.path().join("only.png");
    let v = json(&[
        "map",
        "--x",
        "K:0:1e5:20",
        "--y",
        "B:0:200:20",
        "--plot",
        png.to_str().unwrap(),
    ]);
    assert_eq!(v["plot"], serde_json::json!([png.to_str().unwrap()]));
    assert!(is_png(&png) && !dir.path().join("only.svg").exists());
}

/// Runs a command with `--plot <dir>/<name>.svg` and returns the SVG.
fn plot_svg(dir: &std::path::Path, name: &str, args: &[&str]) -> String {
    let path = dir.join(format!("{name}.svg"));
    let mut a = args.to_vec();
    a.extend(["--plot", path.to_str().unwrap()]);
    run_quiet(&a);
    std::fs::read_to_string(&path).unwrap()
}

/// The default loop as the figures name it: the CLI's device (0.1 kg) held by the typical
/// arm, the paper's backward difference, T = 1 ms, no delay.
const DEFAULT_LOOP: &str = "device 0.1 kg + arm, backward difference, T = 1 ms, t_d = 0";

#[test]
fn legends_lie_below_the_axes_and_subtitles_name_the_loop() {
    let dir = tempfile::tempdir().unwrap();
    let k_axis = "virtual stiffness K (N/m)";
    let cases: [(&str, Vec<&str>, &str, Vec<&str>); 4] = [
        (
            "kmax",
            vec!["kmax"],
            k_axis,
            vec!["stable (exact)", "damping range 0 Ns/m ≤ B ≤ ∞"],
        ),
        ("boundary", vec!["boundary"], k_axis, vec!["stable (exact)"]),
        (
            "simb",
            vec!["simboundary", "--quantization", "3e-5", "--beta-count", "3"],
            k_axis,
            vec!["exact linear stable region", "simulated boundary"],
        ),
        (
            "sweep",
            vec!["sweep", "--param", "delay-time:0:0.004:5"],
            "delay-time (ms)",
            vec!["stable (exact)"],
        ),
    ];
    for (name, args, x_title, labels) in cases {
        let svg = plot_svg(dir.path(), name, &args);
        // below the x-axis title, hence below every data point and tick label
        let axis = text_y(&svg, x_title);
        for l in labels {
            assert!(
                text_y(&svg, l) > axis,
                "{name}: legend entry '{l}' not below the axes"
            );
        }
        if name != "sweep" {
            assert!(svg.contains(DEFAULT_LOOP), "{name}: no loop subtitle");
        } else {
            // the swept delay is left out of the loop's description
            let want = "device 0.1 kg + arm, backward difference, T = 1 ms";
            assert!(
                svg_texts(&svg).iter().any(|t| t.3 == want),
                "sweep subtitle"
            );
        }
    }
}

#[test]
fn check_plot_names_the_loop_and_zooms_on_the_wall_and_on_z_1() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "check",
        "--velocity",
        "lowpass:100",
        "--delay-time",
        "0.002",
        "--no-arm",
    ];
    let svg = plot_svg(dir.path(), "c", &args);
    assert!(svg.contains("m = 0.1 kg, b = 1.5 Ns/m, low-pass 100 Hz, T = 1 ms, t_d = 2 ms"));
    let svg = plot_svg(dir.path(), "d", &["check"]);
    assert!(svg.contains(DEFAULT_LOOP));
    let (w, h) = svg_size(&svg);
    let extent = |t: &[(f64, f64)]| {
        t.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p.0), b.max(p.0))
            })
    };
    // lower left: the wall zoom, its K ticks around the wall's 10 kN/m and far narrower
    // than the whole region (K from 0 to 765 kN/m)
    let zoom = axes(&svg, [0.0, 0.5 * w, 0.5 * h, h]);
    let (k_lo, k_hi) = extent(&zoom.x_ticks);
    assert!(
        k_lo <= 10e3 && k_hi >= 10e3 && k_hi - k_lo < 100e3,
        "{:?}",
        zoom.x_ticks
    );
    let (b_lo, b_hi) = extent(&zoom.y_ticks);
    assert!(b_lo <= 10.0 && b_hi >= 10.0 && b_hi - b_lo < 500.0);
    // lower right: around z = 1, holding the roots of check --json within 0.5 of it
    let z1 = axes(&svg, [0.5 * w, w, 0.5 * h, h]);
    let (re_lo, re_hi) = extent(&z1.x_ticks);
    let (im_lo, im_hi) = extent(&z1.y_ticks);
    assert!(re_lo > 0.5 && re_hi < 1.5 && re_lo < 1.0 && re_hi > 1.0);
    let v = json(&["check"]);
    let near: Vec<(f64, f64)> = v["roots"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| (f(&r[0]), f(&r[1])))
        .filter(|r| (r.0 - 1.0).hypot(r.1) < 0.5)
        .collect();
    assert_eq!(near.len(), 2, "{v}");
    for (re, im) in near {
        let (px, py) = ((re_hi - re_lo) / 50.0, (im_hi - im_lo) / 50.0);
        assert!(
            re > re_lo - px && im > im_lo - py && im < im_hi + py,
            "root {re} {im}"
        );
    }
}

#[test]
fn sweep_plots_k_max_on_a_log_axis() {
    let dir = tempfile::tempdir().unwrap();
    let args = ["sweep", "--param", "delay-time:0:0.005:6", "--no-arm"];
    let svg = plot_svg(dir.path(), "s", &args);
    // the y tick labels lie at equal distances per decade: y = a + b·log10(value)
    let ax = axes(&svg, WHOLE);
    let t: Vec<(f64, f64)> = ax.y_ticks.iter().map(|(v, y)| (v.log10(), *y)).collect();
    assert!(t.len() >= 4, "{t:?}");
    let (lo, hi) = (t[0].0.min(t[t.len() - 1].0), t[0].0.max(t[t.len() - 1].0));
    assert!(hi - lo > 1.5, "less than two decades: {t:?}");
    let slope = (t[t.len() - 1].1 - t[0].1) / (t[t.len() - 1].0 - t[0].0);
    for (lv, y) in &t {
        let fit = t[0].1 + slope * (lv - t[0].0);
        assert!(
            (y - fit).abs() <= 1.5,
            "tick {lv} at {y}, log fit {fit}: {t:?}"
        );
    }
}

#[test]
fn zwidth_outlines_every_passive_region_over_the_fills() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "zwidth",
        "--no-arm",
        "--compare",
        "lowpass:100",
        "--compare",
        "average:15",
    ];
    let svg = plot_svg(dir.path(), "z", &args);
    // after the last filled polygon (the zoom's), each loop's colour outlines its region
    let tail = &svg[svg.rfind("<polygon").unwrap()..];
    for c in ["#0072B2", "#D55E00", "#009E73"] {
        let outlined = tail
            .split("<polyline")
            .skip(1)
            .any(|p| p.contains(&format!("stroke=\"{c}\"")) && p.contains("stroke-width=\"3\""));
        assert!(outlined, "no outline in {c} over the fills");
    }
}

#[test]
fn simulate_plot_shows_the_transient_and_the_judged_window() {
    let dir = tempfile::tempdir().unwrap();
    let svg = plot_svg(dir.path(), "sim", &["simulate"]);
    assert!(svg.contains(DEFAULT_LOOP));
    // the run's second half is judged (10 s by default)
    assert!(svg.contains("judged window t = 5 … 10 s"), "judged window");
    let label = svg_texts(&svg)
        .into_iter()
        .map(|t| t.3)
        .find(|t| t.contains("the transient, first"))
        .expect("transient axis label");
    let shown: f64 = label
        .split("first ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap();
    // the motion decays by the spectral radius ρ per sample: it falls to 2 % of its peak
    // after ln(0.02)/ln(ρ) samples; the panel shows about 1.3 times that
    let rho = f(&json(&["check"])["spectral_radius"]);
    let t2 = 0.02f64.ln() / rho.ln() * 1e-3;
    assert!(
        shown >= t2 && shown <= 1.5 * t2,
        "shown {shown} s, 2 % after {t2} s"
    );
}

// ---- progress bars ---------------------------------------------------------------------

/// Every command with a progress bar, run in text mode (where a bar would be drawn on a
/// terminal) on a small problem: standard error is not a terminal under the test harness,
/// so it stays empty.
#[test]
fn long_commands_write_nothing_to_a_non_terminal_stderr() {
    let dir = tempfile::tempdir().unwrap();
    let plot = dir.path().join("b");
    let runs: Vec<Vec<&str>> = vec![
        vec!["kmax", "--robust", "--box-samples", "3"],
        vec![
            "map",
            "--x",
            "alpha:0:1:300",
            "--y",
            "beta:0:1:300",
            "--delay",
            "50",
        ],
        vec!["sweep", "--param", "delay-time:0:0.002:3"],
        vec!["zwidth", "--compare", "lowpass:100"],
        vec![
            "simboundary",
            "--no-arm",
            "--beta-min",
            "0.1",
            "--beta-max",
            "0.3",
            "--beta-count",
            "2",
            "--duration-samples",
            "2000",
            "--rel-tol",
            "1e-2",
            "--plot",
            plot.to_str().unwrap(),
        ],
    ];
    for args in runs {
        let out = run_quiet(&args);
        assert!(!out.is_empty(), "{args:?} printed nothing");
    }
}

/// A growing run (the bilateral wall α = 0.5, β = 0.2 beyond α_max at γ = 0.001, δ = 0.005,
/// d = 1, from the default x(0) = 1 mm) that blows up: its figure ends where |x| first exceeds
/// 10³ × 1 mm = 1 m and says so, so every tick label stays within 1000 (mm, samples, T²F/m);
/// the CSV keeps every recorded row, out to the blow-up.
#[test]
fn simulate_plot_of_a_growing_run_is_clipped_at_a_thousand_times_its_start() {
    let dir = tempfile::tempdir().unwrap();
    let stem = dir.path().join("run");
    let csv = dir.path().join("run.csv");
    let v = json(&[
        "simulate",
        "--alpha",
        "0.5",
        "--beta",
        "0.2",
        "--gamma",
        "0.001",
        "--delta",
        "0.005",
        "--delay",
        "1",
        "--plot",
        stem.to_str().unwrap(),
        "--csv",
        csv.to_str().unwrap(),
    ]);
    assert_eq!(
        (&v["outcome"], &v["blown_up"]),
        (&"growing".into(), &true.into())
    );
    let svg = std::fs::read_to_string(dir.path().join("run.svg")).unwrap();
    let texts: Vec<String> = svg_texts(&svg).into_iter().map(|t| t.3).collect();
    assert!(
        texts
            .iter()
            .any(|t| t.starts_with("unstable: clipped at t = ") && t.ends_with(", |x| &gt; 1 m"))
            && texts.iter().any(|t| t == "position x (mm)"),
        "{texts:?}"
    );
    let ticks: Vec<f64> = texts.iter().filter_map(|t| tick_value(t)).collect();
    assert!(
        ticks.len() > 10 && ticks.iter().all(|t| t.abs() <= 1000.0),
        "{ticks:?}"
    );
    let peak = std::fs::read_to_string(&csv)
        .unwrap()
        .lines()
        .skip(1)
        .filter_map(|l| l.split(',').nth(1)?.parse::<f64>().ok())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(peak > 1e90, "the CSV keeps the whole run: {peak}");
}
