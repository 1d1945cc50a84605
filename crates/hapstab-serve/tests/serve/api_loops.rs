//! API tests of `hapstab serve` against the real server on an ephemeral loopback port:
//! the paper's plant given as a loop is analysed as `hapstab check` does (a loop beyond the
//! paper's is compared with `hapstab check` and `hapstab simulate` in hapstab-cli's
//! `serve_parity`).

use crate::serve_support;

use hapstab::stability::Analysis;
use hapstab::{Normalized, PlantParams};
use serve_support::{Server, library_region};

/// The paper's plant given as a loop (with an explicit backward velocity estimator): the
/// explorer recognizes the paper's loop (its linear condition is drawn, the robust region is
/// offered) and analyses it as `hapstab check` does (`System`, through the paper's family in
/// (α, β)), so its region is the paper's region exactly and every point's verdict and radius
/// are `Analysis::new`'s, on the boundary too.
#[test]
fn a_loop_with_the_papers_view_is_analysed_as_check_does() {
    let s = Server::start(&[]);
    let lp = "mode=physical&device_mass=0.1&device_damping=1.5&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001&d=1&estimator=backward";
    let r = s.get(&format!("/api/region?{lp}"));
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    assert!(
        j["loop"].is_null(),
        "the paper's loop, not a loop beyond it: {j}"
    );
    assert_eq!(j["linear"]["slope"].as_f64(), Some(1.0 / 1.5), "{j}");
    let eff =
        hapstab::Effective::combine(hapstab::Device::PHANTOM_LIKE, hapstab::Arm::TYPICAL).unwrap();
    let pp = PlantParams::from_physical(&eff, 1e-3).unwrap();
    let lib = library_region(pp.gamma, pp.delta, 1);
    // K and B with the paper's normalized view beside them: α_max as the library gives it,
    // K_max = α_max·m/T²
    assert_eq!(
        j["region"]["normalized"]["alpha_max"].as_f64().unwrap(),
        lib.a_max
    );
    let k_max = j["region"]["k_max"].as_f64().unwrap();
    assert!(
        (k_max - lib.a_max * 1.1 / 1e-6).abs() <= 1e-12 * k_max,
        "{k_max}"
    );
    assert!(j["region"]["alpha_max"].is_null(), "{j}");
    let vertices = &lib.polygons[0].vertices;
    for v in vertices.iter().step_by(vertices.len() / 12 + 1) {
        let p = s
            .get(&format!("/api/point?{lp}&alpha={}&beta={}", v.a, v.b))
            .json();
        let an = Analysis::new(Normalized::new(v.a, v.b, pp.gamma, pp.delta, 1).unwrap()).unwrap();
        assert_eq!(p["verdict"], an.verdict.as_str(), "({}, {})", v.a, v.b);
        let rho = p["spectral_radius"].as_f64().unwrap();
        // (serde_json's float parser may be an ulp off the server's shortest form)
        assert!(
            (rho - an.spectral_radius).abs() <= 1e-15,
            "{rho} vs {}",
            an.spectral_radius
        );
    }
}

/// `hapstab serve --loop FILE` prints the page's address with the file's loop and wall in its
/// query: a loop saved by "Save loop" (two-mass device, low-pass, lag, fractional delay)
/// opens on the same loop, whose point answers as the original query's, bit for bit; a file
/// that is not a loop is refused before anything listens, in one line naming the file and
/// the field, exit 2.
#[test]
fn serve_opens_on_a_loop_file() {
    let a = Server::start(&[]);
    let query = "mode=physical&motor_mass=0.05&motor_damping=0.5&handle_mass=0.05\
                 &transmission_stiffness=20000&transmission_damping=2&arm_mass=1&arm_damping=6\
                 &arm_stiffness=350&force_lag=0.0002&period=0.001&delay_time=0.00137\
                 &estimator=lowpass%3A200";
    let wall = "&alpha=0.001&beta=0.02";
    let saved = a.get(&format!("/api/export?{query}{wall}&format=loop"));
    assert_eq!(saved.status, 200, "{}", saved.body);
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("device.json");
    std::fs::write(&file, &saved.body).unwrap();
    let b = Server::start(&["--loop", file.to_str().unwrap()]);
    let (_, opened) = b
        .listening
        .split_once("/?")
        .unwrap_or_else(|| panic!("no query in {:?}", b.listening));
    let opened = opened.split_whitespace().next().unwrap();
    let want = a.get(&format!("/api/point?{query}{wall}")).json();
    let got = b.get(&format!("/api/point?{opened}")).json();
    assert_eq!(got["verdict"], want["verdict"], "{opened}");
    assert_eq!(got["spectral_radius"], want["spectral_radius"], "{opened}");
    assert_eq!(got["margins"], want["margins"], "{opened}");
    let bad = dir.path().join("bad.json");
    let period = r#""period": 0.001"#;
    assert!(saved.body.contains(period), "{}", saved.body);
    std::fs::write(&bad, saved.body.replace(period, r#""period": -0.001"#)).unwrap();
    let out = serve_support::server_with(&["--port", "0", "--loop", bad.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains("bad.json") && err.contains("period"), "{err}");
    assert!(out.stdout.is_empty(), "nothing listens: {:?}", out.stdout);
}
