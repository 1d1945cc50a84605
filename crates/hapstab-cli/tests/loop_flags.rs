//! Binary tests of the loop flags (transfer-function plant, two-mass device, actuator lag,
//! velocity estimators, fractional delay) and of `hapstab discretize`: closed forms,
//! published values (MATLAB's c2d documentation), identities between flag families, the
//! refusal of contradictory flags and bad input (one line, exit 2).

mod common;

use common::{hapstab, json};
use serde_json::Value;

fn text(args: &[&str]) -> String {
    let out = hapstab().args(args).output().unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array().unwrap().iter().map(f).collect()
}

/// x rounded to `digits` significant digits, as text (MATLAB's display precision).
fn round_sig(x: f64, digits: usize) -> String {
    format!("{:.*e}", digits - 1, x)
}

// ---- discretize ---------------------------------------------------------------------------

/// MATLAB's c2d documentation, "Discretize Model with Fractional Delay Absorbed into
/// Coefficients": h = tf(10,[1 3 10],'IODelay',0.25); hd = c2d(h,0.1) prints
/// z^(-3) * (0.01187 z^2 + 0.06408 z + 0.009721)/(z^2 - 1.655 z + 0.7408).
const MATLAB: [&str; 8] = [
    "discretize",
    "--plant-num",
    "10",
    "--plant-den",
    "1,3,10",
    "--period",
    "0.1",
    "--delay-time=0.25",
];
const MATLAB_NUM: [&str; 3] = ["0.01187", "0.06408", "0.009721"];
const MATLAB_DEN: [&str; 3] = ["1", "-1.655", "0.7408"];

#[test]
fn discretize_reproduces_matlab_c2d_example_json() {
    let v = json(&MATLAB);
    assert_eq!(v["plant"]["delay"], 3);
    let num = floats(&v["plant"]["num"]);
    let den = floats(&v["plant"]["den"]);
    assert_eq!(num.len(), 3);
    assert_eq!(den.len(), 3);
    for (got, want) in num.iter().zip(MATLAB_NUM) {
        assert_eq!(round_sig(*got, 4), round_sig(want.parse().unwrap(), 4));
    }
    for (got, want) in den.iter().zip(MATLAB_DEN) {
        assert_eq!(round_sig(*got, 4), round_sig(want.parse().unwrap(), 4));
    }
    assert_eq!(v["input"]["loop"]["period"], 0.1);
    assert_eq!(v["input"]["delay_time"], 0.25);
    assert_eq!(v["input"]["loop"]["delay"]["samples"], 2);
    assert_eq!(v["input"]["loop"]["delay"]["fraction"], 0.5);
    assert_eq!(
        v["input"]["loop"]["plant"]["model"]["kind"],
        "transfer_function"
    );
}

/// The coefficients of a polynomial as text, e.g. "0.0118732 z^2 + 0.0640836 z + 0.00972066"
/// → [0.0118732, 0.0640836, 0.00972066]; a power of z without a number has coefficient ±1.
fn coefficients_of(line: &str) -> Vec<f64> {
    let mut out = Vec::new();
    let mut sign = 1.0;
    let mut after_number = false;
    for tok in line.split_whitespace() {
        match tok {
            "+" | "-" => {
                sign = if tok == "-" { -1.0 } else { 1.0 };
                after_number = false;
            }
            t if t.starts_with('z') => {
                if !after_number {
                    out.push(sign);
                }
                after_number = false;
            }
            t => {
                out.push(sign * t.parse::<f64>().unwrap());
                after_number = true;
            }
        }
    }
    out
}

