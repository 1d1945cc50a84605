//! Helpers shared by the command-line tests: run `hapstab`, read its JSON.
#![allow(dead_code)]

use assert_cmd::Command;
use serde_json::Value;

/// The `hapstab` binary of this build.
pub fn hapstab() -> Command {
    Command::cargo_bin("hapstab").unwrap()
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
