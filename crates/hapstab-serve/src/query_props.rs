//! Property test of the API's query parsing, in process: random query strings over the real
//! parameter names of each endpoint (and unknown ones), with values at and beyond every edge
//! and malformed percent-encoding, go through the same path as a request (axum's `Query`
//! extraction, [`crate::params`], the endpoint's parser and its cost check). Whatever the
//! query: no panic, an answer within a time bound, every refusal a 4xx with a one-line
//! message naming its parameter, and every accepted request within one request's budget.
//!
//! A longer run: `HAPSTAB_FUZZ_CASES=1000000 cargo test -p hapstab-serve --lib query_props --
//! --nocapture`.

use std::time::{Duration, Instant};

use axum::extract::Query;
use axum::http::Uri;
use hapstab::limits::Budget;
use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};

use crate::query::{ApiError, plant_spec};
use crate::{api, export, params};

/// Cases run by default (CI): parsing is cheap, about 20 µs a case.
const CI_CASES: u32 = 20_000;
/// Longest one parse may take: a parse takes microseconds, so this only catches a
/// pathological one, with room for a machine busy with other work.
const TIME_BOUND: Duration = Duration::from_secs(1);
/// Values: ordinary, at and beyond the edges, words of the choices, and junk (some with
/// broken percent-encoding, kept as they are).
const VALUES: &[&str] = &[
    "0",
    "1",
    "2",
    "0.5",
    "0.001",
    "0.015",
    "-1",
    "-0",
    "1e-7",
    "1e-8",
    "1",
    "1e4",
    "1e9",
    "1e308",
    "-1e308",
    "1e-320",
    "1e400",
    "NaN",
    "inf",
    "-inf",
    "+inf",
    "infinity",
    "200",
    "201",
    "50",
    "51",
    "64",
    "65",
    "256",
    "100000",
    "18446744073709551616",
    "1.5",
    "",
    " ",
    "abc",
    "normalized",
    "physical",
    "hybrid",
    "true",
    "yes",
    "off",
    "svg",
    "csv",
    "json",
    "pdf",
    "bilateral",
    "unilateral_no_pull",
    "0,1,0,1",
    "1,0,0,1",
    "nan,1,0,1",
    "%ZZ",
    "%00",
    "%",
    "%E9",
    "a%20b",
    "é",
    "=",
    "&",
    "0.002",
    "0.0015",
];
/// A valid plant and point.
const BASE: &[(&str, &str)] = &[
    ("gamma", "0.001"),
    ("delta", "0.015"),
    ("d", "1"),
    ("alpha", "0.05"),
    ("beta", "0.3"),
];
/// Names no endpoint knows.
const UNKNOWN: &[&str] = &["gama", "", "GAMMA", "gamma ", "x"];

/// Percent-encodes a value, leaving '%' alone so that broken encodings stay broken.
fn encode(s: &str) -> String {
    s.bytes()
        .map(|b| match b {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'-' | b'.' | b'_' | b'~' | b'%' => {
                (b as char).to_string()
            }
            _ => format!("%{b:02X}"),
        })
        .collect()
}

/// The endpoints and their parameter names.
fn endpoints() -> Vec<(&'static str, Vec<&'static str>)> {
    vec![
        ("region", api::region_names()),
        ("point", api::point_names()),
        ("simulate", api::simulate_names()),
        ("export", export::export_names()),
    ]
}

/// Parses one query the way the handler of `endpoint` does, including its cost check.
fn parse(endpoint: &str, allowed: &[&str], uri: &Uri) -> Result<(), ApiError> {
    let p = params(Query::try_from_uri(uri), allowed)?;
    match endpoint {
        "region" => {
            let r = api::parse_region(&p)?;
            let mut cost = api::nominal_region_cost(r.spec.cost_d());
            if let Some(rr) = r.robust {
                cost = cost.then(api::robust_cost(
                    r.spec.cost_d(),
                    rr.gamma_samples,
                    rr.beta_samples,
                    rr.refine,
                ));
            }
            assert!(Budget::INTERACTIVE.check(cost).is_ok(), "{uri}: {cost:?}");
        }
        "point" => {
            let spec = plant_spec(&p)?;
            api::wall_point(&p, &spec)?;
            api::point_budget(&spec)?;
        }
        "simulate" => {
            api::parse_simulate(&p)?;
        }
        _ => {
            export::parse_export(&p)?;
        }
    }
    Ok(())
}

fn cases() -> u32 {
    std::env::var("HAPSTAB_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(CI_CASES)
}

#[test]
fn random_queries_are_parsed_or_refused_with_a_4xx_naming_the_parameter() {
    let eps = endpoints();
    let mut runner = TestRunner::new(Config {
        cases: cases(),
        failure_persistence: None,
        ..Config::default()
    });
    // (endpoint, [(name or unknown, value)], with a leading "mode" pair)
    let strategy = (
        0..eps.len(),
        any::<bool>(),
        prop::collection::vec(
            (any::<prop::sample::Index>(), 0..VALUES.len(), 0..20u8),
            0..8,
        ),
    );
    let accepted = std::cell::Cell::new(0usize);
    let t0 = Instant::now();
    let result = runner.run(&strategy, |(e, base, pairs)| {
        let (endpoint, names) = &eps[e];
        // half the queries start from a valid plant and point, so that the random pairs
        // also reach the checks after the plant's
        let mut query: Vec<String> = if base {
            BASE.iter()
                .filter(|(n, _)| names.contains(n))
                .map(|(n, v)| format!("{n}={v}"))
                .collect()
        } else {
            Vec::new()
        };
        query.extend(pairs.iter().map(|(name, value, unknown)| {
            let n = if *unknown == 0 {
                name.get(UNKNOWN)
            } else {
                name.get(names)
            };
            format!("{}={}", encode(n), encode(VALUES[*value]))
        }));
        let text = format!("/api/{endpoint}?{}", query.join("&"));
        let Ok(uri) = text.parse::<Uri>() else {
            return Ok(()); // not a URI at all: refused by the HTTP layer before this
        };
        let t = Instant::now();
        let r = parse(endpoint, names, &uri);
        prop_assert!(t.elapsed() < TIME_BOUND, "{text}: {:?}", t.elapsed());
        match r {
            Ok(()) => accepted.set(accepted.get() + 1),
            Err(err) => {
                prop_assert!(err.status.is_client_error(), "{text}: {err:?}");
                prop_assert!(!err.message.is_empty() && !err.message.contains('\n'));
                if let Some(name) = err.parameter.as_deref().filter(|n| n.len() <= 40) {
                    prop_assert!(err.message.contains(name), "{text}: {err:?}");
                }
            }
        }
        Ok(())
    });
    println!(
        "{} queries in {:.1} s, {} accepted",
        cases(),
        t0.elapsed().as_secs_f64(),
        accepted.get()
    );
    if let Err(e) = result {
        panic!("{e}");
    }
}
