//! API tests of `hapstab serve` against the real server on an ephemeral loopback port:
//! `/api/simulate` returns a decimated contact trace with the analysis's verdict, clipped
//! where a blown-up contact leaves the start's scale.

use crate::serve_support;

use serve_support::Server;

#[test]
fn simulate_returns_a_short_contact_trace() {
    let s = Server::start(&[]);
    let r = s.get("/api/simulate?gamma=0.001&delta=0.015&d=0&alpha=0.3&beta=0.5&push=100");
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    assert_eq!(j["outcome"], "decaying", "{j}");
    assert_eq!(j["linear_verdict"], "stable");
    assert_eq!(j["input"]["effects"]["contact"], "unilateral");
    assert_eq!(j["input"]["human_force"], 100.0);
    assert_eq!(j["input"]["initial"]["velocity"], 0.01);
    assert_eq!(j["input"]["alpha"], 0.3, "the normalized input echoed");
    assert_eq!(j["linear_window"], true);
    assert!(j["measured_growth_per_sample"].as_f64().unwrap() < 1.0);
    assert!(j["trace_clipped"].is_null(), "a decaying run is not cut");
    let n = j["trace"]["time"].as_array().unwrap().len();
    assert!((10..=2000).contains(&n), "{n}");
    assert_eq!(j["trace"]["position"].as_array().unwrap().len(), n);
    // beyond α_max the bilateral loop grows
    let r = s.get(
        "/api/simulate?gamma=0.001&delta=0.015&d=0&alpha=0.75&beta=0.5&contact=bilateral&samples=400",
    );
    let j = r.json();
    assert_eq!(j["linear_verdict"], "unstable");
    assert_eq!(j["outcome"], "growing");
    assert!(j["measured_growth_per_sample"].as_f64().unwrap() > 1.0);
    // long runs are decimated to at most 2000 rows
    let r = s.get("/api/simulate?gamma=0&delta=0.01&d=1&alpha=0.05&beta=0.2&samples=20000");
    assert_eq!(r.status, 200, "{}", r.body);
    assert!(r.json()["trace"]["time"].as_array().unwrap().len() <= 2000);
}

/// A wall beyond α_max at d = 1 (normalized mode, shown for m = 1 kg, T = 1 ms) whose
/// simulated contact blows up (the state reaches the simulator's bound 1e100): the returned
/// trace ends before the first sample where |x| exceeds 10³ times the scale of the start,
/// max(|x(0)| = 0, |ẋ(0)|·T = 0.01 m/s · 1 ms, F_H·T²/m = 1 N · (1 ms)²/1 kg) = 10 µm, so
/// 10 mm; `trace_clipped` says where, and the verdict beside it is growing.
#[test]
fn a_blown_up_contact_is_clipped_where_it_leaves_the_start_scale() {
    let s = Server::start(&[]);
    let j = s
        .get("/api/simulate?gamma=0.001&delta=0.005&d=1&alpha=0.5&beta=0.2")
        .json();
    assert_eq!(j["outcome"], "growing", "{j}");
    assert_eq!(j["linear_verdict"], "unstable");
    assert_eq!(j["blown_up"], true, "the whole run reached 1e100");
    let c = &j["trace_clipped"];
    let scale = c["start_scale"].as_f64().unwrap();
    assert!((scale - 1e-5).abs() < 1e-18, "{c}");
    assert_eq!(c["factor"], 1e3);
    let threshold = c["threshold"].as_f64().unwrap();
    assert!((threshold - 1e-2).abs() < 1e-15, "{c}");
    let (t, x) = (&j["trace"]["time"], &j["trace"]["position"]);
    let n = t.as_array().unwrap().len();
    assert!(n >= 10 && x.as_array().unwrap().len() == n, "{n} rows");
    assert!(j["trace"]["wall_force"].as_array().unwrap().len() == n);
    let peak = (0..n).fold(0.0f64, |m, i| m.max(x[i].as_f64().unwrap().abs()));
    assert!(peak <= threshold && peak > 0.1 * threshold, "{peak}");
    let (ts, xs) = (c["time"].as_f64().unwrap(), c["position"].as_f64().unwrap());
    assert!(xs.abs() > threshold, "{c}");
    assert!(
        t[n - 1].as_f64().unwrap() < ts,
        "the trace ends before the cut"
    );
    let k = c["sample"].as_f64().unwrap();
    assert!((ts - k * 1e-3).abs() < 1e-12, "{c}");
    // the run behind it went on: its verdict and length are the whole run's
    assert!(j["samples"].as_f64().unwrap() > k, "{j}");
}
