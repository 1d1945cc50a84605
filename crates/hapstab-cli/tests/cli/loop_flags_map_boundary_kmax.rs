//! Binary tests of the loop flags (transfer-function plant, two-mass device, actuator lag,
//! velocity estimators, fractional delay) in `hapstab map`,
//! `boundary` and `kmax`: closed forms, the paper's loop in physical units, boundary vertices
//! on the stability boundary, the linear condition.

use crate::common;

use common::{check, f, floats, hapstab, json, radius, text};

/// A wall map over (K, B) of a pure mass (m = 0.1 kg, T = 1 ms, d = 0) against the closed
/// form 0 < α < 2β(2 − β)/(2 + β), α = KT²/m, β = BT/m.
#[test]
fn wall_map_of_a_pure_mass_closed_form() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("m.csv");
    hapstab()
        .args([
            "map",
            "--x",
            "K:-5000:80000:45",
            "--y",
            "B:-10:210:35",
            "--no-arm",
            "--device-damping",
            "0",
            "--out",
        ])
        .arg(&out)
        .assert()
        .success();
    let rows: Vec<String> = std::fs::read_to_string(&out)
        .unwrap()
        .lines()
        .map(String::from)
        .collect();
    assert_eq!(rows[0], "K,B,stable");
    assert_eq!(rows.len(), 1 + 45 * 35);
    let mut stable = 0;
    for r in &rows[1..] {
        let v: Vec<f64> = r.split(',').map(|x| x.parse().unwrap()).collect();
        let (alpha, beta, s) = (v[0] * 1e-6 / 0.1, v[1] * 1e-3 / 0.1, v[2] == 1.0);
        let hi = 2.0 * beta * (2.0 - beta) / (2.0 + beta);
        let inside = alpha > 1e-9 && beta > 0.0 && beta < 2.0 && alpha < hi - 1e-9;
        let outside = alpha < -1e-9 || !(-1e-9..=2.0 + 1e-9).contains(&beta) || alpha > hi + 1e-9;
        if inside {
            assert!(s, "({alpha}, {beta})");
            stable += 1;
        }
        if outside {
            assert!(!s, "({alpha}, {beta})");
        }
    }
    assert!(stable > 100);
}

/// `boundary --csv` of a physical loop writes K in N/m and B in Ns/m (no α, β columns): for
/// a pure mass (m = 0.1 kg, T = 1 ms, d = 0) every vertex lies on the closed-form boundary
/// α = 2β(2 − β)/(2 + β), α = KT²/m, β = BT/m, or on α = 0.
#[test]
fn boundary_csv_of_a_physical_loop_is_in_newtons() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("b.csv");
    hapstab()
        .args(["boundary", "--no-arm", "--device-damping", "0", "--csv"])
        .arg(&out)
        .assert()
        .success();
    let text = std::fs::read_to_string(&out).unwrap();
    let mut rows = text.lines();
    assert_eq!(rows.next(), Some("polygon,vertex,K,B,theta,edge"));
    let mut on_curve = 0;
    for r in rows {
        let v: Vec<&str> = r.split(',').collect();
        let (k, b): (f64, f64) = (v[2].parse().unwrap(), v[3].parse().unwrap());
        let (alpha, beta) = (k * 1e-6 / 0.1, b * 1e-3 / 0.1);
        let hi = 2.0 * beta * (2.0 - beta) / (2.0 + beta);
        assert!(
            alpha.abs() < 1e-9 || (alpha - hi).abs() < 1e-7,
            "vertex K = {k}, B = {b}: α = {alpha}, β = {beta}, curve {hi}"
        );
        on_curve += usize::from(alpha > 1e-3);
    }
    assert!(on_curve > 10, "{on_curve} vertices on the curve");
}

