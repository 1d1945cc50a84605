//! Binary tests of `hapstab simboundary`: the simulated stability boundary against the exact
//! linear one (`hapstab check`'s stable K interval), its table, CSV and plot in the user's
//! units, and a run that leaves the wall counted as no evidence of stability.

use crate::common;
use crate::simulate::{TWO_MASS, assert_png, f, json, text};

#[test]
fn simboundary_table_csv_plot() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("b.csv");
    let plot = dir.path().join("b");
    let v = json(&[
        "simboundary",
        "--no-arm",
        "--quantization",
        "3e-5",
        "--stable-amplitude",
        "6e-4",
        "--beta-min",
        "0.1",
        "--beta-max",
        "0.5",
        "--beta-count",
        "3",
        "--duration-samples",
        "3000",
        "--rel-tol",
        "1e-2",
        "--csv",
        csv.to_str().unwrap(),
        "--plot",
        plot.to_str().unwrap(),
    ]);
    let pts = v["points"].as_array().unwrap();
    assert_eq!(pts.len(), 3);
    // Physical input (the device without arm): the rows speak N/m and Ns/m, B = β·m/T with
    // m = 0.1 kg and T = 1 ms; no α or β key.
    for (p, beta) in pts.iter().zip([0.1, 0.3, 0.5]) {
        let b = f(&p["wall_damping"]);
        assert!((b - beta * 100.0).abs() < 1e-9, "{p}");
        for key in ["beta", "alpha_linear", "alpha_simulated", "alpha_max"] {
            assert!(p.get(key).is_none(), "{key} in a physical row: {p}");
        }
        // The exact linear limit agrees with `hapstab check` at that B.
        let chk = json(&[
            "check",
            "--no-arm",
            "--wall-stiffness",
            "1",
            "--wall-damping",
            &b.to_string(),
        ]);
        let lin = f(&chk["k_interval"][1]);
        assert!((f(&p["k_linear"]) / lin - 1.0).abs() < 1e-9, "{p}");
        // Small quantization limit cycles accepted: the boundary stays near the linear one.
        let r = f(&p["ratio"]);
        assert!(r > 0.8 && r < 1.1, "{p}");
        let ratio = f(&p["k_simulated"]) / f(&p["k_linear"]);
        assert!((r - ratio).abs() < 1e-12, "{p}");
    }
    // α_max of the paper's Fig. 4 region at δ = 0.015, d = 0 is about 0.705: K = α·m/T².
    assert!(
        f(&v["exact_k_max"]) > 70e3 && f(&v["exact_k_max"]) < 71e3,
        "{v}"
    );
    assert!(v.get("exact_alpha_max").is_none());
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.starts_with(
        "wall_damping,k_linear,k_simulated,k_unstable,ratio,censored,k_max,runs,inconclusive_k,inconclusive_outcome\n"
    ));
    assert_eq!(text.lines().count(), 4);
    assert_png(&dir.path().join("b.png"));
    let svg = std::fs::read_to_string(dir.path().join("b.svg")).unwrap();
    // physical input, physical axes
    for t in [
        "exact linear stable region",
        "simulated boundary",
        "virtual stiffness K (N/m)",
        "virtual damping B (Ns/m)",
    ] {
        assert!(svg.contains(t), "SVG lacks {t}");
    }
    assert!(
        !svg.contains("virtual stiffness α"),
        "physical input drawn in α"
    );
}

/// Text mode, stdout not a terminal: the table in physical units, no progress bar on stderr,
/// and no file that was not asked for.
#[test]
fn simboundary_text_table() {
    let dir = tempfile::tempdir().unwrap();
    let out = common::quiet_stdout_in(
        dir.path(),
        &[
            "simboundary",
            "--beta-count",
            "2",
            "--duration-samples",
            "1000",
            "--rel-tol",
            "0.05",
        ],
    );
    let text = String::from_utf8(out).unwrap();
    assert!(
        text.contains("K simulated (N/m)")
            && text.contains("B (Ns/m)")
            && text.contains("exact       K_max = ")
            && !text.contains("α simulated"),
        "{text}"
    );
    // Nothing was asked to be written, so nothing was.
    assert!(!dir.path().join("simboundary.png").exists());
}

/// Reproduction: `simboundary --unilateral --quantization 1e-5` with a device without arm
/// and no push. The device leaves the wall and never returns; that must not count as
/// stability: no β is "stable up to the scan end", the points say the device left the wall,
/// and a warning suggests --push.
#[test]
fn simboundary_does_not_count_separation_as_stability() {
    let args = [
        "simboundary",
        "--no-arm",
        "--unilateral",
        "--quantization",
        "1e-5",
        "--beta-count",
        "3",
        "--duration-samples",
        "3000",
        "--rel-tol",
        "0.01",
    ];
    let v = json(&args);
    for p in v["points"].as_array().unwrap() {
        assert_eq!(p["censored"], false, "{p}");
        assert_eq!(p["inconclusive"]["outcome"], "separated", "{p}");
    }
    let w = v["warnings"].as_array().unwrap();
    assert!(
        w.iter().any(|w| w.as_str().unwrap().contains("--push")),
        "{w:?}"
    );
    let t = text(&args);
    assert!(!t.contains("stable up to scan end"), "{t}");
    assert!(
        t.contains("left the wall at K = ") && t.contains("kN/m") && t.contains("warning"),
        "{t}"
    );
    // Pushed, the same scan finds a boundary.
    let v = json(&[&args[..], &["--push", "2", "--stable-amplitude", "2e-4"]].concat());
    assert!(
        v["points"]
            .as_array()
            .unwrap()
            .iter()
            .any(|p| p["k_simulated"].is_number()),
        "{v}"
    );
}

