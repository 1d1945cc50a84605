//! `bode`, `nyquist-plot` and `locus`: the marked crossovers against `check --json`'s
//! margins, the locus crossing the unit circle at `kmax --json`'s K_max, the CSV against the
//! JSON, and bad input. Expected values come from independent commands, never from the
//! command's own output.

use crate::common;

use common::{hapstab, json, num};
use serde_json::Value;

const LP: [&str; 2] = ["--delay=1", "--period=1e-3"];

fn arr(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn bode_marks_are_the_margins_of_check() {
    let mut args = vec!["bode", "--wall-stiffness=5000", "--wall-damping=5"];
    args.extend(LP);
    let b = json(&args);
    let mut c = vec!["check", "--wall-stiffness=5000", "--wall-damping=5"];
    c.extend(LP);
    let c = json(&c);
    assert_eq!(c["verdict"], "stable");
    for key in [
        "gain_crossover_hz",
        "phase_crossover_hz",
        "phase_margin_deg",
        "gain_margin",
    ] {
        assert_eq!(num(&b, key), num(&c, key), "{key}");
    }
    let gc = b["marks"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["primary"] == true && m["kind"] == "gain")
        .unwrap();
    assert!(num(gc, "magnitude_db").abs() < 1e-9, "{gc}");
}

#[test]
fn locus_crosses_the_unit_circle_at_kmax() {
    for b in ["3", "20"] {
        let mut k = vec!["kmax", "--wall-damping", b];
        k.extend(LP);
        let kmax = num(&json(&k), "k_max");
        let mut l = vec!["locus", "--wall-damping", b];
        l.extend(LP);
        let v = json(&l);
        let ks = arr(&v["stiffness"]);
        let rho = arr(&v["spectral_radius"]);
        let i = ks
            .iter()
            .position(|&x| (x - kmax).abs() <= 1e-9 * kmax)
            .expect("K_max sampled");
        assert!((rho[i] - 1.0).abs() < 1e-9, "B = {b}: {}", rho[i]);
        assert!(rho[i - 1] < 1.0 && rho[i + 1] > 1.0);
    }
}

#[test]
fn bode_csv_equals_its_json() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("b.csv");
    let mut args = vec!["bode", "--csv", csv.to_str().unwrap()];
    args.extend(LP);
    let v = json(&args);
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .map(|x| x.parse::<f64>().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    let cols = [
        "frequency_hz",
        "omega_rad_s",
        "re",
        "im",
        "magnitude_db",
        "phase_deg",
    ];
    for (j, c) in cols.iter().enumerate() {
        let a = arr(&v["curve"][c]);
        assert_eq!(a.len(), rows.len());
        for (x, r) in a.iter().zip(&rows) {
            // serde_json's default float parser may be one ulp off the shortest round trip
            assert!(
                (x - r[j]).abs() <= 4.0 * f64::EPSILON * x.abs(),
                "{c}: {x} vs {}",
                r[j]
            );
        }
    }
}

#[test]
fn bad_input_names_the_parameter_and_exits_2() {
    for (args, word) in [
        (vec!["bode", "--period=-1e-3"], "period"),
        (vec!["nyquist-plot", "--period=-1e-3"], "period"),
        (vec!["locus", "--wall-damping=nan"], "--wall-damping"),
    ] {
        let out = hapstab().args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains(word) && err.trim().lines().count() == 1,
            "{args:?}: {err}"
        );
    }
}