#[test]
fn discretize_text_shows_matlab_display_to_its_digits() {
    let s = text(&MATLAB);
    let lines: Vec<&str> = s.lines().collect();
    let rule = lines
        .iter()
        .position(|l| l.trim_start().starts_with("z^(-3) * ---"))
        .unwrap_or_else(|| panic!("no delay line in\n{s}"));
    let num = coefficients_of(lines[rule - 1]);
    // the denominator line starts with the unit leading term "z^2"
    let den_line = lines[rule + 1].trim();
    assert!(den_line.starts_with("z^2 - "), "{den_line}");
    let den = coefficients_of(den_line.trim_start_matches("z^2"));
    assert_eq!(num.len(), 3, "{}", lines[rule - 1]);
    for (got, want) in num.iter().zip(MATLAB_NUM) {
        assert_eq!(round_sig(*got, 4), round_sig(want.parse().unwrap(), 4));
    }
    for (got, want) in den.iter().zip(&MATLAB_DEN[1..]) {
        assert_eq!(round_sig(*got, 4), round_sig(want.parse().unwrap(), 4));
    }
    assert!(s.contains("Sample time: 0.1 seconds"), "{s}");
}

/// A pure mass m behind a zero-order hold: H(z) = T²/(2m)·(z + 1)/(z − 1)²; with the
/// backward difference V(z) = (z − 1)/(T z) the loop closes on
/// z(z − 1)² + g(z + 1)(K z + B(z − 1)/T) = 0, g = T²/(2m).
#[test]
fn discretize_pure_mass_closed_forms() {
    let (m, t, k, b) = (0.7, 1e-3, 3000.0, 4.0);
    let v = json(&[
        "discretize",
        "--mass",
        "0.7",
        "--damping",
        "0",
        "--stiffness",
        "0",
        "--wall-stiffness",
        "3000",
        "--wall-damping",
        "4",
    ]);
    let g = t * t / (2.0 * m);
    let num = floats(&v["plant"]["num"]);
    let den = floats(&v["plant"]["den"]);
    assert_eq!(v["plant"]["delay"], 0);
    for (x, y) in num.iter().zip([g, g]) {
        assert!((x - y).abs() < 1e-14 * g, "{num:?}");
    }
    for (x, y) in den.iter().zip([1.0, -2.0, 1.0]) {
        assert!((x - y).abs() < 4e-16, "{den:?}");
    }
    assert_eq!(floats(&v["velocity"]["num"]), vec![1000.0, -1000.0]);
    assert_eq!(floats(&v["velocity"]["den"]), vec![1.0, 0.0]);
    // z³ − 2z² + z + g[(K + B/T) z² + K z − (B/T) z + (K... ) ]: expand (z + 1)(c1 z − c0)
    let (c1, c0) = (k + b / t, b / t);
    let want = [1.0, -2.0 + g * c1, 1.0 + g * (c1 - c0), -g * c0];
    let p = floats(&v["characteristic"]);
    assert_eq!(p.len(), 4);
    for (x, y) in p.iter().zip(want) {
        assert!((x - y).abs() < 1e-14, "{p:?} vs {want:?}");
    }
}

/// The modified z-transform of a pure mass with a delay of half a sample:
/// N(z) = g((1 − λ)² z² + (1 + 2λ − 2λ²) z + λ²) over z (z − 1)², g = T²/(2m), λ = 1/2.
#[test]
fn discretize_fractional_delay_closed_form() {
    let v = json(&[
        "discretize",
        "--mass",
        "2",
        "--damping",
        "0",
        "--delay-time",
        "0.0005",
    ]);
    let g = 1e-6 / 4.0;
    let want = [0.25 * g, 1.5 * g, 0.25 * g];
    assert_eq!(v["plant"]["delay"], 1);
    let num = floats(&v["plant"]["num"]);
    for (x, y) in num.iter().zip(want) {
        assert!((x - y).abs() < 1e-14 * g, "{num:?}");
    }
}

