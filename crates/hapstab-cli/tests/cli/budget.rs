//! Every command estimates its cost before it starts and refuses what is beyond its budget,
//! naming the flag that drives the cost; inputs beyond the representable range get one-line
//! range errors naming the flag and the value instead of numerical failures.
//!
//! `HAPSTAB_MAX_SECONDS` lowers the time budget so that the refusals can be shown on runs
//! that would take minutes (each must be refused within a second, before any work).

use crate::common;

use common::hapstab;
use std::time::{Duration, Instant};

/// Exit code, stdout and stderr of a command line run with environment `env`, which must end
/// within `limit`.
fn run_env(args: &[&str], env: &[(&str, &str)], limit: Duration) -> (i32, String, String) {
    let t = Instant::now();
    let mut cmd = hapstab();
    cmd.args(args).timeout(limit);
    for (k, v) in env {
        cmd.env(k, v);
    }
    let out = cmd.output().unwrap();
    assert!(t.elapsed() < limit, "{args:?} took {:?}", t.elapsed());
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// A refusal: exit 2, one line on stderr containing every needle, nothing on stdout.
fn refused(args: &[&str], env: &[(&str, &str)], needles: &[&str]) -> String {
    let (code, out, err) = run_env(args, env, Duration::from_secs(10));
    assert_eq!(code, 2, "{args:?}: {out}{err}");
    assert!(out.is_empty(), "{args:?}: {out}");
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: {err} lacks {n}");
    }
    assert!(!err.contains("numerical failure"), "{err}");
    err
}

/// A budget of 1 core-second: the heavy runs below need a minute or more.
const ONE_SECOND: [(&str, &str); 1] = [("HAPSTAB_MAX_SECONDS", "1")];

#[test]
fn heavy_runs_are_refused_before_they_start_naming_their_flag() {
    let ones = vec!["1"; 2001].join(",");
    let iir = format!("iir:{ones}/1");
    let cases: Vec<(Vec<&str>, Vec<&str>)> = vec![
        (
            vec!["check", "--velocity", "average:2000"],
            vec!["--velocity average:2000", "margins"],
        ),
        (
            vec!["check", "--velocity", &iir],
            vec!["--velocity iir: 2001 coefficients (1, 1, 1, …)"],
        ),
        (
            vec!["sweep", "--param", "delay-time:0:2:2000"],
            vec!["--param delay-time:0:2:2000", "2000 points"],
        ),
        (
            vec!["sweep", "--param", "delay-time:0:0.005:100000"],
            vec!["--param delay-time:0:0.005:100000"],
        ),
        (
            vec!["boundary", "--delay", "2000", "--velocity", "average:1000"],
            vec!["--delay 2000", "exact region"],
        ),
    ];
    for (args, needles) in &cases {
        let err = refused(args, &ONE_SECOND, needles);
        assert!(err.len() < 400, "{} characters: {err}", err.len());
    }
}

#[test]
fn without_the_lower_budget_the_heavy_sweep_is_refused_too() {
    // 2000 exact regions at delays up to 2000 samples: about a quarter of an hour
    refused(
        &["sweep", "--param", "delay-time:0:2:2000"],
        &[],
        &["--param delay-time:0:2:2000", "min of computing"],
    );
}

#[test]
fn the_radius_map_at_the_largest_delay_names_the_delay_and_a_realistic_time() {
    // 10⁴ spectral radii at degree 2003: tens of milliseconds each, minutes in all (not the
    // hundreds of hours of a dense eigenvalue solver)
    let err = refused(
        &[
            "map",
            "--x",
            "K:0:1e4:100",
            "--y",
            "B:0:10:100",
            "--delay",
            "2000",
            "--radius",
        ],
        &[],
        &["--delay 2000", "use a smaller --delay", "min of computing"],
    );
    assert!(!err.contains(" h of computing"), "{err}");
    assert!(!err.contains("degree"), "{err}");
}

