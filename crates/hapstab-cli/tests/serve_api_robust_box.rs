//! The explorer's robust K_max over a box (`/api/region?…&box=NAME:LO:HI,…`) against the
//! command line: the same answer as `hapstab kmax --robust --box … --json` bit for bit (same
//! loop, box, damping, samples, verification and seed), the same text, in the exports; a bad
//! or too costly box is one line, HTTP 400, naming the parameter.

mod serve_support;

use serve_support::{Server, TWO_MASS_LOOP, enc, raw_number};

/// The paper's loop in physical units with the command line's default device and arm, d = 1.
const PAPER_LOOP: &str = "mode=physical&device_mass=0.1&device_damping=1.5&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001&d=1";

/// [`TWO_MASS_LOOP`]'s flags for `hapstab`.
const TWO_MASS_FLAGS: [&str; 22] = [
    "--motor-mass",
    "0.05",
    "--handle-mass",
    "0.05",
    "--transmission-stiffness",
    "5000",
    "--transmission-damping",
    "1",
    "--arm-mass",
    "1",
    "--arm-damping",
    "6",
    "--arm-stiffness",
    "350",
    "--period",
    "0.001",
    "--delay-time",
    "0.0014",
    "--velocity",
    "lowpass:150",
    "--force-lag",
    "0.0002",
];