/// `simboundary` on a general loop, linear and bilateral: at every damping the simulated
/// boundary brackets the exact one (from the loop's family) within the bisection tolerance,
/// in N/m; the exact K at a row's B equals the upper end of `check`'s stable K interval there.
#[test]
fn simboundary_of_a_general_loop_brackets_the_exact_boundary() {
    let mut args = vec!["simboundary"];
    args.extend(TWO_MASS);
    args.extend(["--beta-count", "3", "--grid", "6", "--rel-tol", "1e-3"]);
    args.extend(["--initial-velocity", "0.05", "--duration", "3"]);
    let v = json(&args);
    assert!(v.get("gamma").is_none());
    for p in v["points"].as_array().unwrap() {
        let lin = f(&p["k_linear"]);
        let sim = f(&p["k_simulated"]);
        let hi = p["inconclusive"]["wall_stiffness"]
            .as_f64()
            .or(p["k_unstable"].as_f64())
            .unwrap();
        assert!(sim <= lin * (1.0 + 1e-9) && lin <= hi * (1.0 + 2e-3), "{p}");
        assert!((hi - sim) <= 1e-3 * hi, "{p}");
        let b = p["wall_damping"].as_f64().unwrap().to_string();
        let mut c = vec!["check"];
        c.extend(TWO_MASS);
        c.extend(["--wall-stiffness", "1", "--wall-damping", &b]);
        let iv = json(&c)["k_interval"].clone();
        let k_hi = f(&iv[1]);
        assert!(
            (k_hi - f(&p["k_linear"])).abs() <= 1e-9 * k_hi,
            "{iv} vs {p}"
        );
    }
}

/// A loop in physical units takes its scan in Ns/m and N/m: B from 40 to 60 Ns/m and K up to
/// 200 kN/m of the device without arm (m = 0.1 kg, T = 1 ms) are β = B·T/m from 0.4 to 0.6
/// and α = K·T²/m up to 2 (Table I), the same runs to the bit.
#[test]
fn simboundary_takes_its_range_in_the_users_units() {
    let run = |range: &[&str]| {
        let mut args = vec![
            "simboundary",
            "--no-arm",
            "--beta-count",
            "2",
            "--duration-samples",
            "1000",
            "--rel-tol",
            "0.05",
        ];
        args.extend_from_slice(range);
        let mut v = json(&args);
        v["points"].take()
    };
    let physical = run(&[
        "--wall-damping-min",
        "40",
        "--wall-damping-max",
        "60",
        "--wall-stiffness-max",
        "2e5",
    ]);
    let normalized = run(&["--beta-min", "0.4", "--beta-max", "0.6", "--alpha-max", "2"]);
    // the same runs; the scan's top echoed in N/m, 2e5 up to a rounding of α·m/T²
    let (mut physical, mut normalized) = (physical, normalized);
    for (p, n) in physical
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .zip(normalized.as_array_mut().unwrap())
    {
        let (kp, kn) = (f(&p["k_max"]), f(&n["k_max"]));
        assert!(
            (kp - 2e5).abs() <= 1e-10 && (kn - 2e5).abs() <= 1e-10,
            "{kp} {kn}"
        );
        p["k_max"].take();
        n["k_max"].take();
    }
    assert_eq!(physical, normalized);
    let bs: Vec<f64> = physical
        .as_array()
        .unwrap()
        .iter()
        .map(|p| f(&p["wall_damping"]))
        .collect();
    assert_eq!(bs.len(), 2);
    assert!(
        (bs[0] - 40.0).abs() < 1e-9 && (bs[1] - 60.0).abs() < 1e-9,
        "{bs:?}"
    );
}

/// The physical range flags are refused beside their normalized twins, for normalized input
/// and reversed, in one line naming the flag (and the values in Ns/m), exit 2.
#[test]
fn simboundary_refuses_a_bad_range_in_one_line() {
    for (args, needle) in [
        (
            &["--wall-damping-min", "40", "--beta-min", "0.4"][..],
            "--wall-damping-min",
        ),
        (
            &[
                "--gamma",
                "0.001",
                "--delta",
                "0.01",
                "--wall-stiffness-max",
                "1e5",
            ][..],
            "--wall-stiffness-max needs a loop in physical units",
        ),
        (
            &["--wall-damping-min", "60", "--wall-damping-max", "40"][..],
            "--wall-damping-max (40 Ns/m) must be >= --wall-damping-min (60 Ns/m)",
        ),
    ] {
        let out = common::hapstab()
            .arg("simboundary")
            .args(args)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert!(
            err.contains(needle) && err.trim().lines().count() == 1,
            "{err}"
        );
    }
}
