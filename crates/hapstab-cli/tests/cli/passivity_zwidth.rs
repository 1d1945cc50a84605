//! Binary tests of `passivity`, the margins of `check`, `zwidth` and `sweep`: closed forms
//! (eq. 28 and its delayed form), margins checked by the binary's own verdict on the perturbed
//! wall, the filters shrinking the Z-width, files written, and bad input refused in one line
//! with exit code 2.

use crate::common;

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

/// A refused command: exit 2 and one line on stderr that contains every `needles`.
fn refused(args: &[&str], needles: &[&str]) {
    let out = hapstab().args(args).output().unwrap();
    assert_eq!(out.status.code(), Some(2), "{args:?}");
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: '{n}' not in {err}");
    }
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The PHANToM-like device of Remark 4 without an arm.
const PHANTOM: [&str; 1] = ["--no-arm"];

/// The subcommand `extra[0]` on the PHANToM-like device with the rest of `extra`.
fn args<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let mut out = vec![extra[0]];
    out.extend(PHANTOM);
    out.extend(&extra[1..]);
    out
}

/// Eq. (28) in physical units, b_required = KT/2 + |B|, with the verdict against b = 1.5.
#[test]
fn passivity_json_closed_form() {
    for (k, b, passive) in [
        ("2000", "0.3", true),
        ("2000", "-0.6", false),
        ("3500", "0", false),
    ] {
        let v = json(&args(&[
            "passivity",
            "--wall-stiffness",
            k,
            "--wall-damping",
            b,
        ]));
        let (kf, bf): (f64, f64) = (k.parse().unwrap(), b.parse().unwrap());
        let want = kf * 1e-3 / 2.0 + bf.abs();
        assert!(rel(f(&v["b_required"]), want) < 1e-12, "{v}");
        assert_eq!(v["device_damping"], 1.5);
        assert_eq!(v["meets"], passive, "{v}");
        let region = &v["passive_region"];
        assert!(rel(f(&region["k_max"]), 3000.0) < 1e-12);
        assert!(region["vertices"].as_array().unwrap().len() >= 3);
    }
    // A spring behind 2 samples: K(T/2 + 2T), binding at DC.
    let v = json(&args(&[
        "passivity",
        "--wall-stiffness",
        "1000",
        "--wall-damping",
        "0",
        "--delay",
        "2",
    ]));
    assert!(rel(f(&v["b_required"]), 2.5) < 1e-12, "{v}");
    assert_eq!(v["binding_frequency_hz"], 0.0);
    assert_eq!(v["verdict"], "not_passive");
}

#[test]
fn passivity_text_reads_both_verdicts() {
    let s = text(&args(&[
        "passivity",
        "--wall-stiffness",
        "20000",
        "--wall-damping",
        "20",
    ]));
    assert!(s.contains("NOT PASSIVE"), "{s}");
    assert!(s.contains("STABLE (stable but not passive)"), "{s}");
    let lag = text(&["passivity", "--force-lag", "0.0002"]);
    assert!(lag.contains("not applicable"), "{lag}");
}

fn check(extra: &[&str]) -> Value {
    let mut a = vec!["check"];
    a.extend_from_slice(extra);
    json(&a)
}

fn num(x: f64) -> String {
    format!("{x:e}")
}