/// The low-pass estimator is (1 − a)(z − 1)/(T(z − a)), a = exp(−2π f_c T).
#[test]
fn discretize_lowpass_velocity_closed_form() {
    let v = json(&["discretize", "--velocity", "lowpass:50"]);
    let a = (-2.0 * std::f64::consts::PI * 50.0 * 1e-3_f64).exp();
    let num = floats(&v["velocity"]["num"]);
    let den = floats(&v["velocity"]["den"]);
    let c = (1.0 - a) / 1e-3;
    assert!(
        (num[0] - c).abs() < 1e-12 * c && (num[1] + c).abs() < 1e-12 * c,
        "{num:?}"
    );
    assert!(
        (den[0] - 1.0).abs() < 1e-15 && (den[1] + a).abs() < 1e-15,
        "{den:?}"
    );
    // average:N is (z^N − 1)/(N T z^N)
    let v = json(&["discretize", "--velocity", "average:4"]);
    let num = floats(&v["velocity"]["num"]);
    assert_eq!(num.len(), 5);
    assert!(
        (num[0] - 250.0).abs() < 1e-12 && (num[4] + 250.0).abs() < 1e-12,
        "{num:?}"
    );
    assert_eq!(floats(&v["velocity"]["den"]), vec![1.0, 0.0, 0.0, 0.0, 0.0]);
}

// ---- check on every loop ------------------------------------------------------------------

const WALL: [&str; 4] = ["--wall-stiffness", "20000", "--wall-damping", "5"];

fn check(extra: &[&str]) -> Value {
    json(&[&["check"][..], &WALL, extra].concat())
}

fn radius(v: &Value) -> f64 {
    f(&v["spectral_radius"])
}

/// The radius and verdict agree with the roots printed beside them.
fn assert_consistent(v: &Value) {
    let roots = v["roots"].as_array().unwrap();
    let max = roots
        .iter()
        .map(|r| f(&r[0]).hypot(f(&r[1])))
        .fold(0.0, f64::max);
    assert!((max - radius(v)).abs() < 1e-15, "{v}");
    let want = if radius(v) < 1.0 - 1e-9 {
        "stable"
    } else if radius(v) > 1.0 + 1e-9 {
        "unstable"
    } else {
        return;
    };
    assert_eq!(v["verdict"], want, "{v}");
}

#[test]
fn transfer_function_equals_mass_spring_damper() {
    let tf = check(&[
        "--plant-num",
        "1",
        "--plant-den",
        "1.1,7.5,350",
        "--delay",
        "1",
    ]);
    let msd = check(&[
        "--mass",
        "1.1",
        "--damping",
        "7.5",
        "--stiffness",
        "350",
        "--delay",
        "1",
    ]);
    assert!((radius(&tf) - radius(&msd)).abs() < 1e-12, "{tf} vs {msd}");
    assert_eq!(tf["verdict"], msd["verdict"]);
    assert_consistent(&tf);
    assert_eq!(tf["input"]["loop"]["plant"]["model"]["den"][2], 350.0);
    // the paper's view only for the paper's plant
    assert!(msd.get("normalized").is_some() && tf.get("normalized").is_none());
}

#[test]
fn velocity_estimators_that_are_the_backward_difference() {
    let base = check(&["--no-arm", "--delay", "1"]);
    let avg1 = check(&["--no-arm", "--delay", "1", "--velocity", "average:1"]);
    assert_eq!(base["roots"], avg1["roots"]);
    // (y_k − y_{k−1})/T at T = 1 ms as an IIR filter in z⁻¹
    let iir = check(&["--no-arm", "--delay", "1", "--velocity", "iir:1000,-1000/1"]);
    assert!((radius(&iir) - radius(&base)).abs() < 1e-13);
    // a first-order low-pass far above the sampling rate is the backward difference
    let fast = check(&["--no-arm", "--delay", "1", "--velocity", "lowpass:1e9"]);
    assert!((radius(&fast) - radius(&base)).abs() < 1e-9);
    let slow = check(&["--no-arm", "--delay", "1", "--velocity", "lowpass:20"]);
    assert!((radius(&slow) - radius(&base)).abs() > 1e-4);
    assert_consistent(&slow);
    assert_eq!(slow["input"]["loop"]["velocity"]["kind"], "low_pass");
}

