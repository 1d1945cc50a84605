//! The command line's human-facing output: text and CSV of `boundary` and `nyquist`, the
//! robust box's report, help text without development notes in one default style, every
//! shell example of the README run as written, `simulate`'s JSON beside its wall, and six
//! significant digits in human text.

use crate::common;

use common::strict::strict;
use common::{commands, hapstab, stdout};
use std::collections::BTreeMap;
use std::path::Path;

use serde_json::Value;

/// `kmax --robust --json` names the limiting plant once, as an object in SI units; the box
/// given as 0.2,1.2 or 0.2:1.2 is the one echoed, and its K_max lies below the K_max of its
/// lightest plant alone (a robust bound is at most the bound of any member).
#[test]
fn robust_kmax_box_flags_and_worst_plant() {
    let robust = |mass: &str| {
        let text = stdout(&[
            "kmax",
            "--robust",
            "--box-mass",
            mass,
            "--box-samples",
            "3",
            "--json",
        ]);
        strict(&text).unwrap()
    };
    let (a, b) = (robust("0.2,1.2"), robust("0.2:1.2"));
    assert_eq!(a, b);
    let m: Vec<f64> = serde_json::from_value(a["input"]["box"]["mass"].clone()).unwrap();
    assert_eq!(m, [0.2, 1.2]);
    let w = &a["worst_plant"];
    assert!(w["mass"].is_number() && w["damping"].is_number() && w["stiffness"].is_number());
    let light = strict(&stdout(&[
        "kmax",
        "--mass",
        "0.2",
        "--damping",
        "1.5",
        "--stiffness",
        "0",
        "--json",
    ]))
    .unwrap();
    let k = |v: &Value| v["k_max"].as_f64().unwrap();
    assert!(
        k(&a) <= k(&light) * (1.0 + 1e-9),
        "{} > {}",
        k(&a),
        k(&light)
    );
    // one value per flag: a third number or a missing one is one clear line naming the flag
    for bad in ["0.2", "0.2,1.2,3", "a,b"] {
        let out = hapstab()
            .args(["kmax", "--robust", "--box-mass", bad])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2));
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains("--box-mass") && err.lines().count() == 1,
            "{err}"
        );
    }
}

/// The pure mass (γ = δ = d = 0) has α_max = 2β(2 − β)/(2 + β) at β = 2√2 − 2 (Section V):
/// the text prints both in 6 significant digits, polygon numbers match the CSV's, and the CSV
/// holds the JSON's vertices exactly, in shortest round-trip text (never "0e0").
#[test]
fn boundary_text_and_csv() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("r.csv");
    let csv_arg = csv.to_str().unwrap();
    let args = ["boundary", "--gamma", "0", "--delta", "0", "--csv", csv_arg];
    let text = stdout(&args);
    let beta = 2.0 * 2f64.sqrt() - 2.0;
    let alpha = 2.0 * beta * (2.0 - beta) / (2.0 + beta);
    let line = text.lines().find(|l| l.starts_with("α_max = ")).unwrap();
    let words: Vec<&str> = line.split_whitespace().collect();
    let (a_txt, b_txt) = (words[2], words[6]);
    for (t, want) in [(a_txt, alpha), (b_txt, beta)] {
        let significant = t.trim_start_matches(['-', '0', '.']);
        assert!(
            significant.chars().filter(char::is_ascii_digit).count() <= 6,
            "{line}"
        );
        let got: f64 = t.parse().unwrap();
        assert!((got - want).abs() <= 5e-6 * want, "{line}: {want}");
    }
    let numbered: Vec<usize> = text
        .lines()
        .filter_map(|l| l.strip_prefix("polygon "))
        .map(|l| l.split_whitespace().next().unwrap().parse().unwrap())
        .collect();
    let body = std::fs::read_to_string(&csv).unwrap();
    let mut rows = csv::Reader::from_reader(body.as_bytes());
    let mut in_csv = Vec::new();
    let json = strict(&stdout(&[&args[..], &["--json"]].concat())).unwrap();
    for r in rows.records() {
        let r = r.unwrap();
        let (p, v): (usize, usize) = (r[0].parse().unwrap(), r[1].parse().unwrap());
        if !in_csv.contains(&p) {
            in_csv.push(p);
        }
        for (col, i) in [(2, 0), (3, 1)] {
            assert!(!r[col].ends_with("e0") && &r[col] != "-0", "{:?}", r);
            // serde_json's parser (without its float_roundtrip feature) may miss the
            // nearest double by one unit in the last place; Rust's own parse does not
            let want = json["polygons"][p][v][i].as_f64().unwrap();
            let got: f64 = r[col].parse().unwrap();
            assert!(
                (got - want).abs() <= f64::EPSILON * want.abs(),
                "{r:?}: {want}"
            );
        }
    }
    assert_eq!(numbered, in_csv, "text and CSV number the polygons alike");
    assert!(!body.contains("e0,") && !body.contains("e0\n"), "{body}");
}

