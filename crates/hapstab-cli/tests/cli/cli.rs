//! Binary tests: verdicts against closed forms, JSON shape, and bad input (exit 2, one line).

use crate::common;

use common::hapstab;

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
    assert_eq!(v["input"]["d"], 0);
    assert!(
        v.get("normalized").is_none(),
        "the input is already normalized"
    );
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
    bad(&["check", "--delay-time", "-0.0015"], "-0.0015");
    bad(&["check", "--frobnicate"], "--frobnicate");
    bad(&["check", "--mass", "abc"], "abc");
    bad(&["check", "--gamma", "0.001"], "--alpha");
    bad(&["check", "--delay", "100000"], "delay");
}

#[test]
fn boundary_json_pure_mass_closed_form() {
    let v = json(&["boundary", "--gamma", "0", "--delta", "0", "--delay", "0"]);
    let beta = 2.0 * 2f64.sqrt() - 2.0;
    let alpha = 2.0 * beta * (2.0 - beta) / (2.0 + beta);
    assert!((v["alpha_max"].as_f64().unwrap() - alpha).abs() < 1e-12 * alpha);
    assert!((v["beta_at_alpha_max"].as_f64().unwrap() - beta).abs() < 1e-12 * beta);
    assert!((v["area"].as_f64().unwrap() - (12.0 - 16.0 * 2f64.ln())).abs() < 1e-8);
    let polys = v["polygons"].as_array().unwrap();
    assert_eq!(polys.len(), 1);
    // every vertex satisfies 0 <= α <= 2β(2 − β)/(2 + β) (up to rounding)
    for p in polys[0].as_array().unwrap() {
        let (a, b) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
        assert!(
            a >= -1e-15 && a <= 2.0 * b * (2.0 - b) / (2.0 + b) + 1e-12,
            "({a}, {b})"
        );
    }
}

#[test]
fn boundary_csv_and_map_csv() {
    let dir = tempfile::tempdir().unwrap();
    let b = dir.path().join("b.csv");
    hapstab()
        .args([
            "boundary", "--gamma", "0.001", "--delta", "0.015", "--delay", "1", "--csv",
        ])
        .arg(&b)
        .assert()
        .success();
    let text = std::fs::read_to_string(&b).unwrap();
    assert!(text.starts_with("polygon,vertex,alpha,beta,theta,edge"));
    assert!(text.lines().count() > 1000);
    let m = dir.path().join("m.csv");
    let out = hapstab()
        .args([
            "map",
            "--x",
            "alpha:-0.05:0.7:40",
            "--y",
            "beta:-0.1:2.1:30",
            "--out",
        ])
        .arg(&m)
        .arg("--json")
        .output()
        .unwrap();
    assert!(out.status.success());
    let rows: Vec<String> = std::fs::read_to_string(&m)
        .unwrap()
        .lines()
        .map(String::from)
        .collect();
    assert_eq!(rows[0], "alpha,beta,stable");
    assert_eq!(rows.len(), 1 + 40 * 30);
    // pure mass: stable iff 0 < α < 2β(2 − β)/(2 + β), away from the boundary
    for r in &rows[1..] {
        let f: Vec<f64> = r.split(',').map(|x| x.parse().unwrap()).collect();
        let (a, b, s) = (f[0], f[1], f[2] == 1.0);
        if b > 0.0 && b < 2.0 {
            let hi = 2.0 * b * (2.0 - b) / (2.0 + b);
            if a > 1e-9 && a < hi - 1e-9 {
                assert!(s, "({a}, {b})");
            }
        }
        if a < -1e-9 || !(-1e-9..=2.0 + 1e-9).contains(&b) {
            assert!(!s, "({a}, {b})");
        }
    }
}

#[test]
fn kmax_physical_units() {
    // PHANToM-like device, no arm, T = 1 ms, d = 0: K = α m/T², B = β m/T.
    let v = json(&[
        "kmax",
        "--device-mass",
        "0.1",
        "--device-damping",
        "1.5",
        "--no-arm",
    ]);
    let (kmax, b) = (
        v["k_max"].as_f64().unwrap(),
        v["b_at_k_max"].as_f64().unwrap(),
    );
    let alpha = v["normalized"]["alpha_max"].as_f64().unwrap();
    assert!((kmax - alpha * 0.1 / 1e-6).abs() < 1e-9 * kmax);
    // linear condition (22) at that B: (b + B)/(T/2)
    assert!((v["k_linear"].as_f64().unwrap() - (1.5 + b) / 0.0005).abs() < 1e-6 * kmax);
    // with B given: K interval from −k = 0 to the exact boundary, below the linear estimate
    let v = json(&["kmax", "--no-arm", "--wall-damping", "5", "--delay", "1"]);
    let k = v["k_max"].as_f64().unwrap();
    let lin = v["k_linear"].as_f64().unwrap();
    assert!((lin - 6.5 / 0.0015).abs() < 1e-9);
    assert!(k > 0.9 * lin && k < 1.1 * lin, "{k} vs {lin}");
}

