//! Binary tests of the loop flags (transfer-function plant, two-mass device, actuator lag,
//! velocity estimators, fractional delay) in `hapstab check`: identities between
//! flag families, continuity, the loop described in words and in `--help`.

use crate::common;

use common::{check, f, radius, text};
use serde_json::Value;

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
