//! Helpers shared by the command-line tests: run `hapstab`, read its JSON.
#![allow(dead_code)]

pub mod strict;

use assert_cmd::Command;
use serde_json::Value;

/// The `hapstab` binary of this build.
pub fn hapstab() -> Command {
    Command::cargo_bin("hapstab").unwrap()
}

/// Runs the binary in `dir`, asserting success, and returns what it wrote.
fn succeeded_in(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    let out = hapstab().current_dir(dir).args(args).output().unwrap();
    assert!(
        out.status.success(),
        "hapstab {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Runs the binary in `dir`, asserting success, and returns its standard output.
pub fn stdout_in(dir: &std::path::Path, args: &[&str]) -> String {
    String::from_utf8(succeeded_in(dir, args).stdout).unwrap()
}

/// Runs the binary in `dir`, asserting success and an empty standard error (no progress bar
/// off a terminal, no warning), and returns its standard output.
pub fn quiet_stdout_in(dir: &std::path::Path, args: &[&str]) -> Vec<u8> {
    let out = succeeded_in(dir, args);
    assert!(
        out.stderr.is_empty(),
        "hapstab {}: standard error not empty: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// [`stdout_in`] the system's temporary directory.
pub fn stdout(args: &[&str]) -> String {
    stdout_in(&std::env::temp_dir(), args)
}

/// The JSON a command prints (exit 0 required).
pub fn json(args: &[&str]) -> Value {
    let out = hapstab().args(args).arg("--json").output().unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// A number of a JSON object (present and finite required).
pub fn num(v: &Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} missing in {v}"))
}

/// `check --json` of the loop flags `lp` at the wall (K, B) with `extra` flags.
pub fn check_json(lp: &[&str], k: f64, b: f64, extra: &[&str]) -> Value {
    let mut args = vec!["check"];
    args.extend(lp);
    let (ks, bs) = (
        format!("--wall-stiffness={k:e}"),
        format!("--wall-damping={b:e}"),
    );
    args.extend([ks.as_str(), bs.as_str()]);
    args.extend(extra);
    json(&args)
}

/// `check`'s verdict ("stable", "marginal", "unstable") at (K, B) with `extra` flags.
pub fn verdict(lp: &[&str], k: f64, b: f64, extra: &[&str]) -> String {
    check_json(lp, k, b, extra)["verdict"]
        .as_str()
        .unwrap()
        .to_string()
}

// ---------------------------------------------------------------------------------------
// Shared by the `loop_flags_*` tests.
// ---------------------------------------------------------------------------------------

/// The text a command prints (exit 0 required).
pub fn text(args: &[&str]) -> String {
    let out = hapstab().args(args).output().unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// A JSON number (present required).
pub fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// A JSON array of numbers.
pub fn floats(v: &Value) -> Vec<f64> {
    v.as_array().unwrap().iter().map(f).collect()
}

/// The wall of the `check` runs: K = 20 kN/m, B = 5 Ns/m.
pub const WALL: [&str; 4] = ["--wall-stiffness", "20000", "--wall-damping", "5"];

/// `check --json` at [`WALL`] with the loop flags `extra`.
pub fn check(extra: &[&str]) -> Value {
    json(&[&["check"][..], &WALL, extra].concat())
}

/// The spectral radius of a `check` answer.
pub fn radius(v: &Value) -> f64 {
    f(&v["spectral_radius"])
}

/// The commands of `hapstab --help`, in the order listed.
pub fn commands() -> Vec<String> {
    let help = stdout(&["--help"]);
    help.lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .map(String::from)
        .collect()
}
