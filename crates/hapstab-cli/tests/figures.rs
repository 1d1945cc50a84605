//! Figures in physical units (`--plot` of boundary, map, kmax, check), kmax's damping range,
//! and quiet standard error when it is not a terminal. Expected values come from the library
//! or from closed forms, never from the program's own output.

use assert_cmd::Command;
use hapstab::loop_analysis::{damping_units, k_max_at_damping, k_max_within};
use hapstab::model::Loop;
use hapstab::{AffineFamily, Effective};
use serde_json::Value;

fn hapstab() -> Command {
    Command::cargo_bin("hapstab").unwrap()
}

/// Runs the binary, asserts success and an empty standard error (not a terminal: no
/// progress bar), and returns standard output.
fn run_quiet(args: &[&str]) -> String {
    let out = hapstab().args(args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {err}");
    assert!(err.is_empty(), "{args:?} wrote to stderr: {err}");
    String::from_utf8(out.stdout).unwrap()
}

fn json(args: &[&str]) -> Value {
    let mut a = args.to_vec();
    a.push("--json");
    serde_json::from_str(&run_quiet(&a)).unwrap()
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The CLI's default physical loop: m = m_L + m_H = 0.1 + 1.0 kg, b = 1.5 + 6 Ns/m,
/// k = 350 N/m, T = 1 ms.
fn default_loop(d: usize) -> Loop {
    Loop::paper(Effective::new(1.1, 7.5, 350.0).unwrap(), 1e-3, d).unwrap()
}

// ---- kmax --damping-range ------------------------------------------------------------

#[test]
fn kmax_by_default_keeps_the_damping_non_negative() {
    let lp = default_loop(200);
    let fam = AffineFamily::of_loop(&lp).unwrap();
    let best = k_max_within(&lp, &fam, 0.0, f64::INFINITY)
        .unwrap()
        .unwrap();
    let (k, b) = fam.to_physical(best.alpha, best.beta);
    let v = json(&["kmax", "--delay", "200"]);
    let (k_cli, b_cli) = (f(&v["k_max"]), f(&v["b_at_k_max"]));
    assert!(b_cli >= 0.0, "B = {b_cli}");
    assert!((k_cli - k).abs() <= 1e-12 * k, "{k_cli} vs {k}");
    assert!(
        (b_cli - b).abs() <= 1e-12 * b.abs().max(1.0),
        "{b_cli} vs {b}"
    );
    // without a band the region's maximum lies at a negative B for this delay: the band
    // changes the answer
    let free = k_max_within(&lp, &fam, f64::NEG_INFINITY, f64::INFINITY)
        .unwrap()
        .unwrap();
    assert!(free.beta < 0.0 && free.alpha > best.alpha);
    // K_max at B = 0 (the plant's own damping only)
    let at0 = k_max_at_damping(&lp, &fam, 0.0).unwrap().unwrap();
    let k0 = fam.to_physical(at0.hi, 0.0).0;
    assert!((f(&v["k_max_at_zero_damping"]) - k0).abs() <= 1e-12 * k0);
}

#[test]
fn kmax_damping_range_bounds_the_damping() {
    let lp = default_loop(0);
    let fam = AffineFamily::of_loop(&lp).unwrap();
    let hi = damping_units(&lp, &fam, 50.0).unwrap();
    let best = k_max_within(&lp, &fam, 0.0, hi).unwrap().unwrap();
    let (k, b) = fam.to_physical(best.alpha, best.beta);
    let v = json(&["kmax", "--damping-range", "0:50"]);
    assert!((f(&v["k_max"]) - k).abs() <= 1e-12 * k);
    assert!((f(&v["b_at_k_max"]) - b).abs() <= 1e-9 * 50.0);
    assert!(f(&v["b_at_k_max"]) <= 50.0 + 1e-9);
    assert_eq!(v["damping_range"], serde_json::json!([0.0, 50.0]));
}

#[test]
fn kmax_damping_range_rejects_bad_bands() {
    for bad in ["5", "3:1", "a:2", "nan:1", "0:-inf"] {
        let out = hapstab()
            .args(["kmax", "--damping-range", bad])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{bad}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("--damping-range"), "{bad}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{bad}: {err}");
    }
}