/// Acceptance through the binary: K × gain margin (±1e-6) and the added delay margin (±1e-6)
/// flip `check`'s own verdict; the JSON carries every margin key.
#[test]
fn check_margins_cross_the_boundary() {
    for loop_flags in [
        vec!["--wall-stiffness", "10000", "--wall-damping", "10"],
        vec![
            "--wall-stiffness",
            "4000",
            "--wall-damping",
            "8",
            "--velocity",
            "lowpass:150",
            "--delay-time",
            "0.0013",
        ],
    ] {
        let v = check(&loop_flags);
        for key in [
            "gain_margin",
            "stiffness_margin",
            "phase_margin_deg",
            "gain_crossover_hz",
            "phase_crossover_hz",
            "delay_margin",
            "stiffness_crossover_hz",
            "stability_margin",
        ] {
            assert!(v[key].is_number(), "{key}: {v}");
        }
        let k: f64 = loop_flags[1].parse().unwrap();
        let gm = f(&v["stiffness_margin"]);
        let td = if loop_flags.len() > 6 { 0.0013 } else { 0.0 };
        let dm = f(&v["delay_margin"]);
        for (factor, stable) in [(1.0 - 1e-6, true), (1.0 + 1e-6, false)] {
            let mut a = loop_flags.clone();
            let ks = num(k * gm * factor);
            a[1] = &ks;
            assert_eq!(check(&a)["stable"], stable, "K × {gm} × {factor}");
            let mut a = loop_flags.clone();
            let tds = num(td + dm * factor);
            a.retain(|x| *x != "--delay-time" && *x != "0.0013");
            a.extend(["--delay-time", &tds]);
            assert_eq!(check(&a)["stable"], stable, "t_d + {dm} × {factor}");
        }
    }
    let s = text(&["check", "--no-arm"]);
    assert!(s.contains("margins") && s.contains("gain ×"), "{s}");
    let v = check(&["--wall-stiffness", "1e6"]);
    assert!(v["gain_margin"].is_null());
    assert!(
        v["margin_notes"][0]
            .as_str()
            .unwrap()
            .contains("not stable")
    );
}

/// Acceptance: `zwidth --compare` of backward against lowpass:100 and average:15 on the
/// PHANToM-like device: the filters shrink the stable region and its K_max; the passive
/// triangle of eq. (28) lies inside the stable region; SVG and PNG written.
#[test]
fn zwidth_compare_filters_shrink_the_stable_region() {
    let dir = tempfile::tempdir().unwrap();
    let stem = dir.path().join("zw");
    let stem_s = stem.to_str().unwrap();
    let v = json(&args(&[
        "zwidth",
        "--compare",
        "lowpass:100",
        "--compare",
        "average:15",
        "--plot",
        stem_s,
    ]));
    let loops = v["loops"].as_array().unwrap();
    assert_eq!(loops.len(), 3);
    let area = |l: &Value| f(&l["stable_area"]);
    let kmax = |l: &Value| f(&l["k_max"]["stiffness"]);
    assert_eq!(loops[0]["label"], "backward");
    for l in &loops[1..] {
        assert!(area(l) < area(&loops[0]), "{}", l["label"]);
        assert!(kmax(l) < kmax(&loops[0]), "{}", l["label"]);
        // the device is the same: the compared loops keep --no-arm
        assert_eq!(l["input"]["loop"]["plant"]["model"]["mass"], 0.1);
    }
    assert!(rel(f(&loops[0]["passive"]["k_max"]), 3000.0) < 1e-12);
    assert_eq!(loops[0]["passive_inside_stable"], true);
    let img = image::open(stem.with_extension("png")).unwrap();
    assert!(img.width() > 1000 && img.height() > 500);
    assert!(
        std::fs::read_to_string(stem.with_extension("svg"))
            .unwrap()
            .contains("<svg")
    );
}

#[test]
fn zwidth_table_and_devices() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("t.csv");
    let s = text(&args(&[
        "zwidth",
        "--table-damping",
        "0,10,20",
        "--compare",
        "--device-mass 0.3 --device-damping 4",
        "--csv",
        csv.to_str().unwrap(),
    ]));
    assert!(s.contains("compared with 'backward'"), "{s}");
    let rows = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(rows.lines().count(), 1 + 2 * 3, "{rows}");
    // the linear condition (22) column: (b + B)/(T/2)
    let row: Vec<&str> = rows.lines().nth(2).unwrap().split(',').collect();
    assert!(
        rel(row[5].parse().unwrap(), (1.5 + 10.0) / 5e-4) < 1e-12,
        "{row:?}"
    );
}

