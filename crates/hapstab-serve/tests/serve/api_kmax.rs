//! API tests of `/api/kmax` against the real server: K_max at one damping, over a band and
//! over every damping are the library's [`hapstab::kmax::kmax`] on the same loop, and the
//! walls just below and above K_max are stable and unstable by the library's verdict (the
//! command line's answer is compared in hapstab-cli's `serve_parity_matrix`).

use crate::serve_support;

use hapstab::kmax::{KmaxQuery, NoiseModel, kmax};
use hapstab::stability::Verdict;
use hapstab::{Delay, Loop, System, VelocityEstimator};
use serve_support::{PAPER_LOOP, Server};

/// The loop of [`PAPER_LOOP`], built by the library: the default device held by the typical
/// arm, T = 1 ms, d = 1, backward difference.
fn paper_loop() -> Loop {
    let plant = hapstab::loop_spec::default_plant().unwrap();
    Loop::new(
        plant,
        1e-3,
        Delay::samples(1).unwrap(),
        VelocityEstimator::Backward,
    )
    .unwrap()
}

fn stable(sys: &System, k: f64, b: f64) -> bool {
    let units = sys
        .wall_units(hapstab::Wall {
            stiffness: k,
            damping: b,
        })
        .unwrap();
    sys.analysis(units).unwrap().verdict == Verdict::Stable
}

#[test]
fn kmax_three_ways_is_the_library_s() {
    let s = Server::start(&[]);
    let lp = paper_loop();
    let sys = System::of(&lp).unwrap();
    // at one damping: K_max is the top of the stable interval
    let r = s.get(&format!("/api/kmax?{PAPER_LOOP}&wall_damping=5"));
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    let lib = kmax(&sys, KmaxQuery::AtDamping(5.0)).unwrap();
    let k = j["k_max"].as_f64().unwrap();
    assert_eq!(Some(k), lib.k_max);
    assert_eq!(j["input"]["wall_damping"], 5.0);
    assert!(stable(&sys, k * (1.0 - 1e-6), 5.0));
    assert!(!stable(&sys, k * (1.0 + 1e-6), 5.0));
    // the paper's normalized view: α_max = K_max T²/m
    let alpha = j["normalized"]["alpha_max"].as_f64().unwrap();
    assert!((alpha - k * 1e-6 / 1.1).abs() <= 1e-12 * alpha, "{j}");
    // over a band, and over every damping (the design answer)
    let band = s
        .get(&format!(
            "/api/kmax?{PAPER_LOOP}&damping_lo=0&damping_hi=20"
        ))
        .json();
    let lib = kmax(&sys, KmaxQuery::Band { lo: 0.0, hi: 20.0 }).unwrap();
    assert_eq!(band["k_max"].as_f64(), lib.k_max);
    assert_eq!(band["b_at_k_max"].as_f64(), lib.b_at_k_max);
    assert_eq!(
        band["input"]["damping_range"],
        serde_json::json!([0.0, 20.0])
    );
    let all = s.get(&format!("/api/kmax?{PAPER_LOOP}")).json();
    let lib = kmax(&sys, KmaxQuery::Design(NoiseModel::default())).unwrap();
    assert_eq!(all["k_max"].as_f64(), lib.k_max);
    assert_eq!(
        all["k_max_at_zero_damping"].as_f64(),
        lib.k_max_at_zero_damping
    );
    assert_eq!(
        all["renderable"]["b_max"].as_f64(),
        lib.renderable.as_ref().map(|r| r.b_max)
    );
    // the renderable band of another noise model: B_r = F_n·√12/(Δ·‖V‖₂), proportional to
    // F_n/Δ
    let noisy = s
        .get(&format!(
            "/api/kmax?{PAPER_LOOP}&position_resolution=2e-5&force_noise=0.1"
        ))
        .json();
    let b_r = |j: &serde_json::Value| j["renderable"]["b_max"].as_f64().unwrap();
    assert!(
        (b_r(&noisy) - b_r(&all)).abs() <= 1e-12 * b_r(&all),
        "{noisy}"
    );
    assert_eq!(noisy["renderable"]["force_noise"], 0.1);
    // the band's K_max is at least the K_max at any damping inside it
    assert!(band["k_max"].as_f64().unwrap() >= k);
    assert!(all["k_max"].as_f64().unwrap() >= band["k_max"].as_f64().unwrap());
}

#[test]
fn kmax_refuses_bad_parameters_in_one_line() {
    let s = Server::start(&[]);
    for (query, name) in [
        (format!("{PAPER_LOOP}&wall_damping=x"), "wall_damping"),
        (
            format!("{PAPER_LOOP}&wall_damping=1&damping_lo=0"),
            "damping_lo",
        ),
        (
            format!("{PAPER_LOOP}&damping_lo=5&damping_hi=1"),
            "damping_hi",
        ),
        (format!("{PAPER_LOOP}&damping_hi=1"), "damping_lo"),
        (format!("{PAPER_LOOP}&force_noise=0"), "force_noise"),
        (
            format!("{PAPER_LOOP}&force_noise=1&wall_damping=1"),
            "wall_damping",
        ),
        ("gamma=0.001&delta=0.015&d=1".to_string(), "mode"),
        (format!("{PAPER_LOOP}&bogus=1"), "bogus"),
    ] {
        let r = s.get(&format!("/api/kmax?{query}"));
        assert_eq!(r.status, 400, "{query}: {}", r.body);
        let j = r.json();
        assert_eq!(j["parameter"], name, "{query}: {j}");
        let msg = j["error"].as_str().unwrap();
        assert!(!msg.contains('\n') && msg.contains(name), "{msg}");
    }
}
