//! API tests of `hapstab serve` against the real server on an ephemeral loopback port:
//! the paper's plant given as a loop is analysed as `hapstab check` does (a loop beyond the
//! paper's is compared with `hapstab check` and `hapstab simulate` in hapstab-cli's
//! `serve_parity`).

use crate::serve_support;

use hapstab::stability::Analysis;
use hapstab::{Normalized, PlantParams};
use serve_support::{Server, library_region};

/// The paper's plant given as a loop (an explicit backward velocity estimator makes it a
/// loop request): the explorer analyses it as `hapstab check` does
/// (`hapstab::loop_analysis`, through the paper's family in (α, β)), so its region is the
/// paper's region exactly and every point's verdict and radius are `Analysis::new`'s, on the
/// boundary too.
#[test]
fn a_loop_with_the_papers_view_is_analysed_as_check_does() {
    let s = Server::start(&[]);
    let lp = "mode=physical&device_mass=0.1&device_damping=1.5&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001&d=1&estimator=backward";
    let r = s.get(&format!("/api/region?{lp}"));
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    assert_eq!(j["loop"]["velocity"]["kind"], "backward", "{j}");
    let eff =
        hapstab::Effective::combine(hapstab::Device::PHANTOM_LIKE, hapstab::Arm::TYPICAL).unwrap();
    let pp = PlantParams::from_physical(&eff, 1e-3).unwrap();
    let lib = library_region(pp.gamma, pp.delta, 1);
    assert_eq!(j["region"]["alpha_max"].as_f64().unwrap(), lib.alpha_max);
    let vertices = &lib.polygons[0].vertices;
    for v in vertices.iter().step_by(vertices.len() / 12 + 1) {
        let p = s
            .get(&format!(
                "/api/point?{lp}&alpha={}&beta={}",
                v.alpha, v.beta
            ))
            .json();
        let an = Analysis::new(Normalized::new(v.alpha, v.beta, pp.gamma, pp.delta, 1).unwrap())
            .unwrap();
        assert_eq!(
            p["verdict"],
            an.verdict.as_str(),
            "({}, {})",
            v.alpha,
            v.beta
        );
        let rho = p["spectral_radius"].as_f64().unwrap();
        // (serde_json's float parser may be an ulp off the server's shortest form)
        assert!(
            (rho - an.spectral_radius).abs() <= 1e-15,
            "{rho} vs {}",
            an.spectral_radius
        );
    }
}
