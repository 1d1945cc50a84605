//! Binary tests of the loop flags (transfer-function plant, two-mass device, actuator lag,
//! velocity estimators, fractional delay): contradictory flags
//! and bad input are refused in one line naming the flag and the value (exit 2).

use crate::common;

use common::hapstab;

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

/// Arm flags beside --no-arm, normalized beside physical input, and two delays are refused
/// naming both flags.
#[test]
fn contradictory_arm_units_and_delay_flags_are_refused_naming_both() {
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
    ] {
        refused(args, &[a, b, "cannot be used with"]);
    }
}

/// Two plant models at once (transfer function, two-mass device, mass-spring-damper), and a
/// velocity estimator beside γ, are
/// refused naming both flags.
#[test]
fn contradictory_plant_models_are_refused_naming_both() {
    for (args, a, b) in [
        (
            &[
                "discretize",
                "--plant-num",
                "1",
                "--plant-den",
                "1,0,0",
                "--mass",
                "1",
            ][..],
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
    ] {
        refused(args, &[a, b, "cannot be used with"]);
    }
}

/// Loop flags beside the paper's normalized view, and the robust analysis beside a velocity
/// estimator, are refused naming both flags.
#[test]
fn loop_flags_beside_the_normalized_view_are_refused_naming_both() {
    for (args, a, b) in [
        (
            &["check", "--delta", "0.1", "--force-lag", "0.001"][..],
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

/// A velocity estimator that does not parse or is not causal and proper is refused in one line
/// naming --velocity and the value.
#[test]
fn velocity_estimator_input_is_refused_in_one_line() {
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
    ] {
        refused(args, needles);
    }
}

/// A named low-pass (Butterworth, Bessel, critically damped) with an order outside 1–8, a
/// cut-off at or above the Nyquist frequency 1/(2T), or a malformed spec is refused in one
/// line naming --velocity, the family's parameter and the value (exit 2).
#[test]
fn named_lowpass_input_is_refused_in_one_line() {
    for (family, title) in [
        ("butterworth", "Butterworth"),
        ("bessel", "Bessel"),
        ("critically-damped", "critically damped"),
    ] {
        let order = format!("{title} order N");
        let cutoff = format!("{title} cut-off f_c");
        let form = format!("{family}:ORDER:FC");
        for (spec, extra, needles) in [
            (
                format!("{family}:0:50"),
                &[][..],
                &["--velocity", &order, "0"][..],
            ),
            (format!("{family}:9:50"), &[], &["--velocity", &order, "9"]),
            (
                format!("{family}:2:500"),
                &[],
                &["--velocity", &cutoff, "500 Hz"],
            ),
            (
                format!("{family}:2:300"),
                &["--period", "0.002"][..],
                &["--velocity", &cutoff, "250 Hz", "300 Hz"],
            ),
            (
                format!("{family}:2:-4"),
                &[],
                &["--velocity", &cutoff, "-4"],
            ),
            (format!("{family}:50"), &[], &["--velocity", &form]),
            (format!("{family}:2:fast"), &[], &["--velocity", "'fast'"]),
            (format!("{family}:2.5:50"), &[], &["--velocity", "'2.5'"]),
        ] {
            let mut args = vec!["check", "--velocity", spec.as_str()];
            args.extend(extra);
            refused(&args, needles);
        }
    }
}

/// A transfer function that is not strictly proper, does not parse, is too long, or lacks its
/// other half is refused in one line naming the flag.
#[test]
fn transfer_function_input_is_refused_in_one_line() {
    for (args, needles) in [
        (
            &["check", "--plant-num", "1,2,3", "--plant-den", "1,1"][..],
            &[
                "--plant-num 1,2,3",
                "strictly proper: numerator degree < denominator degree (got numerator degree 2, denominator degree 1)",
            ][..],
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
    ] {
        refused(args, needles);
    }
}

/// A force lag, a two-mass device or a delay time out of range or half given is refused in one
/// line naming the parameter and the value.
#[test]
fn lag_two_mass_and_delay_input_is_refused_in_one_line() {
    for (args, needles) in [
        (
            &["check", "--force-lag", "-1"][..],
            &["--force-lag", "-1"][..],
        ),
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
    ] {
        refused(args, needles);
    }
}

/// Normalized input beside a transfer function, mixed map axes and a half-given normalized wall
/// are refused in one line naming the flags.
#[test]
fn normalized_and_map_input_is_refused_in_one_line() {
    for (args, needles) in [
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
            ][..],
            &["--alpha", "--plant-num"][..],
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
