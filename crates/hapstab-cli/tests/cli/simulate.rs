//! Binary tests of `hapstab simulate` (and the run flags `simboundary` shares): verdicts
//! against the linear analysis of `hapstab check`, the CSV trace, the plots, quantization
//! limit cycles, bouncing and separation from a unilateral wall, and bad or hostile input
//! (exit 2, one line on stderr, nothing written). `simboundary`'s own tests are in
//! `simboundary.rs`.

use crate::common;

use common::hapstab;
use std::path::Path;

use serde_json::Value;

/// Runs with `--json`, asserting success and an empty stderr (no progress bar).
pub(crate) fn json(args: &[&str]) -> Value {
    let mut all = args.to_vec();
    all.push("--json");
    serde_json::from_slice(&common::quiet_stdout_in(&std::env::temp_dir(), &all)).unwrap()
}

/// `simulate` with its CSV and plot in `dir` (named `name`).
fn simulate(dir: &Path, name: &str, args: &[&str]) -> Value {
    let csv = dir.join(format!("{name}.csv"));
    let plot = dir.join(name);
    let mut all = vec!["simulate", "--csv", csv.to_str().unwrap()];
    all.extend(["--plot", plot.to_str().unwrap()]);
    all.extend(args);
    json(&all)
}

pub(crate) fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

pub(crate) fn assert_png(path: &Path) {
    let img = image::open(path).unwrap().to_rgb8();
    let (w, h) = img.dimensions();
    assert!(w >= 900 && h >= 700, "{w}x{h}");
    let ink = img.pixels().filter(|p| p.0 != [255, 255, 255]).count();
    assert!(ink > (w * h) as usize / 50, "blank PNG: {ink} pixels");
}

/// The linear bilateral loop: the outcome agrees with the stability test of `hapstab check`,
/// the spectral radius beside it is check's, and the measured envelope growth is a
/// measurement of it (log-rate within 5 %), on both sides of the boundary, in normalized and
/// physical units and with delay.
#[test]
fn linear_verdict_and_growth_match_check() {
    let dir = tempfile::tempdir().unwrap();
    let points: [&[&str]; 5] = [
        // Pure mass, d = 0: stable iff α < 2β(2 − β)/(2 + β) = 0.6 at β = 0.5.
        &["--alpha", "0.55", "--beta", "0.5"],
        &["--alpha", "0.66", "--beta", "0.5"],
        &[
            "--alpha", "0.05", "--beta", "0.2", "--gamma", "0.001", "--delta", "0.015", "--delay",
            "2",
        ],
        // Physical: the default arm and device, K = 10 kN/m and 900 kN/m, B = 10 Ns/m, d = 1.
        &["--wall-stiffness", "10000", "--delay", "1"],
        &["--wall-stiffness", "900000", "--delay", "1"],
    ];
    let mut verdicts = Vec::new();
    for (i, p) in points.iter().enumerate() {
        let chk = json(&[&["check"], *p].concat());
        let sim = simulate(
            dir.path(),
            &format!("p{i}"),
            &[&["--duration-samples", "3000"], *p].concat(),
        );
        let rho = f(&chk["spectral_radius"]);
        let g = f(&sim["measured_growth_per_sample"]);
        assert!(
            (g.ln() - rho.ln()).abs() <= 0.05 * rho.ln().abs(),
            "{p:?}: growth {g} vs spectral radius {rho}"
        );
        assert_eq!(f(&sim["spectral_radius"]), rho, "{p:?}");
        let stable = chk["stable"].as_bool().unwrap();
        let expect = if stable { "decaying" } else { "growing" };
        assert_eq!(sim["outcome"], expect, "{p:?}");
        assert_eq!(sim["linear_window"], true, "{p:?}");
        assert_eq!(sim["linear_verdict"], chk["verdict"], "{p:?}");
        assert_eq!(sim["normalized"], chk["normalized"], "{p:?}");
        verdicts.push(stable);
    }
    assert_eq!(verdicts, [true, false, true, true, false]);
}