#[test]
fn force_lag_zero_is_no_lag_and_small_lag_is_continuous() {
    let base = check(&["--delay", "1"]);
    let zero = check(&["--delay", "1", "--force-lag", "0"]);
    assert_eq!(base["roots"], zero["roots"]);
    let tiny = check(&["--delay", "1", "--force-lag", "1e-9"]);
    assert!((radius(&tiny) - radius(&base)).abs() < 1e-5);
    let lag = check(&["--delay", "1", "--force-lag", "0.0005"]);
    assert_eq!(lag["roots"].as_array().unwrap().len(), 5);
    assert_consistent(&lag);
}

/// A two-mass device whose transmission is rigid (its internal mode fast and damped) moves as one mass
/// J + m_h + m_H with damping b_m + b_H: its radius approaches the one-mass loop's.
#[test]
fn rigid_two_mass_device_is_one_mass() {
    let two = check(&[
        "--motor-mass",
        "0.06",
        "--motor-damping",
        "1",
        "--handle-mass",
        "0.04",
        "--transmission-stiffness",
        "1e9",
        "--transmission-damping",
        "1e4",
    ]);
    let one = check(&["--mass", "1.1", "--damping", "7", "--stiffness", "350"]);
    assert!((radius(&two) - radius(&one)).abs() < 1e-5, "{two} vs {one}");
    assert_consistent(&two);
    assert_eq!(two["roots"].as_array().unwrap().len(), 5);
    // a compliant transmission changes the answer
    let soft = check(&[
        "--motor-mass",
        "0.06",
        "--handle-mass",
        "0.04",
        "--transmission-stiffness",
        "5e4",
    ]);
    assert_consistent(&soft);
    assert_eq!(
        soft["input"]["loop"]["plant"]["model"]["arm"]["stiffness"],
        350.0
    );
}

/// t_d = (d + λ)T: λ → 0 and λ → 1 match d and d + 1 samples.
#[test]
fn fractional_delay_time_is_continuous() {
    let d1 = check(&["--delay", "1"]);
    let d2 = check(&["--delay", "2"]);
    let just_above = check(&["--delay-time", "0.00100000001"]);
    let just_below = check(&["--delay-time", "0.00199999999"]);
    assert!((radius(&just_above) - radius(&d1)).abs() < 1e-6);
    assert!((radius(&just_below) - radius(&d2)).abs() < 1e-6);
    let half = check(&["--delay-time", "0.0015"]);
    assert_eq!(half["input"]["loop"]["delay"]["fraction"], 0.5);
    assert!(half.get("normalized").is_none());
    assert_consistent(&half);
}

#[test]
fn check_text_describes_the_loop() {
    let s = text(&[
        "check",
        "--plant-num",
        "1",
        "--plant-den",
        "0.1,1.5,0",
        "--velocity",
        "average:3",
        "--force-lag",
        "0.0002",
        "--delay-time",
        "0.0005",
    ]);
    for want in [
        "P(s) = (1) / (0.1 s^2 + 1.5 s) m/N",
        "τ = 0.2 ms",
        "t_d = 0.5 ms (d = 0, λ = 0.5)",
        "velocity  average:3",
        "verdict",
    ] {
        assert!(s.contains(want), "{want} not in\n{s}");
    }
}

// ---- map, boundary and kmax of a loop ----------------------------------------------------

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

// ---- contradictions and bad input ---------------------------------------------------------

