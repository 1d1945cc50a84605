//! Extreme inputs that once took gigabytes, said "empty" beside a stable check, or printed
//! NaN: each must now give a right answer or an honest refusal (exit 2, one line), within
//! bounded time and memory.

use crate::common;

use common::hapstab;
use std::time::{Duration, Instant};

/// Largest resident set of any child process waited for so far, in bytes.
fn children_max_rss() -> u64 {
    // SAFETY: getrusage writes into the struct we own.
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut u) };
    u.ru_maxrss as u64 * 1024
}

/// Runs a command line with a time bound; returns exit code, stdout, stderr.
fn run(args: &[&str], limit: Duration) -> (i32, String, String) {
    let t = Instant::now();
    let out = hapstab().args(args).timeout(limit).output().unwrap();
    assert!(t.elapsed() < limit, "{args:?} took {:?}", t.elapsed());
    let code = out.status.code().unwrap_or(-1);
    (
        code,
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

const MEMORY: u64 = 512 * 1024 * 1024;

fn check_stable(args: &[&str]) -> bool {
    let mut a = vec!["check", "--json"];
    a.extend_from_slice(args);
    let (code, out, err) = run(&a, Duration::from_secs(30));
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    v["verdict"] == "stable"
}

/// Either a region that agrees with `check` at the wall-free point, or one error line.
fn region_or_refusal(plant: &[&str]) {
    let mut a = vec!["boundary", "--json"];
    a.extend_from_slice(plant);
    let (code, out, err) = run(&a, Duration::from_secs(60));
    assert!(
        children_max_rss() < MEMORY,
        "{plant:?}: RSS {}",
        children_max_rss()
    );
    let mut probe = vec!["--alpha", "1e-9", "--beta", "1e-9"];
    probe.extend_from_slice(plant);
    let stable_here = check_stable(&probe);
    match code {
        0 => {
            let v: serde_json::Value = serde_json::from_str(&out).unwrap();
            let empty = v["polygons"].as_array().unwrap().is_empty();
            assert!(
                !(empty && stable_here),
                "{plant:?}: empty region beside a stable check"
            );
            assert!(!out.contains("NaN") && !out.contains("inf"), "{out}");
        }
        2 => assert_eq!(err.trim().lines().count(), 1, "{err}"),
        c => panic!("{plant:?}: exit {c}: {err}"),
    }
}

#[test]
fn heavy_damping_regions_are_bounded_and_consistent() {
    region_or_refusal(&[
        "--gamma",
        "967.8197089101616",
        "--delta",
        "100",
        "--delay",
        "100",
    ]);
    region_or_refusal(&["--gamma", "2.6e-10", "--delta", "19.3", "--delay", "200"]);
    region_or_refusal(&["--gamma", "1000", "--delta", "60"]);
}

#[test]
fn a_region_is_not_empty_where_check_is_stable() {
    // γ = 1000, δ = 60: the wall-free loop is stable, so the region is not empty.
    let (code, out, err) = run(
        &["boundary", "--gamma", "1000", "--delta", "60", "--json"],
        Duration::from_secs(30),
    );
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(!v["polygons"].as_array().unwrap().is_empty());
    assert!(check_stable(&[
        "--alpha", "0", "--beta", "0", "--gamma", "1000", "--delta", "60"
    ]));
}

#[test]
fn linear_condition_at_long_delay_prints_numbers() {
    let (code, out, err) = run(&["linear", "--delay", "200"], Duration::from_secs(60));
    assert_eq!(code, 0, "{err}");
    assert!(!out.contains("NaN"), "{out}");
    let (code, out, _) = run(
        &["linear", "--delay", "200", "--json"],
        Duration::from_secs(60),
    );
    assert_eq!(code, 0);
    assert!(!out.contains("null") && !out.contains("NaN"), "{out}");
}

/// Past the exact discretization's range the loop is refused in one line that names the
/// parameter, its value and the range; just inside it the answers stay right.
#[test]
fn out_of_range_time_scales_name_the_parameter() {
    let refused: [(&[&str], &[&str]); 5] = [
        (
            &["kmax", "--stiffness", "1e308"],
            &["stiffness k = 1e308 N/m", "rate × T ≤ 1e7"],
        ),
        (
            &["check", "--damping", "1e300", "--alpha", "0", "--beta", "0"],
            &["damping b = 1e300 Ns/m", "rate × T ≤ 1e50"],
        ),
        (
            &["kmax", "--force-lag", "1e-60"],
            &["force lag tau = 1e-60 s", "rate × T ≤ 1e50"],
        ),
        (
            &["kmax", "--period", "1e-300"],
            &["sampling period T", "[1e-7, 1] s", "1e-300"],
        ),
        (
            &["boundary", "--period", "2"],
            &["sampling period T", "[1e-7, 1] s"],
        ),
    ];
    for (args, words) in refused {
        let (code, _, err) = run(args, Duration::from_secs(10));
        assert_eq!(code, 2, "{args:?}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        for w in words {
            assert!(err.contains(w), "{args:?}: {err} lacks {w}");
        }
    }
    // A damper 10⁴³ times the mass per second still has its closed form: with k = 0 and
    // δ = bT/m ≫ 1 the plant is T/b·1/(z − 1) and K_max at B = 0 is 2b/T.
    let (code, out, err) = run(
        &["kmax", "--damping", "1e40", "--stiffness", "0", "--json"],
        Duration::from_secs(30),
    );
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let k0 = v["k_max_at_zero_damping"].as_f64().unwrap();
    assert!((k0 / 2e43 - 1.0).abs() < 1e-9, "{out}");
}
