//! API tests of `/api/sweep` against the real server: every point's K_max is the K_max of
//! the loop at that value (the library's [`hapstab::kmax::kmax`] on a loop built with the
//! value), and bad parameters are refused naming them (the command line's answer is compared
//! in hapstab-cli's `serve_parity_matrix`).

use crate::serve_support;

use hapstab::kmax::{KmaxQuery, kmax};
use hapstab::{Delay, Loop, VelocityEstimator};
use serve_support::{PAPER_LOOP, Server};

#[test]
fn each_point_is_the_kmax_of_its_loop() {
    let s = Server::start(&[]);
    let r = s.get(&format!(
        "/api/sweep?{PAPER_LOOP}&param=delay-time&lo=0.001&hi=0.003&n=3&wall_damping=2"
    ));
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    assert_eq!(j["input"]["param"], "delay-time");
    assert_eq!(j["input"]["k_max_at"]["kind"], "damping");
    assert_eq!(j["unit"], "s");
    let points = j["points"].as_array().unwrap();
    assert_eq!(points.len(), 3);
    for (p, d) in points.iter().zip([1, 2, 3]) {
        assert_eq!(p["value"].as_f64().unwrap(), d as f64 * 1e-3);
        let plant = hapstab::loop_spec::default_plant().unwrap();
        let lp = Loop::new(
            plant,
            1e-3,
            Delay::samples(d).unwrap(),
            VelocityEstimator::Backward,
        )
        .unwrap();
        let sys = hapstab::System::of(&lp).unwrap();
        let lib = kmax(&sys, KmaxQuery::AtDamping(2.0)).unwrap();
        let k = p["k_max"].as_f64().unwrap();
        let want = lib.k_max.unwrap();
        assert!((k - want).abs() <= 1e-9 * want, "d = {d}: {k} vs {want}");
    }
    // a longer delay never allows a stiffer wall
    let k: Vec<f64> = points
        .iter()
        .map(|p| p["k_max"].as_f64().unwrap())
        .collect();
    assert!(k[0] > k[1] && k[1] > k[2], "{k:?}");
}

#[test]
fn sweep_refuses_bad_parameters_in_one_line() {
    let s = Server::start(&[]);
    let sweep = "param=period&lo=0.001&hi=0.002&n=3";
    for (query, name) in [
        (format!("{PAPER_LOOP}&param=bogus&lo=0&hi=1&n=3"), "param"),
        (
            format!("{PAPER_LOOP}&param=period&lo=0.001&hi=0.002&n=1"),
            "n",
        ),
        (
            format!("{PAPER_LOOP}&param=period&lo=0.001&hi=0.002&n=100000"),
            "n",
        ),
        (format!("{PAPER_LOOP}&param=period&lo=x&hi=0.002&n=3"), "lo"),
        (
            format!("{PAPER_LOOP}&param=period&lo=-1&hi=0.002&n=3"),
            "param",
        ),
        (format!("{PAPER_LOOP}&param=period&lo=0.001&n=3"), "hi"),
        (format!("gamma=0.001&delta=0.015&d=1&{sweep}"), "mode"),
    ] {
        let r = s.get(&format!("/api/sweep?{query}"));
        assert_eq!(r.status, 400, "{query}: {}", r.body);
        let j = r.json();
        assert_eq!(j["parameter"], name, "{query}: {j}");
        assert!(!j["error"].as_str().unwrap().contains('\n'), "{j}");
    }
}