fn refused(args: &[&str], needles: &[&str]) {
    let out = hapstab().args(args).output().unwrap();
    assert_eq!(out.status.code(), Some(2), "{args:?}");
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: {n} not in {err}");
    }
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn contradictory_flags_are_refused_naming_both() {
    for (args, a, b) in [
        (
            &["check", "--no-arm", "--arm-mass", "1"][..],
            "--no-arm",
            "--arm-mass",
        ),
        (
            &["kmax", "--no-arm", "--arm-stiffness", "9"],
            "--no-arm",
            "--arm-stiffness",
        ),
        (
            &["check", "--gamma", "0.1", "--mass", "1"],
            "--gamma",
            "--mass",
        ),
        (
            &["boundary", "--delta", "0.1", "--period", "1e-3"],
            "--delta",
            "--period",
        ),
        (
            &[
                "check",
                "--alpha",
                "0.1",
                "--beta",
                "0.1",
                "--wall-stiffness",
                "5",
            ],
            "--alpha",
            "--wall-stiffness",
        ),
        (
            &["check", "--gamma", "0.1", "--wall-damping", "5"],
            "--gamma",
            "--wall-damping",
        ),
        (
            &["check", "--delay", "1", "--delay-time", "0.001"],
            "--delay",
            "--delay-time",
        ),
        (
            &[
                "discretize",
                "--plant-num",
                "1",
                "--plant-den",
                "1,0,0",
                "--mass",
                "1",
            ],
            "--plant-num",
            "--mass",
        ),
        (
            &["kmax", "--plant-den", "1,0,0", "--arm-damping", "1"],
            "--plant-den",
            "--arm-damping",
        ),
        (
            &["check", "--plant-num", "1", "--motor-mass", "1"],
            "--plant-num",
            "--motor-mass",
        ),
        (
            &["check", "--motor-mass", "1", "--mass", "1"],
            "--motor-mass",
            "--mass",
        ),
        (
            &[
                "map",
                "--x",
                "K:0:1:2",
                "--y",
                "B:0:1:2",
                "--handle-mass",
                "1",
                "--stiffness",
                "1",
            ],
            "--handle-mass",
            "--stiffness",
        ),
        (
            &[
                "check",
                "--transmission-stiffness",
                "1e5",
                "--device-mass",
                "1",
            ],
            "--transmission-stiffness",
            "--device-mass",
        ),
        (
            &["check", "--gamma", "0.1", "--velocity", "lowpass:5"],
            "--gamma",
            "--velocity",
        ),
        (
            &["check", "--delta", "0.1", "--force-lag", "0.001"],
            "--delta",
            "--force-lag",
        ),
        (
            &[
                "check",
                "--alpha",
                "0.1",
                "--beta",
                "0.1",
                "--plant-num",
                "1",
                "--plant-den",
                "1,0,0",
            ],
            "--alpha",
            "--plant-num",
        ),
        (
            &["discretize", "--beta", "0.1", "--motor-mass", "1"],
            "--beta",
            "--motor-mass",
        ),
        (
            &["kmax", "--robust", "--velocity", "average:2"],
            "--robust",
            "--velocity",
        ),
        (
            &[
                "map",
                "--x",
                "alpha:0:1:2",
                "--y",
                "beta:0:1:2",
                "--alpha",
                "0.1",
                "--mass",
                "1",
            ],
            "--alpha",
            "--mass",
        ),
    ] {
        refused(args, &[a, b, "cannot be used with"]);
    }
}