#[test]
fn boundary_and_kmax_of_the_paper_loop_in_physical_units() {
    // K = α m/T², B = β m/T with m = 0.1 kg, T = 1 ms
    let b = json(&["boundary", "--no-arm"]);
    let k = json(&["kmax", "--no-arm"]);
    let (kmax, bk) = (f(&b["k_max"]), f(&b["b_at_k_max"]));
    let n = &b["normalized"];
    assert!((kmax - f(&n["alpha_max"]) * 1e5).abs() < 1e-9 * kmax);
    assert!((bk - f(&n["beta_at_alpha_max"]) * 100.0).abs() < 1e-9 * bk);
    assert!((f(&k["k_max"]) - kmax).abs() < 1e-9 * kmax);
    assert!((f(&b["wall_units"]["stiffness"]) - 1e5).abs() < 1e-9);
    assert!((f(&b["area"]) - f(&n["area"]) * 1e5 * 100.0).abs() < 1e-9 * f(&b["area"]));
    assert_eq!(b["input"]["loop"]["plant"]["model"]["mass"], 0.1);
}

/// The vertices of a general loop's region lie on the stability boundary: ρ = 1 to 1e-9 and
/// the verdict marginal. Sampled along the arcs, away from the corners where the arc meets
/// the z = 1 line: there p(z) has a double root at z = 1, whose modulus moves with the
/// square root of any rounding.
#[test]
fn boundary_vertices_of_a_two_mass_loop_are_marginal() {
    let loop_flags = [
        "--motor-mass",
        "0.06",
        "--handle-mass",
        "0.04",
        "--transmission-stiffness",
        "2e5",
        "--transmission-damping",
        "2",
        "--velocity",
        "lowpass:200",
        "--delay-time",
        "0.0013",
    ];
    let b = json(&[&["boundary"][..], &loop_flags].concat());
    let poly = b["polygons"][0].as_array().unwrap();
    let corners: Vec<usize> = b["edges"][0]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["start"].as_u64().unwrap() as usize)
        .collect();
    assert!(poly.len() > 100);
    let step = poly.len() / 12;
    for (i, v) in poly.iter().enumerate().skip(step).step_by(step) {
        if corners.iter().any(|&c| i.abs_diff(c) < 2) {
            continue;
        }
        let (k, bw) = (f(&v[0]).to_string(), f(&v[1]).to_string());
        let c = json(
            &[
                &["check", "--wall-stiffness", &k, "--wall-damping", &bw][..],
                &loop_flags,
            ]
            .concat(),
        );
        assert!((radius(&c) - 1.0).abs() < 1e-9, "({k}, {bw}): {c}");
        assert_eq!(c["verdict"], "marginal", "({k}, {bw})");
    }
}

/// The linear condition with a fractional delay: K_max (t_d + T/2)/(b + B) → 1 as
/// (b + B)T/m → 0.
#[test]
fn kmax_with_fractional_delay_meets_the_linear_condition() {
    for td in ["0.0005", "0.0013", "0.0027"] {
        let v = json(&[
            "kmax",
            "--mass",
            "10",
            "--damping",
            "0.5",
            "--stiffness",
            "0",
            "--delay-time",
            td,
            "--wall-damping",
            "0.5",
        ]);
        let t_d: f64 = td.parse().unwrap();
        let ratio = f(&v["k_max"]) * (t_d + 0.0005) / 1.0;
        assert!((ratio - 1.0).abs() < 1e-3, "t_d = {td}: {ratio}");
    }
}

#[test]
fn check_gives_the_k_interval_of_every_loop() {
    let v = check(&["--velocity", "lowpass:100", "--force-lag", "0.0003"]);
    let iv = floats(&v["k_interval"]);
    let k = 20000.0;
    assert_eq!(v["verdict"] == "stable", iv[0] < k && k < iv[1], "{v}");
    // the upper end is marginal
    let hi = iv[1].to_string();
    let c = json(&[
        "check",
        "--wall-stiffness",
        &hi,
        "--wall-damping",
        "5",
        "--velocity",
        "lowpass:100",
        "--force-lag",
        "0.0003",
    ]);
    assert!((radius(&c) - 1.0).abs() < 1e-9, "{c}");
}

