//! The command line's output conventions, across every command: JSON that a strict parser
//! accepts (no repeated key, no -0) with the inputs under `input` and each command's documented
//! keys; human text in 6 significant digits with "—" for undefined values; CSV in shortest
//! round-trip floats; help text without development notes, in one default style; and every
//! shell example of the README run as written.

mod common;

use common::hapstab;
use std::collections::BTreeMap;
use std::fmt;
use std::path::Path;

use serde::de::{self, Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_json::Value;

/// Runs the binary in `dir`, asserting success, and returns its standard output.
fn stdout_in(dir: &Path, args: &[&str]) -> String {
    let out = hapstab().current_dir(dir).args(args).output().unwrap();
    assert!(
        out.status.success(),
        "hapstab {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn stdout(args: &[&str]) -> String {
    stdout_in(&std::env::temp_dir(), args)
}

/// A JSON value parsed by a parser that rejects a key repeated within one object (serde_json
/// alone keeps the last one silently).
struct Strict(Value);

impl<'de> Deserialize<'de> for Strict {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(StrictVisitor).map(Strict)
    }
}

struct StrictVisitor;

impl<'de> Visitor<'de> for StrictVisitor {
    type Value = Value;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a JSON value")
    }
    fn visit_bool<E>(self, v: bool) -> Result<Value, E> {
        Ok(Value::Bool(v))
    }
    fn visit_i64<E>(self, v: i64) -> Result<Value, E> {
        Ok(v.into())
    }
    fn visit_u64<E>(self, v: u64) -> Result<Value, E> {
        Ok(v.into())
    }
    fn visit_f64<E>(self, v: f64) -> Result<Value, E> {
        Ok(v.into())
    }
    fn visit_str<E>(self, v: &str) -> Result<Value, E> {
        Ok(Value::String(v.to_owned()))
    }
    fn visit_string<E>(self, v: String) -> Result<Value, E> {
        Ok(Value::String(v))
    }
    fn visit_unit<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }
    fn visit_none<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let mut v = Vec::new();
        while let Some(Strict(x)) = seq.next_element()? {
            v.push(x);
        }
        Ok(Value::Array(v))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let mut m = serde_json::Map::new();
        while let Some(k) = map.next_key::<String>()? {
            let Strict(v) = map.next_value()?;
            if m.insert(k.clone(), v).is_some() {
                return Err(de::Error::custom(format!("duplicate key '{k}'")));
            }
        }
        Ok(Value::Object(m))
    }
}

fn strict(text: &str) -> Result<Value, serde_json::Error> {
    serde_json::from_str::<Strict>(text).map(|s| s.0)
}

