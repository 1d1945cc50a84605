//! `hapstab identify`: from a recording made by the independent simulator
//! (benches/baseline/identify_data.py) to the loop and its K_max; bad data, bad flags and a
//! model that cannot fit are one line naming the column or the parameter, exit 2.

use crate::common;

use std::path::PathBuf;

use common::{f, hapstab, json};

fn fixture(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../hapstab/tests/fixtures/identify")
        .join(name)
        .display()
        .to_string()
}

/// The single stderr line of a refused run (exit 2).
fn refused(args: &[&str]) -> String {
    let out = hapstab().args(args).output().unwrap();
    assert_eq!(out.status.code(), Some(2), "{args:?}");
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    err
}

#[test]
fn the_identified_loop_file_gives_kmax_the_same_k_max() {
    let dir = tempfile::tempdir().unwrap();
    let lp = dir.path().join("held.json");
    let plot = dir.path().join("fit.png");
    let data = fixture("held_prbs_40db.csv");
    let out = json(&[
        "identify",
        "--data",
        &data,
        "--fix",
        "device-mass=0.1",
        "--fix",
        "device-damping=1.5",
        "--write-loop",
        lp.to_str().unwrap(),
        "--plot",
        plot.to_str().unwrap(),
        "--draws",
        "50",
    ]);
    assert_eq!(out["model"], "held-device");
    let arm = &out["parameters"][2];
    assert_eq!(arm["name"], "arm-mass");
    let [lo, hi] = [f(&arm["ci95"][0]), f(&arm["ci95"][1])];
    assert!(lo < 1.0 && 1.0 < hi, "{arm}");
    let k = f(&out["stiffness_limit"]["k_max"]);
    let own = json(&[
        "kmax",
        "--loop",
        lp.to_str().unwrap(),
        "--wall-damping",
        "0",
    ]);
    assert!((f(&own["k_max"]) - k).abs() <= 1e-12 * k, "{own} vs {k}");
    let spread = &out["stiffness_limit"]["spread"];
    assert!(f(&spread[0]) <= k && k <= f(&spread[1]), "{spread}");
    assert!(plot.exists() && dir.path().join("fit.svg").exists());
}

