//! API tests of `/api/map` against the real server: every grid point's verdict is the
//! library's analysis of that wall (a (K, B) map of a physical loop, an (α, β) map of the
//! paper's normalized loop), and the axes are refused where the loop has no such parameter
//! (the command line's answer is compared in hapstab-cli's `serve_parity_matrix`).

use crate::serve_support;

use hapstab::stability::{Analysis, Verdict};
use hapstab::{Delay, Loop, Normalized, VelocityEstimator};
use serve_support::{PAPER_LOOP, PLANT, Server};

#[test]
fn a_wall_map_is_the_verdict_at_each_wall() {
    let s = Server::start(&[]);
    let r = s.get(&format!(
        "/api/map?{PAPER_LOOP}&x=K:0:40000:5&y=B:0:20:4&radius=1"
    ));
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    assert_eq!(j["points"], 20);
    let plant = hapstab::loop_spec::default_plant().unwrap();
    let lp = Loop::new(
        plant,
        1e-3,
        Delay::samples(1).unwrap(),
        VelocityEstimator::Backward,
    )
    .unwrap();
    let sys = hapstab::System::of(&lp).unwrap();
    let fam = sys.family();
    let stable = j["stable"].as_array().unwrap();
    let radius = j["spectral_radius"].as_array().unwrap();
    let mut count = 0;
    for iy in 0..4 {
        for ix in 0..5 {
            let (k, b) = (ix as f64 * 10000.0, iy as f64 * 20.0 / 3.0);
            let (a, bb) = fam.to_units(k, b);
            let an = sys.analysis((a, bb)).unwrap();
            let i = iy * 5 + ix;
            // the verdict away from the boundary, where both decide the same way
            if (an.spectral_radius - 1.0).abs() > 1e-6 {
                assert_eq!(stable[i], an.verdict == Verdict::Stable, "K = {k}, B = {b}");
                let rho = radius[i].as_f64().unwrap();
                assert!((rho - an.spectral_radius).abs() <= 1e-9, "{rho}");
            }
            count += usize::from(stable[i].as_bool().unwrap());
        }
    }
    assert_eq!(j["stable_points"], count);
    assert!(count > 0 && count < 20, "{count}");
}

#[test]
fn a_normalized_map_is_the_paper_s_verdict() {
    let s = Server::start(&[]);
    let r = s.get(&format!(
        "/api/map?{PLANT}&x=alpha:0.001:0.1:4&y=beta:0:0.4:3"
    ));
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    let stable = j["stable"].as_array().unwrap();
    for iy in 0..3 {
        for ix in 0..4 {
            let (a, b) = (0.001 + ix as f64 * 0.033, iy as f64 * 0.2);
            let an = Analysis::new(Normalized::new(a, b, 0.001, 0.015, 1).unwrap()).unwrap();
            if (an.spectral_radius - 1.0).abs() > 1e-6 {
                assert_eq!(
                    stable[iy * 4 + ix],
                    an.verdict == Verdict::Stable,
                    "{a} {b}"
                );
            }
        }
    }
    assert!(j["spectral_radius"].is_null());
    assert_eq!(j["input"]["gamma"], 0.001);
}

#[test]
fn map_refuses_bad_axes_in_one_line() {
    let s = Server::start(&[]);
    for (query, name) in [
        (format!("{PAPER_LOOP}&x=alpha:0:1:3&y=beta:0:1:3"), "x"),
        (format!("{PLANT}&x=K:0:1:3&y=B:0:1:3"), "x"),
        (format!("{PAPER_LOOP}&x=K:0:1:3&y=beta:0:1:3"), "y"),
        (format!("{PAPER_LOOP}&x=K:0:1&y=B:0:1:3"), "x"),
        (format!("{PAPER_LOOP}&x=K:0:1:3&y=B:0:1:100000"), "y"),
        (format!("{PAPER_LOOP}&x=Q:0:1:3&y=B:0:1:3"), "x"),
        (format!("{PAPER_LOOP}&x=K:1:0:3&y=B:0:1:3"), "x"),
        (format!("{PAPER_LOOP}&x=K:0:1:3&y=B:0:1:3&alpha=1"), "alpha"),
        (
            format!("{PAPER_LOOP}&x=K:0:1:3&y=B:0:1:3&radius=maybe"),
            "radius",
        ),
        (
            format!("{PAPER_LOOP}&x=K:0:1e6:1000&y=B:0:1:1000&radius=1"),
            "x",
        ),
    ] {
        let r = s.get(&format!("/api/map?{query}"));
        assert_eq!(r.status, 400, "{query}: {}", r.body);
        let j = r.json();
        assert_eq!(j["parameter"], name, "{query}: {j}");
        assert!(!j["error"].as_str().unwrap().contains('\n'), "{j}");
    }
}
