//! Binary tests: verdicts against closed forms, JSON shape, and bad input (exit 2, one line).

use assert_cmd::Command;

fn hapstab() -> Command {
    Command::cargo_bin("hapstab").unwrap()
}

fn json(args: &[&str]) -> serde_json::Value {
    let out = hapstab().args(args).arg("--json").output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn check_json_against_pure_mass_closed_form() {
    // α < 2β(2 − β)/(2 + β): at β = 0.5 the bound is 0.6.
    let v = json(&["check", "--alpha", "0.59", "--beta", "0.5"]);
    assert_eq!(v["stable"], true);
    assert_eq!(v["verdict"], "stable");
    assert!(v["spectral_radius"].as_f64().unwrap() < 1.0);
    assert_eq!(v["roots"].as_array().unwrap().len(), 3);
    assert_eq!(v["normalized"]["d"], 0);
    let hi = v["alpha_interval"][1].as_f64().unwrap();
    assert!((hi - 0.6).abs() < 1e-14, "{hi}");
    let v = json(&["check", "--alpha", "0.61", "--beta", "0.5"]);
    assert_eq!(v["verdict"], "unstable");
    assert!(v["spectral_radius"].as_f64().unwrap() > 1.0);
}

#[test]
fn check_physical_matches_normalization() {
    // m = 1.1 kg, T = 1 ms: α = K T²/m.
    let v = json(&[
        "check",
        "--wall-stiffness",
        "11000",
        "--wall-damping",
        "11",
        "--delay",
        "1",
    ]);
    let n = &v["normalized"];
    assert!((n["alpha"].as_f64().unwrap() - 0.01).abs() < 1e-15);
    assert!((n["beta"].as_f64().unwrap() - 0.01).abs() < 1e-15);
    assert!((n["gamma"].as_f64().unwrap() - 350e-6 / 1.1).abs() < 1e-18);
    assert_eq!(n["d"], 1);
    let v2 = json(&[
        "check",
        "--wall-stiffness",
        "11000",
        "--wall-damping",
        "11",
        "--delay-time",
        "0.001",
    ]);
    assert_eq!(v["roots"], v2["roots"]);
}

#[test]
fn default_run_prints_verdict_and_stiffness() {
    let out = hapstab().arg("check").output().unwrap();
    assert!(out.status.success());
    let s = String::from_utf8(out.stdout).unwrap();
    assert!(s.contains("verdict"), "{s}");
    assert!(s.contains("< K <"), "{s}");
}

fn bad(args: &[&str], needle: &str) {
    let out = hapstab().args(args).output().unwrap();
    assert_eq!(out.status.code(), Some(2), "{args:?}");
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    assert!(err.contains(needle), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn bad_input_is_one_line_and_exit_2() {
    bad(&["check", "--mass", "-1"], "-1");
    bad(&["check", "--device-mass", "-0.1"], "m_L");
    bad(&["check", "--period", "0"], "period");
    bad(&["check", "--alpha", "NaN", "--beta", "0.1"], "alpha");
    bad(
        &["check", "--gamma", "nan", "--alpha", "0", "--beta", "0"],
        "gamma",
    );
    bad(&["check", "--delay", "-1"], "delay");
    bad(&["check", "--delay", "1.5"], "delay");
    bad(&["check", "--delay-time", "0.0015"], "0.0015");
    bad(&["check", "--frobnicate"], "--frobnicate");
    bad(&["check", "--mass", "abc"], "abc");
    bad(&["check", "--gamma", "0.001"], "--alpha");
    bad(&["check", "--delay", "100000"], "delay");
}