#[test]
fn bad_loop_input_is_one_line_naming_flag_and_value() {
    for (args, needles) in [
        (
            &["check", "--velocity", "forward"][..],
            &["--velocity", "forward"][..],
        ),
        (
            &["check", "--velocity", "lowpass"],
            &["--velocity", "lowpass"],
        ),
        (
            &["check", "--velocity", "lowpass:-5"],
            &["--velocity", "-5"],
        ),
        (
            &["check", "--velocity", "lowpass:fast"],
            &["--velocity", "fast"],
        ),
        (
            &["check", "--velocity", "average:0"],
            &["--velocity", "average:0"],
        ),
        (
            &["check", "--velocity", "average:1.5"],
            &["--velocity", "1.5"],
        ),
        (
            &["check", "--velocity", "iir:1,-1"],
            &["--velocity", "iir:1,-1"],
        ),
        (
            &["check", "--velocity", "iir:1,-1/0,1"],
            &["--velocity", "a0"],
        ),
        (
            &["check", "--velocity", "iir:1,x/1"],
            &["--velocity", "'x'"],
        ),
        (
            &["check", "--velocity", "backward:3"],
            &["--velocity", "backward:3"],
        ),
        (
            &["check", "--plant-num", "1,2,3", "--plant-den", "1,1"],
            &["--plant-num 1,2,3", "strictly proper"],
        ),
        (
            &["check", "--plant-num", "1,2", "--plant-den", "1,2"],
            &["--plant-den 1,2", "strictly proper"],
        ),
        (
            &["check", "--plant-num", "1", "--plant-den", "0,0"],
            &["--plant-den 0,0", "denominator"],
        ),
        (
            &["check", "--plant-num", "1,x", "--plant-den", "1,0"],
            &["--plant-num", "'x'"],
        ),
        (
            &["check", "--plant-num", "1", "--plant-den", "1,nan"],
            &["--plant-den", "nan"],
        ),
        (
            &[
                "check",
                "--plant-num",
                "1",
                "--plant-den",
                "1,1,1,1,1,1,1,1,1,1,1,1,1,1",
            ],
            &["plant order", "13"],
        ),
        (
            &["check", "--plant-num", "1"],
            &["--plant-num", "--plant-den"],
        ),
        (
            &["check", "--plant-den", "1,0,0"],
            &["--plant-den", "--plant-num"],
        ),
        (&["check", "--force-lag", "-1"], &["--force-lag", "-1"]),
        (&["check", "--force-lag", "inf"], &["--force-lag", "inf"]),
        (
            &["check", "--motor-mass", "0.1"],
            &["--transmission-stiffness"],
        ),
        (
            &["check", "--transmission-stiffness", "1e5"],
            &["--motor-mass"],
        ),
        (
            &[
                "check",
                "--motor-mass",
                "-0.1",
                "--transmission-stiffness",
                "1e5",
            ],
            &["motor mass", "-0.1"],
        ),
        (
            &[
                "check",
                "--motor-mass",
                "0.1",
                "--transmission-stiffness",
                "0",
            ],
            &["transmission stiffness", "0"],
        ),
        (
            &["check", "--delay-time", "-0.001"],
            &["delay time", "-0.001"],
        ),
        (&["check", "--delay-time", "nan"], &["delay time", "NaN"]),
        (
            &[
                "check",
                "--plant-num",
                "1",
                "--plant-den",
                "1,0",
                "--alpha",
                "0.1",
                "--beta",
                "0.1",
            ],
            &["--alpha", "--plant-num"],
        ),
        (
            &["map", "--x", "K:0:1:2", "--y", "alpha:0:1:2"],
            &["K", "alpha"],
        ),
        (
            &["map", "--x", "K:0:1:2", "--y", "B:0:1:2", "--gamma", "0.1"],
            &["--gamma"],
        ),
        (
            &["map", "--x", "alpha:0:1:2", "--y", "beta:0:1:2", "--no-arm"],
            &["K:LO:HI:N"],
        ),
        (&["discretize", "--alpha", "0.1"], &["--beta"]),
    ] {
        refused(args, needles);
    }
}

#[test]
fn help_documents_the_velocity_formulas() {
    let s = text(&["check", "--help"]);
    for want in [
        "v_k = (y_k − y_{k−1})/T",
        "v_k = a·v_{k−1} + (1 − a)(y_k − y_{k−1})/T",
        "a = exp(−2π·f_c·T)",
        "v_k = (y_k − y_{k−N})/(N·T)",
        "v = (b0 + b1 z⁻¹ + …)/(a0 + a1 z⁻¹ + …) · y",
        "--plant-num",
        "--force-lag",
        "--transmission-stiffness",
    ] {
        assert!(s.contains(want), "{want} not in check --help");
    }
}