/// At δ = 0 the sweep of `nyquist` meets γ = π²/4·… where every stable point has α ≤ 0
/// (α_max at round-off) and γ = π² where every p(z) has a root at z = −1 (undefined α_max):
/// the table prints "—" and 0 there, never NaN or a round-off number.
#[test]
fn nyquist_table_has_no_nan_or_roundoff() {
    let text = stdout(&["nyquist", "--delta", "0"]);
    assert!(!text.contains("NaN"), "{text}");
    // the table's numbers: "—", 0, or far above round-off
    let rows: Vec<&str> = text
        .lines()
        .skip_while(|l| !l.contains("γ/γ_N"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .collect();
    assert_eq!(rows.len(), 5, "{text}");
    for row in &rows {
        for cell in row.split_whitespace().take(5) {
            if cell != "—" {
                let x: f64 = cell.parse().unwrap_or_else(|_| panic!("{row}"));
                assert!(x == 0.0 || x.abs() > 1e-9, "{row}");
            }
        }
    }
    let degenerate = text.lines().find(|l| l.contains("limit stable")).unwrap();
    assert!(degenerate.contains('—'), "{degenerate}");
    let flat = text.lines().find(|l| l.contains("α ≤ 0")).unwrap();
    let cells: Vec<&str> = flat.split_whitespace().collect();
    assert_eq!(cells[2], "0", "{flat}");
}

/// Remark 4 through the plant flags every command takes: k = π² m/T² + b²/(4m).
#[test]
fn nyquist_takes_the_plant_flags() {
    let v = strict(&stdout(&[
        "nyquist",
        "--device-mass",
        "0.1",
        "--device-damping",
        "1.5",
        "--no-arm",
        "--period",
        "0.001",
        "--json",
    ]))
    .unwrap();
    let want = std::f64::consts::PI.powi(2) * 0.1 / 1e-6 + 1.5 * 1.5 / 0.4;
    let got = v["stiffness"].as_f64().unwrap();
    assert!((got - want).abs() <= 1e-12 * want, "{got} vs {want}");
    assert_eq!(v["input"]["mass"], 0.1);
}

/// Help: what hapstab is, commands in the order of use, clap's "[default: X]" style only,
/// no development notes; a mistyped command gets a suggestion.
#[test]
fn help_is_consistent() {
    let top = stdout(&["--help"]);
    assert!(
        top.lines()
            .next()
            .unwrap()
            .contains("stability of haptic virtual walls")
    );
    assert!(!top.contains("front end"));
    let order = commands();
    assert_eq!(&order[..4], ["check", "kmax", "boundary", "map"]);
    assert!(order.iter().position(|c| c == "serve") == Some(order.len() - 1));
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../README.md"))
            .unwrap();
    let mut texts = vec![("README.md".to_string(), readme), ("--help".into(), top)];
    for c in &order {
        texts.push((c.clone(), stdout(&[c, "--help"])));
    }
    for (what, t) in &texts {
        for bad in [
            "(issue",
            "issue 1",
            "issue 5",
            "issue 6",
            "issue 7",
            "[default ",
        ] {
            assert!(!t.contains(bad), "{what}: contains '{bad}'");
        }
    }
    let out = hapstab().arg("chek").output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("'check'") && err.lines().count() == 1, "{err}");
}

/// The `hapstab …` and `cargo run --release -- …` lines of the README's sh blocks.
fn readme_examples() -> Vec<Vec<String>> {
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../README.md"))
            .unwrap();
    let mut out = Vec::new();
    let mut in_sh = false;
    for line in readme.lines() {
        if line.starts_with("```") {
            in_sh = line.trim() == "```sh";
            continue;
        }
        if !in_sh {
            continue;
        }
        let cmd = line.split(" #").next().unwrap().trim();
        let rest = cmd
            .strip_prefix("hapstab ")
            .or_else(|| cmd.strip_prefix("cargo run --release -- "));
        if let Some(rest) = rest {
            out.push(rest.split_whitespace().map(String::from).collect());
        }
    }
    out
}

/// Every shell example of the README runs as written and exits 0 (in a temporary folder);
/// only `serve`, which runs until stopped, is left out (the `cargo test` line is no hapstab
/// command).
#[test]
fn readme_examples_run() {
    let examples = readme_examples();
    assert!(examples.len() >= 15, "{examples:?}");
    let dir = tempfile::tempdir().unwrap();
    let results: BTreeMap<String, Result<(), String>> = std::thread::scope(|s| {
        let handles: Vec<_> = examples
            .iter()
            .filter(|e| e[0] != "serve")
            .map(|e| {
                let dir = dir.path();
                s.spawn(move || {
                    let out = hapstab().current_dir(dir).args(e).output().unwrap();
                    let r = if out.status.success() {
                        Ok(())
                    } else {
                        Err(String::from_utf8_lossy(&out.stderr).into_owned())
                    };
                    (e.join(" "), r)
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let failed: Vec<_> = results.iter().filter(|(_, r)| r.is_err()).collect();
    assert!(failed.is_empty(), "{failed:#?}");
    assert!(
        results.keys().any(|k| k == "check"),
        "the two-command example"
    );
}

/// `simulate --json` carries the wall it ran: K and B in N/m and Ns/m (α and β normalized)
/// under `input`, with the run's setting beside the loop.
#[test]
fn simulate_json_carries_the_wall() {
    let v = strict(&stdout(&[
        "simulate",
        "--wall-stiffness",
        "30000",
        "--wall-damping",
        "7.5",
        "--duration",
        "0.05",
        "--json",
    ]))
    .unwrap();
    assert_eq!(v["input"]["wall"]["stiffness"], 30000.0);
    assert_eq!(v["input"]["wall"]["damping"], 7.5);
    assert!(v["input"]["effects"].is_object() && v["input"]["initial"].is_object());
    let v = strict(&stdout(&[
        "simulate",
        "--alpha",
        "0.2",
        "--beta",
        "0.5",
        "--gamma",
        "0.001",
        "--duration-samples",
        "500",
        "--json",
    ]))
    .unwrap();
    assert_eq!(v["input"]["alpha"], 0.2);
    assert_eq!(v["input"]["beta"], 0.5);
    assert!(
        v.get("normalized").is_none(),
        "the input is the normalized point"
    );
}

/// The significant digits of a decimal number written with a point or an exponent (counts
/// and sample numbers, written without either, are not measurements).
fn significant_digits(token: &str) -> Option<usize> {
    let t = token.trim_start_matches(['-', '+', '−', '(', '[', '×', '±']);
    let t = t.trim_end_matches([',', ')', ']', ';', ':', '%']);
    let mantissa = t.split(['e', 'E']).next()?;
    let is_number = !mantissa.is_empty()
        && mantissa.chars().all(|c| c.is_ascii_digit() || c == '.')
        && mantissa.chars().any(|c| c.is_ascii_digit())
        && t.parse::<f64>().is_ok();
    if !is_number || !(t.contains('.') || t.contains(['e', 'E'])) {
        return None;
    }
    let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
    Some(digits.trim_start_matches('0').len())
}

/// Human output of every analysis command shows at most 6 significant digits per number
/// (engineering notation), "—" rather than NaN, and no number in raw exponent form longer
/// than that.
#[test]
fn human_output_has_six_significant_digits() {
    assert_eq!(significant_digits("1.477436755520836e-1"), Some(16));
    assert_eq!(significant_digits("0.000318182,"), Some(6));
    assert_eq!(significant_digits("2003"), None);
    let runs: &[&[&str]] = &[
        &["check"],
        &[
            "check", "--alpha", "0.1", "--beta", "0.5", "--gamma", "0.001", "--delay", "2",
        ],
        &["kmax"],
        &["kmax", "--wall-damping", "10"],
        &["kmax", "--robust", "--box-samples", "3"],
        &["boundary"],
        &[
            "boundary", "--gamma", "0.001", "--delta", "0.015", "--delay", "1",
        ],
        &["linear", "--mass", "1", "--damping", "1"],
        &[
            "nyquist",
            "--delta",
            "0.5",
            "--steps",
            "2",
            "--beta-samples",
            "16",
        ],
        &["nyquist", "--device-mass", "0.1", "--no-arm"],
        &["passivity"],
        &["zwidth", "--no-arm", "--table-damping", "0,10"],
        &["sweep", "--param", "delay-time:0:0.002:3", "--no-arm"],
        &["ranges"],
        &["discretize"],
        &["simulate", "--duration", "0.1"],
    ];
    std::thread::scope(|s| {
        for args in runs {
            s.spawn(move || {
                let text = stdout(args);
                assert!(!text.contains("NaN"), "{args:?}:\n{text}");
                for tok in text.split_whitespace() {
                    if let Some(n) = significant_digits(tok) {
                        assert!(n <= 6, "{args:?}: '{tok}' has {n} digits:\n{text}");
                    }
                }
            });
        }
    });
}