/// Physical input, physical answer: `boundary` on the default device without an arm leads
/// with the loop and K_max in N/m, and no line speaks α, β or γ; the paper's normalized view
/// is in the JSON, whose α_max is K_max·T²/m (Table I).
#[test]
fn boundary_text_speaks_physical_units() {
    let text = text(&["boundary", "--no-arm"]);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "stable region of the loop", "{text}");
    let k_line = lines.iter().find(|l| l.starts_with("K_max = ")).unwrap();
    let k_kn: f64 = k_line.split_whitespace().nth(2).unwrap().parse().unwrap();
    assert!(k_line.contains("kN/m at B = "), "{k_line}");
    // the paper's normalized view is in the JSON only: K_max = α_max m/T²
    let alpha = f(&json(&["boundary", "--no-arm"])["normalized"]["alpha_max"]);
    // the default device alone: m = 0.1 kg, T = 1 ms
    let (m, t) = (0.1, 1e-3);
    assert!(
        (k_kn * 1e3 * t * t / m - alpha).abs() < 1e-5 * alpha,
        "{k_line} / α_max {alpha}"
    );
    let spoken = |l: &&&str| l.contains('α') || l.contains('β') || l.contains('γ');
    assert_eq!(lines.iter().filter(spoken).count(), 0, "{text}");
}

/// `kmax` leads with the pure spring: its first K_max line is the one at B = 0, equal to
/// `kmax --wall-damping 0` (the interval at one damping, another path); the overall maximum
/// follows, with a line that names the damping it needs and --damping-range.
#[test]
fn kmax_text_leads_with_zero_damping() {
    let text = text(&["kmax", "--no-arm"]);
    let lines: Vec<&str> = text.lines().filter(|l| l.starts_with("K_max = ")).collect();
    assert_eq!(lines.len(), 3, "{text}");
    assert!(lines[0].contains(" at B = 0 (no virtual damping"), "{text}");
    assert!(
        lines[1].contains("largest over the renderable band 0 ≤ B ≤ "),
        "{text}"
    );
    let at_zero = json(&["kmax", "--no-arm", "--wall-damping", "0"]);
    let k0 = f(&at_zero["k_max"]);
    let printed: f64 = lines[0].split_whitespace().nth(2).unwrap().parse().unwrap();
    assert!(
        (printed * 1e3 - k0).abs() <= 5e-6 * k0,
        "{} vs {k0}",
        lines[0]
    );
    let overall = json(&["kmax", "--no-arm"]);
    assert_eq!(f(&overall["k_max_at_zero_damping"]), k0);
    let b = f(&overall["b_at_k_max"]);
    assert!(b > 0.0);
    let hint = text
        .lines()
        .find(|l| l.contains("--damping-range LO:HI"))
        .unwrap();
    assert!(hint.contains("needs the device to render B = "), "{hint}");
    // a band given: no hint
    let banded = common::text(&["kmax", "--no-arm", "--damping-range", "0:20"]);
    assert!(!banded.contains("--damping-range LO:HI"), "{banded}");
}

/// The renderable band B_r = F_n·√12/(Δ·‖V‖₂) of the backward difference (‖V‖₂ = √2/T)
/// and K_max over it, equal to K_max over the band given as --damping-range.
#[test]
fn kmax_reports_the_renderable_band() {
    let out = json(&[
        "kmax",
        "--no-arm",
        "--position-resolution",
        "2e-5",
        "--force-noise",
        "0.08",
    ]);
    let rb = &out["renderable"];
    let b_r = 0.08 * 12f64.sqrt() * 1e-3 / (2e-5 * 2f64.sqrt());
    assert!((f(&rb["b_max"]) - b_r).abs() <= 1e-14 * b_r, "{rb}");
    assert_eq!(f(&rb["position_resolution"]), 2e-5);
    assert_eq!(f(&rb["force_noise"]), 0.08);
    let band = format!("0:{}", f(&rb["b_max"]));
    let given = json(&["kmax", "--no-arm", "--damping-range", &band]);
    assert_eq!(f(&rb["k_max"]), f(&given["k_max"]));
    assert!(f(&rb["k_max"]) < f(&out["k_max"]));
    assert!(given.get("renderable").is_none());
}

#[test]
fn kmax_refuses_a_bad_noise_model() {
    for (flags, needle) in [
        (
            &["--force-noise", "0"][..],
            "--force-noise must be a positive finite number (got 0)",
        ),
        (
            &["--position-resolution", "-1e-5"][..],
            "--position-resolution must be a positive finite number (got -0.00001)",
        ),
        (
            &["--force-noise", "0.1", "--wall-damping", "3"][..],
            "--wall-damping",
        ),
    ] {
        let mut args = vec!["kmax"];
        args.extend_from_slice(flags);
        let out = hapstab().args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{flags:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{flags:?}: {err}");
    }
}