/// `hapstab ARGS` (exit 0 required): its standard output.
fn hapstab_stdout(args: &[&str]) -> String {
    let out = assert_cmd::Command::cargo_bin("hapstab")
        .unwrap()
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// The explorer's answer for `loop_query` + `box_query` equals `hapstab kmax --robust` with
/// `flags`: the whole JSON object, the numbers' exact decimals, and the text's lines.
fn assert_same_as_the_command_line(s: &Server, loop_query: &str, box_query: &str, flags: &[&str]) {
    let r = s.get(&format!("/api/region?{loop_query}&{box_query}"));
    assert_eq!(r.status, 200, "{box_query}: {}", r.body);
    let api = r.json();
    let mut args = vec!["kmax", "--robust"];
    args.extend_from_slice(flags);
    let mut json_args = args.clone();
    json_args.push("--json");
    let cli_text = hapstab_stdout(&json_args);
    let cli: serde_json::Value = serde_json::from_str(&cli_text).unwrap();
    assert_eq!(api["robust_kmax"], cli, "{box_query}");
    let api_text = &r.body[r.body.find("\"robust_kmax\":").unwrap()..];
    for key in ["k_max", "k_min", "k_max_nominal"] {
        let (a, c) = (
            raw_number(api_text, "\"wall_damping\"", key),
            raw_number(&cli_text, "\"wall_damping\"", key),
        );
        assert_eq!(a.to_bits(), c.to_bits(), "{box_query}: {key}");
    }
    assert!(cli["k_max"].as_f64().is_some(), "a robust K_max: {cli}");
    // the same words: the command line's text ends with the explorer's lines
    let text = hapstab_stdout(&args);
    let lines: Vec<&str> = text.lines().collect();
    let api_lines: Vec<&str> = api["robust_kmax_text"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l.as_str().unwrap())
        .collect();
    assert_eq!(lines[lines.len() - api_lines.len()..], api_lines[..]);
    assert!(
        api_lines
            .iter()
            .any(|l| l.contains("random plants verified"))
    );
}

#[test]
fn the_explorer_robust_k_max_is_the_command_line_s() {
    let s = Server::start(&[]);
    assert_same_as_the_command_line(
        &s,
        PAPER_LOOP,
        &format!(
            "box={}&wall_damping=5",
            enc("arm-stiffness:0:2000,arm-mass:0.2:2")
        ),
        &[
            "--delay",
            "1",
            "--box",
            "arm-stiffness:0:2000",
            "--box",
            "arm-mass:0.2:2",
            "--wall-damping",
            "5",
        ],
    );
    let mut flags = TWO_MASS_FLAGS.to_vec();
    flags.extend([
        "--box",
        "transmission-stiffness:3000:8000",
        "--box",
        "cutoff:100:200",
        "--wall-damping",
        "2",
        "--samples",
        "64",
        "--verify",
        "2000",
        "--seed",
        "7",
    ]);
    assert_same_as_the_command_line(
        &s,
        TWO_MASS_LOOP,
        &format!(
            "box={}&wall_damping=2&samples=64&verify=2000&seed=7",
            enc("transmission-stiffness:3000:8000,cutoff:100:200")
        ),
        &flags,
    );
}

/// A refusal: HTTP 400, one line naming `param`.
fn assert_refused(s: &Server, query: &str, param: &str, words: &str) {
    let r = s.get(&format!("/api/region?{query}"));
    assert_eq!(r.status, 400, "{query}: {}", r.body);
    let j = r.json();
    let msg = j["error"].as_str().unwrap();
    assert!(!msg.contains('\n'), "one line: {msg}");
    assert_eq!(j["parameter"], param, "{query}: {msg}");
    assert!(msg.contains(param), "names the parameter: {msg}");
    assert!(msg.contains(words), "{query}: {msg}");
}

#[test]
fn a_bad_or_too_costly_box_is_refused_in_one_line() {
    let s = Server::start(&[]);
    let q = |tail: &str| format!("{PAPER_LOOP}&{tail}");
    assert_refused(
        &s,
        &q(&format!("box={}", enc("arm-stifness:0:2000"))),
        "box",
        "arm-stifness",
    );
    assert_refused(
        &s,
        &q(&format!("box={}", enc("arm-stiffness:2000:0"))),
        "box",
        "LO must not exceed HI",
    );
    assert_refused(
        &s,
        &q(&format!("box={}", enc("arm-stiffness:0:x"))),
        "box",
        "not a finite number",
    );
    assert_refused(
        &s,
        &q(&format!("box={}", enc("cutoff:10:100"))),
        "box",
        "low-pass",
    );
    // too costly: the verification, or a box whose delay makes p(z) long
    assert_refused(
        &s,
        &q(&format!(
            "box={}&verify=1000000",
            enc("arm-stiffness:0:2000")
        )),
        "verify",
        "limit",
    );
    assert_refused(
        &s,
        &q(&format!("box={}", enc("delay-time:0:0.2"))),
        "box",
        "limit",
    );
    assert_refused(&s, &q("wall_damping=5"), "wall_damping", "needs box");
    assert_refused(
        &s,
        &format!(
            "gamma=0.001&delta=0.015&d=1&box={}",
            enc("arm-stiffness:0:1")
        ),
        "box",
        "mode=physical",
    );
}

#[test]
fn the_exports_carry_the_robust_k_max() {
    let s = Server::start(&[]);
    let q = format!(
        "{PAPER_LOOP}&box={}&wall_damping=5&verify=1000",
        enc("arm-stiffness:0:2000")
    );
    let j = s.get(&format!("/api/region?{q}")).json();
    let (k_min, k_max) = (
        j["robust_kmax"]["k_min"].as_f64().unwrap(),
        j["robust_kmax"]["k_max"].as_f64().unwrap(),
    );
    let csv = s.get(&format!("/api/export?{q}&format=csv")).body;
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .filter(|l| l.starts_with("robust_kmax,"))
        .map(|l| l.split(',').skip(3).map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 2, "{csv}");
    // K and B in N/m and Ns/m (through the page's α, β), the damping the one asked for
    for (row, k) in rows.iter().zip([k_min, k_max]) {
        assert!(
            (row[2] - k).abs() <= 1e-9 * k.abs().max(1.0),
            "{row:?} vs {k}"
        );
        assert!((row[3] - 5.0).abs() <= 1e-9, "{row:?}");
    }
    let svg = s.get(&format!("/api/export?{q}&format=svg")).body;
    assert!(svg.contains("class=\"robust-kmax\""), "{svg}");
    assert!(svg.contains("robust K_max = "), "legend");
    let limits = s.get("/api/limits").json();
    let names = limits["robust_box_params"].as_array().unwrap();
    assert!(
        names
            .iter()
            .any(|p| p["name"] == "arm-stiffness" && p["unit"] == "N/m")
    );
}