#[test]
fn csv_trace_plot_files() {
    let dir = tempfile::tempdir().unwrap();
    let v = simulate(
        dir.path(),
        "run",
        &[
            "--alpha",
            "0.3",
            "--beta",
            "0.4",
            "--duration-samples",
            "500",
        ],
    );
    assert_eq!(v["samples"], 500);
    assert_eq!(v["units"], "normalized");
    let files = &v["files"];
    assert_eq!(files["rows"], 500);
    assert_eq!(files["record_every"], 1);
    let csv_path = dir.path().join("run.csv");
    assert_eq!(files["csv"], csv_path.to_str().unwrap());
    let text = std::fs::read_to_string(&csv_path).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("t,x,v,F"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 500);
    // Normalized units: t counts samples; x(0) = 1 mm at rest; F = α x + β (x − x_prev).
    assert_eq!(rows[0], vec![0.0, 1e-3, 0.0, 0.3 * 1e-3]);
    assert!(rows.windows(2).all(|w| w[1][0] == w[0][0] + 1.0));
    for (name, ext) in [("svg", "svg"), ("png", "png")] {
        let p = dir.path().join(format!("run.{ext}"));
        assert_eq!(files[name], p.to_str().unwrap());
        assert!(p.is_file(), "{} missing", p.display());
    }
    assert_png(&dir.path().join("run.png"));
    let svg = std::fs::read_to_string(dir.path().join("run.svg")).unwrap();
    for t in [
        "position x",
        "wall force",
        "time t (samples)",
        "Simulation: decaying",
        "judged window",
    ] {
        assert!(svg.contains(t), "SVG lacks {t}");
    }
}

/// Physical units, a run extended until it settles: the trace keeps at most --max-rows rows,
/// every n-th sample over the whole run.
#[test]
fn csv_trace_of_a_long_run_is_thinned_to_max_rows() {
    let dir = tempfile::tempdir().unwrap();
    let v = simulate(
        dir.path(),
        "long",
        &[
            "--duration",
            "2",
            "--max-rows",
            "300",
            "--unilateral",
            "--push",
            "3",
        ],
    );
    let samples = v["samples"].as_u64().unwrap();
    assert!(samples >= 2000);
    let every = v["files"]["record_every"].as_u64().unwrap();
    let rows = v["files"]["rows"].as_u64().unwrap();
    assert!((150..=300).contains(&rows), "{rows}");
    assert!(every >= 2000u64.div_ceil(299));
    assert_eq!(rows, samples.div_ceil(every), "rows cover the whole run");
    let text = std::fs::read_to_string(dir.path().join("long.csv")).unwrap();
    assert_eq!(text.lines().count() as u64, rows + 1);
    let t1: f64 = text
        .lines()
        .nth(2)
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!((t1 - every as f64 * 1e-3).abs() < 1e-12, "{t1}");
    assert!(
        std::fs::read_to_string(dir.path().join("long.svg"))
            .unwrap()
            .contains("human push F_H")
    );
}

/// Quantization near the boundary (Diolaiti et al., the paper's [13]): a PHANToM-like device
/// without arm (m = 0.1 kg, b = 1.5 Ns/m, δ = 0.015), 30 µm encoder, β = 0.1 and α at 90 %
/// of the exact linear limit: linearly stable, yet the run sustains a limit cycle of about
/// one encoder step near the frequency of the dominant linear mode.
#[test]
fn quantization_limit_cycle_near_the_boundary() {
    let dir = tempfile::tempdir().unwrap();
    let chk = json(&["check", "--no-arm", "--alpha", "0.1", "--beta", "0.1"]);
    let lin = f(&chk["alpha_interval"][1]);
    let alpha = format!("{}", 0.9 * lin);
    let base = ["--no-arm", "--alpha", alpha.as_str(), "--beta", "0.1"];
    let chk = json(&[&["check"][..], &base].concat());
    assert_eq!(chk["stable"], true);
    // Dominant root → frequency of the linear mode.
    let (re, im) = (f(&chk["roots"][0][0]), f(&chk["roots"][0][1]));
    let f_dom = im.atan2(re).abs() / (2.0 * std::f64::consts::PI * 1e-3);
    let q = 3e-5;
    let v = simulate(
        dir.path(),
        "q",
        &[&base[..], &["--quantization", "3e-5", "--duration", "5"]].concat(),
    );
    assert_eq!(v["outcome"], "limit_cycle", "{v}");
    assert_eq!(v["linear_verdict"], "stable");
    let lc = &v["limit_cycle"];
    let a = f(&lc["peak_to_peak"]);
    assert!(a > 0.5 * q && a < 20.0 * q, "amplitude {a}");
    assert!((f(&lc["counts"]) - a / q).abs() < 1e-9 * a / q);
    assert_eq!(lc["bouncing"], false);
    let fr = f(&lc["frequency_hz"]);
    assert!(
        (fr / f_dom - 1.0).abs() < 0.25,
        "frequency {fr} Hz vs linear mode {f_dom} Hz"
    );
    assert!(v["measured_growth_per_sample"].is_null());
    let svg = std::fs::read_to_string(dir.path().join("q.svg")).unwrap();
    assert!(svg.contains("Limit cycle: the last periods"));
    assert!(svg.contains("quantization q = 3e-5 m"));
    // The same run without quantization decays and reports no amplitude.
    let v = simulate(
        dir.path(),
        "lin",
        &[&base[..], &["--duration", "5"]].concat(),
    );
    assert_eq!(v["outcome"], "decaying");
    assert!(v["limit_cycle"].is_null());
}

