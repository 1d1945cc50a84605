//! `kmax --robust --box NAME:LO:HI`: robust K_max of any loop over a box of its parameters.
//! The worst plant, given back to `kmax` as flags, has the reported K_max; the paper's box
//! gives the paper search's K_max at its damping; a bad box is one line, exit 2.

use crate::common;

use common::{f, hapstab, json};

#[test]
fn the_worst_plant_has_the_robust_k_max() {
    let out = json(&[
        "kmax",
        "--robust",
        "--box",
        "arm-stiffness:0:2000",
        "--box",
        "arm-mass:0.2:2",
        "--wall-damping",
        "5",
        "--velocity",
        "lowpass:150",
        "--verify",
        "3000",
    ]);
    let k = f(&out["k_max"]);
    let worst = out["worst_plant"].as_array().unwrap();
    let mut flags = vec!["kmax".to_string(), "--wall-damping".into(), "5".into()];
    flags.extend(["--velocity".into(), "lowpass:150".into()]);
    for p in worst {
        flags.push(format!("--{}", p["param"].as_str().unwrap()));
        flags.push(format!("{}", f(&p["value"])));
    }
    let args: Vec<&str> = flags.iter().map(String::as_str).collect();
    let own = json(&args);
    assert!((f(&own["k_max"]) - k).abs() <= 1e-12 * k, "{own} vs {k}");
    assert!(k <= f(&out["k_max_nominal"]));
    assert_eq!(out["plants_verified"], 3000);
    assert_eq!(out["input"]["box"][0]["param"], "arm-stiffness");
}

#[test]
fn the_paper_box_at_its_damping_is_the_paper_search() {
    let paper = json(&["kmax", "--robust"]);
    let b = format!("{}", f(&paper["b_at_k_max"]));
    let ours = json(&[
        "kmax",
        "--robust",
        "--mass",
        "1.1",
        "--damping",
        "7.5",
        "--stiffness",
        "350",
        "--box",
        "mass:0.1:1.1",
        "--box",
        "damping:1.5:7.5",
        "--box",
        "stiffness:0:350",
        "--wall-damping",
        &b,
    ]);
    let (k, kp) = (f(&ours["k_max"]), f(&paper["k_max"]));
    assert!((k - kp).abs() <= 1e-9 * kp, "{k} vs {kp}");
}

#[test]
fn a_bad_box_is_one_line() {
    for (args, needle) in [
        (
            &["kmax", "--robust", "--box", "foo:0:1"][..],
            "'foo' is not one of delay-time",
        ),
        (
            &["kmax", "--robust", "--box", "mass:2:1"][..],
            "LO must not exceed HI",
        ),
        (
            &["kmax", "--robust", "--box", "cutoff:10:20"][..],
            "cutoff needs a low-pass",
        ),
        (&["kmax", "--box", "mass:1:2"][..], "--robust"),
        (
            &["kmax", "--robust", "--velocity", "lowpass:100"][..],
            "--robust without --box cannot be used with --velocity",
        ),
    ] {
        let out = hapstab().args(args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}