#[test]
fn oversized_analyses_are_refused_before_they_start() {
    // each of these used to panic or allocate gigabytes; now one line names the flag and the
    // value, within a second
    let cases: &[(&[&str], &str)] = &[
        (
            &["nyquist", "--beta-samples", "18446744073709551615"],
            "--beta-samples 18446744073709551615",
        ),
        (
            &["nyquist", "--gamma-samples", "1000000000"],
            "--gamma-samples 1000000000",
        ),
        (&["nyquist", "--steps", "100000000"], "--steps 100000000"),
        (
            &["kmax", "--robust", "--box-samples", "10000000"],
            "--box-samples 10000000",
        ),
        (
            &["kmax", "--robust", "--box-samples", "18446744073709551615"],
            "--box-samples",
        ),
        (
            &[
                "map",
                "--x",
                "alpha:0:1:10000",
                "--y",
                "beta:0:1:10000",
                "--radius",
                "--delay",
                "100",
            ],
            "--delay 100",
        ),
    ];
    // about as many --levels as one argument can carry
    let levels = vec!["0.1"; 30_000].join(",");
    bad(&["linear", "--levels", &levels], "--levels (30000 values)");
    for (args, needle) in cases {
        let t = std::time::Instant::now();
        bad(args, needle);
        bad(args, "limit");
        assert!(
            t.elapsed().as_secs_f64() < 5.0,
            "{args:?}: {:?}",
            t.elapsed()
        );
    }
}

#[test]
fn messages_name_the_flag_the_path_and_the_physical_parameter() {
    // a missing required flag is named
    bad(&["map", "--x", "alpha:0:1:10"], "--y");
    bad(&["paper"], "--out");
    // output errors name the file
    bad(
        &[
            "boundary",
            "--gamma",
            "0",
            "--delta",
            "0",
            "--csv",
            "/dev/full",
        ],
        "/dev/full",
    );
    bad(
        &[
            "map",
            "--x",
            "alpha:0:1:3",
            "--y",
            "beta:0:1:3",
            "--out",
            "/dev/full",
        ],
        "/dev/full",
    );
    bad(
        &["boundary", "--csv", "/nonexistent-dir/x.csv"],
        "/nonexistent-dir/x.csv",
    );
    // a mass so small that the normalized values would overflow is refused by the plant's
    // range first, naming the flag, the range and the value
    let range = "--mass: mass m must be in [1e-6, 1e6] kg (got 1e-320)";
    bad(&["check", "--mass", "1e-320"], range);
    bad(&["check", "--mass", "1e-320", "--stiffness", "1"], range);
    // an actuator lag beyond any actuator (near 1e300 s its discretization underflows: the
    // check hung) is refused, naming the flag and the value
    bad(
        &["check", "--force-lag", "1e308"],
        "--force-lag: force lag tau must be in [0, 1e3] s (got 1e308)",
    );
}

#[test]
fn a_full_standard_output_is_one_error_line_and_exit_2() {
    for args in [&["check", "--json"][..], &["check"][..], &["ranges"][..]] {
        let full = std::fs::File::create("/dev/full").unwrap();
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_hapstab"))
            .args(args)
            .stdout(full)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains("standard output"), "{args:?}: {err}");
    }
}

/// d = 2000 (degree 2003): all roots in well under a second (the dense eigen-solver took
/// 88 s), and a verdict that agrees with the spectral radius printed beside it.
#[test]
fn check_at_the_largest_delay_is_fast_and_consistent() {
    let t = std::time::Instant::now();
    let v = json(&["check", "--delay", "2000"]);
    assert!(t.elapsed().as_secs_f64() < 5.0, "{:?}", t.elapsed());
    assert_eq!(v["roots"].as_array().unwrap().len(), 2003);
    let rho = v["spectral_radius"].as_f64().unwrap();
    let expect = if rho < 1.0 { "stable" } else { "unstable" };
    assert!((rho - 1.0).abs() > 1e-6, "{rho}");
    assert_eq!(v["verdict"], expect, "ρ = {rho}");
}

/// γ = 1e10, δ = 1e4: the plant poles have modulus e^{−δ/2} = e^{−5000}, zero in double
/// precision, so with α = β = 0 every root of p = z D(z) is 0: stable, ρ = 0.
#[test]
fn check_stiff_plant_has_its_roots_at_zero() {
    let v = json(&[
        "check", "--gamma", "1e10", "--delta", "1e4", "--alpha", "0", "--beta", "0",
    ]);
    assert_eq!(v["verdict"], "stable");
    assert_eq!(v["spectral_radius"].as_f64().unwrap(), 0.0);
}

/// γ = δ = 0 (a free unit mass) without a wall: p(z) = z^{d+1}(z − 1)² has an exact double
/// root at z = 1, so the verdict is marginal with ρ = 1 to rounding, never unstable.
#[test]
fn free_mass_without_a_wall_is_marginal() {
    for d in ["0", "1", "3"] {
        let v = json(&[
            "check", "--gamma", "0", "--delta", "0", "--alpha", "0", "--beta", "0", "--delay", d,
        ]);
        assert_eq!(v["verdict"], "marginal", "d = {d}: {v}");
        let rho = v["spectral_radius"].as_f64().unwrap();
        assert!((rho - 1.0).abs() < 1e-10, "d = {d}: ρ = {rho}");
    }
}

/// `check --fail-unstable` exits 1 for a wall that is not stable and 0 for a stable one (the
/// paper's pure mass with β = 0.5: α < 0.6 is stable, α = 0.61 is not); without the flag the
/// status is 0 either way, and bad input stays 2.
#[test]
fn check_fail_unstable_sets_the_exit_status() {
    let status = |args: &[&str]| hapstab().args(args).output().unwrap().status.code();
    let wall = |a: &'static str| ["check", "--alpha", a, "--beta", "0.5"];
    let flagged = |a: &'static str| {
        let mut v = wall(a).to_vec();
        v.push("--fail-unstable");
        v
    };
    assert_eq!(status(&flagged("0.59")), Some(0));
    assert_eq!(status(&flagged("0.61")), Some(1));
    assert_eq!(status(&wall("0.61")), Some(0));
    let mut json = flagged("0.61");
    json.push("--json");
    assert_eq!(status(&json), Some(1));
    assert_eq!(
        status(&["check", "--alpha", "x", "--fail-unstable"]),
        Some(2)
    );
}
