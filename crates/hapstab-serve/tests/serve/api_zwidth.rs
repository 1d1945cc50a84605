//! API tests of `/api/zwidth` against the real server: the Z-width of a loop is the
//! library's [`hapstab::zwidth::zwidth`] of the same loop, its table's K_max at each damping
//! is the library's K_max there, and bad parameters are refused naming them (the command
//! line's answer is compared in hapstab-cli's `serve_parity_matrix`).

use crate::serve_support;

use hapstab::kmax::{KmaxQuery, kmax};
use hapstab::{Delay, Loop, VelocityEstimator};
use serve_support::{PAPER_LOOP, Server};

#[test]
fn zwidth_is_the_library_s() {
    let s = Server::start(&[]);
    let r = s.get(&format!("/api/zwidth?{PAPER_LOOP}&table_damping=0,2,5"));
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    assert_eq!(
        j["input"]["table_damping"],
        serde_json::json!([0.0, 2.0, 5.0])
    );
    let z = &j["loops"][0];
    assert_eq!(z["label"], "backward");
    let plant = hapstab::loop_spec::default_plant().unwrap();
    let lp = Loop::new(
        plant,
        1e-3,
        Delay::samples(1).unwrap(),
        VelocityEstimator::Backward,
    )
    .unwrap();
    let sys = hapstab::System::of(&lp).unwrap();
    let lib = hapstab::zwidth::zwidth(&lp, Some(&[0.0, 2.0, 5.0])).unwrap();
    assert_eq!(z["stable_area"].as_f64(), Some(lib.stable_area));
    assert_eq!(
        z["k_max"]["stiffness"].as_f64(),
        lib.k_max.map(|w| w.stiffness)
    );
    for (row, b) in z["table"].as_array().unwrap().iter().zip([0.0, 2.0, 5.0]) {
        let k = kmax(&sys, KmaxQuery::AtDamping(b)).unwrap().k_max.unwrap();
        let got = row["k_max"].as_f64().unwrap();
        assert!((got - k).abs() <= 1e-9 * k, "B = {b}: {got} vs {k}");
    }
    // the paper's loop: the linear condition (22) with b = b_L + b_H and t_d + T/2
    assert_eq!(z["linear"]["damping"].as_f64(), Some(7.5));
    assert_eq!(z["linear"]["effective_delay"].as_f64(), Some(1.5e-3));
}

#[test]
fn zwidth_refuses_bad_parameters_in_one_line() {
    let s = Server::start(&[]);
    let many = vec!["1"; 201].join(",");
    for (query, name) in [
        (format!("{PAPER_LOOP}&table_damping=1,x"), "table_damping"),
        (
            format!("{PAPER_LOOP}&table_damping={many}"),
            "table_damping",
        ),
        ("gamma=0.001&delta=0.015&d=1".to_string(), "mode"),
    ] {
        let r = s.get(&format!("/api/zwidth?{query}"));
        assert_eq!(r.status, 400, "{query}: {}", r.body);
        let j = r.json();
        assert_eq!(j["parameter"], name, "{query}: {j}");
        assert!(!j["error"].as_str().unwrap().contains('\n'), "{j}");
    }
}