/// Bad input exits 2 with exactly one line on stderr and nothing on stdout.
#[test]
fn bad_input_exits_2_with_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let cases: &[&[&str]] = &[
        &["simulate", "--quantization", "-1e-5"],
        &["simulate", "--quantization", "0"],
        &["simulate", "--duration", "0"],
        &["simulate", "--duration", "-1"],
        &["simulate", "--duration-samples", "0"],
        &["simulate", "--duration-samples", "2.5"],
        &["simulate", "--duration", "1", "--duration-samples", "100"],
        &[
            "simulate",
            "--alpha",
            "0.1",
            "--beta",
            "0.1",
            "--duration",
            "1",
        ],
        &["simulate", "--alpha", "NaN", "--beta", "0.1"],
        &["simulate", "--push", "nan"],
        &["simulate", "--initial-position", "inf"],
        &["simulate", "--coulomb", "2", "--stiction", "1"],
        &["simulate", "--saturation", "-3"],
        &["simulate", "--duration", "1e9"],
        &["simulate", "--no-pull"],
        &["simulate", "--max-rows", "1"],
        &["simulate", "--csv", "/nonexistent-dir/x.csv"],
        &["simboundary", "--beta-count", "0"],
        &["simboundary", "--rel-tol", "2"],
        &["simboundary", "--beta-min", "0.5", "--beta-max", "0.1"],
        &["simboundary", "--stable-amplitude", "-1"],
        &["simboundary", "--quantization", "NaN"],
        &["simboundary", "--rel-tol", "1e-17"],
        &["simboundary", "--rel-tol", "0"],
        &["simboundary", "--plot", "/nonexistent-dir/b"],
        &[
            "simulate",
            "--max-rows",
            "100000000",
            "--duration-samples",
            "1e8",
        ],
        &["simulate", "--plot", "/nonexistent-dir/x"],
        &["simulate", "--duration", "2", "--max-duration", "1"],
        &["simulate", "--max-duration", "1e7"],
        &["simulate", "--max-duration", "-1"],
        &[
            "simulate",
            "--alpha",
            "0.1",
            "--beta",
            "0.1",
            "--max-duration",
            "5",
        ],
        &["simulate", "--max-duration-samples", "1e12"],
        &[
            "simulate",
            "--max-duration",
            "5",
            "--max-duration-samples",
            "5000",
        ],
    ];
    for args in cases {
        let out = hapstab()
            .current_dir(dir.path())
            .args(*args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
    // Nothing was written by the failed runs.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// Runs a command in `dir`, expecting exit 2 with one line on stderr that contains `needle`.
fn refused(dir: &Path, args: &[&str], needle: &str) -> std::time::Duration {
    let t0 = std::time::Instant::now();
    let out = hapstab().current_dir(dir).args(args).output().unwrap();
    let took = t0.elapsed();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    assert!(err.contains(needle), "{args:?}: {err}");
    took
}

/// Hostile sizes are refused before any work, naming the flag: a bisection tolerance below
/// the documented minimum (it would never end), a trace of 10⁸ rows (4 GB), a plot in a
/// folder that does not exist (which is not created).
#[test]
fn hostile_sizes_are_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let quick = std::time::Duration::from_secs(5);
    let t = refused(
        dir.path(),
        &["simboundary", "--unilateral", "--rel-tol", "1e-17"],
        "--rel-tol",
    );
    assert!(t < quick, "{t:?}");
    let t = refused(
        dir.path(),
        &[
            "simulate",
            "--duration-samples",
            "1e8",
            "--max-rows",
            "100000000",
        ],
        "--max-rows",
    );
    assert!(t < quick, "{t:?}");
    refused(
        dir.path(),
        &["simulate", "--plot", "/nonexistent-hapstab-dir/x"],
        "/nonexistent-hapstab-dir",
    );
    assert!(!Path::new("/nonexistent-hapstab-dir").exists());
    refused(
        dir.path(),
        &["simulate", "--csv", "/nonexistent-hapstab-dir/x.csv"],
        "--csv",
    );
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// Plain `simulate` (text and JSON) writes no file.
#[test]
fn plain_simulate_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    for json in [false, true] {
        let mut cmd = hapstab();
        cmd.current_dir(dir.path())
            .args(["simulate", "--duration", "1"]);
        if json {
            cmd.arg("--json");
        }
        let out = cmd.output().unwrap();
        assert!(out.status.success());
        let text = String::from_utf8(out.stdout).unwrap();
        assert!(!text.contains("files"), "{text}");
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// The device of the reproductions: 0.2 kg, 2 Ns/m, with the default arm, d = 1.
const DEVICE: [&str; 6] = [
    "--device-mass",
    "0.2",
    "--device-damping",
    "2",
    "--delay",
    "1",
];

pub(crate) fn text(args: &[&str]) -> String {
    let out = hapstab().args(args).output().unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// Every number printed on a "growth" line, in order.
fn growth_numbers(text: &str) -> Vec<f64> {
    text.lines()
        .filter(|l| l.starts_with("growth"))
        .flat_map(|l| l.split_whitespace().filter_map(|w| w.parse::<f64>().ok()))
        .collect()
}

/// Reproduction: K = 20 kN/m, B = 5 Ns/m against a unilateral wall, pushed with 1 N, from
/// the surface at 10 mm/s, 0.3 s. In contact the loop is unstable (spectral radius 1.007, as
/// `check` says): the run is a bouncing limit cycle, and the output says that contact is lost
/// and regained every cycle; it prints no growth factor below 1.
#[test]
fn unstable_unilateral_contact_is_a_bouncing_cycle() {
    let run = [
        &DEVICE[..],
        &[
            "--wall-stiffness",
            "20000",
            "--wall-damping",
            "5",
            "--unilateral",
            "--push",
            "1",
            "--initial-position",
            "0",
            "--initial-velocity",
            "0.01",
            "--duration",
            "0.3",
        ],
    ]
    .concat();
    let chk = json(
        &[
            &["check"],
            &DEVICE[..],
            &["--wall-stiffness", "20000", "--wall-damping", "5"],
        ]
        .concat(),
    );
    assert_eq!(chk["verdict"], "unstable");
    let v = json(&[&["simulate"], &run[..]].concat());
    assert_eq!(v["outcome"], "limit_cycle", "{v}");
    assert_eq!(v["limit_cycle"]["bouncing"], true);
    assert!(v["measured_growth_per_sample"].is_null());
    assert_eq!(v["spectral_radius"], chk["spectral_radius"]);
    assert!(
        v["contact"]["judged_separations"].as_u64().unwrap() >= 10,
        "{v}"
    );
    let t = text(&[&["simulate"], &run[..]].concat());
    assert!(t.contains("LIMIT CYCLE, BOUNCING"), "{t}");
    assert!(
        t.contains("contact is lost and regained every cycle"),
        "{t}"
    );
    assert!(growth_numbers(&t).iter().all(|g| *g >= 1.0), "{t}");
    assert!(!t.contains("DECAYING"), "{t}");
}

/// Reproduction: K = 8 kN/m (stable in contact), 10 µm encoder, pushed with 2 N. A 2 s run
/// has not settled (a slowly decaying transient); it is extended and reports the same
/// limit cycle as a 20 s run: about 25 µm peak-to-peak (2.5 counts).
#[test]
fn quantized_contact_reports_the_settled_cycle() {
    let base = [
        &DEVICE[..],
        &[
            "--wall-stiffness",
            "8000",
            "--wall-damping",
            "5",
            "--quantization",
            "1e-5",
            "--unilateral",
            "--push",
            "2",
        ],
    ]
    .concat();
    let short = json(&[&["simulate"], &base[..], &["--duration", "2"]].concat());
    let long = json(&[&["simulate"], &base[..], &["--duration", "20"]].concat());
    assert!(f(&short["samples"]) > 2000.0, "extended: {short}");
    for v in [&short, &long] {
        assert_eq!(v["outcome"], "limit_cycle", "{v}");
        assert_eq!(v["linear_verdict"], "stable");
        let counts = f(&v["limit_cycle"]["counts"]);
        assert!((2.0..4.0).contains(&counts), "{v}");
    }
    let pp = |v: &Value| f(&v["limit_cycle"]["peak_to_peak"]);
    assert!((pp(&short) / pp(&long) - 1.0).abs() < 0.1);
    let t = text(&[&["simulate"], &base[..], &["--duration", "2"]].concat());
    assert!(
        t.contains("counts)") && t.contains("µm peak-to-peak"),
        "{t}"
    );
    assert!(t.contains("extended from 2000 samples"), "{t}");
}

/// The loop flags of a general loop: a two-mass device with an actuator lag, a low-pass
/// velocity and a fractional delay (order 5, t_d = 1.4 T).
pub(crate) const TWO_MASS: [&str; 14] = [
    "--motor-mass",
    "0.05",
    "--handle-mass",
    "0.05",
    "--transmission-stiffness",
    "5000",
    "--transmission-damping",
    "1",
    "--force-lag",
    "0.0002",
    "--velocity",
    "lowpass:150",
    "--delay-time",
    "0.0014",
];

/// A transfer-function plant with an average velocity (order 3 with a real pole).
const TF: [&str; 6] = [
    "--plant-num",
    "1",
    "--plant-den",
    "0.001,0.21,3,300",
    "--velocity",
    "average:3",
];

/// `simulate` on general loops: its spectral radius is `check`'s for the same flags, its
/// verdict agrees with check's stability on both sides of the boundary, the measured growth
/// lies on the same side of 1, and the input echo is the loop.
#[test]
fn general_loops_simulate_like_check() {
    for plant in [&TWO_MASS[..], &TF[..]] {
        let mut seen = Vec::new();
        for (k, b) in [("1000", "4"), ("60000", "4")] {
            let mut args: Vec<&str> = plant.to_vec();
            args.extend(["--wall-stiffness", k, "--wall-damping", b]);
            let mut c = vec!["check"];
            c.extend(&args);
            let check = json(&c);
            let mut s = vec!["simulate"];
            s.extend(&args);
            let sim = json(&s);
            let tag = format!("{args:?}: {sim}");
            assert_eq!(sim["spectral_radius"], check["spectral_radius"], "{tag}");
            let stable = check["stable"].as_bool().unwrap();
            seen.push(stable);
            let outcome = sim["outcome"].as_str().unwrap();
            assert_eq!(
                outcome,
                if stable { "decaying" } else { "growing" },
                "{tag}"
            );
            let g = f(&sim["measured_growth_per_sample"]);
            assert_eq!(g < 1.0, stable, "{tag}");
            assert_eq!(sim["input"]["wall"]["stiffness"], k.parse::<f64>().unwrap());
            assert!(sim["input"]["loop"]["plant"].is_object(), "{tag}");
            assert!(sim.get("normalized").is_none(), "{tag}");
        }
        assert_eq!(seen, [true, false], "both sides of the boundary: {plant:?}");
    }
}

/// Friction acts on a mass: on a transfer-function plant it is refused with one line naming
/// the flags, exit 2; on a two-mass device it acts on the motor side and runs.
#[test]
fn friction_needs_a_mass() {
    let mut args = vec!["simulate"];
    args.extend(TF);
    args.extend(["--coulomb", "0.1"]);
    let out = hapstab().args(&args).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(
        err.contains("--coulomb/--stiction") && err.contains("--plant-num"),
        "{err}"
    );
    let mut args = vec!["simulate"];
    args.extend(TWO_MASS);
    args.extend([
        "--wall-stiffness",
        "1000",
        "--coulomb",
        "0.2",
        "--push",
        "1",
    ]);
    let v = json(&args);
    assert_eq!(v["input"]["effects"]["friction"]["coulomb"], 0.2);
}
