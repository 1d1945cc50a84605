//! The command line's JSON, across every command: what a strict parser accepts (no repeated
//! key, no -0), with the inputs under `input` and each command's documented keys (the human
//! text, CSV, help and README examples: `human_output.rs`).

use crate::common;

use common::strict::strict;
use common::{commands, stdout_in};

use serde_json::Value;

#[test]
fn the_strict_parser_rejects_a_repeated_key() {
    assert!(strict(r#"{"a": 1, "b": {"c": 2, "c": 3}}"#).is_err());
    assert!(strict(r#"{"a": 1, "b": {"c": 2}, "c": [1, {"a": 2}]}"#).is_ok());
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
            vec!["exact_k_max", "exact_b_at_k_max", "points", "warnings"],
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
