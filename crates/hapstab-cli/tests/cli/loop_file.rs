//! `--loop FILE`: the loop a report echoes under "input", saved and given back, gives every
//! command the same answer as the flags it came from; flags beside the file change its parts
//! as those flags change the flags' loop; a malformed file is refused in one line, exit 2.

use crate::common;

use common::{hapstab, json};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// Loops of every kind as flags: the paper's default, a device without an arm, a two-mass
/// device held by an arm, a transfer function of order 5 with a force lag, an IIR estimator
/// and a fractional delay.
const LOOPS: [&[&str]; 5] = [
    &[],
    &[
        "--no-arm",
        "--device-mass",
        "0.25",
        "--device-damping",
        "2",
        "--period",
        "5e-4",
        "--delay",
        "2",
    ],
    &[
        "--motor-mass",
        "0.3",
        "--transmission-stiffness",
        "2300",
        "--handle-mass",
        "0.1",
        "--arm-mass",
        "2",
        "--arm-damping",
        "3",
        "--arm-stiffness",
        "1200",
        "--velocity",
        "lowpass:40",
        "--period",
        "0.002",
    ],
    &[
        "--plant-num",
        "0.5,120,35000",
        "--plant-den",
        "0.44,113,11000,715000,35000000,800000000",
        "--force-lag",
        "0.0004",
        "--period",
        "4e-4",
        "--delay-time",
        "1.4e-4",
    ],
    &[
        "--velocity",
        "iir:0.5,0,-0.5/1,-0.2",
        "--delay-time",
        "0.00037",
        "--arm-stiffness",
        "900",
    ],
];

/// A fresh file path in a temporary directory kept alive by the caller.
fn path_in(dir: &tempfile::TempDir, name: &str) -> PathBuf {
    dir.path().join(name)
}

/// Writes JSON to a file.
fn save(path: &Path, v: &Value) {
    std::fs::write(path, v.to_string()).unwrap();
}

/// A command's JSON without its timing (the one field that differs between two runs).
fn answer(args: &[&str]) -> Value {
    let mut v = json(args);
    if let Some(o) = v.as_object_mut() {
        o.remove("seconds");
    }
    v
}

/// `args` followed by `extra`.
fn with<'a>(args: &[&'a str], extra: &[&'a str]) -> Vec<&'a str> {
    args.iter().chain(extra).copied().collect()
}

#[test]
fn check_reads_its_own_input_back() {
    let dir = tempfile::tempdir().unwrap();
    for (i, lp) in LOOPS.iter().enumerate() {
        let wall = ["--wall-stiffness", "3000", "--wall-damping", "2"];
        let from_flags = answer(&with(&with(&["check"], lp), &wall));
        // the report's input, its loop object (with the wall flags) and the whole report
        let input = path_in(&dir, &format!("input{i}.json"));
        save(&input, &from_flags["input"]);
        let lp_only = path_in(&dir, &format!("loop{i}.json"));
        save(&lp_only, &from_flags["input"]["loop"]);
        let report = path_in(&dir, &format!("report{i}.json"));
        save(&report, &from_flags);
        let (p1, p2, p3) = (
            input.to_str().unwrap(),
            lp_only.to_str().unwrap(),
            report.to_str().unwrap(),
        );
        assert_eq!(answer(&["check", "--loop", p1]), from_flags, "{lp:?}");
        assert_eq!(
            answer(&with(&["check", "--loop", p2], &wall)),
            from_flags,
            "{lp:?}"
        );
        assert_eq!(answer(&["check", "--loop", p3]), from_flags, "{lp:?}");
    }
}

#[test]
fn every_loop_command_takes_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let commands: [&[&str]; 10] = [
        &["kmax"],
        &["boundary"],
        &["passivity"],
        &["discretize"],
        &["locus"],
        &["bode"],
        &["nyquist-plot"],
        &["simulate", "--duration", "0.2"],
        &["sweep", "--param", "delay-time:0:0.002:4"],
        &["map", "--x", "K:0:20000:8", "--y", "B:0:40:6"],
    ];
    for (i, lp) in LOOPS.iter().enumerate() {
        let file = path_in(&dir, &format!("l{i}.json"));
        save(&file, &json(&with(&["check"], lp))["input"]);
        let f = file.to_str().unwrap();
        for cmd in commands {
            let a = answer(&with(cmd, lp));
            let b = answer(&with(cmd, &["--loop", f]));
            assert_eq!(a, b, "{cmd:?} {lp:?}");
        }
    }
}

#[test]
fn the_paper_commands_take_a_paper_loop_and_refuse_others() {
    let dir = tempfile::tempdir().unwrap();
    let flags = ["--gamma", "0.3", "--delta", "0.1", "--delay", "1"];
    let normalized = path_in(&dir, "n.json");
    save(
        &normalized,
        &json(&with(
            &["check", "--alpha", "0.1", "--beta", "0.05"],
            &flags,
        ))["input"],
    );
    let n = normalized.to_str().unwrap();
    assert_eq!(
        answer(&with(&["linear"], &flags)),
        answer(&["linear", "--loop", n])
    );
    assert_eq!(
        answer(&with(&["boundary"], &flags)),
        answer(&["boundary", "--loop", n])
    );
    assert_eq!(
        answer(&[
            "map",
            "--x",
            "alpha:0:1:6",
            "--y",
            "beta:0:1:6",
            "--gamma",
            "0.3",
            "--delta",
            "0.1",
            "--delay",
            "1"
        ]),
        answer(&[
            "map",
            "--x",
            "alpha:0:1:6",
            "--y",
            "beta:0:1:6",
            "--loop",
            n
        ])
    );
    assert_eq!(
        answer(&["nyquist", "--delta", "0.1", "--delay", "1"]),
        answer(&["nyquist", "--loop", n])
    );
    // the normalized wall of the file is check's wall
    assert_eq!(
        answer(&with(
            &["check", "--alpha", "0.1", "--beta", "0.05"],
            &flags
        )),
        answer(&["check", "--loop", n])
    );
    let tf = path_in(&dir, "tf.json");
    save(&tf, &json(&with(&["check"], LOOPS[3]))["input"]);
    let out = hapstab()
        .args(["linear", "--loop", tf.to_str().unwrap()])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("paper's loop only") && err.trim().lines().count() == 1,
        "{err}"
    );
}

