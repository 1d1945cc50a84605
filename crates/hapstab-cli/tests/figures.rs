//! Figures in physical units (`--plot` of boundary, map, kmax, check), a growing simulation's
//! clipped figure, kmax's damping range, and quiet standard error when it is not a terminal.
//! Expected values come from the library or from closed forms, never from the program's own
//! output.

mod common;

use common::hapstab;
use hapstab::loop_analysis::{damping_units, k_max_at_damping, k_max_within};
use hapstab::model::Loop;
use hapstab::{AffineFamily, Effective};
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
    let fam = AffineFamily::of_loop(&lp).unwrap();
    let best = k_max_within(&lp, &fam, 0.0, f64::INFINITY)
        .unwrap()
        .unwrap();
    let (k, b) = fam.to_physical(best.alpha, best.beta);
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
    let free = k_max_within(&lp, &fam, f64::NEG_INFINITY, f64::INFINITY)
        .unwrap()
        .unwrap();
    assert!(free.beta < 0.0 && free.alpha > best.alpha);
    // K_max at B = 0 (the plant's own damping only)
    let at0 = k_max_at_damping(&lp, &fam, 0.0).unwrap().unwrap();
    let k0 = fam.to_physical(at0.hi, 0.0).0;
    assert!((f(&v["k_max_at_zero_damping"]) - k0).abs() <= 1e-12 * k0);
}

#[test]
fn kmax_damping_range_bounds_the_damping() {
    let lp = default_loop(0);
    let fam = AffineFamily::of_loop(&lp).unwrap();
    let hi = damping_units(&lp, &fam, 50.0).unwrap();
    let best = k_max_within(&lp, &fam, 0.0, hi).unwrap().unwrap();
    let (k, b) = fam.to_physical(best.alpha, best.beta);
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

/// Data coordinates of the anchor of the text `tag` in the panel whose tick labels lie in
/// x < `panel_right` px, and the data size of one pixel along each axis.
fn tag_position(svg: &str, tag: &str, panel_right: f64) -> ((f64, f64), (f64, f64)) {
    let texts = svg_texts(svg);
    let numeric = |t: &(f64, f64, String, String)| tick_value(&t.3);
    let x_ticks: Vec<(f64, f64)> = texts
        .iter()
        .filter(|t| t.2 == "middle" && t.0 < panel_right)
        .filter_map(|t| numeric(t).map(|v| (v, t.0)))
        .collect();
    let y_ticks: Vec<(f64, f64)> = texts
        .iter()
        .filter(|t| t.2 == "end" && t.0 < panel_right)
        .filter_map(|t| numeric(t).map(|v| (v, t.1)))
        .collect();
    let (fx, fy) = (axis_map(&x_ticks), axis_map(&y_ticks));
    let hits: Vec<_> = texts.iter().filter(|t| t.3 == tag).collect();
    assert_eq!(hits.len(), 1, "text '{tag}' in {texts:?}");
    let (x, y) = (hits[0].0, hits[0].1);
    let px = ((fx(x + 1.0) - fx(x)).abs(), (fy(y + 1.0) - fy(y)).abs());
    ((fx(x), fy(y)), px)
}

/// Asserts that a tag lies at `want` to within 1.5 px on each axis.
fn assert_at(svg: &str, tag: &str, panel_right: f64, want: (f64, f64)) {
    let ((x, y), (px, py)) = tag_position(svg, tag, panel_right);
    assert!(
        (x - want.0).abs() <= 1.5 * px && (y - want.1).abs() <= 1.5 * py,
        "{tag} at ({x}, {y}), expected {want:?} (pixel {px}, {py})"
    );
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
    let fam = AffineFamily::of_loop(&lp).unwrap();
    let r = hapstab::loop_analysis::region(&lp, &fam).unwrap();
    let want = fam.to_physical(r.alpha_max, r.beta_at_alpha_max);
    assert_at(&svg, "K_max", f64::INFINITY, want);
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
    let fam = AffineFamily::of_loop(&lp).unwrap();
    let r = hapstab::loop_analysis::region(&lp, &fam).unwrap();
    assert_at(
        &svg,
        "α_max",
        f64::INFINITY,
        (r.alpha_max, r.beta_at_alpha_max),
    );
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
    // two panels side by side: the region's ticks lie in the left half
    let width: f64 = svg_texts(&svg).iter().map(|t| t.0).fold(0.0, f64::max);
    assert_at(&svg, "wall", 0.5 * width.max(1600.0), (k, b));
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
    let fam = AffineFamily::of_loop(&lp).unwrap();
    let hi = damping_units(&lp, &fam, 300.0).unwrap();
    let best = k_max_within(&lp, &fam, 0.0, hi).unwrap().unwrap();
    assert_at(
        &svg,
        "K_max",
        f64::INFINITY,
        fam.to_physical(best.alpha, best.beta),
    );
    let at0 = k_max_at_damping(&lp, &fam, 0.0).unwrap().unwrap();
    assert_at(
        &svg,
        "B = 0",
        f64::INFINITY,
        (fam.to_physical(at0.hi, 0.0).0, 0.0),
    );
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