#[test]
fn the_strict_parser_rejects_a_repeated_key() {
    assert!(strict(r#"{"a": 1, "b": {"c": 2, "c": 3}}"#).is_err());
    assert!(strict(r#"{"a": 1, "b": {"c": 2}, "c": [1, {"a": 2}]}"#).is_ok());
}

/// The commands of `hapstab --help`, in the order listed.
fn commands() -> Vec<String> {
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

/// Commands without a `--json` and why.
const NO_JSON: &[(&str, &str)] = &[(
    "serve",
    "a long-running server; its JSON API has its own tests (serve_api)",
)];

/// Small, fast runs of every command with `--json`, and the top-level keys that each must
/// print (README, "JSON output"). `{dir}` is a temporary folder.
fn json_cases() -> Vec<JsonCase> {
    [
        verdict_cases(),
        region_cases(),
        more_cases(),
        identify_cases(),
    ]
    .concat()
}

/// `identify` on a recording of the independent simulator (benches/baseline/identify_data.py).
fn identify_cases() -> Vec<JsonCase> {
    vec![(
        "identify",
        vec![
            "identify",
            "--data",
            concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../hapstab/tests/fixtures/identify/msd_chirp_40db.csv"
            ),
            "--draws",
            "20",
        ],
        vec![
            "model",
            "source",
            "parameters",
            "fit",
            "whiteness",
            "stiffness_limit",
            "loop",
        ],
    )]
}

/// A command, its arguments and the top-level keys its `--json` must print.
type JsonCase = (&'static str, Vec<&'static str>, Vec<&'static str>);

/// The verdicts and stiffness limits of [`json_cases`]: check, kmax and population.
fn verdict_cases() -> Vec<JsonCase> {
    let results_of_check = vec![
        "stable",
        "verdict",
        "spectral_radius",
        "roots",
        "gain_margin",
        "margin_notes",
    ];
    vec![
        (
            "check",
            vec!["check"],
            [results_of_check.clone(), vec!["k_interval", "normalized"]].concat(),
        ),
        (
            "check",
            vec![
                "check", "--alpha", "0.1", "--beta", "0.5", "--gamma", "0.001",
            ],
            [results_of_check, vec!["alpha_interval", "alpha_linear"]].concat(),
        ),
        (
            "kmax",
            vec!["kmax", "--no-arm"],
            vec!["k_max", "b_at_k_max", "k_linear", "normalized"],
        ),
        (
            "kmax",
            vec!["kmax", "--no-arm", "--wall-damping", "10"],
            vec!["k_max", "k_interval", "k_linear", "normalized"],
        ),
        (
            "kmax",
            vec!["kmax", "--robust", "--box-samples", "3"],
            vec![
                "k_max",
                "b_at_k_max",
                "k_min",
                "worst_plant",
                "k_linear_worst",
            ],
        ),
        (
            "population",
            vec!["population", "--samples", "200"],
            vec!["samples", "k", "probability", "levels", "param_names"],
        ),
    ]
}

/// The regions and their sections of [`json_cases`]: boundary, map, linear, nyquist.
fn region_cases() -> Vec<JsonCase> {
    vec![
        (
            "boundary",
            vec!["boundary", "--gamma", "0.001", "--delta", "0.015"],
            vec![
                "alpha_max",
                "beta_at_alpha_max",
                "area",
                "polygons",
                "edges",
            ],
        ),
        (
            "boundary",
            vec!["boundary", "--no-arm"],
            vec![
                "k_max",
                "b_at_k_max",
                "area",
                "polygons",
                "edges",
                "wall_units",
                "normalized",
            ],
        ),
        (
            "map",
            vec!["map", "--x", "alpha:0:1:4", "--y", "beta:0:1:3"],
            vec!["points", "stable_points", "seconds"],
        ),
        (
            "map",
            vec!["map", "--x", "K:0:1000:4", "--y", "B:0:10:3"],
            vec!["points", "stable_points", "seconds"],
        ),
        (
            "linear",
            vec!["linear", "--mass", "1", "--damping", "1"],
            vec![
                "normalized",
                "linear_slope",
                "linear_intercept",
                "alpha_lower",
                "points",
            ],
        ),
        (
            "nyquist",
            vec![
                "nyquist",
                "--delta",
                "0",
                "--steps",
                "2",
                "--beta-samples",
                "16",
                "--gamma-samples",
                "3",
            ],
            vec!["gamma_nyquist", "sweep", "robust"],
        ),
        (
            "nyquist",
            vec!["nyquist", "--device-mass", "0.1", "--no-arm"],
            vec![
                "stiffness",
                "delta",
                "gamma_nyquist",
                "nyquist_frequency_hz",
            ],
        ),
    ]
}

/// The rest of [`json_cases`]: passivity to the paper.
fn more_cases() -> Vec<JsonCase> {
    vec![
        (
            "passivity",
            vec!["passivity", "--no-arm"],
            vec!["b_required", "verdict", "stable", "passive_region"],
        ),
        (
            "zwidth",
            vec!["zwidth", "--no-arm", "--table-damping", "0,10"],
            vec!["loops"],
        ),
        (
            "sweep",
            vec!["sweep", "--param", "delay-time:0:0.002:3", "--no-arm"],
            vec!["unit", "points", "seconds"],
        ),
        (
            "ranges",
            vec!["ranges"],
            vec!["limits", "gamma_max", "delta_max"],
        ),
        (
            "discretize",
            vec!["discretize"],
            vec!["plant", "velocity", "characteristic"],
        ),
        (
            "simulate",
            vec!["simulate", "--duration", "0.1"],
            vec![
                "outcome",
                "reason",
                "spectral_radius",
                "samples",
                "duration",
            ],
        ),
        (
            "simboundary",
            vec![
                "simboundary",
                "--no-arm",
                "--beta-count",
                "2",
                "--grid",
                "4",
                "--duration-samples",
                "2000",
                "--rel-tol",
                "1e-2",
            ],
            vec!["exact_alpha_max", "points", "warnings"],
        ),
        (
            "bode",
            vec!["bode"],
            vec![
                "stable",
                "gain_margin",
                "phase_margin_deg",
                "closest",
                "curve",
            ],
        ),
        (
            "nyquist-plot",
            vec!["nyquist-plot"],
            vec!["stable", "gain_crossover_hz", "closest", "curve"],
        ),
        (
            "locus",
            vec!["locus"],
            vec!["k_max", "crossing", "stiffness", "roots"],
        ),
        (
            "paper",
            vec!["paper", "--out", "{dir}/paper"],
            vec!["files", "claims", "seconds"],
        ),
    ]
}

/// True when the JSON text holds the number -0 ("-0.0" or "-0"), not e.g. -0.05.
fn has_negative_zero(text: &str) -> bool {
    text.match_indices("-0").any(|(i, _)| {
        let rest = text[i + 2..].trim_start_matches(['.', '0']);
        let zeros = &text[i + 2..text.len() - rest.len()];
        !zeros.contains(|c: char| c.is_ascii_digit() && c != '0')
            && !rest.starts_with(|c: char| c.is_ascii_digit())
            && !rest.starts_with(['e', 'E'])
    })
}

#[test]
fn negative_zero_is_told_from_small_numbers() {
    assert!(has_negative_zero("[-0.0, 1]"));
    assert!(has_negative_zero("{\"a\": -0}"));
    assert!(!has_negative_zero("[-0.05, -0.0001, -0.5e-3, 0.0]"));
}

/// Every key of every object of a JSON value, with its path.
fn keys(v: &Value, path: &str, out: &mut Vec<String>) {
    match v {
        Value::Object(m) => {
            for (k, x) in m {
                out.push(format!("{path}.{k}"));
                keys(x, &format!("{path}.{k}"), out);
            }
        }
        Value::Array(a) => a.iter().for_each(|x| keys(x, path, out)),
        _ => {}
    }
}

/// Every command of `hapstab --help` prints one JSON object with `--json` that a
/// duplicate-rejecting parser accepts, with its inputs under `input`, no -0 and no redundant
/// copy of a result under another name, and its documented keys at the top level.
#[test]
fn every_command_prints_schema_conformant_json() {
    let dir = tempfile::tempdir().unwrap();
    let cases = json_cases();
    let listed = commands();
    assert!(listed.len() >= 15, "{listed:?}");
    for c in &listed {
        let exempt = NO_JSON.iter().any(|(n, _)| n == c);
        let covered = cases.iter().any(|(n, _, _)| n == c);
        assert!(
            exempt != covered,
            "{c}: every command needs a JSON case here (or an exemption with its reason)"
        );
    }
    std::thread::scope(|s| {
        for (name, args, want) in &cases {
            let dir = dir.path();
            s.spawn(move || {
                let args: Vec<String> = args
                    .iter()
                    .map(|a| a.replace("{dir}", dir.to_str().unwrap()))
                    .collect();
                let mut argv: Vec<&str> = args.iter().map(String::as_str).collect();
                argv.push("--json");
                let text = stdout_in(dir, &argv);
                let v = strict(&text).unwrap_or_else(|e| panic!("{argv:?}: {e}\n{text}"));
                assert!(v["input"].is_object(), "{argv:?}: no input object");
                assert!(!has_negative_zero(&text), "{argv:?}: negative zero");
                for k in want {
                    assert!(v.get(k).is_some(), "{name}: no top-level '{k}' in {argv:?}");
                }
                // an input is not repeated among the results
                for (k, x) in v["input"].as_object().unwrap() {
                    assert!(
                        x.is_object() || v.get(k).is_none(),
                        "{argv:?}: input '{k}' repeated at the top level"
                    );
                }
                let mut all = Vec::new();
                keys(&v, "", &mut all);
                for redundant in ["stiffness_max", "damping_at_max", "stiffness_min"] {
                    assert!(
                        !all.iter().any(|k| k.ends_with(&format!(".{redundant}"))),
                        "{argv:?}: redundant '{redundant}'"
                    );
                }
            });
        }
    });
}

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