#[test]
fn zwidth_and_sweep_refuse_bad_input() {
    refused(
        &["zwidth", "--compare", "lowpass:-3"],
        &["--compare", "lowpass:-3"],
    );
    refused(&["zwidth", "--compare", "--no-such-flag 3"], &["--compare"]);
    refused(&["zwidth", "--gamma", "0.1"], &["physical"]);
    refused(
        &["zwidth", "--table-damping", "1,nan"],
        &["--table-damping"],
    );
    refused(
        &["sweep", "--param", "delay:0:1:5"],
        &["delay", "delay-time"],
    );
    refused(
        &["sweep", "--param", "delay-time:0:1:1"],
        &["sweep points", "1"],
    );
    refused(
        &["sweep", "--param", "cutoff:10:100:5"],
        &["cutoff", "low-pass"],
    );
    refused(
        &["sweep", "--param", "delay-time:-0.002:0.001:4"],
        &["delay time", "-0.002"],
    );
    refused(
        &["sweep", "--param", "period:0:0.001:3"],
        &["sampling period", "0"],
    );
    refused(
        &["sweep", "--param", "mass:0.1:1:3", "--damping-range", "5:1"],
        &["--damping-range", "LO must not exceed HI"],
    );
    refused(
        &["passivity", "--wall-stiffness", "nan"],
        &["stiffness", "NaN"],
    );
    refused(
        &["passivity", "--velocity", "iir:1000,-1000/1,-1.2"],
        &["velocity filter", "1.2"],
    );
}

/// K_max against the delay through the binary: CSV, JSON and plot; the passive K at B = 0 is
/// b/(T/2 + t_d) at whole samples (eq. 28 delayed).
#[test]
fn sweep_delay_time() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("s.csv");
    let stem = dir.path().join("s");
    let v = json(&args(&[
        "sweep",
        "--param",
        "delay-time:0:0.005:51",
        "--wall-damping",
        "0",
        "--csv",
        csv.to_str().unwrap(),
        "--plot",
        stem.to_str().unwrap(),
    ]));
    let pts = v["points"].as_array().unwrap();
    assert_eq!(pts.len(), 51);
    for p in pts.iter().step_by(10) {
        let td = f(&p["value"]);
        let want = 1.5 / (5e-4 + td);
        assert!(rel(f(&p["k_max_passive"]), want) < 1e-10, "{p}");
        assert!(f(&p["k_max"]) > f(&p["k_max_passive"]));
    }
    assert_eq!(std::fs::read_to_string(&csv).unwrap().lines().count(), 52);
    assert!(image::open(stem.with_extension("png")).is_ok());
    let s = text(&args(&["sweep", "--param", "mass:0.1:1:4"]));
    assert!(s.contains("K_max stable") && s.contains("kg"), "{s}");
}

