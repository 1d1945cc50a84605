//! The explorer's robust K_max over a box (`/api/region?…&box=NAME:LO:HI,…`): in the exports,
//! and a bad or too costly box is one line, HTTP 400, naming the parameter (the answer is
//! compared with `hapstab kmax --robust --box … --json` in hapstab-cli's `serve_parity`).

use crate::serve_support;

use serve_support::{PAPER_LOOP, Server, enc};

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
    assert_eq!(
        csv.lines().next(),
        Some("layer,polygon,vertex,K_N_per_m,B_Ns_per_m")
    );
    // K and B in N/m and Ns/m (through the page's α, β), the damping the one asked for
    for (row, k) in rows.iter().zip([k_min, k_max]) {
        assert!(
            (row[0] - k).abs() <= 1e-9 * k.abs().max(1.0),
            "{row:?} vs {k}"
        );
        assert!((row[1] - 5.0).abs() <= 1e-9, "{row:?}");
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
