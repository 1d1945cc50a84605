//! `hapstab population`: the curve (each operator's exact interval) and the wall (each
//! operator's verdict) count the same operators alike; the plot is written; bad input is one
//! line, exit 2.

use crate::common;

use common::{f, hapstab, json};

#[test]
fn the_curve_and_the_wall_agree() {
    let curve = json(&[
        "population",
        "--wall-damping",
        "3",
        "--samples",
        "600",
        "--seed",
        "9",
    ]);
    let ks = curve["k"].as_array().unwrap();
    let ps = curve["probability"].as_array().unwrap();
    for i in [40, 120, 200, 300] {
        let k = format!("{}", f(&ks[i]));
        let wall = json(&[
            "population",
            "--wall-damping",
            "3",
            "--samples",
            "600",
            "--seed",
            "9",
            "--wall-stiffness",
            &k,
        ]);
        assert_eq!(f(&wall["probability"]), f(&ps[i]), "K = {k}");
        let [lo, hi] = [f(&wall["interval"][0]), f(&wall["interval"][1])];
        assert!(lo <= f(&ps[i]) && f(&ps[i]) <= hi);
    }
    // a bracket end is absent where 600 operators cannot show the level at 95 %
    for l in curve["levels"].as_array().unwrap() {
        let k = f(&l["k"]);
        assert!(l["k_lo"].as_f64().is_none_or(|lo| lo <= k), "{l}");
        assert!(l["k_hi"].as_f64().is_none_or(|hi| k <= hi), "{l}");
    }
}

#[test]
fn the_plot_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let stem = dir.path().join("pop");
    let out = json(&[
        "population",
        "--samples",
        "300",
        "--plot",
        stem.to_str().unwrap(),
    ]);
    assert_eq!(out["plot"].as_array().unwrap().len(), 2);
    let svg = std::fs::read_to_string(dir.path().join("pop.svg")).unwrap();
    assert!(svg.contains("P(stable) ≥ 0.99 up to K = "), "levels tagged");
    assert!(std::fs::metadata(dir.path().join("pop.png")).unwrap().len() > 1000);
}

#[test]
fn bad_input_is_one_line() {
    for (args, needle) in [
        (
            &["population", "--dist", "foo=uniform:0:1"][..],
            "'foo' is not one of",
        ),
        (
            &["population", "--dist", "arm-mass=uniform:2:1"][..],
            "distribution",
        ),
        (
            &["population", "--levels", "1.5"][..],
            "level must be in (0, 1)",
        ),
        (
            &["population", "--samples", "0"][..],
            "samples must be at least 1",
        ),
        (
            &["population", "--wall-stiffness", "1e4", "--plot", "x"][..],
            "--plot",
        ),
    ] {
        let out = hapstab().args(args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(
            err.trim().lines().count() <= 3 && !err.contains("panicked"),
            "{err}"
        );
    }
}