/// The flags `base` with the flags of `extra` in place of those they replace: the same flag,
/// the arm flags for --no-arm, every plant flag for a transfer function (the documented
/// parts of `--loop`).
fn replaced<'a>(base: &[&'a str], extra: &[&'a str]) -> Vec<&'a str> {
    let plant = [
        "--motor-mass",
        "--transmission-stiffness",
        "--handle-mass",
        "--device-mass",
        "--device-damping",
        "--arm-mass",
        "--arm-damping",
        "--arm-stiffness",
        "--no-arm",
    ];
    let gone = |flag: &str| {
        extra.contains(&flag)
            || (extra.contains(&"--no-arm") && flag.starts_with("--arm-"))
            || (extra.contains(&"--plant-num") && plant.contains(&flag))
    };
    let mut out = Vec::new();
    let mut i = 0;
    while i < base.len() {
        let switch = base[i] == "--no-arm";
        if gone(base[i]) {
            i += if switch { 1 } else { 2 };
            continue;
        }
        out.push(base[i]);
        i += 1;
    }
    out.extend(extra);
    out
}

#[test]
fn flags_beside_the_file_change_its_parts() {
    let dir = tempfile::tempdir().unwrap();
    let overrides: [&[&str]; 7] = [
        &["--arm-stiffness", "800"],
        &["--no-arm"],
        &["--device-mass", "0.3"],
        &["--velocity", "average:3"],
        &["--wall-stiffness", "5000"],
        &["--period", "5e-4"],
        &["--plant-num", "10", "--plant-den", "1,3,10"],
    ];
    for lp in [LOOPS[0], LOOPS[1], LOOPS[2], LOOPS[4]] {
        let wall = ["--wall-stiffness", "3000", "--wall-damping", "2"];
        let flags = with(&with(&["check"], lp), &wall);
        let file = path_in(&dir, "f.json");
        save(&file, &json(&flags)["input"]);
        let f = file.to_str().unwrap();
        for extra in overrides {
            if (lp == LOOPS[2] && extra[0] == "--device-mass")
                || (lp == LOOPS[1] && extra[0] == "--no-arm")
            {
                continue; // a two-mass device has no --device-mass; LOOPS[1] has no arm
            }
            if extra[0] == "--period" && lp.iter().any(|a| a.starts_with("--delay")) {
                continue; // the file keeps its delay in samples, the flags in their own unit
            }
            // an arm flag on a file without an arm adds that part to an arm of zeros
            let mut flags = flags.clone();
            if lp == LOOPS[1] && extra[0].starts_with("--arm-") {
                flags.retain(|a| *a != "--no-arm");
                flags.extend(["--arm-mass", "0", "--arm-damping", "0"]);
            }
            let expected = answer(&replaced(&flags, extra));
            let got = answer(&with(&["check", "--loop", f], extra));
            assert_eq!(got, expected, "{lp:?} {extra:?}");
        }
    }
}

#[test]
fn zwidth_compares_two_saved_loops() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (path_in(&dir, "a.json"), path_in(&dir, "b.json"));
    save(&a, &json(&["check"])["input"]);
    save(&b, &json(&["check", "--velocity", "lowpass:100"])["input"]);
    let spec = format!("--loop {}", b.display());
    let from_files = answer(&[
        "zwidth",
        "--loop",
        a.to_str().unwrap(),
        "--compare",
        &spec,
        "--table-damping",
        "0,5",
    ]);
    let from_flags = answer(&[
        "zwidth",
        "--compare",
        "lowpass:100",
        "--table-damping",
        "0,5",
    ]);
    let k = |v: &Value, i: usize| v["loops"][i]["zwidth"]["k_max"].clone();
    assert_eq!(k(&from_files, 0), k(&from_flags, 0));
    assert_eq!(k(&from_files, 1), k(&from_flags, 1));
}

#[test]
fn malformed_files_are_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (r#"{"loop": {"period": "fast"}}"#, "loop.period"),
        (r#"{"loop": {"perod": 0.001}}"#, "perod"),
        (r#"{"loop": {"period": 7}}"#, "sampling period T"),
        (
            r#"{"loop": {"plant": {"model": {"kind": "two_mass"}}}}"#,
            "motor_mass",
        ),
        ("not json", "not JSON"),
    ];
    for (text, named) in cases {
        let file = path_in(&dir, "bad.json");
        std::fs::write(&file, text).unwrap();
        let out = hapstab()
            .args(["check", "--loop", file.to_str().unwrap()])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{text}: {err}");
        assert!(
            err.contains(named) && err.trim().lines().count() == 1,
            "{text}: {err}"
        );
    }
    // an endless device is refused at the size bound, not read into memory
    let out = hapstab()
        .args(["boundary", "--loop", "/dev/zero"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("longer than"));
    let out = hapstab()
        .args(["kmax", "--loop", "/nonexistent/loop.json"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("/nonexistent/loop.json"));
}