/// `passivity --quantization Δ --coulomb f_c`: Abbott & Okamura's closed forms K ≤ 2b/T and
/// K ≤ 2f_c/Δ (pure spring, no delay), the smaller binding, the step and the friction echoed.
#[test]
fn quantized_spring_closed_forms() {
    let run = |k: &str| {
        json(&[
            "passivity",
            "--no-arm",
            "--device-damping",
            "2",
            "--wall-stiffness",
            k,
            "--wall-damping",
            "0",
            "--quantization",
            "1e-4",
            "--coulomb",
            "0.1",
        ])
    };
    let v = run("1500");
    let q = &v["quantized"];
    assert_eq!(q["quantization_step"], 1e-4);
    assert_eq!(q["coulomb_friction"], 0.1);
    assert_eq!(q["sampling"]["k_bound"], 2.0 * 2.0 / 1e-3);
    assert_eq!(q["quantization"]["k_bound"], 2.0 * 0.1 / 1e-4);
    assert_eq!(q["binding"], "quantization");
    assert_eq!(q["k_max"], 2000.0);
    assert_eq!(q["verdict"], "passive");
    assert_eq!(run("2500")["quantized"]["verdict"], "not_passive");
    let out = hapstab()
        .args([
            "passivity",
            "--alpha",
            "0.1",
            "--beta",
            "0",
            "--quantization",
            "1e-4",
        ])
        .args(["--coulomb", "0.1"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--quantization"));
}

/// Colgate–Schenkel's condition counts the device's own damping b_L (passive towards any
/// passive operator); the paper's eq. (28) with the arm's damping counted, b = b_L + b_H, is
/// a second, labelled figure.
#[test]
fn passivity_counts_the_devices_own_damping() {
    let held = [
        "passivity",
        "--device-mass",
        "0.25",
        "--device-damping",
        "2",
        "--period",
        "0.001",
        "--delay-time",
        "0.0004",
        "--wall-stiffness",
        "5000",
        "--wall-damping",
        "5",
    ];
    let v = json(&held);
    assert_eq!(v["device_damping"], 2.0, "{v}");
    assert_eq!(v["verdict"], "not_passive", "{v}");
    assert_eq!(v["effective_damping"], 8.0, "{v}");
    assert_eq!(v["effective_verdict"], "passive", "{v}");
    let req = f(&v["b_required"]);
    assert!(req > 2.0 && req < 8.0, "{v}");
    let s = text(&held);
    assert!(s.contains("NOT PASSIVE (device's own b_L = 2 Ns/m"), "{s}");
    assert!(
        s.contains("PASSIVE by eq. (28) with the arm's damping counted"),
        "{s}"
    );
    assert!(s.contains("towards this operator only"), "{s}");
    // the same device without an arm: the same requirement, no second figure
    let bare = json(&[&held[..], &["--no-arm"]].concat());
    assert_eq!(bare["b_required"], v["b_required"]);
    assert!(bare.get("effective_damping").is_none(), "{bare}");
    // whole-sample closed form: a spring behind one sample needs K(T/2 + T) = 7.5 Ns/m
    let one = json(&[
        "passivity",
        "--device-damping",
        "2",
        "--delay",
        "1",
        "--wall-stiffness",
        "5000",
        "--wall-damping",
        "0",
    ]);
    assert!(rel(f(&one["b_required"]), 7.5) < 1e-12, "{one}");
    assert_eq!(one["verdict"], "not_passive");
    assert_eq!(one["effective_verdict"], "passive", "{one}");
    // plain `passivity`: the PHANToM-like device's b_L = 1.5 Ns/m, not b_L + b_H = 7.5
    let plain = json(&["passivity"]);
    assert_eq!(plain["device_damping"], 1.5, "{plain}");
    assert_eq!(plain["effective_damping"], 7.5, "{plain}");
}

/// zwidth and sweep: the passive K_max for b_L, and the eq. (28) figure with the arm counted;
/// the passive region is homogeneous in b, so the two stand in the ratio (b_L + b_H)/b_L.
#[test]
fn zwidth_and_sweep_passive_kmax_use_the_devices_own_damping() {
    let z = json(&["zwidth"]);
    let zw = &z["loops"][0];
    // backward difference, d = 0: K_max passive = 2b/T at B = 0 (eq. 28)
    assert!(
        rel(f(&zw["passive"]["k_max"]), 2.0 * 1.5 / 1e-3) < 1e-9,
        "{zw}"
    );
    assert!(
        rel(
            f(&zw["k_max_passive_with_arm"]["stiffness"]),
            2.0 * 7.5 / 1e-3
        ) < 1e-9
    );
    // the linear condition (22) is a stability condition: the arm's damping counts
    assert_eq!(zw["linear"]["damping"], 7.5, "{zw}");
    let s = json(&["sweep", "--param", "delay-time:0:0.003:4"]);
    for p in s["points"].as_array().unwrap() {
        let (own, arm) = (f(&p["k_max_passive"]), f(&p["k_max_passive_with_arm"]));
        assert!(rel(arm, 5.0 * own) < 1e-9, "{p}");
    }
}

/// Where passivity does not apply (an actuator lag), `sweep` says why instead of a bare "—":
/// every point's passive K_max is null with the same reason `passivity` gives for the loop,
/// printed once under the table; where it applies, no reason is given.
#[test]
fn sweep_says_why_the_passive_column_is_empty() {
    let lag = [
        "sweep",
        "--param",
        "delay-time:0:0.002:3",
        "--force-lag",
        "0.0002",
    ];
    let reason = json(&["passivity", "--force-lag", "0.0002"])["note"]
        .as_str()
        .unwrap()
        .to_string();
    assert!(reason.contains("actuator lag"), "{reason}");
    let j = json(&lag);
    for p in j["points"].as_array().unwrap() {
        assert!(p["k_max_passive"].is_null(), "{p}");
        assert_eq!(p["passive_note"].as_str(), Some(reason.as_str()), "{p}");
    }
    let t = text(&lag);
    assert_eq!(t.matches(&reason).count(), 1, "{t}");
    let plain = json(&["sweep", "--param", "delay-time:0:0.002:3"]);
    for p in plain["points"].as_array().unwrap() {
        assert!(p["k_max_passive"].as_f64().unwrap() > 0.0, "{p}");
        assert!(p["passive_note"].is_null(), "{p}");
    }
}