#[test]
fn the_text_report_names_the_parameters_with_their_intervals() {
    let data = fixture("msd_chirp_40db.csv");
    let out = hapstab()
        .args(["identify", "--data", &data, "--draws", "20"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for want in [
        "mass ",
        "damping ",
        "stiffness ",
        "95 % interval",
        "K_max at B = 0",
        "robust",
    ] {
        assert!(text.contains(want), "{want}: {text}");
    }
}

#[test]
fn bad_data_and_flags_are_one_line_naming_the_problem() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, text: &str| {
        let p = dir.path().join(name);
        std::fs::write(&p, text).unwrap();
        p.display().to_string()
    };
    let rows = |f: &dyn Fn(usize) -> String| {
        let mut s = String::from("time,force,position\n");
        for k in 0..50 {
            s.push_str(&f(k));
        }
        s
    };
    let nan = write(
        "nan.csv",
        &rows(&|k| {
            format!(
                "{},{},{}\n",
                k as f64 * 1e-3,
                (k % 7) as f64,
                if k == 9 {
                    "nan".into()
                } else {
                    "0".to_string()
                }
            )
        }),
    );
    let e = refused(&["identify", "--data", &nan]);
    assert!(e.contains("column 'position': sample 10 is NaN"), "{e}");
    let flat = write("flat.csv", &rows(&|k| format!("{},1,0\n", k as f64 * 1e-3)));
    let e = refused(&["identify", "--data", &flat]);
    assert!(e.contains("column 'force': constant"), "{e}");
    let jitter = write(
        "jitter.csv",
        &rows(&|k| {
            format!(
                "{},{},0\n",
                k as f64 * 1e-3 + if k == 20 { 3e-4 } else { 0.0 },
                k % 3
            )
        }),
    );
    let e = refused(&["identify", "--data", &jitter]);
    assert!(e.contains("column 'time': not uniformly sampled"), "{e}");
    let data = fixture("msd_chirp_40db.csv");
    let e = refused(&["identify", "--data", &data, "--columns", "t,f,x"]);
    assert!(e.contains("column 't': not in the header"), "{e}");
    let e = refused(&["identify", "--data", &data, "--fix", "spring=3"]);
    assert!(
        e.contains("parameter 'spring': not a parameter of mass-spring-damper"),
        "{e}"
    );
    let e = refused(&["identify", "--data", &data, "--model", "three-mass"]);
    assert!(e.contains("parameter 'model': 'three-mass'"), "{e}");
    let e = refused(&["identify", "--data", "/nonexistent/run.csv"]);
    assert!(
        e.contains("--data '/nonexistent/run.csv': cannot read"),
        "{e}"
    );
}

#[test]
fn a_simulated_log_of_the_default_loop_gives_back_its_arm() {
    let dir = tempfile::tempdir().unwrap();
    let log = dir.path().join("run.csv");
    let log = log.to_str().unwrap();
    let out = hapstab()
        .args([
            "simulate",
            "--identification-log",
            log,
            "--excitation",
            "prbs:20",
        ])
        .args([
            "--excitation-amplitude",
            "2",
            "--log-snr",
            "40",
            "--quantization",
            "1e-5",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = json(&[
        "identify",
        "--data",
        log,
        "--fix",
        "device-mass=0.1",
        "--fix",
        "device-damping=1.5",
        "--draws",
        "20",
    ]);
    // the default arm (README): m_H = 1 kg, b_H = 6 Ns/m, k_H = 350 N/m
    for (p, truth) in out["parameters"].as_array().unwrap()[2..]
        .iter()
        .zip([1.0, 6.0, 350.0])
    {
        assert!((f(&p["value"]) / truth - 1.0).abs() < 0.02, "{p}");
    }
    let e = refused(&[
        "simulate",
        "--identification-log",
        log,
        "--excitation",
        "sine",
    ]);
    assert!(e.contains("'--excitation"), "{e}");
    let e = refused(&[
        "simulate",
        "--identification-log",
        log,
        "--log-samples",
        "1",
    ]);
    assert!(e.contains("--log-samples"), "{e}");
}

#[test]
fn the_band_s_k_max_is_the_identified_loop_s_at_the_quantization_step() {
    let dir = tempfile::tempdir().unwrap();
    let lp = dir.path().join("msd.json");
    let data = fixture("msd_chirp_40db.csv");
    let args = [
        "identify",
        "--data",
        &data,
        "--draws",
        "20",
        "--quantization",
        "2e-5",
    ];
    let out = json(&[&args[..], &["--write-loop", lp.to_str().unwrap()]].concat());
    assert_eq!(f(&out["input"]["quantization"]), 2e-5);
    let lim = &out["stiffness_limit"];
    let band = &lim["renderable"];
    assert_eq!(f(&band["position_resolution"]), 2e-5);
    let own = json(&[
        "kmax",
        "--loop",
        lp.to_str().unwrap(),
        "--position-resolution",
        "2e-5",
    ]);
    let k = f(&band["k_max"]);
    assert!(
        (f(&own["renderable"]["k_max"]) - k).abs() <= 1e-9 * k,
        "{own} vs {band}"
    );
    for p in [&lim["interval"], &band["interval"]] {
        let [lo, hi] = [f(&p["ci95"][0]), f(&p["ci95"][1])];
        let v = f(&p["value"]);
        assert!(lo < v && v < hi && f(&p["standard_error"]) > 0.0, "{p}");
    }
    let text = hapstab().args(args).output().unwrap();
    let text = String::from_utf8(text.stdout).unwrap();
    assert!(
        text.contains("95 % interval") && text.contains("over the renderable band 0 ≤ B ≤"),
        "{text}"
    );
    let err = refused(&["identify", "--data", &data, "--quantization", "nan"]);
    assert!(err.contains("'quantization'"), "{err}");
}
