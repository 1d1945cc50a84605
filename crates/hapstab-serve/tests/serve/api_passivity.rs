//! API tests of `/api/passivity` against the real server: the requirement and the verdict
//! are the library's [`hapstab::passivity::passivity`] of the same loop and wall, equal to
//! `/api/point`'s, and the passive region's largest stiffness is passive while a stiffer wall
//! at its damping is not (the command line's answer is compared in hapstab-cli's
//! `serve_parity_matrix`).

use crate::serve_support;

use hapstab::passivity::{PassivityVerdict, passivity};
use hapstab::{Delay, Loop, VelocityEstimator, Wall};
use serve_support::{PAPER_LOOP, PLANT, Server};

#[test]
fn passivity_is_the_library_s_and_the_point_s() {
    let s = Server::start(&[]);
    let wall = "wall_stiffness=300&wall_damping=0.5";
    let r = s.get(&format!("/api/passivity?{PAPER_LOOP}&{wall}"));
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    let plant = hapstab::loop_spec::default_plant().unwrap();
    let lp = Loop::new(
        plant,
        1e-3,
        Delay::samples(1).unwrap(),
        VelocityEstimator::Backward,
    )
    .unwrap();
    let w = Wall {
        stiffness: 300.0,
        damping: 0.5,
    };
    let lib = passivity(&lp, w).unwrap();
    assert_eq!(j["b_required"].as_f64(), Some(lib.requirement.b_required));
    assert_eq!(j["device_damping"].as_f64(), Some(1.5));
    assert_eq!(j["effective_damping"].as_f64(), Some(7.5));
    assert_eq!(j["input"]["wall"]["stiffness"], 300.0);
    let point = s.get(&format!("/api/point?{PAPER_LOOP}&{wall}")).json();
    assert_eq!(j["verdict"], point["passivity"]["verdict"]);
    assert_eq!(j["stable"], point["stable"]);
    // the passive region's corner: passive just inside, not passive beyond
    let region = &j["passive_region"];
    let (k, b) = (
        region["k_max"].as_f64().unwrap(),
        region["b_at_k_max"].as_f64().unwrap(),
    );
    let at = |k: f64| {
        passivity(
            &lp,
            Wall {
                stiffness: k,
                damping: b,
            },
        )
        .unwrap()
        .verdict
    };
    assert_eq!(at(k * (1.0 - 1e-6)), PassivityVerdict::Passive);
    assert_eq!(at(k * (1.0 + 1e-6)), PassivityVerdict::NotPassive);
}

#[test]
fn a_normalized_wall_is_alpha_and_beta() {
    let s = Server::start(&[]);
    let r = s.get(&format!("/api/passivity?{PLANT}&alpha=0.001&beta=0.002"));
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    let lp = Loop::normalized(hapstab::PlantParams::new(0.001, 0.015).unwrap(), 1).unwrap();
    let lib = passivity(
        &lp,
        Wall {
            stiffness: 0.001,
            damping: 0.002,
        },
    )
    .unwrap();
    assert_eq!(j["b_required"].as_f64(), Some(lib.requirement.b_required));
    assert_eq!(j["input"]["alpha"], 0.001);
}

#[test]
fn passivity_refuses_bad_parameters_in_one_line() {
    let s = Server::start(&[]);
    for (query, name) in [
        (
            format!("{PAPER_LOOP}&wall_stiffness=x&wall_damping=1"),
            "wall_stiffness",
        ),
        (format!("{PLANT}&alpha=0.1"), "beta"),
        (
            format!("{PLANT}&wall_stiffness=1&wall_damping=1"),
            "wall_stiffness",
        ),
    ] {
        let r = s.get(&format!("/api/passivity?{query}"));
        assert_eq!(r.status, 400, "{query}: {}", r.body);
        let j = r.json();
        assert_eq!(j["parameter"], name, "{query}: {j}");
        assert!(!j["error"].as_str().unwrap().contains('\n'), "{j}");
    }
}