#[test]
fn an_estimate_is_printed_on_request_and_light_runs_are_not_refused() {
    let env = [("HAPSTAB_ESTIMATE", "1")];
    let commands: [&[&str]; 8] = [
        &["check", "--delay", "20"],
        &["kmax", "--delay", "20"],
        &["boundary", "--delay", "20"],
        &["passivity", "--delay", "20"],
        &["zwidth", "--delay", "5"],
        &["sweep", "--param", "delay-time:0:0.005:5"],
        &["simulate", "--duration", "0.5"],
        &["map", "--x", "K:0:1e4:20", "--y", "B:0:10:20"],
    ];
    for args in commands {
        let (code, _, err) = run_env(args, &env, Duration::from_secs(60));
        assert_eq!(code, 0, "{args:?}: {err}");
        let est = err
            .lines()
            .find_map(|l| l.strip_prefix("estimate: "))
            .unwrap_or_else(|| panic!("{args:?} printed no estimate: {err}"));
        let seconds: f64 = est.split(' ').next().unwrap().parse().unwrap();
        assert!(seconds > 0.0 && seconds < 10.0, "{args:?}: {est}");
    }
}

#[test]
fn walls_filters_and_masses_beyond_the_representable_get_range_errors() {
    let cases: &[(&[&str], &[&str])] = &[
        (
            &["check", "--wall-stiffness", "1e308"],
            &["--wall-stiffness", "1e308"],
        ),
        (
            &["check", "--wall-damping", "-1e308"],
            &["--wall-damping", "-1e308"],
        ),
        (
            &[
                "passivity",
                "--no-arm",
                "--wall-stiffness",
                "1e308",
                "--wall-damping",
                "1e308",
            ],
            &["--wall-stiffness", "1e308"],
        ),
        (
            &["check", "--alpha", "1e308", "--beta", "0"],
            &["--alpha", "1e308"],
        ),
        (
            &["check", "--velocity", "iir:1e300,-1e300/1"],
            &["--velocity", "numerator b = 1e300"],
        ),
        (
            &["check", "--velocity", "iir:1000,-1000/1e-320"],
            &["--velocity", "a0 = 1e-320"],
        ),
        (
            &[
                "check",
                "--motor-mass",
                "1e300",
                "--transmission-stiffness",
                "1e4",
            ],
            &["--motor-mass", "1e300"],
        ),
        (
            &[
                "check",
                "--motor-mass",
                "1e-300",
                "--transmission-stiffness",
                "1e4",
            ],
            &["--motor-mass", "1e-300"],
        ),
        (
            &["check", "--mass", "1e-300"],
            &["--mass", "mass m", "1e-300"],
        ),
        (&["check", "--mass", "1e20"], &["--mass", "1e20"]),
        (
            &["sweep", "--param", "mass:1e-300:1:3"],
            &["--param mass:1e-300:1:3", "mass m", "1e-300"],
        ),
    ];
    for (args, needles) in cases {
        let err = refused(args, &[], needles);
        assert!(
            !err.contains("stiffness k ="),
            "{args:?} blames the stiffness: {err}"
        );
        assert!(!err.contains("not finite"), "{err}");
    }
}

#[test]
fn long_lists_are_echoed_as_a_short_excerpt() {
    let ones = vec!["1"; 10_000].join(",");
    let cases: Vec<Vec<String>> = vec![
        vec!["check".into(), "--velocity".into(), format!("iir:{ones}/1")],
        vec!["check".into(), "--velocity".into(), format!("iir:{ones}/x")],
        vec![
            "check".into(),
            "--plant-num".into(),
            ones.clone(),
            "--plant-den".into(),
            "1,2".into(),
        ],
        vec![
            "check".into(),
            "--plant-num".into(),
            "1".into(),
            "--plant-den".into(),
            ones.clone(),
        ],
    ];
    for args in cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let err = refused(&args, &[], &["10000 coefficients (1, 1, 1, …)"]);
        assert!(err.len() < 400, "{} characters: {err}", err.len());
    }
}

#[test]
fn nyquist_refuses_a_delay_time_in_one_line() {
    refused(
        &["nyquist", "--delay-time", "0.0015"],
        &[],
        &["--delay-time 0.0015"],
    );
    refused(
        &["nyquist", "--device-mass", "0.1", "--delay", "2"],
        &[],
        &["--delay 2", "Remark 4"],
    );
}
